//! Tangent frames for bump and normal maps (003), in f64 from the definitions, sharing
//! nothing with `hdl`.
//!
//! * Per triangle: with edges `v1 = P1 - P0`, `v2 = P2 - P0` and UV edges `d1`, `d2`,
//!   `uvk = d2.x d1.y - d1.x d2.y`; `dP/du = (d1.y v2 - d2.y v1) / uvk` and `dP/dv = (d2.x v1 -
//!   d1.x v2) / uvk`. With `uvk = 0` (UVs on a line) the seed takes `v1 / d1.x`, else `v2 /
//!   d2.x`, else nothing: a zero tangent, flagged, never NaN.
//! * Per vertex: Gram-Schmidt against the normal, `t = normalize(T - (n.T) n)`, `b = s n x t`.
//!   The seed's sign `s` looks at the UV winding only (`mapNormal.z = (uv1 - uv0) x (uv2 -
//!   uv1) < 0` flips), right only when the triangle winds counter-clockwise about n; the
//!   general test is `s = sign((n x t) . dP/dv)` ([`handedness`]).
//! * Modes (the seed's three): 3ds Max (the face normal, the face's T and B), Maya (the
//!   vertex normal, the smoothed T and B as they are: the shader re-orthogonalises per pixel),
//!   DirectX (the vertex normal, T orthogonalised per vertex, B = s n x t).

/// A vector's operations.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a / |a|`, or zero (and `false`) for a zero vector.
pub fn normalize(a: [f64; 3]) -> ([f64; 3], bool) {
    let l = dot(a, a).sqrt();
    if l > 0.0 && l.is_finite() {
        (scale(a, 1.0 / l), true)
    } else {
        ([0.0; 3], false)
    }
}

/// A triangle's `dP/du`, `dP/dv` (unnormalised) and whether its UVs were degenerate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceTangent {
    pub dpdu: [f64; 3],
    pub dpdv: [f64; 3],
    pub degenerate: bool,
}

/// The tangents of the triangle `p` with UVs `uv`.
pub fn face_tangent(p: [[f64; 3]; 3], uv: [[f64; 2]; 3]) -> FaceTangent {
    let (v1, v2) = (sub(p[1], p[0]), sub(p[2], p[0]));
    let d1 = [uv[1][0] - uv[0][0], uv[1][1] - uv[0][1]];
    let d2 = [uv[2][0] - uv[0][0], uv[2][1] - uv[0][1]];
    let uvk = d2[0] * d1[1] - d1[0] * d2[1];
    if uvk != 0.0 {
        let dpdu = scale(sub(scale(v2, d1[1]), scale(v1, d2[1])), 1.0 / uvk);
        let dpdv = scale(sub(scale(v1, d2[0]), scale(v2, d1[0])), 1.0 / uvk);
        return FaceTangent {
            dpdu,
            dpdv,
            degenerate: false,
        };
    }
    let dpdu = if d1[0] != 0.0 {
        scale(v1, 1.0 / d1[0])
    } else if d2[0] != 0.0 {
        scale(v2, 1.0 / d2[0])
    } else {
        [0.0; 3]
    };
    FaceTangent {
        dpdu,
        dpdv: [0.0; 3],
        degenerate: true,
    }
}

/// The seed's sign: -1 when the UV triangle winds clockwise (`mapNormal.z < 0`).
pub fn printed_sign(uv: [[f64; 2]; 3]) -> f64 {
    let a = [uv[1][0] - uv[0][0], uv[1][1] - uv[0][1]];
    let b = [uv[2][0] - uv[1][0], uv[2][1] - uv[1][1]];
    if a[0] * b[1] - a[1] * b[0] < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The general handedness: the sign of `(n x t) . dP/dv` (1 when dP/dv is zero).
pub fn handedness(n: [f64; 3], t: [f64; 3], dpdv: [f64; 3]) -> f64 {
    if dot(cross(n, t), dpdv) < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// A frame at a corner: tangent, bitangent, normal, and whether the tangent was zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub t: [f64; 3],
    pub b: [f64; 3],
    pub n: [f64; 3],
    pub zero: bool,
}

/// Gram-Schmidt of `t` against the unit `n`, and `b = s n x t` with the general sign of
/// `dpdv`.
pub fn orthonormal(n: [f64; 3], t: [f64; 3], dpdv: [f64; 3]) -> Frame {
    let (t, ok) = normalize(sub(t, scale(n, dot(n, t))));
    let s = handedness(n, t, dpdv);
    Frame {
        t,
        b: scale(cross(n, t), s),
        n,
        zero: !ok,
    }
}

/// The per-pixel frame: optional Gram-Schmidt of `(t, b)` against `n`, then the unit
/// `a n + gx t + gy b` (`None` when it has no direction).
pub fn perturb(frame: [[f64; 3]; 3], w: [f64; 3], gram_schmidt: bool) -> Option<[f64; 3]> {
    let [t, b, n] = frame;
    let (t, b, n) = if gram_schmidt {
        let n = normalize(n).0;
        let f = orthonormal(n, t, cross(n, t));
        let s = if dot(b, cross(n, f.t)) < 0.0 {
            -1.0
        } else {
            1.0
        };
        (f.t, scale(cross(n, f.t), s), n)
    } else {
        (t, b, n)
    };
    let v = add(add(scale(n, w[0]), scale(t, w[1])), scale(b, w[2]));
    let (u, ok) = normalize(v);
    ok.then_some(u)
}

/// Parallax: `uv + h V.xy / max(V.z, 1/8)`, or `uv + h V.xy` when `limited`.
pub fn parallax(uv: [f64; 2], h: f64, eye: [f64; 3], limited: bool) -> [f64; 2] {
    let k = if limited { h } else { h / eye[2].max(0.125) };
    [uv[0] + k * eye[0], uv[1] + k * eye[1]]
}

/// 003's bump perturbation as printed: `dM.x dP/du + dM.y dP/dv` (the slope added as it is).
pub fn printed_bump(dm: [f64; 2], dpdu: [f64; 3], dpdv: [f64; 3]) -> [f64; 3] {
    add(scale(dpdu, dm[0]), scale(dpdv, dm[1]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 003's bump basis: the perturbation is not a unit vector (N + it must be renormalised)
    /// and, with dM the height's slope, it tilts the normal up the slope, into the bump; the
    /// surface's normal tilts away from the rising height (Blinn's -grad).
    #[test]
    fn the_printed_bump_perturbation_is_neither_unit_nor_signed_right() {
        let (dpdu, dpdv, n) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        // Height rising along +u: slope (0.5, 0).
        let p = printed_bump([0.5, 0.0], dpdu, dpdv);
        assert!((dot(p, p).sqrt() - 1.0).abs() > 0.1, "not unit");
        // The true normal of h = 0.5 u: (-0.5, 0, 1) normalised: x negative.
        let printed = normalize(add(n, p)).0;
        let blinn = perturb([dpdu, dpdv, n], [1.0, -0.5, 0.0], false).unwrap();
        assert!(printed[0] > 0.0 && blinn[0] < 0.0);
        let truth = normalize([-0.5, 0.0, 1.0]).0;
        assert!((0..3).all(|c| (blinn[c] - truth[c]).abs() < 1e-12));
    }

    /// 002's App. A reads a normal-map texel as the vector itself: a flat texel (0.5, 0.5, 1)
    /// is then tilted 35 degrees; with the range change it is the normal.
    #[test]
    fn the_printed_normal_map_read_tilts_a_flat_texel() {
        let c = [128.0 / 255.0, 128.0 / 255.0, 1.0];
        let printed = normalize(c).0;
        let decoded = normalize(c.map(|x| 2.0 * x - 1.0)).0;
        assert!(printed[2] < 0.85 && decoded[2] > 0.9999);
        // Its `upVector = tVector ^ sVector` is t x s: inward for a right-handed s, t.
        let (s, t) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(cross(t, s), [0.0, 0.0, -1.0]);
    }

    /// A planar mapping `P = O + u A + v C`: dP/du = A and dP/dv = C exactly.
    #[test]
    fn planar_mapping_gives_its_axes() {
        let (o, a, c) = ([1.0, 2.0, 3.0], [2.0, 0.5, 0.0], [0.0, 1.0, -1.0]);
        let at = |u: f64, v: f64| {
            [
                o[0] + u * a[0] + v * c[0],
                o[1] + u * a[1] + v * c[1],
                o[2] + u * a[2] + v * c[2],
            ]
        };
        let uv = [[0.1, 0.2], [0.7, 0.3], [0.4, 0.9]];
        let p = uv.map(|q| at(q[0], q[1]));
        let f = face_tangent(p, uv);
        for k in 0..3 {
            assert!((f.dpdu[k] - a[k]).abs() < 1e-12 && (f.dpdv[k] - c[k]).abs() < 1e-12);
        }
        assert!(!f.degenerate);
    }

    /// UVs on a line, or all equal: a finite tangent or zero, flagged.
    #[test]
    fn degenerate_uvs_never_give_nan() {
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        for uv in [
            [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]],
            [[0.5, 0.5]; 3],
            [[0.0, 0.0], [0.0, 1.0], [0.0, 2.0]],
        ] {
            let f = face_tangent(p, uv);
            assert!(f.degenerate);
            assert!(f.dpdu.iter().chain(&f.dpdv).all(|x| x.is_finite()));
            let fr = orthonormal([0.0, 0.0, 1.0], f.dpdu, f.dpdv);
            assert!(fr.t.iter().chain(&fr.b).all(|x| x.is_finite()));
        }
    }

    /// The seed's flip follows the UV winding alone: a triangle winding clockwise about its
    /// normal, with counter-clockwise UVs, gets the wrong handedness from it; the general test
    /// gets the right one (b along +dP/dv).
    #[test]
    fn the_printed_flip_fails_on_a_clockwise_triangle() {
        // Counter-clockwise about +z in xy, UVs = xy: right-handed.
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let uv = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let n = [0.0, 0.0, 1.0];
        let f = face_tangent(p, uv);
        let fr = orthonormal(n, f.dpdu, f.dpdv);
        assert!(dot(fr.b, f.dpdv) > 0.0 && printed_sign(uv) > 0.0);
        // The same surface with its normal toward -z (the triangle winds clockwise about it)
        // and v running down: b must follow dP/dv.
        let n = [0.0, 0.0, -1.0];
        let uv = [[0.0, 1.0], [1.0, 1.0], [0.0, 0.0]];
        let f = face_tangent(p, uv);
        let fr = orthonormal(n, f.dpdu, f.dpdv);
        assert!(dot(fr.b, f.dpdv) > 0.0, "the general test follows dP/dv");
        let printed = scale(cross(n, fr.t), printed_sign(uv));
        assert!(
            dot(printed, f.dpdv) < 0.0,
            "the printed flip points b against dP/dv"
        );
    }
}
