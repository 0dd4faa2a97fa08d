//! The derivative filters of para. 0086 (Fenney): the testbench of the unit, its golden
//! comparison, and the render comparison with the FIG. 7 surfaces (the FIG. 8 comparison
//! extended).

use golden::derivative::Kernel;
use hdl::kernel::Sim;
use units::bump::derivative_0086::{five_point, DerivFilter, Derivative, DerivativeUnit};
use units::bump::params::{Border, BumpParams};
use verif::{
    About, Coverage, Coverpoint, Ctx, PinDriver, PinMonitor, RunSpec, Scoreboard, Stimulus,
    TbResult, Testbench,
};
use waves::VcdTracer;

pub const NAME: &str = "derivative_0086";
/// Position fraction bits of the unit's u, v.
pub const POS_FRAC: u32 = 16;

/// The golden kernel of a filter (the table's taps as the integers say).
pub fn kernel(f: &DerivFilter) -> Kernel {
    match f {
        DerivFilter::Central => Kernel::Central,
        DerivFilter::Sobel => Kernel::Sobel,
        DerivFilter::Prewitt => Kernel::Prewitt,
        DerivFilter::Table(c) => Kernel::Taps(c.iter().map(|x| *x as f64 / 4096.0).collect()),
    }
}

/// The filters, as the testbench's configurations.
pub fn filters() -> [DerivFilter; 4] {
    [
        DerivFilter::Central,
        DerivFilter::Sobel,
        DerivFilter::Prewitt,
        DerivFilter::Table(five_point()),
    ]
}

/// The f64 normal of the unit's inputs (raw u, v, scale uQ8.8).
pub fn golden_normal(d: &Derivative, u: i64, v: i64, scale: i64, frac: i32) -> [f64; 3] {
    let h = |x: i64, y: i64| d.height(x, y) as f64 * 2f64.powi(-frac);
    let p = 2f64.powi(-(POS_FRAC as i32));
    golden::derivative::normal(
        &kernel(&d.filter),
        &h,
        u as f64 * p,
        v as f64 * p,
        scale as f64 / 256.0,
    )
}

/// One normalisation's component error (156's rsqrt and the rounding to sQ1.14).
pub fn bound() -> f64 {
    let r = units::bump::params::RsqrtParams::default();
    golden::rsqrt::error_bound_ulps(r.table_bits, r.iterations, r.y_frac)
        * 2f64.powi(-(r.y_frac as i32))
        + 2f64.powi(-15)
        + 1e-12
}

type Query = (i64, i64, i64);

fn drive_query(d: &mut DerivativeUnit, t: Option<&Query>) {
    d.valid_in.set_bool(t.is_some());
    if let Some((u, v, s)) = t {
        d.u.set_raw(*u);
        d.v.set_raw(*v);
        d.scale.set_raw(*s);
    }
}

fn sample_normal(d: &DerivativeUnit) -> Option<[i64; 3]> {
    d.valid
        .q()
        .is_high()
        .then(|| d.n.each_ref().map(|r| r.q().raw()))
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    c.add(Coverpoint::new("slope").values(&["flat", "gentle", "steep"]));
    c.add(Coverpoint::new("edge").values(&["inside", "across the border"]));
    c
}

/// The regress testbench: every filter on the bumps map (wrap) and the noise map (clamp).
pub struct DerivativeTb;

impl Testbench for DerivativeTb {
    fn about(&self) -> About {
        About::new(NAME, "derivative filters of para. 0086 (central, Sobel, Prewitt, antisymmetric table) at four texel centres, bilinear, normal by 156's rsqrt (Fenney)")
            .count(2000, "samples")
    }
    fn configurations(&self) -> Vec<String> {
        filters().iter().map(|f| f.name()).collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let f = filters()[ctx.index].clone();
        let p = BumpParams::default();
        let (name, border) = if ctx.index.is_multiple_of(2) {
            ("bumps", Border::Wrap)
        } else {
            ("noise", Border::Clamp)
        };
        let map = crate::maps::builtin(name, 32, 32, p.texel_fmt())?;
        let frac = map.fmt().frac();
        let mut stim = Stimulus::new(ctx.seed);
        let side = 32i64 << POS_FRAC;
        let mut qs: Vec<Query> = (0..ctx.count.max(16))
            .map(|_| {
                (
                    stim.draw(&(-side / 16..side + side / 16)),
                    stim.draw(&(0..side)),
                    stim.draw(&(0i64..1024)),
                )
            })
            .collect();
        // A flat scale and a steep one whatever the count.
        qs.push((side / 2, side / 3, 0));
        qs.push((side / 2 + 77, side / 3, 1023));
        let d = Derivative::new(f, map, border, POS_FRAC);
        let want: Vec<(Query, [f64; 3])> = qs
            .iter()
            .map(|q| (*q, golden_normal(&d, q.0, q.1, q.2, frac)))
            .collect();
        let (sim, _) = ctx.sim(
            DerivativeUnit::new(d),
            &format!("{NAME} {}", ctx.label),
            10_000,
            |_| (),
        )?;
        run_queries(sim, ctx, want)
    }
}

fn run_queries(
    mut sim: Sim<DerivativeUnit, VcdTracer>,
    ctx: &Ctx,
    want: Vec<(Query, [f64; 3])>,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let lsb = 2f64.powi(-14);
    let b = bound();
    let mut sb: Scoreboard<(Query, [f64; 3]), [i64; 3]> =
        Scoreboard::new(move |(_, g): &(Query, [f64; 3]), a: &[i64; 3]| {
            verif::within(&a.map(|x| x as f64 * lsb), g, b)
        });
    let n = want.len() as u64;
    let mut spec =
        RunSpec::new(n, 3 * n + 50).pacing(verif::Pacing::random(200, ctx.seed.derive(8)));
    let side = 32i64 << POS_FRAC;
    let r = sb.run(
        &mut sim,
        &mut PinDriver::new(drive_query),
        &mut PinMonitor::new(sample_normal),
        want.into_iter().map(|w| (w.0, w)),
        &mut spec,
        |_, (q, g), txn| {
            for c in 0..3 {
                res.stats.record(txn[c] as f64 * lsb, g[c], lsb);
            }
            let tilt = 1.0 - g[2];
            let slope = if tilt < 1e-9 {
                0
            } else if tilt < 0.05 {
                1
            } else {
                2
            };
            let near = 2i64 << POS_FRAC;
            cov.sample(&[slope, i64::from(q.0 < near || q.0 > side - near)]);
        },
    );
    res.score(&sb);
    res.ran(&r);
    res.notes.push(format!(
        "{}: {n} samples, normals within {:.2} LSB of f64 (bound {:.2})",
        ctx.label,
        res.stats.max_abs_lsb,
        b / lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}
