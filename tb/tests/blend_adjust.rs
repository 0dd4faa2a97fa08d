//! The blend-adjust testbench itself: it passes on the model, it fails on a one-bit error,
//! and random single evaluations match the golden model exactly.

use hdl::kernel::Sim;
use proptest::prelude::*;
use tb::blend_adjust::{golden, BaIn, BlendAdjustTb};
use units::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
use verif::{run_testbench, seeded_runner, RunOptions, Seed, TbResult};

/// Runs the testbench through the framework, as `texrtl regress` does.
fn run_tb(tb: BlendAdjustTb, count: usize, seed: Seed, check_schedule: bool) -> TbResult {
    let opts = RunOptions {
        seed,
        count: Some(count),
        check_schedule,
        ..RunOptions::default()
    };
    run_testbench(&tb, &opts, &mut |_| {}).unwrap()
}

#[test]
fn every_input_of_every_width_matches_golden_exactly() {
    let r = run_tb(BlendAdjustTb::default(), 2000, Seed(1), true);
    assert!(r.passed, "{:?} {:?}", r.mismatch_log, r.failures);
    // 2 * 2^F sweep transactions per width plus the random ones.
    let sweep: u64 = (4..=16).map(|f| 2u64 << f).sum();
    assert_eq!(r.transactions, sweep + 13 * 2000);
    assert_eq!(r.stats.count, 4 * r.transactions);
    assert_eq!(r.stats.max_abs_lsb, 0.0);
    assert_eq!(r.stats.exact, r.stats.count);
    assert_eq!(r.coverage_percent, 100.0);
    assert_eq!(r.latency, Some(1));
}

#[test]
fn combinational_variant_has_latency_zero() {
    let tb = BlendAdjustTb {
        registered: false,
        widths: 4..=10,
        ..BlendAdjustTb::default()
    };
    let r = run_tb(tb, 300, Seed(1), false);
    assert_eq!(r.latency, Some(0));
    assert_eq!(r.mismatches, 0);
    // Widths 11..=16 were not run: their coverage bins must be reported as holes.
    assert!(!r.passed);
    assert!(r.unhit.iter().any(|u| u.contains("F[12]")), "{:?}", r.unhit);
}

#[test]
fn a_one_bit_error_is_caught_with_its_cycle() {
    let tb = BlendAdjustTb {
        widths: 4..=4,
        fault: Some(5),
        ..BlendAdjustTb::default()
    };
    let r = run_tb(tb, 0, Seed(1), false);
    assert!(!r.passed);
    assert_eq!(r.mismatches, 1);
    // Reset takes cycles 0-1; transaction 5 enters in cycle 7 and leaves in cycle 8.
    assert!(
        r.mismatch_log[0].contains("Some(8)"),
        "{}",
        r.mismatch_log[0]
    );
    assert!(r.mismatch_log[0].contains("u1="), "{}", r.mismatch_log[0]);
    assert!((r.stats.max_abs_lsb - 1.0).abs() < 1e-12);
}

#[test]
fn random_single_evaluations_match_golden() {
    let mut runner = seeded_runner("blend_adjust random", 4000);
    let s = (4u32..=16, any::<u32>(), any::<u32>(), any::<bool>());
    runner
        .run(&s, |(f, u, v, bypass)| {
            let p = BlendAdjustParams {
                frac_bits: f,
                registered: false,
            };
            let mask = (1u32 << f) - 1;
            let t = BaIn {
                u: u & mask,
                v: v & mask,
                bypass,
            };
            let mut sim = Sim::new(BlendAdjust::new("blend_adjust_153", p).unwrap());
            sim.dut.i.u_in.set_bits(u64::from(t.u));
            sim.dut.i.v_in.set_bits(u64::from(t.v));
            sim.dut.i.bypass.set_bool(bypass);
            sim.eval();
            let g = golden(&t, f);
            let o = &sim.dut.o;
            let got = [&o.u0, &o.u1, &o.v0, &o.v1].map(|s| s.fx().to_f64());
            prop_assert_eq!(got, g);
            Ok(())
        })
        .unwrap();
}

#[test]
fn seeds_replay() {
    let tb = || BlendAdjustTb {
        widths: 5..=5,
        ..BlendAdjustTb::default()
    };
    let a = run_tb(tb(), 2000, Seed(99), false);
    let b = run_tb(tb(), 2000, Seed(99), false);
    assert_eq!(a.cycles, b.cycles, "same seed, same idle pattern");
    assert_eq!(a.stats.histogram, b.stats.histogram);
}
