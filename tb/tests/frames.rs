//! The per-pixel frame unit and the parallax unit (002, 003): testbenches and properties.

use tb::frames::{golden_parallax, parallax_queries, FrameUnitTb, ParallaxTb};
use units::frames::frame_unit::{decode_rgb8, Decode, FrameMath};
use units::frames::parallax::Parallax;
use verif::{Seed, Stimulus};

#[test]
fn the_testbenches_pass_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(1500),
        check_schedule: true,
        ..Default::default()
    };
    for tb in [&FrameUnitTb as &dyn verif::Testbench, &ParallaxTb] {
        let r = verif::run_testbench(tb, &opts, &mut |_| {}).unwrap();
        assert!(
            r.passed,
            "{}: {:?} {:?}",
            r.name, r.failures, r.mismatch_log
        );
        assert!(r.coverage_percent > 99.0, "{:?}", r.unhit);
    }
}

/// A flat normal-map texel gives the interpolated normal's direction within an LSB, in any
/// frame (through Gram-Schmidt), with the offset decode.
#[test]
fn a_flat_texel_gives_n_in_any_frame() {
    let m = FrameMath::new();
    let mut stim = Stimulus::new(Seed(8));
    for p in tb::frames::frame_pixels(600, &mut stim) {
        let o = m.perturb(p.frame, decode_rgb8([128, 128, 255], Decode::Offset), true);
        let nu = m.orthonormalise(p.frame[0], p.frame[1], p.frame[2]).2;
        for c in 0..3 {
            assert!((o.n[c] - nu[c]).abs() <= 1, "{:?} {nu:?}", o.n);
        }
    }
}

/// A constant height H with bias = -scale H moves no coordinate, in either form; the unit is
/// within its bound of f64 everywhere (the testbench's check, on more queries).
#[test]
fn a_cancelled_height_moves_nothing() {
    let p = Parallax::new();
    let mut stim = Stimulus::new(Seed(9));
    for q in parallax_queries(2000, &mut stim) {
        let bias = -((i64::from(q.height) * q.scale) >> 8);
        if (i64::from(q.height) * q.scale) % 256 == 0 {
            assert_eq!(
                p.offset(q.uv, q.height, (q.scale, bias), q.eye, q.limited),
                q.uv
            );
        }
        let got = p.offset(q.uv, q.height, (q.scale, q.bias), q.eye, q.limited);
        let (g, bound) = golden_parallax(&q);
        for c in 0..2 {
            assert!((got[c] as f64 / 256.0 - g[c]).abs() <= bound, "{q:?}");
        }
    }
}
