//! Real-time mipmap generation for interlaced video (Schilling & Knittel, section 12,
//! FIG. 14): the generation unit 816 with its levels (adders 1402 and 1410, register 1404,
//! FIFOs 1408 and 1412) and frame store.
//!
//! ## The real-time mipmap generator (Schilling & Knittel, section 12, FIG. 14)
//!
//! `hdl/units/src/mipmap/mipmap_gen_816.rs` (with `level_fig14.rs` and `fifo.rs` beside it), tests
//! `tb/tests/mipmap.rs`, testbench `tb/src/mipmap.rs`, golden `golden/src/mipmap.rs`. Level 1 is Figure 14a: progressive video
//! adds horizontal pairs (register 1404, adder 1402), buffers even lines' sums in FIFO 1408 (a line
//! buffer) and adds odd lines' sums to them in adder 1410; interlaced video writes the first field
//! to the frame store and, for each line of the second field, reads its partner line through the
//! bank's page register into shift register 826, adds vertical pairs in adder 1402, holds the even
//! column in FIFO 1408 (a one-entry register) and adds the odd column in 1410. Every higher level
//! is Figure 14b, the progressive circuit on the previous level's stream, its FIFOs half as deep.
//! Each level's line goes through FIFO 1412 into the frame store (two frame buffers used
//! alternately; even and odd lines of level 0 in different banks, so the line read for the shift
//! register never competes with the line being written). The sum of four is divided with round
//! half up, `(a+b+c+d+2) >> 2`, by default, or truncated; once a side is 1, pairs are averaged
//! with `(a+b+1) >> 1` (or `>> 1`). FIFO overflow, underflow and video sync errors set a sticky
//! error code; nothing wraps silently.
//!
//! Checked in every scan order (progressive, top field first, bottom field first), both roundings,
//! square, wide, tall and one-texel-wide sizes from 1x1 to 256x256, several frames back to back:
//! every level bit-identical to an integer reference (a plain loop over the frame) and identical
//! across scan orders; FIFO occupancy within the declared depth (half a level-0 line at level 1,
//! halving per level); one texel per clock; complete at most `levels + 2` cycles after the last
//! texel (8 cycles for 256x256). Error against the real block averages (`texrtl regress`): with
//! round half up, worst 0.50 / 1.00 / 1.38 / 1.50 / 1.46 / 1.65 / 2.03 / 0.76 LSB at levels 1-8
//! (analytic bound k/2); with truncation 0.75 / 1.50 / 1.97 / 2.18 / 2.57 / 2.81 / 3.09 / 3.24
//! (bound 3k/4 for sums of four); the bound is derived in `golden/src/mipmap.rs` and asserted.

pub mod fifo;
pub mod level_fig14;
pub mod mipmap_gen_816;

pub use mipmap_gen_816::{FrameBuffer, MipmapGen, MipmapParams, Rounding, Scan};
