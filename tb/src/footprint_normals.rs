//! Footprint assembly on the FIG. 7 height-map pipeline (para. 0081): the testbench of the
//! generator and the pipeline's tangent average. Each pixel's expectation is built from the
//! plain pipeline (verified on its own by `normal_pipeline_fig7`): its tangents at the sample
//! points (the reference's own point arithmetic), averaged with integer division, and the
//! f64 normal of that average; the unit's normal must be within normal unit 156's derived
//! tolerance of it, and its height equal to the averaged height.

use crate::footprint::pixels;
use hdl::kernel::{Sim, Trace};
use units::bump::height_map::HeightMap;
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::{Border, BumpParams, Filter};
use units::footprint::normals_0081::FootprintNormals;
use units::footprint::setup_fig12::{setup, SetupParams, SetupUnit};
use verif::{
    run, About, Coverage, Coverpoint, Ctx, Event, Pacing, PinDriver, PinMonitor, RunSpec,
    Scoreboard, Stimulus, TbResult, Testbench,
};

pub const NAME: &str = "footprint_normals_0081";
/// The pipeline's clock (10 ns, as the FIG. 7 testbench).
const CYCLE_PS: u64 = 10_000;

/// One pixel: centre (raw, the pipeline's position format), step (raw sQ11.14), N, scale.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NPixel {
    pub u: i64,
    pub v: i64,
    pub du: i32,
    pub dv: i32,
    pub log2_n: u32,
    pub scale: i64,
}

/// One normal out: nx, ny, nz and the height, raw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NOut {
    pub n: [i64; 3],
    pub height: i64,
}

/// The reference's sample points of a pixel, raw in the position format: `p + (2i - (N-1))
/// dr/2` in sQ.15, rounded half up.
pub fn points(p: &BumpParams, q: &NPixel) -> Vec<(i64, i64)> {
    let n = 1i64 << q.log2_n;
    let f = p.pos_frac as i64;
    let at = |c: i64, d: i32, i: i64| {
        let q15 = c * (1 << (15 - f)) + (2 * i - (n - 1)) * i64::from(d);
        let unit = 1i64 << (15 - f);
        (q15 + unit / 2).div_euclid(unit)
    };
    (0..n)
        .map(|i| (at(q.u, q.du, i), at(q.v, q.dv, i)))
        .collect()
}

/// The plain pipeline's tangents (du, dv, height, raw) at each point with its scale.
pub fn plain_tangents(
    p: &BumpParams,
    map: &HeightMap,
    pts: &[(i64, i64, i64)],
) -> Result<Vec<[i64; 3]>, String> {
    let mut sim = Sim::new(NormalPipeline::new("plain", *p, map.clone(), None)?);
    sim.reset(1);
    let mut out = Vec::with_capacity(pts.len());
    for c in 0..pts.len() + 4 {
        let d = &mut sim.dut;
        if let Some(&(u, v, s)) = pts.get(c) {
            d.u.set_raw(u);
            d.v.set_raw(v);
            d.scale.set_raw(s);
            d.valid_in.set_bool(true);
        }
        sim.eval();
        if c >= 4 {
            let t = &sim.dut.tangent;
            out.push([t.du.raw(), t.dv.raw(), t.height.raw()]);
        }
        sim.tick();
    }
    Ok(out)
}

/// What a pixel should give: its tangent average (integer division, rounded half up) and the
/// f64 unit normal of it.
pub type NExpected = (NPixel, [i64; 3], [f64; 3]);

/// The expectations of `px`, in order, from the plain pipeline.
pub fn expectations(
    p: &BumpParams,
    map: &HeightMap,
    px: &[NPixel],
) -> Result<Vec<NExpected>, String> {
    let mut pts = Vec::new();
    for q in px {
        pts.extend(points(p, q).into_iter().map(|(u, v)| (u, v, q.scale)));
    }
    let t = plain_tangents(p, map, &pts)?;
    let one = (1i64 << p.tangent_frac) as f64;
    let mut at = 0;
    Ok(px
        .iter()
        .map(|q| {
            let n = 1i64 << q.log2_n;
            let avg: [i64; 3] = std::array::from_fn(|c| {
                let sum: i64 = t[at..at + n as usize].iter().map(|x| x[c]).sum();
                (2 * sum + n).div_euclid(2 * n)
            });
            at += n as usize;
            let v = [-(avg[0] as f64), -(avg[1] as f64), one];
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            (*q, avg, v.map(|c| c / l))
        })
        .collect())
}

/// The tolerance of normal unit 156 on a component (its unit test's derivation).
pub fn component_tolerance(p: &BumpParams) -> f64 {
    let r = &p.rsqrt;
    golden::rsqrt::error_bound_ulps(r.table_bits, r.iterations, r.y_frac)
        * (-(r.y_frac as f64)).exp2()
        + 2f64.powi(-22)
        + 0.5 * (-(p.out_frac as f64)).exp2()
}

/// Presents a pixel (`px_valid`, position, footprint step, `log2 N`, scale).
pub fn drive_pixel(dut: &mut FootprintNormals, t: Option<&NPixel>) {
    dut.px_valid.set_bool(t.is_some());
    if let Some(t) = t {
        dut.px_u.set_raw(t.u);
        dut.px_v.set_raw(t.v);
        dut.px_du.set_raw(i64::from(t.du));
        dut.px_dv.set_raw(i64::from(t.dv));
        dut.px_log2_n.set_bits(u64::from(t.log2_n));
        dut.px_scale.set_raw(t.scale);
    }
}

/// The unit takes a pixel in a cycle with `px_ready` high.
pub fn pixel_ready(dut: &FootprintNormals) -> bool {
    dut.px_ready.is_high()
}

/// The averaged normal and height, in a cycle with the pipeline's `valid` high.
pub fn sample_normal(dut: &FootprintNormals) -> Option<NOut> {
    let p = &dut.pipe;
    p.valid.is_high().then(|| NOut {
        n: [p.nx.raw(), p.ny.raw(), p.nz.raw()],
        height: p.height.raw(),
    })
}

/// Random pixels over a `w x h` map: the setup unit's N and step of random derivatives
/// (footprints up to 64 texels), scales 0.5 to 4.
pub fn npixels(p: &BumpParams, w: u32, h: u32, n: usize, stim: &mut Stimulus) -> Vec<NPixel> {
    let sp = SetupParams::default();
    let table = *SetupUnit::new("s", sp).expect("default").table();
    let (wl, hl) = (w.ilog2(), h.ilog2());
    let px = pixels(wl, hl, n, stim);
    let scales = stim.draw_n(&(128i64..1024), n);
    let f = p.pos_frac;
    px.iter()
        .zip(scales)
        .map(|(q, scale)| {
            let s = setup(&sp, q.r1, q.r2, &table);
            NPixel {
                u: i64::from(q.u) << f >> 8,
                v: i64::from(q.v) << f >> 8,
                du: s.du,
                dv: s.dv,
                log2_n: s.log2_n,
                scale: scale << p.scale_frac >> 8,
            }
        })
        .collect()
}

const CONFIGS: [(Filter, Border); 4] = [
    (Filter::BSpline, Border::Wrap),
    (Filter::Blinn, Border::Clamp),
    (Filter::Bezier, Border::Mirror),
    (Filter::BSpline, Border::Constant(255)),
];

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let n = c.add(Coverpoint::new("n").values(&["1", "2", "4", "8", "16"]));
    let f = c.add(Coverpoint::new("filter").values(&["bspline", "blinn", "bezier"]));
    c.add(Coverpoint::new("border").values(&["wrap", "clamp", "mirror", "constant"]));
    c.cross("n_x_filter", n, f);
    c
}

/// The regress testbench.
pub struct FootprintNormalsTb;

impl Testbench for FootprintNormalsTb {
    fn about(&self) -> About {
        About::new(NAME, "footprint assembly on the FIG. 7 pipeline (Fenney para. 0081): generator, tangent average before normal unit 156")
            .count(600, "random pixels")
    }
    fn configurations(&self) -> Vec<String> {
        CONFIGS
            .iter()
            .map(|(f, b)| format!("32x32 bumps, {f:?}, {b:?}"))
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (filter, border) = CONFIGS[ctx.index];
        let p = BumpParams {
            filter,
            border,
            ..BumpParams::default()
        };
        let map = crate::maps::builtin("bumps", 32, 32, p.texel_fmt())?;
        let mut stim = Stimulus::new(ctx.seed);
        let mut px = npixels(&p, 32, 32, ctx.count, &mut stim);
        // Every N whatever the count: 1 to 16 squares along u.
        for k in 0..=4 {
            px.push(NPixel {
                u: 10 << p.pos_frac,
                v: 7 << p.pos_frac,
                du: 1 << 14,
                dv: 0,
                log2_n: k,
                scale: 1 << p.scale_frac,
            });
        }
        let want = expectations(&p, &map, &px)?;
        let dut = FootprintNormals::new(NormalPipeline::new("normal_pipeline_fig7", p, map, None)?);
        let (sim, _) = ctx.sim(dut, &format!("{NAME} {}", ctx.label), CYCLE_PS, |_| ())?;
        let (sim, mut res) = run_npixels(sim, ctx, &p, (filter, border), want)?;
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}

/// Drives the pixels with random gaps; scores normals within 156's tolerance of the average's
/// f64 normal and heights equal to the averaged height.
fn run_npixels<T: Trace>(
    mut sim: Sim<FootprintNormals, T>,
    ctx: &Ctx,
    p: &BumpParams,
    (filter, border): (Filter, Border),
    want: Vec<NExpected>,
) -> Result<(Sim<FootprintNormals, T>, TbResult), String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let tol = component_tolerance(p);
    let lsb = (-(p.out_frac as f64)).exp2();
    let mut sb: Scoreboard<NExpected, NOut> =
        Scoreboard::new(move |(_, avg, n): &NExpected, a: &NOut| {
            let within = (0..3).all(|c| (a.n[c] as f64 * lsb - n[c]).abs() <= tol);
            if within && a.height == avg[2] {
                Ok(())
            } else {
                Err(format!("got {a:?}, want {n:?} and height {}", avg[2]))
            }
        });
    let n = want.len() as u64;
    let px: Vec<NPixel> = want.iter().map(|w| w.0).collect();
    let samples: u64 = px.iter().map(|q| 1u64 << q.log2_n).sum();
    let mut fed = 0u64;
    let mut pending = want.into_iter();
    let pacing = Pacing::random(300, ctx.seed.derive(9));
    let mut spec = RunSpec::new(n, 20 * n + 200).pacing(pacing);
    let fi = match filter {
        Filter::BSpline => 0,
        Filter::Blinn => 1,
        Filter::Bezier => 2,
    };
    let bi = crate::normals::border_id(&BumpParams { border, ..*p });
    let r = run(
        &mut sim,
        &mut PinDriver::new(drive_pixel).ready(pixel_ready),
        &mut PinMonitor::new(sample_normal),
        px,
        &mut spec,
        |sim, ev| match ev {
            Event::Sent { .. } => sb.expect(pending.next().expect("one a pixel")),
            Event::Received { cycle, txn } => {
                if let Some((q, _, g)) = sb.observe(cycle, txn).expected {
                    for (got, want) in txn.n.iter().zip(g) {
                        res.stats.record(*got as f64 * lsb, want, lsb);
                    }
                    cov.sample(&[i64::from(q.log2_n), fi, bi]);
                }
            }
            Event::Settled { .. } => fed += u64::from(sim.dut.pipe.valid_in.is_high()),
        },
    );
    res.score(&sb);
    res.ran(&r);
    // The generator feeds the pipeline a pixel's N samples and nothing between pixels.
    if fed != samples {
        res.failures.push(format!(
            "{fed} samples went into the pipeline, the pixels have {samples}"
        ));
    }
    res.notes.push(format!(
        "{}: {n} pixels, normals within {:.2} LSB of the f64 normal of the averaged tangents (156's tolerance {:.2} LSB)",
        ctx.label,
        res.stats.max_abs_lsb,
        tol / lsb
    ));
    res.coverage = Some(cov);
    Ok((sim, res))
}
