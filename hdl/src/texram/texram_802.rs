//! The TEXRAM chip 802 (Figure 8), cycle by cycle: a request port from the rasterizer 804,
//! the address and control unit 812, the page registers 824, the banks 810 and the trilinear
//! interpolator 818. In the waveform each unit is its own scope under `texram_802`.
//!
//! # Timing ([C], the document gives the 30 ns slot only)
//! The clock is 5 ns (as `dram_604`); one access slot is `slot_cycles` = 6 cycles.
//! * cycle 0: `req_valid && req_ready`: 812 computes the footprint (levels, weights, border
//!   operations, bank words) into its registers;
//! * next cycle, when the banks are free, the access moves into the bank stage: 824 compares
//!   the eight bank words' rows with the open rows; the banks are busy one slot, two when a
//!   bank missed (the rows it opens are open from then on);
//! * last cycle of the slot(s): the banks' data (or the border colour) go through 818 into
//!   the output registers: `out_valid` one cycle, then `value`, the eight `texels` (texel t in
//!   bits `8t..8t+8`) and `fault`.
//!
//! 812 takes the next request while the banks serve the last, so back-to-back requests come
//! out one per slot (33.3 M per second at 30 ns) when no page faults. The DRFs and the bank
//! contents are loaded through [`Texram802::set_drf`] and [`Texram802::load`] (the chain
//! walker and the video port that write them are later work).

use super::address_812::Footprint;
use super::banks_810::{bank_words, locate, BANKS, ROW_WORDS};
use super::clut_814::Clut;
use super::stub::next_level;
use super::trilinear_818::trilinear;
use super::{Border, Config, Drf, DRFS};
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::signals;

/// Bank words need 19 bits (280,064 words in banks 0-3).
const WORD_BITS: u32 = 19;
/// A texel's source: bank 0-7, or 8 for the border colour.
const COLOUR: u64 = 8;
const WORD_NAMES: [&str; BANKS] = [
    "word0", "word1", "word2", "word3", "word4", "word5", "word6", "word7",
];
const OPEN_NAMES: [&str; BANKS] = [
    "open0", "open1", "open2", "open3", "open4", "open5", "open6", "open7",
];

/// The chip's timing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexramParams {
    /// Clock cycles per access slot (30 ns at a 5 ns clock).
    pub slot_cycles: u32,
}

impl Default for TexramParams {
    fn default() -> Self {
        TexramParams { slot_cycles: 6 }
    }
}

impl TexramParams {
    pub fn validate(&self) -> Result<(), String> {
        if !(1..=15).contains(&self.slot_cycles) {
            return Err(format!("slot_cycles {}: 1..=15", self.slot_cycles));
        }
        Ok(())
    }
}

/// One access's registers between units: words per bank, texel sources, weights, levels.
#[derive(Clone, Debug)]
struct Access {
    valid: Reg,
    word: Vec<Reg>,
    read: Reg,
    src: Reg,
    weights: Reg,
    colour: Reg,
    /// The DRF's configuration: 1 for index (CLUT 814), 0 for luminance.
    index: Reg,
}

impl Access {
    fn new() -> Access {
        Access {
            valid: Reg::new("valid", Format::uint(1)),
            word: WORD_NAMES
                .iter()
                .map(|n| Reg::new(n, Format::uint(WORD_BITS)))
                .collect(),
            // Which banks the access reads (one bit per bank).
            read: Reg::new("read", Format::uint(BANKS as u32)),
            // Texel t's source in bits 4t..4t+4.
            src: Reg::new("src", Format::uint(32)),
            // a0, b0, a1, b1, f in bytes 0-4.
            weights: Reg::new("weights", Format::uint(40)),
            colour: Reg::new("colour", Format::uint(8)),
            index: Reg::new("index", Format::uint(1)),
        }
    }

    fn copy_from(&mut self, o: &Access) {
        for (w, x) in self.word.iter_mut().zip(&o.word) {
            w.set_next_bits(x.q().bits());
        }
        self.read.set_next_bits(o.read.q().bits());
        self.src.set_next_bits(o.src.q().bits());
        self.weights.set_next_bits(o.weights.q().bits());
        self.colour.set_next_bits(o.colour.q().bits());
        self.index.set_next_bits(o.index.q().bits());
    }

    fn tick(&mut self, reset: bool) {
        self.valid.tick(reset);
        for w in &mut self.word {
            w.tick(reset);
        }
        self.read.tick(reset);
        self.src.tick(reset);
        self.weights.tick(reset);
        self.colour.tick(reset);
        self.index.tick(reset);
    }

    fn visit(&self, v: &mut dyn Visitor) {
        signals!(v; Reg: self.valid, self.read, self.src, self.weights, self.colour, self.index);
        for w in &self.word {
            v.reg(w);
        }
    }
}

/// The chip: request port, units 812, 824, 810, 818, and its DRFs and bank contents.
#[derive(Clone, Debug)]
pub struct Texram802 {
    name: String,
    p: TexramParams,
    drfs: [Option<Drf>; DRFS],
    banks: Vec<Vec<u8>>,
    clut: Clut,
    pub req_valid: Signal,
    pub req_ready: Signal,
    pub req_drf: Signal,
    pub req_u: Signal,
    pub req_v: Signal,
    pub req_lambda: Signal,
    /// 812's registers.
    addr: Access,
    /// 824: per bank the open row plus one (0: closed).
    open: Vec<Reg>,
    /// 810: the access being served and the cycles left in its slot(s).
    bank: Access,
    left: Reg,
    fault: Reg,
    /// Counters: slots, faulting banks and bank conflicts since reset.
    pub slots: Reg,
    pub conflicts: Reg,
    pub faults: Reg,
    /// 818's output registers.
    pub out_valid: Reg,
    pub out_value: Reg,
    /// R, G, B, alpha from the top byte down (luminance: the value four times).
    pub out_rgba: Reg,
    pub out_texels: Reg,
    pub out_fault: Reg,
}

impl Texram802 {
    pub fn new(p: TexramParams) -> Result<Texram802, String> {
        p.validate()?;
        Ok(Texram802 {
            name: "texram_802".into(),
            p,
            drfs: [None; DRFS],
            banks: (0..BANKS)
                .map(|b| vec![0; bank_words(b) as usize])
                .collect(),
            clut: Clut::identity(),
            req_valid: Signal::bit("req_valid"),
            req_ready: Signal::bit("req_ready"),
            req_drf: Signal::new("req_drf", Format::uint(3)),
            req_u: Signal::new("req_u", Format::signed(super::UV_BITS, 8)),
            req_v: Signal::new("req_v", Format::signed(super::UV_BITS, 8)),
            req_lambda: Signal::new("req_lambda", Format::signed(14, 8)),
            addr: Access::new(),
            open: OPEN_NAMES
                .iter()
                .map(|n| Reg::new(n, Format::uint(11)))
                .collect(),
            bank: Access::new(),
            left: Reg::new("left", Format::uint(5)),
            fault: Reg::new("fault", Format::uint(1)),
            slots: Reg::new("slots", Format::uint(40)),
            conflicts: Reg::new("conflicts", Format::uint(40)),
            faults: Reg::new("faults", Format::uint(40)),
            out_valid: Reg::new("out_valid", Format::uint(1)),
            out_value: Reg::new("out_value", Format::uint(8)),
            out_rgba: Reg::new("out_rgba", Format::uint(32)),
            out_texels: Reg::new("out_texels", Format::uint(64)),
            out_fault: Reg::new("out_fault", Format::uint(1)),
        })
    }

    /// The same chip under another instance name (several chips in one design).
    pub fn named(mut self, name: &str) -> Texram802 {
        self.name = name.into();
        self
    }

    /// Sets DRF `k` (its map must then be loaded).
    pub fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String> {
        drf.validate()?;
        if matches!(drf.config, Config::Planar | Config::Literal) {
            return Err(format!(
                "drf {k}: the {:?} colour layout is in the stub only so far (use one chip per component)",
                drf.config
            ));
        }
        let slot = self
            .drfs
            .get_mut(k)
            .ok_or_else(|| format!("drf {k}: 0..{DRFS}"))?;
        *slot = Some(drf);
        Ok(())
    }

    /// Loads the CLUT 814.
    pub fn set_clut(&mut self, clut: Clut) {
        self.clut = clut;
    }

    /// Loads level 0 of DRF `k`'s map and the levels above it (as the stub does).
    pub fn load(&mut self, k: usize, level0: &[u8]) -> Result<(), String> {
        let d = self
            .drfs
            .get(k)
            .copied()
            .flatten()
            .ok_or(format!("drf {k}: not set"))?;
        let mut level = level0.to_vec();
        for lv in 0..=d.max_level() {
            let (w, h) = d.level_size(lv);
            if level.len() != (w * h) as usize {
                return Err(format!("level {lv}: {} texels for {w}x{h}", level.len()));
            }
            for y in 0..h {
                for x in 0..w {
                    let (bank, word) = locate(&d, lv, x, y);
                    let cell = self.banks[bank]
                        .get_mut(word as usize)
                        .ok_or_else(|| format!("drf {k}: level {lv} beyond bank {bank}"))?;
                    *cell = level[(y * w + x) as usize];
                }
            }
            level = next_level(w, h, &level);
        }
        Ok(())
    }

    /// 812: the request on the port into the address registers.
    fn address(&mut self) {
        let k = self.req_drf.bits() as usize;
        // An unset DRF reads nothing: every texel is 0 (the testbench checks DRFs are set).
        let Some(d) = self.drfs.get(k).copied().flatten() else {
            self.addr.read.set_next_bits(0);
            self.addr.src.set_next_bits(0x8888_8888);
            self.addr.colour.set_next_bits(0);
            return;
        };
        let (u, v, l) = (self.req_u.raw(), self.req_v.raw(), self.req_lambda.raw());
        let fp = Footprint::of(&d, u as i32, v as i32, l as i32);
        let (mut read, mut src) = (0u64, 0u64);
        let mut conflict = false;
        for (n, lv) in [fp.fine, fp.coarse].into_iter().enumerate() {
            for (t, at) in fp.texels[n].iter().enumerate() {
                let from = match at {
                    Some((x, y)) => {
                        let (bank, word) = locate(&d, lv, *x, *y);
                        let w = &mut self.addr.word[bank];
                        conflict |= read >> bank & 1 == 1 && w.next_bits() != u64::from(word);
                        w.set_next_bits(u64::from(word));
                        read |= 1 << bank;
                        bank as u64
                    }
                    None => COLOUR,
                };
                src |= from << (4 * (4 * n + t));
            }
        }
        self.addr.read.set_next_bits(read);
        self.addr.src.set_next_bits(src);
        // The layout makes this impossible; counted so that a run shows it.
        self.conflicts
            .set_next_bits(self.conflicts.q().bits() + u64::from(conflict));
        let w = [fp.a[0], fp.b[0], fp.a[1], fp.b[1], fp.f];
        let packed = w
            .iter()
            .enumerate()
            .fold(0u64, |acc, (i, x)| acc | u64::from(*x) << (8 * i));
        self.addr.weights.set_next_bits(packed);
        let colour = match d.border {
            Border::Colour(c) => c,
            _ => 0,
        };
        self.addr.colour.set_next_bits(u64::from(colour));
        self.addr.index.set_next_bool(d.config == Config::Index);
    }

    /// 824: the access moving into the banks: its cost in slots, the rows it opens.
    fn open_rows(&mut self) {
        let read = self.addr.read.q().bits();
        let mut missed = 0u64;
        for b in 0..BANKS {
            if read >> b & 1 == 1 {
                let row = self.addr.word[b].q().bits() / u64::from(ROW_WORDS) + 1;
                if self.open[b].q().bits() != row {
                    missed += 1;
                    self.open[b].set_next_bits(row);
                }
            }
        }
        let slots = if missed > 0 { 2 } else { 1 };
        self.left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        self.fault.set_next_bool(missed > 0);
        self.slots.set_next_bits(self.slots.q().bits() + slots);
        self.faults.set_next_bits(self.faults.q().bits() + missed);
    }

    /// 810 and 818: the banks' data at the end of the slot, interpolated.
    fn interpolate(&mut self) {
        let src = self.bank.src.q().bits();
        let mut texels = [0u8; 8];
        for (t, x) in texels.iter_mut().enumerate() {
            let from = src >> (4 * t) & 0xF;
            *x = if from == COLOUR {
                self.bank.colour.q().bits() as u8
            } else {
                let word = self.bank.word[from as usize].q().bits();
                self.banks[from as usize][word as usize]
            };
        }
        let w = self.bank.weights.q().bits().to_le_bytes();
        let (a, b, f) = ([w[0], w[2]], [w[1], w[3]], w[4]);
        let rgba = if self.bank.index.q().is_high() {
            self.clut.filter(&texels, a, b, f)
        } else {
            [trilinear(&texels, a, b, f); 4]
        };
        self.out_value.set_next_bits(u64::from(rgba[0]));
        self.out_rgba
            .set_next_bits(u64::from(u32::from_be_bytes(rgba)));
        self.out_texels.set_next_bits(u64::from_le_bytes(texels));
        self.out_fault.set_next_bits(self.fault.q().bits());
    }
}

impl Module for Texram802 {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "texram_802"
    }

    fn eval(&mut self) {
        let busy = self.bank.valid.q().is_high();
        let finishing = busy && self.left.q().bits() == 1;
        self.out_valid.set_next_bool(finishing);
        if finishing {
            self.interpolate();
        }
        let move_on = self.addr.valid.q().is_high() && (!busy || finishing);
        if move_on {
            self.open_rows();
            let (a, b) = (&self.addr, &mut self.bank);
            b.copy_from(a);
            b.valid.set_next_bool(true);
        } else if finishing {
            self.bank.valid.set_next_bool(false);
        } else if busy {
            self.left.set_next_bits(self.left.q().bits() - 1);
        }
        let ready = !self.addr.valid.q().is_high() || move_on;
        self.req_ready.set_bool(ready);
        let take = ready && self.req_valid.is_high();
        if take {
            self.address();
        }
        if take || move_on {
            // A new access, or the last one gone to the banks; otherwise it waits.
            self.addr.valid.set_next_bool(take);
        }
    }

    fn tick(&mut self, reset: bool) {
        self.addr.tick(reset);
        for r in &mut self.open {
            r.tick(reset);
        }
        self.bank.tick(reset);
        for r in [
            &mut self.left,
            &mut self.fault,
            &mut self.slots,
            &mut self.faults,
            &mut self.conflicts,
        ] {
            r.tick(reset);
        }
        for r in [
            &mut self.out_valid,
            &mut self.out_value,
            &mut self.out_rgba,
            &mut self.out_texels,
            &mut self.out_fault,
        ] {
            r.tick(reset);
        }
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        signals!(v;
            Input: self.req_valid, self.req_drf, self.req_u, self.req_v, self.req_lambda;
            Output: self.req_ready);
        v.enter("address_812", "address_812");
        self.addr.visit(v);
        v.reg(&self.conflicts);
        v.leave();
        v.enter("page_registers_824", "page_registers_824");
        for r in &self.open {
            v.reg(r);
        }
        signals!(v; Reg: self.slots, self.faults);
        v.leave();
        v.enter("banks_810", "banks_810");
        self.bank.visit(v);
        signals!(v; Reg: self.left, self.fault);
        v.leave();
        v.enter("trilinear_818", "trilinear_818");
        signals!(v; Reg: self.out_valid, self.out_value, self.out_rgba, self.out_texels, self.out_fault);
        v.leave();
        v.leave();
    }
}
