//! The twin against the model in every simulator installed, and a one-bit bug in the Verilog
//! found at the cycle and port the model predicts. Without a simulator the test says so and
//! passes, unless `TEXRTL_REQUIRE_COSIM=1`.
use std::path::PathBuf;
use verif::cosim::{run, CosimUnit, Simulator, RESET_CYCLES};

fn simulators() -> Vec<Simulator> {
    let all = [Simulator::Verilator, Simulator::Icarus];
    let there: Vec<Simulator> = all.into_iter().filter(|s| s.check_installed().is_ok()).collect();
    let required = std::env::var("TEXRTL_REQUIRE_COSIM").is_ok_and(|v| v == "1");
    assert!(!required || there.len() == all.len(), "TEXRTL_REQUIRE_COSIM=1 and a simulator is missing");
    if there.is_empty() {
        eprintln!("no simulator installed: co-simulation not run");
    }
    there
}

fn signed(bits: u64, width: u32) -> i64 {
    ((bits << (64 - width)) as i64) >> (64 - width)
}

/// The first cycle the upper rail saturates (acc + x > 511 with valid_in): the acc port
/// shows the saturated value one cycle later.
fn first_high_saturation(twin: &dyn CosimUnit, stim: &[Vec<u64>]) -> usize {
    let mut m = twin.model().unwrap();
    let saturates = |c: usize, out: &[u64]| {
        c >= RESET_CYCLES && stim[c][0] == 1 && signed(out[1], 10) + signed(stim[c][1], 8) > 511
    };
    (0..stim.len()).find(|&c| saturates(c, &m.cycle(c < RESET_CYCLES, &stim[c]))).expect("never saturates")
        + 1
}

#[test]
fn the_twin_agrees_and_a_one_bit_bug_is_found_where_predicted() {
    let twin = sat_acc::twin();
    let (seed, n) = (verif::Seed(7), 5000);
    let want = first_high_saturation(&twin, &twin.stimulus(seed, n));
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let good = std::fs::read_to_string(root.join("rtl/sat_acc.v")).unwrap();
    // 511 is 0x1ff: its bit 0 cleared, the upper rail one LSB low.
    let bad = good.replace("? 10'sd511 :", "? 10'sd510 :");
    assert_ne!(bad, good, "the bug is injected");
    for sim in simulators() {
        let dir = std::env::temp_dir().join(format!("sat-acc-cosim-{}-{}", std::process::id(), sim.name()));
        let r = run(&twin, sim, &[], n, seed, &dir).unwrap();
        assert!(r.mismatch.is_none(), "{}: {}", sim.name(), r.mismatch.unwrap());
        std::fs::create_dir_all(&dir).unwrap();
        let mutant = dir.join("sat_acc_bug.v");
        std::fs::write(&mutant, &bad).unwrap();
        let r = run(&twin, sim, &[mutant], n, seed, &dir.join("bug")).unwrap();
        let d = r.mismatch.expect("the bug is found");
        assert_eq!(
            (d.cycle, d.port.as_str(), d.model, d.rtl),
            (want, "acc", 511, Some(510)),
            "{}",
            sim.name()
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn the_testbench_passes_and_the_vectors_are_kept() {
    let p = sat_acc::project();
    let dir = std::env::temp_dir().join(format!("sat-acc-tb-{}", std::process::id()));
    let opts = verif::RunOptions { check_schedule: true, ..verif::RunOptions::with_waves(&dir) };
    let r = verif::run_testbench(&sat_acc::tb::SatAccTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.mismatch_log, r.failures);
    let vcd = dir.join("sat_acc.vcd");
    waves::check::check_gtkw(&vcd, &waves::check::read_vcd(&vcd).unwrap()).unwrap();
    let diffs = verif::vectors::check(p.kept_vectors().unwrap(), p.vectors()).unwrap();
    assert!(diffs.is_empty(), "{diffs:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
