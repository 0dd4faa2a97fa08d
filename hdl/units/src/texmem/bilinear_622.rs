//! Bilinear interpolator 622 (Schilling & Knittel, Figure 6): one 24-bit RGB result from the
//! four texels colour extract 618 registered.
//!
//! # Arithmetic (per channel, all unsigned, exact until the one rounding)
//! With `F = frac_bits`, `W = 2^F`, channel values `c00, c10, c01, c11` (8 bits) and fractions
//! `fu, fv` (F bits):
//! * `top = c00 (W - fu) + c10 fu`, `bot = c01 (W - fu) + c11 fu`: `8 + F` bits, exact;
//! * `sum = top (W - fv) + bot fv`: `8 + 2F` bits, exact;
//! * `out = (sum + 2^(2F-1)) >> 2F`: round half up to 8 bits. No overflow is possible
//!   (`sum <= 255 * 2^(2F)`, so `out <= 255`): the overflow mode is "cannot happen", asserted.
//!
//! The result is registered: one cycle from 618's registers to `rgb` / `valid`.

use crate::fx::{Bit, Format};
use crate::kernel::{Module, Reg, RegOf, Signal, SignalOf};
use crate::texmem::ccc_decode_608::Rgb;

/// The arithmetic of one channel (exposed for the unit's exhaustive test).
#[inline]
pub fn lerp2(c00: u32, c10: u32, c01: u32, c11: u32, fu: u32, fv: u32, frac_bits: u32) -> u32 {
    let sum = lerp2_sum(c00, c10, c01, c11, fu, fv, frac_bits);
    let out = (sum + (1u64 << (2 * frac_bits - 1))) >> (2 * frac_bits);
    debug_assert!(out <= 255);
    out as u32
}

/// The exact sum before the rounding: the channel value times `2^2F` (`8 + 2F` bits).
#[inline]
pub fn lerp2_sum(c00: u32, c10: u32, c01: u32, c11: u32, fu: u32, fv: u32, frac_bits: u32) -> u64 {
    let w = 1u32 << frac_bits;
    let top = c00 * (w - fu) + c10 * fu;
    let bot = c01 * (w - fu) + c11 * fu;
    u64::from(top) * u64::from(w - fv) + u64::from(bot) * u64::from(fv)
}

#[derive(Clone, Debug, Module)]
#[module(kind = "bilinear_622")]
pub struct ColorBilinear {
    #[instance]
    name: String,
    frac_bits: u32,
    #[input]
    pub in_valid: SignalOf<Bit>,
    /// The 2 x 2 texels c00, c10, c01, c11 (24-bit RGB).
    #[input]
    pub c: [SignalOf<Rgb>; 4],
    #[input]
    pub fu: Signal,
    #[input]
    pub fv: Signal,
    #[reg]
    pub valid: RegOf<Bit>,
    #[reg]
    pub rgb: RegOf<Rgb>,
    /// The exact sums before the rounding, R, G, B (for footprint assembly).
    #[reg]
    pub sums: [Reg; 3],
}

impl ColorBilinear {
    /// `frac_bits` in 1..=12.
    pub fn new(name: &str, frac_bits: u32) -> Result<ColorBilinear, String> {
        if !(1..=12).contains(&frac_bits) {
            return Err(format!(
                "bilinear 622: frac_bits {frac_bits} outside 1..=12"
            ));
        }
        Ok(ColorBilinear {
            name: name.into(),
            frac_bits,
            in_valid: SignalOf::new("in_valid"),
            c: ["c00", "c10", "c01", "c11"].map(SignalOf::new),
            fu: Signal::new("fu", Format::unsigned(frac_bits, frac_bits as i32)),
            fv: Signal::new("fv", Format::unsigned(frac_bits, frac_bits as i32)),
            valid: RegOf::new("valid"),
            rgb: RegOf::new("rgb"),
            sums: ["sum_r", "sum_g", "sum_b"]
                .map(|n| Reg::new(n, Format::unsigned(8 + 2 * frac_bits, 2 * frac_bits as i32))),
        })
    }
}

impl ColorBilinear {
    /// The combinational process: the next colour and sums (the generated `tick` registers
    /// them).
    pub fn eval(&mut self) {
        let v = self.in_valid.is_high();
        self.valid.set_next_bool(v);
        if v {
            let c = [0, 1, 2, 3].map(|k| self.c[k].bits() as u32);
            let (fu, fv) = (self.fu.bits() as u32, self.fv.bits() as u32);
            let mut rgb = 0;
            for (k, shift) in [16, 8, 0].into_iter().enumerate() {
                let ch = c.map(|x| x >> shift & 0xff);
                let f = self.frac_bits;
                let sum = lerp2_sum(ch[0], ch[1], ch[2], ch[3], fu, fv, f);
                self.sums[k].set_next_bits(sum);
                rgb |= (((sum + (1u64 << (2 * f - 1))) >> (2 * f)) as u32) << shift;
            }
            self.rgb.set_next_bits(u64::from(rgb));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_are_exact_and_the_centre_rounds_half_up() {
        for f in 1..=8 {
            assert_eq!(lerp2(10, 20, 30, 40, 0, 0, f), 10);
            assert_eq!(
                lerp2(255, 255, 255, 255, (1 << f) - 1, (1 << f) - 1, f),
                255
            );
        }
        // (0 + 1 + 0 + 0) / 4 = 0.25 -> 0; (1 + 1 + 0 + 0) / 4 = 0.5 -> 1 (half up).
        assert_eq!(lerp2(0, 1, 0, 0, 8, 8, 4), 0);
        assert_eq!(lerp2(1, 1, 0, 0, 8, 8, 4), 1);
    }

    #[test]
    fn fraction_bits_are_checked_at_both_ends() {
        for (f, ok) in [(0, false), (1, true), (12, true), (13, false)] {
            match ColorBilinear::new("b", f) {
                Ok(_) => assert!(ok, "{f}"),
                Err(e) => assert!(!ok && e.contains(&format!("frac_bits {f} outside")), "{e}"),
            }
        }
    }
}
