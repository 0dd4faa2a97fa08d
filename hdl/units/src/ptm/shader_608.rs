//! The PTM's evaluator in the light shader 608 of 001's Fig. 6: the occlusion of a light at
//! `(u, v)` from a texel's six stored coefficients, `K = (A1 u + A3 v + A2) u + (A5 v + A4) v
//! + A6` (Horner's form of \[0030\]), exact, then one rounding to uQ0.8 (half up) held to
//! `0 ..= 255`, and the visibility `255 - K` handed to the shading. One register stage.
//!
//! | port | format |
//! |---|---|
//! | `q1` .. `q6` | u8 or u16, with the texture's [`PtmFormat`] |
//! | `u`, `v` | sQ1.14 |
//! | `k`, `visibility` | uQ0.8 |

use super::texture_612::PtmFormat;
use super::UV_FRAC;
use crate::fx::{quantise, Format, Narrowing, Overflow, Quant};
use crate::kernel::{Module, Reg, Signal};

/// K (uQ0.8, held) of stored `q` at raw `(u, v)`.
pub fn occlusion_at(fmt: &PtmFormat, q: &[u64; 6], u: i64, v: i64) -> u8 {
    let k = exact_occlusion(fmt, q, u, v);
    quantise(k, K_FRAC, K, Quant::RoundHalfUp, Overflow::Saturate) as u8
}

/// K's format, uQ0.8.
const K: Format = Format::unsigned(8, 8);
/// Fraction bits of the exact K: A's 20 and u's and v's 14 each.
const K_FRAC: i32 = 20 + 2 * UV_FRAC as i32;

/// K exact, in units of 2^-48 (Horner's form).
fn exact_occlusion(fmt: &PtmFormat, q: &[u64; 6], u: i64, v: i64) -> i128 {
    let a: [i128; 6] = std::array::from_fn(|j| i128::from(fmt.coefficient(j, q[j])));
    let (u, v) = (i128::from(u), i128::from(v));
    // Units: A 2^-20, u and v 2^-14; each sum in 2^-48.
    let first = (a[0] * u + a[2] * v + (a[1] << UV_FRAC)) * u;
    let second = (a[4] * v + (a[3] << UV_FRAC)) * v;
    first + second + (a[5] << (2 * UV_FRAC))
}

/// The unit.
#[derive(Clone, Debug, Module)]
#[module(kind = "ptm_shader_608")]
pub struct Shader608 {
    fmt: PtmFormat,
    #[input]
    pub in_valid: Signal,
    #[input]
    pub q: [Signal; 6],
    #[input]
    pub u: Signal,
    #[input]
    pub v: Signal,
    #[reg]
    pub out_valid: Reg,
    #[reg]
    pub k: Reg,
    #[reg]
    pub visibility: Reg,
    /// K's one rounding, held to `0 ..= 255`.
    #[narrow]
    round: Narrowing,
}

impl Shader608 {
    pub fn new(fmt: PtmFormat) -> Result<Shader608, String> {
        fmt.validate()?;
        const Q: [&str; 6] = ["q1", "q2", "q3", "q4", "q5", "q6"];
        let uv = Format::signed(16, UV_FRAC as i32);
        let u8f = Format::unsigned(8, 8);
        Ok(Shader608 {
            fmt,
            in_valid: Signal::bit("in_valid"),
            q: Q.map(|n| Signal::new(n, Format::uint(fmt.bits))),
            u: Signal::new("u", uv),
            v: Signal::new("v", uv),
            out_valid: Reg::new("out_valid", Format::uint(1)),
            k: Reg::new("k", u8f),
            visibility: Reg::new("visibility", u8f),
            round: Narrowing::new("k", K, Quant::RoundHalfUp, Overflow::Saturate),
        })
    }
}

impl Shader608 {
    /// The occlusion of a valid query, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.in_valid.is_high();
        self.out_valid.set_next_bool(valid);
        if valid {
            let q = self.q.each_ref().map(|s| s.bits());
            let exact = exact_occlusion(&self.fmt, &q, self.u.raw(), self.v.raw());
            let k = self.round.raw(exact, K_FRAC) as u8;
            self.k.set_next_bits(u64::from(k));
            self.visibility.set_next_bits(u64::from(255 - k));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A6 alone (the other coefficients 0) gives A6 at any light, rounded and held.
    #[test]
    fn a_constant_ptm_is_its_constant() {
        let fmt = PtmFormat {
            bits: 8,
            exp: [12; 6],
            bias: [0; 6],
        };
        // A6 = q 2^12 units of 2^-20 = q/256: K = q exactly.
        for q6 in [0u64, 1, 100, 255] {
            for (u, v) in [(0, 0), (16000, -3000), (-8000, 8000)] {
                assert_eq!(
                    u64::from(occlusion_at(&fmt, &[0, 0, 0, 0, 0, q6], u, v)),
                    q6
                );
            }
        }
        // A1 = 1 (q 256 ... held by the format to 255: 255/256): K = u^2.
        let fmt = PtmFormat {
            exp: [12; 6],
            ..fmt
        };
        let half = 1 << 13;
        assert_eq!(occlusion_at(&fmt, &[255, 0, 0, 0, 0, 0], half, 0), 64);
    }
}
