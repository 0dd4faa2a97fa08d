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

use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::mipmap::level_fig14::Level;
use crate::pages::page_registers_824::PageRegisters824;
use crate::signals;

/// Arrival order of a frame's lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scan {
    Progressive,
    /// Field of even lines (0, 2, ...) first.
    InterlacedTop,
    /// Field of odd lines (1, 3, ...) first.
    InterlacedBottom,
}

/// Division of the box sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rounding {
    /// Round half up: `(sum + n/2) / n`.
    Round,
    /// Truncate: `sum / n`.
    Truncate,
}

impl std::str::FromStr for Scan {
    type Err = String;
    fn from_str(s: &str) -> Result<Scan, String> {
        match s {
            "progressive" => Ok(Scan::Progressive),
            "interlaced-top" => Ok(Scan::InterlacedTop),
            "interlaced-bottom" => Ok(Scan::InterlacedBottom),
            _ => Err(format!(
                "unknown scan '{s}' (progressive, interlaced-top, interlaced-bottom)"
            )),
        }
    }
}

impl std::str::FromStr for Rounding {
    type Err = String;
    fn from_str(s: &str) -> Result<Rounding, String> {
        match s {
            "round" => Ok(Rounding::Round),
            "truncate" => Ok(Rounding::Truncate),
            _ => Err(format!("unknown rounding '{s}' (round, truncate)")),
        }
    }
}

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

/// The mipmap generation unit 816 with its frame store.
#[derive(Clone, Debug)]
pub struct MipmapGen {
    name: String,
    p: MipmapParams,
    dims: Vec<(u32, u32)>,
    pub valid: Signal,
    pub texel: Signal,
    pub sof: Signal,
    pub error: Signal,
    pub err_code: Signal,
    pub frame_done: Signal,
    /// Level-0 arrival counters: x, line within the field, field.
    x: Reg,
    line: Reg,
    field: Reg,
    frame0: u64,
    err: Reg,
    code: Reg,
    /// A frame's mipmap was completed at the last edge.
    done: bool,
    /// Levels 1.. of Figure 14.
    pub levels: Vec<Level>,
    /// Shift register 826 (interlaced: the partner line of the line arriving).
    sr: Vec<u8>,
    sr_load: Option<u32>,
    /// The page registers 824 of the own frame store's three banks (none on the TEXRAM's,
    /// whose own count), and row activations counted.
    pages: Option<PageRegisters824>,
    pub activations: [u64; 3],
    /// Row activations per bank at the coming edge (decided by `eval`).
    acts: [u64; 3],
    /// Two frame buffers, used by frame parity.
    pub buffers: [FrameBuffer; 2],
    /// Frames whose mipmap is complete, in order, with the cycle.
    pub completed: Vec<(u64, u64)>,
    cycle: u64,
    pending_store: Option<(u32, u32, u8)>,
    /// Levels whose FIFO 1412 line goes to the frame store at the coming edge, bit `k` for
    /// level `k + 1` (decided by `eval`).
    drains: u32,
    /// The frame store is the unit's own (`buffers`, three banks); false when it sits on the
    /// TEXRAM banks, whose owner takes the writes and serves the shift register's line.
    own_store: bool,
}

impl MipmapGen {
    pub fn new(name: &str, p: MipmapParams) -> Result<MipmapGen, String> {
        p.validate()?;
        let dims = p.levels();
        let interlaced = p.scan != Scan::Progressive;
        let levels = (1..dims.len())
            .map(|k| Level::new(k, dims[k - 1], p.rounding, interlaced && k == 1))
            .collect::<Result<_, _>>()?;
        let buf: FrameBuffer = dims
            .iter()
            .map(|&(w, h)| vec![0u8; (w * h) as usize])
            .collect();
        Ok(MipmapGen {
            name: name.into(),
            p,
            valid: Signal::bit("valid"),
            texel: Signal::new("texel", Format::uint(8)),
            sof: Signal::bit("sof"),
            error: Signal::bit("error"),
            err_code: Signal::new("err_code", Format::uint(2)),
            frame_done: Signal::bit("frame_done"),
            x: Reg::new("x0", Format::uint(11)),
            line: Reg::new("line0", Format::uint(11)),
            field: Reg::new("field", Format::uint(1)),
            frame0: 0,
            err: Reg::new("error_r", Format::uint(1)),
            code: Reg::new("err_code_r", Format::uint(2)),
            done: false,
            levels,
            sr: vec![0; p.width as usize],
            sr_load: None,
            pages: Some(PageRegisters824::new(3, 16)),
            activations: [0; 3],
            acts: [0; 3],
            buffers: [buf.clone(), buf],
            completed: Vec::new(),
            cycle: 0,
            pending_store: None,
            drains: 0,
            own_store: true,
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
        self.own_store = false;
        self.pages = None;
        self.buffers = [Vec::new(), Vec::new()];
        self
    }

    /// At the coming edge: the video texel written into level 0, as `(frame, x, y, texel)`.
    pub fn level0_write(&self) -> Option<(u64, u32, u32, u8)> {
        self.pending_store.map(|(x, y, t)| (self.frame0, x, y, t))
    }

    /// At the coming edge: the level-0 line of the current frame to load into shift register
    /// 826 for the next line of the second field (interlaced video only).
    pub fn partner_read(&self) -> Option<(u64, u32)> {
        self.sr_load.map(|row| (self.frame0, row))
    }

    /// At the coming edge: each level whose FIFO 1412 line goes to the frame store, as
    /// `(level, frame, row, texels)`.
    pub fn line_writes(&self) -> impl Iterator<Item = (u32, u64, u32, Vec<u8>)> + '_ {
        (0..self.levels.len()).filter_map(move |k| {
            let l = &self.levels[k];
            let (frame, row) = l.line_write().filter(|_| self.drains >> k & 1 == 1)?;
            let texels = l.fifo_1412.iter().map(|t| t as u8).collect();
            Some((k as u32 + 1, frame, row, texels))
        })
    }

    /// Shift register 826 loaded with the partner line (the unit on the TEXRAM banks).
    pub fn load_partner(&mut self, line: &[u8]) {
        self.sr.copy_from_slice(line);
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

    /// At the edge: each level whose FIFO 1412 holds a full line writes it into its frame's
    /// buffer (bank 2); the last level's line completes the frame's mipmap.
    fn store_lines(&mut self) {
        let n = self.dims.len();
        let mut d = self.drains;
        while d != 0 {
            let k = d.trailing_zeros() as usize;
            d &= d - 1;
            let l = &self.levels[k];
            let Some((frame, row)) = l.line_write() else {
                continue;
            };
            if self.own_store {
                let lw = self.dims[k + 1].0;
                let b = (frame % 2) as usize;
                let dst =
                    &mut self.buffers[b][k + 1][(row * lw) as usize..((row + 1) * lw) as usize];
                for (d, s) in dst.iter_mut().zip(l.fifo_1412.iter()) {
                    *d = s as u8;
                }
            }
            if k + 2 == n {
                self.completed.push((frame, self.cycle));
                self.done = true;
            }
        }
    }

    /// At the edge: the video texel into bank `y % 2` of its frame's buffer, and (interlaced)
    /// the next line's partner from the frame store into shift register 826.
    fn store_level0(&mut self) {
        let w = self.p.width;
        if let Some((x, y, t)) = self.pending_store {
            if self.own_store {
                let b = (self.frame0 % 2) as usize;
                self.buffers[b][0][(y * w + x) as usize] = t;
            }
            let last = x + 1 == w
                && y == self.frame_line(
                    u32::from(self.p.scan != Scan::Progressive),
                    self.lines_per_field() - 1,
                );
            if last {
                if self.dims.len() == 1 {
                    // A 1x1 frame is its own mipmap.
                    self.completed.push((self.frame0, self.cycle));
                    self.done = true;
                }
                self.frame0 += 1;
            }
        }
        if let Some(row) = self.sr_load.filter(|_| self.own_store) {
            let b = (self.frame0 % 2) as usize;
            let line = &self.buffers[b][0][(row * w) as usize..((row + 1) * w) as usize];
            self.sr.copy_from_slice(line);
        }
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
        if let Some((_, y, _)) = self.pending_store {
            open((y % 2) as usize, y / 2);
        }
        if let Some(row) = self.sr_load {
            open((row % 2) as usize, row / 2);
        }
        let mut d = self.drains;
        while d != 0 {
            let k = d.trailing_zeros() as usize;
            d &= d - 1;
            if let Some((_, row)) = self.levels[k].line_write() {
                open(2, (k as u32) << 10 | row);
            }
        }
        self.acts = acts;
    }
}

impl Module for MipmapGen {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "mipmap_gen_816"
    }
    fn eval(&mut self) {
        self.error.follow(self.err.q());
        self.err_code.follow(self.code.q());
        self.frame_done.set_bool(self.done);
        self.pending_store = None;
        self.sr_load = None;
        let valid = self.valid.is_high();
        let (x, n, f) = (
            self.x.q().bits() as u32,
            self.line.q().bits() as u32,
            self.field.q().bits() as u32,
        );
        let mut code = 0;
        if valid {
            let first = x == 0 && n == 0 && f == 0;
            if self.sof.is_high() != first {
                code = 3;
            }
            let y = self.frame_line(f, n);
            self.pending_store = Some((x, y, self.texel.bits() as u8));
            // Next position; at a line end, the next line's partner goes into the shift register.
            let (mut nx, mut nn, mut nf) = (x + 1, n, f);
            if nx == self.p.width {
                nx = 0;
                nn += 1;
                if nn == self.lines_per_field() {
                    nn = 0;
                    nf += 1;
                    if nf == 1 + u32::from(self.p.scan != Scan::Progressive) {
                        nf = 0;
                    }
                }
                if self.p.scan != Scan::Progressive && nf == 1 {
                    self.sr_load = Some(self.frame_line(nf, nn) ^ 1);
                }
            }
            self.x.set_next_bits(u64::from(nx));
            self.line.set_next_bits(u64::from(nn));
            self.field.set_next_bits(u64::from(nf));
        }
        // Level 1 reads the video port (and, interlaced, the shift register in the second field).
        let second_field = self.p.scan == Scan::Progressive || f == 1;
        self.drains = 0;
        if let Some(l1) = self.levels.first_mut() {
            l1.in_valid.set_bool(valid && second_field);
            l1.in_texel.follow(&self.texel);
            if let Some(sr) = &mut l1.sr_texel {
                sr.set_bits(u64::from(self.sr[x as usize]));
            }
            l1.eval();
            self.drains |= u32::from(l1.line_write().is_some());
        }
        // Each level reads the one before; an idle level with nothing arriving is not
        // evaluated (most cycles, for the upper levels).
        for k in 1..self.levels.len() {
            let (a, b) = self.levels.split_at_mut(k);
            let (prev, l) = (&a[k - 1], &mut b[0]);
            if !prev.out_valid.is_high() && l.quiescent() {
                continue;
            }
            l.in_valid.follow(&prev.out_valid);
            l.in_texel.follow(&prev.out_texel);
            l.eval();
            self.drains |= u32::from(l.line_write().is_some()) << k;
        }
        self.page_registers();
        // A FIFO error of any level takes precedence over a sync error.
        if let Some(e) = self.levels.iter().map(Level::error_code).find(|&e| e != 0) {
            code = e;
        }
        if code != 0 && !self.err.q().is_high() {
            self.err.set_next_bool(true);
            self.code.set_next_bits(code);
        }
    }
    fn tick(&mut self, reset: bool) {
        self.done = false;
        self.x.tick(reset);
        self.line.tick(reset);
        self.field.tick(reset);
        self.err.tick(reset);
        self.code.tick(reset);
        if let Some(p) = &mut self.pages {
            p.tick(reset);
        }
        self.cycle += 1;
        if reset {
            // Frame numbers start again at 0: the record of completed frames with them.
            self.frame0 = 0;
            self.completed.clear();
            for l in &mut self.levels {
                l.tick(true);
            }
            return;
        }
        for (a, n) in self.activations.iter_mut().zip(self.acts) {
            *a += n;
        }
        // The levels' lines leave their FIFOs 1412 at this edge: store them first.
        self.store_lines();
        for l in &mut self.levels {
            l.tick(false);
        }
        self.store_level0();
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        signals!(v;
            Input: self.valid, self.texel, self.sof;
            Output: self.error, self.err_code, self.frame_done;
            Reg: self.x, self.line, self.field);
        // On the TEXRAM banks the chip's page registers 824 are the ones that count.
        if let Some(p) = &self.pages {
            p.visit(v);
        }
        for l in &self.levels {
            l.visit(v);
        }
        v.leave();
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
