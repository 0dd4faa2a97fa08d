//! texrtl's hardware side: the RTL kernel, bit-accurate fixed point and the datapath models.
//!
//! No floating point is used inside a model: values are integers with a declared
//! [`fx::Format`]; conversions to `f64` exist only at the edges (tracing, golden comparison).

pub mod fx;
pub mod kernel;

pub mod blend_adjust;
