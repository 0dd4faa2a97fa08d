//! Polynomial texture maps of micro-occlusion (001, paragraphs \[0029\]-\[0061\], Figs 2, 3, 6):
//! per texel six coefficients of `K(u, v) = A1 u^2 + A2 u + A3 u v + A4 v + A5 v^2 + A6`,
//! the occlusion of a light at `(u, v)` (the light vector in the tangent plane).
//!
//! * [`texture_612`](crate::ptm::texture_612): the occlusion PTM 612 as stored: six coefficients of 8 or 16 bits,
//!   each with a scale `2^e` and a bias, derived from the fit's pseudo-inverse so that no fit
//!   of any samples can fall outside;
//! * [`fitter_604`](crate::ptm::fitter_604): the fitter 604, a streaming six-lane multiply-accumulate over the
//!   samples of a texel, one light a cycle, against a precomputed pseudo-inverse;
//! * [`shader_608`](crate::ptm::shader_608): the evaluator in the light shader 608, `K = (A1 u + A3 v + A2) u +
//!   (A5 v + A4) v + A6`, exact and rounded once, clamped, visibility `1 - K`.
//!
//! The sample generator 602 (height field, occlusion by marching toward each light) and the
//! pseudo-inverse are the host's, in f64 (`golden::ptm`): the hardware reads P from a table.
//!
//! Formats (\[C\]: the document stores floats):
//!
//! | value | format |
//! |---|---|
//! | sample | uQ0.8, 255 lit; the fit takes `K_i = 255 - sample` (polarity: \[0036\] against \[0044\]) |
//! | P (pseudo-inverse, 6 x L) | sQ7.20, rounded from f64 half up |
//! | lane accumulator | sQ17.28 (exact: `P K` summed over up to 1024 lights) |
//! | coefficient `A_j` | `q_j 2^e_j + b_j` in units of 2^-20, `q_j` u8 or u16 |
//! | u, v | sQ1.14 |
//! | K, visibility | uQ0.8 |
//!
//! ## PTM micro-occlusion (001, paragraphs \[0029\]-\[0061\], Fig. 6)
//!
//! Per texel six coefficients of `K(u, v) = A1 u^2 + A2 u + A3 u v + A4 v + A5 v^2 + A6`, the
//! occlusion of a light whose direction projects to (u, v) on the tangent plane.
//!
//! * **Sample generator 602** (host, `golden/src/ptm.rs`): a tileable height field, each texel's
//!   occlusion toward each light of a dome (rings x azimuths) by marching in quarter-texel
//!   steps over the field repeated (the 3 x 3 tiles of \[0061\]); white = lit, as the sample
//!   images. The march is bounded: a ray still below the field's highest point after 16 swatch
//!   widths is occluded (a grazing light; at 15 degrees and up the bound is never reached).
//! * **Fitter 604** (`hdl/units/src/ptm/fitter_604.rs`): the least-squares fit is `A = P K` with the
//!   pseudo-inverse `P = (A^T A)^-1 A^T` (host, by QR, rounded to sQ7.20), the same for every
//!   texel, so six multiply-accumulate lanes take one light a cycle. `K_i = 255 - sample`
//!   (the seed's polarity: K = 0 unoccluded \[0036\] against white = lit \[0044\]), widened to uQ1.8
//!   as `x + (x >> 7)` \[C\] (0 and 1 exact). The lanes are exact; each coefficient is rounded once
//!   into the texture format.
//! * **Occlusion PTM 612** (`ptm/texture_612.rs`): six unsigned coefficients of 8 or 16 bits, each
//!   `q 2^e + b` \[C\]; the ranges come from P before any fit (with K in \[0, 1\] a coefficient lies
//!   between the sums of P's negative and positive entries), so no fit is ever held at a limit.
//!   The ranges are wide against typical coefficients: the price of knowing them first.
//! * **Light shader 608** (`ptm/shader_608.rs`): `K = (A1 u + A3 v + A2) u + (A5 v + A4) v + A6`
//!   exact, one rounding to uQ0.8, held to 0..=255, visibility `255 - K`.
//!
//! The seed's misprints, each with a test that fails on the printed form: the cubic basis of
//! \[0037\] repeats `u` (`A1 u` for `A1 u^3`): its design matrix is singular
//! (`golden::ptm::the_printed_cubic_basis_is_singular`); the polarity (a lit texel must fit to
//! K = 0, `tb/tests/ptm.rs`); one ring of lights makes `u^2 + v^2` constant and the fit singular
//! (refused with the reason, by `texrtl ptm fit` too). Checks: data made from the basis is
//! recovered and the residual is orthogonal to it (f64 QR); `ptm_fitter_604` (four domes and
//! widths, marched and grey samples): every stored coefficient equals the integer reference
//! and is within its derived bound of the f64 fit (P's rounding, the occlusion's widening, half
//! a step; measured 0.5 steps, 60 steps for 16-bit grey samples, where the widening dominates);
//! `ptm_shader_608`: bit-exact against the integer reference and within half an LSB of the f64
//! polynomial (one where f64 reaches 1). Measured on a 32 x 32 woven cloth under a 4 x 12 dome
//! (`texrtl regress`): fit RMSE a texel 0.18 mean, 0.27 worst (occlusion in \[0, 1\]: a quadratic
//! fitted to binary shadows); storage 6,144 bytes of 8-bit PTM against 6,144 bytes of binary
//! sample images (the PTM wins from 48 lights on, and interpolates between them) and 3.2 GB of
//! 4096 x 4096 32-bit shadow maps, one a light.
//!
//! `texrtl ptm fit --height H.pgm --lights L.csv --out T.ptm [--bits 8|16] [--height-scale S]`:
//! heights are the PGM's levels times S texels (default 1/16), the map square and tiled; L has
//! the header `elevation,azimuth` (degrees). `texrtl ptm eval --ptm T.ptm --queries Q.csv --out
//! O.csv`: Q `x,y,lu,lv`, O `x,y,lu,lv,k,visibility` (uQ0.8 integers). The `.ptm` file:
//! `texrtl-ptm 1`, a line `W H BITS`, a line of the six `e b` pairs, then the coefficients texel
//! by texel (u8, or u16 little-endian); read with its length checked before any allocation.

pub mod fitter_604;
pub mod shader_608;
pub mod texture_612;

/// Fraction bits of P and of the coefficients.
pub const P_FRAC: u32 = 20;
/// P's width (sQ7.20).
pub const P_BITS: u32 = 28;
/// Fraction bits of u, v.
pub const UV_FRAC: u32 = 14;
/// The most lights a texel's fit may use.
pub const MAX_LIGHTS: usize = 1024;
