//! `texrtl volume` and the ray caster's regression vectors: rays through the cycle-accurate ray
//! caster of Figure 15, each sample checked against the integer reference; and the document's
//! timings from the page-register model (section 13), which the testbench's conclusion holds
//! against the document.

use crate::volume::{
    count_slots, drive_ray, ray_points, ray_ready, ref_sample, sample_ray, Ray, VolSample,
    CYCLE_PS, NAME,
};
use units::volume::layout::{Mode, Order, VolumeParams, POS_FRAC};
use units::volume::ray_caster_fig15::RayCaster;
use verif::{run, Event, PinDriver, PinMonitor, RunSpec, Workload};

/// What a run cost.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct VolumeStats {
    pub rays: u64,
    pub samples: u64,
    pub accesses: u64,
    pub slots: u64,
    /// Slots added by page faults, and the banks that missed.
    pub fault_slots: u64,
    pub bank_misses: u64,
    pub cycles: u64,
    pub ns: u64,
    pub samples_per_second: f64,
}

/// The samples of every ray, in order, and the costs.
pub struct VolumeRun {
    pub samples: Vec<VolSample>,
    pub stats: VolumeStats,
}

/// `rays` through the ray caster over `vox` (x fastest) in `mode`, each sample checked
/// against the integer reference (`Err` names the first that differs).
pub fn run_volume(
    p: VolumeParams,
    mode: Mode,
    vox: &[u8],
    rs: &[Ray],
    vcd: Option<&std::path::Path>,
) -> Result<VolumeRun, crate::RunError> {
    let dut = RayCaster::new(p, mode, vox)?;
    let work = Workload::vcd(vcd);
    let (mut sim, _) = work
        .sim(dut, NAME, CYCLE_PS, |_| ())
        .map_err(crate::RunError::Waveform)?;
    sim.reset(2);
    let want: Vec<[i64; 3]> = rs
        .iter()
        .flat_map(|r| ray_points(r).collect::<Vec<_>>())
        .collect();
    let n = want.len() as u64;
    let mut samples = Vec::with_capacity(want.len());
    let mut wrong = None;
    let per_ray = 16 * mode.accesses() as u64;
    let mut spec = RunSpec::new(n, per_ray * (n + rs.len() as u64) + 100);
    let st = run(
        &mut sim,
        &mut PinDriver::new(drive_ray).ready(ray_ready),
        &mut PinMonitor::new(sample_ray),
        rs.to_vec(),
        &mut spec,
        |_, ev| {
            if let Event::Received { txn, .. } = ev {
                let k = samples.len();
                let r = ref_sample(vox, p.dims, want[k], mode);
                if (txn.p, txn.value, txn.g) != (want[k], r.0, r.1) && wrong.is_none() {
                    wrong = Some(format!(
                        "sample {k}: the caster {txn:?}, the reference {r:?}"
                    ));
                }
                samples.push(txn);
            }
        },
    )
    .map_err(|e| e.to_string())?;
    if let Some(e) = wrong {
        return Err(e.into());
    }
    let d = &sim.dut;
    let ns = st.cycles * CYCLE_PS / 1000;
    let stats = VolumeStats {
        rays: rs.len() as u64,
        samples: n,
        accesses: d.seq.accesses.q().bits(),
        slots: d.seq.slots.q().bits(),
        fault_slots: d.seq.fault_slots.q().bits(),
        bank_misses: d.seq.bank_misses.q().bits(),
        cycles: st.cycles,
        ns,
        samples_per_second: if ns == 0 {
            0.0
        } else {
            n as f64 / ns as f64 * 1e9
        },
    };
    work.finish(sim).map_err(crate::RunError::Waveform)?;
    Ok(VolumeRun { samples, stats })
}
// The document's timings from the page-register model (section 13, timing of section 5).

/// A ray direction for the timing runs: rays along this axis, one resample per voxel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
    Z,
}

/// One timing: what, samples, accesses, slots, milliseconds, the document's.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    pub what: &'static str,
    pub samples: u64,
    pub accesses: u64,
    pub slots: u64,
    pub ms: f64,
    pub document_ms: f64,
}

/// One resample per voxel of `(x0..x1) x Y x Z` at the voxel centres shifted by half a voxel
/// (so every point interpolates), rays along `axis`, the rays in order of the other two axes;
/// each point with its index along its ray.
fn voxel_walk(
    (x0, x1): (u32, u32),
    (ny, nz): (u32, u32),
    axis: Axis,
) -> impl Iterator<Item = ([i64; 3], u64)> {
    let half = 1i64 << (POS_FRAC - 1);
    let at = move |x: u32, y: u32, z: u32| [x, y, z].map(|c| (i64::from(c) << POS_FRAC) + half);
    let (a, b, c) = match axis {
        Axis::X => (x1 - x0, ny, nz),
        Axis::Y => (ny, x1 - x0, nz),
        Axis::Z => (nz, x1 - x0, ny),
    };
    (0..c).flat_map(move |k| {
        (0..b).flat_map(move |j| {
            (0..a).map(move |i| {
                let p = match axis {
                    Axis::X => at(x0 + i, j, k),
                    Axis::Y => at(x0 + j, i, k),
                    Axis::Z => at(x0 + j, k, i),
                };
                (p, u64::from(i))
            })
        })
    })
}

/// Section 13's two timings with the voxel store in `order`, rows of `row_words`, rays along
/// `axis`: RGBA 64x128x128 pre-classified on four chips in lock-step (each chip one
/// component, the same addresses, so one chip's time), one resample per voxel in value mode
/// (document: about 70 ms); the original 256x128x128 with gradients, four chips in parallel,
/// each holding a slab of 64 + 2 overlap voxels along x (the central differences at the slab
/// faces need the neighbour's voxels) and resampling its 64 (document: about 0.28 s).
pub fn timings(order: Order, row_words: u32, axis: Axis) -> Result<[Timing; 2], String> {
    let p = |x| VolumeParams {
        order,
        row_words,
        ..VolumeParams::new(x, 128, 128)
    };
    let rgba = p(64);
    rgba.validate()?;
    let slab = p(66);
    slab.validate()?;
    let figure = |what, v: &VolumeParams, mode, walk: (u32, u32), document_ms| {
        let (accesses, slots, _) = count_slots(v, mode, voxel_walk(walk, (128, 128), axis));
        Timing {
            what,
            samples: u64::from(walk.1 - walk.0) * 128 * 128,
            accesses,
            slots,
            ms: slots as f64 * 30e-6,
            document_ms,
        }
    };
    Ok([
        figure(
            "RGBA 64x128x128, 4 chips in lock-step, value mode",
            &rgba,
            Mode::Value,
            (0, 64),
            70.0,
        ),
        figure(
            "256x128x128 with gradients, 4 chips in parallel (slabs of 64 + 2)",
            &slab,
            Mode::Gradient,
            (1, 65),
            280.0,
        ),
    ])
}
