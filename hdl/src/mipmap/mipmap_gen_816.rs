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
use crate::kernel::{Dir, Module, Reg, Signal, Visitor};
use crate::mipmap::fifo::{Fifo, FifoError};
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

/// `sum / n` with the chosen rounding (n = 2 or 4).
#[inline]
fn divide(sum: u32, n: u32, r: Rounding) -> u32 {
    match r {
        Rounding::Round => (sum + n / 2) / n,
        Rounding::Truncate => sum / n,
    }
}

/// One level of Figure 14: level `k` from the texel stream of level `k-1`.
#[derive(Clone, Debug)]
pub struct Reducer {
    name: String,
    k: usize,
    /// Size of the level read.
    wp: u32,
    hp: u32,
    pair_x: bool,
    pair_y: bool,
    rounding: Rounding,
    /// Level 1 of interlaced video: vertical pairs from the shift register.
    interlaced: bool,
    pub in_valid: Signal,
    pub in_texel: Signal,
    /// Interlaced level 1: the partner line's texel from shift register 826.
    pub sr_texel: Signal,
    pub sum1402: Signal,
    pub sum1410: Signal,
    pub out_valid: Signal,
    pub out_texel: Signal,
    x: Reg,
    y: Reg,
    r1404: Reg,
    out_v: Reg,
    out_t: Reg,
    pub fifo1408: Fifo,
    pub fifo1412: Fifo,
    /// Pending FIFO operations decided by `eval`, applied by `tick`.
    push1408: Option<u16>,
    pop1408: bool,
    push1412: Option<u16>,
    drain1412: bool,
    /// The line drained from FIFO 1412 at the last edge: `(frame, row, texels)`.
    pub written: Option<(u64, u32, Vec<u16>)>,
    /// Whether this cycle changes anything (an idle level skips its edge).
    busy: bool,
    frame: u64,
    rows_out: u32,
    pub error: Option<FifoError>,
}

const NAMES: [&str; 11] = [
    "level0", "level1", "level2", "level3", "level4", "level5", "level6", "level7", "level8",
    "level9", "level10",
];

impl Reducer {
    fn new(k: usize, prev: (u32, u32), rounding: Rounding, interlaced: bool) -> Reducer {
        let (wp, hp) = prev;
        let wk = (wp / 2).max(1) as usize;
        let c = |b: u32| Format::uint(b);
        Reducer {
            name: NAMES[k].into(),
            k,
            wp,
            hp,
            pair_x: wp > 1,
            pair_y: hp > 1,
            rounding,
            interlaced,
            in_valid: Signal::bit("in_valid"),
            in_texel: Signal::new("in_texel", c(8)),
            sr_texel: Signal::new("sr826", c(8)),
            sum1402: Signal::new("sum1402", c(9)),
            sum1410: Signal::new("sum1410", c(10)),
            out_valid: Signal::bit("out_valid"),
            out_texel: Signal::new("out_texel", c(8)),
            x: Reg::new("x", c(11)),
            y: Reg::new("y", c(11)),
            r1404: Reg::new("r1404", c(8)),
            out_v: Reg::new("out_valid_r", c(1)),
            out_t: Reg::new("out_texel_r", c(8)),
            fifo1408: Fifo::new("fifo1408_occupancy", wk),
            fifo1412: Fifo::new("fifo1412_occupancy", wk),
            push1408: None,
            pop1408: false,
            push1412: None,
            drain1412: false,
            written: None,
            busy: true,
            frame: 0,
            rows_out: 0,
            error: None,
        }
    }

    /// Width of the level this reducer writes.
    pub fn out_width(&self) -> u32 {
        (self.wp / 2).max(1)
    }

    /// Level number.
    pub fn level(&self) -> usize {
        self.k
    }

    /// Nothing in, nothing out, no line to write, and its ports already showing that:
    /// evaluating and clocking this level would change nothing, so the parent may skip it.
    #[inline]
    fn quiescent(&self) -> bool {
        !self.in_valid.is_high()
            && !self.out_valid.is_high()
            && !self.out_v.q().is_high()
            && self.fifo1412.len() < self.fifo1412.depth()
    }
}

impl Module for Reducer {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "mipmap_level_fig14"
    }
    fn eval(&mut self) {
        self.out_valid.follow(self.out_v.q());
        self.out_texel.follow(self.out_t.q());
        let valid = self.in_valid.is_high();
        let drain = self.fifo1412.len() == self.fifo1412.depth();
        // Idle: no texel in, none out, no line to write: nothing can change at the edge.
        self.busy = valid || drain || self.out_v.q().is_high();
        if !self.busy {
            return;
        }
        self.push1408 = None;
        self.pop1408 = false;
        self.push1412 = None;
        self.drain1412 = drain;
        self.out_v.set_next_bool(false);
        if !valid {
            return;
        }
        let t = self.in_texel.bits() as u32;
        let (x, y) = (self.x.q().bits() as u32, self.y.q().bits() as u32);
        let r = self.rounding;
        let mut out = None;
        fn front(f: &Fifo, e: &mut Option<FifoError>) -> u32 {
            match f.front() {
                Some(v) => u32::from(v),
                None => {
                    e.get_or_insert(FifoError::Underflow);
                    0
                }
            }
        }
        if self.interlaced {
            // Vertical pair from the shift register, then the odd column through FIFO 1408.
            let s = t + self.sr_texel.bits() as u32;
            self.sum1402.set_bits(u64::from(s));
            if !self.pair_x {
                out = Some(divide(s, 2, r));
            } else if x % 2 == 0 {
                self.push1408 = Some(s as u16);
            } else {
                let a = front(&self.fifo1408, &mut self.error);
                self.pop1408 = true;
                self.sum1410.set_bits(u64::from(a + s));
                out = Some(divide(a + s, 4, r));
            }
        } else {
            match (self.pair_x, self.pair_y) {
                (true, _) if x % 2 == 0 => self.r1404.set_next_bits(u64::from(t)),
                (true, true) => {
                    let s = self.r1404.q().bits() as u32 + t;
                    self.sum1402.set_bits(u64::from(s));
                    if y % 2 == 0 {
                        self.push1408 = Some(s as u16);
                    } else {
                        let a = front(&self.fifo1408, &mut self.error);
                        self.pop1408 = true;
                        self.sum1410.set_bits(u64::from(a + s));
                        out = Some(divide(a + s, 4, r));
                    }
                }
                (true, false) => {
                    let s = self.r1404.q().bits() as u32 + t;
                    self.sum1402.set_bits(u64::from(s));
                    out = Some(divide(s, 2, r));
                }
                (false, true) => {
                    if y % 2 == 0 {
                        self.push1408 = Some(t as u16);
                    } else {
                        let a = front(&self.fifo1408, &mut self.error);
                        self.pop1408 = true;
                        self.sum1402.set_bits(u64::from(a + t));
                        out = Some(divide(a + t, 2, r));
                    }
                }
                (false, false) => unreachable!("a 1x1 level has no next level"),
            }
        }
        // Counters over the level read (for interlaced level 1, x only: lines come from the top).
        let nx = if x + 1 == self.wp { 0 } else { x + 1 };
        self.x.set_next_bits(u64::from(nx));
        if nx == 0 && !self.interlaced {
            let ny = if y + 1 == self.hp { 0 } else { y + 1 };
            self.y.set_next_bits(u64::from(ny));
        }
        if let Some(o) = out {
            self.out_v.set_next_bool(true);
            self.out_t.set_next_bits(u64::from(o));
            self.push1412 = Some(o as u16);
        }
    }
    fn tick(&mut self, reset: bool) {
        if !self.busy && !reset {
            return;
        }
        self.written = None;
        for r in [
            &mut self.x,
            &mut self.y,
            &mut self.r1404,
            &mut self.out_v,
            &mut self.out_t,
        ] {
            r.tick(reset);
        }
        if reset {
            self.fifo1408.clear();
            self.fifo1412.clear();
            self.error = None;
            return;
        }
        if self.drain1412 {
            let line = self.fifo1412.drain_all();
            let rows = (self.hp / 2).max(1);
            self.written = Some((self.frame, self.rows_out, line));
            self.rows_out += 1;
            if self.rows_out == rows {
                self.rows_out = 0;
                self.frame += 1;
            }
        }
        if self.pop1408 {
            if let Err(e) = self.fifo1408.pop() {
                self.error.get_or_insert(e);
            }
        }
        if let Some(v) = self.push1408 {
            if let Err(e) = self.fifo1408.push(v) {
                self.error.get_or_insert(e);
            }
        }
        if let Some(v) = self.push1412 {
            if let Err(e) = self.fifo1412.push(v) {
                self.error.get_or_insert(e);
            }
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        signals!(v;
            Input: self.in_valid, self.in_texel;
            Wire: self.sum1402, self.sum1410, self.fifo1408.occupancy, self.fifo1412.occupancy;
            Output: self.out_valid, self.out_texel;
            Reg: self.r1404, self.x, self.y);
        if self.interlaced {
            v.signal(Dir::Input, &self.sr_texel);
        }
        v.leave();
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
    /// The first FIFO error of any level (reported through `err_code`).
    fifo_error: Option<FifoError>,
    pub reducers: Vec<Reducer>,
    /// Shift register 826 (interlaced: the partner line of the line arriving).
    sr: Vec<u8>,
    sr_load: Option<u32>,
    /// Open row of each bank's page register, and row activations counted.
    pub page_row: [Signal; 3],
    pub activations: [u64; 3],
    /// Two frame buffers, used by frame parity.
    pub buffers: [FrameBuffer; 2],
    /// Frames whose mipmap is complete, in order, with the cycle.
    pub completed: Vec<(u64, u64)>,
    cycle: u64,
    pending_store: Option<(u32, u32, u8)>,
}

impl MipmapGen {
    pub fn new(name: &str, p: MipmapParams) -> Result<MipmapGen, String> {
        p.validate()?;
        let dims = p.levels();
        let interlaced = p.scan != Scan::Progressive;
        let reducers = (1..dims.len())
            .map(|k| Reducer::new(k, dims[k - 1], p.rounding, interlaced && k == 1))
            .collect();
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
            fifo_error: None,
            reducers,
            sr: vec![0; p.width as usize],
            sr_load: None,
            page_row: ["page_row_bank0", "page_row_bank1", "page_row_bank2"]
                .map(|n| Signal::new(n, Format::uint(16))),
            activations: [0; 3],
            buffers: [buf.clone(), buf],
            completed: Vec::new(),
            cycle: 0,
            pending_store: None,
            dims,
        })
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

    fn open_row(&mut self, bank: usize, row: u32) {
        if self.page_row[bank].bits() != u64::from(row) || self.activations[bank] == 0 {
            self.activations[bank] += 1;
            self.page_row[bank].set_bits(u64::from(row) & 0xffff);
        }
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
        if let Some(r1) = self.reducers.first_mut() {
            r1.in_valid.set_bool(valid && second_field);
            r1.in_texel.follow(&self.texel);
            r1.sr_texel.set_bits(u64::from(self.sr[x as usize]));
            r1.eval();
        }
        for k in 1..self.reducers.len() {
            let (a, b) = self.reducers.split_at_mut(k);
            let prev = &a[k - 1];
            let r = &mut b[0];
            if !prev.out_valid.is_high() && r.quiescent() {
                r.busy = false;
                continue;
            }
            r.in_valid.follow(&prev.out_valid);
            r.in_texel.follow(&prev.out_texel);
            r.eval();
        }
        if let Some(e) = self.fifo_error {
            code = match e {
                FifoError::Overflow => 1,
                FifoError::Underflow => 2,
            };
        }
        if code != 0 && !self.err.q().is_high() {
            self.err.set_next_bool(true);
            self.code.set_next_bits(code);
        }
    }
    fn tick(&mut self, reset: bool) {
        self.done = false;
        for r in [
            &mut self.x,
            &mut self.line,
            &mut self.field,
            &mut self.err,
            &mut self.code,
        ] {
            r.tick(reset);
        }
        for r in &mut self.reducers {
            // An idle level's edge changes nothing: skip the call.
            if r.busy || reset {
                r.tick(reset);
                if let Some(e) = r.error {
                    self.fifo_error.get_or_insert(e);
                }
            }
        }
        self.cycle += 1;
        if reset {
            self.frame0 = 0;
            self.fifo_error = None;
            return;
        }
        let w = self.p.width;
        let n = self.dims.len();
        if let Some((x, y, t)) = self.pending_store {
            // Level 0 into bank y % 2 of this frame's buffer, through its page register.
            self.open_row((y % 2) as usize, y / 2);
            let b = (self.frame0 % 2) as usize;
            self.buffers[b][0][(y * w + x) as usize] = t;
            let last = x + 1 == w
                && y == self.frame_line(
                    u32::from(self.p.scan != Scan::Progressive),
                    self.lines_per_field() - 1,
                );
            if last {
                if n == 1 {
                    // A 1x1 frame is its own mipmap.
                    self.completed.push((self.frame0, self.cycle));
                    self.done = true;
                }
                self.frame0 += 1;
            }
        }
        if let Some(row) = self.sr_load {
            // The partner line of the next line: its bank's page register, then the shift register.
            self.open_row((row % 2) as usize, row / 2);
            let b = (self.frame0 % 2) as usize;
            self.sr
                .copy_from_slice(&self.buffers[b][0][(row * w) as usize..((row + 1) * w) as usize]);
        }
        for k in 0..self.reducers.len() {
            if self.reducers[k].written.is_none() {
                continue;
            }
            if let Some((frame, row, line)) = self.reducers[k].written.take() {
                let lw = self.dims[k + 1].0;
                self.open_row(2, (k as u32) << 10 | row);
                let b = (frame % 2) as usize;
                let dst =
                    &mut self.buffers[b][k + 1][(row * lw) as usize..((row + 1) * lw) as usize];
                for (d, s) in dst.iter_mut().zip(&line) {
                    *d = *s as u8;
                }
                if k + 2 == n {
                    self.completed.push((frame, self.cycle));
                    self.done = true;
                }
            }
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        signals!(v;
            Input: self.valid, self.texel, self.sof;
            Output: self.error, self.err_code, self.frame_done;
            Reg: self.x, self.line, self.field);
        for p in &self.page_row {
            v.signal(Dir::Wire, p);
        }
        for r in &self.reducers {
            r.visit(v);
        }
        v.leave();
    }
}
