//! PTM micro-occlusion (US 2004/0207631's companion 001, paragraphs \[0029\]-\[0061\]) in f64,
//! from the text and sharing nothing with `hdl`: the sample generator 602 (a tileable height
//! field, binary occlusion toward each light of a dome), the least-squares fit 604 by QR,
//! the evaluation of the polynomial and its clamp.
//!
//! * Basis \[0030\]: `K = A1 u^2 + A2 u + A3 u v + A4 v + A5 v^2 + A6`, total degree 2 (six
//!   terms, not the nine of a tensor bi-quadratic); `(u, v)` the light vector projected onto
//!   the surface's tangent plane, `u = L.T`, `v = L.B`.
//! * Polarity: K is the occlusion, 0 lit and 1 occluded \[0036\]; the sample images are white
//!   where lit \[0044, 0047\], so the fit takes `K_i = 1 - sample_i`.
//! * The cubic basis of \[0037\] as printed (`A1 u + A2 v^3 ...`) repeats the linear term u; it
//!   must read `A1 u^3` (claims 18, 27): [`Basis::Cubic`] is the corrected one,
//!   [`printed_cubic`] the printed one (its design matrix is singular, see the tests).

/// The bases of a PTM.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Basis {
    /// The six terms of \[0030\] in the order A1 .. A6: u^2, u, uv, v, v^2, 1.
    Quadratic,
    /// The corrected cubic basis of \[0037\]: u^3, v^3, u^2 v^2, u^2 v, u v^2, u^2, v^2, uv, u, v, 1.
    Cubic,
}

impl Basis {
    pub fn terms(self) -> usize {
        match self {
            Basis::Quadratic => 6,
            Basis::Cubic => 11,
        }
    }

    /// The terms at `(u, v)`.
    pub fn row(self, u: f64, v: f64) -> Vec<f64> {
        match self {
            Basis::Quadratic => vec![u * u, u, u * v, v, v * v, 1.0],
            Basis::Cubic => vec![
                u * u * u,
                v * v * v,
                u * u * v * v,
                u * u * v,
                u * v * v,
                u * u,
                v * v,
                u * v,
                u,
                v,
                1.0,
            ],
        }
    }

    /// The fit's design matrix over a dome: one [`Basis::row`] a light, at its `(u, v)`.
    pub fn rows(self, lights: &[Light]) -> Vec<Vec<f64>> {
        lights
            .iter()
            .map(|l| {
                let (u, v) = l.uv();
                self.row(u, v)
            })
            .collect()
    }
}

/// The cubic basis as \[0037\] prints it: `A1 u` where `A1 u^3` is meant (u appears twice).
pub fn printed_cubic(u: f64, v: f64) -> Vec<f64> {
    vec![
        u,
        v * v * v,
        u * u * v * v,
        u * u * v,
        u * v * v,
        u * u,
        v * v,
        u * v,
        u,
        v,
        1.0,
    ]
}

/// The quadratic PTM's value at `(u, v)`, held to [0, 1].
pub fn evaluate(c: &[f64; 6], u: f64, v: f64) -> f64 {
    let r = Basis::Quadratic.row(u, v);
    (0..6).map(|j| c[j] * r[j]).sum::<f64>().clamp(0.0, 1.0)
}

/// A light of the dome: elevation above the surface and azimuth, in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub elevation: f64,
    pub azimuth: f64,
}

impl Light {
    /// The unit vector toward the light (z the surface normal, x = T, y = B).
    pub fn dir(self) -> [f64; 3] {
        let (e, a) = (self.elevation.to_radians(), self.azimuth.to_radians());
        [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
    }

    /// `(u, v)`: the direction projected onto the tangent plane.
    pub fn uv(self) -> (f64, f64) {
        let d = self.dir();
        (d[0], d[1])
    }
}

/// A dome of `rings` elevations (evenly from 15 to 75 degrees) times `azimuths` directions.
pub fn dome(rings: usize, azimuths: usize) -> Vec<Light> {
    let mut v = Vec::with_capacity(rings * azimuths);
    for r in 0..rings {
        let elevation = if rings == 1 {
            45.0
        } else {
            15.0 + 60.0 * r as f64 / (rings - 1) as f64
        };
        for a in 0..azimuths {
            // Alternate rings are turned by half a step: more distinct (u, v).
            let azimuth = (a as f64 + 0.5 * (r % 2) as f64) * 360.0 / azimuths as f64;
            v.push(Light { elevation, azimuth });
        }
    }
    v
}

/// Householder QR of the `m x n` matrix `a` (rows), `m >= n`: `(qt_b, r)` for each right-hand
/// side in `b`; `None` when a diagonal of R is below `1e-9` of the largest column norm
/// (rank deficient).
fn householder(a: &[Vec<f64>], rhs: &mut [Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let (m, n) = (a.len(), a.first().map_or(0, Vec::len));
    if m < n || n == 0 {
        return None;
    }
    let mut r: Vec<Vec<f64>> = a.to_vec();
    let scale = (0..n)
        .map(|j| (0..m).map(|i| r[i][j] * r[i][j]).sum::<f64>().sqrt())
        .fold(0.0f64, f64::max);
    for k in 0..n {
        let norm = (k..m).map(|i| r[i][k] * r[i][k]).sum::<f64>().sqrt();
        if norm <= 1e-9 * scale {
            return None;
        }
        let alpha = if r[k][k] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = (k..m).map(|i| r[i][k]).collect();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        #[allow(clippy::needless_range_loop)] // column j of the rows below k
        for j in k..n {
            let f = 2.0 * (k..m).map(|i| v[i - k] * r[i][j]).sum::<f64>() / vv;
            for i in k..m {
                r[i][j] -= f * v[i - k];
            }
        }
        for b in rhs.iter_mut() {
            let f = 2.0 * (k..m).map(|i| v[i - k] * b[i]).sum::<f64>() / vv;
            for i in k..m {
                b[i] -= f * v[i - k];
            }
        }
    }
    Some(r)
}

/// Back substitution of the upper triangle of `r` (n x n) on `y`.
fn solve_upper(r: &[Vec<f64>], y: &[f64], n: usize) -> Vec<f64> {
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| r[i][j] * x[j]).sum();
        x[i] = (y[i] - s) / r[i][i];
    }
    x
}

/// The least-squares coefficients of `k` over the design rows `a` by QR (not the normal
/// equations); `None` when `a` is rank deficient.
pub fn fit(a: &[Vec<f64>], k: &[f64]) -> Option<Vec<f64>> {
    let n = a.first()?.len();
    let mut rhs = vec![k.to_vec()];
    let r = householder(a, &mut rhs)?;
    Some(solve_upper(&r, &rhs[0], n))
}

/// The pseudo-inverse `P = (A^T A)^-1 A^T` of the design rows `a` (n x m, column i for row i
/// of `a`), by QR: each column solves for the unit vector e_i.
pub fn pseudo_inverse(a: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let (m, n) = (a.len(), a.first()?.len());
    let mut rhs: Vec<Vec<f64>> = (0..m)
        .map(|i| (0..m).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    let r = householder(a, &mut rhs)?;
    let cols: Vec<Vec<f64>> = rhs.iter().map(|y| solve_upper(&r, y, n)).collect();
    Some(
        (0..n)
            .map(|j| cols.iter().map(|c| c[j]).collect())
            .collect(),
    )
}

/// A tileable height field of `n x n` texels (heights in texel units): woven sinusoids, the
/// threads of a cloth, periodic in n.
pub fn woven(n: usize, amplitude: f64) -> Vec<f64> {
    let w = std::f64::consts::TAU / n as f64;
    (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            let weft = (w * 4.0 * y).sin().max(0.0) * (w * 4.0 * x).cos();
            let warp = (w * 4.0 * x).sin().max(0.0) * (w * 4.0 * y).cos();
            amplitude * (1.0 + 0.5 * (weft - warp))
        })
        .collect()
}

/// The height at `(x, y)`, bilinear between texel centres, the field repeated (the 3 x 3
/// tiles of \[0061\]: any neighbour of a border texel is the opposite border's).
fn height_at(h: &[f64], n: usize, x: f64, y: f64) -> f64 {
    let (x0, y0) = (x.floor(), y.floor());
    let (a, b) = (x - x0, y - y0);
    let t = |dx: f64, dy: f64| {
        let i = ((x0 + dx) as i64).rem_euclid(n as i64) as usize;
        let j = ((y0 + dy) as i64).rem_euclid(n as i64) as usize;
        h[j * n + i]
    };
    (1.0 - a) * (1.0 - b) * t(0.0, 0.0)
        + a * (1.0 - b) * t(1.0, 0.0)
        + (1.0 - a) * b * t(0.0, 1.0)
        + a * b * t(1.0, 1.0)
}

/// How far a ray marches toward its light at most, in swatch widths: a grazing light (its ray
/// still below the field's highest point after 16 swatches) counts as occluded, so the march is
/// bounded at every elevation in (0, 90] (steps grow as 1/tan(elevation) otherwise).
pub const MAX_MARCH_SWATCHES: usize = 16;

/// Whether texel `(x, y)` sees light `l`: a ray from its top toward the light, in quarter
/// texel steps, stays above the field until it is above the field's highest point, within
/// [`MAX_MARCH_SWATCHES`] swatch widths (beyond: occluded).
pub fn lit(h: &[f64], n: usize, x: usize, y: usize, l: Light) -> bool {
    let d = l.dir();
    let top = h.iter().copied().fold(f64::MIN, f64::max);
    let flat = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if flat < 1e-12 {
        return true;
    }
    let (sx, sy, sz) = (d[0] / flat * 0.25, d[1] / flat * 0.25, d[2] / flat * 0.25);
    let (mut px, mut py) = (x as f64, y as f64);
    let mut pz = h[y * n + x] + 1e-6;
    // Quarter-texel steps over at most MAX_MARCH_SWATCHES widths.
    let mut left = 4 * n * MAX_MARCH_SWATCHES;
    while pz <= top {
        if left == 0 {
            return false;
        }
        left -= 1;
        px += sx;
        py += sy;
        pz += sz;
        if height_at(h, n, px, py) > pz {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Data made from the basis is recovered exactly (to rounding); the residual of any data
    /// is orthogonal to the basis.
    #[test]
    fn the_fit_recovers_the_basis_and_its_residual_is_orthogonal() {
        let lights = dome(3, 8);
        for b in [Basis::Quadratic, Basis::Cubic] {
            let a = b.rows(&lights);
            let c: Vec<f64> = (0..b.terms()).map(|j| 0.3 - 0.1 * j as f64).collect();
            let k: Vec<f64> = a
                .iter()
                .map(|r| r.iter().zip(&c).map(|(x, y)| x * y).sum())
                .collect();
            let got = fit(&a, &k).unwrap();
            assert!(
                got.iter().zip(&c).all(|(x, y)| (x - y).abs() < 1e-10),
                "{got:?}"
            );
            let noisy: Vec<f64> = (0..k.len()).map(|i| f64::from((i * 7 % 5) as u8)).collect();
            let c = fit(&a, &noisy).unwrap();
            for j in 0..b.terms() {
                let dot: f64 = (0..a.len())
                    .map(|i| {
                        let pred: f64 = a[i].iter().zip(&c).map(|(x, y)| x * y).sum();
                        a[i][j] * (noisy[i] - pred)
                    })
                    .sum();
                assert!(dot.abs() < 1e-9, "{b:?} {j} {dot}");
            }
            // The pseudo-inverse gives the same coefficients.
            let p = pseudo_inverse(&a).unwrap();
            for j in 0..b.terms() {
                let x: f64 = (0..a.len()).map(|i| p[j][i] * noisy[i]).sum();
                assert!((x - c[j]).abs() < 1e-9);
            }
        }
    }

    /// One ring of lights makes u^2 + v^2 constant: u^2, v^2 and 1 are dependent and the fit
    /// has no unique answer; two rings fix it.
    #[test]
    fn one_ring_of_lights_is_singular() {
        assert!(fit(&Basis::Quadratic.rows(&dome(1, 12)), &[0.5; 12]).is_none());
        assert!(fit(&Basis::Quadratic.rows(&dome(2, 6)), &[0.5; 12]).is_some());
    }

    /// \[0037\] as printed repeats u: its design matrix is rank deficient on any dome; with
    /// `A1 u^3` it is not.
    #[test]
    fn the_printed_cubic_basis_is_singular() {
        let lights = dome(4, 8);
        let printed: Vec<Vec<f64>> = lights
            .iter()
            .map(|l| {
                let (u, v) = l.uv();
                printed_cubic(u, v)
            })
            .collect();
        assert!(fit(&printed, &vec![0.5; lights.len()]).is_none());
        assert!(fit(&Basis::Cubic.rows(&lights), &vec![0.5; lights.len()]).is_some());
    }

    /// A flat field is lit from everywhere; a deep pit is not lit from a low light.
    #[test]
    fn a_grazing_light_marches_a_bounded_distance() {
        // A field with one bump: at 1e-300 degrees the ray never rises; it stops after the
        // bounded march, occluded. At 30 degrees the bound is never reached.
        let n = 8;
        let mut h = vec![0.0; n * n];
        h[3 * n + 5] = 2.0;
        let grazing = Light {
            elevation: 1e-300,
            azimuth: 0.0,
        };
        let t0 = std::time::Instant::now();
        assert!(!lit(&h, n, 0, 0, grazing));
        assert!(t0.elapsed().as_secs() < 2);
        let steep = Light {
            elevation: 30.0,
            azimuth: 0.0,
        };
        // From the bump's top the ray starts above everything: lit at once.
        assert!(lit(&h, n, 5, 3, steep));
        assert!(
            lit(&h, n, 5, 3, grazing),
            "the highest texel sees every light"
        );
    }

    #[test]
    fn occlusion_by_marching() {
        let flat = vec![1.0; 16 * 16];
        for l in dome(3, 8) {
            assert!(lit(&flat, 16, 3, 4, l));
        }
        let mut pit = vec![4.0; 16 * 16];
        pit[8 * 16 + 8] = 0.0;
        let low = Light {
            elevation: 20.0,
            azimuth: 0.0,
        };
        assert!(!lit(&pit, 16, 8, 8, low));
        assert!(lit(&pit, 16, 3, 3, low));
    }
}
