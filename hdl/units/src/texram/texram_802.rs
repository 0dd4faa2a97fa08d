//! The TEXRAM chip 802 (Figure 8), cycle by cycle: a request port from the rasterizer 804,
//! the address and control unit 812, the page registers 824, the banks 810 and the trilinear
//! interpolator 818, the output stage 820 (eq. 5). In the waveform each unit is its own scope
//! under `texram_802`.
//!
//! # Timing (\[C\], the document gives the 30 ns slot only)
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
//! out one per slot (33.3 M per second at 30 ns) when no page faults.
//!
//! Colour (section 6): an index DRF looks the eight texels up in the CLUT 814 and filters each
//! component; a planar or literal DRF splits a request into four component accesses, one
//! after the other through 812 and the banks, the result out with the last (`out_rgba`). In
//! the literal layout a component's 2x2 lies in one bank: 812 gives each bank up to four
//! words, read in successive rounds of a slot each (two on a page fault), and counts the
//! access in `conflicts`. The DRFs and the bank
//! contents are loaded through [`Texram802::set_drf`] and [`Texram802::load`], or a whole
//! map with its mipmap through [`Texram802::load_map`] (what the map chain uses).
//!
//! Video (sections 11-12): with [`Texram802::attach_video`] the chip has its video port 808,
//! the mipmap generator 816 and the shift registers 826 (`video_port_808.rs`). Their row
//! transfers take the bank stage at a slot boundary before a waiting rasterizer access
//! (`vid_round` segments, one slot, two when a bank has another row open): the slots stolen
//! from the rasterizer are counted in `video_port_808/shift_registers_826/video_slots`, and
//! in `slots` with the rasterizer's.

use super::address_812::Footprint;
use super::banks_810::{bank_words, locate, store_level, BANKS, ROW_WORDS};
use super::clut_814::Clut;
use super::output_820::{shade, Modulate};
use super::trilinear_818::{trilinear, trilinear_sum};
use super::video_port_808::{VideoParams, VideoPort808};
use super::{Border, Config, Drf, DRFS};
use crate::fx::Format;
use crate::kernel::declared::Regs as _;
use crate::kernel::{Module, Reg, Regs, Signal, Visitor};
use crate::pages::page_registers_824::{check_slot_cycles, PageRegisters824};
use crate::signals;

/// Bank words need 19 bits (280,064 words in banks 0-3).
const WORD_BITS: u32 = 19;
/// Words one bank may be asked for in one access: one, but four in the literal colour layout
/// (a component's 2x2 all in one bank), read in successive rounds.
const ROUNDS: usize = 4;
/// A texel's source: `4 bank + round`, or 32 for the border colour (6 bits per texel).
const COLOUR: u64 = 32;
const WORD_NAMES: [&str; BANKS * ROUNDS] = [
    "word0_0", "word0_1", "word0_2", "word0_3", "word1_0", "word1_1", "word1_2", "word1_3",
    "word2_0", "word2_1", "word2_2", "word2_3", "word3_0", "word3_1", "word3_2", "word3_3",
    "word4_0", "word4_1", "word4_2", "word4_3", "word5_0", "word5_1", "word5_2", "word5_3",
    "word6_0", "word6_1", "word6_2", "word6_3", "word7_0", "word7_1", "word7_2", "word7_3",
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
        check_slot_cycles(self.slot_cycles)
    }
}

/// One access's registers between units: words per bank and round, texel sources, weights,
/// the component it reads.
#[derive(Clone, Debug)]
struct Access {
    valid: Reg,
    word: Vec<Reg>,
    read: Reg,
    src: Reg,
    weights: Reg,
    colour: Reg,
    /// The DRF's configuration: 1 for index (CLUT 814), 0 otherwise.
    index: Reg,
    /// The colour component this access reads (planar, literal) and whether it is the
    /// request's last; a luminance or index access is part 0 and last.
    part: Reg,
    last: Reg,
    /// Eq. 5: the request's illumination and the DRF's choice (0 I_d, 1 k_T, 2 one) and k_T.
    illum: Reg,
    modulate: Reg,
}

impl Access {
    fn new() -> Access {
        Access {
            valid: Reg::new("valid", Format::uint(1)),
            word: WORD_NAMES
                .iter()
                .map(|n| Reg::new(n, Format::uint(WORD_BITS)))
                .collect(),
            // Which bank words the access reads: bit 4 bank + round.
            read: Reg::new("read", Format::uint((BANKS * ROUNDS) as u32)),
            // Texel t's source in bits 6t..6t+6.
            src: Reg::new("src", Format::uint(48)),
            // a0, b0, a1, b1, f in bytes 0-4.
            weights: Reg::new("weights", Format::uint(40)),
            colour: Reg::new("colour", Format::uint(8)),
            index: Reg::new("index", Format::uint(1)),
            part: Reg::new("part", Format::uint(2)),
            last: Reg::new("last", Format::uint(1)),
            illum: Reg::new("illum", Format::uint(32)),
            modulate: Reg::new("modulate", Format::uint(10)),
        }
    }

    fn regs(&self) -> impl Iterator<Item = &Reg> {
        let one = [&self.read, &self.src, &self.weights, &self.colour];
        one.into_iter()
            .chain([
                &self.index,
                &self.part,
                &self.last,
                &self.illum,
                &self.modulate,
            ])
            .chain(&self.word)
    }

    fn regs_mut(&mut self) -> impl Iterator<Item = &mut Reg> {
        let one = [
            &mut self.read,
            &mut self.src,
            &mut self.weights,
            &mut self.colour,
        ];
        one.into_iter()
            .chain([&mut self.index, &mut self.part, &mut self.last])
            .chain([&mut self.illum, &mut self.modulate])
            .chain(&mut self.word)
    }

    fn copy_from(&mut self, o: &Access) {
        for (to, from) in self.regs_mut().zip(o.regs()) {
            to.set_next_bits(from.q().bits());
        }
    }

    fn tick(&mut self, reset: bool) {
        self.valid.tick(reset);
        for r in self.regs_mut() {
            r.tick(reset);
        }
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.reg(&self.valid);
        for r in self.regs() {
            v.reg(r);
        }
    }

    /// The bank stage: its decoded bank words and which it reads in the scope of the
    /// address decoders 822, the rest beside them.
    fn visit_banks(&self, v: &mut dyn Visitor) {
        v.enter("address_decoders_822", "address_decoders_822");
        v.reg(&self.read);
        for r in &self.word {
            v.reg(r);
        }
        v.leave();
        v.reg(&self.valid);
        for r in [
            &self.src,
            &self.weights,
            &self.colour,
            &self.index,
            &self.part,
            &self.last,
            &self.illum,
            &self.modulate,
        ] {
            v.reg(r);
        }
    }
}

/// The request 812 is splitting into component accesses (a colour request of the planar or
/// literal layout): its DRF, `u`, `v`, `lambda`.
#[derive(Clone, Debug, Regs)]
struct Held {
    drf: Reg,
    u: Reg,
    v: Reg,
    lambda: Reg,
}

/// The chip: request port, units 812, 824, 810, 818, and its DRFs and bank contents.
#[derive(Clone, Debug)]
pub struct Texram802 {
    name: String,
    p: TexramParams,
    drfs: [Option<Drf>; DRFS],
    /// 812's working descriptor (request pointer [`super::WORKING`]): the map the chain
    /// walker selected for its next access.
    working: Option<Drf>,
    banks: Vec<Vec<u8>>,
    clut: Clut,
    pub req_valid: Signal,
    pub req_ready: Signal,
    pub req_drf: Signal,
    pub req_u: Signal,
    pub req_v: Signal,
    pub req_lambda: Signal,
    /// The rasterizer's interpolated illumination `I_d` (R top byte), for eq. 5.
    pub req_illum: Signal,
    /// 812's registers, and the request it is splitting into component accesses.
    addr: Access,
    held: Held,
    /// 824: per bank the open row.
    pages: PageRegisters824,
    /// 810: the access being served and the cycles left in its slot(s).
    bank: Access,
    left: Reg,
    fault: Reg,
    /// Counters: slots, faulting banks and bank conflicts since reset.
    pub slots: Reg,
    /// Component accesses served, and the slots their page faults added.
    pub accesses: Reg,
    pub fault_slots: Reg,
    pub conflicts: Reg,
    pub faults: Reg,
    /// 818's output registers.
    pub out_valid: Reg,
    pub out_value: Reg,
    /// R, G, B, alpha from the top byte down (luminance: the value four times).
    pub out_rgba: Reg,
    pub out_texels: Reg,
    pub out_fault: Reg,
    /// 818's exact sum before its rounding (luminance: `value * 2^24`, u32), for the
    /// footprint accumulator.
    pub out_sum: Reg,
    /// The components of a colour request finished so far (R top byte).
    acc_rgba: Reg,
    /// 814: the eight texels' table entries (R top byte) as an index access finishes.
    pub clut_entries: [Signal; 8],
    /// The bank stage serves `vid_round` segments of the video port (0: a rasterizer access).
    pub vid_round: Reg,
    /// The video port 808 with the generator 816 and shift registers 826, when set up.
    video: Option<Box<VideoPort808>>,
}

impl Texram802 {
    pub fn new(p: TexramParams) -> Result<Texram802, String> {
        p.validate()?;
        Ok(Texram802 {
            name: "texram_802".into(),
            p,
            drfs: [None; DRFS],
            working: None,
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
            req_illum: Signal::new("req_illum", Format::uint(32)),
            addr: Access::new(),
            pages: PageRegisters824::new(BANKS, 11),
            bank: Access::new(),
            left: Reg::new("left", Format::uint(8)),
            fault: Reg::new("fault", Format::uint(1)),
            slots: Reg::new("slots", Format::uint(40)),
            conflicts: Reg::new("conflicts", Format::uint(40)),
            accesses: Reg::new("accesses", Format::uint(40)),
            fault_slots: Reg::new("fault_slots", Format::uint(40)),
            faults: Reg::new("faults", Format::uint(40)),
            out_valid: Reg::new("out_valid", Format::uint(1)),
            out_value: Reg::new("out_value", Format::uint(8)),
            out_rgba: Reg::new("out_rgba", Format::uint(32)),
            out_texels: Reg::new("out_texels", Format::uint(64)),
            out_fault: Reg::new("out_fault", Format::uint(1)),
            out_sum: Reg::new("out_sum", Format::unsigned(32, 24)),
            acc_rgba: Reg::new("acc_rgba", Format::uint(32)),
            clut_entries: [
                "entry0", "entry1", "entry2", "entry3", "entry4", "entry5", "entry6", "entry7",
            ]
            .map(|n| Signal::new(n, Format::uint(32))),
            vid_round: Reg::new("vid_round", Format::uint(4)),
            video: None,
            held: Held {
                drf: Reg::new("held_drf", Format::uint(3)),
                u: Reg::new("held_u", Format::signed(super::UV_BITS, 8)),
                v: Reg::new("held_v", Format::signed(super::UV_BITS, 8)),
                lambda: Reg::new("held_lambda", Format::signed(14, 8)),
            },
        })
    }

    /// The same chip under another instance name (several chips in one design).
    pub fn named(mut self, name: &str) -> Texram802 {
        self.name = name.into();
        self
    }

    /// Sets DRF `k` (its map must then be loaded). A video map's DRF keeps its size.
    pub fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String> {
        drf.validate()?;
        let mut drfs = self.drfs;
        let slot = drfs
            .get_mut(k)
            .ok_or_else(|| format!("drf {k}: 0..{DRFS}"))?;
        *slot = Some(drf);
        if let Some(v) = &self.video {
            v.params().validate(&drfs)?;
        }
        self.drfs = drfs;
        Ok(())
    }

    /// Sets up the video port 808: frames of `p` written into the maps of DRFs `p.drfs`
    /// (set before, luminance, of the frames' size), their upper levels made by the
    /// generator 816. Takes effect at the next reset.
    pub fn attach_video(&mut self, p: VideoParams) -> Result<(), String> {
        self.video = Some(Box::new(VideoPort808::new(p, &self.drfs)?));
        Ok(())
    }

    /// The video port, when set up.
    pub fn video(&self) -> Option<&VideoPort808> {
        self.video.as_deref()
    }

    /// The video port, to drive its inputs.
    pub fn video_mut(&mut self) -> Option<&mut VideoPort808> {
        self.video.as_deref_mut()
    }

    /// Texels of level `lv` of DRF `k`'s map as the banks hold them, row-major.
    pub fn read_level(&self, k: usize, lv: u32) -> Result<Vec<u8>, String> {
        let d = self
            .drfs
            .get(k)
            .copied()
            .flatten()
            .ok_or(format!("drf {k}: not set"))?;
        let (w, h) = d.level_size(lv);
        Ok((0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let (b, word) = locate(&d, lv, x, y);
                self.banks[b][word as usize]
            })
            .collect())
    }

    /// 824 for a video round starting: the rows its segments write or read, the slots it
    /// takes (one, two if any bank has another row open). False when there is none to start.
    fn video_round(&mut self) -> bool {
        let Some(v) = self.video.as_deref_mut() else {
            return false;
        };
        let segments = v.round();
        let n = segments.iter().flatten().count();
        if n == 0 {
            return false;
        }
        let rows = segments.into_iter().flatten();
        let cost = self
            .pages
            .round(rows.map(|s| (s.bank, u64::from(s.word / ROW_WORDS))));
        let slots = u64::from(cost.slots);
        v.start(slots);
        self.left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        self.slots.set_next_bits(self.slots.q().bits() + slots);
        self.vid_round.set_next_bits(n as u64);
        true
    }

    /// Loads the CLUT 814.
    pub fn set_clut(&mut self, clut: Clut) {
        self.clut = clut;
    }

    /// Writes level `lv` of DRF `k`'s map (levels made by the host, e.g. an index map's).
    pub fn write_level(&mut self, k: usize, lv: u32, texels: &[u8]) -> Result<(), String> {
        let d = self
            .drfs
            .get(k)
            .copied()
            .flatten()
            .ok_or(format!("drf {k}: not set"))?;
        if lv > d.max_level() {
            return Err(format!(
                "level {lv}: the map has levels 0..={}",
                d.max_level()
            ));
        }
        store_level(&mut self.banks, &d, lv, texels).map_err(|e| format!("drf {k}: {e}"))
    }

    /// Writes the map `d` describes, every level, wherever its bases say.
    pub fn load_map(&mut self, d: &Drf, level0: &[u8]) -> Result<(), String> {
        let banks = &mut self.banks;
        super::load_levels(d, level0, |k, t| store_level(banks, d, k, t))
    }

    /// Sets 812's working descriptor (what request pointer [`super::WORKING`] reads).
    pub fn set_working(&mut self, d: &Drf) -> Result<(), String> {
        d.validate()?;
        self.working = Some(*d);
        Ok(())
    }

    /// Loads level 0 of DRF `k`'s map and the levels above it (as the stub does).
    pub fn load(&mut self, k: usize, level0: &[u8]) -> Result<(), String> {
        let d = self
            .drfs
            .get(k)
            .copied()
            .flatten()
            .ok_or(format!("drf {k}: not set"))?;
        let banks = &mut self.banks;
        super::load_levels(&d, level0, |lv, t| {
            store_level(banks, &d, lv, t).map_err(|e| format!("drf {k}: {e}"))
        })
    }

    /// 812: part `part` of the request (DRF `k`, raw `u`, `v`, `lambda`) into the address
    /// registers: its footprint, on the component's map for the colour layouts.
    fn address(&mut self, part: u32, k: usize, (u, v, l): (i32, i32, i32)) {
        // An unset DRF reads nothing: every texel is 0 (the testbench checks DRFs are set).
        let d = if k == usize::from(super::WORKING) {
            self.working
        } else {
            self.drfs.get(k).copied().flatten()
        };
        let colour_map = d.is_some_and(|d| matches!(d.config, Config::Planar | Config::Literal));
        self.addr.part.set_next_bits(u64::from(part));
        self.addr.last.set_next_bool(!colour_map || part == 3);
        let Some(d) = d else {
            self.addr.read.set_next_bits(0);
            self.addr
                .src
                .set_next_bits((0..8).fold(0, |a, t| a | COLOUR << (6 * t)));
            self.addr.colour.set_next_bits(0);
            return;
        };
        let plane = if colour_map { d.component_map() } else { d };
        let fp = Footprint::of(&plane, u, v, l);
        let (mut read, mut src, mut rounds) = (0u64, 0u64, 1);
        for (n, lv) in [fp.fine, fp.coarse].into_iter().enumerate() {
            for (t, at) in fp.texels[n].iter().enumerate() {
                let from = match at {
                    Some((x, y)) => {
                        let (gx, gy) = d.config.place(&plane, part, lv, *x, *y);
                        let (bank, word) = locate(&d, lv, gx, gy);
                        let slot = self.word_slot(bank, u64::from(word), &mut read);
                        rounds = rounds.max(slot % ROUNDS + 1);
                        slot as u64
                    }
                    None => COLOUR,
                };
                src |= from << (6 * (4 * n + t));
            }
        }
        self.addr.read.set_next_bits(read);
        self.addr.src.set_next_bits(src);
        // Only the literal colour layout asks a bank for more than one word.
        self.conflicts
            .set_next_bits(self.conflicts.q().bits() + u64::from(rounds > 1));
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
        let m = match d.modulate {
            Modulate::Illumination => 0,
            Modulate::Constant(k) => 1 << 8 | u64::from(k),
            Modulate::One => 2 << 8,
        };
        self.addr.modulate.set_next_bits(m);
    }

    /// The round in which `bank` reads `word`: the round that already reads it, else the next
    /// free one (`read` marks the taken ones). Returns `4 bank + round`.
    fn word_slot(&mut self, bank: usize, word: u64, read: &mut u64) -> usize {
        for r in 0..ROUNDS {
            let at = bank * ROUNDS + r;
            let reg = &mut self.addr.word[at];
            if *read >> at & 1 == 0 {
                reg.set_next_bits(word);
                *read |= 1 << at;
                return at;
            }
            if reg.next_bits() == word {
                return at;
            }
        }
        unreachable!("a footprint reads at most four texels of one bank");
    }

    /// 824: the access moving into the banks, round by round: its cost in slots (one a round,
    /// two when a bank misses its open row), the rows it leaves open.
    fn open_rows(&mut self) {
        let read = self.addr.read.q().bits();
        let (mut slots, mut missed, mut fault_slots) = (0u64, 0u64, 0u64);
        for r in 0..ROUNDS {
            let reads = (0..BANKS).filter(|b| read >> (b * ROUNDS + r) & 1 == 1);
            let rows = reads.map(|b| {
                let word = self.addr.word[b * ROUNDS + r].q().bits();
                (b, word / u64::from(ROW_WORDS))
            });
            let any = rows.clone().next().is_some();
            if any || r == 0 {
                let cost = self.pages.round(rows);
                slots += u64::from(cost.slots);
                fault_slots += u64::from(cost.slots - 1);
                missed += u64::from(cost.faults);
            }
        }
        self.left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        self.fault.set_next_bool(missed > 0);
        self.slots.set_next_bits(self.slots.q().bits() + slots);
        self.faults.set_next_bits(self.faults.q().bits() + missed);
        self.accesses.set_next_bits(self.accesses.q().bits() + 1);
        self.fault_slots
            .set_next_bits(self.fault_slots.q().bits() + fault_slots);
    }

    /// 810 and 818: the banks' data at the end of the slot(s), interpolated; a colour request's
    /// components are collected and come out with its last.
    fn interpolate(&mut self) {
        let src = self.bank.src.q().bits();
        let mut texels = [0u8; 8];
        for (t, x) in texels.iter_mut().enumerate() {
            let from = src >> (6 * t) & 0x3F;
            *x = if from == COLOUR {
                self.bank.colour.q().bits() as u8
            } else {
                let word = self.bank.word[from as usize].q().bits();
                self.banks[from as usize / ROUNDS][word as usize]
            };
        }
        let w = self.bank.weights.q().bits().to_le_bytes();
        let (a, b, f) = ([w[0], w[2]], [w[1], w[3]], w[4]);
        let value = trilinear(&texels, a, b, f);
        let sum = trilinear_sum(&texels, a, b, f);
        let part = self.bank.part.q().bits();
        let rgba = if self.bank.index.q().is_high() {
            for (e, &t) in self.clut_entries.iter_mut().zip(&texels) {
                e.set_bits(u64::from(u32::from_be_bytes(self.clut.rgba(t))));
            }
            u32::from_be_bytes(self.clut.filter(&texels, a, b, f))
        } else if self.bank.last.q().is_high() && part == 0 {
            u32::from_be_bytes([value; 4])
        } else {
            // Component `part` of a colour request: R in the top byte.
            let shift = 8 * (3 - part);
            (self.acc_rgba.q().bits() as u32 & !(0xFF << shift)) | u32::from(value) << shift
        };
        self.acc_rgba.set_next_bits(u64::from(rgba));
        let done = self.bank.last.q().is_high();
        self.out_valid.set_next_bool(done);
        if done {
            // 820: eq. 5 on the finished colour.
            let m = self.bank.modulate.q().bits();
            let m = match m >> 8 {
                0 => Modulate::Illumination,
                1 => Modulate::Constant(m as u8),
                _ => Modulate::One,
            };
            let illum = (self.bank.illum.q().bits() as u32).to_be_bytes();
            let rgba = u32::from_be_bytes(shade(m, illum, rgba.to_be_bytes()));
            self.out_value.set_next_bits(u64::from(rgba >> 24));
            self.out_rgba.set_next_bits(u64::from(rgba));
            self.out_texels.set_next_bits(u64::from_le_bytes(texels));
            self.out_fault.set_next_bits(self.fault.q().bits());
            self.out_sum.set_next_bits(sum);
        }
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
        self.pages.eval();
        let busy = self.bank.valid.q().is_high();
        let finishing = busy && self.left.q().bits() == 1;
        self.out_valid.set_next_bool(false);
        for e in &mut self.clut_entries {
            e.set_bits(0);
        }
        let served = self.vid_round.q().bits() as usize;
        if let Some(v) = self.video.as_deref_mut() {
            v.eval(finishing && served > 0);
        }
        if finishing && served == 0 {
            self.interpolate();
        }
        let waiting = self.addr.valid.q().is_high();
        // The video port goes first at a slot boundary: video cannot wait.
        let video = (!busy || finishing) && self.video_round();
        let move_on = waiting && (!busy || finishing) && !video;
        if video {
            self.bank.valid.set_next_bool(true);
        } else if move_on {
            self.open_rows();
            self.vid_round.set_next_bits(0);
            let (a, b) = (&self.addr, &mut self.bank);
            b.copy_from(a);
            b.valid.set_next_bool(true);
        } else if finishing {
            self.bank.valid.set_next_bool(false);
            self.vid_round.set_next_bits(0);
        } else if busy {
            self.left.set_next_bits(self.left.q().bits() - 1);
        }
        // A colour request's next component follows its last into 812; a new request is
        // taken only when 812 holds nothing more of the last one.
        let more = waiting && !self.addr.last.q().is_high();
        let ready = (!waiting || move_on) && !more;
        self.req_ready.set_bool(ready);
        let take = ready && self.req_valid.is_high();
        if take {
            let k = self.req_drf.bits();
            let uvl = [&self.req_u, &self.req_v, &self.req_lambda].map(|x| x.raw() as i32);
            let h = &mut self.held;
            h.drf.set_next_bits(k);
            h.u.set_next_raw(i64::from(uvl[0]));
            h.v.set_next_raw(i64::from(uvl[1]));
            h.lambda.set_next_raw(i64::from(uvl[2]));
            self.address(0, k as usize, (uvl[0], uvl[1], uvl[2]));
            self.addr.illum.set_next_bits(self.req_illum.bits());
        } else if move_on && more {
            let h = &self.held;
            let k = h.drf.q().bits() as usize;
            let uvl = [&h.u, &h.v, &h.lambda].map(|r| r.q().raw() as i32);
            let part = self.addr.part.q().bits() as u32 + 1;
            self.address(part, k, (uvl[0], uvl[1], uvl[2]));
        }
        if take || move_on {
            // A new access (or component), or the last one gone to the banks; else it waits.
            self.addr.valid.set_next_bool(take || more);
        }
    }

    fn tick(&mut self, reset: bool) {
        self.addr.tick(reset);
        self.held.tick_regs(reset);
        self.acc_rgba.tick(reset);
        self.pages.tick(reset);
        self.bank.tick(reset);
        if let Some(v) = self.video.as_deref_mut() {
            v.tick(reset, &self.drfs, &mut self.banks);
        }
        for r in [
            &mut self.vid_round,
            &mut self.left,
            &mut self.fault,
            &mut self.slots,
            &mut self.faults,
            &mut self.conflicts,
            &mut self.accesses,
            &mut self.fault_slots,
        ] {
            r.tick(reset);
        }
        for r in [
            &mut self.out_valid,
            &mut self.out_value,
            &mut self.out_rgba,
            &mut self.out_texels,
            &mut self.out_fault,
            &mut self.out_sum,
        ] {
            r.tick(reset);
        }
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        signals!(v;
            Input: self.req_valid, self.req_drf, self.req_u, self.req_v, self.req_lambda, self.req_illum;
            Output: self.req_ready;
            Reg: self.slots, self.faults, self.accesses, self.fault_slots);
        v.enter("address_812", "address_812");
        self.addr.visit(v);
        self.held.visit_regs(v);
        v.reg(&self.conflicts);
        v.leave();
        self.pages.visit(v);
        v.enter("banks_810", "banks_810");
        self.bank.visit_banks(v);
        signals!(v; Reg: self.left, self.fault, self.vid_round);
        v.leave();
        v.enter("clut_814", "clut_814");
        for e in &self.clut_entries {
            v.signal(crate::kernel::Dir::Wire, e);
        }
        v.leave();
        v.enter("trilinear_818", "trilinear_818");
        v.reg(&self.acc_rgba);
        v.leave();
        v.enter("output_820", "output_820");
        signals!(v; Reg: self.out_valid, self.out_value, self.out_rgba, self.out_texels, self.out_fault, self.out_sum);
        v.leave();
        if let Some(port) = &self.video {
            port.visit(v);
        }
        v.leave();
    }
}

/// The cycle-accurate chip behind [`super::TexramAccess`]: each access is driven into the
/// request port and the chip clocked until its result comes out, so code written against the
/// interface (footprint assembly, the map chain) runs on the chip as on the stub. Slots and
/// faults are the chip's counters; the levels and weights are 812's (from the request).
pub struct Texram802Access {
    sim: crate::kernel::Sim<Texram802, crate::kernel::NoTrace>,
}

impl Texram802Access {
    /// The chip, reset, with its DRFs and banks as given.
    pub fn new(chip: Texram802) -> Texram802Access {
        let mut sim = crate::kernel::Sim::new(chip);
        sim.reset(2);
        Texram802Access { sim }
    }

    /// The chip, to load DRFs, maps and the CLUT.
    pub fn chip(&mut self) -> &mut Texram802 {
        &mut self.sim.dut
    }
}

impl super::TexramAccess for Texram802Access {
    fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String> {
        self.sim.dut.set_drf(k, drf)
    }

    fn access(&mut self, req: super::TexramRequest) -> Result<super::TexramReply, String> {
        req.validate()?;
        let d =
            self.sim.dut.drfs[usize::from(req.drf)].ok_or(format!("drf {}: not set", req.drf))?;
        self.run(d, req)
    }

    fn load_map(&mut self, drf: &Drf, level0: &[u8]) -> Result<(), String> {
        self.sim.dut.load_map(drf, level0)
    }

    fn access_with(
        &mut self,
        drf: &Drf,
        u: i32,
        v: i32,
        lambda: i32,
    ) -> Result<super::TexramReply, String> {
        let req = super::TexramRequest {
            drf: 0,
            u,
            v,
            lambda,
        };
        req.validate()?;
        self.sim.dut.set_working(drf)?;
        let req = super::TexramRequest {
            drf: super::WORKING,
            ..req
        };
        self.run(*drf, req)
    }

    fn slots(&self) -> u64 {
        self.sim.dut.slots.q().bits()
    }
}

impl Texram802Access {
    /// Drives `req` (on the map `d`) into the request port and clocks the chip until its
    /// result comes out.
    fn run(&mut self, d: Drf, req: super::TexramRequest) -> Result<super::TexramReply, String> {
        let (slots0, faults0) = (
            self.sim.dut.slots.q().bits(),
            self.sim.dut.faults.q().bits(),
        );
        let dut = &mut self.sim.dut;
        dut.req_drf.set_bits(u64::from(req.drf));
        dut.req_u.set_raw(i64::from(req.u));
        dut.req_v.set_raw(i64::from(req.v));
        dut.req_lambda.set_raw(i64::from(req.lambda));
        let mut sent = false;
        for _ in 0..1000 {
            self.sim.dut.req_valid.set_bool(!sent);
            self.sim.eval();
            sent |= self.sim.dut.req_ready.is_high();
            let done = self.sim.dut.out_valid.q().is_high() && sent;
            if done {
                let dut = &self.sim.dut;
                let rgba = (dut.out_rgba.q().bits() as u32).to_be_bytes();
                let plane = match d.config {
                    Config::Planar | Config::Literal => d.component_map(),
                    _ => d,
                };
                let fp = Footprint::of(&plane, req.u, req.v, req.lambda);
                let reply = super::TexramReply {
                    fine: fp.fine,
                    coarse: fp.coarse,
                    texels: dut.out_texels.q().bits().to_le_bytes(),
                    a: fp.a,
                    b: fp.b,
                    f: fp.f,
                    value: rgba[0],
                    rgba,
                    slots: (dut.slots.q().bits() - slots0) as u32,
                    faults: (dut.faults.q().bits() - faults0) as u32,
                };
                self.sim.tick();
                return Ok(reply);
            }
            self.sim.tick();
        }
        Err("the chip gave no result in 1000 cycles".into())
    }
}
