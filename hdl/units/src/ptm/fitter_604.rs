//! The fitter 604 of 001's Fig. 6 as a streaming unit: the least-squares fit of a texel's
//! occlusion samples is `A = P K` with the pseudo-inverse `P = (A^T A)^-1 A^T` the same for
//! every texel (\[0049\]), so six multiply-accumulate lanes take one light's sample a cycle
//! and, after the texel's L-th, the six coefficients go out quantised to the PTM 612 format.
//!
//! * Sample: uQ0.8, 255 lit. Occlusion `x = 255 - sample`, widened to uQ1.8 as
//!   `K = x + (x >> 7)` \[C\] (0 and 255 map to 0 and 1 exactly; any other within 2^-9 of
//!   x/255).
//! * Lane j: `acc_j = sum_i P_ji K_i`, exact (sQ7.20 times uQ1.8 into sQ17.28).
//! * Out: `q_j = round((acc_j - b_j 2^8) / 2^(e_j + 8))`, half up ([`PtmFormat::quantise`]).
//!
//! Samples come in texel by texel, lights in the order of P's columns, one a cycle when
//! `in_valid` (no backpressure); `out_valid` rises the cycle after a texel's last sample.

use super::texture_612::PtmFormat;
use super::MAX_LIGHTS;
use crate::fx::{Format, Narrowing};
use crate::kernel::{Module, Reg, Signal};

/// Lane register width: sQ17.28.
const ACC_BITS: u32 = 46;

/// The occlusion of a sample, uQ1.8.
pub fn occlusion(sample: u8) -> u32 {
    let x = 255 - u32::from(sample);
    x + (x >> 7)
}

/// The unit.
#[derive(Clone, Debug, Module)]
#[module(kind = "ptm_fitter_604")]
pub struct Fitter604 {
    p: [Vec<i32>; 6],
    fmt: PtmFormat,
    #[input]
    pub in_valid: Signal,
    #[input]
    pub in_sample: Signal,
    /// The sample's occlusion (combinational).
    #[output]
    pub k: Signal,
    #[reg]
    pub light: Reg,
    #[reg]
    pub acc: [Reg; 6],
    #[reg]
    pub out_valid: Reg,
    #[reg]
    pub out_q: [Reg; 6],
    /// Each coefficient's one rounding into its stored format.
    #[narrow]
    round: [Narrowing; 6],
}

impl Fitter604 {
    /// The fitter of the pseudo-inverse `p` (6 rows of L raw sQ7.20 entries) into `fmt`.
    pub fn new(p: [Vec<i32>; 6], fmt: PtmFormat) -> Result<Fitter604, String> {
        fmt.validate()?;
        let l = p[0].len();
        if !(6..=MAX_LIGHTS).contains(&l) || p.iter().any(|r| r.len() != l) {
            return Err(format!("P: 6 rows of 6..={MAX_LIGHTS} entries"));
        }
        let acc = Format::signed(ACC_BITS, 28);
        const ACC: [&str; 6] = ["acc1", "acc2", "acc3", "acc4", "acc5", "acc6"];
        const Q: [&str; 6] = ["q1", "q2", "q3", "q4", "q5", "q6"];
        Ok(Fitter604 {
            p,
            fmt,
            in_valid: Signal::bit("in_valid"),
            in_sample: Signal::new("in_sample", Format::uint(8)),
            k: Signal::new("k", Format::unsigned(9, 8)),
            light: Reg::new("light", Format::uint(10)),
            acc: ACC.map(|n| Reg::new(n, acc)),
            out_valid: Reg::new("out_valid", Format::uint(1)),
            out_q: Q.map(|n| Reg::new(n, Format::uint(fmt.bits))),
            round: Q.map(|n| fmt.narrowing(n)),
        })
    }

    pub fn lights(&self) -> usize {
        self.p[0].len()
    }
}

impl Fitter604 {
    /// One sample into the accumulators; the coefficients out after the last.
    pub fn eval(&mut self) {
        let k = occlusion(self.in_sample.bits() as u8);
        self.k.set_bits(u64::from(k));
        self.out_valid.set_next_bool(false);
        if !self.in_valid.is_high() {
            return;
        }
        let i = self.light.q().bits() as usize;
        let last = i + 1 == self.lights();
        for j in 0..6 {
            let base = if i == 0 { 0 } else { self.acc[j].q().raw() };
            let sum = base + i64::from(self.p[j][i]) * i64::from(k);
            self.acc[j].set_next_raw(sum);
            if last {
                let q = self.fmt.quantise_in(j, sum, &mut self.round[j]);
                self.out_q[j].set_next_bits(q);
            }
        }
        self.out_valid.set_next_bool(last);
        self.light
            .set_next_bits(if last { 0 } else { i as u64 + 1 });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn occlusion_maps_the_ends_exactly_and_the_rest_within_half_a_step() {
        assert_eq!(occlusion(255), 0);
        assert_eq!(occlusion(0), 256);
        for s in 0..=255u8 {
            let x = 255 - i64::from(s);
            // |K/256 - x/255| <= 1/510, i.e. |255 K - 256 x| <= 128.
            let k = i64::from(occlusion(s));
            assert!((255 * k - 256 * x).abs() <= 128, "{s}");
        }
    }

    /// P has six rows of one length L in 6..=MAX_LIGHTS (both ends taken), else it is refused.
    #[test]
    fn the_pseudo_inverse_shape_is_checked() {
        let p = |l: usize| std::array::from_fn(|_| vec![0; l]);
        let fmt = PtmFormat {
            bits: 8,
            exp: [4; 6],
            bias: [0; 6],
        };
        for (l, ok) in [
            (5, false),
            (6, true),
            (MAX_LIGHTS, true),
            (MAX_LIGHTS + 1, false),
        ] {
            let r = Fitter604::new(p(l), fmt);
            assert_eq!(r.is_ok(), ok, "{l}");
            if let Ok(f) = r {
                assert_eq!(f.lights(), l);
            }
        }
        let mut ragged: [Vec<i32>; 6] = p(8);
        ragged[5].pop();
        let e = Fitter604::new(ragged, fmt).unwrap_err();
        assert_eq!(e, format!("P: 6 rows of 6..={MAX_LIGHTS} entries"));
    }
}
