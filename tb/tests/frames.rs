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
    let mut m = FrameMath::new();
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

/// Directed closure of numeric coverage: the random queries never take the coordinates'
/// saturations or a rounding tie (holes the numeric coverage names), the directed edge
/// queries take every one of them, and the testbench with both passes against the golden
/// model, which holds the coordinate at the format's ends as the unit does.
#[test]
fn directed_queries_close_the_holes_random_parallax_stimulus_leaves() {
    use tb::frames::{drive_parallax, parallax_edges};
    use units::frames::parallax::ParallaxUnit;
    let holes = |qs: &[tb::frames::ParallaxQ]| {
        let mut sim = hdl::kernel::Sim::new(ParallaxUnit::new());
        hdl::fx::set_tracking(true);
        for q in qs {
            drive_parallax(&mut sim.dut, Some(q));
            sim.step();
        }
        hdl::fx::set_tracking(false);
        let rows = verif::numeric::rows(&sim.dut);
        assert_eq!(rows.len(), 2, "u_out, v_out");
        assert!(rows.iter().all(|r| r.narrowed == qs.len() as u64));
        rows.iter().flat_map(|r| r.holes()).collect::<Vec<_>>()
    };
    let random = parallax_queries(3000, &mut Stimulus::new(Seed(0x7e47)));
    let found = holes(&random);
    for c in ["u_out", "v_out"] {
        for h in ["saturation high", "saturation low", "tie"] {
            let hole = format!("parallax.{c}: {h} never reached");
            assert!(found.contains(&hole), "{hole} not in {found:?}");
        }
    }
    assert_eq!(found.len(), 6);
    let mut both = random;
    both.extend(parallax_edges());
    assert_eq!(holes(&both), Vec::<String>::new(), "every path taken");
    let opts = verif::RunOptions {
        count: Some(200),
        ..Default::default()
    };
    let r = verif::run_testbench(&ParallaxTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.failures, r.mismatch_log);
    assert_eq!(r.numeric_percent, Some(100.0));
    assert!(r.numeric_holes.is_empty(), "{:?}", r.numeric_holes);
}
