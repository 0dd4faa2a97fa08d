//! The blend-factor adjustment of US 2004/0207631, para. 0058 (and its bypass, para. 0085), as
//! real numbers.
//!
//! The four bilinear units of FIG. 7 evaluate the bi-quadratic B-spline of the 3x3 height
//! neighbourhood when their blend factors are `(1 + t) / 2` and `t / 2`: the uniform quadratic
//! B-spline segment through control points `p0, p1, p2` is, on the overlapping 2x2 windows,
//! a linear interpolation of the midpoints `(p0 + p1) / 2` and `(p1 + p2) / 2`, which a
//! bilinear unit computes from `p0, p1` at `(1 + t) / 2` and from `p1, p2` at `t / 2`.

/// Adjusted blend factors `(t0, t1)` for one blend factor `t` in `[0, 1)`:
/// `t0 = 1/2 + t/2`, `t1 = t/2`; in bypass (Blinn's height function) both are `t`.
pub fn adjust(t: f64, bypass: bool) -> (f64, f64) {
    if bypass {
        (t, t)
    } else {
        (0.5 + 0.5 * t, 0.5 * t)
    }
}

/// The blend factors `(u, v)` each bilinear unit receives (para. 0060): red `(U0, V0)`, green
/// `(U1, V0)`, blue `(U0, V1)`, alpha `(U1, V1)`.
pub fn distribute(u: f64, v: f64, bypass: bool) -> [(f64, f64); 4] {
    let (u0, u1) = adjust(u, bypass);
    let (v0, v1) = adjust(v, bypass);
    [(u0, v0), (u1, v0), (u0, v1), (u1, v1)]
}

/// The point of the adjustment: one quadratic B-spline segment evaluated with two linear
/// interpolations at the adjusted factors equals the B-spline basis form
/// `((1-t)^2 p0 + (-2t^2 + 2t + 1) p1 + t^2 p2) / 2`.
pub fn bspline_segment(p: [f64; 3], t: f64) -> f64 {
    ((1.0 - t).powi(2) * p[0] + (-2.0 * t * t + 2.0 * t + 1.0) * p[1] + t * t * p[2]) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lerp(a: f64, b: f64, t: f64) -> f64 {
        a + (b - a) * t
    }

    #[test]
    fn adjusted_lerps_evaluate_the_bspline() {
        // Two lerps at the adjusted factors, then a lerp of those at t, give the B-spline:
        // that is why unit 153 exists.
        let p = [0.3, -1.25, 2.0];
        for k in 0..=16 {
            let t = k as f64 / 16.0;
            let (t0, t1) = adjust(t, false);
            let a = lerp(p[0], p[1], t0);
            let b = lerp(p[1], p[2], t1);
            let v = lerp(a, b, t);
            assert!((v - bspline_segment(p, t)).abs() < 1e-12, "t={t}");
        }
    }

    #[test]
    fn bypass_and_distribution() {
        assert_eq!(adjust(0.25, true), (0.25, 0.25));
        let d = distribute(0.5, 0.0, false);
        assert_eq!(d[0], (0.75, 0.5));
        assert_eq!(d[1], (0.25, 0.5));
        assert_eq!(d[2], (0.75, 0.0));
        assert_eq!(d[3], (0.25, 0.0));
    }
}
