//! The TEXRAM chip 802 (Figure 8), cycle by cycle: a request port from the rasterizer 804,
//! the address and control unit 812, the page registers 824, the banks 810, the CLUT 814, the
//! trilinear interpolator 818 and the output stage 820 (eq. 5). Each unit is a child module
//! with its registers in its own file (`address_812.rs`, `banks_810.rs`, ...) and its own
//! scope under `texram_802` in the waveform; this file says how the chip moves an access
//! through them.
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

use super::address_812::{Address812, Footprint};
use super::banks_810::ROUNDS;
use super::banks_810::{bank_words, locate, store_level, Banks810, BANKS, ROW_WORDS};
use super::clut_814::{Clut, Clut814};
use super::output_820::Output820;
use super::trilinear_818::{trilinear, trilinear_sum, Trilinear818};
use super::video_port_808::{VideoParams, VideoPort808};
use super::{Config, Drf, DRFS};
use crate::fx::Format;
use crate::kernel::declared::Regs;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::pages::page_registers_824::{check_slot_cycles, PageRegisters824};

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

/// The chip's memory: the DRFs, the banks' contents they describe, and the video port 808
/// (with the generator 816 and the shift registers 826) whose row transfers write frames
/// into the banks, and read partner lines out of them, at the clock edge. The host loads it
/// between cycles.
#[derive(Clone, Debug)]
pub struct ChipMemory {
    drfs: [Option<Drf>; DRFS],
    banks: Vec<Vec<u8>>,
    video: Option<Box<VideoPort808>>,
}

impl Regs for ChipMemory {
    fn tick_regs(&mut self, reset: bool) {
        if let Some(v) = self.video.as_deref_mut() {
            v.tick(reset, &mut self.banks);
        }
    }
    fn visit_regs(&self, v: &mut dyn Visitor) {
        if let Some(port) = &self.video {
            port.visit(v);
        }
    }
}

/// The chip: request port, units 812, 824, 810, 814, 818, 820 as its children, and its
/// memory.
#[derive(Clone, Debug, Module)]
#[module(kind = "texram_802")]
pub struct Texram802 {
    #[instance]
    name: String,
    p: TexramParams,
    /// 812's working descriptor (request pointer [`super::WORKING`]): the map the chain
    /// walker selected for its next access.
    working: Option<Drf>,
    #[input]
    pub req_valid: Signal,
    #[input]
    pub req_drf: Signal,
    #[input]
    pub req_u: Signal,
    #[input]
    pub req_v: Signal,
    #[input]
    pub req_lambda: Signal,
    /// The rasterizer's interpolated illumination `I_d` (R top byte), for eq. 5.
    #[input]
    pub req_illum: Signal,
    #[output]
    pub req_ready: Signal,
    /// Counters since reset: slots (the rasterizer's and the video port's), faulting banks,
    /// component accesses served, and the slots their page faults added.
    #[reg]
    pub slots: Reg,
    #[reg]
    pub faults: Reg,
    #[reg]
    pub accesses: Reg,
    #[reg]
    pub fault_slots: Reg,
    #[child]
    pub address: Address812,
    /// 824: per bank the open row.
    #[child]
    pages: PageRegisters824,
    #[child]
    pub banks: Banks810,
    #[child]
    pub clut: Clut814,
    #[child]
    pub trilinear: Trilinear818,
    #[child]
    pub output: Output820,
    #[reg]
    memory: ChipMemory,
}

impl Texram802 {
    pub fn new(p: TexramParams) -> Result<Texram802, String> {
        p.validate()?;
        let u = |name, bits| Reg::new(name, Format::uint(bits));
        Ok(Texram802 {
            name: "texram_802".into(),
            p,
            working: None,
            req_valid: Signal::bit("req_valid"),
            req_ready: Signal::bit("req_ready"),
            req_drf: Signal::new("req_drf", Format::uint(3)),
            req_u: Signal::new("req_u", Format::signed(super::UV_BITS, 8)),
            req_v: Signal::new("req_v", Format::signed(super::UV_BITS, 8)),
            req_lambda: Signal::new("req_lambda", Format::signed(14, 8)),
            req_illum: Signal::new("req_illum", Format::uint(32)),
            slots: u("slots", 40),
            faults: u("faults", 40),
            accesses: u("accesses", 40),
            fault_slots: u("fault_slots", 40),
            address: Address812::new(),
            pages: PageRegisters824::new(BANKS, 11),
            banks: Banks810::new(),
            clut: Clut814::new(),
            trilinear: Trilinear818::new(),
            output: Output820::new(),
            memory: ChipMemory {
                drfs: [None; DRFS],
                banks: (0..BANKS)
                    .map(|b| vec![0; bank_words(b) as usize])
                    .collect(),
                video: None,
            },
        })
    }

    /// The same chip under another instance name (several chips in one design).
    pub fn named(mut self, name: &str) -> Texram802 {
        self.name = name.into();
        self
    }

    /// DRF `k`'s descriptor, if set.
    pub fn drf(&self, k: usize) -> Option<Drf> {
        self.memory.drfs.get(k).copied().flatten()
    }

    /// Sets DRF `k` (its map must then be loaded). A video map's DRF keeps its size.
    pub fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String> {
        drf.validate()?;
        let mut drfs = self.memory.drfs;
        let slot = drfs
            .get_mut(k)
            .ok_or_else(|| format!("drf {k}: 0..{DRFS}"))?;
        *slot = Some(drf);
        if let Some(v) = &self.memory.video {
            v.params().validate(&drfs)?;
        }
        self.memory.drfs = drfs;
        Ok(())
    }

    /// Sets up the video port 808: frames of `p` written into the maps of DRFs `p.drfs`
    /// (set before, luminance, of the frames' size), their upper levels made by the
    /// generator 816. Takes effect at the next reset.
    pub fn attach_video(&mut self, p: VideoParams) -> Result<(), String> {
        self.memory.video = Some(Box::new(VideoPort808::new(p, &self.memory.drfs)?));
        Ok(())
    }

    /// The video port, when set up.
    pub fn video(&self) -> Option<&VideoPort808> {
        self.memory.video.as_deref()
    }

    /// The video port, to drive its inputs.
    pub fn video_mut(&mut self) -> Option<&mut VideoPort808> {
        self.memory.video.as_deref_mut()
    }

    /// DRF `k`'s descriptor, or why there is none.
    fn set(&self, k: usize) -> Result<Drf, String> {
        self.drf(k).ok_or(format!("drf {k}: not set"))
    }

    /// Texels of level `lv` of DRF `k`'s map as the banks hold them, row-major.
    pub fn read_level(&self, k: usize, lv: u32) -> Result<Vec<u8>, String> {
        let d = self.set(k)?;
        let (w, h) = d.level_size(lv);
        Ok((0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let (b, word) = locate(&d, lv, x, y);
                self.memory.banks[b][word as usize]
            })
            .collect())
    }

    /// 824 for a video round starting: the rows its segments write or read, the slots it
    /// takes (one, two if any bank has another row open). False when there is none to start.
    fn video_round(&mut self) -> bool {
        let Some(v) = self.memory.video.as_deref_mut() else {
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
        self.banks
            .left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        self.slots.set_next_bits(self.slots.q().bits() + slots);
        self.banks.vid_round.set_next_bits(n as u64);
        true
    }

    /// Loads the CLUT 814.
    pub fn set_clut(&mut self, clut: Clut) {
        self.clut.table = clut;
    }

    /// Writes level `lv` of DRF `k`'s map (levels made by the host, e.g. an index map's).
    pub fn write_level(&mut self, k: usize, lv: u32, texels: &[u8]) -> Result<(), String> {
        let d = self.set(k)?;
        store_level(&mut self.memory.banks, &d, lv, texels).map_err(|e| format!("drf {k}: {e}"))
    }

    /// Writes the map `d` describes, every level, wherever its bases say.
    pub fn load_map(&mut self, d: &Drf, level0: &[u8]) -> Result<(), String> {
        let banks = &mut self.memory.banks;
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
        let d = self.set(k)?;
        let banks = &mut self.memory.banks;
        super::load_levels(&d, level0, |lv, t| {
            store_level(banks, &d, lv, t).map_err(|e| format!("drf {k}: {e}"))
        })
    }

    /// The descriptor a request's DRF number reads: DRF `k`, or 812's working descriptor.
    fn request_drf(&self, k: usize) -> Option<Drf> {
        if k == usize::from(super::WORKING) {
            self.working
        } else {
            self.drf(k)
        }
    }

    /// 824: the access moving into the banks, round by round: its cost in slots (one a round,
    /// two when a bank misses its open row), the rows it leaves open.
    fn open_rows(&mut self) {
        let words = &self.address.access.words;
        let (mut slots, mut missed, mut fault_slots) = (0u64, 0u64, 0u64);
        for r in 0..ROUNDS {
            let reads = (0..BANKS).filter_map(|b| words.reads(b, r).map(|w| (b, w)));
            let rows = reads.map(|(b, word)| (b, word / u64::from(ROW_WORDS)));
            let any = rows.clone().next().is_some();
            if any || r == 0 {
                let cost = self.pages.round(rows);
                slots += u64::from(cost.slots);
                fault_slots += u64::from(cost.slots - 1);
                missed += u64::from(cost.faults);
            }
        }
        self.banks
            .left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        self.banks.fault.set_next_bool(missed > 0);
        self.slots.set_next_bits(self.slots.q().bits() + slots);
        self.faults.set_next_bits(self.faults.q().bits() + missed);
        self.accesses.set_next_bits(self.accesses.q().bits() + 1);
        self.fault_slots
            .set_next_bits(self.fault_slots.q().bits() + fault_slots);
    }

    /// 810, 814 and 818: the banks' data at the end of the slot(s), interpolated (an index
    /// access's looked up first); a colour request's components are collected and come out
    /// through 820 with its last.
    fn interpolate(&mut self) {
        let access = &self.banks.access;
        let texels = self.banks.texels(&self.memory.banks);
        let (a, b, f) = access.weights();
        let sum = trilinear_sum(&texels, a, b, f);
        let last = access.last.q().is_high();
        let rgba = if access.index.q().is_high() {
            let rgba = self.clut.look_up(&texels, a, b, f);
            self.trilinear.keep(rgba);
            rgba
        } else {
            let value = trilinear(&texels, a, b, f);
            self.trilinear.collect(value, access.part.q().bits(), last)
        };
        if last {
            let illum = access.illum.q().bits() as u32;
            let fault = self.banks.fault.q().is_high();
            let m = access.modulate();
            self.output.finish(m, illum, rgba, texels, fault, sum);
        }
    }

    /// The bank stage this cycle: the video port's round or the access waiting in 812 moves
    /// in at a slot boundary (video first: video cannot wait), or the access under way goes
    /// on. Returns whether 812's access moved on.
    fn bank_stage(&mut self, busy: bool, finishing: bool) -> bool {
        let waiting = self.address.access.valid.q().is_high();
        let video = (!busy || finishing) && self.video_round();
        let move_on = waiting && (!busy || finishing) && !video;
        if video {
            self.banks.access.valid.set_next_bool(true);
        } else if move_on {
            self.open_rows();
            let b = &mut self.banks;
            b.vid_round.set_next_bits(0);
            b.access.take_from(&self.address.access);
            b.access.valid.set_next_bool(true);
        } else if finishing {
            self.banks.access.valid.set_next_bool(false);
            self.banks.vid_round.set_next_bits(0);
        } else if busy {
            let left = &mut self.banks.left;
            left.set_next_bits(left.q().bits() - 1);
        }
        move_on
    }

    pub fn eval(&mut self) {
        self.pages.eval();
        self.output.eval();
        self.clut.eval();
        let busy = self.banks.access.valid.q().is_high();
        let finishing = busy && self.banks.left.q().bits() == 1;
        let served = self.banks.vid_round.q().bits() as usize;
        let memory = &mut self.memory;
        if let Some(v) = memory.video.as_deref_mut() {
            v.eval(finishing && served > 0, &memory.drfs);
        }
        if finishing && served == 0 {
            self.interpolate();
        }
        let waiting = self.address.access.valid.q().is_high();
        let move_on = self.bank_stage(busy, finishing);
        // A colour request's next component follows its last into 812; a new request is
        // taken only when 812 holds nothing more of the last one.
        let more = waiting && !self.address.access.last.q().is_high();
        let ready = (!waiting || move_on) && !more;
        self.req_ready.set_bool(ready);
        let take = ready && self.req_valid.is_high();
        if take {
            let k = self.req_drf.bits();
            let d = self.request_drf(k as usize);
            let uvl = [&self.req_u, &self.req_v, &self.req_lambda].map(|x| x.raw() as i32);
            let illum = self.req_illum.bits();
            self.address.take(k, d, (uvl[0], uvl[1], uvl[2]), illum);
        } else if move_on && more {
            let d = self.request_drf(self.address.held_drf());
            self.address.next_part(d);
        }
        if take || move_on {
            // A new access (or component), or the last one gone to the banks; else it waits.
            self.address.access.valid.set_next_bool(take || more);
        }
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
        let d = self.sim.dut.set(usize::from(req.drf))?;
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

    /// The chip, as its last access left it.
    fn visit(&self, v: &mut dyn crate::kernel::Visitor) {
        self.sim.dut.visit(v);
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
            let done = self.sim.dut.output.out_valid.q().is_high() && sent;
            if done {
                let dut = &self.sim.dut;
                let rgba = (dut.output.out_rgba.q().bits() as u32).to_be_bytes();
                let plane = match d.config {
                    Config::Planar | Config::Literal => d.component_map(),
                    _ => d,
                };
                let fp = Footprint::of(&plane, req.u, req.v, req.lambda);
                let reply = super::TexramReply {
                    fine: fp.fine,
                    coarse: fp.coarse,
                    texels: dut.output.out_texels.q().bits().to_le_bytes(),
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
