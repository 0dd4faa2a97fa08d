//! Real-time mipmap generation for (interlaced) video, section 12 and Figures 14a-b of
//! Schilling & Knittel (TEXRAM), fed by a video port at one texel per clock.
//!
//! * **Level 1, progressive** (Figure 14a): adder 1402 adds horizontal neighbours, the even
//!   column held one cycle in register 1404; on even lines the sums go into FIFO 1408, a line
//!   buffer; on odd lines they bypass it and adder 1410 adds them to FIFO 1408's output.
//! * **Level 1, interlaced**: the first field is only written to the frame store. For each
//!   line of the second field, the partner line of the first field (the other line of the same
//!   pair 2k, 2k+1) is read through its bank's page register into shift register 826; adder
//!   1402 adds vertical neighbours of the same column, FIFO 1408 acts as a single-entry
//!   register for the even column and adder 1410 adds the odd one. Both field orders; since
//!   additions commute, the scan order cannot change a bit.
//! * **Higher levels** (Figure 14b): the same progressive circuit on the previous level's
//!   texel stream, each level's FIFOs half as deep as the one before (FIFO 1408 holds half a
//!   line of the level it reads). Each level's results also go into FIFO 1412, whose full line
//!   is transferred to the shift register and written into the frame store after each line.
//! * Entries of level k are computed as soon as the entries of level k-1 they need exist.
//!
//! Division: a sum of four `(a+b+c+d+2) >> 2` (round half up, default) or `>> 2` (truncate);
//! once one side has reached 1, pairs along the other side `(a+b+1) >> 1` or `>> 1`.
//!
//! Frame store: two frame buffers used alternately (so frame f's upper levels finish while
//! frame f+1 arrives); in each, bank 0 holds even lines of level 0, bank 1 odd lines (so the
//! line read for the shift register and the line being written are always in different
//! banks), bank 2 the upper levels. Each bank has one page register (the open row), counted.
//!
//! # Formats
//! Texels `u8`; adder 1402 `u9`; adder 1410 `u10`; FIFO 1408 entries `u9` (`u8` when only
//! vertical pairs are left); FIFO 1412 entries `u8`. One register stage per level: level k's
//! texel appears k cycles after the level-0 texel that completes it.
//!
//! Errors (sticky `error`, `err_code`): 1 FIFO overflow, 2 FIFO underflow, 3 video sync
//! (`sof` high other than with a frame's first texel, or low with it).

use crate::fx::{Bit, Format};
use crate::kernel::declared::Regs;
use crate::kernel::{Module, RegOf, SignalOf, Visitor};
use crate::mipmap::fifo::ErrCode;
pub use crate::mipmap::level_fig14::Rounding;
use crate::mipmap::level_fig14::{Coord, FrameNo, Level, Texel};
use crate::pages::page_registers_824::PageRegisters824;

hdl::formats! {
    /// Row activations of a frame-store bank, counted.
    pub Activations = Format::uint(40);
}

/// Arrival order of a frame's lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scan {
    Progressive,
    /// Field of even lines (0, 2, ...) first.
    InterlacedTop,
    /// Field of odd lines (1, 3, ...) first.
    InterlacedBottom,
}

parse_names!(Scan, "progressive" => Scan::Progressive, "interlaced-top" => Scan::InterlacedTop, "interlaced-bottom" => Scan::InterlacedBottom);

/// Frame size, scan order, rounding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MipmapParams {
    pub width: u32,
    pub height: u32,
    pub scan: Scan,
    pub rounding: Rounding,
}

impl MipmapParams {
    pub const MAX_SIDE: u32 = 1024;

    /// Sides must be powers of two up to 1024; interlaced video needs at least two lines.
    pub fn validate(&self) -> Result<(), String> {
        for (n, v) in [("width", self.width), ("height", self.height)] {
            if !v.is_power_of_two() || v > Self::MAX_SIDE {
                return Err(format!(
                    "{n} {v} is not a power of two in 1..={}",
                    Self::MAX_SIDE
                ));
            }
        }
        if self.scan != Scan::Progressive && self.height < 2 {
            return Err("interlaced video needs at least 2 lines".into());
        }
        Ok(())
    }

    /// `(width, height)` of every level, level 0 first, down to 1x1.
    pub fn levels(&self) -> Vec<(u32, u32)> {
        let (mut w, mut h) = (self.width, self.height);
        let mut v = vec![(w, h)];
        while w > 1 || h > 1 {
            w = (w / 2).max(1);
            h = (h / 2).max(1);
            v.push((w, h));
        }
        v
    }
}

/// One frame buffer: every level's texels, row-major.
pub type FrameBuffer = Vec<Vec<u8>>;

/// The frame store (two frame buffers, used by frame parity) and shift register 826, which
/// reads it. The writes and the line read `eval` decides are made at the edge, as registers'
/// next values are: the levels' lines, then the video texel, then the partner line into the
/// shift register (which may be the line that texel completes).
#[derive(Clone, Debug)]
pub struct FrameStore {
    width: u32,
    dims: Vec<(u32, u32)>,
    /// Empty on the TEXRAM banks, whose owner takes the writes and serves the partner line.
    buffers: [FrameBuffer; 2],
    /// Shift register 826 (interlaced: the partner line of the line arriving).
    sr: Vec<u8>,
    /// At the coming edge: the video texel, `(frame, x, y, texel)`.
    texel: Option<(u64, u32, u32, u8)>,
    /// At the coming edge: the level-0 line `(frame, row)` read into shift register 826.
    partner: Option<(u64, u32)>,
    /// At the coming edge, bit `k` for level `k + 1`: its FIFO 1412 writes the line `(frame,
    /// row)` at index `k` of `lines`, with the texels at index `k` of `line_texels`.
    staged: u32,
    lines: Vec<(u64, u32)>,
    line_texels: Vec<Vec<u8>>,
}

impl FrameStore {
    fn new(dims: &[(u32, u32)], own: bool) -> FrameStore {
        let buf: FrameBuffer = dims
            .iter()
            .map(|&(w, h)| vec![0u8; (w * h) as usize])
            .collect();
        let upper = &dims[1..];
        FrameStore {
            width: dims[0].0,
            dims: dims.to_vec(),
            buffers: if own {
                [buf.clone(), buf]
            } else {
                Default::default()
            },
            sr: vec![0; dims[0].0 as usize],
            texel: None,
            partner: None,
            staged: 0,
            lines: vec![(0, 0); upper.len()],
            line_texels: upper
                .iter()
                .map(|&(w, _)| Vec::with_capacity(w as usize))
                .collect(),
        }
    }

    fn own(&self) -> bool {
        !self.buffers[0].is_empty()
    }

    fn clear_staged(&mut self) {
        self.texel = None;
        self.partner = None;
        self.staged = 0;
    }

    /// Level `k + 1`'s FIFO 1412 line goes to the frame store at the coming edge.
    fn stage_line(&mut self, k: usize, at: (u64, u32), texels: impl Iterator<Item = u16>) {
        self.staged |= 1 << k;
        self.lines[k] = at;
        let t = &mut self.line_texels[k];
        t.clear();
        t.extend(texels.map(|v| v as u8));
    }

    /// The lines staged at the coming edge, level `k + 1`'s at `k`, lowest level first.
    fn staged_lines(&self) -> impl Iterator<Item = (usize, (u64, u32), &[u8])> + '_ {
        let mut bits = self.staged;
        std::iter::from_fn(move || {
            let k = bits.trailing_zeros() as usize;
            bits &= bits.wrapping_sub(1);
            (k < 32).then(|| (k, self.lines[k], &self.line_texels[k][..]))
        })
    }

    fn write_lines(&mut self) {
        let mut bits = self.staged;
        while bits != 0 {
            let k = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let ((frame, row), texels) = (self.lines[k], &self.line_texels[k]);
            let lw = self.dims[k + 1].0 as usize;
            let row = row as usize;
            let dst = &mut self.buffers[(frame % 2) as usize][k + 1][row * lw..(row + 1) * lw];
            dst.copy_from_slice(texels);
        }
    }
}

impl Regs for FrameStore {
    #[inline]
    fn tick_regs(&mut self, reset: bool) {
        if !reset && self.own() {
            if self.staged != 0 {
                self.write_lines();
            }
            let w = self.width as usize;
            if let Some((frame, x, y, t)) = self.texel {
                self.buffers[(frame % 2) as usize][0][y as usize * w + x as usize] = t;
            }
            if let Some((frame, row)) = self.partner {
                let row = row as usize;
                let b = &self.buffers[(frame % 2) as usize][0];
                self.sr.copy_from_slice(&b[row * w..(row + 1) * w]);
            }
        }
        self.clear_staged();
    }
    fn visit_regs(&self, _: &mut dyn Visitor) {}
}

/// The frames whose mipmap is complete, in order, each with the cycle of its edge; the one
/// `eval` completes is recorded at the edge. Reset starts the record again (frame numbers
/// start again at 0).
#[derive(Clone, Debug, Default)]
pub struct Completed {
    frames: Vec<(u64, u64)>,
    cycle: u64,
    next: Option<u64>,
}

impl Regs for Completed {
    #[inline]
    fn tick_regs(&mut self, reset: bool) {
        self.cycle += 1;
        let next = self.next.take();
        if reset {
            self.frames.clear();
        } else if let Some(f) = next {
            self.frames.push((f, self.cycle));
        }
    }
    fn visit_regs(&self, _: &mut dyn Visitor) {}
}

/// The mipmap generation unit 816 with its frame store.
#[derive(Clone, Debug, Module)]
#[module(kind = "mipmap_gen_816")]
pub struct MipmapGen {
    #[instance]
    name: String,
    p: MipmapParams,
    dims: Vec<(u32, u32)>,
    #[input]
    pub valid: SignalOf<Bit>,
    #[input]
    pub texel: SignalOf<Texel>,
    #[input]
    pub sof: SignalOf<Bit>,
    #[output]
    pub error: SignalOf<Bit>,
    #[output]
    pub err_code: SignalOf<ErrCode>,
    #[output]
    pub frame_done: SignalOf<Bit>,
    /// Level-0 arrival counters: x, line within the field, field; the frame arriving.
    #[reg]
    x: RegOf<Coord>,
    #[reg]
    line: RegOf<Coord>,
    #[reg]
    field: RegOf<Bit>,
    #[reg]
    frame0: RegOf<FrameNo>,
    /// Sticky error and its code.
    #[reg]
    err: RegOf<Bit>,
    #[reg]
    code: RegOf<ErrCode>,
    /// A frame's mipmap was completed at the last edge.
    #[reg]
    done: RegOf<Bit>,
    /// Row activations of the own frame store's banks 0, 1 and 2.
    #[reg]
    activations: [RegOf<Activations>; 3],
    /// The page registers 824 of the own frame store's three banks (none on the TEXRAM's,
    /// whose own count).
    #[child]
    pages: Option<PageRegisters824>,
    /// Levels 1.. of Figure 14.
    #[child]
    pub levels: Vec<Level>,
    #[reg]
    store: FrameStore,
    #[reg]
    completed: Completed,
}

impl MipmapGen {
    pub fn new(name: &str, p: MipmapParams) -> Result<MipmapGen, String> {
        p.validate()?;
        let dims = p.levels();
        let interlaced = p.scan != Scan::Progressive;
        let levels = (1..dims.len())
            .map(|k| Level::new(k, dims[k - 1], p.rounding, interlaced && k == 1))
            .collect::<Result<_, _>>()?;
        Ok(MipmapGen {
            name: name.into(),
            p,
            valid: SignalOf::new("valid"),
            texel: SignalOf::new("texel"),
            sof: SignalOf::new("sof"),
            error: SignalOf::new("error"),
            err_code: SignalOf::new("err_code"),
            frame_done: SignalOf::new("frame_done"),
            x: RegOf::new("x0"),
            line: RegOf::new("line0"),
            field: RegOf::new("field"),
            frame0: RegOf::new("frame"),
            err: RegOf::new("error_r"),
            code: RegOf::new("err_code_r"),
            done: RegOf::new("frame_done_r"),
            activations: ["activations0", "activations1", "activations2"].map(RegOf::new),
            pages: Some(PageRegisters824::new(3, 16)),
            levels,
            store: FrameStore::new(&dims, true),
            completed: Completed::default(),
            dims,
        })
    }

    /// The unit on the TEXRAM chip's banks: no frame store of its own. Its owner
    /// writes what [`MipmapGen::level0_write`] and [`MipmapGen::line_writes`] give at each
    /// edge, reads the line [`MipmapGen::partner_read`] names and hands it back through
    /// [`MipmapGen::load_partner`] before the line that needs it arrives.
    /// `completed` and `frame_done` then say that a frame's last line left FIFO 1412, not
    /// that it is in the banks (the owner knows when it is).
    pub fn on_banks(mut self) -> MipmapGen {
        self.pages = None;
        self.store = FrameStore::new(&self.dims, false);
        self
    }

    /// At the coming edge: the video texel written into level 0, as `(frame, x, y, texel)`.
    pub fn level0_write(&self) -> Option<(u64, u32, u32, u8)> {
        self.store.texel
    }

    /// At the coming edge: the level-0 line of the current frame to load into shift register
    /// 826 for the next line of the second field (interlaced video only).
    pub fn partner_read(&self) -> Option<(u64, u32)> {
        self.store.partner
    }

    /// At the coming edge: each level whose FIFO 1412 line goes to the frame store, as
    /// `(level, frame, row, texels)`.
    pub fn line_writes(&self) -> impl Iterator<Item = (u32, u64, u32, Vec<u8>)> + '_ {
        let lines = self.store.staged_lines();
        lines.map(|(k, (f, row), t)| (k as u32 + 1, f, row, t.to_vec()))
    }

    /// Shift register 826 loaded with the partner line (the unit on the TEXRAM banks).
    pub fn load_partner(&mut self, line: &[u8]) {
        self.store.sr.copy_from_slice(line);
    }

    /// This cycle the video texel is added to the shift register's (interlaced level 1 in the
    /// second field): the partner line must be there.
    pub fn reads_partner(&self) -> bool {
        self.p.scan != Scan::Progressive && self.valid.is_high() && self.field.q().is_high()
    }

    /// The row bank `bank` of the own frame store has open (at the last edge).
    pub fn open_row(&self, bank: usize) -> Option<u64> {
        self.pages.as_ref()?.open_row(bank)
    }

    /// Row activations of the own frame store's banks 0, 1, 2 since reset.
    pub fn activations(&self) -> [u64; 3] {
        self.activations.each_ref().map(|r| r.q().bits())
    }

    /// Frames whose mipmap is complete, in order, each with the cycle of its edge.
    pub fn completed(&self) -> &[(u64, u64)] {
        &self.completed.frames
    }

    /// The own frame store's buffer frame `frame` is written into (by frame parity).
    pub fn frame_buffer(&self, frame: u64) -> &FrameBuffer {
        &self.store.buffers[(frame % 2) as usize]
    }

    pub fn params(&self) -> &MipmapParams {
        &self.p
    }
    pub fn dims(&self) -> &[(u32, u32)] {
        &self.dims
    }

    /// The frame line arriving as line `n` of field `f`.
    fn frame_line(&self, f: u32, n: u32) -> u32 {
        match self.p.scan {
            Scan::Progressive => n,
            Scan::InterlacedTop => 2 * n + f,
            Scan::InterlacedBottom => 2 * n + (1 - f),
        }
    }

    fn lines_per_field(&self) -> u32 {
        match self.p.scan {
            Scan::Progressive => self.p.height,
            _ => self.p.height / 2,
        }
    }

    /// The video port: the texel stored into level 0, the sync check, the next arrival
    /// position and, at a line end into the second field, the partner line for shift register
    /// 826. Returns the sync error code and the frame the texel completes, if any.
    fn arrive(&mut self, x: u32, n: u32, f: u32) -> (u64, Option<u64>) {
        let frame = self.frame0.q().bits();
        let first = x == 0 && n == 0 && f == 0;
        let code = if self.sof.is_high() != first { 3 } else { 0 };
        let y = self.frame_line(f, n);
        self.store.texel = Some((frame, x, y, self.texel.bits() as u8));
        let interlaced = self.p.scan != Scan::Progressive;
        let (mut nx, mut nn, mut nf) = (x + 1, n, f);
        if nx == self.p.width {
            nx = 0;
            nn += 1;
            if nn == self.lines_per_field() {
                nn = 0;
                nf += 1;
                if nf == 1 + u32::from(interlaced) {
                    nf = 0;
                }
            }
            if interlaced && nf == 1 {
                self.store.partner = Some((frame, self.frame_line(nf, nn) ^ 1));
            }
        }
        self.x.set_next_bits(u64::from(nx));
        self.line.set_next_bits(u64::from(nn));
        self.field.set_next_bits(u64::from(nf));
        // The frame's last texel: the position starts again.
        let last = (nx, nn, nf) == (0, 0, 0);
        if last {
            self.frame0.set_next_bits(frame + 1);
        }
        // A 1x1 frame is its own mipmap.
        (code, (last && self.dims.len() == 1).then_some(frame))
    }

    /// Levels 1.. of Figure 14: level 1 reads the video port (and, interlaced, the shift
    /// register in the second field), each next level the one before. Each level's FIFO 1412
    /// line is staged for the frame store; returns the frame the last level's line completes.
    fn eval_levels(&mut self, x: u32, second_field: bool) -> Option<u64> {
        let valid = self.valid.is_high();
        let l1 = self.levels.first_mut()?;
        l1.in_valid.set_bool(valid && second_field);
        l1.in_texel.follow(&self.texel);
        if let Some(sr) = &mut l1.sr_texel {
            sr.set_bits(u64::from(self.store.sr[x as usize]));
        }
        l1.eval();
        let mut completes = self.stage_line(0);
        // An idle level with nothing arriving is not evaluated (most cycles, for the upper
        // levels): it has no line to write.
        for k in 1..self.levels.len() {
            let (a, b) = self.levels.split_at_mut(k);
            let (prev, l) = (&a[k - 1], &mut b[0]);
            if !prev.out_valid.is_high() && l.quiescent() {
                continue;
            }
            l.in_valid.follow(&prev.out_valid);
            l.in_texel.follow(&prev.out_texel);
            l.eval();
            completes = self.stage_line(k).or(completes);
        }
        completes
    }

    /// Level `k + 1`'s FIFO 1412 line, if it goes to the frame store at the coming edge, staged
    /// there; returns the frame it completes (the last level's line).
    #[inline(always)]
    fn stage_line(&mut self, k: usize) -> Option<u64> {
        let at = self.levels[k].line_write()?;
        self.stage_line_at(k, at)
    }

    /// [`MipmapGen::stage_line`] for a line that goes out (one cycle in a line's width).
    #[inline(never)]
    fn stage_line_at(&mut self, k: usize, at: (u64, u32)) -> Option<u64> {
        let l = &self.levels[k];
        self.store.stage_line(k, at, l.fifo_1412.iter());
        (k + 2 == self.dims.len()).then_some(at.0)
    }

    /// The bank accesses of this cycle on the own frame store, in the order the edge makes
    /// them (level-0 store, the shift register's line, the levels' lines), through the page
    /// registers: the activations they count (a row not already open).
    fn page_registers(&mut self) {
        let Some(pages) = &mut self.pages else {
            return;
        };
        pages.eval();
        let mut acts = [0u64; 3];
        let mut open = |bank: usize, row: u32| {
            acts[bank] += u64::from(pages.open(bank, u64::from(row)));
        };
        let s = &self.store;
        if let Some((_, _, y, _)) = s.texel {
            open((y % 2) as usize, y / 2);
        }
        if let Some((_, row)) = s.partner {
            open((row % 2) as usize, row / 2);
        }
        for (k, (_, row), _) in s.staged_lines() {
            open(2, (k as u32) << 10 | row);
        }
        for (r, n) in self.activations.iter_mut().zip(acts) {
            if n != 0 {
                r.set_next_bits(r.q().bits() + n);
            }
        }
    }

    pub fn eval(&mut self) {
        self.error.follow(self.err.q());
        self.err_code.follow(self.code.q());
        self.frame_done.follow(self.done.q());
        self.store.clear_staged();
        let (x, n, f) = (
            self.x.q().bits() as u32,
            self.line.q().bits() as u32,
            self.field.q().bits() as u32,
        );
        let (mut code, mut completes) = (0, None);
        if self.valid.is_high() {
            (code, completes) = self.arrive(x, n, f);
        }
        let second_field = self.p.scan == Scan::Progressive || f == 1;
        completes = self.eval_levels(x, second_field).or(completes);
        self.page_registers();
        // A FIFO error of any level takes precedence over a sync error.
        if let Some(e) = self.levels.iter().map(Level::error_code).find(|&e| e != 0) {
            code = e;
        }
        if code != 0 && !self.err.q().is_high() {
            self.err.set_next_bool(true);
            self.code.set_next_bits(code);
        }
        if completes.is_some() || self.done.q().is_high() {
            self.done.set_next_bool(completes.is_some());
            self.completed.next = completes;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The command line's names of the scan orders and roundings, each to its own variant;
    /// anything else refused with the value and the choices.
    #[test]
    fn scan_and_rounding_names_parse_to_their_variants() {
        let scans = [
            ("progressive", Scan::Progressive),
            ("interlaced-top", Scan::InterlacedTop),
            ("interlaced-bottom", Scan::InterlacedBottom),
        ];
        for (name, scan) in scans {
            assert_eq!(name.parse::<Scan>(), Ok(scan));
        }
        let e = "interlaced".parse::<Scan>().unwrap_err();
        assert!(
            e.contains("'interlaced'") && e.contains("interlaced-bottom"),
            "{e}"
        );
        for (name, r) in [("round", Rounding::Round), ("truncate", Rounding::Truncate)] {
            assert_eq!(name.parse::<Rounding>(), Ok(r));
        }
        let e = "floor".parse::<Rounding>().unwrap_err();
        assert!(e.contains("'floor'") && e.contains("truncate"), "{e}");
    }

    /// Reset at the edge where an upper level's line leaves FIFO 1412 (on the banks, where
    /// the owner writes what `line_writes` gives): no line goes out again until video comes,
    /// and the next frame's lines come cycle for cycle as a fresh unit's do.
    #[test]
    fn reset_as_an_upper_level_drains_writes_no_line_twice() {
        let p = MipmapParams {
            width: 8,
            height: 8,
            scan: Scan::Progressive,
            rounding: Rounding::Round,
        };
        let mut g = MipmapGen::new("mipmap_gen_816", p).unwrap().on_banks();
        let mut fresh = MipmapGen::new("mipmap_gen_816", p).unwrap().on_banks();
        // Texel n of a frame (none from 64 on), evaluated: the lines going out at the edge.
        let lines = |g: &mut MipmapGen, n: u32| -> Vec<(u32, u64, u32)> {
            g.valid.set_bool(n < 64);
            g.sof.set_bool(n == 0);
            g.texel.set_bits(u64::from(n * 3 % 256));
            g.eval();
            g.line_writes().map(|(k, f, r, _)| (k, f, r)).collect()
        };
        let mut n = 0;
        loop {
            let upper = lines(&mut g, n).iter().any(|l| l.0 >= 2);
            g.tick(upper);
            if upper {
                break;
            }
            n += 1;
            assert!(n < 64, "no level-2 line in a frame");
        }
        for m in 64..80 {
            assert_eq!(lines(&mut g, m), vec![], "cycle {m} after the reset");
            g.tick(false);
        }
        // A frame after the reset: the lines a fresh generator gives, cycle for cycle.
        for m in 0..80 {
            assert_eq!(lines(&mut g, m), lines(&mut fresh, m), "texel {m}");
            g.tick(false);
            fresh.tick(false);
        }
    }
}
