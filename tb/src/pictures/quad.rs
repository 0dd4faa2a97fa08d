//! The map chain's picture in the report: a bumped, detailed, environment-mapped quad through
//! the chain walker 812 (Figure 9), one chip a colour component.

use crate::mapchain::{scene, Maps, Scene, Shape, DETAIL_LOG2, FACE_LOG2, TEX_LOG2};
use units::mapchain::drf_812::Kind;
use units::mapchain::program::ChainRequest;
use units::mapchain::walker_812::walk_pixel;
use units::texram::Border;

/// The direction of texel centre `(x, y)` of face `face` of a `side`-texel cube map (the
/// OpenGL table read backwards).
fn face_direction(face: usize, x: usize, y: usize, side: usize) -> [f64; 3] {
    let s = 2.0 * (x as f64 + 0.5) / side as f64 - 1.0;
    let t = 2.0 * (y as f64 + 0.5) / side as f64 - 1.0;
    let d = match face {
        0 => [1.0, -t, -s],
        1 => [-1.0, -t, s],
        2 => [s, 1.0, t],
        3 => [s, -1.0, -t],
        4 => [s, -t, 1.0],
        _ => [-s, -t, -1.0],
    };
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|c| c / l)
}

/// The picture's maps, one set a colour component: bricks, a grain detail in tiles, a sky
/// over a checkered ground in the cube.
fn picture_maps(c: usize) -> Maps {
    let n = 1usize << TEX_LOG2;
    let brick = [[170u8, 70, 50], [150, 140, 130]];
    let texture = (0..n * n)
        .map(|i| {
            let (x, y) = (i % n, i / n);
            let row = y / 4;
            let mortar = y % 4 == 0 || (x + 4 * (row % 2)) % 8 == 0;
            brick[usize::from(mortar)][c]
        })
        .collect();
    let mut m = Maps::formula();
    m.texture = texture;
    let d = 1usize << DETAIL_LOG2;
    m.detail = (0..d * d)
        .map(|i| {
            let (x, y) = (i % d, i / d);
            let grain = ((x * 7 + y * 3) % 16) * 8 + ((x ^ y) % 5) * 16;
            (255 - grain.min(150)) as u8
        })
        .collect();
    let f = 1usize << FACE_LOG2;
    let (zenith, horizon, ground) = (
        [40.0, 90.0, 200.0],
        [210.0, 215.0, 230.0],
        [90.0, 75.0, 55.0],
    );
    m.faces = (0..6)
        .map(|k| {
            (0..f * f)
                .map(|i| {
                    let dir = face_direction(k, i % f, i / f, f);
                    if dir[1] >= 0.0 {
                        (horizon[c] + (zenith[c] - horizon[c]) * dir[1]) as u8
                    } else {
                        let checker =
                            ((dir[0] / -dir[1]).floor() + (dir[2] / -dir[1]).floor()) as i64;
                        (ground[c] * if checker % 2 == 0 { 1.0 } else { 0.7 }) as u8
                    }
                })
                .collect()
        })
        .collect();
    m
}

/// The picture's scene for colour component `c`: texture -> offsets -> detail (multiply)
/// -> environment (k_s 130).
fn quad_scene(c: usize) -> Result<Scene, String> {
    let m = picture_maps(c);
    let mut sc = scene(Shape::Detail, &m)?;
    let fl = (FACE_LOG2, FACE_LOG2);
    sc.add(6, Kind::Environment, fl, Border::Clamp, m.faces)?
        .k_s = 130;
    if let Some(d) = sc.file.drfs[2].as_mut() {
        d.link = Some(6);
    }
    sc.file.validate()?;
    Ok(sc)
}

/// What the rasterizer sends for pixel `(px, py)` of the quad (`None`: the wall is not
/// there): a quad 5 x 8 units, its centre at (0, -0.5, -5.5), tilted 60 degrees back from
/// facing the eye, bricks 8 x 4 texels of 1/6 unit, the mortar
/// grooves perturbing its normal (eq. 3), the eye vector and I_d (Lambert).
fn quad_pixel(px: usize, py: usize, side: usize) -> Option<ChainRequest> {
    let (ct, st) = (60f64.to_radians().cos(), 60f64.to_radians().sin());
    let (normal, e2) = ([0.0, st, ct], [0.0, ct, -st]);
    let centre = [0.0, -0.5, -5.5];
    let light = [0.3, 0.8, 0.52];
    let per_unit = 6.0;
    let k = 1.6 / side as f64;
    let d = [
        (px as f64 + 0.5) * k - 0.8,
        0.8 - (py as f64 + 0.5) * k,
        -1.0,
    ];
    let len = (d[0] * d[0] + d[1] * d[1] + 1.0).sqrt();
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let denom = dot(d, normal);
    if denom >= 0.0 {
        return None;
    }
    let t = dot(centre, normal) / denom;
    let r = [0, 1, 2].map(|c| d[c] * t - centre[c]);
    let (a, b) = (r[0], dot(r, e2));
    // The quad: 5 units wide, 8 deep.
    if a.abs() > 2.5 || b.abs() > 4.0 {
        return None;
    }
    let (u, v) = (a * per_unit + 32.0, 32.0 - b * per_unit);
    // Texels a pixel: the ray's spread at distance t over the square root of the slant.
    let slant = (denom.abs() / len).max(0.2);
    let lambda = (k * t * len * per_unit / slant.sqrt())
        .log2()
        .clamp(-4.0, 10.0);
    let groove = |x: f64, period: f64| match (x / period).rem_euclid(1.0) {
        f if f < 0.08 => 1.0,
        f if f > 0.92 => -1.0,
        _ => 0.0,
    };
    let b1 = 0.35 * groove(u + 4.0 * ((v / 4.0).floor() % 2.0), 8.0);
    let b2 = 0.35 * groove(v, 4.0);
    let nb = [b1, normal[1] - e2[1] * b2, normal[2] - e2[2] * b2];
    let nl = (nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2]).sqrt();
    let lambert = (0..3).map(|k| nb[k] / nl * light[k]).sum::<f64>().max(0.0);
    let q = |x: f64, f: f64| (x * f).round();
    Some(ChainRequest {
        drf: 0,
        u: q(u, 256.0) as i32,
        v: q(v, 256.0) as i32,
        lambda: q(lambda, 256.0) as i32,
        n: nb.map(|c| q(c, 16384.0) as i64),
        eye: d.map(|c| q(-c / len, 16384.0) as i64),
        face: 0,
        i_d: (60.0 + 195.0 * lambert) as u8,
        i_s: 0,
    })
}

/// A bumped, detailed, environment-mapped quad, `side x side` pixels: each colour component
/// a chain texture -> offsets -> detail -> environment on its own stub (one chip a
/// component in lock-step, configuration 4). The rasterizer's part (`quad_pixel`) is f64.
pub fn render_quad(side: usize) -> Result<Vec<[u8; 3]>, String> {
    let mut chains = Vec::with_capacity(3);
    for c in 0..3 {
        let sc = quad_scene(c)?;
        let stub = sc.stub()?;
        chains.push((sc, stub));
    }
    let mut out = Vec::with_capacity(side * side);
    for py in 0..side {
        for px in 0..side {
            let Some(q) = quad_pixel(px, py, side) else {
                out.push([30, 30, 40]);
                continue;
            };
            q.validate()?;
            let mut rgb = [0u8; 3];
            for (c, (sc, stub)) in chains.iter_mut().enumerate() {
                rgb[c] = walk_pixel(&sc.file, stub, &q)?.colour;
            }
            out.push(rgb);
        }
    }
    Ok(out)
}
