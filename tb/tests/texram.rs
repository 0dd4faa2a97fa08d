//! The TEXRAM access (`units::texram`, its behavioural stub for now) against the integer
//! reference of `tb::texram` (bit-exact on 10^6 random requests over square, rectangular and
//! 1-wide maps and every border operation) and the f64 golden model of `golden::texram`
//! (within half an LSB with the chip's truncated weights; inside the min/max of the eight
//! texels; integer lambda is the bilinear of that level). Seeds are printed; replay with
//! `TEXRTL_SEED`.

use proptest::prelude::*;
use tb::texram::{RefBorder, RefMipmap};
use units::texram::stub::TexramStub;
use units::texram::{Border, Drf, TexramAccess, TexramRequest};

const MAPS: [(u32, u32); 5] = [(6, 6), (7, 3), (0, 5), (4, 0), (2, 2)];

fn borders() -> [(Border, RefBorder, golden::texram::Border); 4] {
    use golden::texram::Border as G;
    [
        (Border::Wrap, RefBorder::Wrap, G::Wrap),
        (Border::Clamp, RefBorder::Clamp, G::Clamp),
        (Border::Mirror, RefBorder::Mirror, G::Mirror),
        (Border::Colour(77), RefBorder::Colour(77), G::Colour(77.0)),
    ]
}

/// A request to DRF 0.
fn req(u: i32, v: i32, lambda: i32) -> TexramRequest {
    TexramRequest {
        drf: 0,
        u,
        v,
        lambda,
    }
}

/// A chip with `map` loaded in DRF 0, and the reference's mipmap of the same level 0.
fn setup(wl: u32, hl: u32, border: Border, seed: u64) -> (TexramStub, RefMipmap) {
    let (w, h) = (1u32 << wl, 1u32 << hl);
    let level0: Vec<u8> = (0..w * h)
        .map(|k| ((u64::from(k) * 0x9e37_79b9 + seed) >> 13) as u8)
        .collect();
    let mut chip = TexramStub::new();
    chip.set_drf(0, Drf::new(wl, hl, border)).unwrap();
    chip.load(0, &level0).unwrap();
    (chip, RefMipmap::build(w, h, &level0))
}

/// Requests over the map and two texels beyond its edges, every lambda.
fn requests(wl: u32, hl: u32) -> impl Strategy<Value = (i32, i32, i32)> {
    let (w, h) = ((1i32 << wl) << 8, (1i32 << hl) << 8);
    (-512..w + 512, -512..h + 512, -4 * 256..=10 * 256)
}

#[test]
fn the_access_is_bit_exact_against_the_integer_reference() {
    let mut stim = verif::seeded_stimulus("texram bit-exact");
    let per = 1_000_000 / (MAPS.len() * 4);
    for (wl, hl) in MAPS {
        for (border, rb, _) in borders() {
            let (mut chip, reference) = setup(wl, hl, border, stim.seed().0);
            for (u, v, lambda) in stim.draw_n(&requests(wl, hl), per) {
                let r = chip.access(req(u, v, lambda)).unwrap();
                let (texels, value) = reference.access(u, v, lambda, rb);
                assert_eq!(
                    (r.texels, r.value),
                    (texels, value),
                    "map {wl},{hl} {border:?} u {u} v {v} lambda {lambda}"
                );
            }
        }
    }
}

#[test]
fn the_access_is_within_half_an_lsb_of_golden_and_within_its_texels() {
    let mut stim = verif::seeded_stimulus("texram golden");
    let mut worst: f64 = 0.0;
    for (wl, hl) in MAPS {
        for (border, rb, gb) in borders() {
            let (mut chip, reference) = setup(wl, hl, border, stim.seed().0);
            let g = golden::texram::Mipmap {
                width: 1 << wl,
                height: 1 << hl,
                levels: &reference.levels,
                border: gb,
            };
            let lmax = reference.levels.len() - 1;
            for (u, v, lambda) in stim.draw_n(&requests(wl, hl), 20_000) {
                let r = chip.access(req(u, v, lambda)).unwrap();
                let (fu, fv, fl) = (
                    f64::from(u) / 256.0,
                    f64::from(v) / 256.0,
                    f64::from(lambda) / 256.0,
                );
                let want = golden::texram::trilinear(
                    &g,
                    &golden::texram::Weights::truncated(fu, fv, fl, lmax),
                );
                let err = (f64::from(r.value) - want).abs();
                worst = worst.max(err);
                assert!(
                    err <= golden::texram::ERROR_BOUND_LSB,
                    "{wl},{hl} {rb:?} ({u},{v},{lambda}): {} vs {want}",
                    r.value
                );
                let (lo, hi) = (
                    r.texels.iter().min().unwrap(),
                    r.texels.iter().max().unwrap(),
                );
                assert!((lo..=hi).contains(&&r.value));
                if lambda % 256 == 0 || lambda < 0 {
                    // Integer (or negative) lambda: the coarser level has no weight.
                    assert_eq!(r.f, 0);
                }
            }
        }
    }
    eprintln!("texram against golden (truncated weights): worst error {worst:.4} LSB");
}

#[test]
fn integer_lambda_is_exactly_the_bilinear_of_its_level() {
    let (mut chip, reference) = setup(5, 4, Border::Wrap, 1);
    let g = golden::texram::Mipmap {
        width: 32,
        height: 16,
        levels: &reference.levels,
        border: golden::texram::Border::Wrap,
    };
    for l in 0..=5 {
        for (u, v) in [(300, 900), (2000, 17), (8191, 4095)] {
            let r = chip
                .access(TexramRequest {
                    drf: 0,
                    u,
                    v,
                    lambda: l << 8,
                })
                .unwrap();
            let w = golden::texram::Weights::truncated(
                f64::from(u) / 256.0,
                f64::from(v) / 256.0,
                f64::from(l),
                5,
            );
            let bil = golden::texram::trilinear(&g, &golden::texram::Weights { f: 0.0, ..w });
            assert!((f64::from(r.value) - bil).abs() <= 0.5 + 1e-9, "level {l}");
            assert_eq!(r.fine, l as u32);
        }
    }
}

/// One result of the chip.
#[derive(Clone, Copy, Debug)]
struct Out {
    /// The cycle it came out.
    cycle: u64,
    value: u8,
    rgba: [u8; 4],
    texels: [u8; 8],
    fault: bool,
}

/// Runs `reqs` back to back through the cycle-accurate chip (request k on DRF `drfs[k]` with
/// the illumination `illum[k]`, each 0 past its end; traced to `vcd` when given): its
/// results, its slot and conflict counts.
fn run_chip(
    chip: units::texram::texram_802::Texram802,
    reqs: &[(i32, i32, i32)],
    (drfs, illum): (&[u8], &[u32]),
    vcd: Option<&std::path::Path>,
) -> (Vec<Out>, u64, u64) {
    use hdl::kernel::Sim;
    let tracer = vcd.map(|p| waves::VcdTracer::create(p, "texram", Default::default()).unwrap());
    let mut sim = Sim::maybe_traced(chip, tracer)
        .unwrap()
        .check_schedule(true);
    sim.reset(2);
    let (mut next, mut out) = (0, Vec::new());
    while out.len() < reqs.len() {
        assert!(
            sim.cycle() < 100 + 200 * reqs.len() as u64,
            "the chip stalled"
        );
        let d = &mut sim.dut;
        d.req_valid.set_bool(next < reqs.len());
        if let Some(&(u, v, l)) = reqs.get(next) {
            d.req_u.set_raw(i64::from(u));
            d.req_v.set_raw(i64::from(v));
            d.req_lambda.set_raw(i64::from(l));
            d.req_drf
                .set_bits(u64::from(drfs.get(next).copied().unwrap_or(0)));
            d.req_illum
                .set_bits(u64::from(illum.get(next).copied().unwrap_or(0)));
        }
        sim.eval();
        let d = &sim.dut;
        if d.req_valid.is_high() && d.req_ready.is_high() {
            next += 1;
        }
        if d.output.out_valid.q().is_high() {
            out.push(Out {
                cycle: sim.cycle(),
                value: d.output.out_value.q().bits() as u8,
                rgba: (d.output.out_rgba.q().bits() as u32).to_be_bytes(),
                texels: d.output.out_texels.q().bits().to_le_bytes(),
                fault: d.output.out_fault.q().is_high(),
            });
        }
        sim.tick();
    }
    let (slots, conflicts) = (
        sim.dut.slots.q().bits(),
        sim.dut.address.conflicts.q().bits(),
    );
    sim.finish().unwrap();
    (out, slots, conflicts)
}

#[test]
fn the_cycle_accurate_chip_matches_the_stub_texel_for_texel_and_slot_for_slot() {
    use units::texram::texram_802::{Texram802, TexramParams};
    let mut stim = verif::seeded_stimulus("texram chip");
    for (wl, hl) in [(6, 6), (10, 10), (0, 5)] {
        for (border, _, _) in borders() {
            let (mut stub, reference) = setup(wl, hl, border, stim.seed().0);
            let mut chip = Texram802::new(TexramParams::default()).unwrap();
            chip.set_drf(0, Drf::new(wl, hl, border)).unwrap();
            chip.load(0, &reference.levels[0]).unwrap();
            let reqs = stim.draw_n(&requests(wl, hl), 2000);
            let (out, slots, _) = run_chip(chip, &reqs, (&[], &[]), None);
            let mut last = None;
            for (k, &(u, v, lambda)) in reqs.iter().enumerate() {
                let r = stub.access(req(u, v, lambda)).unwrap();
                let Out {
                    cycle,
                    value,
                    texels,
                    fault,
                    ..
                } = out[k];
                assert_eq!((value, texels), (r.value, r.texels), "request {k}");
                assert_eq!(fault, r.slots == 2, "request {k}");
                // Back to back: each result one slot (6 cycles) after the last, two after a fault.
                if let Some(prev) = last {
                    assert_eq!(cycle - prev, 6 * u64::from(r.slots), "request {k}");
                }
                last = Some(cycle);
            }
            assert_eq!(slots, stub.slots());
        }
    }
}

/// The three ways of putting a map into the chip (`load`, level by level with
/// `write_level`, and `load_map` through the `TexramAccess` interface) store the same texels:
/// each answers 300 requests as the stub does. `write_level` refuses an unset DRF and a level
/// the map does not have, and takes its top level.
#[test]
fn every_way_of_loading_the_chip_stores_the_same_map() {
    use units::texram::texram_802::{Texram802, Texram802Access, TexramParams};
    let mut stim = verif::seeded_stimulus("texram loads");
    let (wl, hl, border) = (5, 3, Border::Wrap);
    let d = Drf::new(wl, hl, border);
    let (mut stub, reference) = setup(wl, hl, border, stim.seed().0);
    let chip = || {
        let mut c = Texram802::new(TexramParams::default()).unwrap();
        c.set_drf(0, d).unwrap();
        c
    };
    let mut by_levels = chip();
    for (k, level) in reference.levels.iter().enumerate() {
        by_levels.write_level(0, k as u32, level).unwrap();
    }
    let mut by_levels = Texram802Access::new(by_levels);
    let mut by_map = Texram802Access::new(chip());
    by_map.load_map(&d, &reference.levels[0]).unwrap();
    let mut by_load = chip();
    by_load.load(0, &reference.levels[0]).unwrap();
    let mut by_load = Texram802Access::new(by_load);
    for (u, v, l) in stim.draw_n(&requests(wl, hl), 300) {
        let want = stub.access(req(u, v, l)).unwrap();
        for c in [&mut by_levels, &mut by_map, &mut by_load] {
            let got = c.access(req(u, v, l)).unwrap();
            assert_eq!(
                (got.value, got.texels),
                (want.value, want.texels),
                "{u} {v} {l}"
            );
        }
    }
    let mut c = chip();
    let top = d.max_level();
    let e = c.write_level(1, 0, &reference.levels[0]).unwrap_err();
    assert!(e.contains("drf 1: not set"), "{e}");
    let e = c.write_level(0, top + 1, &[0]).unwrap_err();
    assert!(e.contains(&format!("levels 0..={top}")), "{e}");
    assert_eq!(
        c.write_level(0, top, &reference.levels[top as usize]),
        Ok(())
    );
    let e = c.write_level(0, 0, &[0; 255]).unwrap_err();
    assert_eq!(e, "drf 0: level 0: 255 texels for 32x8");
}

/// A request to an unset DRF reads nothing: all its texels are 0 (the border colour's
/// source, 0), even straight after an access that left every bank's word on a texel of 7.
#[test]
fn an_unset_drf_reads_zeros_whatever_the_banks_hold() {
    use units::texram::texram_802::{Texram802, TexramParams};
    let mut chip = Texram802::new(TexramParams::default()).unwrap();
    chip.set_drf(0, Drf::new(4, 4, Border::Wrap)).unwrap();
    chip.load(0, &[7; 256]).unwrap();
    let (out, _, _) = run_chip(chip, &[(300, 500, -256); 4], (&[0, 1, 0, 1], &[]), None);
    let texels: Vec<u64> = out.iter().map(|o| u64::from_le_bytes(o.texels)).collect();
    assert_eq!(texels, [0x0707_0707_0707_0707, 0, 0x0707_0707_0707_0707, 0]);
}

#[test]
fn the_chip_waveform_has_one_scope_per_unit() {
    use units::texram::texram_802::{Texram802, TexramParams};
    let dir = std::env::temp_dir().join(format!("texrtl-texram-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let vcd = dir.join("texram_802.vcd");
    let mut chip = Texram802::new(TexramParams::default()).unwrap();
    chip.set_drf(0, Drf::new(4, 4, Border::Mirror)).unwrap();
    chip.load(0, &[7; 256]).unwrap();
    let (out, _, _) = run_chip(
        chip,
        &[(100, 200, 300), (4000, -90, 0)],
        (&[], &[]),
        Some(&vcd),
    );
    assert_eq!(out.len(), 2);
    let rb = waves::check::read_vcd(&vcd).unwrap();
    for unit in [
        "address_812",
        "page_registers_824",
        "banks_810",
        "banks_810.address_decoders_822",
        "clut_814",
        "trilinear_818",
        "output_820",
    ] {
        let scope = format!("tb.texram_802.{unit}.");
        assert!(
            rb.vars.keys().any(|n| n.starts_with(&scope)),
            "no scope {scope}"
        );
    }
    waves::check::check_gtkw(&vcd, &rb).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_documents_pixel_rates_come_from_the_page_registers() {
    let f = tb::runs::texram::figures();
    let rate = |what: &str| {
        f.iter()
            .find(|x| x.what.starts_with(what))
            .map(|x| x.pixels_per_second / 1e6)
            .unwrap()
    };
    let near = |got: f64, want: f64| (got / want - 1.0).abs() < 0.01;
    assert!(near(rate("one access"), 33.33), "{}", rate("one access"));
    assert!(near(rate("8 pixels"), 26.67), "{}", rate("8 pixels"));
    assert!(near(rate("2 accesses"), 16.67));
    assert!(near(rate("4 accesses"), 8.33));
    // Two maps in different rows of the same banks: every access faults, half the rate.
    assert!(near(rate("texture + environment maps"), 8.33));
}

/// The regress testbench over every configuration: no mismatch, coverage, the error bound.
#[test]
fn the_testbench_passes_the_chip_and_reports_full_coverage() {
    let tb = tb::texram::TexramTb;
    let opts = verif::RunOptions {
        count: Some(500),
        ..Default::default()
    };
    let r = verif::run_testbench(&tb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?}", r.failures);
    assert_eq!(r.mismatches, 0);
    assert!(r.coverage_percent > 99.0, "{}", r.coverage_percent);
    assert!(r.stats.max_abs_lsb <= 0.5 + 1e-9);
}

/// Index mode (CLUT 814): with the identity table it equals luminance mode component by
/// component; with a random table each component is the reference's trilinear of the
/// looked-up component; the cycle-accurate chip agrees with the stub.
#[test]
fn index_mode_filters_each_component_after_the_lookup() {
    use units::texram::clut_814::Clut;
    use units::texram::texram_802::{Texram802, TexramParams};
    use units::texram::Config;
    let mut stim = verif::seeded_stimulus("texram index");
    let (wl, hl, border) = (6, 5, Border::Mirror);
    let (_, reference) = setup(wl, hl, border, stim.seed().0);
    let level0 = reference.levels[0].clone();
    let entries: Vec<u32> = stim.draw_n(&any::<u32>(), 256);
    let random = Clut {
        entries: entries.try_into().unwrap(),
    };
    let mut drf = Drf::new(wl, hl, border);
    drf.config = Config::Index;
    for (clut, identity) in [(Clut::identity(), true), (random, false)] {
        let mut stub = TexramStub::new();
        stub.set_drf(0, drf).unwrap();
        stub.load(0, &level0).unwrap();
        stub.set_clut(clut.clone());
        let mut lum = TexramStub::new();
        lum.set_drf(0, Drf::new(wl, hl, border)).unwrap();
        lum.load(0, &level0).unwrap();
        let reqs = stim.draw_n(&requests(wl, hl), 3000);
        let mut chip = Texram802::new(TexramParams::default()).unwrap();
        chip.set_drf(0, drf).unwrap();
        chip.load(0, &level0).unwrap();
        chip.set_clut(clut.clone());
        let (out, _, _) = run_chip(chip, &reqs, (&[], &[]), None);
        for (k, &(u, v, lambda)) in reqs.iter().enumerate() {
            let q = req(u, v, lambda);
            let r = stub.access(q).unwrap();
            if identity {
                assert_eq!(r.rgba, [lum.access(q).unwrap().value; 4]);
            }
            for c in 0..4 {
                let comp = |t: u8| clut.rgba(t)[c];
                let (_, want) = reference.access_mapped(u, v, lambda, RefBorder::Mirror, &comp);
                assert_eq!(r.rgba[c], want, "request {k} component {c}");
            }
            assert_eq!(out[k].rgba, r.rgba, "chip, request {k}");
        }
    }
}

/// The CLUT 814's scope shows the eight table entries of an index access in the cycle it
/// finishes (the cycle before its result is out): the entries of the eight texels it read.
#[test]
fn the_clut_shows_the_entries_it_looked_up() {
    use hdl::kernel::Sim;
    use units::texram::clut_814::Clut;
    use units::texram::texram_802::{Texram802, TexramParams};
    use units::texram::Config;
    let mut stim = verif::seeded_stimulus("texram clut scope");
    let entries: Vec<u32> = stim.draw_n(&any::<u32>(), 256);
    let clut = Clut {
        entries: entries.try_into().unwrap(),
    };
    let mut drf = Drf::new(4, 4, Border::Wrap);
    drf.config = Config::Index;
    let mut chip = Texram802::new(TexramParams::default()).unwrap();
    chip.set_drf(0, drf).unwrap();
    chip.load(0, &stim.draw_n(&any::<u8>(), 256)).unwrap();
    chip.set_clut(clut.clone());
    let mut sim = Sim::new(chip).check_schedule(true);
    sim.reset(2);
    let (mut shown, mut results, mut sent) = (None, 0, 0);
    for cycle in 0..1000 {
        let d = &mut sim.dut;
        d.req_valid.set_bool(sent < 40);
        d.req_u.set_raw(i64::from(cycle * 97 % 4096));
        d.req_v.set_raw(i64::from(cycle * 61 % 4096));
        d.req_lambda.set_raw(i64::from(cycle * 37 % 1024));
        sim.eval();
        let d = &sim.dut;
        sent += i32::from(d.req_valid.is_high() && d.req_ready.is_high());
        if d.output.out_valid.q().is_high() {
            let texels = d.output.out_texels.q().bits().to_le_bytes();
            let want = texels.map(|t| u32::from_be_bytes(clut.rgba(t)));
            assert_eq!(shown, Some(want), "cycle {cycle}");
            results += 1;
        }
        let now = d.clut.entries.each_ref().map(|e| e.bits() as u32);
        shown = now.iter().any(|&e| e != 0).then_some(now);
        sim.tick();
    }
    assert_eq!(results, 40);
}

/// The colour configurations agree component by component: four component planes in the
/// quadrants of one chip (planar, four accesses a pixel), one plane per chip in lock-step
/// (one slot a pixel), and one luminance chip per plane. The literal layout of section 6
/// (R, G, B, alpha in a 2x2 cell) gives the same level-0 colours but asks a bank for two
/// words in most accesses (all but those of the smallest levels and clamped corners).
#[test]
fn colour_configurations_agree_component_by_component() {
    use hdl::kernel::Sim;
    use units::texram::lockstep::TexramLockstep;
    use units::texram::texram_802::TexramParams;
    use units::texram::Config;
    let mut stim = verif::seeded_stimulus("texram colour");
    let (pl, n) = (5u32, 32usize);
    let planes: [Vec<u8>; 4] = std::array::from_fn(|_| stim.draw_n(&any::<u8>(), n * n));
    let mut planar0 = vec![0u8; 4 * n * n];
    let mut literal0 = vec![0u8; 4 * n * n];
    for c in 0..4 {
        for y in 0..n {
            for x in 0..n {
                let t = planes[c][y * n + x];
                planar0[(y + n * (c >> 1)) * 2 * n + x + n * (c & 1)] = t;
                literal0[(2 * y + (c >> 1)) * 2 * n + 2 * x + (c & 1)] = t;
            }
        }
    }
    let stub = |config, level0: &[u8]| {
        let mut s = TexramStub::new();
        let mut d = Drf::new(pl + 1, pl + 1, Border::Clamp);
        d.config = config;
        s.set_drf(0, d).unwrap();
        s.load(0, level0).unwrap();
        s
    };
    let (mut planar, mut literal) = (
        stub(Config::Planar, &planar0),
        stub(Config::Literal, &literal0),
    );
    let mut lum: Vec<TexramStub> = planes
        .iter()
        .map(|p| {
            let mut s = TexramStub::new();
            s.set_drf(0, Drf::new(pl, pl, Border::Clamp)).unwrap();
            s.load(0, p).unwrap();
            s
        })
        .collect();
    let mut group = TexramLockstep::new(TexramParams::default()).unwrap();
    group
        .load(0, Drf::new(pl, pl, Border::Clamp), &planes)
        .unwrap();
    let reqs = stim.draw_n(&requests(pl, pl), 2000);
    // The lock-step chips, back to back.
    let mut sim = Sim::new(group).check_schedule(true);
    sim.reset(2);
    let (mut next, mut rgba) = (0, Vec::new());
    while rgba.len() < reqs.len() {
        assert!(sim.cycle() < 40_000, "stalled");
        sim.dut.port.valid.set_bool(next < reqs.len());
        if let Some(&(u, v, l)) = reqs.get(next) {
            sim.dut.port.u.set_raw(i64::from(u));
            sim.dut.port.v.set_raw(i64::from(v));
            sim.dut.port.lambda.set_raw(i64::from(l));
        }
        sim.eval();
        if sim.dut.port.valid.is_high() && sim.dut.ready.is_high() {
            next += 1;
        }
        if sim.dut.out_valid.is_high() {
            rgba.push((sim.dut.out_rgba.bits() as u32).to_be_bytes());
        }
        sim.tick();
    }
    assert!(!sim.dut.out_of_step.q().is_high());
    let mut level0_requests = 0;
    for (k, &(u, v, lambda)) in reqs.iter().enumerate() {
        let q = req(u, v, lambda);
        let p = planar.access(q).unwrap();
        let each: Vec<u8> = lum.iter_mut().map(|s| s.access(q).unwrap().value).collect();
        assert_eq!(p.rgba.to_vec(), each, "planar, request {k}");
        assert_eq!(rgba[k], p.rgba, "lock-step chips, request {k}");
        let l = literal.access(q).unwrap();
        if lambda <= 0 {
            // Level 0 only (f = 0): the literal layout holds the same colours there.
            assert_eq!(l.rgba, p.rgba, "literal, request {k}");
            level0_requests += 1;
        }
    }
    assert!(level0_requests > 50);
    assert_eq!(literal.counts().0, reqs.len() as u64);
    let conflicts = literal.conflicts();
    // All but the accesses to the 1-texel levels and clamped corners.
    assert!(
        conflicts > 2 * reqs.len() as u64,
        "{conflicts} conflicting component accesses"
    );
    assert_eq!(planar.conflicts(), 0);
    // Planar: four accesses a pixel; lock-step: one slot a pixel on each chip.
    assert!(planar.slots() >= 4 * reqs.len() as u64);
    assert!(literal.slots() > planar.slots());
}

/// Section 11-12: interlaced 768 x 576 video at 25 frames a second written into a map while
/// the rasterizer reads it "without slowing down": each video line's texels go through the
/// shift registers 826 into their banks' rows, a transfer per bank and line, at every level
/// the mipmap generator 816 makes; a transfer takes a slot (two when it opens a row) and
/// leaves its row open, so the rasterizer's next access there faults. Counted from the page
/// registers over one frame time of full-rate rasterizer accesses: under 1 % of the slots.
#[test]
fn video_at_25_frames_a_second_takes_under_one_percent_of_the_slots() {
    use units::texram::banks_810::locate;
    let drf = Drf::new(10, 10, Border::Wrap);
    // The transfers of one frame, in video order: level k's lines as the generator completes
    // them (one per 2^k input lines), two banks per line (x even and odd).
    let mut transfers = Vec::new();
    for y in 0..576u32 {
        // Interlaced: the even field, then the odd one.
        let line = if y < 288 { 2 * y } else { 2 * (y - 288) + 1 };
        for k in 0..=9u32 {
            if (line + 1) % (1 << k) != 0 || (line >> k) >= (576 >> k).max(1) {
                continue;
            }
            for x in 0..2 {
                transfers.push(locate(&drf, k, x, line >> k));
            }
        }
    }
    // One frame time (40 ms) of 30 ns slots, the rasterizer reading a span over and over.
    let frame_slots = 40_000_000 / 30;
    let run = |video: bool| {
        let mut chip = TexramStub::new();
        chip.set_drf(0, drf).unwrap();
        let every = frame_slots / transfers.len() as u64;
        let (mut k, mut t) = (0u64, 0);
        while chip.slots() < frame_slots {
            let q = TexramRequest {
                drf: 0,
                u: ((k % 400) as i32) << 8,
                v: 300 << 8,
                lambda: 64,
            };
            chip.access(q).unwrap();
            k += 1;
            if video && k % every == 0 && t < transfers.len() {
                let (bank, word) = transfers[t];
                chip.video_transfer(bank, word);
                t += 1;
            }
        }
        (k, chip.video_slots())
    };
    let (alone, _) = run(false);
    let (shared, video_slots) = run(true);
    let lost = (alone - shared) as f64 / alone as f64;
    eprintln!(
        "video: {} transfers a frame, {video_slots} slots; rasterizer accesses {alone} -> {shared} ({:.3} % fewer)",
        transfers.len(),
        100.0 * lost
    );
    assert!(
        lost < 0.01,
        "{:.3} % of the rasterizer's accesses lost",
        100.0 * lost
    );
    assert!(video_slots >= transfers.len() as u64);
}

/// The cycle-accurate chip in the planar and literal colour layouts: the stub's colours,
/// slots and conflicts, one component access after the other (a planar pixel every four
/// slots when no page faults).
#[test]
fn the_chip_reads_colour_layouts_like_the_stub() {
    use units::texram::texram_802::{Texram802, TexramParams};
    use units::texram::Config;
    let mut stim = verif::seeded_stimulus("texram colour chip");
    for (config, border) in [
        (Config::Planar, Border::Wrap),
        (Config::Literal, Border::Mirror),
    ] {
        let level0: Vec<u8> = stim.draw_n(&any::<u8>(), 64 * 64);
        let mut d = Drf::new(6, 6, border);
        d.config = config;
        let mut stub = TexramStub::new();
        stub.set_drf(0, d).unwrap();
        stub.load(0, &level0).unwrap();
        let mut chip = Texram802::new(TexramParams::default()).unwrap();
        chip.set_drf(0, d).unwrap();
        chip.load(0, &level0).unwrap();
        let reqs = stim.draw_n(&requests(5, 5), 1500);
        let (out, slots, conflicts) = run_chip(chip, &reqs, (&[], &[]), None);
        for (k, &(u, v, lambda)) in reqs.iter().enumerate() {
            let r = stub.access(req(u, v, lambda)).unwrap();
            assert_eq!(out[k].rgba, r.rgba, "{config:?} request {k}");
            if k > 0 {
                assert_eq!(
                    out[k].cycle - out[k - 1].cycle,
                    6 * u64::from(r.slots),
                    "{config:?} request {k}"
                );
            }
        }
        assert_eq!(slots, stub.slots(), "{config:?}");
        assert_eq!(conflicts, stub.conflicts(), "{config:?}");
    }
}

/// Eq. 5 in the output stage 820: `C_d = (I_d | k_T | 1) . T` on R, G, B (alpha the
/// texture's), in the chip as in the stub, for luminance and planar colour.
#[test]
fn the_output_stage_shades_with_illumination_or_a_constant() {
    use units::texram::output_820::{mul255, Modulate};
    use units::texram::texram_802::{Texram802, TexramParams};
    use units::texram::Config;
    let mut stim = verif::seeded_stimulus("texram eq5");
    let level0: Vec<u8> = stim.draw_n(&any::<u8>(), 32 * 32);
    for (config, m) in [
        (Config::Luminance, Modulate::Illumination),
        (Config::Planar, Modulate::Constant(100)),
        (Config::Planar, Modulate::Illumination),
    ] {
        let mut d = Drf::new(5, 5, Border::Clamp);
        (d.config, d.modulate) = (config, m);
        let mut stub = TexramStub::new();
        stub.set_drf(0, d).unwrap();
        stub.load(0, &level0).unwrap();
        let mut chip = Texram802::new(TexramParams::default()).unwrap();
        chip.set_drf(0, d).unwrap();
        chip.load(0, &level0).unwrap();
        let reqs = stim.draw_n(&requests(4, 4), 500);
        let illum: Vec<u32> = stim.draw_n(&any::<u32>(), reqs.len());
        let (out, _, _) = run_chip(chip, &reqs, (&[], &illum), None);
        let mut plain = TexramStub::new();
        plain
            .set_drf(
                0,
                Drf {
                    modulate: Modulate::One,
                    ..d
                },
            )
            .unwrap();
        plain.load(0, &level0).unwrap();
        for (k, &(u, v, lambda)) in reqs.iter().enumerate() {
            let q = req(u, v, lambda);
            let i = illum[k].to_be_bytes();
            let r = stub.access_lit(q, i).unwrap();
            assert_eq!(out[k].rgba, r.rgba, "{config:?} {m:?} request {k}");
            let t = plain.access(q).unwrap().rgba;
            for c in 0..3 {
                let f = match m {
                    Modulate::Illumination => i[c],
                    Modulate::Constant(x) => x,
                    Modulate::One => 255,
                };
                assert_eq!(r.rgba[c], mul255(f, t[c]));
            }
            assert_eq!(r.rgba[3], t[3], "alpha is the texture's");
        }
    }
}

/// The chip behind the `TexramAccess` interface answers like the stub, access by access
/// (what the footprint assembly and the map chain will call).
#[test]
fn the_chip_behind_the_interface_answers_like_the_stub() {
    use units::texram::texram_802::{Texram802, Texram802Access, TexramParams};
    use units::texram::Config;
    let mut stim = verif::seeded_stimulus("texram interface");
    let level0: Vec<u8> = stim.draw_n(&any::<u8>(), 64 * 64);
    for config in [Config::Luminance, Config::Planar] {
        let mut d = Drf::new(6, 6, Border::Mirror);
        d.config = config;
        let mut stub = TexramStub::new();
        stub.set_drf(0, d).unwrap();
        stub.load(0, &level0).unwrap();
        let mut chip = Texram802Access::new(Texram802::new(TexramParams::default()).unwrap());
        chip.set_drf(0, d).unwrap();
        chip.chip().load(0, &level0).unwrap();
        for (u, v, lambda) in stim.draw_n(&requests(6, 6), 300) {
            let q = req(u, v, lambda);
            let (a, b) = (chip.access(q).unwrap(), stub.access(q).unwrap());
            assert_eq!(
                (a.rgba, a.slots, a.faults),
                (b.rgba, b.slots, b.faults),
                "{q:?}"
            );
            assert_eq!(
                (a.fine, a.coarse, a.a, a.b, a.f),
                (b.fine, b.coarse, b.a, b.b, b.f)
            );
            if config == Config::Luminance {
                assert_eq!(a.texels, b.texels);
            }
        }
        assert_eq!(chip.slots(), stub.slots());
    }
}

/// The report's per-configuration figures: one slot a pixel in luminance and index modes
/// without faults along a scanline; the planar layout's four component accesses a pixel
/// switch between the quadrants' rows; the literal layout adds conflict rounds.
#[test]
fn slots_per_pixel_by_configuration() {
    let rows = tb::pictures::texram::layout_rows();
    for (name, slots, faults) in &rows {
        eprintln!("{name}: {slots:.3} slots a pixel, {faults:.2} slots lost a scanline");
    }
    let get = |n: &str| {
        rows.iter()
            .find(|r| r.0.starts_with(n))
            .map(|r| (r.1, r.2))
            .unwrap()
    };
    assert!(get("luminance").0 < 1.1);
    assert!(get("index").0 < 1.1);
    let (planar, literal) = (get("planar").0, get("literal").0);
    assert!((4.0..=8.0).contains(&planar), "{planar}");
    assert!(literal > planar, "{literal} {planar}");
}
