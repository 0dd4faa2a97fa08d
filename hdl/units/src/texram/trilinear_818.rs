//! The trilinear interpolator 818, \[C\]: the exact sum of the eight texels, each weighed by
//! `w_a * w_b * w_f` (8-bit weights `256 - a` and `a`, so the eight products sum to `2^24`),
//! rounded once to 8 bits, half up: `(sum + 2^23) >> 24`. The sum fits 32 bits
//! (`255 * 2^24 < 2^32`); it is carried in a u64.

use crate::fx::Format;
use crate::kernel::{Module, Reg};

/// The weights of one level's 2x2 in texel order (i, j), (i+1, j), (i, j+1), (i+1, j+1):
/// each at most `2^16`, together `2^16`.
pub fn bilinear_weights(a: u8, b: u8) -> [u32; 4] {
    let (a, b) = (u32::from(a), u32::from(b));
    [(256 - a) * (256 - b), a * (256 - b), (256 - a) * b, a * b]
}

/// The interpolated texel: `texels` fine 2x2 then coarse 2x2, `a`, `b` per level, `f` the
/// coarse level's weight.
pub fn trilinear(texels: &[u8; 8], a: [u8; 2], b: [u8; 2], f: u8) -> u8 {
    ((trilinear_sum(texels, a, b, f) + (1 << 23)) >> 24) as u8
}

/// The exact weighted sum before the rounding: the texel value times `2^24` (u32; footprint
/// assembly adds these up and rounds once).
pub fn trilinear_sum(texels: &[u8; 8], a: [u8; 2], b: [u8; 2], f: u8) -> u64 {
    let wf = [256 - u64::from(f), u64::from(f)];
    let mut sum = 0u64;
    for n in 0..2 {
        let w = bilinear_weights(a[n], b[n]);
        for t in 0..4 {
            sum += u64::from(texels[4 * n + t]) * u64::from(w[t]) * wf[n];
        }
    }
    sum
}

/// The interpolator's register: the components of a colour request finished so far (R in the
/// top byte), which come out with its last.
#[derive(Clone, Debug, Module)]
#[module(kind = "trilinear_818")]
pub struct Trilinear818 {
    #[reg]
    pub acc_rgba: Reg,
}

impl Default for Trilinear818 {
    fn default() -> Self {
        Trilinear818::new()
    }
}

impl Trilinear818 {
    pub fn new() -> Trilinear818 {
        Trilinear818 {
            acc_rgba: Reg::new("acc_rgba", Format::uint(32)),
        }
    }

    /// Nothing of its own: the chip's `eval` sets its register.
    pub fn eval(&mut self) {}

    /// The colour so far with this access's interpolated `value`: all four components for a
    /// luminance access (`part` 0, the last), else component `part` (R top byte); kept.
    pub fn collect(&mut self, value: u8, part: u64, last: bool) -> u32 {
        let rgba = if last && part == 0 {
            u32::from_be_bytes([value; 4])
        } else {
            let shift = 8 * (3 - part);
            (self.acc_rgba.q().bits() as u32 & !(0xFF << shift)) | u32::from(value) << shift
        };
        self.keep(rgba);
        rgba
    }

    /// `rgba` (an index access's looked-up colour) kept as the colour so far.
    pub fn keep(&mut self, rgba: u32) {
        self.acc_rgba.set_next_bits(u64::from(rgba));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_for_every_a_and_b() {
        for a in 0..=255u8 {
            for b in 0..=255u8 {
                assert_eq!(bilinear_weights(a, b).iter().sum::<u32>(), 1 << 16);
            }
        }
    }

    #[test]
    fn the_result_is_the_rounded_mean_and_within_its_texels() {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let t: [u8; 8] = x.to_le_bytes();
            let (a, b, f) = ([t[1] ^ t[5], t[2]], [t[3], t[7] ^ t[0]], t[6] ^ t[4]);
            let got = trilinear(&t, a, b, f);
            let (lo, hi) = (*t.iter().min().unwrap(), *t.iter().max().unwrap());
            assert!((lo..=hi).contains(&got), "{t:?} {a:?} {b:?} {f}: {got}");
            // The one rounding: `got` is the exact weighted mean rounded half up, i.e.
            // 2^24 (got - 1/2) <= sum < 2^24 (got + 1/2), with the weights as integer products.
            let mut sum = 0u128;
            for n in 0..2 {
                let wf = if n == 0 {
                    256 - u128::from(f)
                } else {
                    u128::from(f)
                };
                let (fa, fb) = (u128::from(a[n]), u128::from(b[n]));
                let w = [
                    (256 - fa) * (256 - fb),
                    fa * (256 - fb),
                    (256 - fa) * fb,
                    fa * fb,
                ];
                for k in 0..4 {
                    sum += u128::from(t[4 * n + k]) * w[k] * wf;
                }
            }
            let g = u128::from(got) << 25;
            assert!(
                g <= 2 * sum + (1 << 24) && 2 * sum + (1 << 24) < g + (1 << 25),
                "{got}"
            );
        }
    }

    #[test]
    fn zero_weights_select_the_first_texel_and_constants_stay() {
        let t = [10, 20, 30, 40, 50, 60, 70, 80];
        assert_eq!(trilinear(&t, [0, 0], [0, 0], 0), 10);
        assert_eq!(trilinear(&[77; 8], [13, 200], [255, 1], 99), 77);
        assert_eq!(trilinear(&[255; 8], [255, 255], [255, 255], 255), 255);
    }
}
