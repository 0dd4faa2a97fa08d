//! texrtl's RTL kernel and bit-accurate fixed point: what every model is built of.
//!
//! * [`kernel`]: signals with a declared [`fx::Format`], registers, the [`kernel::Module`]
//!   trait (combinational `eval`, clocked `tick`, `visit` to declare ports, registers and
//!   children) and the simulator [`kernel::Sim`] that runs a module cycle by cycle, checks its
//!   schedule and traces it;
//! * [`fx`]: fixed-point values and formats, with every narrowing's rounding and overflow mode
//!   declared.
//!
//! No floating point is used inside a model: values are integers with a declared
//! [`fx::Format`]; conversions to `f64` exist only at the edges (tracing, golden comparison).
//! This crate holds no model of its own: texrtl's texture-mapping units are in `texrtl-units`.

#![warn(missing_docs)]

// `#[derive(Module)]` names this crate `::hdl` wherever it expands, here too.
extern crate self as hdl;

pub mod fx;
pub mod kernel;
