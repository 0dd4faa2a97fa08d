//! Waveforms of texrtl simulations: a VCD tracer that sees every signal of a design through the
//! kernel's [`Visitor`](hdl::kernel::Visitor), and GTKWave save files that open each trace with
//! its signals grouped per unit.
//!
//! Conventions: the timescale is 1 ps; cycle `n` is sampled at `n * period` with `clk` rising
//! there and falling half a period later; the DUT's instance sits in scope `tb` beside `clk`,
//! `rst` and `tb.golden` (the testbench's probes). Every fixed-point signal gets a companion
//! `real` variable `<name>_real` with its value.
//!
//! Feature `read` (off by default: it brings the `wellen` reader and its dependencies, most of
//! a first build's time): [`check`], which reads a VCD or FST back and checks it, and
//! [`fst::vcd_to_fst`].

#![warn(missing_docs)]

mod fst_file;
mod fst_trace;
pub mod glob;
pub mod gtkw;
mod vcd_text;
mod vcd_trace;
mod vcd_writer;

pub use fst_trace::FstTracer;
pub use vcd_trace::{design_variables, ProbeId, TraceConfig, VcdTracer, ROOT};
#[cfg(feature = "read")]
pub mod check;
pub mod compare;
#[cfg(feature = "read")]
pub mod fst;
/// Writing output files so that no partial file is left behind, and naming values in messages.
pub mod output;
pub mod sample;
