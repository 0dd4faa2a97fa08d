//! Colour extract unit 618 (Schilling & Knittel, Figure 6): from the four 64-bit cache lines
//! it picks the 2x2 texels of the bilinear footprint, and registers them with the blend
//! weights for interpolator 622.
//!
//! # Formats
//! * Inputs: the four cache lines (64 bits, [`Line`]) indexed by entry (Figure 7), the
//!   footprint's texel positions `x0, x1, y0, y1` (unsigned, `coord_bits` bits; `x1` is `x0 + 1`
//!   clamped to the texture), and the fractions `fu`, `fv` (unsigned, `frac_bits` bits, the
//!   weight of `x1` / `y1` in units of `2^-frac_bits`).
//! * Outputs (registered, one cycle): `c00, c10, c01, c11` (24-bit RGB of texels `(x0, y0)`,
//!   `(x1, y0)`, `(x0, y1)`, `(x1, y1)`), `fu`, `fv`, `valid`.
//!
//! Pure selection: no arithmetic, no rounding.

use crate::fx::{Bit, Format};
use crate::kernel::{Module, Reg, RegOf, Signal, SignalOf};
use crate::texmem::cache_614::entry_of;
use crate::texmem::ccc_decode_608::{Line, Rgb};

#[derive(Clone, Debug, Module)]
#[module(kind = "extract_618")]
pub struct ColorExtract {
    #[instance]
    name: String,
    #[input]
    pub in_valid: SignalOf<Bit>,
    #[input]
    pub x0: Signal,
    #[input]
    pub x1: Signal,
    #[input]
    pub y0: Signal,
    #[input]
    pub y1: Signal,
    #[input]
    pub in_fu: Signal,
    #[input]
    pub in_fv: Signal,
    /// The four 64-bit lines from cache 614 (entries A-D).
    pub lines: [u64; 4],
    #[reg]
    pub valid: RegOf<Bit>,
    #[reg]
    pub c00: RegOf<Rgb>,
    #[reg]
    pub c10: RegOf<Rgb>,
    #[reg]
    pub c01: RegOf<Rgb>,
    #[reg]
    pub c11: RegOf<Rgb>,
    #[reg]
    pub fu: Reg,
    #[reg]
    pub fv: Reg,
}

impl ColorExtract {
    pub fn new(name: &str, coord_bits: u32, frac_bits: u32) -> ColorExtract {
        let c = RegOf::new;
        ColorExtract {
            name: name.into(),
            in_valid: SignalOf::new("in_valid"),
            x0: Signal::new("x0", Format::uint(coord_bits)),
            x1: Signal::new("x1", Format::uint(coord_bits)),
            y0: Signal::new("y0", Format::uint(coord_bits)),
            y1: Signal::new("y1", Format::uint(coord_bits)),
            in_fu: Signal::new("in_fu", Format::unsigned(frac_bits, frac_bits as i32)),
            in_fv: Signal::new("in_fv", Format::unsigned(frac_bits, frac_bits as i32)),
            lines: [0; 4],
            valid: RegOf::new("valid"),
            c00: c("c00"),
            c10: c("c10"),
            c01: c("c01"),
            c11: c("c11"),
            fu: Reg::new("fu", Format::unsigned(frac_bits, frac_bits as i32)),
            fv: Reg::new("fv", Format::unsigned(frac_bits, frac_bits as i32)),
        }
    }

    #[inline]
    fn texel(&self, x: u64, y: u64) -> u64 {
        let (x, y) = (x as u32, y as u32);
        u64::from(Line(self.lines[entry_of(x >> 2, y >> 2)]).texel(x & 3, y & 3))
    }
}

impl ColorExtract {
    /// The combinational process: the next texels and weights (the generated `tick`
    /// registers them).
    #[inline]
    pub fn eval(&mut self) {
        let v = self.in_valid.is_high();
        self.valid.set_next_bool(v);
        if v {
            let (x0, x1, y0, y1) = (
                self.x0.bits(),
                self.x1.bits(),
                self.y0.bits(),
                self.y1.bits(),
            );
            self.c00.set_next_bits(self.texel(x0, y0));
            self.c10.set_next_bits(self.texel(x1, y0));
            self.c01.set_next_bits(self.texel(x0, y1));
            self.c11.set_next_bits(self.texel(x1, y1));
            self.fu.set_next_bits(self.in_fu.bits());
            self.fv.set_next_bits(self.in_fv.bits());
        }
    }
}
