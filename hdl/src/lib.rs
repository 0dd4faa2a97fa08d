//! texrtl's hardware side: the RTL kernel, bit-accurate fixed point and the datapath models.
//!
//! No floating point is used inside a model: values are integers with a declared
//! [`fx::Format`]; conversions to `f64` exist only at the edges (tracing, golden comparison).

pub mod fx;
pub mod kernel;

/// FIG. 7 of US 2004/0207631: the per-pixel normal pipeline.
pub mod bump;
/// FIG. 14 of Schilling & Knittel: the real-time mipmap generator.
pub mod mipmap;
/// Figure 6 of Schilling & Knittel: the texture memory path.
pub mod texmem;
