//! # The texrtl user guide
//!
//! texrtl models hardware the way RTL is written, bit for bit and cycle for cycle, in Rust:
//! the bit-exact reference a Verilog implementation must match. This guide takes you from a
//! unit of your own to a regression on a cluster. Every code sample in it is compiled and run
//! by `cargo test` (`cargo test -p texrtl-guide`); read it with `cargo doc -p texrtl-guide
//! --open`, or as markdown in `docs/guide/`.
//!
//! The guide's running example is a unit a user would write: a two-stage alpha blend,
//! [`blend`], with its testbench [`blend_tb`] and its project [`project`] (descriptor,
//! Verilog twin `docs/rtl/blend.v`, vectors). It depends on the framework's three crates only:
//! `texrtl-hdl` (kernel and fixed point), `texrtl-verif` (testbenches, co-simulation,
//! vectors, regressions, the command line as a library) and `texrtl-waves` (waveforms).
//!
//! 1. [Your own unit](own_unit)
//! 2. [Testbenches and coverage](testbenches)
//! 3. [Co-simulation against your Verilog](cosim)
//! 4. [Bit-accuracy vectors](vectors)
//! 5. [Regressions, at scale](regressions)
//! 6. [Waveforms](waveforms)
//! 7. [Fixed point](fixed_point)
//! 8. [Speed](speed)
//! 9. [Bad input and the files texrtl writes](outputs)
//! 10. [The texture models, texrtl's first user](texture)

pub mod blend;
pub mod blend_tb;
pub mod project;

#[doc = include_str!("../guide/unit.md")]
pub mod own_unit {}
#[doc = include_str!("../guide/testbenches.md")]
pub mod testbenches {}
#[doc = include_str!("../guide/cosim.md")]
pub mod cosim {}
#[doc = include_str!("../guide/vectors.md")]
pub mod vectors {}
#[doc = include_str!("../guide/regressions.md")]
pub mod regressions {}
#[doc = include_str!("../guide/waveforms.md")]
pub mod waveforms {}
#[doc = include_str!("../guide/fixed_point.md")]
pub mod fixed_point {}
#[doc = include_str!("../guide/speed.md")]
pub mod speed {}
#[doc = include_str!("../guide/outputs.md")]
pub mod outputs {}
#[doc = include_str!("../guide/texture.md")]
pub mod texture {}
