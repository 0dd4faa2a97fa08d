//! The texture mapping unit 602 of Schilling & Knittel, Figure 6, end to end: requests from
//! the rasterizer, the block-fetch part of DRAM control unit 607 (with [`DramCtrl`] driving
//! DRAM 604's pins), CCC decode 608/610/612, cache 614 with lookahead, colour extract 618 and
//! bilinear interpolator 622. One 24-bit RGB result per request, in request order.
//!
//! # Request format
//! `u`, `v`: unsigned `uQ12.F` texel coordinates (`12 + F` bits, `F = frac_bits`, default 4):
//! the integer part is the texel `x0` (must be below the texture's width / height), the
//! fraction `fu` is the weight of texel `x0 + 1`. Texel `(x, y)` is sampled exactly at integer
//! coordinates. Addressing clamps to the edge (`x1 = min(x0 + 1, width - 1)`), which keeps the
//! Figure 7 interleave conflict-free for every texture size. `newline`: the rasterizer's
//! scanline-change flag.
//!
//! # Pipeline and timing (controller cycles of `dram.cycle_ns`, default 5 ns)
//! * Stage 0 (`req_*` registers): the request's 2x2 footprint covers 1, 2 or 4 blocks; each is
//!   looked up in its entry of cache 614. All present: the four lines go to colour extract 618
//!   this cycle and the next request is accepted (one request per cycle when everything hits).
//! * A missing block (lowest entry first) starts a demand fill when the fill engine is free:
//!   two word reads through control unit 607 (page mode when the row is open: 6 cycles = 30 ns
//!   each; a page fault adds `t_rp + t_rcd` = 30 ns), into register 608, two CLUT cycles, the
//!   line written to the cache. The request is looked up again every cycle until all its
//!   blocks are present. One fill at a time; a fill in progress is never abandoned.
//! * Lookahead (cache on, [`Lookahead`] not off): when a request completes and it was not
//!   flagged `newline`, up to three neighbours of its block are queued: those of its quadrant,
//!   or those in the direction of motion from the previous point of the scanline (registers
//!   `prev_u`, `prev_v`; see [`crate::texmem::cache_614`]), except one that would go into the
//!   entry of another block of its footprint (a preload never evicts a block the footprint
//!   uses). The fill engine preloads them one at a time whenever it is free and the request in
//!   stage 0 (if any) needs nothing. A demand miss,
//!   or a request flagged `newline`, empties the queue. Candidates already in the cache are
//!   dropped without a fill.
//! * Cache off: all entries are invalidated when a request completes, so every request fetches
//!   all its blocks; lookahead is off too. The results are bit-identical in every mode.
//! * 618 registers the texels (1 cycle), 622 registers the colour (1 cycle): a request that
//!   hits is answered two cycles after its lookup.
//!
//! # Statistics ([`TexStats`])
//! Counted at clock edges (so a schedule check evaluating twice does not count twice).

use crate::fx::{Bit, Format};
use crate::kernel::declared::Regs;
use crate::kernel::{Module, Reg, RegOf, Signal, SignalOf, Visitor};
use crate::texmem::bilinear_622::ColorBilinear;
use crate::texmem::cache_614::{entry_of, EntryMask, Lookahead, TextureCache};
use crate::texmem::ccc_decode_608::{CccDecode, Rgb};
use crate::texmem::control_607::{DramCtrl, FillEngine, LookaheadQueue};
use crate::texmem::dram_604::DramParams;
use crate::texmem::extract_618::ColorExtract;
use crate::texmem::layout::{BlockMap, Layout};

/// Bits of the integer part of `u` and `v`.
pub const COORD_BITS: u32 = 12;

/// Configuration of the unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexParams {
    /// Texture size in texels: multiples of 4 in 4..=4096.
    pub width: u32,
    pub height: u32,
    /// Fraction bits `F` of `u`, `v` and of the blend weights (1..=8).
    pub frac_bits: u32,
    pub layout: Layout,
    /// First DRAM word of the texture.
    pub base: u64,
    pub cache: bool,
    pub lookahead: Lookahead,
    pub dram: DramParams,
}

impl TexParams {
    pub fn new(width: u32, height: u32) -> TexParams {
        TexParams {
            width,
            height,
            frac_bits: 4,
            layout: Layout::RowMajor,
            base: 0,
            cache: true,
            lookahead: Lookahead::Quadrant,
            dram: DramParams::default(),
        }
    }

    pub fn blocks(&self) -> (u32, u32) {
        (self.width / 4, self.height / 4)
    }

    pub fn block_map(&self) -> BlockMap {
        let (bw, bh) = self.blocks();
        BlockMap::new(self.layout, bw, bh, self.dram.cols, self.base)
    }

    pub fn validate(&self) -> Result<(), String> {
        self.dram.validate()?;
        for (n, v) in [("width", self.width), ("height", self.height)] {
            if v % 4 != 0 || !(4..=1 << COORD_BITS).contains(&v) {
                return Err(format!(
                    "texture {n} {v}: a multiple of 4 in 4..={}",
                    1 << COORD_BITS
                ));
            }
        }
        if !(1..=8).contains(&self.frac_bits) {
            return Err(format!("frac_bits {}: 1..=8", self.frac_bits));
        }
        let need = self.base + self.block_map().words();
        if need > self.dram.words() {
            return Err(format!(
                "a {}x{} texture ({} layout) needs DRAM words up to {need}, the DRAM has {}",
                self.width,
                self.height,
                self.layout.name(),
                self.dram.words()
            ));
        }
        Ok(())
    }

    /// Is `(u, v)` (raw `uQ12.F`) inside the texture?
    pub fn in_range(&self, u: u32, v: u32) -> bool {
        (u >> self.frac_bits) < self.width && (v >> self.frac_bits) < self.height
    }
}

/// Counts, at clock edges.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TexStats {
    /// Requests accepted.
    pub requests: u64,
    /// Blocks referenced by requests (1, 2 or 4 each), at their first lookup.
    pub block_refs: u64,
    /// Of those, found in the cache at the first lookup.
    pub hits: u64,
    /// Of the hits, blocks brought in by a prefetch and not used before.
    pub prefetch_hits: u64,
    /// Blocks missing at the first lookup that a prefetch was already fetching.
    pub late_prefetches: u64,
    /// Demand fills (blocks fetched because a request needed them).
    pub demand_fills: u64,
    /// Prefetch fills started, and candidates dropped because the block was present.
    pub prefetch_fills: u64,
    pub prefetch_dropped: u64,
    /// Cycles a request sat in stage 0 without completing.
    pub stall_cycles: u64,
}

#[derive(Clone, Copy, Debug, Default)]
struct Events {
    accept: u64,
    refs: u64,
    hits: u64,
    pf_hits: u64,
    late: u64,
    demand: u64,
    prefetch: u64,
    dropped: u64,
    stall: u64,
}

/// What the first lookup of a request saw (a monitor port for testbenches: the real
/// cache's hit or miss per block, for miss classification).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Lookup {
    /// A request's first lookup happened this cycle.
    pub first: bool,
    pub n: usize,
    pub blocks: [(u32, u32); 4],
    pub hit: [bool; 4],
}

/// Stage 0's view of its request this cycle.
#[derive(Clone, Copy, Debug, Default)]
struct Stage0 {
    /// A request is in stage 0, and all its blocks are present (it leaves this cycle).
    busy: bool,
    done: bool,
    /// Its first missing block (lowest entry first).
    missing: Option<(u32, u32)>,
    /// Its first lookup, and it is flagged `newline`.
    newline_now: bool,
}

/// Texture mapping unit 602.
#[derive(Clone, Debug, Module)]
#[module(kind = "texture_unit_602")]
pub struct TextureUnit {
    #[instance]
    name: String,
    p: TexParams,
    // Rasterizer side.
    #[input]
    pub in_valid: SignalOf<Bit>,
    #[input]
    pub in_u: Signal,
    #[input]
    pub in_v: Signal,
    #[input]
    pub in_newline: SignalOf<Bit>,
    #[output]
    pub in_ready: SignalOf<Bit>,
    #[output]
    pub out_valid: SignalOf<Bit>,
    #[output]
    pub out_rgb: SignalOf<Rgb>,
    // Stage 0.
    #[reg]
    pub req_valid: RegOf<Bit>,
    #[reg]
    pub req_u: Reg,
    #[reg]
    pub req_v: Reg,
    #[reg]
    pub req_newline: RegOf<Bit>,
    #[reg]
    req_seen: RegOf<Bit>,
    /// Entries the request needs and entries that hit (this cycle).
    #[wire]
    pub need_mask: SignalOf<EntryMask>,
    #[wire]
    pub hit_mask: SignalOf<EntryMask>,
    /// Control unit 607: block fetch, lookahead queue, word reads (with DRAM 604).
    #[child]
    pub fill: FillEngine,
    #[child]
    pub queue: LookaheadQueue,
    #[child]
    pub mem: DramCtrl,
    #[child]
    pub decode: CccDecode,
    #[child]
    pub cache: TextureCache,
    #[child]
    pub extract: ColorExtract,
    #[child]
    pub bilinear: ColorBilinear,
    /// The statistics ([`TextureUnit::stats`]).
    #[reg]
    counters: Counters,
    /// The monitor port (valid after `eval`).
    pub lookup: Lookup,
}

impl TextureUnit {
    /// The statistics so far.
    pub fn stats(&self) -> TexStats {
        self.counters.stats
    }

    /// A unit with the DRAM loaded from `words` at `p.base` (see
    /// [`crate::texmem::layout`]) and CLUT 612 from `clut`.
    pub fn new(name: &str, p: TexParams, clut: &[u32], words: &[u16]) -> Result<Self, String> {
        p.validate()?;
        let mut mem = DramCtrl::new("control_607", p.dram)?;
        mem.dram.load(p.base, words)?;
        let ub = COORD_BITS + p.frac_bits;
        // uQ12.F: the waveform shows u and v as texel coordinates beside the bits.
        let uq = Format::unsigned(ub, p.frac_bits as i32);
        let bb = COORD_BITS - 2;
        let look = if p.cache { p.lookahead } else { Lookahead::Off };
        Ok(TextureUnit {
            name: name.into(),
            p,
            in_valid: SignalOf::new("in_valid"),
            in_u: Signal::new("in_u", uq),
            in_v: Signal::new("in_v", uq),
            in_newline: SignalOf::new("in_newline"),
            in_ready: SignalOf::new("in_ready"),
            out_valid: SignalOf::new("out_valid"),
            out_rgb: SignalOf::new("out_rgb"),
            req_valid: RegOf::new("req_valid"),
            req_u: Reg::new("req_u", uq),
            req_v: Reg::new("req_v", uq),
            req_newline: RegOf::new("req_newline"),
            req_seen: RegOf::new("req_seen"),
            need_mask: SignalOf::new("need_mask"),
            hit_mask: SignalOf::new("hit_mask"),
            fill: FillEngine::new(p.block_map(), bb, mem.req_addr.fmt()),
            queue: LookaheadQueue::new(look, p.blocks(), uq, bb),
            mem,
            decode: CccDecode::new("ccc_decode_608", clut)?,
            cache: TextureCache::new("cache_614", bb - 1),
            extract: ColorExtract::new("extract_618", COORD_BITS, p.frac_bits),
            bilinear: ColorBilinear::new("bilinear_622", p.frac_bits)?,
            counters: Counters::default(),
            lookup: Lookup::default(),
        })
    }

    pub fn params(&self) -> &TexParams {
        &self.p
    }

    /// Nothing in flight: no request in stage 0 or in 618/622, no fill, no queued prefetch
    /// that could still start.
    pub fn idle(&self) -> bool {
        !self.req_valid.q().is_high()
            && !self.extract.valid.q().is_high()
            && !self.bilinear.valid.q().is_high()
            && self.fill.is_idle()
            && self.queue.mask.q().bits() == 0
    }

    /// Stage 0: looks the request's 1, 2 or 4 blocks up in cache 614 (the monitor port and the
    /// statistics see the first lookup); when all are present, hands the footprint to colour
    /// extract 618 and (cache off) invalidates the cache or (lookahead on) offers the request's
    /// neighbours to the lookahead queue.
    fn stage0(&mut self) -> Stage0 {
        self.lookup.first = false;
        self.queue.complete.set_bool(false);
        self.cache.touch.set_bits(0);
        self.cache.invalidate.set_bool(false);
        let busy = self.req_valid.q().is_high();
        if !busy {
            self.need_mask.set_bits(0);
            self.hit_mask.set_bits(0);
            self.extract.in_valid.set_bool(false);
            return Stage0::default();
        }
        let f = self.p.frac_bits;
        let (u, v) = (self.req_u.q().bits(), self.req_v.q().bits());
        let (x0, y0) = ((u >> f) as u32, (v >> f) as u32);
        let x1 = (x0 + 1).min(self.p.width - 1);
        let y1 = (y0 + 1).min(self.p.height - 1);
        let first = !self.req_seen.q().is_high();
        let missing = self.lookup_blocks([x0 >> 2, x1 >> 2], [y0 >> 2, y1 >> 2], first);
        let newline = self.req_newline.q().is_high();
        if first {
            self.req_seen.set_next_bool(true);
        }
        let done = missing.is_none();
        self.counters.ev.stall = u64::from(!done);
        let ex = &mut self.extract;
        ex.in_valid.set_bool(done);
        if done {
            let fmask = (1u64 << f) - 1;
            ex.x0.set_bits(u64::from(x0));
            ex.x1.set_bits(u64::from(x1));
            ex.y0.set_bits(u64::from(y0));
            ex.y1.set_bits(u64::from(y1));
            ex.in_fu.set_bits(u & fmask);
            ex.in_fv.set_bits(v & fmask);
            for e in 0..4 {
                ex.lines[e] = self.cache.line(e);
            }
            self.cache.invalidate.set_bool(!self.p.cache);
            let q = &mut self.queue;
            q.complete
                .set_bool(self.p.cache && self.p.lookahead != Lookahead::Off);
            q.u.set_bits(u);
            q.v.set_bits(v);
            q.newline.set_bool(newline);
        }
        Stage0 {
            busy,
            done,
            missing,
            newline_now: first && newline,
        }
    }

    /// The lookup of blocks `bxs x bys` (deduplicated): need and hit masks, the monitor port,
    /// the entries to touch, the first lookup's statistics. Returns the first missing block.
    fn lookup_blocks(&mut self, bxs: [u32; 2], bys: [u32; 2], first: bool) -> Option<(u32, u32)> {
        let nx = if bxs[0] == bxs[1] { 1 } else { 2 };
        let ny = if bys[0] == bys[1] { 1 } else { 2 };
        let (fbx, fby, fill_pf) = self.fill.block();
        let filling = !self.fill.is_idle();
        let (mut need, mut hit, mut missing) = (0u64, 0u64, None);
        // Written in place (a local copy made this the hottest line: a 56-byte store
        // forwarded from narrow writes).
        let lk = &mut self.lookup;
        lk.first = first;
        lk.n = 0;
        for &by in &bys[..ny] {
            for &bx in &bxs[..nx] {
                let e = entry_of(bx, by);
                let h = self.cache.holds(bx, by);
                need |= 1 << e;
                hit |= u64::from(h) << e;
                lk.blocks[lk.n] = (bx, by);
                lk.hit[lk.n] = h;
                lk.n += 1;
                if !h && missing.is_none() {
                    missing = Some((bx, by));
                }
                // A prefetched block counts as used by the first request that finds it; as a
                // prefetch hit only if that was the request's first lookup.
                if h && first && self.cache.prefetched(e) {
                    self.counters.ev.pf_hits += 1;
                }
                if first && !h && filling && fill_pf && (fbx, fby) == (bx, by) {
                    self.counters.ev.late += 1;
                }
            }
        }
        self.cache.touch.set_bits(hit);
        self.need_mask.set_bits(need);
        self.hit_mask.set_bits(hit);
        if first {
            self.counters.ev.refs = lk.n as u64;
            self.counters.ev.hits = u64::from(hit.count_ones());
        }
        missing
    }

    /// The fill path of 607: the fill engine's word request to the word controller (and DRAM
    /// 604), words into register 608, multiplexer 610 and CLUT 612, the line into cache 614.
    fn fill_path(&mut self) {
        let req = self.fill.word_request();
        self.mem.req_valid.set_bool(req.is_some());
        if let Some(a) = req {
            self.mem.req_addr.set_bits(a);
        }
        self.mem.eval();
        self.decode.word_valid.follow(&self.mem.resp_valid);
        self.decode.word.follow(&self.mem.resp_data);
        self.decode.eval();
        let (bx, by, prefetch) = self.fill.block();
        let c = &mut self.cache;
        c.write.follow(&self.decode.line_valid);
        c.write_bx.set_bits(u64::from(bx));
        c.write_by.set_bits(u64::from(by));
        c.write_data.follow(&self.decode.line);
        c.write_prefetched.set_bool(prefetch);
        c.eval();
    }

    /// Starts a fill when the engine is free: a demand miss of stage 0 first (it empties the
    /// lookahead queue, as a `newline` request does), else the queue's first candidate (dropped
    /// when the cache already holds it).
    fn start_fills(&mut self, s0: &Stage0) {
        let free = self.fill.is_idle();
        let demand = s0.missing.filter(|_| free);
        let q = &mut self.queue;
        q.flush.set_bool(demand.is_some() || s0.newline_now);
        q.engine_free.set_bool(free);
        q.stage0_missing.set_bool(s0.missing.is_some());
        q.eval();
        let mut start = demand.map(|b| (b, false));
        if start.is_some() {
            self.counters.ev.demand = 1;
        } else if self.queue.take.is_high() {
            let b = (
                self.queue.take_bx.bits() as u32,
                self.queue.take_by.bits() as u32,
            );
            if self.cache.holds(b.0, b.1) {
                self.counters.ev.dropped = 1;
            } else {
                start = Some((b, true));
                self.counters.ev.prefetch = 1;
            }
        }
        let f = &mut self.fill;
        f.start.set_bool(start.is_some());
        let ((bx, by), pf) = start.unwrap_or(((0, 0), false));
        f.start_bx.set_bits(u64::from(bx));
        f.start_by.set_bits(u64::from(by));
        f.start_prefetch.set_bool(pf);
        f.word_ready.follow(&self.mem.ready);
        f.word_resp.follow(&self.mem.resp_valid);
        f.line_done.follow(&self.decode.line_valid);
        f.eval();
    }

    /// The rasterizer handshake: a new request is taken when stage 0 is empty or its request
    /// leaves this cycle.
    fn handshake(&mut self, s0: &Stage0) {
        let ready = !s0.busy || s0.done;
        self.in_ready.set_bool(ready);
        let accept = ready && self.in_valid.is_high();
        self.counters.ev.accept = u64::from(accept);
        if accept {
            self.req_valid.set_next_bool(true);
            self.req_u.set_next_bits(self.in_u.bits());
            self.req_v.set_next_bits(self.in_v.bits());
            self.req_newline.set_next_bool(self.in_newline.is_high());
            self.req_seen.set_next_bool(false);
        } else if s0.done {
            self.req_valid.set_next_bool(false);
        }
    }

    /// Colour extract 618 (registered texels) and bilinear interpolator 622 (registered
    /// colour), and the unit's output.
    fn output_stages(&mut self) {
        self.extract.eval();
        let ex = &self.extract;
        let bl = &mut self.bilinear;
        bl.in_valid.follow(ex.valid.q());
        bl.c[0].follow(ex.c00.q());
        bl.c[1].follow(ex.c10.q());
        bl.c[2].follow(ex.c01.q());
        bl.c[3].follow(ex.c11.q());
        bl.fu.follow(ex.fu.q());
        bl.fv.follow(ex.fv.q());
        bl.eval();
        self.out_valid.follow(self.bilinear.valid.q());
        self.out_rgb.follow(self.bilinear.rgb.q());
    }
}

impl TextureUnit {
    /// Figure 6 from left to right: stage 0 looks the footprint up in cache 614; 607 fetches
    /// the missing block or a lookahead candidate through DRAM 604 into 608/610/612 and the
    /// cache; the rasterizer handshake; extract 618 and bilinear 622.
    pub fn eval(&mut self) {
        self.counters.ev = Events::default();
        let s0 = self.stage0();
        self.fill_path();
        self.start_fills(&s0);
        self.handshake(&s0);
        self.output_stages();
    }
}

/// The statistics' counters: this cycle's events, decided by `eval`, are added at the clock
/// edge as a register's next value is committed (so a schedule check that evaluates twice
/// does not count twice); none under reset. Statistics, not hardware: not traced.
#[derive(Clone, Debug, Default)]
struct Counters {
    stats: TexStats,
    ev: Events,
}

impl Regs for Counters {
    #[inline]
    fn tick_regs(&mut self, reset: bool) {
        if !reset {
            self.count_events();
        }
    }
    fn visit_regs(&self, _: &mut dyn Visitor) {}
}

impl Counters {
    /// This cycle's events into the statistics.
    fn count_events(&mut self) {
        let ev = self.ev;
        let s = &mut self.stats;
        // One branch per counter: adjacent counters updated together got vectorised into
        // 16-byte loads of 8-byte stores, a store-forwarding stall every cycle.
        let add = |c: &mut u64, x: u64| {
            if x != 0 {
                *c += x;
            }
        };
        add(&mut s.requests, ev.accept);
        add(&mut s.block_refs, ev.refs);
        add(&mut s.hits, ev.hits);
        add(&mut s.prefetch_hits, ev.pf_hits);
        add(&mut s.late_prefetches, ev.late);
        add(&mut s.demand_fills, ev.demand);
        add(&mut s.prefetch_fills, ev.prefetch);
        add(&mut s.prefetch_dropped, ev.dropped);
        add(&mut s.stall_cycles, ev.stall);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside means texel column below the width and row below the height (raw `uQ12.F`).
    #[test]
    fn in_range_ends_at_the_last_texel() {
        let p = TexParams::new(64, 32);
        let f = p.frac_bits;
        assert!(p.in_range(0, 0));
        assert!(p.in_range((64 << f) - 1, (32 << f) - 1));
        assert!(!p.in_range(64 << f, 0));
        assert!(!p.in_range(0, 32 << f));
    }
}
