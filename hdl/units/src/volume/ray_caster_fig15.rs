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
use crate::kernel::{Module, Reg, Signal, Signals};
use crate::pages::page_registers_824::PageRegisters824;

/// The voxel buffer's registers: `voxel{4a + t}` is voxel `t` of access `a`.
const VOXEL_NAMES: [&str; 32] = [
    "voxel0", "voxel1", "voxel2", "voxel3", "voxel4", "voxel5", "voxel6", "voxel7", "voxel8",
    "voxel9", "voxel10", "voxel11", "voxel12", "voxel13", "voxel14", "voxel15", "voxel16",
    "voxel17", "voxel18", "voxel19", "voxel20", "voxel21", "voxel22", "voxel23", "voxel24",
    "voxel25", "voxel26", "voxel27", "voxel28", "voxel29", "voxel30", "voxel31",
];

/// The 3-D stepper's registers: the point, the step, samples left, the sample's index, the
/// ray's. Written by the caster's sequencer.
#[derive(Clone, Debug, Module)]
#[module(kind = "volume_stepper", instance = "stepper")]
pub struct Stepper {
    #[reg]
    pos: [Reg; 3],
    #[reg]
    step: [Reg; 3],
    #[reg]
    left: Reg,
    #[reg]
    k: Reg,
    #[reg]
    ray: Reg,
}

impl Stepper {
    fn eval(&mut self) {}
}

/// The access sequencer's registers: the access under way (index), cycles left in it, its
/// page fault, the voxels read so far for the point, and the counters.
#[derive(Clone, Debug, Module)]
#[module(kind = "access_sequencer", instance = "sequencer")]
pub struct Sequencer {
    #[reg]
    acc: Reg,
    #[reg]
    slot_left: Reg,
    #[reg]
    pub fault: Reg,
    #[reg]
    voxels: [Reg; 32],
    #[reg]
    pub accesses: Reg,
    #[reg]
    pub slots: Reg,
    #[reg]
    pub fault_slots: Reg,
    #[reg]
    pub bank_misses: Reg,
}

impl Sequencer {
    fn eval(&mut self) {}
}

/// The interpolator 818's output registers: a sample, valid one cycle, and the count.
#[derive(Clone, Debug, Module)]
#[module(kind = "trilinear_818")]
pub struct Sample818 {
    #[reg]
    pub valid: Reg,
    #[reg]
    pub ray: Reg,
    #[reg]
    pub k: Reg,
    #[reg]
    pub value: Reg,
    #[reg]
    pub samples: Reg,
    #[reg]
    pub p: [Reg; 3],
    #[reg]
    pub g: [Reg; 3],
}

impl Sample818 {
    fn eval(&mut self) {}
}

/// The ray port: a ray from `p` by `d` (each sQ9.12) for `steps` samples (u16), offered
/// with `valid`, taken when the caster is ready.
#[derive(Clone, Debug, Signals)]
pub struct RayIn {
    pub valid: Signal,
    pub p: [Signal; 3],
    pub d: [Signal; 3],
    pub steps: Signal,
}

impl RayIn {
    fn new() -> RayIn {
        let pos = Format::signed(POS_BITS, POS_FRAC as i32);
        RayIn {
            valid: Signal::bit("ray_valid"),
            p: ["ray_x", "ray_y", "ray_z"].map(|n| Signal::new(n, pos)),
            d: ["ray_dx", "ray_dy", "ray_dz"].map(|n| Signal::new(n, pos)),
            steps: Signal::new("ray_steps", Format::uint(16)),
        }
    }

    /// Drives this port from `from` (a group of casters sharing one ray port).
    pub fn follow(&mut self, from: &RayIn) {
        self.valid.follow(&from.valid);
        for c in 0..3 {
            self.p[c].follow(&from.p[c]);
            self.d[c].follow(&from.d[c]);
        }
        self.steps.follow(&from.steps);
    }
}

/// The ray caster with its voxel store.
#[derive(Clone, Debug, Module)]
#[module(kind = "ray_caster_fig15")]
pub struct RayCaster {
    #[instance]
    name: &'static str,
    p: VolumeParams,
    mode: Mode,
    /// The voxel store: level 0 of banks 0-3, loaded by the host.
    banks: Vec<Vec<u8>>,
    #[input]
    pub ray: RayIn,
    #[output]
    pub ray_ready: Signal,
    #[child]
    stepper: Stepper,
    /// Page registers 824 of banks 0-3.
    #[child]
    pages: PageRegisters824,
    #[child]
    pub seq: Sequencer,
    #[child]
    pub out: Sample818,
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
        Ok(RayCaster {
            name: "ray_caster_fig15",
            p,
            mode,
            banks,
            ray: RayIn::new(),
            ray_ready: Signal::bit("ray_ready"),
            stepper: Stepper::new(),
            pages: PageRegisters824::new(4, 18),
            seq: Sequencer::new(),
            out: Sample818::new(),
        })
    }

    /// The same caster under another instance name (several chips in one design).
    pub fn named(mut self, name: &'static str) -> RayCaster {
        self.name = name;
        self
    }

    /// The access in place `n` of sample `k`'s order, of the point `pos` (raw sQ.12),
    /// starts: its four voxels into the buffer, the page registers, its slots.
    fn start_access(&mut self, n: usize, k: u64, pos: [i64; 3]) {
        let a = access_order(self.mode, k)[n];
        let ijk = (pos[0] >> POS_FRAC, pos[1] >> POS_FRAC, pos[2] >> POS_FRAC);
        let mut rows = [(0, 0); 4];
        let seq = &mut self.seq;
        for (t, (x, y, z)) in access_voxels(&self.p, a, ijk).into_iter().enumerate() {
            let (b, w) = locate(&self.p, x, y, z);
            seq.voxels[4 * a + t].set_next_bits(u64::from(self.banks[b][w as usize]));
            rows[t] = (b, u64::from(w / self.p.row_words));
        }
        let cost = self.pages.round(rows);
        let slots = u64::from(cost.slots);
        seq.acc.set_next_bits(n as u64);
        seq.slot_left
            .set_next_bits(slots * u64::from(self.p.slot_cycles));
        seq.fault.set_next_bool(cost.faults > 0);
        let add = |r: &mut Reg, n: u64| r.set_next_bits(r.q().bits() + n);
        add(&mut seq.accesses, 1);
        add(&mut seq.slots, slots);
        add(&mut seq.fault_slots, slots - 1);
        add(&mut seq.bank_misses, u64::from(cost.faults));
    }

    /// The point's last access ended: its result into the output registers.
    fn finish_point(&mut self, pos: [i64; 3]) {
        let frac = |p: i64| ((p & ((1 << POS_FRAC) - 1)) >> (POS_FRAC - 8)) as u8;
        let w = weights(frac(pos[0]), frac(pos[1]), frac(pos[2]));
        let buf = self.seq.voxels.each_ref().map(|r| r.q().bits() as u8);
        let out = &mut self.out;
        out.valid.set_next_bool(true);
        out.ray.set_next_bits(self.stepper.ray.q().bits());
        out.k.set_next_bits(self.stepper.k.q().bits());
        for (r, x) in out.p.iter_mut().zip(pos) {
            r.set_next_raw(x);
        }
        out.value.set_next_bits(u64::from(value(&buf, &w)));
        let g = match self.mode {
            Mode::Value => [0; 3],
            Mode::Gradient => gradient(&buf, &w),
        };
        for (r, x) in out.g.iter_mut().zip(g) {
            r.set_next_raw(x);
        }
        out.samples.set_next_bits(out.samples.q().bits() + 1);
    }

    /// A ray taken from the port.
    fn take_ray(&mut self) {
        let st = &mut self.stepper;
        for (r, s) in st.pos.iter_mut().zip(&self.ray.p) {
            r.set_next_raw(s.raw());
        }
        for (r, s) in st.step.iter_mut().zip(&self.ray.d) {
            r.set_next_raw(s.raw());
        }
        st.left.set_next_bits(self.ray.steps.bits());
        st.k.set_next_bits(0);
        st.ray.set_next_bits(st.ray.q().bits() + 1);
        self.seq.slot_left.set_next_bits(0);
    }

    /// The sequencer, one cycle: a ray taken when idle, else the next access or the wait
    /// for the one under way; a point's last access ending moves the stepper on.
    pub fn eval(&mut self) {
        self.pages.eval();
        self.out.valid.set_next_bool(false);
        let left = self.stepper.left.q().bits();
        let busy = left > 0;
        self.ray_ready.set_bool(!busy);
        if !busy {
            if self.ray.valid.is_high() {
                self.take_ray();
            }
            return;
        }
        let st = &self.stepper;
        let pos = st.pos.each_ref().map(|r| r.q().raw());
        let k = st.k.q().bits();
        let slot_left = self.seq.slot_left.q().bits();
        let n = self.seq.acc.q().bits() as usize;
        if slot_left == 0 {
            // A ray's first access.
            self.start_access(0, k, pos);
        } else if slot_left > 1 {
            self.seq.slot_left.set_next_bits(slot_left - 1);
        } else if n + 1 < self.mode.accesses() {
            self.start_access(n + 1, k, pos);
        } else {
            // The point is done; the next one's first access starts now.
            self.finish_point(pos);
            let st = &mut self.stepper;
            let next: [i64; 3] = std::array::from_fn(|c| pos[c] + st.step[c].q().raw());
            for (r, x) in st.pos.iter_mut().zip(next) {
                r.set_next_raw(x);
            }
            st.left.set_next_bits(left - 1);
            st.k.set_next_bits(k + 1);
            if left > 1 {
                self.start_access(0, k + 1, next);
            } else {
                self.seq.slot_left.set_next_bits(0);
            }
        }
    }
}

impl Stepper {
    fn new() -> Stepper {
        let wide = Format::signed(32, POS_FRAC as i32);
        Stepper {
            pos: ["x", "y", "z"].map(|n| Reg::new(n, wide)),
            step: ["dx", "dy", "dz"].map(|n| Reg::new(n, wide)),
            left: Reg::new("left", Format::uint(16)),
            k: Reg::new("k", Format::uint(16)),
            ray: Reg::new("ray", Format::uint(32)),
        }
    }
}

impl Sequencer {
    fn new() -> Sequencer {
        let count = |n| Reg::new(n, Format::uint(40));
        Sequencer {
            acc: Reg::new("acc", Format::uint(3)),
            slot_left: Reg::new("slot_left", Format::uint(5)),
            fault: Reg::new("fault", Format::uint(1)),
            voxels: VOXEL_NAMES.map(|n| Reg::new(n, Format::uint(8))),
            accesses: count("accesses"),
            slots: count("slots"),
            fault_slots: count("fault_slots"),
            bank_misses: count("bank_misses"),
        }
    }
}

impl Sample818 {
    fn new() -> Sample818 {
        let wide = Format::signed(32, POS_FRAC as i32);
        let grad = Format::signed(9 + GRAD_FRAC + 1, GRAD_FRAC as i32);
        Sample818 {
            valid: Reg::new("out_valid", Format::uint(1)),
            ray: Reg::new("out_ray", Format::uint(32)),
            k: Reg::new("out_k", Format::uint(16)),
            value: Reg::new("out_value", Format::uint(8)),
            samples: Reg::new("samples", Format::uint(40)),
            p: ["out_x", "out_y", "out_z"].map(|n| Reg::new(n, wide)),
            g: ["out_gx", "out_gy", "out_gz"].map(|n| Reg::new(n, grad)),
        }
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
            dut.ray.valid.set_bool(c == 0);
            for k in 0..3 {
                dut.ray.p[k].set_raw(p[k]);
                dut.ray.d[k].set_raw(d[k]);
            }
            dut.ray.steps.set_bits(steps);
            sim.eval();
            let dut = &sim.dut;
            assert!(
                c > 0 || dut.ray_ready.is_high(),
                "an idle caster takes the ray"
            );
            if dut.out.valid.q().is_high() {
                seen.outs.push(c);
            }
            seen.fault_cycles += u64::from(dut.seq.fault.q().is_high());
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
            let (slots, faults) = (r(&dut.seq.slots), r(&dut.seq.fault_slots));
            assert_eq!(r(&dut.out.samples), 10, "{mode:?}");
            assert_eq!(
                r(&dut.seq.accesses),
                10 * mode.accesses() as u64,
                "{mode:?}"
            );
            assert_eq!(slots, r(&dut.seq.accesses) + faults, "{mode:?}");
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
