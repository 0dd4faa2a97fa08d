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
//!   `prev_u`, `prev_v`; see [`crate::texmem::cache_614`]). The fill engine preloads them one at a
//!   time whenever it is free and the request in stage 0 (if any) needs nothing. A demand miss,
//!   or a request flagged `newline`, empties the queue. Candidates already in the cache are
//!   dropped without a fill.
//! * Cache off: all entries are invalidated when a request completes, so every request fetches
//!   all its blocks; lookahead is off too. The results are bit-identical in every mode.
//! * 618 registers the texels (1 cycle), 622 registers the colour (1 cycle): a request that
//!   hits is answered two cycles after its lookup.
//!
//! # Statistics ([`TexStats`])
//! Counted at clock edges (so a schedule check evaluating twice does not count twice).

use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::signals;
use crate::texmem::bilinear_622::ColorBilinear;
use crate::texmem::cache_614::{entry_of, lookahead, lookahead_direction, Lookahead, TextureCache};
use crate::texmem::ccc_decode_608::CccDecode;
use crate::texmem::control_607::DramCtrl;
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

const FILL_IDLE: u64 = 0;
const FILL_FETCH: u64 = 1;
const FILL_DECODE: u64 = 2;

/// Texture mapping unit 602.
#[derive(Clone, Debug)]
pub struct TextureUnit {
    name: String,
    p: TexParams,
    map: BlockMap,
    // Rasterizer side.
    pub in_valid: Signal,
    pub in_u: Signal,
    pub in_v: Signal,
    pub in_newline: Signal,
    pub in_ready: Signal,
    pub out_valid: Signal,
    pub out_rgb: Signal,
    // Stage 0.
    pub req_valid: Reg,
    pub req_u: Reg,
    pub req_v: Reg,
    pub req_newline: Reg,
    req_seen: Reg,
    /// Entries the request needs and entries that hit (this cycle).
    pub need_mask: Signal,
    pub hit_mask: Signal,
    // Fill engine (part of 607).
    pub fill_state: Reg,
    pub fill_bx: Reg,
    pub fill_by: Reg,
    pub fill_prefetch: Reg,
    words_issued: Reg,
    /// Lookahead queue: up to three blocks, `pf_mask` says which slots are live.
    pub pf_mask: Reg,
    pf_bx: [Reg; 3],
    pf_by: [Reg; 3],
    /// The previous completed point of this scanline (direction lookahead).
    pub prev_valid: Reg,
    pub prev_u: Reg,
    pub prev_v: Reg,
    pub mem: DramCtrl,
    pub decode: CccDecode,
    pub cache: TextureCache,
    pub extract: ColorExtract,
    pub bilinear: ColorBilinear,
    pub stats: TexStats,
    /// The monitor port (valid after `eval`).
    pub lookup: Lookup,
    ev: Events,
}

impl TextureUnit {
    /// A unit with the DRAM loaded from `words` at `p.base` (see
    /// [`crate::texmem::layout`]) and CLUT 612 from `clut`.
    pub fn new(name: &str, p: TexParams, clut: &[u32], words: &[u16]) -> Result<Self, String> {
        p.validate()?;
        let map = p.block_map();
        let mut mem = DramCtrl::new("control_607", p.dram)?;
        mem.dram.load(p.base, words)?;
        let ub = COORD_BITS + p.frac_bits;
        // uQ12.F: the waveform shows u and v as texel coordinates beside the bits.
        let uq = Format::unsigned(ub, p.frac_bits as i32);
        let bb = COORD_BITS - 2;
        Ok(TextureUnit {
            name: name.into(),
            p,
            map,
            in_valid: Signal::bit("in_valid"),
            in_u: Signal::new("in_u", uq),
            in_v: Signal::new("in_v", uq),
            in_newline: Signal::bit("in_newline"),
            in_ready: Signal::bit("in_ready"),
            out_valid: Signal::bit("out_valid"),
            out_rgb: Signal::new("out_rgb", Format::uint(24)),
            req_valid: Reg::new("req_valid", Format::uint(1)),
            req_u: Reg::new("req_u", uq),
            req_v: Reg::new("req_v", uq),
            req_newline: Reg::new("req_newline", Format::uint(1)),
            req_seen: Reg::new("req_seen", Format::uint(1)),
            need_mask: Signal::new("need_mask", Format::uint(4)),
            hit_mask: Signal::new("hit_mask", Format::uint(4)),
            fill_state: Reg::new("fill_state", Format::uint(2)),
            fill_bx: Reg::new("fill_bx", Format::uint(bb)),
            fill_by: Reg::new("fill_by", Format::uint(bb)),
            fill_prefetch: Reg::new("fill_prefetch", Format::uint(1)),
            words_issued: Reg::new("words_issued", Format::uint(2)),
            pf_mask: Reg::new("pf_mask", Format::uint(3)),
            pf_bx: [0, 1, 2].map(|_| Reg::new("pf_bx", Format::uint(bb))),
            pf_by: [0, 1, 2].map(|_| Reg::new("pf_by", Format::uint(bb))),
            prev_valid: Reg::new("prev_valid", Format::uint(1)),
            prev_u: Reg::new("prev_u", uq),
            prev_v: Reg::new("prev_v", uq),
            mem,
            decode: CccDecode::new("ccc_decode_608", clut)?,
            cache: TextureCache::new("cache_614", bb - 1),
            extract: ColorExtract::new("extract_618", COORD_BITS, p.frac_bits),
            bilinear: ColorBilinear::new("bilinear_622", p.frac_bits),
            stats: TexStats::default(),
            lookup: Lookup::default(),
            ev: Events::default(),
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
            && self.fill_state.q().bits() == FILL_IDLE
            && self.pf_mask.q().bits() == 0
    }

    fn start_fill(&mut self, bx: u32, by: u32, prefetch: bool) {
        self.fill_state.set_next_bits(FILL_FETCH);
        self.fill_bx.set_next_bits(u64::from(bx));
        self.fill_by.set_next_bits(u64::from(by));
        self.fill_prefetch.set_next_bool(prefetch);
        self.words_issued.set_next_bits(0);
    }
}

impl Module for TextureUnit {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "texture_unit_602"
    }
    fn eval(&mut self) {
        let mut ev = Events::default();
        let f = self.p.frac_bits;
        let fmask = (1u64 << f) - 1;
        let fill = self.fill_state.q().bits();
        let (fbx, fby) = (
            self.fill_bx.q().bits() as u32,
            self.fill_by.q().bits() as u32,
        );
        let fill_pf = self.fill_prefetch.q().is_high();

        // Stage 0: look the request's blocks up.
        let busy = self.req_valid.q().is_high();
        let mut done = false;
        let mut missing = None;
        let mut newline_now = false;
        let mut new_queue = None;
        self.lookup.first = false;
        if busy {
            let (u, v) = (self.req_u.q().bits(), self.req_v.q().bits());
            let (x0, y0) = ((u >> f) as u32, (v >> f) as u32);
            let x1 = (x0 + 1).min(self.p.width - 1);
            let y1 = (y0 + 1).min(self.p.height - 1);
            let bxs = [x0 >> 2, x1 >> 2];
            let bys = [y0 >> 2, y1 >> 2];
            let nx = if bxs[0] == bxs[1] { 1 } else { 2 };
            let ny = if bys[0] == bys[1] { 1 } else { 2 };
            let first = !self.req_seen.q().is_high();
            let (mut need, mut hit) = (0u64, 0u64);
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
                    // A prefetched block counts as used by the first request that finds it;
                    // as a prefetch hit only if that was the request's first lookup.
                    if h && self.cache.touch(bx, by) && first {
                        ev.pf_hits += 1;
                    }
                    if first && !h && fill != FILL_IDLE && fill_pf && (fbx, fby) == (bx, by) {
                        ev.late += 1;
                    }
                }
            }
            self.need_mask.set_bits(need);
            self.hit_mask.set_bits(hit);
            if first {
                ev.refs = self.lookup.n as u64;
                ev.hits = u64::from(hit.count_ones());
                self.req_seen.set_next_bool(true);
                newline_now = self.req_newline.q().is_high();
            }
            done = missing.is_none();
            self.extract.in_valid.set_bool(done);
            if done {
                self.extract.x0.set_bits(u64::from(x0));
                self.extract.x1.set_bits(u64::from(x1));
                self.extract.y0.set_bits(u64::from(y0));
                self.extract.y1.set_bits(u64::from(y1));
                self.extract.in_fu.set_bits(u & fmask);
                self.extract.in_fv.set_bits(v & fmask);
                for e in 0..4 {
                    self.extract.lines[e] = self.cache.line(e);
                }
                if !self.p.cache {
                    self.cache.invalidate();
                } else if self.p.lookahead != Lookahead::Off {
                    let newline = self.req_newline.q().is_high();
                    if self.p.lookahead == Lookahead::Direction {
                        self.prev_valid.set_next_bool(true);
                        self.prev_u.set_next_bits(u);
                        self.prev_v.set_next_bits(v);
                    }
                    let (bw, bh) = self.p.blocks();
                    let (mut q, mut m) = ([(0, 0); 3], 0);
                    let mut put = |k: usize, blk: (u32, u32)| {
                        q[k] = blk;
                        m |= 1 << k;
                    };
                    if newline {
                        // No lookahead for the first point of a scanline.
                    } else if self.p.lookahead == Lookahead::Quadrant {
                        for (k, blk) in lookahead(x0, y0, bw, bh).enumerate() {
                            put(k, blk);
                        }
                    } else if self.prev_valid.q().is_high() {
                        let sign = |a: u64, b: u64| (a > b) as i32 - (a < b) as i32;
                        let dx = sign(u, self.prev_u.q().bits());
                        let dy = sign(v, self.prev_v.q().bits());
                        for (k, blk) in
                            lookahead_direction(x0 >> 2, y0 >> 2, dx, dy, bw, bh).enumerate()
                        {
                            put(k, blk);
                        }
                    }
                    new_queue = Some((q, m));
                }
            } else {
                ev.stall = 1;
            }
        } else {
            self.need_mask.set_bits(0);
            self.hit_mask.set_bits(0);
            self.extract.in_valid.set_bool(false);
        }

        // Fill engine: word reads through 607.
        let issued = self.words_issued.q().bits();
        let want = fill == FILL_FETCH && issued < 2;
        self.mem.req_valid.set_bool(want);
        if want {
            self.mem
                .req_addr
                .set_bits(self.map.block_addr(fbx, fby) + issued);
        }
        self.mem.eval();
        if want && self.mem.ready.is_high() {
            self.words_issued.set_next_bits(issued + 1);
        }
        let resp = self.mem.resp_valid.is_high();
        self.decode.word_valid.set_bool(resp);
        if resp {
            self.decode.word.follow(&self.mem.resp_data);
            if issued == 2 && fill == FILL_FETCH {
                self.fill_state.set_next_bits(FILL_DECODE);
            }
        }
        self.decode.eval();
        let fill_free = fill == FILL_IDLE;
        if self.decode.line_valid.is_high() {
            self.cache.write(fbx, fby, self.decode.line.bits(), fill_pf);
            self.fill_state.set_next_bits(FILL_IDLE);
        }

        // Start a fill: demand first, then the lookahead queue. The queue: emptied by a demand
        // fill or a `newline` request, replaced by the neighbours of a request that completes,
        // and its first live candidate taken whenever the engine is free and stage 0 needs
        // nothing (the same cycle a request completes, from its new candidates).
        let (queue, mut qmask) = match new_queue {
            Some((q, m)) => (q, m),
            None => {
                let mut q = [(0, 0); 3];
                for (k, c) in q.iter_mut().enumerate() {
                    *c = (
                        self.pf_bx[k].q().bits() as u32,
                        self.pf_by[k].q().bits() as u32,
                    );
                }
                (q, self.pf_mask.q().bits())
            }
        };
        if let (true, Some((bx, by))) = (fill_free, missing) {
            self.start_fill(bx, by, false);
            ev.demand = 1;
            qmask = 0;
        } else if newline_now {
            qmask = 0;
        } else if fill_free && qmask != 0 && missing.is_none() {
            let k = qmask.trailing_zeros() as usize;
            let (bx, by) = queue[k];
            qmask &= !(1 << k);
            if self.cache.holds(bx, by) {
                ev.dropped = 1;
            } else {
                self.start_fill(bx, by, true);
                ev.prefetch = 1;
            }
        }
        if new_queue.is_some() {
            for (k, &(bx, by)) in queue.iter().enumerate() {
                self.pf_bx[k].set_next_bits(u64::from(bx));
                self.pf_by[k].set_next_bits(u64::from(by));
            }
        }
        self.pf_mask.set_next_bits(qmask);

        // Request handshake.
        let ready = !busy || done;
        self.in_ready.set_bool(ready);
        let accept = ready && self.in_valid.is_high();
        ev.accept = u64::from(accept);
        if accept {
            self.req_valid.set_next_bool(true);
            self.req_u.set_next_bits(self.in_u.bits());
            self.req_v.set_next_bits(self.in_v.bits());
            self.req_newline.set_next_bool(self.in_newline.is_high());
            self.req_seen.set_next_bool(false);
        } else if done {
            self.req_valid.set_next_bool(false);
        }

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
        self.ev = ev;
    }

    fn tick(&mut self, reset: bool) {
        if !reset {
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
        self.ev = Events::default();
        for r in [
            &mut self.req_valid,
            &mut self.req_u,
            &mut self.req_v,
            &mut self.req_newline,
            &mut self.req_seen,
            &mut self.fill_state,
            &mut self.fill_bx,
            &mut self.fill_by,
            &mut self.fill_prefetch,
            &mut self.words_issued,
            &mut self.pf_mask,
            &mut self.prev_valid,
            &mut self.prev_u,
            &mut self.prev_v,
        ] {
            r.tick(reset);
        }
        for r in self.pf_bx.iter_mut().chain(self.pf_by.iter_mut()) {
            r.tick(reset);
        }
        self.mem.tick(reset);
        self.decode.tick(reset);
        self.cache.tick(reset);
        self.extract.tick(reset);
        self.bilinear.tick(reset);
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        signals!(v;
            Input: self.in_valid, self.in_u, self.in_v, self.in_newline;
            Output: self.in_ready, self.out_valid, self.out_rgb;
            Reg: self.req_valid, self.req_u, self.req_v, self.req_newline, self.req_seen;
            Wire: self.need_mask, self.hit_mask;
            Reg: self.fill_state, self.fill_bx, self.fill_by, self.fill_prefetch,
                 self.words_issued, self.pf_mask, self.prev_valid, self.prev_u, self.prev_v);
        self.mem.visit(v);
        self.decode.visit(v);
        self.cache.visit(v);
        self.extract.visit(v);
        self.bilinear.visit(v);
        v.leave();
    }
}
