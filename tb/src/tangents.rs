//! The testbench of the fixed-point tangent setup unit (003); the host's per-corner frames it
//! is the hardware side of are in [`crate::runs::tangents`].

use golden::tangents::{add, cross, face_tangent, normalize, orthonormal, scale, Frame};
use hdl::kernel::Sim;
use units::frames::tangent_setup::{TangentSetup, POS_FRAC, VEC_FRAC};
use verif::{
    About, Coverage, Coverpoint, Ctx, PinDriver, PinMonitor, RunSpec, Scoreboard, Stimulus,
    TbResult, Testbench,
};
use waves::VcdTracer;

pub const NAME: &str = "tangent_setup";

/// One triangle for the setup unit: edges (sQ7.16), UV edges (sQ3.16), unit normal
/// (sQ1.14), raw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tri {
    pub v: [[i64; 3]; 2],
    pub d: [[i64; 2]; 2],
    pub n: [i64; 3],
}

/// What the unit gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SetupOut {
    pub t: [i64; 3],
    pub b: [i64; 3],
    pub dpdu: [i64; 3],
    pub degenerate: bool,
    pub zero: bool,
}

/// The f64 frame of a triangle as the unit sees it (its quantised inputs) and the bound on
/// t's and b's components: the inverse square root's relative error, the rounding, and the
/// direction error of dP/du's rounding (sqrt 3 2^-17 over the length of its part across n).
pub fn golden_setup(q: &Tri) -> (golden::tangents::FaceTangent, Frame, f64) {
    let f = |x: i64, k: u32| x as f64 * 2f64.powi(-(k as i32));
    let p = [
        [0.0; 3],
        q.v[0].map(|x| f(x, POS_FRAC)),
        q.v[1].map(|x| f(x, POS_FRAC)),
    ];
    let uv = [
        [0.0; 2],
        q.d[0].map(|x| f(x, POS_FRAC)),
        q.d[1].map(|x| f(x, POS_FRAC)),
    ];
    let n = q.n.map(|x| f(x, VEC_FRAC));
    let ft = face_tangent(p, uv);
    let fr = orthonormal(n, ft.dpdu, ft.dpdv);
    let across = {
        let d = golden::tangents::dot(n, ft.dpdu);
        let r = golden::tangents::sub(ft.dpdu, scale(n, d));
        golden::tangents::dot(r, r).sqrt()
    };
    let r = units::bump::params::RsqrtParams::default();
    let rs = golden::rsqrt::error_bound_ulps(r.table_bits, r.iterations, r.y_frac)
        * 2f64.powi(-(r.y_frac as i32));
    // |n| differs from 1 by its own rounding: up to sqrt 3 2^-15.
    let bound = 2.0 * rs
        + 2f64.powi(-15)
        + 3f64.sqrt() * 2f64.powi(-17) * 4.0 / across.max(1e-30)
        + 3f64.sqrt() * 2f64.powi(-15);
    (ft, fr, bound)
}

fn drive_tri(dut: &mut TangentSetup, t: Option<&Tri>) {
    dut.valid_in.set_bool(t.is_some());
    if let Some(t) = t {
        for r in 0..2 {
            for c in 0..3 {
                dut.v[r][c].set_raw(t.v[r][c]);
            }
            for c in 0..2 {
                dut.d[r][c].set_raw(t.d[r][c]);
            }
        }
        for c in 0..3 {
            dut.n[c].set_raw(t.n[c]);
        }
    }
}

fn sample_setup(d: &TangentSetup) -> Option<SetupOut> {
    let raw = |r: &[hdl::kernel::Reg; 3]| r.each_ref().map(|x| x.q().raw());
    d.valid.q().is_high().then(|| SetupOut {
        t: raw(&d.t),
        b: raw(&d.b),
        dpdu: raw(&d.dpdu),
        degenerate: d.degenerate.q().is_high(),
        zero: d.zero.q().is_high(),
    })
}

/// Random triangles: positions within 8 units, UVs within 2, the face normal (or a
/// perturbed one, as a vertex normal); every eighth with UVs on a line, every sixteenth all
/// equal, every sixteenth with its first edge a point in UV (the second edge gives dP/du),
/// and half with the UV triangle mirrored.
pub fn triangles(n: usize, stim: &mut Stimulus) -> Vec<Tri> {
    let one = 1i64 << POS_FRAC;
    (0..n)
        .map(|i| {
            let v = [0, 1].map(|_| [0, 1, 2].map(|_| stim.draw(&(-8 * one..8 * one))));
            let mut d = [0, 1].map(|_| [0, 1].map(|_| stim.draw(&(-2 * one..2 * one))));
            match i % 16 {
                7 => d[1] = [d[0][0] * 2, d[0][1] * 2],
                15 => d = [[0, 0], [0, 0]],
                3 => d[0] = [0, 0],
                k if k % 2 == 1 => d = d.map(|x| [-x[0], x[1]]),
                _ => {}
            }
            let fv = |k: usize| v[k].map(|x| x as f64);
            let (nf, _) = normalize(cross(fv(0), fv(1)));
            let jitter = f64::from(stim.draw(&(0u32..3))) * 0.1;
            let (nv, _) = normalize(add(nf, [jitter, -jitter, 0.0]));
            let n = nv.map(|c| (c * 16384.0).round() as i64);
            Tri { v, d, n }
        })
        .collect()
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    // A degenerate triangle has no dP/dv: its handedness is right by definition.
    c.add(Coverpoint::new("uvs").values(&[
        "triangle",
        "on a line",
        "one point",
        "first edge a point",
    ]));
    c.add(Coverpoint::new("handedness").values(&["right", "left"]));
    c
}

/// The regress testbench of the tangent setup unit.
pub struct TangentSetupTb;

impl Testbench for TangentSetupTb {
    fn about(&self) -> About {
        About::new(NAME, "tangent setup: dP/du, dP/dv by the reciprocal of the UV determinant (table + Newton), Gram-Schmidt and the general handedness (003)")
            .count(3000, "triangles")
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let mut stim = Stimulus::new(ctx.seed);
        let tris = triangles(ctx.count.max(32), &mut stim);
        let (sim, _) = ctx.sim(
            TangentSetup::new(),
            &format!("{NAME} {}", ctx.label),
            10_000,
            |_| (),
        )?;
        run_setup(sim, ctx, tris)
    }
}

/// Whether the unit's result is the f64 frame's within the bound.
fn check(q: &Tri, a: &SetupOut) -> Result<(), String> {
    let (ft, fr, bound) = golden_setup(q);
    let lsb = 2f64.powi(-(VEC_FRAC as i32));
    if a.degenerate != ft.degenerate || a.zero != fr.zero {
        return Err(format!(
            "flags {} {}, f64 {} {}",
            a.degenerate, a.zero, ft.degenerate, fr.zero
        ));
    }
    if a.zero {
        return if a.t == [0; 3] {
            Ok(())
        } else {
            Err("a zero tangent not zero".into())
        };
    }
    for c in 0..3 {
        let (t, b) = (a.t[c] as f64 * lsb, a.b[c] as f64 * lsb);
        if (t - fr.t[c]).abs() > bound || (b - fr.b[c]).abs() > 2.0 * bound + lsb {
            return Err(format!(
                "t {:?} b {:?}: f64 {:?} {:?} (bound {bound:.2e})",
                a.t, a.b, fr.t, fr.b
            ));
        }
    }
    Ok(())
}

fn run_setup(
    mut sim: Sim<TangentSetup, VcdTracer>,
    ctx: &Ctx,
    tris: Vec<Tri>,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let mut sb: Scoreboard<Tri, SetupOut> = Scoreboard::new(check);
    let n = tris.len() as u64;
    let mut spec =
        RunSpec::new(n, 3 * n + 50).pacing(verif::Pacing::random(200, ctx.seed.derive(5)));
    let lsb = 2f64.powi(-(VEC_FRAC as i32));
    let r = sb.run(
        &mut sim,
        &mut PinDriver::new(drive_tri),
        &mut PinMonitor::new(sample_setup),
        tris.into_iter().map(|q| (q, q)),
        &mut spec,
        |_, q, txn| {
            let (ft, fr, _) = golden_setup(&q);
            if !fr.zero {
                for c in 0..3 {
                    res.stats.record(txn.t[c] as f64 * lsb, fr.t[c], lsb);
                }
            }
            let kind = match (ft.degenerate, fr.zero) {
                (false, _) => 0,
                (true, false) if q.d[0] == [0, 0] => 3,
                (true, false) => 1,
                (true, true) => 2,
            };
            let hand = golden::tangents::handedness(fr.n, fr.t, ft.dpdv);
            cov.sample(&[kind, i64::from(hand < 0.0)]);
        },
    );
    res.score(&sb);
    res.ran(&r);
    res.notes.push(format!(
        "{}: {n} triangles, t within {:.2} LSB of the f64 Gram-Schmidt frame",
        ctx.label, res.stats.max_abs_lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}
