//! The local frame of eqs 2-3 (Schilling & Knittel section 5 end, section 7: bump mapping
//! before environment mapping): from the interpolated normal `n1` and a reference direction
//! `h`, the unit normal `n = n1/|n1|`, the tangents `e1 = (h x n)/|h x n|` and `e2 = n x e1`
//! (right-handed, `e2` needs no normalisation), and the perturbed normal
//! `n_b = n + e1 b1 + e2 b2` with the bump map's offsets (eq. 3).
//!
//! # Arithmetic \[C\]
//! Lengths by the inverse square root of normal unit 156 (its table and Newton step,
//! [`crate::bump::rsqrt_156::rsqrt`], default parameters): `s = m 4^k` with the mantissa `m` in
//! [1, 4) truncated to 22 fraction bits, `1/sqrt(s) = rsqrt(m) 2^-k`; each component the exact
//! product rounded once to sQ1.14, ties to even. Cross products exact. `n_b`'s sum exact, one
//! rounding to sQ2.14. When `h` is parallel to `n` (`h x n = 0`) the unit uses the x axis, or
//! the y axis if that is parallel too, and raises `parallel` \[C\].
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `n1` (not unit, `0 < |n1| < 2`), `h` | sQ1.14 |
//! | `b1`, `b2` | sQ1.7 (the bump map's offsets, a DRF scale of 1 \[C\]) |
//! | `n`, `e1`, `e2` | sQ1.14 |
//! | `nb` | sQ2.14 (reflection unit's input) |

use crate::bump::normal_156::{unit_narrowings, unit_vector_in as unit, UNIT_FRAC};
use crate::bump::params::{RsqrtParams, ROUND, SAT};
use crate::bump::rsqrt_156::RsqrtTable;
use crate::fx::{Format, Narrowing};
use crate::kernel::{declared::Narrowings, Visitor};

/// Fraction bits of the vectors: those of unit 156's unit vectors.
pub const FRAC: u32 = UNIT_FRAC;

fn cross(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The frame's results.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    pub n: [i64; 3],
    pub e1: [i64; 3],
    pub e2: [i64; 3],
    pub nb: [i64; 3],
    /// `h` was parallel to `n` and an axis stood in for it.
    pub parallel: bool,
}

/// The frame unit as a function: raw `n1`, `h` (sQ1.14), `b1`, `b2` (sQ1.7), with its named
/// narrowings (a unit that holds one visits them with `#[narrow]`).
pub struct FrameUnit {
    p: RsqrtParams,
    table: RsqrtTable,
    n: [Narrowing; 3],
    e1: [Narrowing; 3],
    e2: [Narrowing; 3],
    nb: [Narrowing; 3],
}

impl Narrowings for FrameUnit {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        for x in [&self.n, &self.e1, &self.e2, &self.nb] {
            x.visit_narrowings(v);
        }
    }
}

/// Why `e2 = n x e1` never saturates.
const E2_BOUND: &str = "e2 = n x e1 of two orthogonal unit vectors: |e2| = 1, inside (-2, 2)";
/// Why `n_b` never saturates.
const NB_BOUND: &str =
    "n_b = n + e1 b1 + e2 b2 with unit n, e1, e2 and |b1|, |b2| < 1: |n_b| < 3, inside (-4, 4)";

impl Default for FrameUnit {
    fn default() -> Self {
        FrameUnit::new()
    }
}

impl FrameUnit {
    pub fn new() -> FrameUnit {
        let p = RsqrtParams::default();
        let held = |names: [&'static str; 3], f: Format, why: &'static str| {
            names.map(|n| Narrowing::new(n, f, ROUND, SAT).never_overflows(why))
        };
        FrameUnit {
            table: RsqrtTable::new(p).expect("the default parameters are valid"),
            p,
            n: unit_narrowings(["nx", "ny", "nz"]),
            e1: unit_narrowings(["e1x", "e1y", "e1z"]),
            e2: held(
                ["e2x", "e2y", "e2z"],
                Format::signed(16, FRAC as i32),
                E2_BOUND,
            ),
            nb: held(
                ["nbx", "nby", "nbz"],
                Format::signed(17, FRAC as i32),
                NB_BOUND,
            ),
        }
    }

    /// `None` for a zero `n1`.
    pub fn frame(&mut self, n1: [i64; 3], h: [i64; 3], b: (i64, i64)) -> Option<Frame> {
        let n1 = n1.map(i128::from);
        if n1 == [0; 3] {
            return None;
        }
        let n = unit(n1, &self.table, &self.p, &mut self.n);
        let nw = n.map(i128::from);
        let one = 1i128 << FRAC;
        let mut c = cross(h.map(i128::from), nw);
        let mut parallel = false;
        for axis in [[one, 0, 0], [0, one, 0]] {
            if c != [0; 3] {
                break;
            }
            parallel = true;
            c = cross(axis, nw);
        }
        let e1 = unit(c, &self.table, &self.p, &mut self.e1);
        let e2w = cross(nw, e1.map(i128::from));
        let e2: [i64; 3] = std::array::from_fn(|i| self.e2[i].raw(e2w[i], 2 * FRAC as i32) as i64);
        // n + e1 b1 + e2 b2 in units of 2^-21, rounded to sQ2.14.
        let nb = std::array::from_fn(|i| {
            let x = (i128::from(n[i]) << 7)
                + i128::from(e1[i]) * i128::from(b.0)
                + i128::from(e2[i]) * i128::from(b.1);
            self.nb[i].raw(x, 21) as i64
        });
        Some(Frame {
            n,
            e1,
            e2,
            nb,
            parallel,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_axes_give_the_axes() {
        let mut u = FrameUnit::new();
        let one = 1i64 << FRAC;
        let f = u.frame([0, 0, one / 2], [one, 0, 0], (0, 0)).unwrap();
        assert_eq!(f.n, [0, 0, one]);
        // e1 = x cross z = -y; e2 = z cross -y = x.
        assert_eq!(f.e1, [0, -one, 0]);
        assert_eq!(f.e2, [one, 0, 0]);
        assert_eq!(f.nb, [0, 0, one]);
        assert!(!f.parallel);
        let p = u.frame([0, 0, one], [0, 0, one], (64, 0)).unwrap();
        assert!(p.parallel);
        // With x standing in for h: e1 = -y as above; b1 = 1/2 moves n_b along -y.
        assert_eq!(p.nb, [0, -one / 2, one]);
        assert!(u.frame([0, 0, 0], [one, 0, 0], (0, 0)).is_none());
    }
}
