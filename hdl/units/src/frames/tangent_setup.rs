//! The tangent setup unit (003, in hardware \[C\]): per triangle, from its edges and UV edges,
//! `dP/du` and `dP/dv`, and at a corner with the unit normal `n` the orthonormal tangent
//! `t = normalize(dP/du - (n . dP/du) n)` and bitangent `b = s n x t`, `s` the general
//! handedness `sign((n x t) . dP/dv)` (the seed's UV-winding test is wrong for triangles
//! winding clockwise about n; `golden::tangents` has the test that shows it).
//!
//! # Arithmetic
//! * `uvk = d2.x d1.y - d1.x d2.y` and the numerators `d1.y v2 - d2.y v1`, `d2.x v1 - d1.x v2`
//!   exact; `1/|uvk|` by the cube-face unit's reciprocal (64-entry table of interval
//!   midpoints, one Newton step: relative error at most 5 x 2^-16, `envmap::cube_face`);
//!   `dP/du`, `dP/dv` the exact products rounded once to sQ23.16 (ties to even, held). The
//!   reciprocal scales both alike: it changes their length, never their direction.
//! * UVs on a line (`uvk = 0`): `dP/du = v1 / d1.x`, else `v2 / d2.x` (the seed's), by the
//!   same reciprocal; else zero; `degenerate` raised, never a NaN.
//! * `t`: the Gram-Schmidt sum exact from the rounded `dP/du`, normalised by normal unit 156's
//!   inverse square root (`envmap::frame_eq2`'s `unit`), sQ1.14; a zero remainder gives
//!   `t = 0` and `zero` \[C\]. `b = s n x t`, exact, rounded once to sQ1.14.
//!
//! | port | format |
//! |---|---|
//! | `v1`, `v2` (edges P1 - P0, P2 - P0) | sQ7.16 |
//! | `d1`, `d2` (UV edges) | sQ3.16 |
//! | `n` (unit) | sQ1.14 |
//! | `dpdu`, `dpdv` | sQ23.16 |
//! | `t`, `b` | sQ1.14 |

use crate::bump::normal_156::{unit_narrowings, unit_vector_in as unit};
use crate::bump::params::{RsqrtParams, ROUND, SAT};
use crate::bump::rsqrt_156::RsqrtTable;
use crate::envmap::cube_face::{reciprocal, CubeFace};
use crate::fx::{Format, Narrowing};
use crate::kernel::{declared::Narrowings, Module, Reg, Signal, Visitor};

/// Fraction bits of positions, UVs and dP/du.
pub const POS_FRAC: u32 = 16;
/// Fraction bits of the unit vectors.
pub const VEC_FRAC: u32 = 14;

/// A triangle corner's setup.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Setup {
    pub dpdu: [i64; 3],
    pub dpdv: [i64; 3],
    pub t: [i64; 3],
    pub b: [i64; 3],
    pub degenerate: bool,
    pub zero: bool,
}

/// The unit's arithmetic, its tables made once, with its named narrowings: `dP/du` and
/// `dP/dv` into sQ23.16, `t` and `b` into sQ1.14.
pub struct TangentMath {
    recip: [u64; 64],
    rsqrt: RsqrtTable,
    p: RsqrtParams,
    /// `dP/du`'s and `dP/dv`'s components.
    dp: [[Narrowing; 3]; 2],
    t: [Narrowing; 3],
    b: [Narrowing; 3],
}

impl Narrowings for TangentMath {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        self.dp.visit_narrowings(v);
        self.t.visit_narrowings(v);
        self.b.visit_narrowings(v);
    }
}

/// Why `b = s n x t` never saturates.
const B_BOUND: &str =
    "b = s n x t of two unit vectors (n by the port's contract): |b| <= 1, inside (-2, 2)";

impl Default for TangentMath {
    fn default() -> Self {
        TangentMath::new()
    }
}

fn cross(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl TangentMath {
    pub fn new() -> TangentMath {
        let p = RsqrtParams::default();
        let dp = |names: [&'static str; 3]| {
            names.map(|n| Narrowing::new(n, Format::signed(40, POS_FRAC as i32), ROUND, SAT))
        };
        TangentMath {
            recip: *CubeFace::new().table(),
            rsqrt: RsqrtTable::new(p).expect("the default parameters are valid"),
            p,
            dp: [
                dp(["dpdu_x", "dpdu_y", "dpdu_z"]),
                dp(["dpdv_x", "dpdv_y", "dpdv_z"]),
            ],
            t: unit_narrowings(["tx", "ty", "tz"]),
            b: ["bx", "by", "bz"].map(|n| {
                Narrowing::new(n, Format::signed(16, VEC_FRAC as i32), ROUND, SAT)
                    .never_overflows(B_BOUND)
            }),
        }
    }

    /// `num / den` for exact `num` rounded to sQ23.16 by the narrowings of `dP/du` (`which`
    /// 0) or `dP/dv` (1): `num` carries `nf` fraction bits, `den` (not zero) `df`.
    fn divide(
        &mut self,
        which: usize,
        num: [i128; 3],
        den: i128,
        (nf, df): (u32, u32),
    ) -> [i64; 3] {
        // 1/|den| = r1 2^-16 2^-e with den read as 16 fraction bits; den really has df.
        let (r1, e) = reciprocal(den.unsigned_abs() as u64, &self.recip);
        let sign = den.signum();
        // num r1: nf + 16 fraction bits; times 2^-e and 2^(df - 16) for den's own bits.
        let frac = nf as i32 + 16 + e - (df as i32 - 16);
        let round = &mut self.dp[which];
        std::array::from_fn(|c| round[c].raw(num[c] * i128::from(r1) * sign, frac) as i64)
    }

    /// The setup of the triangle with edges `v` (sQ7.16), UV edges `d` (sQ3.16) at the corner
    /// with unit normal `n` (sQ1.14).
    pub fn setup(&mut self, v: [[i64; 3]; 2], d: [[i64; 2]; 2], n: [i64; 3]) -> Setup {
        let (v1, v2) = (v[0].map(i128::from), v[1].map(i128::from));
        let (d1, d2) = (d[0].map(i128::from), d[1].map(i128::from));
        let uvk = d2[0] * d1[1] - d1[0] * d2[1];
        let mut s = Setup::default();
        if uvk != 0 {
            // Numerators: 16 + 16 fraction bits; uvk 32.
            let nu: [i128; 3] = std::array::from_fn(|c| d1[1] * v2[c] - d2[1] * v1[c]);
            let nv: [i128; 3] = std::array::from_fn(|c| d2[0] * v1[c] - d1[0] * v2[c]);
            s.dpdu = self.divide(0, nu, uvk, (32, 32));
            s.dpdv = self.divide(1, nv, uvk, (32, 32));
        } else {
            s.degenerate = true;
            if d1[0] != 0 {
                s.dpdu = self.divide(0, v1, d1[0], (16, 16));
            } else if d2[0] != 0 {
                s.dpdu = self.divide(0, v2, d2[0], (16, 16));
            }
        }
        self.frame(&mut s, n);
        s
    }

    /// `t` and `b` of `s.dpdu`, `s.dpdv` at `n`.
    fn frame(&mut self, s: &mut Setup, n: [i64; 3]) {
        let n = n.map(i128::from);
        let du = s.dpdu.map(i128::from);
        // dP/du - (n . dP/du) n, in units of 2^-(16 + 28).
        let nd: i128 = (0..3).map(|c| n[c] * du[c]).sum();
        let r: [i128; 3] = std::array::from_fn(|c| (du[c] << 28) - nd * n[c]);
        if r == [0; 3] {
            s.zero = true;
            return;
        }
        s.t = unit(r, &self.rsqrt, &self.p, &mut self.t);
        let nt = cross(n, s.t.map(i128::from));
        let dv = s.dpdv.map(i128::from);
        let sign = if (0..3).map(|c| nt[c] * dv[c]).sum::<i128>() < 0 {
            -1
        } else {
            1
        };
        let b = &mut self.b;
        s.b = std::array::from_fn(|c| b[c].raw(sign * nt[c], 2 * VEC_FRAC as i32) as i64);
    }
}

const V: [[&str; 3]; 2] = [["v1x", "v1y", "v1z"], ["v2x", "v2y", "v2z"]];
const D: [[&str; 2]; 2] = [["d1u", "d1v"], ["d2u", "d2v"]];

/// The unit: one register stage.
#[derive(Module)]
#[module(kind = "tangent_setup")]
pub struct TangentSetup {
    /// The arithmetic and its narrowings.
    #[narrow]
    math: TangentMath,
    #[input]
    pub valid_in: Signal,
    #[input]
    pub v: [[Signal; 3]; 2],
    #[input]
    pub d: [[Signal; 2]; 2],
    #[input]
    pub n: [Signal; 3],
    #[reg]
    pub valid: Reg,
    #[reg]
    pub dpdu: [Reg; 3],
    #[reg]
    pub dpdv: [Reg; 3],
    #[reg]
    pub t: [Reg; 3],
    #[reg]
    pub b: [Reg; 3],
    #[reg]
    pub degenerate: Reg,
    #[reg]
    pub zero: Reg,
}

impl Default for TangentSetup {
    fn default() -> Self {
        TangentSetup::new()
    }
}

impl TangentSetup {
    pub fn new() -> TangentSetup {
        let (pos, uv) = (Format::signed(24, 16), Format::signed(20, 16));
        let (big, unitf) = (Format::signed(40, 16), Format::signed(16, 14));
        let reg3 = |names: [&'static str; 3], f: Format| names.map(|n| Reg::new(n, f));
        TangentSetup {
            math: TangentMath::new(),
            valid_in: Signal::bit("valid_in"),
            v: V.map(|r| r.map(|n| Signal::new(n, pos))),
            d: D.map(|r| r.map(|n| Signal::new(n, uv))),
            n: ["nx", "ny", "nz"].map(|x| Signal::new(x, unitf)),
            valid: Reg::new("valid", Format::uint(1)),
            dpdu: reg3(["dpdu_x", "dpdu_y", "dpdu_z"], big),
            dpdv: reg3(["dpdv_x", "dpdv_y", "dpdv_z"], big),
            t: reg3(["tx", "ty", "tz"], unitf),
            b: reg3(["bx", "by", "bz"], unitf),
            degenerate: Reg::new("degenerate", Format::uint(1)),
            zero: Reg::new("zero", Format::uint(1)),
        }
    }
}

impl TangentSetup {
    /// The frame of a valid triangle, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.valid_in.is_high();
        self.valid.set_next_bool(valid);
        if !valid {
            return;
        }
        let v = self.v.each_ref().map(|r| r.each_ref().map(|s| s.raw()));
        let d = self.d.each_ref().map(|r| r.each_ref().map(|s| s.raw()));
        let s = self.math.setup(v, d, self.n.each_ref().map(|x| x.raw()));
        for c in 0..3 {
            self.dpdu[c].set_next_raw(s.dpdu[c]);
            self.dpdv[c].set_next_raw(s.dpdv[c]);
            self.t[c].set_next_raw(s.t[c]);
            self.b[c].set_next_raw(s.b[c]);
        }
        self.degenerate.set_next_bool(s.degenerate);
        self.zero.set_next_bool(s.zero);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis-aligned quad's triangle: UVs = xy, n = z: t = x, b = y exactly; dP/du = x.
    #[test]
    fn the_axes_give_the_axes() {
        let mut m = TangentMath::new();
        let one = 1i64 << POS_FRAC;
        let s = m.setup(
            [[one, 0, 0], [0, one, 0]],
            [[one, 0], [0, one]],
            [0, 0, 1 << 14],
        );
        // The lengths within the reciprocal's 5 x 2^-16 (relative), the directions exact.
        assert!((s.dpdu[0] - one).abs() <= 5 && s.dpdu[1..] == [0, 0]);
        assert!((s.dpdv[1] - one).abs() <= 5 && s.dpdv[0] == 0 && s.dpdv[2] == 0);
        assert_eq!(s.t, [1 << 14, 0, 0]);
        assert_eq!(s.b, [0, 1 << 14, 0]);
        assert!(!s.degenerate && !s.zero);
        // UVs all equal: no tangent, flagged.
        let s = m.setup(
            [[one, 0, 0], [0, one, 0]],
            [[0, 0], [0, 0]],
            [0, 0, 1 << 14],
        );
        assert!(s.degenerate && s.zero);
        assert_eq!(s.t, [0; 3]);
    }
}
