//! Footprint assembly (section 10): the setup unit against the f64 setup, the generator's
//! invariants, the assembled pixel against the integer reference on the stub and the chip,
//! the regress testbench, and the quality claim measured.

use golden::footprint::LAMBDA_BOUND;
use tb::footprint::{pixels, ref_assemble, ref_setup, Pixel};
use tb::texram::{test_map, RefBorder, RefMipmap};
use units::footprint::assembly_fig12::{assemble, first_point};
use units::footprint::setup_fig12::{setup, NRounding, SetupParams, SetupUnit};
use units::texram::stub::TexramStub;
use units::texram::{Border, Drf, TexramAccess, TexramRequest};

fn table() -> [i32; 64] {
    *SetupUnit::new("s", SetupParams::default()).unwrap().table()
}

/// Eqs 19-21 against f64 with real square roots and logarithms on 200,000 random
/// derivative pairs: the same N except within 2^-20 of a rounding threshold (at least
/// 99.9 % agree), the same step, lambda within its derived bound.
#[test]
fn the_setup_unit_agrees_with_the_f64_setup() {
    let t = table();
    let mut stim = verif::seeded_stimulus("footprint setup");
    for rounding in [NRounding::Log, NRounding::Linear] {
        let p = SetupParams {
            max_log2_n: 4,
            rounding,
        };
        let px = pixels(10, 10, 100_000, &mut stim);
        let (mut same, mut near, mut worst) = (0, 0, 0.0f64);
        for q in &px {
            let s = setup(&p, q.r1, q.r2, &t);
            let f = |r: (i32, i32)| (f64::from(r.0) / 256.0, f64::from(r.1) / 256.0);
            let g = golden::footprint::setup(f(q.r1), f(q.r2), 4, rounding == NRounding::Linear);
            let linear = rounding == NRounding::Linear;
            if s.log2_n == g.log2_n {
                same += 1;
                let step = (f64::from(s.du) / 16384.0, f64::from(s.dv) / 16384.0);
                assert_eq!(step, g.step, "{q:?}");
            } else {
                assert!(
                    golden::footprint::near_threshold(&g, linear),
                    "{q:?}: N 2^{} against 2^{}",
                    s.log2_n,
                    g.log2_n
                );
                near += 1;
            }
            if g.q > 0.0 && (-4.0..=10.0).contains(&g.lambda) {
                worst = worst.max((f64::from(s.lambda) / 256.0 - g.lambda).abs());
            }
        }
        eprintln!("{rounding:?}: {same} same N, {near} near a threshold, lambda error {worst:.5}");
        assert!(same as f64 >= 0.999 * px.len() as f64);
        assert!(worst <= LAMBDA_BOUND, "{worst} > {LAMBDA_BOUND}");
        assert!(
            worst > LAMBDA_BOUND / 2.0,
            "the bound is not loose: {worst}"
        );
    }
}

/// The sample points are symmetric about p: their offsets sum to exactly zero, the first
/// and last are mirror images, and N = 1 samples p itself.
#[test]
fn the_sample_points_are_symmetric_about_the_pixel_centre() {
    for k in 0..=6u32 {
        for (u, du) in [(1000, 16384), (-77, -12345), (5, 1), (0, (1 << 25) - 1)] {
            let (p0, d) = first_point(u, du, k);
            let p = i64::from(u) << 7;
            let offsets: Vec<i64> = (0..1i64 << k).map(|i| p0 + i * d - p).collect();
            assert_eq!(offsets.iter().sum::<i64>(), 0, "k {k} du {du}");
            assert_eq!(offsets[0], -offsets[offsets.len() - 1]);
        }
    }
    assert_eq!(first_point(1234, 999, 0), (1234 << 7, 2 * 999));
}

fn chip_pair(wl: u32, hl: u32, border: Border, level0: &[u8]) -> TexramStub {
    let mut stub = TexramStub::new();
    stub.set_drf(0, Drf::new(wl, hl, border)).unwrap();
    stub.load(0, level0).unwrap();
    stub
}

/// Assembly at transaction level on the stub and on the cycle-accurate chip behind the same
/// interface: the integer reference's value and N, pixel by pixel; the same slots; the
/// result within the min/max of the texels read.
#[test]
fn assembly_matches_the_integer_reference_on_the_stub_and_the_chip() {
    use units::texram::texram_802::{Texram802, Texram802Access, TexramParams};
    let mut stim = verif::seeded_stimulus("footprint assembly");
    let t = table();
    let (wl, hl, border) = (7, 6, Border::Mirror);
    let level0 = test_map(1 << wl, 1 << hl, &mut stim);
    let reference = RefMipmap::build(1 << wl, 1 << hl, &level0);
    let mut stub = chip_pair(wl, hl, border, &level0);
    let mut chip = Texram802::new(TexramParams::default()).unwrap();
    chip.set_drf(0, Drf::new(wl, hl, border)).unwrap();
    chip.load(0, &level0).unwrap();
    let mut chip = Texram802Access::new(chip);
    let p = SetupParams::default();
    for q in pixels(wl, hl, 2000, &mut stim) {
        let s = setup(&p, q.r1, q.r2, &t);
        let (slots0, (n0, faults0)) = (stub.slots(), stub.counts());
        let a = assemble(&mut stub, 0, (q.u, q.v), &s).unwrap();
        // The pixel's accesses, slots and faults are what the chip counted for it.
        let (n1, faults1) = stub.counts();
        let took = (stub.slots() - slots0, n1 - n0, faults1 - faults0);
        assert_eq!(took, (a.slots.into(), a.n.into(), a.faults.into()), "{q:?}");
        let c = assemble(&mut chip, 0, (q.u, q.v), &s).unwrap();
        assert_eq!(a, c, "{q:?}");
        let (want, points) = ref_assemble(&reference, RefBorder::Mirror, &p, &q);
        assert_eq!((a.value, a.n), (want.value, want.n), "{q:?}");
        let (lo, hi) = points.iter().fold((255, 0), |(lo, hi), &(u, v)| {
            let (tx, _) = reference.access(u, v, s.lambda, RefBorder::Mirror);
            (
                lo.min(*tx.iter().min().unwrap()),
                hi.max(*tx.iter().max().unwrap()),
            )
        });
        assert!(
            (lo..=hi).contains(&a.value),
            "{q:?}: {} not in {lo}..={hi}",
            a.value
        );
    }
    assert_eq!(stub.slots(), chip.slots());
    assert!(stub.counts().1 > 0, "some pixel faulted");
}

/// An isotropic footprint (r1 perpendicular to r2, equal lengths) is one access: N = 1 and
/// the result is the plain trilinear access at lambda = log2 |r|.
#[test]
fn an_isotropic_footprint_is_exactly_trilinear() {
    let mut stim = verif::seeded_stimulus("footprint isotropic");
    let t = table();
    let level0 = test_map(64, 64, &mut stim);
    let mut stub = chip_pair(6, 6, Border::Wrap, &level0);
    let p = SetupParams::default();
    for len in [64, 200, 256, 700, 1024, 5000] {
        for (r1, r2) in [((len, 0), (0, len)), ((0, -len), (len, 0))] {
            let q = Pixel {
                u: 3000,
                v: 7000,
                r1,
                r2,
            };
            let s = setup(&p, q.r1, q.r2, &t);
            assert_eq!(s.log2_n, 0, "{q:?}");
            assert_eq!(ref_setup(&p, &q).0, 1);
            let a = assemble(&mut stub, 0, (q.u, q.v), &s).unwrap();
            let r = stub
                .access(TexramRequest {
                    drf: 0,
                    u: q.u,
                    v: q.v,
                    lambda: s.lambda,
                })
                .unwrap();
            assert_eq!((a.value, a.n), (r.value, 1));
        }
    }
}

/// The regress testbench over every configuration, with the schedule check.
#[test]
fn the_testbench_passes_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(300),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&tb::footprint::FootprintTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?}", r.failures);
    assert_eq!(r.mismatches, 0);
    assert!(r.coverage_percent > 99.0, "{}", r.coverage_percent);
    assert!(r.stats.max_abs_lsb <= 0.5 + 1e-9);
}

/// Section 4's claim, measured: on a plane seen at 75 and 85 degrees footprint assembly is
/// closer to the exact footprint's mean than isotropic trilinear filtering; facing the
/// camera both are one access a pixel and equal.
#[test]
fn footprint_assembly_beats_trilinear_on_tilted_planes() {
    let p = SetupParams::default();
    for tilt in [0.0, 60.0, 75.0, 85.0] {
        let r = tb::runs::footprint::quality(tilt, &p).unwrap();
        eprintln!("{r:?}");
        assert!(r.pixels > 1000, "{r:?}");
        if tilt == 0.0 {
            assert_eq!(r.mean_n, 1.0);
            assert_eq!(r.rmse_trilinear, r.rmse_footprint);
        }
        if tilt >= 75.0 {
            assert!(r.rmse_footprint < r.rmse_trilinear, "{r:?}");
            assert!(r.mean_n > 2.0, "{r:?}");
        }
    }
}

/// Para. 0081 on the FIG. 7 pipeline: the tangent average handed to normal unit 156 with each
/// pixel's last sample is, bit for bit, the integer mean of the plain pipeline's tangents at
/// the reference's sample points; with N = 1 the normals are the plain pipeline's.
#[test]
fn the_fig7_tangent_average_is_the_mean_of_the_plain_pipelines_tangents() {
    use hdl::kernel::Sim;
    use tb::footprint_normals::{expectations, npixels, NPixel};
    use units::bump::normal_pipeline_fig7::NormalPipeline;
    use units::bump::params::BumpParams;
    use units::footprint::normals_0081::FootprintNormals;
    let p = BumpParams::default();
    let map = tb::maps::builtin("noise", 32, 32, p.texel_fmt()).unwrap();
    let mut stim = verif::seeded_stimulus("footprint fig7");
    let mut px = npixels(&p, 32, 32, 400, &mut stim);
    let ones: Vec<NPixel> = px.iter().map(|q| NPixel { log2_n: 0, ..*q }).collect();
    px.extend(ones.iter().copied());
    let want = expectations(&p, &map, &px).unwrap();
    let pipe = NormalPipeline::new("fig7", p, map.clone(), None).unwrap();
    let mut sim = Sim::new(FootprintNormals::new(pipe)).check_schedule(true);
    sim.reset(2);
    let (mut next, mut avgs, mut normals) = (0, Vec::new(), Vec::new());
    for _ in 0..40 * px.len() {
        tb::footprint_normals::drive_pixel(&mut sim.dut, px.get(next));
        sim.eval();
        let d = &sim.dut;
        next += usize::from(d.px_valid.is_high() && d.px_ready.is_high());
        let a = d.pipe.tangent_average().unwrap();
        if a.last.is_high() && avgs.len() < next {
            avgs.push([a.du.raw(), a.dv.raw(), a.height.raw()]);
        }
        if d.pipe.valid.is_high() {
            normals.push([d.pipe.nx.raw(), d.pipe.ny.raw(), d.pipe.nz.raw()]);
        }
        sim.tick();
        if normals.len() == px.len() {
            break;
        }
    }
    assert_eq!(normals.len(), px.len());
    for (k, (got, (q, avg, _))) in avgs.iter().zip(&want).enumerate() {
        assert_eq!(got, avg, "pixel {k}: {q:?}");
    }
    // N = 1: the plain pipeline's normals at the pixel centres, bit for bit.
    let mut plain = Sim::new(NormalPipeline::new("plain", p, map, None).unwrap());
    plain.reset(1);
    let lat = plain.dut.latency();
    for (k, q) in ones
        .iter()
        .enumerate()
        .map(|(k, q)| (k + px.len() - ones.len(), q))
    {
        let d = &mut plain.dut;
        d.u.set_raw(q.u);
        d.v.set_raw(q.v);
        d.scale.set_raw(q.scale);
        d.valid_in.set_bool(true);
        for _ in 0..lat {
            plain.eval();
            plain.tick();
        }
        plain.eval();
        let d = &plain.dut;
        assert_eq!(
            normals[k],
            [d.nx.raw(), d.ny.raw(), d.nz.raw()],
            "pixel {k}"
        );
        plain.tick();
    }
}

/// The FIG. 7 footprint testbench over its configurations, with the schedule check.
#[test]
fn the_fig7_footprint_testbench_passes() {
    let opts = verif::RunOptions {
        count: Some(150),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(
        &tb::footprint_normals::FootprintNormalsTb,
        &opts,
        &mut |_| {},
    )
    .unwrap();
    assert!(r.passed, "{:?}", r.failures);
    assert_eq!(r.mismatches, 0);
    assert!(r.coverage_percent > 99.0, "{}", r.coverage_percent);
}
