//! Bi-quadratic colour filtering of para. 0087: the unit's testbench against the f64
//! B-spline of the same texels (with the declared 8-bit t), within half an LSB.

use hdl::kernel::Sim;
use units::bump::biquadratic_0087::{Biquadratic0087, ColourMap, POS_FRAC};
use units::bump::params::Border;
use verif::{
    About, Coverage, Coverpoint, Ctx, PinDriver, PinMonitor, RunSpec, Scoreboard, Stimulus,
    TbResult, Testbench,
};
use waves::VcdTracer;

pub const NAME: &str = "biquadratic_0087";

/// The f64 filter: B0 = (1 - t)^2 / 2, B1 = (1 + 2t - 2t^2) / 2, B2 = t^2 / 2 on each axis, t
/// the fraction inside the nearest texel truncated to 8 bits.
pub fn golden(m: &ColourMap, u: i64, v: i64) -> [f64; 3] {
    let ax = |c: i64| {
        let x = c as f64 / 65536.0;
        let i = x.floor();
        let t = ((x - i) * 256.0).floor() / 256.0;
        (
            i as i64,
            [
                (1.0 - t) * (1.0 - t) / 2.0,
                (1.0 + 2.0 * t - 2.0 * t * t) / 2.0,
                t * t / 2.0,
            ],
        )
    };
    let ((i, wu), (j, wv)) = (ax(u), ax(v));
    let mut s = [0.0; 3];
    for (dy, wy) in wv.iter().enumerate() {
        for (dx, wx) in wu.iter().enumerate() {
            let t = m.texel(i + dx as i64 - 1, j + dy as i64 - 1);
            for c in 0..3 {
                s[c] += f64::from(t[c]) * wx * wy;
            }
        }
    }
    s
}

/// A colour map: smooth ramps in R, a checker in G, noise in B.
pub fn test_map(n: u32, border: Border, stim: &mut Stimulus) -> ColourMap {
    let noise = stim.draw_n(&(0u8..=255), (n * n) as usize);
    let rgb = (0..n * n)
        .flat_map(|k| {
            let (x, y) = (k % n, k / n);
            [
                (x * 7 + y * 3) as u8,
                if (x / 2 + y / 2) % 2 == 0 { 230 } else { 20 },
                noise[k as usize],
            ]
        })
        .collect();
    ColourMap {
        width: n,
        height: n,
        rgb,
        border,
    }
}

fn drive_uv(d: &mut Biquadratic0087, t: Option<&(i64, i64)>) {
    d.valid_in.set_bool(t.is_some());
    if let Some((u, v)) = t {
        d.u.set_raw(*u);
        d.v.set_raw(*v);
    }
}

fn sample_rgb(d: &Biquadratic0087) -> Option<[u8; 3]> {
    d.valid
        .q()
        .is_high()
        .then(|| d.rgb.each_ref().map(|r| r.q().bits() as u8))
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    c.add(Coverpoint::new("t").ranges("t", 0, 255, 4));
    c.add(Coverpoint::new("edge").values(&["inside", "across the border"]));
    c
}

/// The regress testbench: wrap and clamp borders.
pub struct BiquadraticTb;

impl Testbench for BiquadraticTb {
    fn about(&self) -> About {
        About::new(NAME, "bi-quadratic B-spline colour filter of para. 0087 over 3 x 3 texels, per channel (Fenney)")
            .count(2000, "samples")
    }
    fn configurations(&self) -> Vec<String> {
        vec!["16x16 wrap".into(), "16x16 clamp".into()]
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let border = if ctx.index == 0 {
            Border::Wrap
        } else {
            Border::Clamp
        };
        let mut stim = Stimulus::new(ctx.seed);
        let map = test_map(16, border, &mut stim);
        let side = 16i64 << POS_FRAC;
        let qs: Vec<(i64, i64)> = (0..ctx.count.max(16))
            .map(|k| {
                let u = stim.draw(&(-side / 8..side + side / 8));
                let v = if k % 8 == 0 {
                    stim.draw(&(0..side / 16))
                } else {
                    stim.draw(&(0..side))
                };
                (u, v)
            })
            .collect();
        let (sim, _) = ctx.sim(
            Biquadratic0087::new(map.clone())?,
            &format!("{NAME} {}", ctx.label),
            10_000,
            |_| (),
        )?;
        run_samples(sim, ctx, &map, qs)
    }
}

fn run_samples(
    mut sim: Sim<Biquadratic0087, VcdTracer>,
    ctx: &Ctx,
    map: &ColourMap,
    qs: Vec<(i64, i64)>,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let m2 = map.clone();
    let mut sb: Scoreboard<(i64, i64), [u8; 3]> =
        Scoreboard::new(move |q: &(i64, i64), a: &[u8; 3]| {
            verif::within(&a.map(f64::from), &golden(&m2, q.0, q.1), 0.5 + 1e-9)
        });
    let n = qs.len() as u64;
    let mut spec =
        RunSpec::new(n, 3 * n + 50).pacing(verif::Pacing::random(200, ctx.seed.derive(9)));
    let side = 16i64 << POS_FRAC;
    let r = sb.run(
        &mut sim,
        &mut PinDriver::new(drive_uv),
        &mut PinMonitor::new(sample_rgb),
        qs.into_iter().map(|q| (q, q)),
        &mut spec,
        |_, q, txn| {
            let g = golden(map, q.0, q.1);
            for c in 0..3 {
                res.stats.record(f64::from(txn[c]), g[c], 1.0);
            }
            let edge = q.0 < 1 << POS_FRAC || q.0 >= side - (1 << POS_FRAC) || q.1 < 1 << POS_FRAC;
            cov.sample(&[(q.0 >> (POS_FRAC - 8)) & 255, i64::from(edge)]);
        },
    );
    res.score(&sb);
    res.ran(&r);
    res.notes.push(format!(
        "{}: {n} samples within {:.3} LSB of f64",
        ctx.label, res.stats.max_abs_lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}
