//! Environment mapping from the mathematics (Schilling & Knittel section 7), in f64: the cube
//! face of a direction (its largest component, ties to x then y) and the face coordinates
//! `s = (sc/|ma| + 1)/2`, `t = (tc/|ma| + 1)/2` of the OpenGL cube-map table.

/// The face (+X 0, -X 1, +Y 2, -Y 3, +Z 4, -Z 5) and `(s, t)` of `w`; a zero vector gives
/// +Z at the centre.
pub fn face_st(w: [f64; 3]) -> (u8, f64, f64) {
    let a = w.map(f64::abs);
    let axis = if a[0] >= a[1] && a[0] >= a[2] {
        0
    } else if a[1] >= a[2] {
        1
    } else {
        2
    };
    if a[axis] == 0.0 {
        return (4, 0.5, 0.5);
    }
    let neg = w[axis] < 0.0;
    let [x, y, z] = w;
    let (sc, tc) = match (axis, neg) {
        (0, false) => (-z, -y),
        (0, true) => (z, -y),
        (1, false) => (x, z),
        (1, true) => (x, -z),
        (_, false) => (x, -y),
        (_, true) => (-x, -y),
    };
    let m = a[axis];
    (
        2 * axis as u8 + u8::from(neg),
        (sc / m + 1.0) / 2.0,
        (tc / m + 1.0) / 2.0,
    )
}

/// Eq. 4 with the perturbed normal: `2 n_b (n_b . v) - v |n_b|^2`.
pub fn reflect(nb: [f64; 3], v: [f64; 3]) -> [f64; 3] {
    let d: f64 = (0..3).map(|c| nb[c] * v[c]).sum();
    let nn: f64 = nb.iter().map(|x| x * x).sum();
    std::array::from_fn(|c| 2.0 * nb[c] * d - v[c] * nn)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The OpenGL table's corners: on +X, looking down x, s grows towards -z and t towards -y.
    #[test]
    fn the_cube_map_table() {
        assert_eq!(face_st([1.0, 0.0, 0.0]), (0, 0.5, 0.5));
        assert_eq!(face_st([1.0, -1.0, -1.0]), (0, 1.0, 1.0));
        assert_eq!(face_st([0.0, 1.0, 1.0]), (2, 0.5, 1.0));
        assert_eq!(face_st([0.0, 0.0, -2.0]), (5, 0.5, 0.5));
        assert_eq!(face_st([0.5, 0.5, -1.0]), (5, 0.25, 0.25));
    }
}
