//! Environment mapping (Schilling & Knittel section 7): the local frame of eqs 2-3, the
//! reflection vector of eq. 4 and the cube-face selection. The chain walker of 812
//! ([`crate::mapchain`]) reads the face's mipmap at the coordinates they give.
//!
//! ### Environment mapping: frame, reflection, cube face (section 7)
//!
//! The local frame of eqs 2-3 (`hdl/units/src/envmap/frame_eq2.rs`): `n = n1/|n1|`, `e1 = (h x
//! n)/|h x n|`, `e2 = n x e1`, `n_b = n + e1 b1 + e2 b2`, lengths by normal unit 156's inverse
//! square root (its table and Newton step; any magnitude, `s = m 4^k` with negative k too),
//! each component one rounding to sQ1.14, `n_b` to sQ2.14; an `h` parallel to `n` replaced by
//! the x (or y) axis and flagged \[C\]. On 50,000 random frames: `n` within its derived bound of
//! `n1/|n1|` (measured 0.57 LSB), `e1`, `e2` unit and orthogonal within the derived 2.6 LSB +
//! twice the reciprocal's error (measured 1.98), `n_b` within half an LSB of the exact
//! combination. The reflection vector of eq. 4 (`hdl/units/src/envmap/reflect_eq4.rs`): `w = 2 n_b (n_b . v) - v
//! |n_b|^2` with the perturbed normal `n_b` (the seed prints `n`; the text means the new normal),
//! `n_b` sQ2.14, `v` sQ1.14, exact products, one rounding to sQ3.16 (the cube-face unit's input);
//! within half an LSB of f64 on 100,000 random perturbed normals and eye vectors, and looking
//! along the normal reflects onto it exactly. Eqs 6 and 7 of the output stage 820
//! (`output_820::environment`, `reflectance`): `C = (C_d | I_d) + k_s . E` and `C = (C_d | I_d)
//! + R . (E | I_s)`, the sums saturating \[C\]; a constant reflectance k gives exactly eq. 6 with
//! k_s = k. The cube-face unit (`hdl/units/src/envmap/cube_face.rs`, golden `golden/src/envmap.rs`,
//! tests `tb/tests/envmap.rs`): from the reflection vector `w` (sQ3.16) the face of its largest
//! component (exact compares, ties to x then y; +X 0 ... -Z 5) and `s = (sc/|ma| + 1)/2`, `t`
//! likewise (uQ0.12) with the OpenGL cube-map table \[C\]; `1/|ma|` from a 64-entry table of
//! interval midpoints and one Newton step (relative error at most 5 x 2^-16, exhaustive over
//! every mantissa), the product exact and one rounding. Checked on 200,000 random vectors
//! (ties included): the face is f64's, s and t within 3/4 LSB of exact (derived: a reciprocal
//! error of 0.16 LSB plus the rounding); chained after eq. 4, the face is f64's unless the two
//! largest components are within 2^-12.

pub mod cube_face;
pub mod frame_eq2;
pub mod reflect_eq4;
