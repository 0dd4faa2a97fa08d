//! Bit-accurate fixed point, equivalent to Algorithmic C `ac_fixed` / SystemC `sc_fixed`.
//!
//! A value is an integer `raw` with a [`Format`]: `width` bits in all, `frac` of them after the
//! binary point, signed (two's complement) or unsigned. Its value is `raw * 2^-frac`.
//!
//! * Arithmetic (`+`, `-`, `*`, unary `-`) keeps full precision: a sum gets `max(F1, F2)`
//!   fraction bits and one integer bit more than the wider operand; a product gets `W1 + W2`
//!   bits and `F1 + F2` fraction bits. Nothing is ever rounded or wrapped by an operator.
//! * Precision is only lost in [`Fx::convert`], which names its [`Quant`] (rounding) and
//!   [`Overflow`] mode. [`Fx::exact`] converts only when no bit is lost and panics otherwise.
//!
//! # Why formats are carried at run time
//! Stable Rust cannot compute `W1 + W2` in a const generic. The alternatives are typenum-style
//! type arithmetic or a format carried beside the value. texrtl carries the format at run time:
//! architects sweep widths from the command line without recompiling, one compiled model serves
//! every width, error messages name widths instead of nested type lists, and compile times stay
//! short. The cost is a few integer operations per arithmetic step to compute the result format;
//! datapath models that sit on the hot path compute their formats once, at construction.
//!
//! # Limits
//! Values are held in an `i128`: a format may be up to 128 bits signed or 127 bits unsigned, so
//! every product of two formats of up to 63 bits (or a signed 64 x signed 64) is exact. A
//! result format that does not fit panics with the two operand formats: that is a design error,
//! not a data-dependent one. Fraction bits may be negative (a coarse LSB) or exceed the width.
//! Signals and registers of the RTL kernel are at most 64 bits wide.

mod format;
mod modes;
mod value;

pub use format::{Format, FormatError};
pub use modes::{Overflow, Quant};
pub use value::{quantise, Fx, FxError};

#[cfg(test)]
mod tests;
