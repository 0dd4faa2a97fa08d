//! The chain walker of the address and control unit 812 (section 14, Fig. 16), cycle by
//! cycle: a pixel port from the rasterizer, the micro-program of [`super::program`] as a
//! state machine whose state is named in the waveform, the banks behind [`TexramAccess`] and
//! the output stage 820.
//!
//! # Timing (\[C\]; the document gives the 30 ns slot and "a linked-map access will most
//! probably cause a page fault")
//! The clock is 5 ns. A pixel is taken in a cycle where `req_ready` is high (idle, the
//! cycle a result is out, or the last cycle of a pixel's last access). An access is issued on `acc_*` in the cycle the
//! walker decides it and read at that clock edge; the walker stays in the access's state for
//! its slots (one, two after a page fault, from the banks' open rows) times `slot_cycles`.
//! Computing an environment map's coordinates (eq. 4 and the cube face) takes one cycle
//! (`ENV_COORDS`); the result is out in the cycle after the last access (`COMBINE`, or
//! `ERROR`): `out_valid` with `out_colour`, the pixel's `out_accesses`, `out_slots`,
//! `out_faults` (accesses that faulted) and `out_error`. The next pixel is taken in the last
//! access's last cycle already, so back-to-back pixels of one access each come one a slot
//! (the chip's 33.3 M per second); the walker then goes from that access straight to the
//! next pixel's, and `COMBINE` shows only when no pixel waits.
//!
//! | port | format |
//! |---|---|
//! | `req_drf` | u3 |
//! | `req_u`, `req_v` | sQ12.8 |
//! | `req_lambda` | sQ5.8 |
//! | `req_nx/ny/nz` | sQ2.14 (n_b of eq. 3) |
//! | `req_ex/ey/ez` | sQ1.14 (unit vector to the eye) |
//! | `req_face` | u3 |
//! | `req_id`, `req_is` | u8 |
//! | `acc_drf`, `acc_plane` | u3 |
//! | `acc_u`, `acc_v`, `acc_lambda` | sQ12.8, sQ12.8, sQ5.8 |
//! | `out_colour` | u8 |

use super::drf_812::DrfFile;
use super::program::{ChainRequest, Fetch, Program, State, Walk, STATES};
use crate::envmap::cube_face::CubeFace;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::texram::{TexramAccess, UV_BITS};

/// The walk's registers: name and width, in the order of [`fields`].
const WALK: [(&str, u32); 18] = [
    ("state", 4),
    ("drf", 3),
    ("steps", 4),
    ("deferred", 1),
    ("to_refl", 1),
    ("tex", 8),
    ("refl", 8),
    ("env", 8),
    ("ou", 8),
    ("ov", 8),
    ("offsets", 1),
    ("detail", 8),
    ("tex_drf", 3),
    ("refl_drf", 3),
    ("env_drf", 3),
    ("face", 3),
    ("s", 12),
    ("t", 12),
];

fn fields(w: &Walk) -> [u64; 18] {
    let b = |x: u8| u64::from(x);
    let f = |x: bool| u64::from(x);
    [
        w.state.bits(),
        b(w.drf),
        b(w.steps),
        f(w.deferred),
        f(w.to_refl),
        b(w.tex),
        b(w.refl),
        b(w.env),
        b(w.ou),
        b(w.ov),
        f(w.offsets),
        b(w.detail),
        b(w.tex_drf),
        b(w.refl_drf),
        b(w.env_drf),
        b(w.face),
        u64::from(w.s),
        u64::from(w.t),
    ]
}

fn walk_of(f: [u64; 18]) -> Walk {
    let (u8_, b) = (|x: u64| x as u8, |x: u64| x != 0);
    Walk {
        state: State::from_bits(f[0]),
        drf: u8_(f[1]),
        steps: u8_(f[2]),
        deferred: b(f[3]),
        to_refl: b(f[4]),
        tex: u8_(f[5]),
        refl: u8_(f[6]),
        env: u8_(f[7]),
        ou: u8_(f[8]),
        ov: u8_(f[9]),
        offsets: b(f[10]),
        detail: u8_(f[11]),
        tex_drf: u8_(f[12]),
        refl_drf: u8_(f[13]),
        env_drf: u8_(f[14]),
        face: u8_(f[15]),
        s: f[16] as u16,
        t: f[17] as u16,
    }
}

/// A pixel's result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ChainResult {
    pub colour: u8,
    pub accesses: u32,
    pub slots: u32,
    pub faults: u32,
    pub error: bool,
}

/// The pixel's fields' formats, in the order of [`REQ`].
fn pixel_formats() -> [Format; 13] {
    let uv = Format::signed(UV_BITS, 8);
    let (nf, ef) = (Format::signed(17, 14), Format::signed(16, 14));
    let (u3, u8f) = (Format::uint(3), Format::uint(8));
    [
        u3,
        uv,
        uv,
        Format::signed(14, 8),
        nf,
        nf,
        nf,
        ef,
        ef,
        ef,
        u3,
        u8f,
        u8f,
    ]
}

fn request_of(x: [i64; 13]) -> ChainRequest {
    ChainRequest {
        drf: x[0] as u8,
        u: x[1] as i32,
        v: x[2] as i32,
        lambda: x[3] as i32,
        n: [x[4], x[5], x[6]],
        eye: [x[7], x[8], x[9]],
        face: x[10] as u8,
        i_d: x[11] as u8,
        i_s: x[12] as u8,
    }
}

fn raw_of(r: &ChainRequest) -> [i64; 13] {
    let [nx, ny, nz] = r.n;
    let [ex, ey, ez] = r.eye;
    [
        r.drf.into(),
        r.u.into(),
        r.v.into(),
        r.lambda.into(),
        nx,
        ny,
        nz,
        ex,
        ey,
        ez,
        r.face.into(),
        r.i_d.into(),
        r.i_s.into(),
    ]
}

const REQ: [&str; 13] = [
    "req_drf",
    "req_u",
    "req_v",
    "req_lambda",
    "req_nx",
    "req_ny",
    "req_nz",
    "req_ex",
    "req_ey",
    "req_ez",
    "req_face",
    "req_id",
    "req_is",
];
const HELD: [&str; 13] = [
    "drf_in", "u", "v", "lambda", "nx", "ny", "nz", "ex", "ey", "ez", "face_in", "i_d", "i_s",
];

/// The walker with the banks it reads through.
pub struct MapChain812<T: TexramAccess> {
    file: DrfFile,
    texram: T,
    tab: [u64; 64],
    slot_cycles: u32,
    pub req_valid: Signal,
    pub req_ready: Signal,
    req: [Signal; 13],
    /// The pixel being walked.
    held: [Reg; 13],
    pub acc_valid: Signal,
    acc: [Signal; 5],
    walk: Vec<Reg>,
    busy: Reg,
    rd_value: Reg,
    rd_slots: Reg,
    px_acc: [Reg; 3],
    pub out_valid: Reg,
    pub out_colour: Reg,
    pub out_error: Reg,
    out_acc: [Reg; 3],
    /// An access the banks refused (a format error: a bug of the walker), kept for the
    /// testbench.
    pub access_error: Option<String>,
}

impl<T: TexramAccess> MapChain812<T> {
    /// The walker over `texram`, whose maps the DRFs of `file` describe (loaded already).
    pub fn new(file: DrfFile, texram: T, slot_cycles: u32) -> Result<MapChain812<T>, String> {
        file.validate()?;
        crate::pages::page_registers_824::check_slot_cycles(slot_cycles)?;
        let fmt = pixel_formats();
        let uv = Format::signed(UV_BITS, 8);
        let (u3, u8f) = (Format::uint(3), Format::uint(8));
        Ok(MapChain812 {
            file,
            texram,
            tab: *CubeFace::new().table(),
            slot_cycles,
            req_valid: Signal::bit("req_valid"),
            req_ready: Signal::bit("req_ready"),
            req: std::array::from_fn(|i| Signal::new(REQ[i], fmt[i])),
            held: std::array::from_fn(|i| Reg::new(HELD[i], fmt[i])),
            acc_valid: Signal::bit("acc_valid"),
            acc: [
                Signal::new("acc_drf", u3),
                Signal::new("acc_plane", u3),
                Signal::new("acc_u", uv),
                Signal::new("acc_v", uv),
                Signal::new("acc_lambda", Format::signed(14, 8)),
            ],
            walk: WALK
                .iter()
                .map(|&(n, w)| {
                    let r = Reg::new(n, Format::uint(w));
                    if n == "state" {
                        r.with_states(&STATES)
                    } else {
                        r
                    }
                })
                .collect(),
            busy: Reg::new("busy", Format::uint(5)),
            rd_value: Reg::new("rd_value", u8f),
            rd_slots: Reg::new("rd_slots", Format::uint(2)),
            px_acc: [
                Reg::new("accesses", Format::uint(4)),
                Reg::new("slots", Format::uint(5)),
                Reg::new("faults", Format::uint(4)),
            ],
            out_valid: Reg::new("out_valid", Format::uint(1)),
            out_colour: Reg::new("out_colour", u8f),
            out_error: Reg::new("out_error", Format::uint(1)),
            out_acc: [
                Reg::new("out_accesses", Format::uint(4)),
                Reg::new("out_slots", Format::uint(5)),
                Reg::new("out_faults", Format::uint(4)),
            ],
            access_error: None,
        })
    }

    /// Drives the pixel port (valid and fields).
    pub fn drive(&mut self, px: Option<&ChainRequest>) {
        self.req_valid.set_bool(px.is_some());
        if let Some(px) = px {
            for (s, x) in self.req.iter_mut().zip(raw_of(px)) {
                s.set_raw(x);
            }
        }
    }

    /// The result in the output registers (when `out_valid`).
    pub fn result(&self) -> ChainResult {
        let [a, s, f] = self.out_acc.each_ref().map(|r| r.q().bits() as u32);
        ChainResult {
            colour: self.out_colour.q().bits() as u8,
            accesses: a,
            slots: s,
            faults: f,
            error: self.out_error.q().is_high(),
        }
    }

    /// The walker's state.
    pub fn state(&self) -> State {
        State::from_bits(self.walk[0].q().bits())
    }

    /// The micro-program's next step for `px`: from its first DRF (`value` `None`) or after
    /// the access that gave `value`; with the output stage's colour at the chain's end.
    fn step(&self, px: &ChainRequest, w: Walk, value: Option<u8>) -> (Walk, Option<Fetch>, u8) {
        let prog = Program {
            file: &self.file,
            px,
            tab: &self.tab,
        };
        let (w, f) = match value {
            None => prog.begin(),
            Some(v) => prog.advance(w, v),
        };
        let colour = if w.state == State::Combine {
            prog.colour(&w)
        } else {
            0
        };
        (w, f, colour)
    }

    /// Sets the walk's next registers, the access to issue and, at the chain's end, the
    /// result (`colour`, 0 on an error). `counts`: the pixel's accesses, slots and faults.
    fn apply(&mut self, (w, f, colour): (Walk, Option<Fetch>, u8), mut counts: [u64; 3]) {
        for (r, x) in self.walk.iter_mut().zip(fields(&w)) {
            r.set_next_bits(x);
        }
        self.busy.set_next_bits(0);
        if let Some(f) = f {
            counts[0] += 1;
            self.acc_valid.set_bool(true);
            let raw = [f.drf.into(), f.plane.into(), f.u, f.v, f.lambda];
            for (s, x) in self.acc.iter_mut().zip(raw) {
                s.set_raw(i64::from(x));
            }
        }
        for (r, x) in self.px_acc.iter_mut().zip(counts) {
            r.set_next_bits(x);
        }
        let error = w.state == State::Error;
        if error || w.state == State::Combine {
            self.out_valid.set_next_bool(true);
            self.out_error.set_next_bool(error);
            self.out_colour.set_next_bits(u64::from(colour));
            for (r, x) in self.out_acc.iter_mut().zip(counts) {
                r.set_next_bits(x);
            }
        }
    }

    /// In the cycle a pixel's last access ends, the next pixel is taken if its first DRF
    /// reads the banks (its access then follows without a gap); one that would end at once
    /// (an unset DRF) waits for the next cycle, so that two results never meet.
    fn overlap(&mut self) {
        if !self.req_valid.is_high() {
            return;
        }
        let px = request_of(self.req.each_ref().map(|s| s.raw()));
        if self.step(&px, Walk::start(), None).1.is_some() {
            self.req_ready.set_bool(true);
            self.begin();
        }
    }

    /// A new pixel from the port: held, and its first DRF visited.
    fn begin(&mut self) {
        let raw = self.req.each_ref().map(|s| s.raw());
        for (r, x) in self.held.iter_mut().zip(raw) {
            r.set_next_raw(x);
        }
        let next = self.step(&request_of(raw), Walk::start(), None);
        self.apply(next, [0; 3]);
    }
}

impl<T: TexramAccess> Module for MapChain812<T> {
    fn kind(&self) -> &'static str {
        "walker_812"
    }

    fn eval(&mut self) {
        let st = self.state();
        self.acc_valid.set_bool(false);
        self.out_valid.set_next_bool(false);
        let idle = matches!(st, State::Idle | State::Combine | State::Error);
        self.req_ready.set_bool(idle);
        if idle {
            if self.req_valid.is_high() {
                self.begin();
            } else {
                self.walk[0].set_next_bits(State::Idle.bits());
            }
            return;
        }
        let slots = self.rd_slots.q().bits();
        let mut counts = self.px_acc.each_ref().map(|r| r.q().bits());
        if st.reads() {
            let busy = self.busy.q().bits() + 1;
            if busy < slots * u64::from(self.slot_cycles) {
                self.busy.set_next_bits(busy);
                return;
            }
            counts[1] += slots;
            counts[2] += u64::from(slots > 1);
        }
        let px = request_of(self.held.each_ref().map(|r| r.q().raw()));
        let w = walk_of(std::array::from_fn(|i| self.walk[i].q().bits()));
        let next = self.step(&px, w, Some(self.rd_value.q().bits() as u8));
        let done = matches!(next.0.state, State::Combine | State::Error);
        self.apply(next, counts);
        if done {
            self.overlap();
        }
    }

    fn tick(&mut self, reset: bool) {
        if !reset && self.acc_valid.is_high() {
            let [drf, plane, u, v, l] = self.acc.each_ref().map(|s| s.raw());
            let got = self
                .file
                .get(drf as u8)
                .filter(|d| (plane as usize) < d.plane_count())
                .ok_or_else(|| format!("drf {drf} plane {plane}: no such map"))
                .and_then(|d| {
                    self.texram
                        .access_with(&d.access(plane as usize), u as i32, v as i32, l as i32)
                });
            let (value, slots) = match got {
                Ok(r) => (r.value, r.slots.min(3)),
                Err(e) => {
                    self.access_error.get_or_insert(e);
                    (0, 1)
                }
            };
            self.rd_value.set_next_bits(u64::from(value));
            self.rd_slots.set_next_bits(u64::from(slots));
        }
        let regs = self.held.iter_mut().chain(&mut self.walk);
        let regs = regs.chain([&mut self.busy, &mut self.rd_value, &mut self.rd_slots]);
        let regs = regs.chain(&mut self.px_acc).chain(&mut self.out_acc);
        for r in regs.chain([
            &mut self.out_valid,
            &mut self.out_colour,
            &mut self.out_error,
        ]) {
            r.tick(reset);
        }
    }

    fn visit(&self, v: &mut dyn Visitor) {
        use crate::kernel::Dir;
        v.enter(self.instance(), self.kind());
        v.signal(Dir::Input, &self.req_valid);
        for s in &self.req {
            v.signal(Dir::Input, s);
        }
        v.signal(Dir::Output, &self.req_ready);
        v.signal(Dir::Output, &self.acc_valid);
        for s in &self.acc {
            v.signal(Dir::Output, s);
        }
        let regs = self.walk.iter().chain(&self.held);
        let regs = regs.chain([&self.busy, &self.rd_value, &self.rd_slots]);
        let regs = regs.chain(&self.px_acc).chain(&self.out_acc);
        for r in regs.chain([&self.out_valid, &self.out_colour, &self.out_error]) {
            v.reg(r);
        }
        v.leave();
    }
}

/// The micro-program over `texram`, access by access without a clock: the result and counts
/// the walker gives for `px` (what the clocked walker is held against).
pub fn walk_pixel<T: TexramAccess>(
    file: &DrfFile,
    texram: &mut T,
    px: &ChainRequest,
) -> Result<ChainResult, String> {
    let tab = *CubeFace::new().table();
    let prog = Program {
        file,
        px,
        tab: &tab,
    };
    let (mut w, mut f) = prog.begin();
    let mut res = ChainResult::default();
    // Seven DRFs of at most four states each: a walk ends well within MAX_STEPS.
    for _ in 0..MAX_STEPS {
        let value = match f {
            Some(f) => {
                let d = file.get(f.drf).ok_or("no drf")?;
                let r = texram.access_with(&d.access(f.plane.into()), f.u, f.v, f.lambda)?;
                res.accesses += 1;
                res.slots += r.slots;
                res.faults += u32::from(r.slots > 1);
                r.value
            }
            None if matches!(w.state, State::Combine | State::Error) => {
                res.error = w.state == State::Error;
                res.colour = if res.error { 0 } else { prog.colour(&w) };
                return Ok(res);
            }
            None => 0,
        };
        (w, f) = prog.advance(w, value);
    }
    Err(format!(
        "the micro-program did not end in {MAX_STEPS} steps"
    ))
}

/// The most steps [`walk_pixel`] takes before it calls the micro-program stuck.
const MAX_STEPS: usize = 64;
