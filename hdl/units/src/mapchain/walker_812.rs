//! The chain walker of the address and control unit 812 (section 14, Fig. 16), cycle by
//! cycle: a pixel port from the rasterizer, the micro-program of [`super::program`] as a
//! state machine whose state is named in the waveform, the banks behind [`TexramAccess`] as its
//! child [`BankPort810`] (scope `banks`) and the output stage 820.
//!
//! # Timing (\[C\]; the document gives the 30 ns slot and "a linked-map access will most
//! probably cause a page fault")
//! The clock is 5 ns. A pixel is taken in a cycle where `req_ready` is high (idle, the
//! cycle a result is out, or the last cycle of a pixel's last access). An access is staged on the bank port's `acc_*` in
//! the cycle the walker decides it and made at that clock edge; the walker stays in the access's state for
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
//! | `req_vx/vy/vz` | sQ1.14 (unit vector to the eye) |
//! | `req_face` | u3 |
//! | `req_id`, `req_is` | u8 |
//! | `out_colour` | u8 |

use super::bank_port_810::BankPort810;
use super::drf_812::DrfFile;
use super::program::{ChainRequest, Fetch, Program, State, Walk, STATES};
use crate::envmap::cube_face::CubeFace;
use crate::fx::Format;
use crate::kernel::declared::{Regs, Signals};
use crate::kernel::{Dir, Module, Payload, Reg, Regs, Signal, Stream, Visitor};
use crate::texram::{TexramAccess, UV_BITS};

/// The walk's registers ([`Walk`] as the walker holds it between cycles), `state` named by
/// [`STATES`] in the waveform.
#[derive(Clone, Debug, Regs)]
struct WalkRegs {
    state: Reg,
    drf: Reg,
    steps: Reg,
    deferred: Reg,
    to_refl: Reg,
    tex: Reg,
    refl: Reg,
    env: Reg,
    ou: Reg,
    ov: Reg,
    offsets: Reg,
    detail: Reg,
    tex_drf: Reg,
    refl_drf: Reg,
    env_drf: Reg,
    face: Reg,
    s: Reg,
    t: Reg,
}

impl WalkRegs {
    fn new() -> WalkRegs {
        let u = |name, bits| Reg::new(name, Format::uint(bits));
        WalkRegs {
            state: u("state", 4).with_states(&STATES),
            drf: u("drf", 3),
            steps: u("steps", 4),
            deferred: u("deferred", 1),
            to_refl: u("to_refl", 1),
            tex: u("tex", 8),
            refl: u("refl", 8),
            env: u("env", 8),
            ou: u("ou", 8),
            ov: u("ov", 8),
            offsets: u("offsets", 1),
            detail: u("detail", 8),
            tex_drf: u("tex_drf", 3),
            refl_drf: u("refl_drf", 3),
            env_drf: u("env_drf", 3),
            face: u("face", 3),
            s: u("s", 12),
            t: u("t", 12),
        }
    }

    /// The walk the registers hold.
    fn walk(&self) -> Walk {
        let b = |r: &Reg| r.q().bits() as u8;
        let f = |r: &Reg| r.q().is_high();
        Walk {
            state: State::from_bits(self.state.q().bits()),
            drf: b(&self.drf),
            steps: b(&self.steps),
            deferred: f(&self.deferred),
            to_refl: f(&self.to_refl),
            tex: b(&self.tex),
            refl: b(&self.refl),
            env: b(&self.env),
            ou: b(&self.ou),
            ov: b(&self.ov),
            offsets: f(&self.offsets),
            detail: b(&self.detail),
            tex_drf: b(&self.tex_drf),
            refl_drf: b(&self.refl_drf),
            env_drf: b(&self.env_drf),
            face: b(&self.face),
            s: self.s.q().bits() as u16,
            t: self.t.q().bits() as u16,
        }
    }

    /// `w` into the registers at the coming edge.
    fn set_next(&mut self, w: &Walk) {
        let b = |r: &mut Reg, x: u8| r.set_next_bits(u64::from(x));
        self.state.set_next_bits(w.state.bits());
        b(&mut self.drf, w.drf);
        b(&mut self.steps, w.steps);
        self.deferred.set_next_bool(w.deferred);
        self.to_refl.set_next_bool(w.to_refl);
        b(&mut self.tex, w.tex);
        b(&mut self.refl, w.refl);
        b(&mut self.env, w.env);
        b(&mut self.ou, w.ou);
        b(&mut self.ov, w.ov);
        self.offsets.set_next_bool(w.offsets);
        b(&mut self.detail, w.detail);
        b(&mut self.tex_drf, w.tex_drf);
        b(&mut self.refl_drf, w.refl_drf);
        b(&mut self.env_drf, w.env_drf);
        b(&mut self.face, w.face);
        self.s.set_next_bits(u64::from(w.s));
        self.t.set_next_bits(u64::from(w.t));
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

/// A field of the pixel: its name (the command line's column), its port's name, its format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelField {
    pub name: &'static str,
    pub port: &'static str,
    pub fmt: Format,
}

/// The rasterizer's pixel, each field once with its name and format: `Pixel<Signal>` is the
/// walker's port (`req_drf` ...), `Pixel<Reg>` the pixel it holds while walking (scope
/// `pixel`), `Pixel<PixelField>` ([`Pixel::fields`]) the names and formats alone, which the
/// command line reads its columns by.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Pixel<S> {
    /// The leading DRF, u3.
    pub drf: S,
    /// sQ12.8, sQ12.8, sQ5.8.
    pub u: S,
    pub v: S,
    pub lambda: S,
    /// The perturbed normal n_b of eq. 3, sQ2.14.
    pub n: [S; 3],
    /// The unit vector to the eye, sQ1.14.
    pub eye: [S; 3],
    /// u3, the face when an environment DRF has no `new_coords`.
    pub face: S,
    /// Diffuse illumination and external specular term, u8.
    pub i_d: S,
    pub i_s: S,
}

impl Pixel<PixelField> {
    /// Every field's name, port name and format.
    pub fn fields() -> Pixel<PixelField> {
        let uv = Format::signed(UV_BITS, 8);
        let (nf, ef) = (Format::signed(17, 14), Format::signed(16, 14));
        let (u3, u8f) = (Format::uint(3), Format::uint(8));
        let f = |name, port, fmt| PixelField { name, port, fmt };
        Pixel {
            drf: f("drf", "req_drf", u3),
            u: f("u", "req_u", uv),
            v: f("v", "req_v", uv),
            lambda: f("lambda", "req_lambda", Format::signed(14, 8)),
            n: [
                f("nx", "req_nx", nf),
                f("ny", "req_ny", nf),
                f("nz", "req_nz", nf),
            ],
            eye: [
                f("vx", "req_vx", ef),
                f("vy", "req_vy", ef),
                f("vz", "req_vz", ef),
            ],
            face: f("face", "req_face", u3),
            i_d: f("id", "req_id", u8f),
            i_s: f("is", "req_is", u8f),
        }
    }
}

impl<S> Pixel<S> {
    /// Each field, in order.
    pub fn each(&self) -> [&S; 13] {
        let [nx, ny, nz] = &self.n;
        let [ex, ey, ez] = &self.eye;
        [
            &self.drf,
            &self.u,
            &self.v,
            &self.lambda,
            nx,
            ny,
            nz,
            ex,
            ey,
            ez,
            &self.face,
            &self.i_d,
            &self.i_s,
        ]
    }

    /// Each field, in order, to change.
    pub fn each_mut(&mut self) -> [&mut S; 13] {
        let [nx, ny, nz] = &mut self.n;
        let [ex, ey, ez] = &mut self.eye;
        [
            &mut self.drf,
            &mut self.u,
            &mut self.v,
            &mut self.lambda,
            nx,
            ny,
            nz,
            ex,
            ey,
            ez,
            &mut self.face,
            &mut self.i_d,
            &mut self.i_s,
        ]
    }

    /// The same pixel with each field mapped by `f`.
    pub fn map<T>(&self, mut f: impl FnMut(&S) -> T) -> Pixel<T> {
        Pixel {
            drf: f(&self.drf),
            u: f(&self.u),
            v: f(&self.v),
            lambda: f(&self.lambda),
            n: self.n.each_ref().map(&mut f),
            eye: self.eye.each_ref().map(&mut f),
            face: f(&self.face),
            i_d: f(&self.i_d),
            i_s: f(&self.i_s),
        }
    }
}

impl Pixel<i64> {
    /// The request the raw fields make.
    pub fn request(&self) -> ChainRequest {
        ChainRequest {
            drf: self.drf as u8,
            u: self.u as i32,
            v: self.v as i32,
            lambda: self.lambda as i32,
            n: self.n,
            eye: self.eye,
            face: self.face as u8,
            i_d: self.i_d as u8,
            i_s: self.i_s as u8,
        }
    }

    /// The raw fields of `r`.
    pub fn of(r: &ChainRequest) -> Pixel<i64> {
        Pixel {
            drf: r.drf.into(),
            u: r.u.into(),
            v: r.v.into(),
            lambda: r.lambda.into(),
            n: r.n,
            eye: r.eye,
            face: r.face.into(),
            i_d: r.i_d.into(),
            i_s: r.i_s.into(),
        }
    }
}

/// The pixel port carries a request: each field raw on its signal.
impl Payload<Pixel<Signal>> for ChainRequest {
    fn put(&self, port: &mut Pixel<Signal>) {
        let raw = Pixel::of(self);
        for (s, x) in port.each_mut().into_iter().zip(raw.each()) {
            s.set_raw(*x);
        }
    }
    fn take(port: &Pixel<Signal>) -> ChainRequest {
        port.map(Signal::raw).request()
    }
}

impl Signals for Pixel<Signal> {
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        self.each().into_iter().for_each(|s| v.signal(dir, s));
    }
}

impl Regs for Pixel<Reg> {
    fn tick_regs(&mut self, reset: bool) {
        self.each_mut().into_iter().for_each(|r| r.tick(reset));
    }
    fn visit_regs(&self, v: &mut dyn Visitor) {
        v.enter("pixel", "pixel");
        self.each().into_iter().for_each(|r| v.reg(r));
        v.leave();
    }
}

/// A pixel's access, slot and fault counts.
#[derive(Clone, Debug, Regs)]
struct Counts {
    accesses: Reg,
    slots: Reg,
    faults: Reg,
}

impl Counts {
    fn new(accesses: &'static str, slots: &'static str, faults: &'static str) -> Counts {
        Counts {
            accesses: Reg::new(accesses, Format::uint(4)),
            slots: Reg::new(slots, Format::uint(5)),
            faults: Reg::new(faults, Format::uint(4)),
        }
    }

    fn get(&self) -> [u64; 3] {
        [&self.accesses, &self.slots, &self.faults].map(|r| r.q().bits())
    }

    fn set_next(&mut self, [a, s, f]: [u64; 3]) {
        self.accesses.set_next_bits(a);
        self.slots.set_next_bits(s);
        self.faults.set_next_bits(f);
    }
}

/// The walker with the banks it reads through.
#[derive(Clone, Module)]
#[module(kind = "walker_812")]
pub struct MapChain812<T: TexramAccess> {
    /// The pixel port: `req_valid`, the pixel's fields, `req_ready`.
    #[input]
    pub req: Stream<Pixel<Signal>>,
    #[reg]
    walk: WalkRegs,
    /// The pixel being walked.
    #[reg]
    held: Pixel<Reg>,
    #[reg]
    busy: Reg,
    /// The pixel's counts so far.
    #[reg]
    px_acc: Counts,
    #[reg]
    pub out_valid: Reg,
    #[reg]
    pub out_colour: Reg,
    #[reg]
    pub out_error: Reg,
    /// The counts of the result out.
    #[reg]
    out_acc: Counts,
    /// The banks, with the access port the walker drives and the value and slots it reads.
    #[child]
    pub banks: BankPort810<T>,
    tab: [u64; 64],
    slot_cycles: u32,
}

impl<T: TexramAccess> MapChain812<T> {
    /// The walker over `texram`, whose maps the DRFs of `file` describe (loaded already).
    pub fn new(file: DrfFile, texram: T, slot_cycles: u32) -> Result<MapChain812<T>, String> {
        file.validate()?;
        crate::pages::page_registers_824::check_slot_cycles(slot_cycles)?;
        let fields = Pixel::fields();
        Ok(MapChain812 {
            req: Stream::new(
                "req_valid",
                "req_ready",
                fields.map(|f| Signal::new(f.port, f.fmt)),
            ),
            walk: WalkRegs::new(),
            held: fields.map(|f| Reg::new(f.name, f.fmt)),
            busy: Reg::new("busy", Format::uint(5)),
            px_acc: Counts::new("accesses", "slots", "faults"),
            out_valid: Reg::new("out_valid", Format::uint(1)),
            out_colour: Reg::new("out_colour", Format::uint(8)),
            out_error: Reg::new("out_error", Format::uint(1)),
            out_acc: Counts::new("out_accesses", "out_slots", "out_faults"),
            banks: BankPort810::new(file, texram, fields.lambda.fmt),
            tab: *CubeFace::new().table(),
            slot_cycles,
        })
    }

    /// The result in the output registers (when `out_valid`).
    pub fn result(&self) -> ChainResult {
        let [a, s, f] = self.out_acc.get().map(|x| x as u32);
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
        State::from_bits(self.walk.state.q().bits())
    }

    /// The micro-program's next step for `px`: from its first DRF (`value` `None`) or after
    /// the access that gave `value`; with the output stage's colour at the chain's end.
    fn step(&self, px: &ChainRequest, w: Walk, value: Option<u8>) -> (Walk, Option<Fetch>, u8) {
        let prog = Program {
            file: self.banks.file(),
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
        self.walk.set_next(&w);
        self.busy.set_next_bits(0);
        if let Some(f) = f {
            counts[0] += 1;
            let a = &mut self.banks.acc;
            a.valid.set_bool(true);
            a.drf.set_raw(f.drf.into());
            a.plane.set_raw(f.plane.into());
            a.u.set_raw(f.u.into());
            a.v.set_raw(f.v.into());
            a.lambda.set_raw(f.lambda.into());
        }
        self.px_acc.set_next(counts);
        let error = w.state == State::Error;
        if error || w.state == State::Combine {
            self.out_valid.set_next_bool(true);
            self.out_error.set_next_bool(error);
            self.out_colour.set_next_bits(u64::from(colour));
            self.out_acc.set_next(counts);
        }
    }

    /// The pixel on the port.
    fn port_pixel(&self) -> ChainRequest {
        ChainRequest::take(&self.req.payload)
    }

    /// In the cycle a pixel's last access ends, the next pixel is taken if its first DRF
    /// reads the banks (its access then follows without a gap); one that would end at once
    /// (an unset DRF) waits for the next cycle, so that two results never meet.
    fn overlap(&mut self) {
        if !self.req.valid.is_high() {
            return;
        }
        if self
            .step(&self.port_pixel(), Walk::start(), None)
            .1
            .is_some()
        {
            self.req.ready.set_bool(true);
            self.begin();
        }
    }

    /// A new pixel from the port: held, and its first DRF visited.
    fn begin(&mut self) {
        for (r, s) in self
            .held
            .each_mut()
            .into_iter()
            .zip(self.req.payload.each())
        {
            r.set_next_raw(s.raw());
        }
        let next = self.step(&self.port_pixel(), Walk::start(), None);
        self.apply(next, [0; 3]);
    }
}

impl<T: TexramAccess> MapChain812<T> {
    fn eval(&mut self) {
        let st = self.state();
        self.banks.acc.valid.set_bool(false);
        self.out_valid.set_next_bool(false);
        let idle = matches!(st, State::Idle | State::Combine | State::Error);
        self.req.ready.set_bool(idle);
        if idle {
            if self.req.valid.is_high() {
                self.begin();
            } else {
                self.walk.state.set_next_bits(State::Idle.bits());
            }
            return;
        }
        let slots = self.banks.rd_slots.q().bits();
        let mut counts = self.px_acc.get();
        if st.reads() {
            let busy = self.busy.q().bits() + 1;
            if busy < slots * u64::from(self.slot_cycles) {
                self.busy.set_next_bits(busy);
                return;
            }
            counts[1] += slots;
            counts[2] += u64::from(slots > 1);
        }
        let px = self.held.map(|r| r.q().raw()).request();
        let next = self.step(
            &px,
            self.walk.walk(),
            Some(self.banks.rd_value.q().bits() as u8),
        );
        let done = matches!(next.0.state, State::Combine | State::Error);
        self.apply(next, counts);
        if done {
            self.overlap();
        }
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
