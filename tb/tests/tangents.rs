//! Tangent frames (003): the setup unit's testbench, and the frames' invariants on meshes:
//! orthonormal where they should be, planar mapping along the u axis, mirrored UVs with
//! opposite handedness, degenerate UVs never NaN.

use golden::tangents::{cross, dot};
use tb::runs::tangents::{frames, Mode};
use tb::tangents::TangentSetupTb;

#[test]
fn the_testbench_passes_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(2000),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&TangentSetupTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.failures, r.mismatch_log);
    assert!(r.coverage_percent > 99.0, "{:?}", r.unhit);
}

/// A bumpy grid in the xz plane (heights along y), UVs planar along x and z: the left half's
/// UVs mirrored in u. Smoothing group 1, no normals given.
fn grid(mirror: bool) -> formats::obj::Mesh {
    let mut text = String::new();
    let n = 6;
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (i as f64, j as f64);
            let y = 0.3 * ((x * 1.3).sin() + (z * 0.7).cos());
            text.push_str(&format!("v {x} {y} {z}\n"));
            let u = if mirror && i < n / 2 { -x } else { x };
            text.push_str(&format!("vt {u} {z}\n"));
        }
    }
    text.push_str("s 1\n");
    let at = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            // Counter-clockwise seen from +y: a, d, c, b.
            text.push_str(&format!("f {a}/{a} {d}/{d} {c}/{c} {b}/{b}\n"));
        }
    }
    formats::obj::parse("grid.obj", &text).unwrap()
}

#[test]
fn frames_are_orthonormal_where_the_mode_says() {
    let m = grid(false);
    for mode in [Mode::Max, Mode::DirectX, Mode::Maya] {
        for r in frames(&m, mode) {
            let f = r.frame;
            assert!(!f.zero);
            assert!((dot(f.t, f.t) - 1.0).abs() < 1e-12, "{mode:?}");
            assert!((dot(f.n, f.n) - 1.0).abs() < 1e-12);
            if mode != Mode::Maya {
                assert!(dot(f.t, f.n).abs() < 1e-12, "{mode:?}: T.N");
                let nt = cross(f.n, f.t);
                let s = dot(f.b, nt);
                assert!((s.abs() - 1.0).abs() < 1e-12, "{mode:?}: B = +-N x T");
            }
            // u grows along x: the tangent points along +x, give or take the bumps.
            assert!(f.t[0] > 0.8, "{mode:?} {:?}", f.t);
        }
    }
}

/// Away from the seam, B follows v (+z) on both halves and the handedness flips.
#[test]
fn mirrored_uvs_give_opposite_handedness() {
    let m = grid(true);
    for mode in [Mode::Max, Mode::DirectX] {
        let (mut left, mut right) = (Vec::new(), Vec::new());
        for r in frames(&m, mode) {
            let f = r.frame;
            let s = dot(f.b, cross(f.n, f.t)).signum();
            let xs = m.faces[r.face].corners.iter().map(|c| m.positions[c.p][0]);
            let x = m.positions[m.faces[r.face].corners[r.corner].p][0];
            if xs.clone().all(|x| x <= 2.0) && x < 2.0 {
                assert!(f.t[0] < -0.8 && f.b[2] > 0.5, "{mode:?} left {f:?}");
                left.push(s);
            }
            if xs.clone().all(|x| x >= 3.0) && x > 3.0 {
                assert!(f.t[0] > 0.8 && f.b[2] > 0.5, "{mode:?} right {f:?}");
                right.push(s);
            }
            // (Corners by the seam share UVs with the other half: smoothing there averages
            // opposite tangents, as it would in any tool that did not split the seam.)
        }
        assert!(!left.is_empty() && !right.is_empty());
        let sr = right[0];
        assert!(
            right.iter().all(|&s| s == sr) && left.iter().all(|&s| s == -sr),
            "{mode:?}"
        );
    }
}

#[test]
fn degenerate_uvs_give_zero_tangents_not_nan() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0.5 0.5\nf 1/1 2/1 3/1\nvt 0 0\nvt 1 1\nvt 2 2\nf 1/2 2/3 3/4\n";
    let m = formats::obj::parse("d.obj", text).unwrap();
    for mode in [Mode::Max, Mode::Maya, Mode::DirectX] {
        for r in frames(&m, mode) {
            let f = r.frame;
            assert!(
                f.t.iter().chain(&f.b).chain(&f.n).all(|x| x.is_finite()),
                "{mode:?}"
            );
            if r.face == 0 {
                assert!(f.zero && f.t == [0.0; 3]);
            }
        }
    }
}
