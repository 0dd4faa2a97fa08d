//! Volume rendering on the TEXRAM (section 13): the regress testbench, the document's two
//! timings from the page-register model, and the linear-field properties.

use tb::runs::volume::{timings, Axis};
use tb::volume::ref_sample;
use units::volume::layout::{Mode, Order, VolumeParams};

/// The testbench over every configuration with the schedule check: bit-exact against the
/// reference, within 0.5 LSB of golden, slots as the page-register model counts them.
#[test]
fn the_testbench_passes_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(80),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&tb::volume::VolumeTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?}", r.failures);
    assert_eq!(r.mismatches, 0);
    assert!(r.coverage_percent > 99.0, "{}", r.coverage_percent);
}

/// Section 13's timings, reproduced from the page registers with column-major voxel words,
/// 512-word rows and rays along x: RGBA 64x128x128 on four chips (about 70 ms) and
/// 256x128x128 with gradients on four chips (about 0.28 s), both within 15 %. Slice-major
/// words (as level 0 stores a texture) put a ray's two slices in different rows: every
/// access faults, twice the time.
#[test]
fn the_documents_timings_from_the_page_registers() {
    let [rgba, grad] = timings(Order::ColumnMajor, 512, Axis::X).unwrap();
    eprintln!("{rgba:?}\n{grad:?}");
    assert_eq!(rgba.samples, 64 * 128 * 128);
    assert_eq!(rgba.accesses, 2 * rgba.samples);
    assert_eq!(grad.accesses, 8 * grad.samples);
    for t in [&rgba, &grad] {
        assert!((t.ms / t.document_ms - 1.0).abs() < 0.15, "{t:?}");
        // The ideal is one slot an access.
        assert!(t.slots > t.accesses);
    }
    let [slice, _] = timings(Order::SliceMajor, 512, Axis::X).unwrap();
    assert_eq!(slice.slots, 2 * slice.accesses, "every access faults");
}

/// A linear field `ax + by + cz + d`: the value within 0.5 LSB of the field at the
/// weight-quantised point, the gradient exactly (2a, 2b, 2c) wherever the neighbours are
/// inside, on the ray caster and the reference.
#[test]
fn a_linear_field_gives_exact_gradients_inside() {
    use hdl::kernel::Sim;
    use units::volume::ray_caster_fig15::RayCaster;
    let dims = (16u32, 12u32, 10u32);
    let (a, b, c, d) = (3i64, 5, 7, 20);
    let vox: Vec<u8> = (0..dims.0 * dims.1 * dims.2)
        .map(|n| {
            let (x, y, z) = (n % dims.0, n / dims.0 % dims.1, n / (dims.0 * dims.1));
            (a * i64::from(x) + b * i64::from(y) + c * i64::from(z) + d) as u8
        })
        .collect();
    let p = VolumeParams::new(dims.0, dims.1, dims.2);
    let mut sim = Sim::new(RayCaster::new(p, Mode::Gradient, &vox).unwrap());
    sim.reset(2);
    let mut stim = verif::seeded_stimulus("volume linear");
    let pts: Vec<[i64; 3]> = (0..500)
        .map(|_| {
            let r = |n: u32| 1i64 << 12..(i64::from(n) - 2) << 12;
            let s = (r(dims.0), r(dims.1), r(dims.2));
            let (x, y, z) = stim.draw(&s);
            [x, y, z]
        })
        .collect();
    let (mut got, mut next) = (Vec::new(), 0);
    for _ in 0..100 * pts.len() {
        let dut = &mut sim.dut;
        dut.ray.valid.set_bool(next < pts.len());
        if let Some(pt) = pts.get(next) {
            for (c, x) in pt.iter().enumerate() {
                dut.ray.p[c].set_raw(*x);
                dut.ray.d[c].set_raw(0);
            }
            dut.ray.steps.set_bits(1);
        }
        sim.eval();
        let d = &sim.dut;
        next += usize::from(d.ray.valid.is_high() && d.ray_ready.is_high());
        if d.out.valid.q().is_high() {
            got.push((
                d.out.value.q().bits(),
                d.out.g.each_ref().map(|r| r.q().raw()),
            ));
        }
        sim.tick();
        if got.len() == pts.len() {
            break;
        }
    }
    assert_eq!(got.len(), pts.len());
    for (pt, (v, g)) in pts.iter().zip(&got) {
        let q = pt.map(|c| (c >> 4 << 4) as f64 / 4096.0);
        let exact = a as f64 * q[0] + b as f64 * q[1] + c as f64 * q[2] + d as f64;
        assert!((*v as f64 - exact).abs() <= 0.5, "{pt:?}: {v} vs {exact}");
        assert_eq!(*g, [(2 * a) << 4, (2 * b) << 4, (2 * c) << 4], "{pt:?}");
        assert_eq!(ref_sample(&vox, dims, *pt, Mode::Gradient), (*v as u8, *g));
    }
}

/// Pre-classified RGBA on four chips in lock-step: every sample's four components equal the
/// reference of their planes (checked inside `render`), the chips never fall out of step,
/// and the composited picture is not empty.
/// The caster takes exactly the volume's voxels: one fewer or one more is refused, naming
/// both counts.
#[test]
fn the_voxel_count_is_the_volumes() {
    use units::volume::ray_caster_fig15::RayCaster;
    let p = VolumeParams::new(4, 4, 4);
    assert!(RayCaster::new(p, Mode::Value, &[0; 64]).is_ok());
    for n in [63, 65] {
        let e = RayCaster::new(p, Mode::Value, &vec![0; n]).err().unwrap();
        assert_eq!(e, format!("{n} voxels for a 4x4x4 volume (64)"));
    }
}

/// A chip in gradient mode (eight accesses a sample) among three in value mode (two) falls
/// out of step on the first ray: the group flags it the cycle after they first differ, in
/// ready or in valid, and keeps the flag.
#[test]
fn chips_out_of_step_are_flagged_at_once() {
    use hdl::kernel::Sim;
    use units::volume::lockstep::VolumeLockstep;
    use units::volume::ray_caster_fig15::RayCaster;
    let p = VolumeParams::new(8, 8, 8);
    let planes = [0, 1, 2, 3].map(|c| vec![40 * c as u8; 512]);
    let mut group = VolumeLockstep::new(p, &planes).unwrap();
    group.chips[3] = RayCaster::new(p, Mode::Gradient, &planes[3])
        .unwrap()
        .named("chip_a");
    let mut sim = Sim::new(group).check_schedule(true);
    sim.reset(2);
    let one = 1i64 << units::volume::layout::POS_FRAC;
    let mut first_apart = None;
    for _ in 0..200 {
        let d = &mut sim.dut;
        d.port.valid.set_bool(true);
        for (c, (pos, dir)) in [(2, one / 4), (3, one / 8), (1, one / 2)]
            .into_iter()
            .enumerate()
        {
            d.port.p[c].set_raw(pos * one);
            d.port.d[c].set_raw(dir);
        }
        d.port.steps.set_bits(8);
        sim.eval();
        let c = &sim.dut.chips;
        let differ = |f: &dyn Fn(&RayCaster) -> bool| c.iter().any(|x| f(x) != f(&c[0]));
        let apart = differ(&|x| x.ray_ready.is_high()) || differ(&|x| x.out.valid.q().is_high());
        if apart && first_apart.is_none() {
            first_apart = Some(sim.cycle());
        }
        assert!(!sim.dut.out_of_step.q().is_high() || first_apart.is_some());
        sim.tick();
        if let Some(at) = first_apart {
            assert!(
                sim.dut.out_of_step.q().is_high(),
                "apart at {at}, not flagged"
            );
        }
    }
    assert!(first_apart.is_some(), "the chips never fell out of step");
}

#[test]
fn four_chips_in_lock_step_render_the_built_in_volume() {
    let (px, samples) = tb::pictures::volume::render(16, 12).unwrap();
    assert_eq!(px.len(), 144);
    assert_eq!(samples, 144 * 32);
    assert!(px.iter().any(|c| c.iter().any(|&x| x > 30)), "{px:?}");
    assert!(
        px.iter().any(|c| c.iter().all(|&x| x < 30)),
        "background rays stay dark"
    );
}

/// The mirror in constant time equals reflecting step by step at 0 and n - 1, for every
/// size up to 9 and every index within twenty periods either side.
#[test]
fn mirror_equals_reflecting_step_by_step() {
    let reflect = |mut i: i64, n: i64| -> usize {
        if n == 1 {
            return 0;
        }
        loop {
            if i < 0 {
                i = -i;
            } else if i >= n {
                i = 2 * (n - 1) - i;
            } else {
                return i as usize;
            }
        }
    };
    for n in 1..=9u32 {
        let span = 40 * i64::from(n);
        for i in -span..=span {
            assert_eq!(
                tb::volume::mirror(i, n),
                reflect(i, i64::from(n)),
                "i {i}, n {n}"
            );
        }
    }
    assert_eq!(
        tb::volume::mirror(i64::from(i32::MAX), 5),
        reflect(i64::from(i32::MAX), 5)
    );
}
