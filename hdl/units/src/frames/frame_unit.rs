//! The per-pixel frame unit \[C\] shared by bump maps (003's basis, Blinn's perturbation) and
//! tangent-space normal maps (002): from the interpolated tangent T, bitangent B and normal
//! N, an optional Gram-Schmidt (Maya's per-pixel re-orthogonalisation, 003), then
//! `n' = a N + gx T + gy B` normalised by normal unit 156's inverse square root.
//!
//! * Bump: `a = 1`, `(gx, gy)` the height's slope scaled and negated (`-dh/du`, `-dh/dv`:
//!   003's listing adds `+dM`, which bends the normal into the bump, and calls the sum a unit
//!   vector, which it is not; `golden::tangents` has both tests).
//! * Normal map: the texel's RGB8 decoded as `c - 128` \[C\] (128 is exactly 0, so a flat
//!   texel (128, 128, 255) gives N exactly; a common factor leaves the direction unchanged),
//!   or as `2c - 255` ([`Decode::Symmetric`], 0 and 255 symmetric, 128 a little above 0);
//!   002's `mapVector = vector(sampleColor)` omits the range change and tilts a flat texel.
//! * Gram-Schmidt: `N^ = N/|N|`, `t = (T - (N^.T) N^)/|...|`, `b = s N^ x t` with `s` the
//!   sign of `B.(N^ x t)`; without it T, B and N are used as they come.
//!
//! Every sum exact, each normalisation rounded once per component to sQ1.14 (ties to even).
//!
//! | port | format |
//! |---|---|
//! | `t`, `b`, `n` (interpolated, `0 < |v| < 2`) | sQ1.14 |
//! | `a`, `gx`, `gy` | sQ3.12 |
//! | `nout`, `tout`, `bout` | sQ1.14 |

use crate::bump::normal_156::{unit_narrowings, unit_vector_in as unit};
use crate::bump::params::{RsqrtParams, ROUND, SAT};
use crate::bump::rsqrt_156::RsqrtTable;
use crate::fx::{Format, Narrowing};
use crate::kernel::{declared::Narrowings, Module, Reg, Signal, Visitor};

/// Fraction bits of the vectors and of the weights.
pub const VEC_FRAC: u32 = 14;
pub const W_FRAC: u32 = 12;

/// What the unit gives: the perturbed unit normal and the frame it used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FrameOut {
    pub n: [i64; 3],
    pub t: [i64; 3],
    pub b: [i64; 3],
    /// The perturbed normal was zero (no direction): `n` is N's unit \[C\].
    pub zero: bool,
}

/// The unit's arithmetic.
pub struct FrameMath {
    table: RsqrtTable,
    p: RsqrtParams,
    /// Its named narrowings: N's unit, Gram-Schmidt's t and b, the perturbed normal.
    round: FrameNarrowings,
}

/// The frame unit's narrowings, each a vector's components into sQ1.14.
struct FrameNarrowings {
    n: [Narrowing; 3],
    t: [Narrowing; 3],
    b: [Narrowing; 3],
    out: [Narrowing; 3],
}

/// Which unit vector a normalisation makes.
#[derive(Clone, Copy)]
enum Which {
    N,
    T,
    Out,
}

impl Narrowings for FrameMath {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        let r = &self.round;
        for x in [&r.n, &r.t, &r.b, &r.out] {
            x.visit_narrowings(v);
        }
    }
}

/// Why Gram-Schmidt's `b` never saturates.
const B_BOUND: &str = "b = s n x t of two unit vectors: |b| <= 1, inside (-2, 2)";

impl Default for FrameMath {
    fn default() -> Self {
        FrameMath::new()
    }
}

fn cross(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [i128; 3], b: [i128; 3]) -> i128 {
    (0..3).map(|c| a[c] * b[c]).sum()
}

impl FrameMath {
    pub fn new() -> FrameMath {
        let p = RsqrtParams::default();
        let b = ["b_gs_x", "b_gs_y", "b_gs_z"].map(|n| {
            Narrowing::new(n, Format::signed(16, VEC_FRAC as i32), ROUND, SAT)
                .never_overflows(B_BOUND)
        });
        FrameMath {
            table: RsqrtTable::new(p).expect("the default parameters are valid"),
            p,
            round: FrameNarrowings {
                n: unit_narrowings(["n_unit_x", "n_unit_y", "n_unit_z"]),
                t: unit_narrowings(["t_gs_x", "t_gs_y", "t_gs_z"]),
                b,
                out: unit_narrowings(["nout_x", "nout_y", "nout_z"]),
            },
        }
    }

    /// `v / |v|` in sQ1.14 (at any binary point of `v`) by the narrowings of `which`, or
    /// `None` for zero.
    fn unit(&mut self, which: Which, v: [i128; 3]) -> Option<[i64; 3]> {
        let r = &mut self.round;
        let n = match which {
            Which::N => &mut r.n,
            Which::T => &mut r.t,
            Which::Out => &mut r.out,
        };
        (v != [0; 3]).then(|| unit(v, &self.table, &self.p, n))
    }

    /// Gram-Schmidt of `(t, b)` against `n` (all raw sQ1.14): unit N, t, and b = s N x t.
    pub fn orthonormalise(
        &mut self,
        t: [i64; 3],
        b: [i64; 3],
        n: [i64; 3],
    ) -> ([i64; 3], [i64; 3], [i64; 3]) {
        let nu = self
            .unit(Which::N, n.map(i128::from))
            .unwrap_or([0, 0, 1 << VEC_FRAC]);
        let nw = nu.map(i128::from);
        let tw = t.map(i128::from);
        // t - (n.t) n in units of 2^-42.
        let d = dot(nw, tw);
        let r: [i128; 3] = std::array::from_fn(|c| (tw[c] << 28) - d * nw[c]);
        let tu = self.unit(Which::T, r).unwrap_or([0; 3]);
        let nt = cross(nw, tu.map(i128::from));
        let s = if dot(b.map(i128::from), nt) < 0 {
            -1
        } else {
            1
        };
        let b = &mut self.round.b;
        let bu = std::array::from_fn(|c| b[c].raw(s * nt[c], 2 * VEC_FRAC as i32) as i64);
        (tu, bu, nu)
    }

    /// The unit's result for frame `(t, b, n)` (sQ1.14) and weights `(a, gx, gy)` (sQ3.12).
    pub fn perturb(&mut self, frame: [[i64; 3]; 3], w: [i64; 3], gram_schmidt: bool) -> FrameOut {
        let [t, b, n] = frame;
        let (t, b, n) = if gram_schmidt {
            self.orthonormalise(t, b, n)
        } else {
            (t, b, n)
        };
        let [a, gx, gy] = w.map(i128::from);
        // a N + gx T + gy B in units of 2^-26.
        let v: [i128; 3] = std::array::from_fn(|c| {
            a * i128::from(n[c]) + gx * i128::from(t[c]) + gy * i128::from(b[c])
        });
        let (out, zero) = match self.unit(Which::Out, v) {
            Some(u) => (u, false),
            None => (
                self.unit(Which::N, n.map(i128::from))
                    .unwrap_or([0, 0, 1 << VEC_FRAC]),
                true,
            ),
        };
        FrameOut { n: out, t, b, zero }
    }
}

/// How an RGB8 normal-map texel becomes a direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Decode {
    /// `c - 128`: 128 is zero.
    #[default]
    Offset,
    /// `2c - 255`: 0 and 255 are -1 and 1.
    Symmetric,
}

/// A normal-map texel as the unit's weights `(a, gx, gy)` in sQ3.12: `(c - 128) 2^-7` or
/// `(2c - 255) 2^-8`, blue weighting N, red T, green B.
pub fn decode_rgb8(rgb: [u8; 3], d: Decode) -> [i64; 3] {
    let x = rgb.map(|c| match d {
        Decode::Offset => (i64::from(c) - 128) << (W_FRAC - 7),
        Decode::Symmetric => (2 * i64::from(c) - 255) << (W_FRAC - 8),
    });
    [x[2], x[0], x[1]]
}

const T: [&str; 3] = ["tx", "ty", "tz"];
const B: [&str; 3] = ["bx", "by", "bz"];
const N: [&str; 3] = ["nx", "ny", "nz"];

/// The unit: one register stage.
#[derive(Module)]
#[module(kind = "frame_unit")]
pub struct FrameUnit {
    /// The arithmetic and its narrowings.
    #[narrow]
    math: FrameMath,
    #[input]
    pub valid_in: Signal,
    #[input]
    pub gram_schmidt: Signal,
    #[input]
    pub frame: [[Signal; 3]; 3],
    /// a, gx, gy.
    #[input]
    pub w: [Signal; 3],
    #[reg]
    pub valid: Reg,
    #[reg]
    pub nout: [Reg; 3],
    #[reg]
    pub tout: [Reg; 3],
    #[reg]
    pub bout: [Reg; 3],
    #[reg]
    pub zero: Reg,
}

impl Default for FrameUnit {
    fn default() -> Self {
        FrameUnit::new()
    }
}

impl FrameUnit {
    pub fn new() -> FrameUnit {
        let (vf, wf) = (Format::signed(16, 14), Format::signed(16, 12));
        FrameUnit {
            math: FrameMath::new(),
            valid_in: Signal::bit("valid_in"),
            gram_schmidt: Signal::bit("gram_schmidt"),
            frame: [T, B, N].map(|r| r.map(|x| Signal::new(x, vf))),
            w: ["a", "gx", "gy"].map(|x| Signal::new(x, wf)),
            valid: Reg::new("valid", Format::uint(1)),
            nout: ["nout_x", "nout_y", "nout_z"].map(|x| Reg::new(x, vf)),
            tout: ["tout_x", "tout_y", "tout_z"].map(|x| Reg::new(x, vf)),
            bout: ["bout_x", "bout_y", "bout_z"].map(|x| Reg::new(x, vf)),
            zero: Reg::new("zero", Format::uint(1)),
        }
    }
}

impl FrameUnit {
    /// The perturbed frame of a valid pixel, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.valid_in.is_high();
        self.valid.set_next_bool(valid);
        if !valid {
            return;
        }
        let f = self.frame.each_ref().map(|r| r.each_ref().map(|s| s.raw()));
        let w = self.w.each_ref().map(|s| s.raw());
        let o = self.math.perturb(f, w, self.gram_schmidt.is_high());
        for c in 0..3 {
            self.nout[c].set_next_raw(o.n[c]);
            self.tout[c].set_next_raw(o.t[c]);
            self.bout[c].set_next_raw(o.b[c]);
        }
        self.zero.set_next_bool(o.zero);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat normal-map texel (128, 128, 255) gives N exactly; the axes frame passes
    /// through Gram-Schmidt unchanged; 002's printed decode (the sample as the vector) does
    /// not give N.
    #[test]
    fn a_flat_texel_gives_the_normal() {
        let mut m = FrameMath::new();
        let one = 1i64 << VEC_FRAC;
        let frame = [[one, 0, 0], [0, one, 0], [0, 0, one]];
        for gs in [false, true] {
            let o = m.perturb(frame, decode_rgb8([128, 128, 255], Decode::Offset), gs);
            assert_eq!(o.n, [0, 0, one]);
            assert_eq!((o.t, o.b), (frame[0], frame[1]));
            // The symmetric decode puts 128 at 1/255: a tilt of 64 LSB.
            let o = m.perturb(frame, decode_rgb8([128, 128, 255], Decode::Symmetric), gs);
            assert_eq!(o.n, [64, 64, one]);
            // As 002's listing reads it (no range change), flat is far from flat.
            let raw = [255, 128, 128].map(|c: i64| c << (W_FRAC - 8));
            assert!(m.perturb(frame, raw, gs).n[0] > 5000);
        }
        // Zero weights: no direction, N's unit, flagged.
        let o = m.perturb(frame, [0, 0, 0], false);
        assert!(o.zero && o.n == [0, 0, one]);
    }

    /// Every byte decodes to its documented weight exactly, in sQ3.12: `(c - 128) / 128` or
    /// `(2c - 255) / 256`; blue weighs N, red t and green b.
    #[test]
    fn texels_decode_to_their_weights() {
        for c in 0..=255u8 {
            let (o, s) = (
                decode_rgb8([c; 3], Decode::Offset),
                decode_rgb8([c; 3], Decode::Symmetric),
            );
            // raw / 2^12 = (c - 128) / 128 and (2c - 255) / 256, cross-multiplied.
            let c = i64::from(c);
            assert_eq!(o[0] * 128, (c - 128) << W_FRAC, "{c}");
            assert_eq!(s[0] * 256, (2 * c - 255) << W_FRAC, "{c}");
            assert!(o.iter().all(|&x| x == o[0]) && s.iter().all(|&x| x == s[0]));
        }
        let o = decode_rgb8([129, 130, 131], Decode::Offset);
        assert_eq!(o, [3 << (W_FRAC - 7), 1 << (W_FRAC - 7), 2 << (W_FRAC - 7)]);
    }

    /// The frame's degenerate inputs: a zero normal is taken as +z (in Gram-Schmidt, and as
    /// the answer to zero weights with it); a bitangent with no part along N x t (zero, or
    /// along t) leaves the frame right-handed; one against N x t makes it left-handed.
    #[test]
    fn degenerate_frames_have_defined_results() {
        let mut m = FrameMath::new();
        let one = 1i64 << VEC_FRAC;
        let (x, y, z) = ([one, 0, 0], [0, one, 0], [0, 0, one]);
        assert_eq!(m.orthonormalise(x, y, [0; 3]), (x, y, z));
        let o = m.perturb([x, y, [0; 3]], [0, 0, 0], false);
        assert!(o.zero && o.n == z, "{o:?}");
        for b in [[0; 3], x] {
            assert_eq!(m.orthonormalise(x, b, z), (x, y, z), "{b:?}");
        }
        assert_eq!(m.orthonormalise(x, [0, -one, 0], z), (x, [0, -one, 0], z));
    }
}
