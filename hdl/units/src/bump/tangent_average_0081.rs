//! Para. 0081's "improved anisotropic filtering" on the FIG. 7 pipeline: footprint assembly
//! (Schilling & Knittel section 10) on a height map. The pipeline computes the tangents of
//! each of a pixel's N sample points in turn; this stage, between tangent unit 155 and normal
//! unit 156, adds them up and hands their mean to 156 with the pixel's last sample: one
//! normalisation a pixel (\[C\], `../shared/notes/seed-systems.md` section 11).
//!
//! # Arithmetic
//! `sum = (first ? 0 : acc) + x` for `x` in `du`, `dv`, `height` (exact: six more integer
//! bits than the tangent format, up to 64 samples); the mean `(sum + 2^(k-1)) >> k` for
//! `N = 2^k` (round half up; floor for negative halves), back in the tangent format (a mean
//! of values in range is in range). N = 1 passes the tangents through unchanged.
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `first`, `last` | `u1`: the sample is its pixel's first, last |
//! | `log2_n` | `u3`, N = 2^log2_n <= 64 |
//! | `du_in`, `dv_in` -> `du`, `dv` | the tangent format `sQ<..>.<tangent_frac>` |
//! | `h_in` -> `height` | the height format `uQ<..>.<tangent_frac>` |
//! | accumulators | the same with 6 more integer bits |

use crate::bump::params::BumpParams;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

#[derive(Clone, Debug, Module)]
#[module(kind = "tangent_average_0081")]
pub struct TangentAverage {
    #[input]
    pub first: Signal,
    #[input]
    pub last: Signal,
    #[input]
    pub log2_n: Signal,
    #[input]
    pub du_in: Signal,
    #[input]
    pub dv_in: Signal,
    #[input]
    pub h_in: Signal,
    #[output]
    pub du: Signal,
    #[output]
    pub dv: Signal,
    #[output]
    pub height: Signal,
    #[reg]
    acc: [Reg; 3],
}

/// The mean of `2^k` summed values, rounded half up.
pub fn mean_of(sum: i64, k: u32) -> i64 {
    if k == 0 {
        sum
    } else {
        (sum + (1 << (k - 1))) >> k
    }
}

impl TangentAverage {
    pub fn new(p: &BumpParams) -> TangentAverage {
        let (t, h) = (p.tangent_fmt(), p.height_out_fmt());
        let wide = |f: Format| Format::new(f.width() + 6, f.frac(), f.is_signed());
        TangentAverage {
            first: Signal::bit("first"),
            last: Signal::bit("last"),
            log2_n: Signal::new("log2_n", Format::uint(3)),
            du_in: Signal::new("du_in", t),
            dv_in: Signal::new("dv_in", t),
            h_in: Signal::new("h_in", h),
            du: Signal::new("du", t),
            dv: Signal::new("dv", t),
            height: Signal::new("height", h),
            acc: [
                Reg::new("acc_du", wide(t)),
                Reg::new("acc_dv", wide(t)),
                Reg::new("acc_height", wide(h)),
            ],
        }
    }

    /// The running sums and their means.
    pub fn eval(&mut self) {
        let first = self.first.is_high();
        let k = self.log2_n.bits() as u32;
        let ins = [self.du_in.raw(), self.dv_in.raw(), self.h_in.raw()];
        let mut means = [0i64; 3];
        for (c, x) in ins.into_iter().enumerate() {
            let sum = if first { 0 } else { self.acc[c].q().raw() } + x;
            self.acc[c].set_next_raw(sum);
            means[c] = mean_of(sum, k);
        }
        self.du.set_raw(means[0]);
        self.dv.set_raw(means[1]);
        self.height.set_raw(means[2]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_rounds_half_up_and_one_sample_passes_through() {
        assert_eq!(mean_of(-7, 0), -7);
        assert_eq!(mean_of(7, 1), 4, "3.5 -> 4");
        assert_eq!(mean_of(-7, 1), -3, "-3.5 -> -3 (half up)");
        assert_eq!(mean_of(13, 2), 3, "3.25 -> 3");
        assert_eq!(mean_of(-13, 2), -3, "-3.25 -> -3");
        assert_eq!(mean_of(-15, 2), -4, "-3.75 -> -4");
    }

    /// Four samples summed from `first`, their mean with the last; a new pixel restarts.
    #[test]
    fn sums_restart_at_each_pixels_first_sample() {
        let p = BumpParams::default();
        let mut a = TangentAverage::new(&p);
        let one = 1i64 << p.tangent_frac;
        let mut out = Vec::new();
        for (i, (x, first, k)) in [
            (1, true, 2),
            (2, false, 2),
            (3, false, 2),
            (6, false, 2),
            (5, true, 0),
        ]
        .into_iter()
        .enumerate()
        {
            a.first.set_bool(first);
            a.log2_n.set_bits(k);
            a.du_in.set_raw(x * one);
            a.dv_in.set_raw(-x * one);
            a.h_in.set_raw(i as i64 * one);
            a.eval();
            out.push((a.du.raw(), a.dv.raw(), a.height.raw()));
            a.tick(false);
        }
        // (1 + 2 + 3 + 6) / 4 = 3; heights (0 + 1 + 2 + 3) / 4 = 1.5 -> exact in Q.16.
        assert_eq!(out[3], (3 * one, -3 * one, 3 * one / 2));
        assert_eq!(out[4], (5 * one, -5 * one, 4 * one));
    }
}
