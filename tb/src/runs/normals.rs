//! `texrtl normals` (and `render`, `sweep normals`, the normals testbench and the regression
//! vectors): samples quantised into the FIG. 7 pipeline's input formats, driven one a clock or
//! with random idle cycles, perhaps traced with the golden normal and its angle error beside
//! the pipeline's; every output scored against the testbench's accuracy criterion
//! ([`crate::normals`]), its time checked against the pipeline's latency.

use crate::normals::{coverage_bins, coverage_model, golden_normal, heights, real, scoreboard};
use golden::bump::{self as g, Heights};
use hdl::fx::{Format, Fx, Overflow, Quant};
use hdl::kernel::{Sim, Trace};
use std::path::PathBuf;
use units::bump::height_map::HeightMap;
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::BumpParams;
use verif::{
    run_scored, Coverage, ErrorStats, Pacing, PinDriver, PinMonitor, ProbeSink, RunSpec, Scored,
    TbResult, Workload,
};
use waves::{ProbeId, TraceConfig};

/// One sample request.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub u: f64,
    pub v: f64,
    pub scale: f64,
    /// Weight of the coarser MIP level (trilinear only).
    pub lod: f64,
}

/// A sample as raw pipeline inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RawSample {
    pub u: i64,
    pub v: i64,
    pub scale: u64,
    pub lod: u64,
}

/// The pipeline's result for one sample: raw `sQ2.<out_frac>` components and raw height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RawNormal {
    pub n: [i64; 3],
    pub height: u64,
}

/// Quantises a sample into the pipeline's input formats.
pub fn quantise(p: &BumpParams, s: &Sample) -> Result<RawSample, String> {
    let q = |x: f64, f: Format, what: &str| -> Result<i64, String> {
        if !x.is_finite() {
            return Err(format!("{what} {x} is not a number"));
        }
        let v = Fx::from_f64(f, x, Quant::RoundHalfEven, Overflow::Saturate)
            .map_err(|e| format!("{what}: {e}"))?;
        let lo = Fx::from_raw(f, f.min_raw()).to_f64();
        let hi = Fx::from_raw(f, f.max_raw()).to_f64();
        if x < lo || x > hi {
            // Short: 1e308 is written as such, not as 309 digits.
            let x = if x.abs() < 1e9 {
                format!("{x}")
            } else {
                format!("{x:e}")
            };
            return Err(format!("{what} {x} outside {lo}..={hi} ({f})"));
        }
        Ok(v.raw() as i64)
    };
    Ok(RawSample {
        u: q(s.u, p.pos_fmt(), "u")?,
        v: q(s.v, p.pos_fmt(), "v")?,
        scale: q(s.scale, p.scale_fmt(), "scale")? as u64,
        lod: q(s.lod, p.blend_fmt(), "lod")? as u64,
    })
}

fn drive_sample(dut: &mut NormalPipeline, t: Option<&RawSample>) {
    dut.valid_in.set_bool(t.is_some());
    if let Some(t) = t {
        dut.u.set_raw(t.u);
        dut.v.set_raw(t.v);
        dut.scale.set_raw(t.scale as i64);
        dut.lod.set_raw(t.lod as i64);
    }
}

fn sample_normal(dut: &NormalPipeline) -> Option<RawNormal> {
    dut.valid.is_high().then(|| RawNormal {
        n: [dut.nx.raw(), dut.ny.raw(), dut.nz.raw()],
        height: dut.height.bits(),
    })
}

/// What to run.
#[derive(Clone, Debug)]
pub struct NormalsRun {
    pub name: String,
    pub params: BumpParams,
    pub map: HeightMap,
    pub samples: Vec<Sample>,
    /// Random idle cycles (per mille) between samples; 0 = one per clock.
    pub idle_per_mille: u32,
    pub vcd: Option<PathBuf>,
    pub trace: TraceConfig,
    /// Check the accuracy criterion (default widths, representable positions).
    pub check_accuracy: bool,
    pub seed: verif::Seed,
    /// Run the kernel's schedule check on every cycle.
    pub check_schedule: bool,
}

/// Results of a run: per-sample outputs and a testbench result.
pub struct NormalsOutcome {
    pub outputs: Vec<RawNormal>,
    pub golden: Vec<[f64; 3]>,
    pub result: TbResult,
    /// Worst angle to the golden normal, degrees.
    pub max_angle_deg: f64,
    /// Worst component error, absolute.
    pub max_component_err: f64,
    /// Worst error of the interpolated, scaled height (para. 0084), absolute.
    pub max_height_err: f64,
    pub latency: usize,
    pub coverage: Coverage,
}

/// Runs the pipeline over the samples under the verification framework.
pub fn run_normals(cfg: &NormalsRun) -> Result<NormalsOutcome, String> {
    let p = cfg.params;
    let coarse_map = p.trilinear.then(|| cfg.map.downsample());
    let dut = NormalPipeline::new(
        "normal_pipeline_fig7",
        p,
        cfg.map.clone(),
        coarse_map.clone(),
    )?;
    let raws = cfg
        .samples
        .iter()
        .map(|s| quantise(&p, s))
        .collect::<Result<Vec<_>, _>>()?;
    let fine = heights(&cfg.map);
    let coarse = coarse_map.as_ref().map(heights);
    let work = Workload::traced(cfg.vcd.clone().map(|p| (p, cfg.trace.clone())));
    let (sim, probes) = work.sim(dut, &cfg.name, cfg.trace.period_ps, |t| {
        [
            t.probe_real("nx_golden", Some("tb.normal_pipeline_fig7.nx")),
            t.probe_real("ny_golden", Some("tb.normal_pipeline_fig7.ny")),
            t.probe_real("nz_golden", Some("tb.normal_pipeline_fig7.nz")),
            t.probe_real("angle_err_deg", Some("tb.normal_pipeline_fig7.nz")),
        ]
    })?;
    let (sim, mut out) = drive(sim, cfg, raws, &fine, coarse.as_ref(), probes);
    let dut = work.finish(sim)?;
    out.result.vcd = cfg.vcd.clone();
    out.result.narrowings = narrowings(&dut);
    Ok(out)
}

/// What the pipeline's narrowings met, when numeric tracking is on.
fn narrowings(dut: &NormalPipeline) -> Vec<verif::numeric::NarrowRow> {
    if hdl::fx::tracking() {
        verif::numeric::rows(dut)
    } else {
        Vec::new()
    }
}

/// The speed benchmarks' stimulus: `cycles` cycles of the default pipeline (16 x 16 texels),
/// `u` and `v` stepping through every texel at two strides, a valid sample and a unit scale
/// every cycle; the sum of the `nz` outputs (so that nothing is optimised away).
pub fn bench_cycles<T: Trace>(sim: &mut Sim<NormalPipeline, T>, cycles: u64) -> u64 {
    let mut acc = 0u64;
    for c in 0..cycles as i64 {
        sim.dut.valid_in.set_bool(true);
        sim.dut.u.set_raw((c * 37) % (16 << 8));
        sim.dut.v.set_raw((c * 91) % (16 << 8));
        sim.dut.scale.set_raw(256);
        sim.eval();
        acc = acc.wrapping_add(sim.dut.nz.bits());
        sim.tick();
    }
    acc
}

/// The run's outcome ([`TbResult::ran`]) and its time against the pipeline's: one sample a
/// clock when `full_rate`, and every sample out exactly `latency` cycles after it went in.
fn check_timing(
    res: &mut TbResult,
    r: Result<verif::RunStats, verif::Timeout>,
    n: u64,
    latency: u64,
    full_rate: bool,
) {
    res.ran(&r);
    let Ok(st) = r else {
        return;
    };
    res.latency = st.max_latency;
    if full_rate && n > 0 && st.cycles != n + latency {
        res.failures.push(format!(
            "{} cycles for {n} samples: not one per clock",
            st.cycles
        ));
    }
    if n > 0 && (st.min_latency != Some(latency) || st.max_latency != Some(latency)) {
        res.failures.push(format!(
            "latency {:?}..{:?}, expected {latency}",
            st.min_latency, st.max_latency
        ));
    }
}

fn drive<T: Trace + ProbeSink>(
    sim: Sim<NormalPipeline, T>,
    cfg: &NormalsRun,
    raws: Vec<RawSample>,
    fine: &Heights,
    coarse: Option<&Heights>,
    probes: Option<[ProbeId; 4]>,
) -> (Sim<NormalPipeline, T>, NormalsOutcome) {
    let p = cfg.params;
    let mut sim = sim.check_schedule(cfg.check_schedule);
    sim.reset(2);
    let latency = sim.dut.latency();
    let lsb = (-(p.out_frac as f64)).exp2();
    let nf = p.normal_fmt();
    let mut res = TbResult::new(
        &cfg.name,
        "FIG. 7 pipeline (units 150-156, para. 0050-0087)",
    );
    res.seed = Some(cfg.seed.to_string());
    let mut stats = ErrorStats::new();
    let mut cov = coverage_model();
    let hf = p.height_out_fmt();
    let mut max_height = 0.0f64;
    let mut sb = scoreboard(nf);
    let n = raws.len() as u64;
    let (mut outputs, mut goldens) = (
        Vec::with_capacity(raws.len()),
        Vec::with_capacity(raws.len()),
    );
    let (mut max_angle, mut max_comp) = (0.0f64, 0.0f64);
    let pacing = if cfg.idle_per_mille == 0 {
        Pacing::full()
    } else {
        Pacing::random(cfg.idle_per_mille, cfg.seed)
    };
    let size = (cfg.map.width() as i64, cfg.map.height() as i64);
    let r = run_scored(
        &mut sim,
        &mut PinDriver::new(drive_sample),
        &mut PinMonitor::new(sample_normal),
        raws,
        &mut RunSpec::new(n, 4 * n + 100).pacing(pacing),
        |sim, ev| match ev {
            Scored::Sent { txn, .. } => {
                sb.expect(golden_normal(&p, fine, coarse, txn));
                cov.sample(&coverage_bins(&p, fine, size, txn));
            }
            Scored::Received { cycle, txn } => {
                let out = sb.observe(cycle, txn);
                if let Some((gn, gh)) = out.expected {
                    max_height = max_height.max((real(txn.height as i64, hf) - gh).abs());
                    let d = txn.n.map(|x| real(x, nf));
                    for k in 0..3 {
                        stats.record(d[k], gn[k], lsb);
                        max_comp = max_comp.max((d[k] - gn[k]).abs());
                    }
                    let a = g::angle_deg(gn, d);
                    max_angle = max_angle.max(a);
                    if let (Some(pr), Some(t)) = (probes.as_ref(), sim.trace_mut()) {
                        for (p, v) in pr.iter().zip([gn[0], gn[1], gn[2], a]) {
                            t.real(*p, v);
                        }
                    }
                    goldens.push(gn);
                }
                outputs.push(txn);
            }
        },
    );
    res.transactions = n;
    check_timing(&mut res, r, n, latency as u64, cfg.idle_per_mille == 0);
    if cfg.check_accuracy {
        res.mismatches = sb.mismatch_count();
        for m in sb.mismatches().iter().take(10) {
            res.mismatch_log.push(format!(
                "sample {} (cycle {:?}): {}",
                m.index, m.cycle, m.detail
            ));
        }
    }
    res.set_coverage(cov.clone());
    res.coverage = None;
    res.stats = stats;
    res.finish_with(false);
    (
        sim,
        NormalsOutcome {
            outputs,
            golden: goldens,
            result: res,
            max_angle_deg: max_angle,
            max_component_err: max_comp,
            max_height_err: max_height,
            latency,
            coverage: cov,
        },
    )
}
