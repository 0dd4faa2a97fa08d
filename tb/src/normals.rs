//! Testbench of the FIG. 7 normal pipeline (`units::bump::normal_pipeline`) against the surfaces of
//! `golden::bump`, and the machinery the `normals`, `render` and `sweep normals` commands use.
//!
//! Stimulus is a list of samples (position, height scale, MIP weight). Inputs are quantised to
//! the pipeline's formats first (positions and scale round to nearest, ties to even; a position
//! outside the format's range is an error, not clamped), and the golden model is evaluated at
//! exactly the quantised inputs, so the measured error is the pipeline's own.
//!
//! Accuracy criterion (default widths, positions exact in the blend-factor format): every
//! component within `2^-13` of the golden normal and every normal within 0.01 degrees of it.

use golden::bump::{self as g, Heights};
use hdl::fx::{Format, Fx, Overflow, Quant};
use hdl::kernel::{Sim, Trace};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use units::bump::height_map::HeightMap;
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::{Border, BumpParams, Filter};
use verif::{
    run_scored, About, Coverage, Coverpoint, Ctx, ErrorStats, Pacing, PinDriver, PinMonitor,
    ProbeSink, RunSpec, Scoreboard, Scored, TbResult, Testbench, Workload,
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

/// The real value of a raw input (what the golden model is evaluated at).
pub fn real(raw: i64, f: Format) -> f64 {
    Fx::from_raw(f, i128::from(raw)).to_f64()
}

/// Golden `(normal, scaled height)` for a raw sample.
pub fn golden_normal(
    p: &BumpParams,
    fine: &Heights,
    coarse: Option<&Heights>,
    r: &RawSample,
) -> ([f64; 3], f64) {
    let (u, v) = (real(r.u, p.pos_fmt()), real(r.v, p.pos_fmt()));
    let scale = real(r.scale as i64, p.scale_fmt());
    let lod = real(r.lod as i64, p.blend_fmt());
    let border = golden_border(p);
    let f: fn(&Heights, f64, f64, g::Border) -> g::Surface = match p.filter {
        Filter::BSpline | Filter::Bezier => g::bspline,
        Filter::Blinn => g::blinn,
    };
    let s = match coarse {
        Some(c) if p.trilinear => g::trilinear(f, fine, c, u, v, lod, border),
        _ => f(fine, u, v, border),
    };
    (g::normal(s, scale), s.0 * scale)
}

fn golden_border(p: &BumpParams) -> g::Border {
    match p.border {
        Border::Wrap => g::Border::Wrap,
        Border::Clamp => g::Border::Clamp,
        Border::Mirror => g::Border::Mirror,
        Border::Constant(c) => {
            g::Border::Constant(f64::from(c) / f64::from(1u32 << p.texel_fmt().frac()))
        }
    }
}

/// Heights of a map for the golden model.
pub fn heights(m: &HeightMap) -> Heights {
    Heights::from_raw(
        m.width() as usize,
        m.height() as usize,
        m.texels(),
        m.fmt().frac() as u32,
    )
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

/// Component tolerance of the accuracy criterion.
pub const COMPONENT_TOL: f64 = 1.0 / 8192.0;
/// Angle tolerance of the accuracy criterion, degrees.
pub const ANGLE_TOL_DEG: f64 = 0.01;

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

/// The coverage model: border mode x variant, blend factors at 0 / interior / max, samples
/// in edge cells, and height extremes (the 3x3 neighbourhood holds the lowest and/or highest
/// texel value of the format).
pub fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let b = c.add(Coverpoint::new("border").values(&["wrap", "clamp", "mirror", "constant"]));
    let v = c.add(Coverpoint::new("variant").values(&["bspline", "bezier", "blinn", "trilinear"]));
    let f = c.add(Coverpoint::new("blend_u").values(&["zero", "interior", "max"]));
    let g = c.add(Coverpoint::new("blend_v").values(&["zero", "interior", "max"]));
    c.add(Coverpoint::new("cell").values(&["inside", "edge"]));
    let h = c.add(Coverpoint::new("height_extremes").values(&["neither", "min", "max", "both"]));
    c.cross("border_x_variant", b, v);
    c.cross("blend_u_x_blend_v", f, g);
    c.cross("variant_x_height_extremes", v, h);
    c
}

fn variant_id(p: &BumpParams) -> i64 {
    match (p.trilinear, p.filter) {
        (true, _) => 3,
        (false, Filter::BSpline) => 0,
        (false, Filter::Bezier) => 1,
        (false, Filter::Blinn) => 2,
    }
}

/// A border operation's coverage bin: wrap 0, clamp 1, mirror 2, constant 3.
pub fn border_id(p: &BumpParams) -> i64 {
    match p.border {
        Border::Wrap => 0,
        Border::Clamp => 1,
        Border::Mirror => 2,
        Border::Constant(_) => 3,
    }
}

/// The scoreboard of the accuracy criterion: every component within [`COMPONENT_TOL`] of the
/// golden normal and the angle within [`ANGLE_TOL_DEG`]; outputs in format `nf`.
fn scoreboard(nf: Format) -> Scoreboard<([f64; 3], f64), RawNormal> {
    Scoreboard::new(move |(g, _): &([f64; 3], f64), a: &RawNormal| {
        let d = a.n.map(|x| real(x, nf));
        let err = (0..3).map(|k| (d[k] - g[k]).abs()).fold(0.0, f64::max);
        let ang = g::angle_deg(*g, d);
        if err <= COMPONENT_TOL && ang <= ANGLE_TOL_DEG {
            Ok(())
        } else {
            Err(format!(
                "normal {d:?} vs golden {g:?}: component error {err:.3e}, angle {ang:.2e} deg"
            ))
        }
    })
}

/// A sample's bins in [`coverage_model`] on a `size` (width, height) map of heights `fine`.
fn coverage_bins(p: &BumpParams, fine: &Heights, (w, h): (i64, i64), s: &RawSample) -> [i64; 6] {
    let tf = p.texel_fmt();
    let tmax = tf.max_raw() as f64 / f64::from(1u32 << tf.frac());
    let fb = p.pos_frac - p.blend_bits;
    let blend = |x: i64| {
        let b = (x >> fb) & ((1 << p.blend_bits) - 1);
        if b == 0 {
            0
        } else if b == (1 << p.blend_bits) - 1 {
            2
        } else {
            1
        }
    };
    let (iu, iv) = (s.u >> p.pos_frac, s.v >> p.pos_frac);
    let edge = iu <= 0 || iv <= 0 || iu >= w - 1 || iv >= h - 1;
    let gb = golden_border(p);
    let mut ext = 0;
    for dj in -1..=1 {
        for di in -1..=1 {
            let t = fine.texel(iu + di, iv + dj, gb);
            ext |= i64::from(t == 0.0) | (i64::from(t == tmax) << 1);
        }
    }
    [
        border_id(p),
        variant_id(p),
        blend(s.u),
        blend(s.v),
        i64::from(edge),
        ext,
    ]
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

/// Positions for a `w x h` map on the grid of `bits` fraction bits: `n` seeded random ones,
/// blend factors 0 / 1/2 / just below 1 in every combination, and every border cell (and one
/// texel beyond, for the border modes). Scales are 1, except every fourth sample, which draws a
/// scale in [0, 8).
pub fn stimulus(
    w: u32,
    h: u32,
    bits: u32,
    n: usize,
    stim: &mut verif::Stimulus,
    trilinear: bool,
) -> Vec<Sample> {
    let step = (-(bits as f64)).exp2();
    let q = |x: u64| x as f64 * step;
    let mut s = Vec::new();
    let lod = |k: usize| {
        if trilinear {
            (k % 257) as f64 / 256.0 % 1.0
        } else {
            0.0
        }
    };
    let strat = (
        0..(u64::from(w) << bits),
        0..(u64::from(h) << bits),
        0u64..2048,
    );
    for k in 0..n {
        let (u, v, sc) = stim.draw(&strat);
        let scale = if k % 4 == 3 { sc as f64 / 256.0 } else { 1.0 };
        s.push(Sample {
            u: q(u),
            v: q(v),
            scale,
            lod: lod(k),
        });
    }
    let edge = 1.0 - step;
    for bu in [0.0, 0.5, edge] {
        for bv in [0.0, 0.5, edge] {
            s.push(Sample {
                u: 1.0 + bu,
                v: 1.0 + bv,
                scale: 1.0,
                lod: lod(s.len()),
            });
        }
    }
    let (fw, fh) = (f64::from(w), f64::from(h));
    for k in 0..w.max(h) {
        let k = f64::from(k);
        for (u, v) in [
            (k, 0.0),
            (k, fh - step),
            (0.0, k),
            (fw - step, k),
            (k - 1.0, -1.0),
            (fw, k + 0.5),
        ] {
            s.push(Sample {
                u,
                v,
                scale: 1.0,
                lod: lod(s.len()),
            });
        }
    }
    s
}

/// The testbench's name: the pipeline's.
pub const NAME: &str = "normal_pipeline_fig7";

/// The maps, variants and border modes the normals testbench crosses.
const MAPS: [&str; 6] = ["flat", "steep", "steps", "noise", "smooth", "extremes"];
const VARIANTS: [(Filter, bool); 4] = [
    (Filter::BSpline, false),
    (Filter::Bezier, false),
    (Filter::Blinn, false),
    (Filter::BSpline, true),
];
const BORDERS: [Border; 4] = [
    Border::Wrap,
    Border::Clamp,
    Border::Mirror,
    Border::Constant(255),
];

/// The normals testbench: every built-in map (flat, steep, steps, noise, smooth, extremes) in
/// every variant (B-spline, Bezier, Blinn, trilinear) and border mode, one configuration each,
/// default widths, against the accuracy criterion; the traced one is noise, B-spline, wrap.
pub struct NormalsTb;

/// A configuration's worst errors, as recorded for the notes.
#[derive(Serialize, Deserialize)]
struct Worst {
    component: f64,
    angle_deg: f64,
    height: f64,
}

impl NormalsTb {
    fn config(index: usize) -> (&'static str, Filter, bool, Border) {
        let (m, rest) = (index / 16, index % 16);
        let (filter, trilinear) = VARIANTS[rest / 4];
        (MAPS[m], filter, trilinear, BORDERS[rest % 4])
    }
}

impl Testbench for NormalsTb {
    fn about(&self) -> About {
        About::new(NAME, "FIG. 7 pipeline (units 150-156, para. 0050-0087)")
            .count(
                150,
                "random positions (plus the directed blend and border positions)",
            )
            // noise, B-spline, wrap.
            .traced(3 * 16)
    }
    fn configurations(&self) -> Vec<String> {
        (0..MAPS.len() * 16)
            .map(|i| {
                let (map, filter, trilinear, border) = NormalsTb::config(i);
                format!("{map} {filter} trilinear={trilinear} {border}")
            })
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (map, filter, trilinear, border) = NormalsTb::config(ctx.index);
        let (w, h) = (16, 16);
        let mut stim = verif::Stimulus::new(ctx.seed);
        let p = BumpParams {
            filter,
            trilinear,
            border,
            ..BumpParams::default()
        };
        let m = crate::maps::builtin(map, w, h, p.texel_fmt())?;
        // Trilinear positions are exact in the coarser level's blend format too.
        let bits = p.blend_bits - u32::from(trilinear);
        let traced = ctx.waves.is_some();
        let o = run_normals(&NormalsRun {
            name: ctx.label.clone(),
            params: p,
            map: m,
            samples: stimulus(w, h, bits, ctx.count, &mut stim, trilinear),
            idle_per_mille: if traced { 0 } else { 100 },
            vcd: ctx.waves.as_ref().map(|w| w.vcd.clone()),
            trace: ctx
                .waves
                .as_ref()
                .map(|w| w.config(10_000))
                .unwrap_or_default(),
            check_accuracy: true,
            seed: ctx.seed.derive(0x9ace),
            check_schedule: ctx.check_schedule,
        })?;
        let mut r = o.result;
        r.coverage = Some(o.coverage);
        r.record(&Worst {
            component: o.max_component_err,
            angle_deg: o.max_angle_deg,
            height: o.max_height_err,
        });
        Ok(r)
    }
    fn conclude(&self, merged: &mut TbResult) {
        let w = merged.records_of::<Worst>();
        let max = |f: fn(&Worst) -> f64| w.iter().map(f).fold(0.0, f64::max);
        merged.notes.push(format!(
            "worst component error {:.3e} (tolerance {COMPONENT_TOL:.3e}), worst angle {:.3e} deg (tolerance {ANGLE_TOL_DEG}), worst height error {:.3e}",
            max(|x| x.component),
            max(|x| x.angle_deg),
            max(|x| x.height)
        ));
    }
}
