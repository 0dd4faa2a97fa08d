//! The FIG. 7 normal pipeline of US 2004/0207631 (Fenney, bump mapping), one file per unit,
//! named after the unit and its number: address unit 150, texel fetch 151, replicate 152,
//! blend-factor adjust 153, bilinear units 65-68, tangent unit 155, normal unit 156 with its
//! inverse square root; the pipeline top that wires them as the figure does; its parameters
//! and the height map it reads; and para. 0081's tangent average for footprint assembly.
//!
//! ## Blend-factor adjust unit 153
//!
//! `Ublend0 = 1/2 + Ublend/2`, `Ublend1 = Ublend/2` (and for V) with F = 4..=16 input fraction
//! bits and F + 1 output fraction bits: exact, so no rounding mode; in hardware it is wiring
//! (`{1'b1, u}` and `{1'b0, u}`). The bypass (Blinn variant, para. 0085) passes `u` unchanged.
//! One output register stage (latency 1) or none (latency 0). The testbench runs every input
//! value of both channels in both modes for every F from 4 to 16 at one transaction per clock
//! (throughput and latency are checked), then 2,000 random transactions per width with random
//! idle cycles; tolerance 0 LSB.
//!
//! ## The FIG. 7 normal pipeline
//!
//! Conventions (code and golden model agree): positions in texel units; texel `(i, j)` covers
//! `[i, i+1) x [j, j+1)` and its value stands at its centre; heights in texel units (8-bit texel
//! / 4), times the height scale; normal = `normalize(-dH/du, -dH/dv, 1)`, x along +u, y along +v,
//! z up. The B-spline's derivative is twice the difference of the last de Casteljau points: the
//! tangent unit applies that factor 2, which the patent's listing leaves implicit.
//!
//! Stages: address 150 | texel fetch 151 with blend adjust 153 beside it | replicate 152 and
//! the four bilinear units | tangent 155 | normal 156 (square and normalise | rsqrt table | one
//! stage per Newton-Raphson iteration | multiply). Latency 8 cycles by default, one sample per
//! clock. Variants: Bezier (unit 153 bypassed, replicate makes Equation 1's points; bit-identical
//! normals, shown by a test), Blinn (three bilinear units, tangents G-R and B-R), height scale
//! (`uQ8.8`), trilinear from two MIP levels (a second address/fetch/bilinear path on the 2x2
//! box-filtered level), interpolated height output.
//!
//! Default formats: position `sQ16.8`, blend factors `uQ0.8` (adjusted `uQ0.9`), texels `uQ6.2`
//! (or `uQ3.1`), bilinear outputs exact (`uQ6.22`), tangents `sQ16.16` (round half even,
//! symmetric saturation), rsqrt mantissa `uQ2.22` (truncated), table 8 index bits and one
//! Newton-Raphson step with `uQ1.24` iterates, normal `sQ2.16` (round half even, saturate).
//! Every one is a parameter (`hdl::bump_params::BumpParams`).
//!
//! The rsqrt unit is checked exhaustively: all 12,582,912 mantissas against the exact integer
//! reference `floor(2^24 / sqrt(m))` (integer square roots); worst error 95.1 ULP of 2^-24
//! against the derived bound 96.7 (`golden::rsqrt::error_bound_ulps`); other table sizes and
//! iteration counts are swept too (a 12-bit table with one step is faithful: 0.63 ULP).
//!
//! Accuracy against the golden surfaces at default widths, positions on the blend grid, every
//! built-in map (flat, steep, steps, noise, smooth, extremes) x variant x border mode, 24,730
//! samples in `texrtl regress`: worst component error 1.47e-5 (0.96 LSB of 2^-16; required
//! 2^-13 = 1.22e-4), mean 0.17 LSB, worst angle 1.14e-3 degrees (required 0.01), worst height
//! error 7.6e-6. Faithful rounding of the output components (the stretch goal) holds on every
//! sample tested (worst 0.96 LSB) but is not proven: the rsqrt's 95 ULP of 2^-24 plus the final
//! half-LSB rounding can in principle exceed one LSB; a 12-bit table makes the rsqrt itself
//! faithful.
//!
//! ### The remaining FIG. 7 embodiments (000)
//!
//! * **Derivative filters of para. 0086** (`hdl/units/src/bump/derivative_0086.rs`, FIG. 9 is absent):
//!   central differences (12 texels a sample), Sobel and Prewitt (16), an antisymmetric tap table
//!   (default the 5-point derivative `(8, -1)/12` in 2^-12, 20 texels), each at the four texel
//!   centres around the sample and then bilinear; the normal `normalize(-Dx s, -Dy s, 1)` through
//!   156's rsqrt. Nothing divides: the filter's denominator (Prewitt's 6 too, which is no shift)
//!   goes into the vector's z, so the normalisation is the only rounding. By linearity the same
//!   as filtering bilinearly interpolated heights: `tb/tests/derivative.rs` checks the equality in
//!   exact integers for every filter. `texrtl normals --filter central|sobel|prewitt|table|
//!   table:c1,..,cK` (sQ1.14 normals); testbench `derivative_0086` (0.56 LSB of f64, bound 0.59);
//!   `derivative_filters.png` in the report extends FIG. 8: B-spline | Blinn | central | Sobel |
//!   Prewitt | table.
//! * **Bi-quadratic colour of para. 0087** (`bump/biquadratic_0087.rs`): the B-spline weights
//!   `(1-t)^2/2, (1+2t-2t^2)/2, t^2/2` on each axis over the 3 x 3 texels, per channel, t of 8
//!   bits, one rounding; exact on a linear ramp before the rounding, a constant stays, the result
//!   within the min and max of its 3 x 3, `(a + 6b + c)/8` (tensor) at a texel centre
//!   (`tb/tests/biquadratic.rs`); testbench `biquadratic_0087` within half an LSB.
//! * **Packed heights of para. 0055** (`bump/packed_0055.rs`): 2 x 2 heights a 32-bit word; any
//!   3 x 3 window spans exactly 2 x 2 words (the four fetch units 60-63), exhaustively tested.
//!
//! Not built: relief mapping (optional in the documents' reading list); the frame unit wired into a pipeline fed
//! by interpolated vertex frames (it is a unit with its testbench).

pub mod address_150;
pub mod bilinear_65_68;
pub mod biquadratic_0087;
pub mod blend_adjust_153;
pub mod derivative_0086;
pub mod height_map;
pub mod normal_156;
pub mod normal_pipeline_fig7;
pub mod packed_0055;
pub mod params;
pub mod replicate_152;
pub mod rsqrt_156;
pub mod tangent_155;
pub mod tangent_average_0081;
pub mod texel_fetch_151;
