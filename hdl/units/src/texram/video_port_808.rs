//! The video port 808 with the mipmap generation unit 816 and the shift registers 826
//! (sections 11-12): video texels enter the chip at the serial port, are written into the
//! banks as they arrive and, in parallel, go through the generator of Figure 14, whose upper
//! levels leave FIFO 1412 a line at a time; every line reaches its banks through the shift
//! registers 826 and the page registers 824, one row transfer per bank, in access slots taken
//! from the rasterizer.
//!
//! # The model (\[C\], the document gives the data path only)
//! * A line of level k goes to the two banks of its row parity (`banks_810::locate`), the
//!   even columns to one, the odd to the other: two **segments**, each split where it would
//!   cross a DRAM row. Level 0's texels are collected in the shift registers as they arrive
//!   (the line's two banks); a level's line comes from its FIFO 1412 when complete.
//! * A finished segment is **loaded in parallel into a row buffer** of the shift register
//!   unit (depth `queue`, default 32), so that the next line can be collected while it waits
//!   for its slot. The depth needed is set by the end of a frame, when a line of every level
//!   finishes within a few cycles: two segments a level and two of level 0, 24 for a
//!   1024 x 1024 frame (`max_buffered` records the most a run needed). A bank round takes
//!   the oldest waiting segment of every bank (each bank's in the order they came), in one
//!   slot, two if any of those banks has another row open (the page register then holds the written row, so the
//!   rasterizer's next access there faults). A segment finishing with every buffer full is an
//!   **overrun** (sticky error 1); so is a frame's line written while the frame two before,
//!   in the same map, is not ready (banks taken in their own orders, its last segments can
//!   still be waiting: the new frame would overwrite what was to be read).
//! * Interlaced video: before each line of the second field, the partner line of the first
//!   field (the other line of its pair) is read from the banks into the shift register, two
//!   read segments through the same buffers. A second-field texel arriving before its partner
//!   line is in is an **underrun** (sticky error 2): the video source must leave the line
//!   blanking the read needs.
//! * Frames go alternately to the maps of two DRFs (`drfs`), so that the rasterizer reads a
//!   complete mipmap while the next is generated; a frame is **ready** when its last segment is
//!   in the banks (`frames_ready`).
//! * The port has priority over the rasterizer (video cannot wait): a waiting segment takes
//!   the banks at the first slot boundary. Counters: `transfers` (segments), `slots`.
//! * Two-process, as a memory is: `eval` stages the segments the coming edge buffers (and the
//!   overrun checks them against the buffers as that edge leaves them); the edge completes
//!   the round under way (its bank writes, its partner-line reads), then appends them.

use std::collections::VecDeque;

use super::banks_810::{locate, BANKS, ROW_WORDS};
use super::{Config, Drf, DRFS};
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::mipmap::mipmap_gen_816::{MipmapGen, MipmapParams};
use crate::signals;

/// What the video port is set up for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VideoParams {
    /// The frames' size, scan order and the generator's rounding.
    pub mipmap: MipmapParams,
    /// The DRFs of the maps that even and odd frames are written to.
    pub drfs: [usize; 2],
    /// Row buffers of the shift register unit 826.
    pub queue: usize,
}

impl VideoParams {
    /// Frames of `mipmap` into DRFs 0 (even frames) and 1 (odd), 32 row buffers.
    pub fn new(mipmap: MipmapParams) -> VideoParams {
        VideoParams {
            mipmap,
            drfs: [0, 1],
            queue: 32,
        }
    }

    /// The generator's parameters, the DRF numbers, the buffer count, and (given the chip's
    /// DRFs) that both maps are set, luminance, and of the frame's size.
    pub fn validate(&self, drfs: &[Option<Drf>; DRFS]) -> Result<(), String> {
        self.mipmap.validate()?;
        if !(1..=64).contains(&self.queue) {
            return Err(format!("queue {}: 1..=64 row buffers", self.queue));
        }
        if self.drfs[0] == self.drfs[1] {
            return Err(format!("drfs: one map ({}) for both frames", self.drfs[0]));
        }
        for k in self.drfs {
            let d = drfs
                .get(k)
                .ok_or_else(|| format!("drf {k}: 0..{DRFS}"))?
                .ok_or_else(|| format!("drf {k}: not set"))?;
            let size = d.level_size(0);
            if size != (self.mipmap.width, self.mipmap.height) {
                return Err(format!(
                    "drf {k}: a {}x{} map for {}x{} video",
                    size.0, size.1, self.mipmap.width, self.mipmap.height
                ));
            }
            if d.config != Config::Luminance {
                return Err(format!("drf {k}: video maps are luminance"));
            }
        }
        Ok(())
    }
}

/// One row transfer between a bank and the shift registers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Segment {
    pub bank: usize,
    /// First bank word; the segment's words are consecutive and in one row.
    pub word: u32,
    /// The texels to write, or `None` for a read of `len` words of the partner line from
    /// column `x0` on (every other column).
    pub data: Option<Vec<u8>>,
    pub len: u32,
    x0: u32,
    /// Its place in the order segments were buffered.
    seq: u64,
}

/// The video port 808, the generator 816 and the shift registers 826 of one chip.
#[derive(Clone, Debug)]
pub struct VideoPort808 {
    p: VideoParams,
    pub valid: Signal,
    pub texel: Signal,
    pub sof: Signal,
    pub gen: MipmapGen,
    /// Level 0's line being collected: even and odd columns.
    collect: [Vec<u8>; 2],
    buffers: VecDeque<Segment>,
    /// The partner line being read, and its segments still to come.
    partner: Vec<u8>,
    partner_left: u32,
    /// Rows buffered, transfers and slots so far, the error flag and code.
    pub occupancy: Reg,
    pub transfers: Reg,
    pub slots: Reg,
    pub error: Reg,
    pub err_code: Reg,
    /// Segments buffered so far; those of the bank round under way; those of the round the
    /// chip starts at the coming edge; whether the one under way finishes then.
    seq: u64,
    in_round: Vec<u64>,
    next_round: Vec<u64>,
    finishing: bool,
    /// Frames whose last segment is buffered, waiting for all segments up to it.
    pending_frames: VecDeque<(u64, u64)>,
    /// Frames whose mipmap is in the banks, with the cycle.
    pub frames_ready: Vec<(u64, u64)>,
    /// The most row buffers in use at once.
    pub max_buffered: usize,
    cycle: u64,
    /// What this cycle's `eval` decided the coming edge buffers.
    staged: Staged,
}

/// What the coming edge buffers, decided in `eval` from the generator's outputs: the new
/// segments (numbered on from the last), frames whose last segment they hold, how many are
/// partner-line reads, and level 0's texel into shift register 826.
#[derive(Clone, Debug, Default)]
struct Staged {
    segments: Vec<Segment>,
    frames: Vec<(u64, u64)>,
    partner: u32,
    texel: Option<(u32, u8)>,
}

impl VideoPort808 {
    pub fn new(p: VideoParams, drfs: &[Option<Drf>; DRFS]) -> Result<VideoPort808, String> {
        p.validate(drfs)?;
        let gen = MipmapGen::new("mipmap_gen_816", p.mipmap)?.on_banks();
        let w = p.mipmap.width as usize;
        Ok(VideoPort808 {
            p,
            valid: Signal::bit("vid_valid"),
            texel: Signal::new("vid_texel", Format::uint(8)),
            sof: Signal::bit("vid_sof"),
            gen,
            collect: [vec![0; w.div_ceil(2)], vec![0; w / 2]],
            buffers: VecDeque::with_capacity(p.queue + 4),
            partner: vec![0; w],
            partner_left: 0,
            occupancy: Reg::new("buffered", Format::uint(7)),
            transfers: Reg::new("transfers", Format::uint(40)),
            slots: Reg::new("video_slots", Format::uint(40)),
            error: Reg::new("error", Format::uint(1)),
            err_code: Reg::new("err_code", Format::uint(2)),
            seq: 0,
            in_round: Vec::with_capacity(BANKS),
            next_round: Vec::with_capacity(BANKS),
            finishing: false,
            pending_frames: VecDeque::new(),
            frames_ready: Vec::new(),
            max_buffered: 0,
            cycle: 0,
            staged: Staged::default(),
        })
    }

    pub fn params(&self) -> &VideoParams {
        &self.p
    }

    /// The segments of the next bank round: for every bank its oldest waiting segment (not
    /// in the round under way, which finishes before this one starts).
    pub fn round(&self) -> [Option<&Segment>; BANKS] {
        let mut pick = [None; BANKS];
        for s in &self.buffers {
            if pick[s.bank].is_none() && !self.in_round.contains(&s.seq) {
                pick[s.bank] = Some(s);
            }
        }
        pick
    }

    /// The chip starts the round [`VideoPort808::round`] gave, taking `slots` slots; it
    /// finishes at the edge the chip says with `eval(true)`.
    pub fn start(&mut self, slots: u64) {
        let pick = self.round().map(|s| s.map(|s| s.seq));
        self.next_round.clear();
        self.next_round.extend(pick.into_iter().flatten());
        let n = self.next_round.len() as u64;
        self.transfers.set_next_bits(self.transfers.q().bits() + n);
        self.slots.set_next_bits(self.slots.q().bits() + slots);
    }

    /// The generator and the port for this cycle: video in, the underrun check, the lines
    /// the coming edge buffers (against the chip's `drfs`); the round under way finishes at
    /// the coming edge when `finishing`.
    pub fn eval(&mut self, finishing: bool, drfs: &[Option<Drf>; DRFS]) {
        self.finishing = finishing;
        self.next_round.clear();
        self.gen.valid.follow(&self.valid);
        self.gen.texel.follow(&self.texel);
        self.gen.sof.follow(&self.sof);
        self.gen.eval();
        if self.gen.reads_partner() && self.partner_left > 0 {
            self.flag(2);
        }
        self.occupancy.set_next_bits(self.buffers.len() as u64);
        self.stage_lines(drfs);
    }

    fn flag(&mut self, code: u64) {
        if self.error.next_bits() == 0 {
            self.error.set_next_bool(true);
            self.err_code.set_next_bits(code);
        }
    }

    /// The edge: the served segments leave (written into `banks`, or read into the partner
    /// line), then the segments `eval` staged are buffered.
    pub fn tick(&mut self, reset: bool, banks: &mut [Vec<u8>]) {
        self.cycle += 1;
        if reset {
            self.staged = Staged::default();
            self.buffers.clear();
            self.partner_left = 0;
            self.in_round.clear();
            self.pending_frames.clear();
            // Frame numbers start again at 0: the record of ready frames with them.
            self.frames_ready.clear();
        } else {
            if self.finishing {
                self.complete(banks);
            }
            if !self.next_round.is_empty() {
                std::mem::swap(&mut self.in_round, &mut self.next_round);
            }
            self.commit_lines();
        }
        for r in [
            &mut self.occupancy,
            &mut self.transfers,
            &mut self.slots,
            &mut self.error,
            &mut self.err_code,
        ] {
            r.tick(reset);
        }
        self.gen.tick(reset);
    }

    /// The round under way done: its writes into the banks, its reads into the partner line;
    /// the frames all of whose segments are done are ready.
    fn complete(&mut self, banks: &mut [Vec<u8>]) {
        let done = std::mem::take(&mut self.in_round);
        for &seq in &done {
            let Some(at) = self.buffers.iter().position(|s| s.seq == seq) else {
                continue;
            };
            let s = self.buffers.remove(at).expect("found");
            let bank = &mut banks[s.bank][s.word as usize..(s.word + s.len) as usize];
            match s.data {
                Some(d) => bank.copy_from_slice(&d),
                None => {
                    for (i, t) in bank.iter().enumerate() {
                        self.partner[(s.x0 + 2 * i as u32) as usize] = *t;
                    }
                    self.partner_left -= 1;
                    if self.partner_left == 0 {
                        self.gen.load_partner(&self.partner);
                    }
                }
            }
        }
        // The round's list, emptied, for the next round (no allocation a round).
        self.in_round = done;
        self.in_round.clear();
        let oldest = self.buffers.front().map_or(u64::MAX, |s| s.seq);
        while let Some(&(f, last)) = self.pending_frames.front() {
            if last >= oldest {
                break;
            }
            self.frames_ready.push((f, self.cycle));
            self.pending_frames.pop_front();
        }
    }

    /// The row buffers held, and the frames ready, after the coming edge's completion: what
    /// the lines buffered at that edge are checked against.
    fn after_edge(&self) -> (usize, usize) {
        if !self.finishing {
            return (self.buffers.len(), self.frames_ready.len());
        }
        let done = &self.in_round;
        let mut left = self.buffers.iter().filter(|s| !done.contains(&s.seq));
        let oldest = left.clone().next().map_or(u64::MAX, |s| s.seq);
        let ready = self
            .pending_frames
            .iter()
            .take_while(|&&(_, last)| last < oldest)
            .count();
        (left.by_ref().count(), self.frames_ready.len() + ready)
    }

    /// The generator's writes and reads of the coming edge, as row-buffer segments staged
    /// for the edge (the overrun checks against the buffers as the edge leaves them).
    fn stage_lines(&mut self, drfs: &[Option<Drf>; DRFS]) {
        self.staged.segments.clear();
        self.staged.frames.clear();
        self.staged.partner = 0;
        self.staged.texel = None;
        let (held, ready) = self.after_edge();
        let which = self.p.drfs;
        let drf = |f: u64| drfs[which[(f % 2) as usize]].expect("video DRFs are checked");
        let levels = self.gen.dims().len() as u32;
        if let Some((f, x, y, t)) = self.gen.level0_write() {
            self.staged.texel = Some((x, t));
            if x + 1 == self.p.mipmap.width {
                let mut line = self.collect.clone();
                line[(x & 1) as usize][(x >> 1) as usize] = t;
                // A map of one level is 1 x 1: its one line completes the frame.
                let last = (levels == 1).then_some(f);
                // Frame f goes into frame f - 2's map: that one must be ready by now.
                if f >= ready as u64 + 2 {
                    self.flag(1);
                }
                self.push_line(held, &drf(f), 0, y, Some(line), last);
            }
        }
        if let Some((f, row)) = self.gen.partner_read() {
            self.staged.partner += self.push_line(held, &drf(f), 0, row, None, None);
        }
        let lines: Vec<_> = self.gen.line_writes().collect();
        for (k, f, row, texels) in lines {
            let halves = [0, 1].map(|p| texels.iter().skip(p).step_by(2).copied().collect());
            let last = (k + 1 == levels).then_some(f);
            self.push_line(held, &drf(f), k, row, Some(halves), last);
        }
    }

    /// Line `y` of level `k` (its even and odd columns, or a read) staged into row buffers,
    /// one segment per bank and row, beside the `held` ones; the last segment carries `last`.
    /// Returns the segments.
    fn push_line(
        &mut self,
        held: usize,
        d: &Drf,
        k: u32,
        y: u32,
        data: Option<[Vec<u8>; 2]>,
        last: Option<u64>,
    ) -> u32 {
        let (w, _) = d.level_size(k);
        let staged = &mut self.staged.segments;
        let mut n = 0;
        for x0 in 0..w.min(2) {
            let (bank, first) = locate(d, k, x0, y);
            let len = (w - x0).div_ceil(2);
            let mut done = 0;
            while done < len {
                let word = first + done;
                let take = (len - done).min(ROW_WORDS - word % ROW_WORDS);
                let part = data
                    .as_ref()
                    .map(|h| h[x0 as usize][done as usize..(done + take) as usize].to_vec());
                let seq = self.seq + staged.len() as u64;
                staged.push(Segment {
                    bank,
                    word,
                    data: part,
                    len: take,
                    x0: x0 + 2 * done,
                    seq,
                });
                done += take;
                n += 1;
            }
        }
        let count = staged.len();
        if let Some(f) = last {
            self.staged.frames.push((f, self.seq + count as u64 - 1));
        }
        if held + count > self.p.queue {
            self.flag(1);
        }
        n
    }

    /// The staged segments into the row buffers (after the edge's completion), level 0's
    /// texel into the shift register.
    fn commit_lines(&mut self) {
        if let Some((x, t)) = self.staged.texel.take() {
            self.collect[(x & 1) as usize][(x >> 1) as usize] = t;
        }
        self.seq += self.staged.segments.len() as u64;
        self.buffers.extend(self.staged.segments.drain(..));
        self.pending_frames.extend(self.staged.frames.drain(..));
        self.partner_left += self.staged.partner;
        self.staged.partner = 0;
        self.max_buffered = self.max_buffered.max(self.buffers.len());
    }

    pub fn visit(&self, v: &mut dyn Visitor) {
        v.enter("video_port_808", "video_port_808");
        signals!(v;
            Input: self.valid, self.texel, self.sof);
        self.gen.visit(v);
        v.enter("shift_registers_826", "shift_registers_826");
        signals!(v; Reg: self.occupancy, self.transfers, self.slots, self.error, self.err_code);
        v.leave();
        v.leave();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mipmap::mipmap_gen_816::{Rounding, Scan};
    use crate::texram::texram_802::{Texram802, TexramParams};
    use crate::texram::Border;

    fn params(w: u32, h: u32) -> VideoParams {
        VideoParams::new(MipmapParams {
            width: w,
            height: h,
            scan: Scan::InterlacedTop,
            rounding: Rounding::Round,
        })
    }

    fn drfs() -> [Option<Drf>; DRFS] {
        let mut d = [None; DRFS];
        let mut second = Drf::new(5, 4, Border::Wrap);
        second.base_even = 4096;
        second.base_odd = 4096;
        d[0] = Some(Drf::new(5, 4, Border::Wrap));
        d[1] = Some(second);
        d
    }

    #[test]
    fn the_parameters_are_checked_against_the_drfs() {
        let d = drfs();
        assert_eq!(params(32, 16).validate(&d), Ok(()));
        let err = |p: VideoParams, d: &[Option<Drf>; DRFS]| p.validate(d).unwrap_err();
        assert!(err(params(32, 8), &d).contains("a 32x16 map for 32x8 video"));
        assert!(err(params(24, 16), &d).contains("width 24"));
        let mut p = params(32, 16);
        p.queue = 0;
        assert!(err(p, &d).contains("queue 0"));
        p.queue = 65;
        assert!(err(p, &d).contains("queue 65"));
        p.queue = 64;
        assert_eq!(p.validate(&d), Ok(()));
        let mut p = params(32, 16);
        p.drfs = [1, 1];
        assert!(err(p, &d).contains("one map (1) for both"));
        p.drfs = [0, 2];
        assert!(err(p, &d).contains("drf 2: not set"));
        p.drfs = [0, 7];
        assert!(err(p, &d).contains("drf 7: 0..7"));
        let mut colour = d;
        colour[1] = colour[1].map(|mut x| {
            x.config = Config::Index;
            x
        });
        assert!(err(params(32, 16), &colour).contains("drf 1: video maps are luminance"));
    }

    #[test]
    fn a_video_map_keeps_its_size_while_the_port_is_set_up() {
        let mut chip = Texram802::new(TexramParams::default()).unwrap();
        let d = drfs();
        chip.set_drf(0, d[0].unwrap()).unwrap();
        assert!(chip.attach_video(params(32, 16)).is_err(), "drf 1 not set");
        chip.set_drf(1, d[1].unwrap()).unwrap();
        chip.attach_video(params(32, 16)).unwrap();
        let e = chip.set_drf(1, Drf::new(4, 4, Border::Wrap)).unwrap_err();
        assert!(e.contains("drf 1: a 16x16 map for 32x16 video"), "{e}");
        // Refused, so the DRF is unchanged: still a 32 x 16 map.
        assert_eq!(chip.read_level(1, 0).unwrap().len(), 32 * 16);
        chip.set_drf(1, d[1].unwrap()).unwrap();
        chip.set_drf(2, Drf::new(4, 4, Border::Wrap)).unwrap();
        assert!(chip.video_mut().is_some());
    }
}
