//! Footprint assembly from the mathematics (Schilling & Knittel section 10), in f64: the
//! setup of eqs 19-21 with real square roots and logarithms, the sample points of eq. 22,
//! and the reference the quality claim is measured against: the mean of level 0 over the
//! pixel's exact footprint (the parallelogram spanned by r1 and r2), by stratified sampling.

/// How far the setup unit's lambda may be from `log2 q` (in levels): its table holds
/// `log2(1 + i/64)` for the six mantissa bits after the leading one, truncated, so half the
/// widest table interval, `log2(1 + 1/64) / 2 = 0.011184`, plus half the table's rounding
/// (1/1024) plus the halving's rounding (1/512).
pub const LAMBDA_BOUND: f64 = 0.011184 + 1.0 / 1024.0 + 1.0 / 512.0;

/// The setup of one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setup {
    pub log2_n: u32,
    /// `q = min(|r1|, |r2|, |r1 + r2|, |r1 - r2|)`, `m = max(|r1|, |r2|)`.
    pub q: f64,
    pub m: f64,
    /// `log2 q` and `log2 m` (unclamped; `-inf` for 0).
    pub lambda: f64,
    pub lambda_iso: f64,
    /// The step along the longer edge, `r / N`.
    pub step: (f64, f64),
    /// `log2(m / q)`, where the power of two is decided.
    pub ratio_log2: f64,
}

/// Eqs 19-21 with `N` the power of two nearest `m / q` in the log domain (`linear`: in the
/// linear domain), at most `2^max_log2_n`; `m = 0` gives 1, `q = 0` the most.
pub fn setup(r1: (f64, f64), r2: (f64, f64), max_log2_n: u32, linear: bool) -> Setup {
    let len = |a: f64, b: f64| a.hypot(b);
    let (l1, l2) = (len(r1.0, r1.1), len(r2.0, r2.1));
    let d1 = len(r1.0 + r2.0, r1.1 + r2.1);
    let d2 = len(r1.0 - r2.0, r1.1 - r2.1);
    let q = l1.min(l2).min(d1).min(d2);
    let m = l1.max(l2);
    let ratio_log2 = (m / q).log2();
    let log2_n = if m == 0.0 {
        0
    } else if q == 0.0 {
        max_log2_n
    } else if linear {
        // The least k with m / q < 1.5 * 2^k.
        (0..max_log2_n)
            .find(|&k| m / q < 1.5 * f64::from(1u32 << k))
            .unwrap_or(max_log2_n)
    } else {
        ((ratio_log2 + 0.5).floor().max(0.0) as u32).min(max_log2_n)
    };
    let r = if l2 > l1 { r2 } else { r1 };
    let n = f64::from(1u32 << log2_n);
    Setup {
        log2_n,
        q,
        m,
        lambda: q.log2(),
        lambda_iso: m.log2(),
        step: (r.0 / n, r.1 / n),
        ratio_log2,
    }
}

/// Whether `(m / q)^2` lies within a relative `2^-20` of one of the thresholds where N
/// doubles (log domain: `m / q = 2^(k + 1/2)`; linear: `1.5 * 2^k`), where an exact compare
/// and f64 may decide differently.
pub fn near_threshold(s: &Setup, linear: bool) -> bool {
    if !s.ratio_log2.is_finite() {
        return false;
    }
    let t = if linear {
        let k = (s.ratio_log2 - 1.5f64.log2()).round();
        k + 1.5f64.log2()
    } else {
        (s.ratio_log2 - 0.5).round() + 0.5
    };
    // Relative distance of (m/q)^2 to the threshold's square: |2^(2(r - t)) - 1|.
    ((2.0 * (s.ratio_log2 - t)).exp2() - 1.0).abs() < 1.0 / f64::from(1u32 << 20)
}

/// The sample points of eq. 22 around `p`: `p + (n/2) step` for `n = -(N-1), ..., N-1` in
/// steps of 2.
pub fn sample_points(p: (f64, f64), s: &Setup) -> Vec<(f64, f64)> {
    let n = 1i32 << s.log2_n;
    (0..n)
        .map(|i| {
            let h = f64::from(2 * i - (n - 1)) / 2.0;
            (p.0 + h * s.step.0, p.1 + h * s.step.1)
        })
        .collect()
}

/// A level-0 map with wrap-around: texel centres at `k + 1/2`.
pub struct Map<'a> {
    pub width: usize,
    pub height: usize,
    pub texels: &'a [u8],
}

impl Map<'_> {
    /// Bilinear interpolation at `(u, v)` (texel units, wrapping).
    pub fn bilinear(&self, u: f64, v: f64) -> f64 {
        let (x, y) = (u - 0.5, v - 0.5);
        let (i, j) = (x.floor(), y.floor());
        let (a, b) = (x - i, y - j);
        let at = |di: f64, dj: f64| {
            let xi = ((i + di) as i64).rem_euclid(self.width as i64) as usize;
            let yj = ((j + dj) as i64).rem_euclid(self.height as i64) as usize;
            f64::from(self.texels[yj * self.width + xi])
        };
        (1.0 - b) * ((1.0 - a) * at(0.0, 0.0) + a * at(1.0, 0.0))
            + b * ((1.0 - a) * at(0.0, 1.0) + a * at(1.0, 1.0))
    }

    /// The mean over the parallelogram `p + s r1 + t r2`, `s, t` in `[-1/2, 1/2]`, by
    /// `k1 x k2` stratified bilinear samples (cell centres; `k1` along r1).
    pub fn box_average(
        &self,
        p: (f64, f64),
        r1: (f64, f64),
        r2: (f64, f64),
        (k1, k2): (usize, usize),
    ) -> f64 {
        let mut sum = 0.0;
        for i in 0..k1 {
            for j in 0..k2 {
                let s = (i as f64 + 0.5) / k1 as f64 - 0.5;
                let t = (j as f64 + 0.5) / k2 as f64 - 0.5;
                sum += self.bilinear(p.0 + s * r1.0 + t * r2.0, p.1 + s * r1.1 + t * r2.1);
            }
        }
        sum / (k1 * k2) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figure_12_and_the_degenerate_cases() {
        let s = setup((2.0, 0.0), (0.0, 1.0), 4, false);
        assert_eq!((s.log2_n, s.q, s.m, s.step), (1, 1.0, 2.0, (1.0, 0.0)));
        assert_eq!(setup((0.0, 1.0), (-4.0, 0.0), 4, false).log2_n, 2);
        assert_eq!(setup((0.0, 0.0), (0.0, 0.0), 4, false).log2_n, 0);
        assert_eq!(setup((3.0, 3.0), (3.0, 3.0), 4, false).log2_n, 4);
        assert_eq!(setup((1.5, 0.0), (0.0, 1.0), 4, true).log2_n, 1);
        assert_eq!(setup((1.49, 0.0), (0.0, 1.0), 4, true).log2_n, 0);
        // A sheared parallelogram: the short diagonal is q.
        let s = setup((4.0, 0.0), (3.5, 0.5), 4, false);
        assert!((s.q - (0.5f64).hypot(0.5)).abs() < 1e-12);
    }

    #[test]
    fn sample_points_are_symmetric_about_p() {
        let s = setup((8.0, 2.0), (0.0, 1.0), 4, false);
        let pts = sample_points((10.0, 20.0), &s);
        assert_eq!(pts.len(), 1 << s.log2_n);
        let (su, sv) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        assert!((su / pts.len() as f64 - 10.0).abs() < 1e-12);
        assert!((sv / pts.len() as f64 - 20.0).abs() < 1e-12);
        let one = setup((1.0, 0.0), (0.0, 1.0), 4, false);
        assert_eq!(sample_points((3.0, 4.0), &one), vec![(3.0, 4.0)]);
    }

    #[test]
    fn the_box_average_of_a_ramp_is_its_centre_value() {
        // A ramp along u (no wrap inside the footprint): the mean is the value at p.
        let texels: Vec<u8> = (0..64 * 64).map(|k| (k % 64) as u8 * 2).collect();
        let map = Map {
            width: 64,
            height: 64,
            texels: &texels,
        };
        let p = (30.0, 30.0);
        let avg = map.box_average(p, (6.0, 1.0), (-1.0, 3.0), (32, 16));
        assert!((avg - map.bilinear(p.0, p.1)).abs() < 1e-9, "{avg}");
    }
}
