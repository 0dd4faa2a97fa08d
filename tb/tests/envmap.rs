//! Environment mapping (issue 15, begun): the cube-face unit against f64.

use hdl::envmap::cube_face::{face_st, CubeFace, ST_BOUND_LSB};
use hdl::kernel::Sim;
use proptest::prelude::*;

/// 200,000 random reflection vectors (every magnitude from 2^-16 to 8, every direction, and
/// the ties of two or three equal components): the face equals f64's (exact compares on the
/// same values); s and t within their derived bound (3/4 LSB) of the exact coordinates.
#[test]
fn the_face_and_coordinates_agree_with_f64() {
    let unit = CubeFace::new();
    let tab = *unit.table();
    let mut stim = verif::seeded_stimulus("cube face");
    let comp = prop_oneof![
        8 => -(1i64 << 19)..(1i64 << 19),
        1 => -300i64..300,
        1 => Just(65536i64),
        1 => Just(-65536i64),
    ];
    let ws = stim.draw_n(&[comp.clone(), comp.clone(), comp], 200_000);
    let mut worst = 0.0f64;
    for w in ws {
        let (face, s, t) = face_st(w, &tab);
        let (gf, gs, gt) = golden::envmap::face_st(w.map(|c| c as f64 / 65536.0));
        assert_eq!(face, gf, "{w:?}");
        for (got, want) in [(s, gs), (t, gt)] {
            let e = (got as f64 / 4096.0 - want.min(1.0 - 1.0 / 4096.0)).abs() * 4096.0;
            worst = worst.max(e);
            assert!(
                e <= ST_BOUND_LSB as f64 / 4.0,
                "{w:?}: {got} vs {want} ({e} LSB)"
            );
        }
    }
    eprintln!("cube face: worst s, t error {worst:.4} LSB");
    assert!(worst > 0.5, "one rounding alone reaches half an LSB");
}

/// The unit: one register stage, its outputs the function's.
#[test]
fn the_unit_registers_the_function() {
    let mut sim = Sim::new(CubeFace::new()).check_schedule(true);
    sim.reset(1);
    let w = [-40_000i64, 90_000, 12_345];
    for (c, x) in w.iter().enumerate() {
        sim.dut.w[c].set_raw(*x);
    }
    sim.dut.valid_in.set_bool(true);
    sim.eval();
    assert!(!sim.dut.valid.q().is_high());
    sim.tick();
    sim.dut.valid_in.set_bool(false);
    sim.eval();
    let tab = *sim.dut.table();
    let (f, s, t) = face_st(w, &tab);
    let d = &sim.dut;
    assert!(d.valid.q().is_high());
    assert_eq!(
        (d.face.q().bits(), d.s.q().bits(), d.t.q().bits()),
        (u64::from(f), s, t)
    );
    assert_eq!(f, 2, "+y is the major axis");
}
