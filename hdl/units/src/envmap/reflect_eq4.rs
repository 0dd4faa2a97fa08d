//! The reflection vector of eq. 4 (Schilling & Knittel section 7) with the perturbed normal:
//! `w = 2 n_b (n_b . v) - v |n_b|^2`, the reflection of the eye vector `v` about `n_b` scaled
//! by `|n_b|^2` (no normalisation: the cube-face unit divides by the major axis anyway).
//! The seed prints `n` where the text says the new normal: read `n_b` [C, see
//! `../shared/notes/seed-systems.md` section 4].
//!
//! # Arithmetic
//! Exact products and sums (`n_b . v`, `n_b . n_b` with 28 fraction bits; `w` with 42), one
//! rounding to sQ3.16, ties to even, saturating (`|w| = |n_b|^2 < 3` for `|b| < 1`, so the
//! saturation is never reached in range).
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `nb` (perturbed normal, `|n_b|^2 = 1 + b1^2 + b2^2`) | sQ2.14 |
//! | `v` (unit, surface to eye) | sQ1.14 |
//! | `w` | sQ3.16, the cube-face unit's input |
//!
//! One register stage.

use crate::fx::{quantise, Format, Narrowing, Overflow, Quant};
use crate::kernel::{Module, Reg, Signal};

/// Fraction bits of the vectors in.
pub const VEC_FRAC: u32 = 14;

/// `w` (raw sQ3.16) of `nb` (raw sQ2.14) and `v` (raw sQ1.14).
pub fn reflect(nb: [i64; 3], v: [i64; 3]) -> [i64; 3] {
    reflect_by(nb, v, |_, x| {
        quantise(x, 42, W, Quant::RoundHalfEven, Overflow::Saturate) as i64
    })
}

/// The output's format, sQ3.16.
const W: Format = Format::signed(20, 16);

/// `2 nb d - v nn` exact (units of 2^-42), each component narrowed by `round`.
#[inline]
fn reflect_by(nb: [i64; 3], v: [i64; 3], mut round: impl FnMut(usize, i128) -> i64) -> [i64; 3] {
    let dot = |a: [i64; 3], b: [i64; 3]| -> i128 {
        (0..3).map(|c| i128::from(a[c]) * i128::from(b[c])).sum()
    };
    let (d, nn) = (dot(nb, v), dot(nb, nb));
    std::array::from_fn(|c| round(c, 2 * i128::from(nb[c]) * d - i128::from(v[c]) * nn))
}

/// The unit: one register stage.
#[derive(Clone, Debug, Module)]
#[module(kind = "reflect_eq4")]
pub struct Reflect {
    #[input]
    pub valid_in: Signal,
    #[input]
    pub nb: [Signal; 3],
    #[input]
    pub v: [Signal; 3],
    #[reg]
    pub valid: Reg,
    #[reg]
    pub w: [Reg; 3],
    /// `w`'s one rounding each, held at sQ3.16's ends.
    #[narrow]
    round: [Narrowing; 3],
}

impl Default for Reflect {
    fn default() -> Self {
        Reflect::new()
    }
}

impl Reflect {
    pub fn new() -> Reflect {
        let (nb, v, w) = (
            Format::signed(17, VEC_FRAC as i32),
            Format::signed(16, VEC_FRAC as i32),
            Format::signed(20, 16),
        );
        Reflect {
            valid_in: Signal::bit("valid_in"),
            nb: ["nbx", "nby", "nbz"].map(|n| Signal::new(n, nb)),
            v: ["vx", "vy", "vz"].map(|n| Signal::new(n, v)),
            valid: Reg::new("valid", Format::uint(1)),
            w: ["wx", "wy", "wz"].map(|n| Reg::new(n, w)),
            round: ["wx", "wy", "wz"]
                .map(|n| Narrowing::new(n, W, Quant::RoundHalfEven, Overflow::Saturate)),
        }
    }
}

impl Reflect {
    /// The reflected vector of a valid query, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.valid_in.is_high();
        self.valid.set_next_bool(valid);
        if valid {
            let round = &mut self.round;
            let w = reflect_by(
                self.nb.each_ref().map(|s| s.raw()),
                self.v.each_ref().map(|s| s.raw()),
                |c, x| round[c].raw(x, 42) as i64,
            );
            for (r, x) in self.w.iter_mut().zip(w) {
                r.set_next_raw(x);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seen along the normal, the eye's reflection is the normal itself, exactly.
    #[test]
    fn looking_along_the_normal_reflects_onto_it() {
        let one = 1i64 << VEC_FRAC;
        for n in [[0, 0, one], [one, 0, 0], [0, -one, 0]] {
            assert_eq!(reflect(n, n), n.map(|c| c << 2));
        }
        // A grazing eye in the tangent plane reflects to its opposite.
        assert_eq!(reflect([0, 0, one], [one, 0, 0]), [-one << 2, 0, 0]);
    }
}
