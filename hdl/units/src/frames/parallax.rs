//! Parallax mapping (002's reading list, Kaneko 2001; the formula is not in the seed): the
//! texture coordinate moved along the eye's direction by the height under it,
//! `uv' = uv + h V.xy / V.z` with `h = height scale + bias` and V the unit vector to the eye
//! in tangent space; the offset-limited form `uv + h V.xy` has no divide.
//!
//! # Arithmetic \[C\]
//! * `h = height 2^-8 scale + bias` exact (height uQ0.8, scale sQ3.12, bias sQ3.12).
//! * `1 / V.z` by the cube-face unit's reciprocal (table + one Newton step, relative error
//!   at most 5 x 2^-16), V.z held to at least 1/8 (grazing views would throw the
//!   coordinate far away).
//! * `h V.xy (1/V.z)` exact, added to uv, one rounding to sQ12.8 (ties to even, held).
//!
//! | port | format |
//! |---|---|
//! | `u`, `v`, `u'`, `v'` | sQ12.8 (texels) |
//! | `height` | uQ0.8 |
//! | `scale`, `bias` | sQ3.12 (texels) |
//! | `V` | sQ1.14 |

use crate::envmap::cube_face::{reciprocal, CubeFace};
use crate::fx::{quantise, Format, Narrowing, Overflow, Quant};
use crate::kernel::{Module, Reg, Signal};

/// The least V.z, raw sQ1.14 (1/8).
pub const VZ_MIN: i64 = 1 << 11;

/// The parallax arithmetic.
pub struct Parallax {
    tab: [u64; 64],
}

impl Default for Parallax {
    fn default() -> Self {
        Parallax::new()
    }
}

impl Parallax {
    pub fn new() -> Parallax {
        Parallax {
            tab: *CubeFace::new().table(),
        }
    }

    /// The new `(u, v)` (raw sQ12.8) of `uv` for `height`, `scale`, `bias` and eye `eye`.
    pub fn offset(
        &self,
        uv: [i64; 2],
        height: u8,
        hb: (i64, i64),
        eye: [i64; 3],
        limited: bool,
    ) -> [i64; 2] {
        let (sum, frac) = self.exact(uv, height, hb, eye, limited);
        sum.map(|x| quantise(x, frac, UV, Quant::RoundHalfEven, Overflow::Saturate) as i64)
    }

    /// The moved coordinates before their one rounding: `(raw, fraction bits)`.
    pub fn exact(
        &self,
        uv: [i64; 2],
        height: u8,
        (scale, bias): (i64, i64),
        eye: [i64; 3],
        limited: bool,
    ) -> ([i128; 2], i32) {
        // h in units of 2^-20: height 2^-8 scale 2^-12, bias 2^-12.
        let h = i128::from(height) * i128::from(scale) + (i128::from(bias) << 8);
        let (num, frac) = if limited {
            // h V.xy: 2^-34.
            (eye.map(|c| h * i128::from(c)), 34)
        } else {
            // V.z in 2^-14, read by the reciprocal as 16 fraction bits: 1/V.z = r1 2^-16
            // 2^-e 2^-2.
            let vz = eye[2].max(VZ_MIN) as u64;
            let (r1, e) = reciprocal(vz, &self.tab);
            (
                eye.map(|c| h * i128::from(c) * i128::from(r1)),
                (34 + 16 + 2 + e) as u32,
            )
        };
        let sum = std::array::from_fn(|c| (i128::from(uv[c]) << (frac - 8)) + num[c]);
        (sum, frac as i32)
    }
}

/// The coordinates' format, sQ12.8 texels.
const UV: Format = Format::signed(21, 8);

/// The unit: one register stage.
#[derive(Module)]
#[module(kind = "parallax")]
pub struct ParallaxUnit {
    math: Parallax,
    #[input]
    pub valid_in: Signal,
    #[input]
    pub limited: Signal,
    #[input]
    pub uv: [Signal; 2],
    #[input]
    pub height: Signal,
    #[input]
    pub scale: Signal,
    #[input]
    pub bias: Signal,
    #[input]
    pub eye: [Signal; 3],
    #[reg]
    pub valid: Reg,
    #[reg]
    pub out: [Reg; 2],
    /// The one rounding of each coordinate, held at the format's ends.
    #[narrow]
    round: [Narrowing; 2],
}

impl Default for ParallaxUnit {
    fn default() -> Self {
        ParallaxUnit::new()
    }
}

impl ParallaxUnit {
    pub fn new() -> ParallaxUnit {
        let uvf = Format::signed(21, 8);
        let w = Format::signed(16, 12);
        ParallaxUnit {
            math: Parallax::new(),
            valid_in: Signal::bit("valid_in"),
            limited: Signal::bit("limited"),
            uv: ["u", "v"].map(|n| Signal::new(n, uvf)),
            height: Signal::new("height", Format::unsigned(8, 8)),
            scale: Signal::new("scale", w),
            bias: Signal::new("bias", w),
            eye: ["vx", "vy", "vz"].map(|n| Signal::new(n, Format::signed(16, 14))),
            valid: Reg::new("valid", Format::uint(1)),
            out: ["u_out", "v_out"].map(|n| Reg::new(n, uvf)),
            round: ["u_out", "v_out"]
                .map(|n| Narrowing::new(n, UV, Quant::RoundHalfEven, Overflow::Saturate)),
        }
    }
}

impl ParallaxUnit {
    /// The offset coordinates of a valid query, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.valid_in.is_high();
        self.valid.set_next_bool(valid);
        if valid {
            let (sum, frac) = self.math.exact(
                self.uv.each_ref().map(|s| s.raw()),
                self.height.bits() as u8,
                (self.scale.raw(), self.bias.raw()),
                self.eye.each_ref().map(|s| s.raw()),
                self.limited.is_high(),
            );
            for ((r, n), x) in self.out.iter_mut().zip(&mut self.round).zip(sum) {
                r.set_next_raw(n.raw(x, frac) as i64);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant height H with bias -scale H moves nothing, exactly, in both forms; looking
    /// straight down moves nothing whatever the height.
    #[test]
    fn a_zero_height_or_a_straight_view_moves_nothing() {
        let p = Parallax::new();
        let uv = [1234, -567];
        let eye = [5000, -3000, 15000];
        for height in [0u8, 77, 255] {
            let scale = 1 << 12;
            let bias = -((i64::from(height) * scale) >> 8);
            for limited in [false, true] {
                if (i64::from(height) * scale) % 256 == 0 {
                    assert_eq!(p.offset(uv, height, (scale, bias), eye, limited), uv);
                }
                assert_eq!(
                    p.offset(uv, height, (scale, 0), [0, 0, 1 << 14], limited),
                    uv
                );
            }
        }
    }
}
