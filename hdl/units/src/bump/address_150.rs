//! Address unit 150 of US 2004/0207631 (FIG. 7, para. 0052; the prior-art FIG. 4a, para.
//! 0010-0016, 0023): sample position -> integer texel coordinate and blend factors.
//!
//! `U' = U - 1/2` in colour mode (step 51, the half-texel subtraction that puts a texel's
//! value at its centre); in bump-map mode step 51 is bypassed and `U' = U`. Then
//! `Ui = floor(U')` and `Ublend = U' - Ui`, truncated (floored) to F fraction bits; the same
//! for V.
//!
//! # Formats
//! | port | format | |
//! |---|---|---|
//! | `u`, `v` | `sQ<pos_int>.<pos_frac>` | position in texel units |
//! | `colour` | `u1` | 1: colour mode (subtract half a texel) |
//! | `ui`, `vj` | `s<pos_int+1>` | integer texel coordinate (one bit wider: `U - 1/2` can fall below the position's minimum) |
//! | `ub`, `vb` | `uQ0.F` | blend factors; the position's bits below `2^-F` are dropped (truncation toward -inf, free in hardware) |
//!
//! One register stage: latency 1.

use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

/// Address unit 150.
#[derive(Clone, Debug, Module)]
#[module(kind = "address_150")]
pub struct AddressUnit {
    #[instance]
    name: String,
    blend_bits: u32,
    pos_frac: u32,
    #[input]
    pub u: Signal,
    #[input]
    pub v: Signal,
    #[input]
    pub colour: Signal,
    #[output]
    pub ui: Signal,
    #[output]
    pub vj: Signal,
    #[output]
    pub ub: Signal,
    #[output]
    pub vb: Signal,
    #[reg]
    r: [Reg; 4],
}

impl AddressUnit {
    /// Positions in `pos` (signed, `pos_frac >= blend_bits`), blend factors of `blend_bits`.
    pub fn new(name: &str, pos: Format, blend_bits: u32) -> Result<AddressUnit, String> {
        if !pos.is_signed() || pos.frac() < blend_bits as i32 {
            return Err(format!(
                "address unit 150: positions {pos} need to be signed with at least \
                 F = {blend_bits} fraction bits"
            ));
        }
        let coord = Format::sint(pos.int_bits() as u32 + 1);
        let blend = Format::unsigned(blend_bits, blend_bits as i32);
        Ok(AddressUnit {
            name: name.into(),
            blend_bits,
            pos_frac: pos.frac() as u32,
            u: Signal::new("u", pos),
            v: Signal::new("v", pos),
            colour: Signal::bit("colour"),
            ui: Signal::new("ui", coord),
            vj: Signal::new("vj", coord),
            ub: Signal::new("ub", blend),
            vb: Signal::new("vb", blend),
            r: [
                Reg::new("ui_r", coord),
                Reg::new("vj_r", coord),
                Reg::new("ub_r", blend),
                Reg::new("vb_r", blend),
            ],
        })
    }

    /// `(floor(p'), blend)` for one raw position `p` (fraction bits `pos_frac`).
    #[inline]
    pub fn split(&self, p: i64, colour: bool) -> (i64, u64) {
        let half = if colour {
            1i64 << (self.pos_frac - 1)
        } else {
            0
        };
        let p = p - half;
        let ip = p >> self.pos_frac;
        let blend =
            ((p >> (self.pos_frac - self.blend_bits)) as u64) & ((1u64 << self.blend_bits) - 1);
        (ip, blend)
    }
}

impl AddressUnit {
    #[inline]
    /// Splits both positions into their texel coordinates and blend factors (one register stage).
    pub fn eval(&mut self) {
        let colour = self.colour.is_high();
        let (ui, ub) = self.split(self.u.raw(), colour);
        let (vj, vb) = self.split(self.v.raw(), colour);
        self.r[0].set_next_raw(ui);
        self.r[1].set_next_raw(vj);
        self.r[2].set_next_raw(ub as i64);
        self.r[3].set_next_raw(vb as i64);
        self.ui.follow(self.r[0].q());
        self.vj.follow(self.r[1].q());
        self.ub.follow(self.r[2].q());
        self.vb.follow(self.r[3].q());
    }
}
