//! Volume rendering on the TEXRAM (section 13): the integer reference of a resample point
//! (plain loops over the volume array, its own reflection and weights), the regress
//! testbench of the ray caster, with the document's timings from the page-register model
//! ([`crate::runs::volume::timings`]) in its conclusion. The rendered picture of a built-in
//! volume on four chips in lock-step is [`crate::pictures::volume`].

use crate::runs::volume::{timings, Axis};
use hdl::kernel::{Sim, Trace};
use proptest::prelude::*;
use units::volume::layout::{locate, Mode, Order, VolumeParams, POS_FRAC};
use units::volume::ray_caster_fig15::RayCaster;
use verif::{
    run, About, Coverage, Coverpoint, Ctx, Event, Pacing, PinDriver, PinMonitor, RunSpec,
    Scoreboard, Stimulus, TbResult, Testbench,
};

pub const NAME: &str = "ray_caster_fig15";
/// The chip's clock (5 ns).
pub const CYCLE_PS: u64 = 5_000;

/// One ray: start and step (raw sQ9.12), samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ray {
    pub p: [i32; 3],
    pub d: [i32; 3],
    pub steps: u16,
}

/// One sample out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VolSample {
    pub ray: u32,
    pub k: u16,
    pub p: [i64; 3],
    pub value: u8,
    pub g: [i64; 3],
}

/// The reference's voxel: reflected into the volume by walking back and forth.
/// Index `i` mirrored into `0..n` (reflected at 0 and at n - 1, period 2 (n - 1)), in
/// constant time however far outside the volume `i` lies.
pub fn mirror(i: i64, n: u32) -> usize {
    let n = i64::from(n);
    if n == 1 {
        return 0;
    }
    let period = 2 * (n - 1);
    let m = i.rem_euclid(period);
    (if m < n { m } else { period - m }) as usize
}

fn ref_voxel(vox: &[u8], (nx, ny, nz): (u32, u32, u32), x: i64, y: i64, z: i64) -> i64 {
    let (x, y, z) = (mirror(x, nx), mirror(y, ny), mirror(z, nz));
    i64::from(vox[(z * ny as usize + y) * nx as usize + x])
}

/// The integer reference of the point `p` (raw sQ.12): the value (u8) and, in gradient
/// mode, the gradient (raw sQ9.4), each one rounding of the exact weighted sum.
pub fn ref_sample(vox: &[u8], dims: (u32, u32, u32), p: [i64; 3], mode: Mode) -> (u8, [i64; 3]) {
    let one = 1i64 << POS_FRAC;
    let ijk = p.map(|c| c.div_euclid(one));
    let w8 = p.map(|c| c.rem_euclid(one) / 16);
    let f = |d: [i64; 3]| ref_voxel(vox, dims, ijk[0] + d[0], ijk[1] + d[1], ijk[2] + d[2]);
    let (mut s, mut g) = (0i64, [0i64; 3]);
    for dz in 0..2 {
        for dy in 0..2 {
            for dx in 0..2 {
                let d = [dx, dy, dz];
                let w: i64 = (0..3)
                    .map(|c| if d[c] == 1 { w8[c] } else { 256 - w8[c] })
                    .product();
                s += w * f(d);
                for (c, gc) in g.iter_mut().enumerate() {
                    let (mut up, mut down) = (d, d);
                    up[c] += 1;
                    down[c] -= 1;
                    *gc += w * (f(up) - f(down));
                }
            }
        }
    }
    let grad = match mode {
        Mode::Value => [0; 3],
        Mode::Gradient => g.map(|x| (x + (1 << 19)).div_euclid(1 << 20)),
    };
    (((s + (1 << 23)) / (1 << 24)) as u8, grad)
}

/// The reference's points of a ray, in order.
pub fn ray_points(r: &Ray) -> impl Iterator<Item = [i64; 3]> + '_ {
    (0..i64::from(r.steps))
        .map(move |k| std::array::from_fn(|c| i64::from(r.p[c]) + k * i64::from(r.d[c])))
}

/// Accesses, slots and faulting banks of `points` (each with its sample index along its
/// ray) from the page-register model (own loop: one slot an access, two when a bank it reads
/// has another row open; the accesses in the order the sequencer alternates).
pub fn count_slots(
    p: &VolumeParams,
    mode: Mode,
    points: impl Iterator<Item = ([i64; 3], u64)>,
) -> (u64, u64, u64) {
    use units::volume::layout::access_voxels;
    let mut open = [u32::MAX; 4];
    let (mut accesses, mut slots, mut misses) = (0, 0, 0);
    for (pt, k) in points {
        let ijk = (pt[0] >> POS_FRAC, pt[1] >> POS_FRAC, pt[2] >> POS_FRAC);
        let order: &[usize] = match (mode, k % 2) {
            (Mode::Value, _) => &[0, 1],
            (Mode::Gradient, 0) => &[0, 1, 6, 7, 2, 3, 4, 5],
            (Mode::Gradient, _) => &[4, 5, 2, 3, 6, 7, 0, 1],
        };
        for &a in order {
            let mut missed = 0;
            for (x, y, z) in access_voxels(p, a, ijk) {
                let (b, w) = locate(p, x, y, z);
                let row = w / p.row_words;
                if open[b] != row {
                    open[b] = row;
                    missed += 1;
                }
            }
            accesses += 1;
            slots += 1 + u64::from(missed > 0);
            misses += missed;
        }
    }
    (accesses, slots, misses)
}

/// Presents a ray (start, step, sample count) on the ray port.
pub fn drive_ray(dut: &mut RayCaster, t: Option<&Ray>) {
    dut.ray.valid.set_bool(t.is_some());
    if let Some(t) = t {
        for c in 0..3 {
            dut.ray.p[c].set_raw(i64::from(t.p[c]));
            dut.ray.d[c].set_raw(i64::from(t.d[c]));
        }
        dut.ray.steps.set_bits(u64::from(t.steps));
    }
}

/// The ray caster takes a ray in a cycle with `ray_ready` high.
pub fn ray_ready(dut: &RayCaster) -> bool {
    dut.ray_ready.is_high()
}

/// A sample along a ray, in a cycle with the output's `valid` high.
pub fn sample_ray(dut: &RayCaster) -> Option<VolSample> {
    dut.out.valid.q().is_high().then(|| VolSample {
        ray: dut.out.ray.q().bits() as u32,
        k: dut.out.k.q().bits() as u16,
        p: dut.out.p.each_ref().map(|r| r.q().raw()),
        value: dut.out.value.q().bits() as u8,
        g: dut.out.g.each_ref().map(|r| r.q().raw()),
    })
}

/// A test volume with structure at every scale: a sphere's distance, a slab, seeded noise.
pub fn test_volume((nx, ny, nz): (u32, u32, u32), stim: &mut Stimulus) -> Vec<u8> {
    let noise = stim.draw_n(&(0u8..40), (nx * ny * nz) as usize);
    (0..nx * ny * nz)
        .map(|n| {
            let (x, y, z) = (n % nx, n / nx % ny, n / (nx * ny));
            let d = |a: u32, m: u32| (2 * a as i64 - m as i64).abs();
            let sphere = (d(x, nx) + d(y, ny) + d(z, nz)) as u32 * 3;
            let slab = if (x + 2 * z) % 7 < 2 { 90 } else { 0 };
            (sphere + slab + u32::from(noise[n as usize])).min(255) as u8
        })
        .collect()
}

/// Random rays through and beside the volume: steps up to 1.5 voxels in any direction,
/// 1 to 40 samples.
pub fn rays((nx, ny, nz): (u32, u32, u32), n: usize, stim: &mut Stimulus) -> Vec<Ray> {
    let one = 1i32 << POS_FRAC;
    let lim = |m: u32| -one..(m as i32 + 1) * one;
    let d = -3 * one / 2..3 * one / 2;
    let s = (
        (lim(nx), lim(ny), lim(nz)),
        (d.clone(), d.clone(), d),
        1u16..=40,
    )
        .prop_map(|((x, y, z), (dx, dy, dz), steps)| Ray {
            p: [x, y, z],
            d: [dx, dy, dz],
            steps,
        });
    stim.draw_n(&s, n)
}

/// Voxels along x, y, z.
type Dims = (u32, u32, u32);

/// The configurations: dimensions, word order, row size, mode.
const CONFIGS: [(Dims, Order, u32, Mode); 5] = [
    ((8, 6, 5), Order::ColumnMajor, 64, Mode::Value),
    ((8, 6, 5), Order::SliceMajor, 16, Mode::Gradient),
    ((16, 16, 16), Order::ColumnMajor, 512, Mode::Gradient),
    ((32, 16, 8), Order::SliceMajor, 256, Mode::Value),
    ((2, 2, 1), Order::ColumnMajor, 16, Mode::Gradient),
];

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let m = c.add(Coverpoint::new("mode").values(&["value", "gradient"]));
    c.add(Coverpoint::new("order").values(&["slice_major", "column_major"]));
    let e = c.add(Coverpoint::new("position").values(&["interior", "at_a_face", "outside"]));
    c.add(Coverpoint::new("page").values(&["hits", "a_fault"]));
    c.cross("mode_x_position", m, e);
    c
}

/// Where a point's 2x2x2 lies: inside with its neighbours, touching a face, outside.
fn position_class(p: [i64; 3], (nx, ny, nz): (u32, u32, u32)) -> i64 {
    let ijk = p.map(|c| c >> POS_FRAC);
    let dims = [nx, ny, nz].map(i64::from);
    if (0..3).any(|c| ijk[c] < 0 || ijk[c] >= dims[c]) {
        2
    } else if (0..3).any(|c| ijk[c] < 1 || ijk[c] + 2 >= dims[c]) {
        1
    } else {
        0
    }
}

/// The regress testbench of the ray caster.
pub struct VolumeTb;

/// What a sample should give: the point, the reference's value and gradient, golden's value.
type VolExpected = ([i64; 3], (u8, [i64; 3]), f64);

impl Testbench for VolumeTb {
    fn about(&self) -> About {
        About::new(NAME, "TEXRAM ray caster (Schilling & Knittel section 13, Figure 15): stepper, value and gradient accesses, page registers 824, trilinear 818")
            .count(300, "random rays")
    }
    fn configurations(&self) -> Vec<String> {
        CONFIGS
            .iter()
            .map(|((x, y, z), o, r, m)| format!("{x}x{y}x{z} {o:?}, rows of {r}, {m:?} mode"))
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn conclude(&self, merged: &mut TbResult) {
        let mut table = String::from(
            "| section 13 timing (column-major words, 512-word rows, rays along x) | samples | accesses | slots | ms | document ms |\n|---|---|---|---|---|---|\n",
        );
        match timings(Order::ColumnMajor, 512, Axis::X) {
            Ok(rows) => {
                for t in rows {
                    table.push_str(&format!(
                        "| {} | {} | {} | {} | {:.1} | {:.0} |\n",
                        t.what, t.samples, t.accesses, t.slots, t.ms, t.document_ms
                    ));
                    merged.notes.push(format!(
                        "{}: {:.1} ms (document about {:.0} ms)",
                        t.what, t.ms, t.document_ms
                    ));
                    if (t.ms / t.document_ms - 1.0).abs() >= 0.15 {
                        merged.failures.push(format!(
                            "{}: {:.1} ms, not within 15 % of the document's {:.0}",
                            t.what, t.ms, t.document_ms
                        ));
                    }
                }
            }
            Err(e) => merged.failures.push(e),
        }
        merged.tables.push(table);
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (dims, order, row_words, mode) = CONFIGS[ctx.index];
        let p = VolumeParams {
            order,
            row_words,
            ..VolumeParams::new(dims.0, dims.1, dims.2)
        };
        let mut stim = Stimulus::new(ctx.seed);
        let vox = test_volume(dims, &mut stim);
        let dut = RayCaster::new(p, mode, &vox)?;
        let (sim, _) = ctx.sim(dut, &format!("{NAME} {}", ctx.label), CYCLE_PS, |_| ())?;
        let rs = rays(dims, ctx.count, &mut stim);
        let (sim, mut res) = run_rays(sim, ctx, (&p, mode, &vox), rs)?;
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}

/// Drives the rays; every sample against the reference (bit-exact) and golden (value within
/// 0.5 LSB at the weight-quantised point); slots against the page-register model.
fn run_rays<T: Trace>(
    mut sim: Sim<RayCaster, T>,
    ctx: &Ctx,
    (p, mode, vox): (&VolumeParams, Mode, &[u8]),
    rs: Vec<Ray>,
) -> Result<(Sim<RayCaster, T>, TbResult), String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let dims = p.dims;
    let expected: Vec<VolExpected> = rs
        .iter()
        .flat_map(|r| ray_points(r).collect::<Vec<_>>())
        .map(|pt| {
            let q = pt.map(|c| (c >> 4 << 4) as f64 / 4096.0);
            let g = golden::volume::Volume {
                dims: (dims.0 as usize, dims.1 as usize, dims.2 as usize),
                voxels: vox,
            };
            (
                pt,
                ref_sample(vox, dims, pt, mode),
                g.value((q[0], q[1], q[2])),
            )
        })
        .collect();
    let n = expected.len() as u64;
    let ks = rs.iter().flat_map(|r| 0..u64::from(r.steps));
    let (_, want_slots, _) = count_slots(p, mode, expected.iter().map(|e| e.0).zip(ks));
    let mut sb: Scoreboard<VolExpected, VolSample> =
        Scoreboard::new(|(pt, (v, g), _): &VolExpected, a: &VolSample| {
            if (a.p, a.value, a.g) == (*pt, *v, *g) {
                Ok(())
            } else {
                Err(format!("got {a:?}, want {pt:?} {v} {g:?}"))
            }
        });
    for e in expected {
        sb.expect(e);
    }
    let per_ray = 16 * mode.accesses() as u64 * 41;
    let pacing = Pacing::random(300, ctx.seed.derive(11));
    let mut spec = RunSpec::new(n, per_ray * rs.len() as u64 + 100).pacing(pacing);
    let (oc, mi) = (
        i64::from(p.order == Order::ColumnMajor),
        i64::from(mode == Mode::Gradient),
    );
    let mut last_slots = 0;
    let r = run(
        &mut sim,
        &mut PinDriver::new(drive_ray).ready(ray_ready),
        &mut PinMonitor::new(sample_ray),
        rs,
        &mut spec,
        |s, ev| {
            if let Event::Received { cycle, txn } = ev {
                if let Some((pt, _, want)) = sb.observe(cycle, txn).expected {
                    res.stats.record(f64::from(txn.value), want, 1.0);
                    let slots = s.dut.seq.slots.q().bits();
                    let fault = i64::from(slots - last_slots > mode.accesses() as u64);
                    last_slots = slots;
                    cov.sample(&[mi, 1 - oc, position_class(pt, dims), fault]);
                }
            }
        },
    );
    res.score(&sb);
    res.ran(&r);
    let slots = sim.dut.seq.slots.q().bits();
    if slots != want_slots {
        res.failures.push(format!(
            "{slots} slots, the page-register model counts {want_slots}"
        ));
    }
    if res.stats.max_abs_lsb > 0.5 + 1e-9 {
        res.failures.push(format!(
            "value {:.4} LSB from golden, bound 0.5",
            res.stats.max_abs_lsb
        ));
    }
    res.notes.push(format!(
        "{}: {n} samples, {} accesses in {slots} slots",
        ctx.label,
        sim.dut.seq.accesses.q().bits()
    ));
    res.coverage = Some(cov);
    Ok((sim, res))
}
