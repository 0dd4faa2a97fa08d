//! The occlusion PTM 612 as the hardware stores it: per texel six unsigned coefficients of
//! `bits` (8 or 16), coefficient j standing for `A_j = q_j 2^e_j + b_j` (units of 2^-20).
//!
//! The ranges come from the pseudo-inverse P before any fit \[C\]: with occlusions `K_i` in
//! [0, 1], `A_j = sum_i P_ji K_i` lies in `[sum of P_ji < 0, sum of P_ji > 0]`, so the bias is
//! that lower end and `e_j` the least exponent whose `2^bits - 1` steps reach the upper end:
//! no fit is ever held at a limit. (The ranges are wide against typical coefficients: the
//! price of knowing them before the data; 16 bits when 8 are too coarse.)

use super::{MAX_LIGHTS, P_BITS};
use crate::fx::{quantise, Format, Narrowing, Overflow, Quant};

/// The six coefficients' scales and biases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PtmFormat {
    /// Bits of a stored coefficient: 8 or 16.
    pub bits: u32,
    /// `e_j`: a step of coefficient j is `2^e_j` units of 2^-20 (0 ..= 40).
    pub exp: [u32; 6],
    /// `b_j` in units of 2^-20.
    pub bias: [i64; 6],
}

impl PtmFormat {
    pub fn validate(&self) -> Result<(), String> {
        if self.bits != 8 && self.bits != 16 {
            return Err(format!("bits {}: 8 or 16", self.bits));
        }
        if let Some(e) = self.exp.iter().find(|e| **e > 40) {
            return Err(format!("exponent {e}: 0..=40"));
        }
        if let Some(b) = self.bias.iter().find(|b| b.unsigned_abs() >= 1 << 40) {
            return Err(format!("bias {b}: |bias| < 2^40"));
        }
        Ok(())
    }

    /// The largest stored value.
    pub fn max_q(&self) -> u64 {
        (1 << self.bits) - 1
    }

    /// The format covering every fit through `p` (6 rows of L raw sQ7.20 entries).
    pub fn for_pinv(p: &[Vec<i32>; 6], bits: u32) -> Result<PtmFormat, String> {
        let lights = p[0].len();
        if lights == 0 || lights > MAX_LIGHTS || p.iter().any(|r| r.len() != lights) {
            return Err(format!("P: 6 rows of 1..={MAX_LIGHTS} entries"));
        }
        let mut f = PtmFormat {
            bits,
            exp: [0; 6],
            bias: [0; 6],
        };
        let max = (1i64 << bits) - 1;
        for (j, row) in p.iter().enumerate() {
            let lo: i64 = row.iter().map(|&x| i64::from(x.min(0))).sum();
            let hi: i64 = row.iter().map(|&x| i64::from(x.max(0))).sum();
            let mut e = 0;
            while (hi - lo) > max << e {
                e += 1;
            }
            (f.exp[j], f.bias[j]) = (e, lo);
        }
        f.validate()?;
        Ok(f)
    }

    /// Coefficient j of stored `q`, in units of 2^-20 (exact).
    pub fn coefficient(&self, j: usize, q: u64) -> i64 {
        ((q as i64) << self.exp[j]) + self.bias[j]
    }

    /// The stored value of an exact accumulator `acc` (units of 2^-28: P 2^-20 times K 2^-8)
    /// of coefficient j: `(acc - b 2^8) / 2^(e + 8)` rounded half up, held to `0 ..= max_q`.
    pub fn quantise(&self, j: usize, acc: i64) -> u64 {
        let (x, frac) = self.unbiased(j, acc);
        quantise(
            x,
            frac,
            self.stored(),
            Quant::RoundHalfUp,
            Overflow::Saturate,
        ) as u64
    }

    /// [`PtmFormat::quantise`] through a named narrowing (see [`PtmFormat::narrowing`]).
    pub fn quantise_in(&self, j: usize, acc: i64, n: &mut Narrowing) -> u64 {
        let (x, frac) = self.unbiased(j, acc);
        n.raw(x, frac) as u64
    }

    /// The narrowing of coefficient j's accumulator, named `name`: into the stored
    /// unsigned `bits`, half up, held; neither end is reached (the format's construction).
    pub fn narrowing(&self, name: &'static str) -> Narrowing {
        const HELD: &str = "A = sum P K with K in [0, 1] lies in [b, b + (2^bits - 1) 2^e] by the format's construction";
        Narrowing::new(name, self.stored(), Quant::RoundHalfUp, Overflow::Saturate)
            .never_overflows(HELD)
    }

    /// The stored format: unsigned `bits`, no fraction.
    fn stored(&self) -> Format {
        Format::uint(self.bits)
    }

    /// `acc - b 2^8` and its fraction bits `e + 8`: the stored value before its rounding.
    fn unbiased(&self, j: usize, acc: i64) -> (i128, i32) {
        let x = i128::from(acc) - (i128::from(self.bias[j]) << 8);
        (x, self.exp[j] as i32 + 8)
    }
}

/// P rounded to sQ7.20 (raw), half up, from any source of its entries in units of 2^-40
/// (the host's table: `round(p 2^40)`), or an error when an entry does not fit.
pub fn p_raw(p40: &[Vec<i64>; 6]) -> Result<[Vec<i32>; 6], String> {
    let lim = 1i64 << (P_BITS - 1);
    let mut out: [Vec<i32>; 6] = Default::default();
    for (j, row) in p40.iter().enumerate() {
        for &x in row {
            let r = (x + (1 << 19)) >> 20;
            if !(-lim..lim).contains(&r) {
                return Err(format!(
                    "P[{j}] entry {r}: outside sQ7.20 (the lights are too close together)"
                ));
            }
            out[j].push(r as i32);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every fit through `p` is in `p`'s format at `bits`, whose exponents are the least
    /// that do it.
    fn check_covers_every_fit(p: &[Vec<i32>; 6], bits: u32) {
        let f = PtmFormat::for_pinv(p, bits).unwrap();
        for (j, row) in p.iter().enumerate() {
            // The extreme fits (K = 1 is 256 in uQ1.8, accumulators in 2^-28): every
            // negative entry's light occluded and none of the others, and the reverse.
            let lo: i64 = row.iter().map(|&x| i64::from(x.min(0))).sum();
            let hi: i64 = row.iter().map(|&x| i64::from(x.max(0))).sum();
            assert_eq!(f.quantise(j, lo << 8), 0);
            let top = f.coefficient(j, f.max_q());
            assert!(top >= hi, "{bits} bits, row {j}: {top} < {hi}");
            // The least exponent: one less would not reach.
            if f.exp[j] > 0 {
                assert!(
                    (f.max_q() as i64) << (f.exp[j] - 1) < hi - lo,
                    "{bits}, {j}"
                );
            }
        }
    }

    #[test]
    fn every_fit_fits_the_format() {
        let p: [Vec<i32>; 6] = std::array::from_fn(|j| {
            (0..12)
                .map(|i| ((i * 7919 + j as i32 * 104_729) % 300_000) - 150_000)
                .collect()
        });
        for bits in [8, 16] {
            check_covers_every_fit(&p, bits);
        }
    }

    /// Rows whose range is just below, at and just above what the stored values reach at
    /// an exponent (`max_q << e`): the range at it takes that exponent, one more the next.
    #[test]
    fn ranges_at_an_exponents_reach_take_the_least_exponent() {
        for bits in [8u32, 16] {
            let max = (1i64 << bits) - 1;
            for e in [0u32, 1, 3] {
                let reach = max << e;
                let p: [Vec<i32>; 6] = std::array::from_fn(|j| {
                    let r = (reach + j as i64 % 3 - 1) as i32;
                    // The range split between a positive and a negative entry.
                    vec![r - r / 3, -(r / 3)]
                });
                check_covers_every_fit(&p, bits);
                let f = PtmFormat::for_pinv(&p, bits).unwrap();
                assert_eq!(f.exp, [e, e, e + 1, e, e, e + 1], "{bits} bits, e {e}");
            }
        }
    }

    #[test]
    fn quantise_rounds_half_up_and_holds() {
        let f = PtmFormat {
            bits: 8,
            exp: [2; 6],
            bias: [-100; 6],
        };
        // acc = (bias + 4 q) 2^8 exactly gives q; half a step more rounds up.
        assert_eq!(f.quantise(0, (-100 + 4 * 7) << 8), 7);
        assert_eq!(f.quantise(0, ((-100 + 4 * 7) << 8) + 512), 8);
        assert_eq!(f.quantise(0, ((-100 + 4 * 7) << 8) + 511), 7);
        assert_eq!(f.quantise(0, -1 << 30), 0);
        assert_eq!(f.quantise(0, 1 << 30), 255);
        assert_eq!(f.coefficient(0, 7), -72);
    }

    /// The format's ranges at both ends, and what P may be.
    #[test]
    fn validate_and_for_pinv_refuse_what_does_not_fit() {
        let f = |bits: u32, e: u32, b: i64| {
            let mut f = PtmFormat {
                bits,
                exp: [0; 6],
                bias: [0; 6],
            };
            (f.exp[5], f.bias[5]) = (e, b);
            f.validate()
        };
        let big = (1i64 << 40) - 1;
        for (bits, e, b) in [(8, 0, 0), (16, 40, big), (8, 0, -big)] {
            assert_eq!(f(bits, e, b), Ok(()), "{bits} {e} {b}");
        }
        assert!(f(12, 0, 0).unwrap_err().starts_with("bits 12"));
        assert!(f(32, 0, 0).unwrap_err().starts_with("bits 32"));
        assert!(f(8, 41, 0).unwrap_err().starts_with("exponent 41"));
        assert!(f(8, 0, big + 1).unwrap_err().starts_with("bias"));
        assert!(f(8, 0, -big - 1).unwrap_err().starts_with("bias"));
        // P: six rows of one length, 1..=MAX_LIGHTS.
        let rows = |n: usize| -> [Vec<i32>; 6] { std::array::from_fn(|_| vec![1; n]) };
        assert!(PtmFormat::for_pinv(&rows(1), 8).is_ok());
        assert!(PtmFormat::for_pinv(&rows(MAX_LIGHTS), 8).is_ok());
        assert!(PtmFormat::for_pinv(&rows(0), 8).is_err());
        assert!(PtmFormat::for_pinv(&rows(MAX_LIGHTS + 1), 8).is_err());
        let mut ragged = rows(3);
        ragged[4].pop();
        assert!(PtmFormat::for_pinv(&ragged, 8).is_err());
        assert!(PtmFormat::for_pinv(&rows(3), 12).is_err(), "bits checked");
    }

    /// Entries in units of 2^-40 rounded half up to sQ7.20, inside `[-2^27, 2^27)`.
    #[test]
    fn p_raw_rounds_half_up_and_refuses_what_sq7_20_cannot_hold() {
        let lim = 1i64 << (P_BITS - 1);
        let one_row = |x: i64| -> [Vec<i64>; 6] { std::array::from_fn(|_| vec![x]) };
        let got = |x: i64| p_raw(&one_row(x)).map(|r| r[0][0]);
        assert_eq!(got(3 << 19), Ok(2), "1.5 rounds up");
        assert_eq!(got((3 << 19) - 1), Ok(1));
        assert_eq!(got(-3 << 19), Ok(-1), "-1.5 rounds up");
        assert_eq!(got((lim - 1) << 20), Ok((lim - 1) as i32));
        assert_eq!(got(-lim << 20), Ok(-lim as i32));
        assert!(got(lim << 20).unwrap_err().contains("outside sQ7.20"));
        assert!(got((-lim - 1) << 20).is_err());
    }
}
