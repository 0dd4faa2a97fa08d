//! Testbench of the FIG. 7 normal pipeline (`units::bump::normal_pipeline`) against the surfaces of
//! `golden::bump`: its references, accuracy criterion, coverage model and stimulus. The run
//! that drives the pipeline (what the `normals`, `render` and `sweep normals` commands run
//! too) is [`crate::runs::normals`].
//!
//! Stimulus is a list of samples (position, height scale, MIP weight). Inputs are quantised to
//! the pipeline's formats first (positions and scale round to nearest, ties to even; a position
//! outside the format's range is an error, not clamped), and the golden model is evaluated at
//! exactly the quantised inputs, so the measured error is the pipeline's own.
//!
//! Accuracy criterion (default widths, positions exact in the blend-factor format): every
//! component within `2^-13` of the golden normal and every normal within 0.01 degrees of it.

use crate::runs::normals::{run_normals, NormalsRun, RawNormal, RawSample, Sample};
use golden::bump::{self as g, Heights};
use hdl::fx::{Format, Fx};
use serde::{Deserialize, Serialize};
use units::bump::height_map::HeightMap;
use units::bump::params::{Border, BumpParams, Filter};
use verif::{About, Coverage, Coverpoint, Ctx, Scoreboard, TbResult, Testbench};

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

pub(crate) fn golden_border(p: &BumpParams) -> g::Border {
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

/// Component tolerance of the accuracy criterion.
pub const COMPONENT_TOL: f64 = 1.0 / 8192.0;
/// Angle tolerance of the accuracy criterion, degrees.
pub const ANGLE_TOL_DEG: f64 = 0.01;

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
pub(crate) fn scoreboard(nf: Format) -> Scoreboard<([f64; 3], f64), RawNormal> {
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
pub(crate) fn coverage_bins(
    p: &BumpParams,
    fine: &Heights,
    (w, h): (i64, i64),
    s: &RawSample,
) -> [i64; 6] {
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
