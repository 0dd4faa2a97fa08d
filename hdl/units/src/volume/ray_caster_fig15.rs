//! The TEXRAM as a ray-casting machine (section 13, Figure 15), cycle by cycle: a ray port
//! (start point, step, number of samples), the 3-D stepper (`p_k = p_0 + k dp`, exact in
//! sQ.12), the access sequencer (2 accesses a resample point in value mode, 8 in gradient
//! mode, each reading four voxels from the four level-0 banks through their page registers
//! 824: one 30 ns slot, two when a bank has another row open), and the interpolator, whose
//! result leaves with the point's last access.
//!
//! # Timing
//! A ray is taken when the caster is idle (`ray_ready`); its first access starts the next
//! cycle; accesses follow back to back (`slot_cycles` cycles a slot); a sample's result is in
//! the output registers the cycle after its last access ends. Counters: `accesses`, `slots`,
//! `fault_slots`, `bank_misses`, `samples`.
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `ray_x`, `ray_y`, `ray_z`, `ray_dx`, `ray_dy`, `ray_dz` | sQ9.12 |
//! | `ray_steps` | u16, samples of the ray |
//! | stepper position | sQ19.12 (32 bits): a ray's points and the position after its last one must lie inside, `\|p + steps d\| < 2^19` voxels per component ([`RayCaster::ray_fits`]; 1100 steps of up to 476 voxels, 65535 of up to 8) |
//! | `out_x`, `out_y`, `out_z` | sQ19.12, the sample's point |
//! | `out_value` | u8 |
//! | `out_gx`, `out_gy`, `out_gz` | sQ9.4 (gradient mode; 0 in value mode) |

use super::interp::{gradient, value, weights, GRAD_FRAC};
use super::layout::{access_order, access_voxels, locate, Mode, VolumeParams, POS_BITS, POS_FRAC};
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::signals;

const OPEN_NAMES: [&str; 4] = ["open0", "open1", "open2", "open3"];

/// The ray caster with its voxel store.
#[derive(Clone, Debug)]
pub struct RayCaster {
    name: String,
    p: VolumeParams,
    mode: Mode,
    banks: Vec<Vec<u8>>,
    pub ray_valid: Signal,
    pub ray_ready: Signal,
    pub ray_p: [Signal; 3],
    pub ray_d: [Signal; 3],
    pub ray_steps: Signal,
    /// Stepper: the point, the step, samples left, the sample's index, the ray's.
    pos: [Reg; 3],
    step: [Reg; 3],
    left: Reg,
    k: Reg,
    ray: Reg,
    /// Sequencer: the access under way (index), cycles left in it, its page fault.
    acc: Reg,
    slot_left: Reg,
    fault: Reg,
    /// Page registers 824 of banks 0-3: open row plus one (0: closed).
    open: Vec<Reg>,
    /// The voxels read so far for the point (`buf[4a + t]`), and those arriving this cycle.
    buf: [u8; 32],
    buf_next: [u8; 32],
    pub out_valid: Reg,
    pub out_ray: Reg,
    pub out_k: Reg,
    pub out_p: [Reg; 3],
    pub out_value: Reg,
    pub out_g: [Reg; 3],
    pub accesses: Reg,
    pub slots: Reg,
    pub fault_slots: Reg,
    pub bank_misses: Reg,
    pub samples: Reg,
}

impl RayCaster {
    /// Whether a ray from `p` by `d` (raw sQ.12) for `steps` samples keeps the stepper in its
    /// 32-bit range: its points and the position after the last (which the stepper computes)
    /// lie in `-2^31..2^31` raw, each component. The port takes only such rays.
    pub fn ray_fits(p: [i32; 3], d: [i32; 3], steps: u16) -> bool {
        let range = i64::from(i32::MIN)..=i64::from(i32::MAX);
        (0..3).all(|c| range.contains(&(i64::from(p[c]) + i64::from(steps) * i64::from(d[c]))))
    }

    /// The caster over `voxels` (x fastest, then y, then z) of volume `p`, in `mode`.
    pub fn new(p: VolumeParams, mode: Mode, voxels: &[u8]) -> Result<RayCaster, String> {
        p.validate()?;
        let (nx, ny, nz) = p.dims;
        let n = (nx * ny * nz) as usize;
        if voxels.len() != n {
            return Err(format!(
                "{} voxels for a {nx}x{ny}x{nz} volume ({n})",
                voxels.len()
            ));
        }
        let mut banks = vec![vec![0u8; p.words() as usize]; 4];
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let (b, w) = locate(&p, x, y, z);
                    banks[b][w as usize] = voxels[((z * ny + y) * nx + x) as usize];
                }
            }
        }
        let pos = Format::signed(POS_BITS, POS_FRAC as i32);
        let wide = Format::signed(32, POS_FRAC as i32);
        let grad = Format::signed(9 + GRAD_FRAC + 1, GRAD_FRAC as i32);
        let count = |n| Reg::new(n, Format::uint(40));
        Ok(RayCaster {
            name: "ray_caster_fig15".into(),
            p,
            mode,
            banks,
            ray_valid: Signal::bit("ray_valid"),
            ray_ready: Signal::bit("ray_ready"),
            ray_p: ["ray_x", "ray_y", "ray_z"].map(|n| Signal::new(n, pos)),
            ray_d: ["ray_dx", "ray_dy", "ray_dz"].map(|n| Signal::new(n, pos)),
            ray_steps: Signal::new("ray_steps", Format::uint(16)),
            pos: ["x", "y", "z"].map(|n| Reg::new(n, wide)),
            step: ["dx", "dy", "dz"].map(|n| Reg::new(n, wide)),
            left: Reg::new("left", Format::uint(16)),
            k: Reg::new("k", Format::uint(16)),
            ray: Reg::new("ray", Format::uint(32)),
            acc: Reg::new("acc", Format::uint(3)),
            slot_left: Reg::new("slot_left", Format::uint(5)),
            fault: Reg::new("fault", Format::uint(1)),
            open: OPEN_NAMES
                .iter()
                .map(|n| Reg::new(n, Format::uint(18)))
                .collect(),
            buf: [0; 32],
            buf_next: [0; 32],
            out_valid: Reg::new("out_valid", Format::uint(1)),
            out_ray: Reg::new("out_ray", Format::uint(32)),
            out_k: Reg::new("out_k", Format::uint(16)),
            out_p: ["out_x", "out_y", "out_z"].map(|n| Reg::new(n, wide)),
            out_value: Reg::new("out_value", Format::uint(8)),
            out_g: ["out_gx", "out_gy", "out_gz"].map(|n| Reg::new(n, grad)),
            accesses: count("accesses"),
            slots: count("slots"),
            fault_slots: count("fault_slots"),
            bank_misses: count("bank_misses"),
            samples: count("samples"),
        })
    }

    /// The same caster under another instance name (several chips in one design).
    pub fn named(mut self, name: &str) -> RayCaster {
        self.name = name.into();
        self
    }

    /// The access in place `n` of sample `k`'s order, of the point `pos` (raw sQ.12),
    /// starts: its four voxels into the buffer, the page registers, its slots.
    fn start_access(&mut self, n: usize, k: u64, pos: [i64; 3]) {
        let a = access_order(self.mode, k)[n];
        let ijk = (pos[0] >> POS_FRAC, pos[1] >> POS_FRAC, pos[2] >> POS_FRAC);
        let mut missed = 0u64;
        for (t, (x, y, z)) in access_voxels(&self.p, a, ijk).into_iter().enumerate() {
            let (b, w) = locate(&self.p, x, y, z);
            self.buf_next[4 * a + t] = self.banks[b][w as usize];
            let row = u64::from(w / self.p.row_words) + 1;
            if self.open[b].q().bits() != row {
                missed += 1;
                self.open[b].set_next_bits(row);
            }
        }
        let slots = 1 + u64::from(missed > 0);
        self.acc.set_next_bits(n as u64);
        self.slot_left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        self.fault.set_next_bool(missed > 0);
        let add = |r: &mut Reg, n: u64| r.set_next_bits(r.q().bits() + n);
        add(&mut self.accesses, 1);
        add(&mut self.slots, slots);
        add(&mut self.fault_slots, slots - 1);
        add(&mut self.bank_misses, missed);
    }

    /// The point's last access ended: its result into the output registers.
    fn finish_point(&mut self, pos: [i64; 3]) {
        let frac = |p: i64| ((p & ((1 << POS_FRAC) - 1)) >> (POS_FRAC - 8)) as u8;
        let w = weights(frac(pos[0]), frac(pos[1]), frac(pos[2]));
        self.out_valid.set_next_bool(true);
        self.out_ray.set_next_bits(self.ray.q().bits());
        self.out_k.set_next_bits(self.k.q().bits());
        for (r, x) in self.out_p.iter_mut().zip(pos) {
            r.set_next_raw(x);
        }
        self.out_value
            .set_next_bits(u64::from(value(&self.buf, &w)));
        let g = match self.mode {
            Mode::Value => [0; 3],
            Mode::Gradient => gradient(&self.buf, &w),
        };
        for (r, x) in self.out_g.iter_mut().zip(g) {
            r.set_next_raw(x);
        }
        self.samples.set_next_bits(self.samples.q().bits() + 1);
    }

    /// A ray taken from the port.
    fn take_ray(&mut self) {
        for (r, s) in self.pos.iter_mut().zip(&self.ray_p) {
            r.set_next_raw(s.raw());
        }
        for (r, s) in self.step.iter_mut().zip(&self.ray_d) {
            r.set_next_raw(s.raw());
        }
        self.left.set_next_bits(self.ray_steps.bits());
        self.k.set_next_bits(0);
        self.ray.set_next_bits(self.ray.q().bits() + 1);
        self.slot_left.set_next_bits(0);
    }
}

impl Module for RayCaster {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "ray_caster_fig15"
    }
    fn eval(&mut self) {
        self.buf_next = self.buf;
        self.out_valid.set_next_bool(false);
        let left = self.left.q().bits();
        let busy = left > 0;
        self.ray_ready.set_bool(!busy);
        if !busy {
            if self.ray_valid.is_high() {
                self.take_ray();
            }
            return;
        }
        let pos = self.pos.each_ref().map(|r| r.q().raw());
        let slot_left = self.slot_left.q().bits();
        let n = self.acc.q().bits() as usize;
        let k = self.k.q().bits();
        if slot_left == 0 {
            // A ray's first access.
            self.start_access(0, k, pos);
        } else if slot_left > 1 {
            self.slot_left.set_next_bits(slot_left - 1);
        } else if n + 1 < self.mode.accesses() {
            self.start_access(n + 1, k, pos);
        } else {
            // The point is done; the next one's first access starts now.
            self.finish_point(pos);
            let next: [i64; 3] = std::array::from_fn(|c| pos[c] + self.step[c].q().raw());
            for (r, x) in self.pos.iter_mut().zip(next) {
                r.set_next_raw(x);
            }
            self.left.set_next_bits(left - 1);
            self.k.set_next_bits(self.k.q().bits() + 1);
            if left > 1 {
                self.start_access(0, k + 1, next);
            } else {
                self.slot_left.set_next_bits(0);
            }
        }
    }
    fn tick(&mut self, reset: bool) {
        self.buf = if reset { [0; 32] } else { self.buf_next };
        let regs = self
            .pos
            .iter_mut()
            .chain(self.step.iter_mut())
            .chain(self.out_p.iter_mut())
            .chain(self.out_g.iter_mut())
            .chain(self.open.iter_mut());
        for r in regs {
            r.tick(reset);
        }
        for r in [
            &mut self.left,
            &mut self.k,
            &mut self.ray,
            &mut self.acc,
            &mut self.slot_left,
            &mut self.fault,
            &mut self.out_valid,
            &mut self.out_ray,
            &mut self.out_k,
            &mut self.out_value,
            &mut self.accesses,
            &mut self.slots,
            &mut self.fault_slots,
            &mut self.bank_misses,
            &mut self.samples,
        ] {
            r.tick(reset);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        let [px, py, pz] = &self.ray_p;
        let [dx, dy, dz] = &self.ray_d;
        signals!(v;
            Input: self.ray_valid, px, py, pz, dx, dy, dz, self.ray_steps;
            Output: self.ray_ready);
        v.enter("stepper", "volume_stepper");
        for r in self.pos.iter().chain(&self.step) {
            v.reg(r);
        }
        signals!(v; Reg: self.left, self.k, self.ray);
        v.leave();
        v.enter("page_registers_824", "page_registers_824");
        for r in &self.open {
            v.reg(r);
        }
        signals!(v; Reg: self.acc, self.slot_left, self.fault, self.accesses, self.slots,
            self.fault_slots, self.bank_misses);
        v.leave();
        v.enter("trilinear_818", "trilinear_818");
        signals!(v; Reg: self.out_valid, self.out_ray, self.out_k, self.out_value, self.samples);
        for r in self.out_p.iter().chain(&self.out_g) {
            v.reg(r);
        }
        v.leave();
        v.leave();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Sim;

    /// What one ray (taken in cycle 0) showed at the pins and in the sequencer: the cycles
    /// its samples came out, the cycles `fault` was high.
    struct Seen {
        outs: Vec<u64>,
        fault_cycles: u64,
    }

    /// One ray of `steps` samples from `p` by `d` (raw sQ.12) through a 16 x 16 x 16 volume
    /// with `slot_cycles`, in `mode`.
    fn one_ray(
        mode: Mode,
        slot_cycles: u32,
        p: [i64; 3],
        d: [i64; 3],
        steps: u64,
    ) -> (Sim<RayCaster>, Seen) {
        let mut vp = VolumeParams::new(16, 16, 16);
        vp.slot_cycles = slot_cycles;
        let vox: Vec<u8> = (0..16 * 16 * 16).map(|n| (n * 7 % 251) as u8).collect();
        let mut sim = Sim::new(RayCaster::new(vp, mode, &vox).unwrap());
        sim.reset(1);
        let mut seen = Seen {
            outs: Vec::new(),
            fault_cycles: 0,
        };
        for c in 0..20_000u64 {
            let dut = &mut sim.dut;
            dut.ray_valid.set_bool(c == 0);
            for k in 0..3 {
                dut.ray_p[k].set_raw(p[k]);
                dut.ray_d[k].set_raw(d[k]);
            }
            dut.ray_steps.set_bits(steps);
            sim.eval();
            let dut = &sim.dut;
            assert!(
                c > 0 || dut.ray_ready.is_high(),
                "an idle caster takes the ray"
            );
            if dut.out_valid.q().is_high() {
                seen.outs.push(c);
            }
            seen.fault_cycles += u64::from(dut.fault.q().is_high());
            sim.tick();
            if seen.outs.len() as u64 == steps {
                break;
            }
        }
        (sim, seen)
    }

    /// The sequencer's timing over one ray, in both modes and two slot lengths: the last
    /// sample leaves `2 + slot_cycles x slots` cycles after the ray was taken (a cycle to start
    /// the first access, `slot_cycles` a slot, two slots for an access that opens a row, a
    /// cycle to register the result), and `fault` is high through exactly the faulting
    /// accesses' two slots each (`fault_slots` counts one each); `samples` counts the samples.
    /// The ray crosses rows, so some accesses fault and most do not.
    #[test]
    fn samples_leave_slot_cycles_a_slot_and_fault_marks_the_row_openings() {
        let (p, d) = ([1 << 12, 2 << 12, 3 << 12], [1 << 12, 1 << 11, 3 << 10]);
        for (mode, sc) in [(Mode::Value, 6), (Mode::Gradient, 6), (Mode::Value, 3)] {
            let (sim, s) = one_ray(mode, sc, p, d, 10);
            let r = |r: &Reg| r.q().bits();
            let dut = &sim.dut;
            let (slots, faults) = (r(&dut.slots), r(&dut.fault_slots));
            assert_eq!(r(&dut.samples), 10, "{mode:?}");
            assert_eq!(r(&dut.accesses), 10 * mode.accesses() as u64, "{mode:?}");
            assert_eq!(slots, r(&dut.accesses) + faults, "{mode:?}");
            assert!(0 < faults && faults < 10, "{mode:?}: {faults} faults");
            let sc = u64::from(sc);
            assert_eq!(s.outs.len(), 10);
            assert_eq!(s.outs[9], 2 + sc * slots, "{mode:?}, {sc} cycles a slot");
            assert_eq!(
                s.fault_cycles,
                2 * sc * faults,
                "{mode:?}, {sc} cycles a slot"
            );
        }
    }
}
