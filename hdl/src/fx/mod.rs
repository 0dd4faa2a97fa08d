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
//! # Formats at run time, folded at compile time
//! Stable Rust cannot compute `W1 + W2` in a const generic, so a value carries its format
//! beside it ([`Fx`] is a raw integer and a [`Format`]), and every operator is inlined. Where
//! the formats are constants, the compiler folds them away: a signal declared with a format
//! type ([`Fmt`], declared by [`formats!`](crate::formats); [`crate::kernel::SignalOf`],
//! [`crate::kernel::RegOf`]) gives values whose formats are constants, and a sum, a product,
//! a `convert` and the write back compile to the shifts, adds and compares a careful person
//! writes on raw integers; results that fit 64 bits are computed in 64 bits. Where a width is
//! a parameter (an architect sweeping it from the command line without recompiling), a
//! [`crate::kernel::Signal`] carries its format at run time and each step also computes its
//! result format: a few integer operations more.
//!
//! # Limits
//! Values are held in an `i128`: a format may be up to 128 bits signed or 127 bits unsigned, so
//! every product of two formats of up to 63 bits (or a signed 64 x signed 64) is exact. A
//! result format that does not fit panics with the two operand formats: that is a design error,
//! not a data-dependent one. Fraction bits may be negative (a coarse LSB) or exceed the width.
//! Signals and registers of the RTL kernel are at most 64 bits wide.

mod format;
mod modes;
mod narrowing;
mod typed;
mod value;

pub use format::{Format, FormatError};
pub use modes::{Overflow, Quant};
pub use narrowing::{set_tracking, tracking, NarrowPath, NarrowStats, Narrowing, NarrowingOf};
pub use typed::{Bit, Fmt};
pub use value::{quantise, Fx, FxError};

#[cfg(test)]
mod tests;
