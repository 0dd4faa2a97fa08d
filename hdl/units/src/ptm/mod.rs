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
