//! Height surfaces and their normals, from the mathematics (US 2004/0207631, para. 0026-0031,
//! 0081-0085), for checking the FIG. 7 pipeline.
//!
//! Conventions: positions in texel units; texel `(i, j)` covers `[i, i+1) x [j, j+1)` and
//! its value stands at the texel's centre `(i + 1/2, j + 1/2)`; heights in texel units (the
//! raw texel over `2^frac`, e.g. an 8-bit texel / 4), times the height scale. The normal is
//! `normalize(-dH/du, -dH/dv, 1)`: x along +u, y along +v, z up.
//!
//! * **B-spline** (the preferred embodiment): the uniform bi-quadratic B-spline with the
//!   texels as control points: `H(u,v) = sum_{a,b in -1..=1} B_a(s) B_b(t) h[i+a][j+b]`,
//!   `i = floor(u)`, `s = u - i` (and `j`, `t` for v), with the quadratic basis
//!   `B_-1 = (1-s)^2/2`, `B_0 = (1 + 2s - 2s^2)/2`, `B_1 = s^2/2`; its partial derivatives come
//!   from the basis derivatives `-(1-s)`, `1 - 2s`, `s`.
//! * **Blinn** (para. 0031): differences of the bilinear interpolant `L` through the texel
//!   centres, one texel apart: `dH/du = L(u+1/2, v-1/2) - L(u-1/2, v-1/2)`,
//!   `dH/dv = L(u-1/2, v+1/2) - L(u-1/2, v-1/2)`, `H = L(u-1/2, v-1/2)`.
//! * **Trilinear** (para. 0081): `H = (1-l) H0(u, v) + l H1(u/2, v/2)`; the coarser level's
//!   derivatives are taken in its own texels, half as many per unit of u: `dH/du =
//!   (1-l) dH0/du + l/2 dH1/du`.

/// Border handling outside the map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Border {
    Wrap,
    Clamp,
    /// Mirrored repeat: the edge texel appears twice in a row.
    Mirror,
    /// A constant height (in texel units) outside.
    Constant(f64),
}

/// A height map in texel units.
#[derive(Clone, Debug)]
pub struct Heights {
    pub width: usize,
    pub height: usize,
    /// Row-major heights.
    pub h: Vec<f64>,
}

impl Heights {
    /// From raw texels with `frac` fraction bits.
    pub fn from_raw(width: usize, height: usize, raw: &[u8], frac: u32) -> Heights {
        let d = f64::from(1u32 << frac);
        Heights {
            width,
            height,
            h: raw.iter().map(|&r| f64::from(r) / d).collect(),
        }
    }

    fn axis(i: i64, n: usize, border: Border) -> Option<usize> {
        let n = n as i64;
        match border {
            Border::Wrap => Some(((i % n + n) % n) as usize),
            Border::Clamp => Some(i.max(0).min(n - 1) as usize),
            Border::Mirror => {
                // Period 2n: 0..n-1 forward, then n-1..0 back.
                let p = ((i % (2 * n)) + 2 * n) % (2 * n);
                Some(if p < n { p } else { 2 * n - 1 - p } as usize)
            }
            Border::Constant(_) => {
                if i >= 0 && i < n {
                    Some(i as usize)
                } else {
                    None
                }
            }
        }
    }

    /// The height of texel `(i, j)`, any integers, under `border`.
    pub fn texel(&self, i: i64, j: i64, border: Border) -> f64 {
        match (
            Self::axis(i, self.width, border),
            Self::axis(j, self.height, border),
        ) {
            (Some(x), Some(y)) => self.h[y * self.width + x],
            _ => match border {
                Border::Constant(c) => c,
                _ => unreachable!(),
            },
        }
    }
}

/// Height and its partial derivatives `(H, dH/du, dH/dv)`, unscaled.
pub type Surface = (f64, f64, f64);

fn basis(s: f64) -> ([f64; 3], [f64; 3]) {
    (
        [
            (1.0 - s) * (1.0 - s) / 2.0,
            (1.0 + 2.0 * s - 2.0 * s * s) / 2.0,
            s * s / 2.0,
        ],
        [-(1.0 - s), 1.0 - 2.0 * s, s],
    )
}

/// The bi-quadratic B-spline surface at `(u, v)`.
pub fn bspline(m: &Heights, u: f64, v: f64, border: Border) -> Surface {
    let (i, j) = (u.floor(), v.floor());
    let (bu, du) = basis(u - i);
    let (bv, dv) = basis(v - j);
    let (mut h, mut hu, mut hv) = (0.0, 0.0, 0.0);
    for b in 0..3 {
        for a in 0..3 {
            let p = m.texel(i as i64 + a as i64 - 1, j as i64 + b as i64 - 1, border);
            h += bu[a] * bv[b] * p;
            hu += du[a] * bv[b] * p;
            hv += bu[a] * dv[b] * p;
        }
    }
    (h, hu, hv)
}

/// Bilinear interpolation through the texel centres.
pub fn bilinear_centres(m: &Heights, x: f64, y: f64, border: Border) -> f64 {
    let (x, y) = (x - 0.5, y - 0.5);
    let (i, j) = (x.floor(), y.floor());
    let (fx, fy) = (x - i, y - j);
    let t = |a: f64, b: f64| m.texel(i as i64 + a as i64, j as i64 + b as i64, border);
    (1.0 - fy) * ((1.0 - fx) * t(0.0, 0.0) + fx * t(1.0, 0.0))
        + fy * ((1.0 - fx) * t(0.0, 1.0) + fx * t(1.0, 1.0))
}

/// Blinn's height function at `(u, v)`.
pub fn blinn(m: &Heights, u: f64, v: f64, border: Border) -> Surface {
    let base = bilinear_centres(m, u - 0.5, v - 0.5, border);
    let right = bilinear_centres(m, u + 0.5, v - 0.5, border);
    let down = bilinear_centres(m, u - 0.5, v + 0.5, border);
    (base, right - base, down - base)
}

/// The trilinear blend of a surface function on two MIP levels with weight `lod` on the
/// coarser one.
pub fn trilinear(
    f: fn(&Heights, f64, f64, Border) -> Surface,
    fine: &Heights,
    coarse: &Heights,
    u: f64,
    v: f64,
    lod: f64,
    border: Border,
) -> Surface {
    let (h0, u0, v0) = f(fine, u, v, border);
    let (h1, u1, v1) = f(coarse, u / 2.0, v / 2.0, border);
    (
        (1.0 - lod) * h0 + lod * h1,
        (1.0 - lod) * u0 + lod * u1 / 2.0,
        (1.0 - lod) * v0 + lod * v1 / 2.0,
    )
}

/// The unit normal `normalize(-k dH/du, -k dH/dv, 1)` for height scale `k`.
pub fn normal(s: Surface, scale: f64) -> [f64; 3] {
    let n = [-scale * s.1, -scale * s.2, 1.0];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / l)
}

/// Angle between two unit vectors, in degrees (robust for tiny angles).
pub fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let cross = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    cross.atan2(dot).to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Heights {
        // h = 2 * x: a plane of slope 2 along u.
        let h: Vec<f64> = (0..64).map(|k| 2.0 * (k % 8) as f64).collect();
        Heights {
            width: 8,
            height: 8,
            h,
        }
    }

    #[test]
    fn bspline_reproduces_planes_and_is_c1() {
        let m = ramp();
        // Inside (away from the wrap seam) a B-spline of a linear function is that function
        // (shifted by half a texel: texel centres) and its slope is exact.
        for k in 0..=16 {
            let u = 2.0 + k as f64 / 8.0;
            let (h, hu, hv) = bspline(&m, u, 3.3, Border::Clamp);
            assert!((hu - 2.0).abs() < 1e-12, "u={u} hu={hu}");
            assert!(hv.abs() < 1e-12);
            assert!((h - 2.0 * (u - 0.5)).abs() < 1e-12);
        }
        // C1: derivative continuous across a texel edge on a random map.
        let n: Vec<f64> = (0..64).map(|k| ((k * 37 % 11) as f64) * 0.25).collect();
        let m = Heights {
            width: 8,
            height: 8,
            h: n,
        };
        let e = 1e-9;
        let a = bspline(&m, 4.0 - e, 2.7, Border::Wrap);
        let b = bspline(&m, 4.0, 2.7, Border::Wrap);
        assert!((a.1 - b.1).abs() < 1e-6 && (a.2 - b.2).abs() < 1e-6);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let n: Vec<f64> = (0..100).map(|k| ((k * 53 % 17) as f64) * 0.25).collect();
        let m = Heights {
            width: 10,
            height: 10,
            h: n,
        };
        {
            let f = bspline;
            let (u, v, e) = (3.3, 6.6, 1e-6);
            let s = f(&m, u, v, Border::Wrap);
            let du =
                (f(&m, u + e, v, Border::Wrap).0 - f(&m, u - e, v, Border::Wrap).0) / (2.0 * e);
            let dv =
                (f(&m, u, v + e, Border::Wrap).0 - f(&m, u, v - e, Border::Wrap).0) / (2.0 * e);
            assert!((s.1 - du).abs() < 1e-6 && (s.2 - dv).abs() < 1e-6);
        }
    }

    #[test]
    fn borders() {
        let m = Heights {
            width: 3,
            height: 2,
            h: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        };
        assert_eq!(m.texel(-1, 0, Border::Wrap), 3.0);
        assert_eq!(m.texel(-1, 0, Border::Clamp), 1.0);
        assert_eq!(m.texel(-1, 0, Border::Mirror), 1.0);
        assert_eq!(m.texel(3, 0, Border::Mirror), 3.0);
        assert_eq!(m.texel(-2, 0, Border::Mirror), 2.0);
        assert_eq!(m.texel(0, 5, Border::Constant(9.0)), 9.0);
        assert_eq!(m.texel(1, 1, Border::Constant(9.0)), 5.0);
    }

    #[test]
    fn normals_and_angles() {
        let n = normal((0.0, 1.0, 0.0), 1.0);
        assert!((n[0] + 0.5f64.sqrt()).abs() < 1e-15 && (n[2] - 0.5f64.sqrt()).abs() < 1e-15);
        assert!((angle_deg([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]) - 90.0).abs() < 1e-12);
    }
}
