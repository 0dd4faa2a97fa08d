//! One level of Figure 14 (Schilling & Knittel): level `k` of the mipmap from the texel stream
//! of level `k-1`, with adder 1402, register 1404, FIFO 1408, adder 1410 and FIFO 1412. See
//! [`super::mipmap_gen_816`] for how the levels are chained and what each does.

use super::fifo::{ErrCode, Fifo};
use crate::fx::{Bit, Format};
use crate::kernel::{Module, RegOf, SignalOf};

hdl::formats! {
    /// A texel, 8 bits.
    pub Texel = Format::uint(8);
    /// Adder 1402's sum of two texels.
    pub Sum2 = Format::uint(9);
    /// Adder 1410's sum of four texels.
    pub Sum4 = Format::uint(10);
    /// A column or row of a level (up to 1024).
    pub Coord = Format::uint(11);
    /// A frame number.
    pub FrameNo = Format::uint(40);
}

/// Division of the box sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rounding {
    /// Round half up: `(sum + n/2) / n`.
    Round,
    /// Truncate: `sum / n`.
    Truncate,
}

parse_names!(Rounding, "round" => Rounding::Round, "truncate" => Rounding::Truncate);

/// `sum / n` with the chosen rounding (n = 2 or 4).
#[inline]
fn divide(sum: u32, n: u32, r: Rounding) -> u32 {
    match r {
        Rounding::Round => (sum + n / 2) / n,
        Rounding::Truncate => sum / n,
    }
}

/// What a texel does to the level's FIFOs this cycle.
#[derive(Clone, Copy, Debug, Default)]
struct Ops {
    push_1408: Option<u32>,
    pop_1408: bool,
    push_1412: Option<u32>,
}

/// One level of Figure 14: level `k` from the texel stream of level `k-1`.
#[derive(Clone, Debug, Module)]
#[module(kind = "mipmap_level_fig14", enable = self.busy.is_high())]
pub struct Level {
    #[instance]
    name: &'static str,
    /// Size of the level read.
    wp: u32,
    hp: u32,
    pair_x: bool,
    pair_y: bool,
    rounding: Rounding,
    /// Level 1 of interlaced video: vertical pairs from the shift register.
    interlaced: bool,
    #[input]
    pub in_valid: SignalOf<Bit>,
    #[input]
    pub in_texel: SignalOf<Texel>,
    /// Interlaced level 1: the partner line's texel from shift register 826.
    #[input]
    pub sr_texel: Option<SignalOf<Texel>>,
    #[wire]
    pub sum1402: SignalOf<Sum2>,
    #[wire]
    pub sum1410: SignalOf<Sum4>,
    #[output]
    pub out_valid: SignalOf<Bit>,
    #[output]
    pub out_texel: SignalOf<Texel>,
    #[reg]
    x: RegOf<Coord>,
    #[reg]
    y: RegOf<Coord>,
    #[reg]
    r1404: RegOf<Texel>,
    #[reg]
    out_v: RegOf<Bit>,
    #[reg]
    out_t: RegOf<Texel>,
    /// Sticky FIFO error: 0 none, 1 overflow, 2 underflow.
    #[reg]
    err: RegOf<ErrCode>,
    #[child]
    pub fifo_1408: Fifo,
    #[child]
    pub fifo_1412: Fifo,
    /// Frame and row (of this level) of the next line FIFO 1412 writes to the frame store.
    #[reg]
    frame: RegOf<FrameNo>,
    #[reg]
    rows_out: RegOf<Coord>,
    /// The clock enable: whether this cycle changes anything (an idle level skips its edge).
    #[wire]
    busy: SignalOf<Bit>,
}

const NAMES: [&str; 11] = [
    "level0", "level1", "level2", "level3", "level4", "level5", "level6", "level7", "level8",
    "level9", "level10",
];

impl Level {
    /// Level `k` (1..=10) reading a level of `prev = (width, height)`.
    pub fn new(
        k: usize,
        prev: (u32, u32),
        rounding: Rounding,
        interlaced: bool,
    ) -> Result<Level, String> {
        let (wp, hp) = prev;
        let wk = (wp / 2).max(1) as usize;
        Ok(Level {
            name: NAMES.get(k).ok_or(format!("level {k}: at most 10"))?,
            wp,
            hp,
            pair_x: wp > 1,
            pair_y: hp > 1,
            rounding,
            interlaced,
            in_valid: SignalOf::new("in_valid"),
            in_texel: SignalOf::new("in_texel"),
            sr_texel: interlaced.then(|| SignalOf::new("sr826")),
            sum1402: SignalOf::new("sum1402"),
            sum1410: SignalOf::new("sum1410"),
            out_valid: SignalOf::new("out_valid"),
            out_texel: SignalOf::new("out_texel"),
            x: RegOf::new("x"),
            y: RegOf::new("y"),
            r1404: RegOf::new("r1404"),
            out_v: RegOf::new("out_valid_r"),
            out_t: RegOf::new("out_texel_r"),
            err: RegOf::new("fifo_error"),
            fifo_1408: Fifo::new("fifo_1408", wk, 9)?,
            fifo_1412: Fifo::new("fifo_1412", wk, 8)?,
            frame: RegOf::new("frame"),
            rows_out: RegOf::new("rows_out"),
            busy: {
                let mut b = SignalOf::new("busy");
                b.set_bool(true);
                b
            },
        })
    }

    /// The sticky FIFO error: 0 none, 1 overflow, 2 underflow.
    pub fn error_code(&self) -> u64 {
        self.err.q().bits()
    }

    /// Nothing in, nothing out, no line to write, and its ports already showing that: its
    /// `eval` would change nothing and its edge would be skipped, so a parent may leave it
    /// unevaluated this cycle (it stays idle: its own `busy` is already false).
    #[inline]
    pub fn quiescent(&self) -> bool {
        !self.in_valid.is_high()
            && !self.out_valid.is_high()
            && !self.out_v.q().is_high()
            && !self.fifo_1412.is_full()
            && !self.busy.is_high()
    }

    /// When FIFO 1412's line goes to the frame store at the coming edge (decided by `eval`):
    /// the frame and the row of this level it belongs to.
    pub fn line_write(&self) -> Option<(u64, u32)> {
        self.fifo_1412
            .clear
            .is_high()
            .then_some((self.frame.q().bits(), self.rows_out.q().bits() as u32))
    }

    /// FIFO 1408's oldest entry for adder 1410 (0 when empty: the FIFO reports the underflow).
    fn front_1408(&self) -> u32 {
        self.fifo_1408.front().map_or(0, u32::from)
    }

    /// Adder 1410: `s` plus FIFO 1408's oldest entry (popped), divided by four.
    fn add_1410(&mut self, s: u32, ops: &mut Ops) -> u32 {
        let sum = self.front_1408() + s;
        ops.pop_1408 = true;
        self.sum1410.set_bits(u64::from(sum));
        divide(sum, 4, self.rounding)
    }

    /// Interlaced level 1: the vertical pair from the shift register, then the odd column
    /// through FIFO 1408 (a one-entry register).
    fn reduce_interlaced(&mut self, t: u32, x: u32) -> (Ops, Option<u32>) {
        let r = self.rounding;
        let sr = self.sr_texel.as_ref().map_or(0, |s| s.bits());
        let s = t + sr as u32;
        self.sum1402.set_bits(u64::from(s));
        let mut ops = Ops::default();
        let out = if !self.pair_x {
            Some(divide(s, 2, r))
        } else if x.is_multiple_of(2) {
            ops.push_1408 = Some(s);
            None
        } else {
            Some(self.add_1410(s, &mut ops))
        };
        (ops, out)
    }

    /// Figure 14a/b: horizontal pairs through register 1404 and adder 1402, even lines into
    /// FIFO 1408, odd lines added to its output in adder 1410.
    fn reduce_progressive(&mut self, t: u32, x: u32, y: u32) -> (Ops, Option<u32>) {
        let r = self.rounding;
        let mut ops = Ops::default();
        let out = match (self.pair_x, self.pair_y) {
            (true, _) if x.is_multiple_of(2) => {
                self.r1404.set_next_bits(u64::from(t));
                None
            }
            (true, pair_y) => {
                let s = self.r1404.q().bits() as u32 + t;
                self.sum1402.set_bits(u64::from(s));
                if !pair_y {
                    Some(divide(s, 2, r))
                } else if y.is_multiple_of(2) {
                    ops.push_1408 = Some(s);
                    None
                } else {
                    Some(self.add_1410(s, &mut ops))
                }
            }
            (false, _) if y.is_multiple_of(2) => {
                ops.push_1408 = Some(t);
                None
            }
            (false, _) => {
                let a = self.front_1408();
                ops.pop_1408 = true;
                self.sum1402.set_bits(u64::from(a + t));
                Some(divide(a + t, 2, r))
            }
        };
        (ops, out)
    }

    /// The level's datapath for one valid input texel: sums, register and counter updates,
    /// the output texel; returns what it does to the FIFOs.
    fn reduce(&mut self) -> Ops {
        let t = self.in_texel.bits() as u32;
        let (x, y) = (self.x.q().bits() as u32, self.y.q().bits() as u32);
        let (mut ops, out) = if self.interlaced {
            self.reduce_interlaced(t, x)
        } else {
            self.reduce_progressive(t, x, y)
        };
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
            ops.push_1412 = Some(o);
        }
        ops
    }

    /// Drives the FIFOs' inputs and evaluates them; a FIFO error is kept (sticky).
    fn drive_fifos(&mut self, ops: Ops, drain: bool) {
        let f = &mut self.fifo_1408;
        f.push.set_bool(ops.push_1408.is_some());
        f.push_data.set_bits(u64::from(ops.push_1408.unwrap_or(0)));
        f.pop.set_bool(ops.pop_1408);
        f.eval();
        let f = &mut self.fifo_1412;
        f.push.set_bool(ops.push_1412.is_some());
        f.push_data.set_bits(u64::from(ops.push_1412.unwrap_or(0)));
        f.clear.set_bool(drain);
        f.eval();
        let e = self.fifo_1408.error.bits().max(self.fifo_1412.error.bits());
        if e != 0 && self.err.q().bits() == 0 {
            self.err.set_next_bits(e);
        }
    }
}

impl Level {
    #[inline]
    pub fn eval(&mut self) {
        self.out_valid.follow(self.out_v.q());
        self.out_texel.follow(self.out_t.q());
        let valid = self.in_valid.is_high();
        // A full FIFO 1412 holds a line: it goes to the frame store at this edge.
        let drain = self.fifo_1412.is_full();
        // Idle: no texel in, none out, no line to write: nothing can change at the edge.
        let was_busy = self.busy.is_high();
        let busy = valid || drain || self.out_v.q().is_high();
        self.busy.set_bool(busy);
        if !busy && !was_busy {
            return;
        }
        if drain {
            // The line leaving FIFO 1412 is the next row of this level, or of the next frame.
            let rows = self.rows_out.q().bits() + 1;
            if rows == u64::from((self.hp / 2).max(1)) {
                self.rows_out.set_next_bits(0);
                self.frame.set_next_bits(self.frame.q().bits() + 1);
            } else {
                self.rows_out.set_next_bits(rows);
            }
        }
        let ops = if valid {
            self.out_v.set_next_bool(false);
            self.reduce()
        } else {
            self.out_v.set_next_bool(false);
            Ops::default()
        };
        self.drive_fifos(ops, drain);
    }
}
