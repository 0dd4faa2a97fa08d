//! Golden model of the TEXRAM chip's trilinear access (Schilling & Knittel, Figure 8 and
//! section 6), in `f64`, from the definitions and sharing nothing with `hdl`.
//!
//! A mipmap is a list of levels, level k of size `max(W >> k, 1) x max(H >> k, 1)`. An access
//! at `(u, v)` (level-0 texel units) with level of detail `lambda`: `L = floor(lambda)` held to
//! `0 ..= Lmax`, `f = lambda - L` (0 when lambda < 0 or L = Lmax), and at each level k of
//! {L, min(L + 1, Lmax)} the bilinear interpolation at `u / 2^k - 1/2`, `v / 2^k - 1/2` of
//! the texels after the border operation; the two results mixed `(1 - f), f`.
//!
//! The hardware quantises `a`, `b` and `f` to 8 bits by truncation before it weighs; to
//! compare its one rounding with this model, [`trilinear`] takes the weights it is to use:
//! [`Weights::exact`] for the mathematics, [`Weights::truncated`] for the weights the chip
//! computes (the difference is the weight quantisation, bounded separately).

/// The border operations of section 6.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Border {
    Wrap,
    Clamp,
    Mirror,
    /// A constant value outside the map.
    Colour(f64),
}

/// A mipmap: `levels[k]` row-major, `width >> k` by `height >> k` (at least 1).
pub struct Mipmap<'a> {
    pub width: usize,
    pub height: usize,
    pub levels: &'a [Vec<u8>],
    pub border: Border,
}

impl Mipmap<'_> {
    fn size(&self, k: usize) -> (usize, usize) {
        ((self.width >> k).max(1), (self.height >> k).max(1))
    }

    /// Texel `(i, j)` of level `k`, any integers, after the border operation.
    pub fn texel(&self, k: usize, i: i64, j: i64) -> f64 {
        let (w, h) = self.size(k);
        let fold = |t: i64, n: usize| -> Option<usize> {
            let n = n as i64;
            let r = match self.border {
                Border::Wrap => t.rem_euclid(n),
                Border::Clamp => t.clamp(0, n - 1),
                Border::Mirror => {
                    let m = t.rem_euclid(2 * n);
                    if m < n {
                        m
                    } else {
                        2 * n - 1 - m
                    }
                }
                Border::Colour(_) => {
                    if t < 0 || t >= n {
                        return None;
                    }
                    t
                }
            };
            Some(r as usize)
        };
        match (fold(i, w), fold(j, h), self.border) {
            (Some(x), Some(y), _) => f64::from(self.levels[k][y * w + x]),
            (_, _, Border::Colour(c)) => c,
            _ => unreachable!("only the border colour leaves the map"),
        }
    }
}

/// The weights of one access: `a`, `b` per level (fine, coarse) and `f`, as reals in [0, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weights {
    pub fine: usize,
    pub coarse: usize,
    pub i: [i64; 2],
    pub j: [i64; 2],
    pub a: [f64; 2],
    pub b: [f64; 2],
    pub f: f64,
}

impl Weights {
    /// The exact weights of `(u, v, lambda)` on a map with last level `lmax`.
    pub fn exact(u: f64, v: f64, lambda: f64, lmax: usize) -> Weights {
        let l = lambda.floor();
        let (fine, f) = if l < 0.0 {
            (0, 0.0)
        } else if l as usize >= lmax {
            (lmax, 0.0)
        } else {
            (l as usize, lambda - l)
        };
        let coarse = (fine + 1).min(lmax);
        let mut w = Weights {
            fine,
            coarse,
            i: [0; 2],
            j: [0; 2],
            a: [0.0; 2],
            b: [0.0; 2],
            f,
        };
        for (n, k) in [fine, coarse].into_iter().enumerate() {
            let s = 2f64.powi(k as i32);
            let (x, y) = (u / s - 0.5, v / s - 0.5);
            (w.i[n], w.j[n]) = (x.floor() as i64, y.floor() as i64);
            (w.a[n], w.b[n]) = (x - x.floor(), y - y.floor());
        }
        w
    }

    /// The same with `a`, `b` and `f` truncated to multiples of 1/256, as the chip forms them.
    pub fn truncated(u: f64, v: f64, lambda: f64, lmax: usize) -> Weights {
        let mut w = Weights::exact(u, v, lambda, lmax);
        let t = |x: f64| (x * 256.0).floor() / 256.0;
        w.a = w.a.map(t);
        w.b = w.b.map(t);
        w.f = t(w.f);
        w
    }
}

/// Trilinear filtering of `map` with the weights `w`.
pub fn trilinear(map: &Mipmap, w: &Weights) -> f64 {
    let mut out = 0.0;
    for (n, (k, wf)) in [(w.fine, 1.0 - w.f), (w.coarse, w.f)]
        .into_iter()
        .enumerate()
    {
        let (i, j, a, b) = (w.i[n], w.j[n], w.a[n], w.b[n]);
        let t = |di, dj| map.texel(k, i + di, j + dj);
        let bil = (1.0 - a) * (1.0 - b) * t(0, 0)
            + a * (1.0 - b) * t(1, 0)
            + (1.0 - a) * b * t(0, 1)
            + a * b * t(1, 1);
        out += wf * bil;
    }
    out
}

/// The chip's bound against [`trilinear`] with [`Weights::truncated`]: the products and their
/// sum are exact, one rounding to nearest follows, so half an LSB (plus the f64 reference's
/// own rounding, far below 1e-9 for 8-bit texels).
pub const ERROR_BOUND_LSB: f64 = 0.5 + 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Vec<Vec<u8>> {
        vec![
            (0..16).map(|k| (k % 4 * 10) as u8).collect(),
            vec![5, 25, 5, 25],
            vec![15],
        ]
    }

    #[test]
    fn at_texel_centres_of_level_zero_the_texel_comes_back() {
        let levels = ramp();
        let m = Mipmap {
            width: 4,
            height: 4,
            levels: &levels,
            border: Border::Clamp,
        };
        for x in 0..4 {
            let w = Weights::exact(x as f64 + 0.5, 1.5, 0.0, 2);
            assert_eq!(trilinear(&m, &w), f64::from(levels[0][4 + x]));
        }
    }

    #[test]
    fn a_linear_ramp_interpolates_linearly_inside_the_map() {
        let levels = ramp();
        let m = Mipmap {
            width: 4,
            height: 4,
            levels: &levels,
            border: Border::Clamp,
        };
        // Between texel centres 1.5 and 2.5 along u: 10 .. 20.
        let w = Weights::exact(2.25, 2.0, 0.0, 2);
        assert!((trilinear(&m, &w) - 17.5).abs() < 1e-12);
    }

    #[test]
    fn border_operations_fold_as_defined() {
        let levels = ramp();
        let m = |border| Mipmap {
            width: 4,
            height: 4,
            levels: &levels,
            border,
        };
        assert_eq!(m(Border::Wrap).texel(0, -1, 0), 30.0);
        assert_eq!(m(Border::Clamp).texel(0, -1, 0), 0.0);
        assert_eq!(m(Border::Mirror).texel(0, -1, 0), 0.0);
        assert_eq!(m(Border::Mirror).texel(0, 4, 0), 30.0);
        assert_eq!(m(Border::Mirror).texel(0, 5, 0), 20.0);
        assert_eq!(m(Border::Colour(99.0)).texel(0, 4, 0), 99.0);
    }

    #[test]
    fn lambda_picks_and_mixes_levels() {
        let w = Weights::exact(8.0, 8.0, 1.25, 4);
        assert_eq!((w.fine, w.coarse, w.f), (1, 2, 0.25));
        let w = Weights::exact(8.0, 8.0, -2.0, 4);
        assert_eq!((w.fine, w.coarse, w.f), (0, 1, 0.0));
        let w = Weights::exact(8.0, 8.0, 7.5, 4);
        assert_eq!((w.fine, w.coarse, w.f), (4, 4, 0.0));
        let t = Weights::truncated(8.3, 8.0, 1.999, 4);
        assert_eq!(t.f, 255.0 / 256.0);
    }
}
