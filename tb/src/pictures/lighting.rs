//! Dot3 lighting of a height map through the FIG. 7 pipeline: the pictures of `texrtl render`
//! and of the report (FIG. 8a against 8b).

use crate::runs::normals::{run_normals, NormalsOutcome, NormalsRun, RawNormal, Sample};
use units::bump::height_map::HeightMap;
use units::bump::params::{BumpParams, Filter};
use verif::Seed;
use waves::TraceConfig;

fn dot3(n: [f64; 3], l: [f64; 3]) -> f64 {
    (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0)
}

/// The pipeline's normals of `map` at `zoom` samples a texel (pixel centres), row by row.
fn zoomed(
    map: &HeightMap,
    p: &BumpParams,
    scale: f64,
    zoom: u32,
) -> Result<NormalsOutcome, String> {
    let (w, h) = (map.width() * zoom, map.height() * zoom);
    let z = f64::from(zoom);
    let samples: Vec<Sample> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| Sample {
            u: (f64::from(x) + 0.5) / z,
            v: (f64::from(y) + 0.5) / z,
            scale,
            lod: 0.0,
        })
        .collect();
    run_normals(&NormalsRun {
        name: format!("render {}", p.filter),
        params: *p,
        map: map.clone(),
        samples,
        idle_per_mille: 0,
        vcd: None,
        trace: TraceConfig::default(),
        check_accuracy: false,
        check_schedule: false,
        seed: Seed(0),
    })
}

/// Dot3 intensities (0..=255) of the FIG. 7 pipeline with `p` at `zoom` samples a texel
/// under the unit light `l`, row by row.
pub fn dot3_panel(
    map: &HeightMap,
    p: &BumpParams,
    l: [f64; 3],
    scale: f64,
    zoom: u32,
) -> Result<Vec<u8>, String> {
    let run = zoomed(map, p, scale, zoom)?;
    let nf = p.normal_fmt();
    Ok(run
        .outputs
        .iter()
        .map(|n| {
            let i = dot3(n.n.map(|x| crate::normals::real(x, nf)), l);
            (i * 255.0).round().clamp(0.0, 255.0) as u8
        })
        .collect())
}

/// The four-panel Dot3 picture as PNG bytes (Blinn | B-spline | golden | heat map of the
/// B-spline's error), and the worst intensity error of the B-spline panel against golden.
pub fn render_png(
    map: &HeightMap,
    p: &BumpParams,
    light: [f64; 3],
    scale: f64,
    zoom: u32,
) -> Result<(Vec<u8>, f64), String> {
    let (w, h) = (map.width() * zoom, map.height() * zoom);
    let l = {
        // Scaled by the largest component first, so no square overflows (1e200,0,0 is +x).
        let m = light.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let d = light.map(|x| x / m);
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        d.map(|x| x / n)
    };
    let run = |filter: Filter| zoomed(map, &BumpParams { filter, ..*p }, scale, zoom);
    let blinn = run(Filter::Blinn)?;
    let bspline = run(Filter::BSpline)?;
    let nf = p.normal_fmt();
    let intensity = |n: &RawNormal| dot3(n.n.map(|x| crate::normals::real(x, nf)), l);
    let mut img = image::RgbImage::new(4 * w + 3 * 4, h);
    let mut worst = 0.0f64;
    for k in 0..bspline.outputs.len() {
        let (x, y) = (k as u32 % w, k as u32 / w);
        let ib = intensity(&blinn.outputs[k]);
        let is = intensity(&bspline.outputs[k]);
        let ig = dot3(bspline.golden[k], l);
        let grey = |i: f64| {
            let g = (i * 255.0).round().clamp(0.0, 255.0) as u8;
            image::Rgb([g, g, g])
        };
        img.put_pixel(x, y, grey(ib));
        img.put_pixel(w + 4 + x, y, grey(is));
        img.put_pixel(2 * (w + 4) + x, y, grey(ig));
        let e = (is - ig).abs();
        worst = worst.max(e);
        img.put_pixel(3 * (w + 4) + x, y, heat(e));
    }
    Ok((
        verif::plot::png(img.width(), img.height(), img.as_raw())?,
        worst,
    ))
}

/// Log-scale heat colour: black below 2^-24, through blue, red and yellow to white at 2^-8.
fn heat(e: f64) -> image::Rgb<u8> {
    let t = if e <= 0.0 {
        0.0
    } else {
        ((e.log2() + 24.0) / 16.0).clamp(0.0, 1.0)
    };
    let stops = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 1.0],
    ];
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let c =
        [0, 1, 2].map(|k| ((stops[i][k] * (1.0 - f) + stops[i + 1][k] * f) * 255.0).round() as u8);
    image::Rgb(c)
}
