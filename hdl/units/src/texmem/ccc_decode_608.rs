//! CCC decode for the texture memory path (Schilling & Knittel, Figures 4-6): register 608,
//! multiplexer 610 and colour look-up table 612. It turns the two DRAM words of one 4x4 block
//! into a 64-bit line of cache 614.
//!
//! # Formats
//! * DRAM word 0 (16 bits): CLUT index of colour a in bits 15..8, of colour b in bits 7..0.
//! * DRAM word 1 (16 bits): decision bits; bit `4 y + x` belongs to texel `(x, y)` of the block,
//!   0 selects colour a, 1 colour b (Figure 4).
//! * Register 608 (32 bits): word 0 in bits 31..16, word 1 in bits 15..0 (filled in that order,
//!   one word per DRAM response).
//! * CLUT 612: 256 entries of 24-bit RGB (`r << 16 | g << 8 | b`, 8 bits unsigned each).
//! * Cache line (64 bits, [`Line`]): colour a in bits 63..40, colour b in 39..16, decision bits
//!   in 15..0 (written from register 608 over line 624).
//!
//! No arithmetic, so no rounding or overflow: every field is a bit-field copy.
//!
//! # Timing
//! After the second word is in register 608: one cycle with multiplexer 610 on colour a (the
//! CLUT output is registered), one with it on colour b; in that second cycle `line_valid` is
//! high and `line` carries the whole entry to the cache (write enable, line 616).

use super::dram_604::Word;
use crate::fx::{Bit, Format};
use crate::kernel::{Module, RegOf, SignalOf};

hdl::formats! {
    /// Register 608: word 0 in bits 31..16, word 1 in bits 15..0.
    pub Reg608 = Format::uint(32);
    /// A CLUT 612 address: a colour index.
    pub ClutIndex = Format::uint(8);
    /// A CLUT 612 entry: 24-bit RGB, 8 bits unsigned a channel.
    pub Rgb = Format::uint(24);
    /// A cache line ([`Line`]).
    pub LineWord = Format::uint(64);
    /// The decoder's state: LOAD, LUT_A, LUT_B.
    pub State = Format::uint(2);
}

/// One encoded block as stored in DRAM.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct CccBlock {
    pub a: u8,
    pub b: u8,
    pub bits: u16,
}

impl CccBlock {
    /// The two DRAM words, word 0 first.
    pub fn words(self) -> [u16; 2] {
        [u16::from(self.a) << 8 | u16::from(self.b), self.bits]
    }
}

/// Fields of a 64-bit cache line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Line(pub u64);

impl Line {
    pub fn new(a: u32, b: u32, bits: u16) -> Line {
        Line(u64::from(a) << 40 | u64::from(b) << 16 | u64::from(bits))
    }
    pub fn color_a(self) -> u32 {
        (self.0 >> 40) as u32 & 0xff_ffff
    }
    pub fn color_b(self) -> u32 {
        (self.0 >> 16) as u32 & 0xff_ffff
    }
    pub fn bits(self) -> u16 {
        self.0 as u16
    }
    /// The colour of texel `(x, y)` of the block, `x, y < 4`.
    #[inline]
    pub fn texel(self, x: u32, y: u32) -> u32 {
        if self.bits() >> (4 * y + x) & 1 == 1 {
            self.color_b()
        } else {
            self.color_a()
        }
    }
}

/// States of the decoder, and their names in the waveform.
const LOAD: u64 = 0;
const LUT_A: u64 = 1;
const LUT_B: u64 = 2;
const STATES: &[&str] = &["LOAD", "LUT_A", "LUT_B"];

/// Register 608, multiplexer 610, CLUT 612.
#[derive(Clone, Debug, Module)]
#[module(kind = "ccc_decode_608")]
pub struct CccDecode {
    #[instance]
    name: String,
    clut: Vec<u32>,
    /// A DRAM word arrives (from control unit 607).
    #[input]
    pub word_valid: SignalOf<Bit>,
    #[input]
    pub word: SignalOf<Word>,
    /// Multiplexer 610's select: 0 colour a, 1 colour b.
    #[wire]
    pub mux_sel: SignalOf<Bit>,
    /// CLUT 612's address and data.
    #[wire]
    pub clut_addr: SignalOf<ClutIndex>,
    #[wire]
    pub clut_data: SignalOf<Rgb>,
    /// The finished cache line (write enable and data).
    #[output]
    pub line_valid: SignalOf<Bit>,
    #[output]
    pub line: SignalOf<LineWord>,
    #[reg]
    pub reg_608: RegOf<Reg608>,
    /// Words held (0, 1) while loading.
    #[reg]
    words_in: RegOf<Bit>,
    #[reg]
    pub state: RegOf<State>,
    #[reg]
    color_a: RegOf<Rgb>,
}

impl CccDecode {
    /// `clut`: 256 RGB entries of 24 bits.
    pub fn new(name: &str, clut: &[u32]) -> Result<CccDecode, String> {
        if clut.len() != 256 {
            return Err(format!("CLUT 612 has 256 entries, got {}", clut.len()));
        }
        if let Some(c) = clut.iter().find(|&&c| c > 0xff_ffff) {
            return Err(format!("CLUT entry {c:#x} wider than 24 bits"));
        }
        Ok(CccDecode {
            name: name.into(),
            clut: clut.to_vec(),
            word_valid: SignalOf::new("word_valid"),
            word: SignalOf::new("word"),
            mux_sel: SignalOf::new("mux_610_sel"),
            clut_addr: SignalOf::new("clut_612_addr"),
            clut_data: SignalOf::new("clut_612_data"),
            line_valid: SignalOf::new("line_valid"),
            line: SignalOf::new("line"),
            reg_608: RegOf::new("reg_608"),
            words_in: RegOf::new("words_in"),
            state: RegOf::new("state").with_states(STATES),
            color_a: RegOf::new("color_a"),
        })
    }
}

impl CccDecode {
    /// Multiplexer 610 and CLUT 612 from the state; register 608 loads the block's words.
    pub fn eval(&mut self) {
        let st = self.state.q().bits();
        let r = self.reg_608.q().bits();
        let sel = st == LUT_B;
        self.mux_sel.set_bool(sel);
        // Multiplexer 610: colour a is bits 31..24, colour b bits 23..16.
        let idx = if sel { (r >> 16) & 0xff } else { r >> 24 };
        self.clut_addr.set_bits(idx);
        let c = self.clut[idx as usize];
        self.clut_data.set_bits(u64::from(c));
        self.line_valid.set_bool(sel);
        if sel {
            let line = Line::new(self.color_a.q().bits() as u32, c, r as u16);
            self.line.set_bits(line.0);
        }
        match st {
            LUT_A => {
                self.color_a.set_next_bits(u64::from(c));
                self.state.set_next_bits(LUT_B);
            }
            LUT_B => self.state.set_next_bits(LOAD),
            _ => {
                if self.word_valid.is_high() {
                    let w = self.word.bits();
                    if self.words_in.q().is_high() {
                        self.reg_608.set_next_bits(r & 0xffff_0000 | w);
                        self.words_in.set_next_bool(false);
                        self.state.set_next_bits(LUT_A);
                    } else {
                        self.reg_608.set_next_bits(w << 16 | r & 0xffff);
                        self.words_in.set_next_bool(true);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Sim;

    #[test]
    fn two_words_make_one_line() {
        let clut: Vec<u32> = (0..256u32).map(|i| (i * 0x010203) & 0xff_ffff).collect();
        let blk = CccBlock {
            a: 7,
            b: 200,
            bits: 0b1010_0000_1111_0001,
        };
        let mut sim = Sim::new(CccDecode::new("dec", &clut).unwrap());
        sim.reset(1);
        let mut got = None;
        let mut cycles = 0;
        for (k, w) in blk
            .words()
            .into_iter()
            .map(Some)
            .chain([None; 4])
            .enumerate()
        {
            sim.dut.word_valid.set_bool(w.is_some());
            sim.dut.word.set_bits(u64::from(w.unwrap_or(0)));
            sim.eval();
            if sim.dut.line_valid.is_high() {
                got = Some(Line(sim.dut.line.bits()));
                cycles = k;
            }
            sim.tick();
        }
        let l = got.expect("no line");
        assert_eq!(cycles, 3, "line two cycles after the second word");
        assert_eq!(l.color_a(), clut[7]);
        assert_eq!(l.color_b(), clut[200]);
        assert_eq!(l.bits(), blk.bits);
        assert_eq!(l.texel(0, 0), clut[200]);
        assert_eq!(l.texel(1, 0), clut[7]);
        assert_eq!(l.texel(3, 3), clut[200]);
        assert_eq!(l.texel(2, 3), clut[7]);
    }

    #[test]
    fn bad_cluts_are_refused() {
        assert!(CccDecode::new("d", &[0; 255]).is_err());
        let mut c = vec![0; 256];
        c[3] = 1 << 24;
        assert!(CccDecode::new("d", &c).is_err());
    }
}
