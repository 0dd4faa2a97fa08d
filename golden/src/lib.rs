//! f64 reference models of texrtl's hardware, written from the mathematics of the source
//! documents. This crate deliberately shares no code with `texrtl-hdl` (it does not even
//! depend on it), so a bug in the hardware model cannot hide in a shared helper.

pub mod blend_adjust;
pub mod bump;
pub mod derivative;
pub mod envmap;
pub mod footprint;
pub mod mapchain;
pub mod mipmap;
pub mod ptm;
pub mod rsqrt;
pub mod tangents;
pub mod texram;
pub mod texture;
pub mod volume;
