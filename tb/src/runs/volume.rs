//! `texrtl volume` and the ray caster's regression vectors: rays through the cycle-accurate ray
//! caster of Figure 15, each sample checked against the integer reference.

use crate::volume::{
    drive_ray, ray_points, ray_ready, ref_sample, sample_ray, Ray, VolSample, CYCLE_PS, NAME,
};
use units::volume::layout::{Mode, VolumeParams};
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
