//! Environment mapping: the cube-face unit against f64.

use hdl::kernel::Sim;
use proptest::prelude::*;
use units::envmap::cube_face::{face_st, CubeFace, ST_BOUND_LSB};

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

/// The reflection unit: one register stage holding `reflect` of what it was given while
/// `valid_in` was high, and holding it through a cycle without.
#[test]
fn the_reflection_unit_registers_the_function_and_holds() {
    use units::envmap::reflect_eq4::{reflect, Reflect};
    let mut sim = Sim::new(Reflect::new()).check_schedule(true);
    sim.reset(1);
    let (nb, v) = ([3_000i64, -20_000, 9_000], [-5_000i64, 7_000, 14_000]);
    let want = reflect(nb, v);
    for c in 0..3 {
        sim.dut.nb[c].set_raw(nb[c]);
        sim.dut.v[c].set_raw(v[c]);
    }
    sim.dut.valid_in.set_bool(true);
    sim.eval();
    assert!(!sim.dut.valid.q().is_high());
    sim.tick();
    // The inputs change but valid_in is low: the result stays, valid falls a cycle later.
    sim.dut.valid_in.set_bool(false);
    sim.dut.v[0].set_raw(1);
    sim.eval();
    let got = |d: &Reflect| d.w.each_ref().map(|r| r.q().raw());
    assert!(sim.dut.valid.q().is_high());
    assert_eq!(got(&sim.dut), want);
    assert_ne!(want, [0; 3]);
    sim.tick();
    sim.eval();
    assert!(!sim.dut.valid.q().is_high());
    assert_eq!(got(&sim.dut), want);
}

/// Eq. 4 against f64 on 100,000 random perturbed normals (`n + e1 b1 + e2 b2` with
/// |b_i| < 1, so |n_b|^2 < 3) and unit eye vectors: within half an LSB of sQ3.16 (one
/// rounding of the exact value); the angle to n_b is the eye's; chained into the cube-face
/// unit, the face is f64's unless the two largest components are within 2^-12 relative.
#[test]
fn the_reflection_vector_is_eq4_with_one_rounding() {
    use units::envmap::reflect_eq4::reflect;
    let mut stim = verif::seeded_stimulus("reflect eq4");
    let tab = *CubeFace::new().table();
    let unit = |a: [f64; 3]| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        a.map(|c| c / l)
    };
    let q = |a: [f64; 3], f: f64| a.map(|c| (c * f).round() as i64);
    let s = proptest::array::uniform3(-1.0f64..1.0);
    let (mut worst, mut near) = (0.0f64, 0);
    for _ in 0..100_000 {
        let (a, b, e) = (stim.draw(&s), stim.draw(&s), stim.draw(&(-0.99f64..0.99)));
        let n = unit(a);
        // A tangent e1 and e2 = n x e1, the bump b1 = e[0], b2 = e[0] / 2.
        let t = unit([
            b[1] * n[2] - b[2] * n[1],
            b[2] * n[0] - b[0] * n[2],
            b[0] * n[1] - b[1] * n[0],
        ]);
        let t2 = [
            n[1] * t[2] - n[2] * t[1],
            n[2] * t[0] - n[0] * t[2],
            n[0] * t[1] - n[1] * t[0],
        ];
        let nb = std::array::from_fn(|c| n[c] + e * t[c] + e / 2.0 * t2[c]);
        let v = unit(b);
        let (nbq, vq) = (q(nb, 16384.0), q(v, 16384.0));
        let w = reflect(nbq, vq);
        let g = golden::envmap::reflect(
            nbq.map(|x| x as f64 / 16384.0),
            vq.map(|x| x as f64 / 16384.0),
        );
        for c in 0..3 {
            let err = (w[c] as f64 / 65536.0 - g[c]).abs() * 65536.0;
            worst = worst.max(err);
            assert!(err <= 0.5 + 1e-9, "{nbq:?} {vq:?}: {w:?} vs {g:?}");
        }
        let (face, _, _) = face_st(w, &tab);
        let (gf, _, _) = golden::envmap::face_st(g);
        if face != gf {
            let mut m = g.map(f64::abs);
            m.sort_by(|x, y| y.total_cmp(x));
            assert!(
                (m[0] - m[1]) / m[0] < 1.0 / 4096.0,
                "{g:?}: face {face} vs {gf}"
            );
            near += 1;
        }
    }
    eprintln!("eq. 4: worst {worst:.4} LSB; {near} faces decided at a near tie");
    assert!(worst > 0.4);
}

/// Eqs 2-3 on 50,000 random interpolated normals (lengths 0.25 to 1.9), reference directions
/// and bumps: `n` within its derived bound of `n1/|n1|` (half an LSB plus the inverse square
/// root's and the mantissa truncation's relative errors); `e1` and `e2` of unit length and
/// orthogonal to `n` and each other within their derived bound; `n_b` within half an LSB of
/// `n + e1 b1 + e2 b2` of the unit's own vectors; a random `h` is never parallel.
#[test]
fn the_local_frame_is_orthonormal_within_its_bound() {
    use units::envmap::frame_eq2::FrameUnit;
    let mut unit = FrameUnit::new();
    let p = units::bump::params::RsqrtParams::default();
    let eps = golden::rsqrt::error_bound_ulps(p.table_bits, p.iterations, p.y_frac)
        * 2.0
        * (-(p.y_frac as f64)).exp2()
        + (-(p.mant_frac as f64 + 1.0)).exp2();
    let lsb = 1.0 / 16384.0;
    let bound_n = 0.5 * lsb + eps;
    // A vector normalised by the unit is off unit length by at most d = eps + sqrt(3)/2 LSB
    // (the reciprocal's error and three component roundings of half an LSB). e1 is h x n
    // normalised: orthogonal to the unit's n before its rounding, so e1.n <= sqrt(3)/2 LSB;
    // e2 = n x e1 is orthogonal to both before its rounding, and its length (1 + d)^2 ~
    // 1 + 2d: so every quantity below within 2d + sqrt(3)/2 LSB.
    let half3 = 3f64.sqrt() / 2.0 * lsb;
    let bound_e = 2.0 * (eps + half3) + half3 + 1e-9;
    let mut stim = verif::seeded_stimulus("local frame");
    let s3 = proptest::array::uniform3(-1.0f64..1.0);
    let (mut worst_n, mut worst_e, mut tested) = (0.0f64, 0.0f64, 0);
    for _ in 0..50_000 {
        let (a, hh, len, b) = (
            stim.draw(&s3),
            stim.draw(&s3),
            stim.draw(&(0.25f64..1.9)),
            stim.draw(&(-127i64..128, -127i64..128)),
        );
        let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        let lh = (hh[0] * hh[0] + hh[1] * hh[1] + hh[2] * hh[2]).sqrt();
        if la < 0.1 || lh < 0.1 {
            continue;
        }
        let n1 = a.map(|c| (c / la * len * 16384.0).round() as i64);
        let h = hh.map(|c| (c / lh * 16384.0).round() as i64);
        let f = unit.frame(n1, h, b).unwrap();
        let v = |x: [i64; 3]| x.map(|c| c as f64 * lsb);
        let (n, e1, e2) = (v(f.n), v(f.e1), v(f.e2));
        let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
        let n1f = v(n1);
        let l1 = dot(n1f, n1f).sqrt();
        for c in 0..3 {
            let e = (n[c] - n1f[c] / l1).abs();
            worst_n = worst_n.max(e / lsb);
            assert!(e <= bound_n, "{n1:?}: n {n:?}");
        }
        tested += 1;
        for (what, x) in [
            ("|e1|", dot(e1, e1).sqrt() - 1.0),
            ("|e2|", dot(e2, e2).sqrt() - 1.0),
            ("e1.n", dot(e1, n)),
            ("e2.n", dot(e2, n)),
            ("e1.e2", dot(e1, e2)),
        ] {
            worst_e = worst_e.max(x.abs() / lsb);
            assert!(x.abs() <= bound_e, "{n1:?} {h:?}: {what} = {x:e}");
        }
        for c in 0..3 {
            let want = n[c] + e1[c] * b.0 as f64 / 128.0 + e2[c] * b.1 as f64 / 128.0;
            assert!(
                (f.nb[c] as f64 * lsb - want).abs() <= 0.5 * lsb + 1e-12,
                "{n1:?}: n_b"
            );
        }
        assert!(!f.parallel);
    }
    eprintln!("frame: n within {worst_n:.3} LSB, e1/e2 within {worst_e:.3} LSB ({tested} frames)");
    assert!(tested > 40_000);
}
