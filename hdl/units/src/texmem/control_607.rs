//! DRAM control unit 607 (Schilling & Knittel, Figure 6, section 5), as three modules: the
//! word-read controller that drives DRAM 604's pins ([`DramCtrl`]), the block fetch that reads
//! a CCC block's two words into register 608 ([`FillEngine`]), and the lookahead queue of
//! blocks to preload ([`LookaheadQueue`]).
//!
//! # The word-read controller
//! Takes word-read requests (valid + address), keeps the open page, and drives the pins: on a
//! page hit straight to the CAS# cycle; on a fault RAS# high for `t_rp`, RAS# low with the new
//! row for `t_rcd`, then the CAS# cycle. Counts reads, page hits and page faults. One request is
//! accepted when the previous one completes (`ready`).
//!
//! Timing parameters and the DRAM are in [`super::dram_604`].

use super::cache_614::{entry_of, lookahead, lookahead_direction, Lookahead};
use super::dram_604::Word;
use super::dram_604::{Dram, DramParams};
use super::layout::BlockMap;
use crate::fx::{Bit, Format};
use crate::kernel::{Module, Reg, RegOf, Signal, SignalOf};

hdl::formats! {
    /// The word controller's state ([`DramCtrl`]).
    pub CtrlState = Format::uint(3);
    /// A timing count, cycles (every timing is at most 1000).
    pub Count = Format::uint(11);
    /// A DRAM row.
    pub Row = Format::uint(11);
    /// A statistics counter.
    pub Tally = Format::uint(40);
    /// The fill engine's state ([`FillEngine`]).
    pub FillState = Format::uint(2);
    /// Words of a block requested so far (0..=2).
    pub Issued = Format::uint(2);
    /// The lookahead queue's live slots, one bit each.
    pub Slots = Format::uint(3);
}

/// Controller states.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    Idle = 0,
    Precharge = 1,
    RowOpen = 2,
    CasLow = 3,
    CasHigh = 4,
}

/// The states' names in the waveform, by value.
const STATES: &[&str] = &["IDLE", "PRECHARGE", "ROW_OPEN", "CAS_LOW", "CAS_HIGH"];

/// DRAM control unit 607 (word reads), with the DRAM 604 it drives.
#[derive(Clone, Debug, Module)]
#[module(kind = "control_607")]
pub struct DramCtrl {
    #[instance]
    name: String,
    p: DramParams,
    #[input]
    pub req_valid: SignalOf<Bit>,
    #[input]
    pub req_addr: Signal,
    #[output]
    pub ready: SignalOf<Bit>,
    #[output]
    pub resp_valid: SignalOf<Bit>,
    #[output]
    pub resp_data: SignalOf<Word>,
    #[reg]
    pub state: RegOf<CtrlState>,
    #[reg]
    count: RegOf<Count>,
    #[reg]
    open_row: RegOf<Row>,
    #[reg]
    row_open: RegOf<Bit>,
    #[reg]
    addr_r: Reg,
    /// Reads taken, and of them page hits and page faults.
    #[reg]
    pub reads: RegOf<Tally>,
    #[reg]
    pub page_hits: RegOf<Tally>,
    #[reg]
    pub page_faults: RegOf<Tally>,
    #[child]
    pub dram: Dram,
}

impl DramCtrl {
    pub fn new(name: &str, p: DramParams) -> Result<DramCtrl, String> {
        let dram = Dram::new("dram_604", p)?;
        let ab = 64 - (p.words() - 1).leading_zeros();
        Ok(DramCtrl {
            name: name.into(),
            p,
            req_valid: SignalOf::new("req_valid"),
            req_addr: Signal::new("req_addr", Format::uint(ab.max(1))),
            ready: SignalOf::new("ready"),
            resp_valid: SignalOf::new("resp_valid"),
            resp_data: SignalOf::new("resp_data"),
            state: RegOf::new("state").with_states(STATES),
            count: RegOf::new("count"),
            open_row: RegOf::new("open_row"),
            row_open: RegOf::new("row_open"),
            addr_r: Reg::new("addr_r", Format::uint(ab.max(1))),
            dram,
            reads: RegOf::new("reads"),
            page_hits: RegOf::new("page_hits"),
            page_faults: RegOf::new("page_faults"),
        })
    }

    pub fn params(&self) -> &DramParams {
        &self.p
    }
}

impl DramCtrl {
    /// The pins from the state, the next state from the request and the DRAM's data.
    pub fn eval(&mut self) {
        let st = self.state.q().bits();
        let n = self.count.q().bits() as u32;
        // A new request is taken when idle, or in the last cycle of CAS# precharge, so page-mode
        // reads follow each other every t_cas + t_cp cycles.
        let last_cp = st == State::CasHigh as u64 && n >= self.p.t_cp;
        let free = st == State::Idle as u64 || last_cp;
        self.ready.set_bool(free);
        let accept = free && self.req_valid.is_high();
        let addr = if accept {
            self.req_addr.bits()
        } else {
            self.addr_r.q().bits()
        };
        let (row, col) = self.p.row_col(addr);
        let open = self.row_open.q().is_high() && self.open_row.q().bits() == row;
        // Pins from the current state (Moore outputs).
        let (ras_n, cas_n, a) = match st {
            s if s == State::Precharge as u64 => (true, true, row),
            s if s == State::RowOpen as u64 => (false, true, row),
            s if s == State::CasLow as u64 => (false, false, col),
            _ => (!self.row_open.q().is_high(), true, col),
        };
        let d = &mut self.dram;
        d.ras_n.set_bool(ras_n);
        d.cas_n.set_bool(cas_n);
        d.oe_n.set_bool(cas_n);
        d.addr.set_bits(a);
        d.eval();
        self.resp_valid.set_bool(false);
        // Next state.
        let (next, cnt) = match st {
            _ if accept => {
                if open {
                    (State::CasLow, 1)
                } else {
                    (State::Precharge, 1)
                }
            }
            s if s == State::Idle as u64 => (State::Idle, 0),
            s if s == State::Precharge as u64 => {
                if n >= self.p.t_rp {
                    (State::RowOpen, 1)
                } else {
                    (State::Precharge, n + 1)
                }
            }
            s if s == State::RowOpen as u64 => {
                if n >= self.p.t_rcd {
                    (State::CasLow, 1)
                } else {
                    (State::RowOpen, n + 1)
                }
            }
            s if s == State::CasLow as u64 => {
                if n >= self.p.t_cas {
                    self.resp_valid.set_bool(self.dram.dq_valid.is_high());
                    self.resp_data.follow(&self.dram.dq);
                    (State::CasHigh, 1)
                } else {
                    (State::CasLow, n + 1)
                }
            }
            _ => {
                if last_cp {
                    (State::Idle, 0)
                } else {
                    (State::CasHigh, n + 1)
                }
            }
        };
        self.state.set_next_raw(next as i64);
        self.count.set_next_raw(i64::from(cnt));
        if accept {
            self.addr_r.set_next_bits(addr);
            self.open_row.set_next_bits(row);
            self.row_open.set_next_bool(true);
            let count = |r: &mut RegOf<Tally>| r.set_next_bits(r.q().bits() + 1);
            count(&mut self.reads);
            count(if open {
                &mut self.page_hits
            } else {
                &mut self.page_faults
            });
        }
    }
}

/// States of the fill engine, and their names in the waveform.
const FILL_IDLE: u64 = 0;
const FILL_FETCH: u64 = 1;
const FILL_DECODE: u64 = 2;
const FILL_STATES: &[&str] = &["IDLE", "FETCH", "DECODE"];

/// The block fetch of control unit 607: reads a CCC block's two DRAM words (word 0, then
/// word 1, in page mode when the row is open) through the word controller [`DramCtrl`] into
/// register 608, then waits while 610/612 decode it until the line is written to cache 614.
/// One fill at a time; a fill in progress is never abandoned.
///
/// Ports: `start` with `start_bx`, `start_by`, `start_prefetch` (taken only when idle);
/// `word_ready`, `word_resp` from the word controller; `line_done` from the decoder;
/// `word_req`, `word_addr` to the word controller (Moore outputs, also readable before `eval`
/// through [`FillEngine::word_request`]).
#[derive(Clone, Debug, Module)]
#[module(kind = "fill_engine_607")]
pub struct FillEngine {
    map: BlockMap,
    #[input]
    pub start: SignalOf<Bit>,
    #[input]
    pub start_bx: Signal,
    #[input]
    pub start_by: Signal,
    #[input]
    pub start_prefetch: SignalOf<Bit>,
    #[input]
    pub word_ready: SignalOf<Bit>,
    #[input]
    pub word_resp: SignalOf<Bit>,
    #[input]
    pub line_done: SignalOf<Bit>,
    #[output]
    pub word_req: SignalOf<Bit>,
    #[output]
    pub word_addr: Signal,
    #[reg]
    pub state: RegOf<FillState>,
    #[reg]
    pub bx: Reg,
    #[reg]
    pub by: Reg,
    #[reg]
    pub prefetch: RegOf<Bit>,
    #[reg]
    words_issued: RegOf<Issued>,
}

impl FillEngine {
    /// An engine for blocks laid out by `map`, block coordinates of `block_bits`, DRAM word
    /// addresses of format `addr`.
    pub fn new(map: BlockMap, block_bits: u32, addr: Format) -> FillEngine {
        let b = Format::uint(block_bits);
        FillEngine {
            map,
            start: SignalOf::new("start"),
            start_bx: Signal::new("start_bx", b),
            start_by: Signal::new("start_by", b),
            start_prefetch: SignalOf::new("start_prefetch"),
            word_ready: SignalOf::new("word_ready"),
            word_resp: SignalOf::new("word_resp"),
            line_done: SignalOf::new("line_done"),
            word_req: SignalOf::new("word_req"),
            word_addr: Signal::new("word_addr", addr),
            state: RegOf::new("state").with_states(FILL_STATES),
            bx: Reg::new("bx", b),
            by: Reg::new("by", b),
            prefetch: RegOf::new("prefetch"),
            words_issued: RegOf::new("words_issued"),
        }
    }

    /// No fill in progress (registered state).
    #[inline]
    pub fn is_idle(&self) -> bool {
        self.state.q().bits() == FILL_IDLE
    }

    /// The block being filled and whether it is a prefetch (registered state).
    #[inline]
    pub fn block(&self) -> (u32, u32, bool) {
        (
            self.bx.q().bits() as u32,
            self.by.q().bits() as u32,
            self.prefetch.q().is_high(),
        )
    }

    /// The DRAM word the engine asks for this cycle (from its state).
    #[inline]
    pub fn word_request(&self) -> Option<u64> {
        let issued = self.words_issued.q().bits();
        (self.state.q().bits() == FILL_FETCH && issued < 2).then(|| {
            let (bx, by, _) = self.block();
            self.map.block_addr(bx, by) + issued
        })
    }
}

impl FillEngine {
    /// The word request from the state; the next state from the controller and decoder.
    #[inline]
    pub fn eval(&mut self) {
        let req = self.word_request();
        self.word_req.set_bool(req.is_some());
        self.word_addr.set_bits(req.unwrap_or(0));
        let (st, issued) = (self.state.q().bits(), self.words_issued.q().bits());
        if req.is_some() && self.word_ready.is_high() {
            self.words_issued.set_next_bits(issued + 1);
        }
        if self.word_resp.is_high() && issued == 2 && st == FILL_FETCH {
            self.state.set_next_bits(FILL_DECODE);
        }
        if self.line_done.is_high() {
            self.state.set_next_bits(FILL_IDLE);
        }
        if self.start.is_high() && st == FILL_IDLE {
            self.state.set_next_bits(FILL_FETCH);
            self.bx.set_next_bits(self.start_bx.bits());
            self.by.set_next_bits(self.start_by.bits());
            self.prefetch.set_next_bool(self.start_prefetch.is_high());
            self.words_issued.set_next_bits(0);
        }
    }
}

/// The lookahead queue of control unit 607: up to three neighbouring blocks to preload,
/// chosen when a request completes (by quadrant or by direction of motion; see
/// [`crate::texmem::cache_614`]), offered to the fill engine one at a time.
///
/// Each cycle: when `complete` (a request leaves stage 0 with the cache and lookahead on),
/// its candidates replace the queue, except one that would go into the entry of another block
/// of the request's footprint: a preload never evicts a block the current footprint uses,
/// which the next point of the scanline needs too (with the Figure 7 interleave, block
/// `bx - 1` shares its entry with `bx + 1`, which a footprint across `bx` and `bx + 1` holds); `flush` (a demand fill starts, or a `newline` request is
/// looked up) empties it; otherwise, when the engine is free and stage 0 misses nothing, the
/// first live candidate is taken (`take`, `take_bx`, `take_by`: the unit drops it without a
/// fill when the cache already holds it). A request's candidates can be taken the cycle it
/// completes. The queue changes only then, on a flush or a take: its clock enable, so in any
/// other cycle its edge is skipped.
#[derive(Clone, Debug, Module)]
#[module(
    kind = "lookahead_queue_607",
    enable = self.complete.is_high() || self.flush.is_high() || self.take.is_high()
)]
pub struct LookaheadQueue {
    mode: Lookahead,
    /// Texture size in blocks, and fraction bits of `u`, `v`.
    blocks: (u32, u32),
    frac_bits: u32,
    #[input]
    pub complete: SignalOf<Bit>,
    #[input]
    pub u: Signal,
    #[input]
    pub v: Signal,
    #[input]
    pub newline: SignalOf<Bit>,
    #[input]
    pub flush: SignalOf<Bit>,
    #[input]
    pub engine_free: SignalOf<Bit>,
    #[input]
    pub stage0_missing: SignalOf<Bit>,
    #[output]
    pub take: SignalOf<Bit>,
    #[output]
    pub take_bx: Signal,
    #[output]
    pub take_by: Signal,
    /// Live slots, and the blocks in them.
    #[reg]
    pub mask: RegOf<Slots>,
    /// The previous completed point of this scanline (direction lookahead).
    #[reg]
    pub prev_valid: RegOf<Bit>,
    #[reg]
    pub prev_u: Reg,
    #[reg]
    pub prev_v: Reg,
    #[reg]
    bx: [Reg; 3],
    #[reg]
    by: [Reg; 3],
}

impl LookaheadQueue {
    /// A queue for a texture of `blocks` (width, height) blocks, coordinates of format `uq`
    /// (`uQ12.F`), block coordinates of `block_bits`.
    pub fn new(mode: Lookahead, blocks: (u32, u32), uq: Format, block_bits: u32) -> Self {
        let b = Format::uint(block_bits);
        LookaheadQueue {
            mode,
            blocks,
            frac_bits: uq.frac() as u32,
            complete: SignalOf::new("complete"),
            u: Signal::new("u", uq),
            v: Signal::new("v", uq),
            newline: SignalOf::new("newline"),
            flush: SignalOf::new("flush"),
            engine_free: SignalOf::new("engine_free"),
            stage0_missing: SignalOf::new("stage0_missing"),
            take: SignalOf::new("take"),
            take_bx: Signal::new("take_bx", b),
            take_by: Signal::new("take_by", b),
            mask: RegOf::new("mask"),
            bx: ["slot0_bx", "slot1_bx", "slot2_bx"].map(|n| Reg::new(n, b)),
            by: ["slot0_by", "slot1_by", "slot2_by"].map(|n| Reg::new(n, b)),
            prev_valid: RegOf::new("prev_valid"),
            prev_u: Reg::new("prev_u", uq),
            prev_v: Reg::new("prev_v", uq),
        }
    }

    /// Queued candidates (registered state): live slots and their blocks.
    pub fn queued(&self) -> (u64, [(u32, u32); 3]) {
        let q = [0, 1, 2].map(|k| (self.bx[k].q().bits() as u32, self.by[k].q().bits() as u32));
        (self.mask.q().bits(), q)
    }

    /// The neighbours of the completing request at `(u, v)` as the slots' next blocks (an
    /// empty slot's block 0, 0): none for the first point of a scanline; those of its
    /// quadrant, or those in the direction of motion from the previous point of the scanline.
    /// Returns the live slots. (Written into the registers as they are found: returned as an
    /// array of pairs, they were written a word at a time and copied out two words at once
    /// before the writes had landed, a stall in every lookahead.)
    fn candidates(&mut self, u: u64, v: u64, newline: bool) -> u64 {
        let f = self.frac_bits;
        let (x0, y0) = ((u >> f) as u32, (v >> f) as u32);
        let (bw, bh) = self.blocks;
        // The footprint's blocks (clamped at the edge, as stage 0 reads them).
        let (x1, y1) = ((x0 + 1).min(4 * bw - 1), (y0 + 1).min(4 * bh - 1));
        let foot = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)].map(|(x, y)| (x >> 2, y >> 2));
        let foot_entries = foot.map(|(bx, by)| entry_of(bx, by));
        let evicts = |b: (u32, u32)| {
            let e = entry_of(b.0, b.1);
            (0..4).any(|i| foot_entries[i] == e && foot[i] != b)
        };
        for k in 0..3 {
            self.bx[k].set_next_bits(0);
            self.by[k].set_next_bits(0);
        }
        let (bxs, bys, mut m) = (&mut self.bx, &mut self.by, 0);
        let mut put = |k: usize, (bx, by): (u32, u32)| {
            if !evicts((bx, by)) {
                bxs[k].set_next_bits(u64::from(bx));
                bys[k].set_next_bits(u64::from(by));
                m |= 1 << k;
            }
        };
        if newline {
            // No lookahead for the first point of a scanline.
        } else if self.mode == Lookahead::Quadrant {
            for (k, blk) in lookahead(x0, y0, bw, bh).enumerate() {
                put(k, blk);
            }
        } else if self.prev_valid.q().is_high() {
            let sign = |a: u64, b: u64| (a > b) as i32 - (a < b) as i32;
            let dx = sign(u, self.prev_u.q().bits());
            let dy = sign(v, self.prev_v.q().bits());
            for (k, blk) in lookahead_direction(x0 >> 2, y0 >> 2, dx, dy, bw, bh).enumerate() {
                put(k, blk);
            }
        }
        m
    }
}

impl LookaheadQueue {
    /// The queue's next contents and this cycle's take.
    #[inline]
    pub fn eval(&mut self) {
        let complete = self.complete.is_high();
        let (u, v) = (self.u.bits(), self.v.bits());
        // The registered slots are read only when taken: copying them into an array of pairs
        // made a store-forwarding stall (narrow stores, one wide load) a quarter of the
        // texture unit's cycle.
        let mut m = if complete {
            self.candidates(u, v, self.newline.is_high())
        } else {
            self.mask.q().bits()
        };
        if complete && self.mode == Lookahead::Direction {
            self.prev_valid.set_next_bool(true);
            self.prev_u.set_next_bits(u);
            self.prev_v.set_next_bits(v);
        }
        let mut take = None;
        if self.flush.is_high() {
            m = 0;
        } else if self.engine_free.is_high() && m != 0 && !self.stage0_missing.is_high() {
            let k = m.trailing_zeros() as usize;
            // A fresh candidate is taken from the slot's next value, as written this cycle.
            let (bx, by) = (&self.bx[k], &self.by[k]);
            take = Some(if complete {
                (bx.next_bits() as u32, by.next_bits() as u32)
            } else {
                (bx.q().bits() as u32, by.q().bits() as u32)
            });
            m &= !(1 << k);
        }
        self.mask.set_next_bits(m);
        self.take.set_bool(take.is_some());
        let (tx, ty) = take.unwrap_or((0, 0));
        self.take_bx.set_bits(u64::from(tx));
        self.take_by.set_bits(u64::from(ty));
    }
}
