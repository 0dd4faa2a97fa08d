//! Co-simulation of the Verilog twins against their models, in Verilator and Icarus, and
//! proof that the harness fails: one-bit bugs injected into a twin are reported with the
//! right cycle and port. Without a simulator the tests say so in one line and pass, unless
//! `TEXRTL_REQUIRE_COSIM=1` (which `.ci/run` sets).

use hdl::bump::blend_adjust_153::BlendAdjustParams;
use std::path::PathBuf;
use tb::cosim::{run, BlendAdjustCosim, CosimUnit, Simulator};
use verif::Seed;

/// Whether `sim` can run; without it, fails only when co-simulation is required.
fn available(sim: Simulator) -> bool {
    match sim.check_installed() {
        Ok(()) => true,
        Err(e) if std::env::var("TEXRTL_REQUIRE_COSIM").as_deref() == Ok("1") => {
            panic!("TEXRTL_REQUIRE_COSIM=1 but {e}")
        }
        Err(e) => {
            println!("co-simulation skipped: {e}");
            false
        }
    }
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("texrtl-cosim-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn params(frac_bits: u32, registered: bool) -> BlendAdjustParams {
    BlendAdjustParams {
        frac_bits,
        registered,
    }
}

#[test]
fn blend_adjust_twin_matches_on_every_cycle_in_verilator() {
    if !available(Simulator::Verilator) {
        return;
    }
    for (f, reg) in [(8, true), (4, false), (16, true)] {
        let u = BlendAdjustCosim(params(f, reg));
        let d = dir(&format!("ba-v-{f}-{reg}"));
        let r = run(&u, Simulator::Verilator, &[], 100_000, Seed(f.into()), &d).unwrap();
        assert_eq!(r.cycles, 100_000);
        assert!(
            r.mismatch.is_none(),
            "F={f} registered={reg}: {}",
            r.mismatch.unwrap()
        );
        let rb = waves::check::read_vcd(&r.vcd).unwrap();
        waves::check::check_gtkw(&r.vcd, &rb).unwrap();
        assert!(rb.vars.contains_key("tb.rtl.u0") && rb.vars.contains_key("tb.model.u0"));
        let _ = std::fs::remove_dir_all(&d);
    }
}

#[test]
fn blend_adjust_twin_matches_on_every_cycle_in_icarus() {
    if !available(Simulator::Icarus) {
        return;
    }
    let u = BlendAdjustCosim(params(8, true));
    let d = dir("ba-i");
    let r = run(&u, Simulator::Icarus, &[], 20_000, Seed(3), &d).unwrap();
    assert!(r.mismatch.is_none(), "{}", r.mismatch.unwrap());
    let _ = std::fs::remove_dir_all(&d);
}

/// The twin with `from` replaced by `to` (a one-bit bug), as a user's `--rtl` file.
fn mutant(d: &std::path::Path, from: &str, to: &str) -> PathBuf {
    let src =
        std::fs::read_to_string(tb::cosim::rtl_dir().join("bump/blend_adjust_153.v")).unwrap();
    assert!(src.contains(from), "the twin has {from}");
    std::fs::create_dir_all(d).unwrap();
    let p = d.join("mutant.v");
    std::fs::write(&p, src.replacen(from, to, 1)).unwrap();
    p
}

/// The first cycle and port where the model with `alt` parameters differs from the model with
/// `base` on the harness's stimulus (what a bug equivalent to that change must report).
fn first_difference(base: BlendAdjustParams, alt: BlendAdjustParams, n: usize) -> (usize, String) {
    let (a, b) = (BlendAdjustCosim(base), BlendAdjustCosim(alt));
    let stim = a.stimulus(Seed(9), n);
    let (mut ma, mut mb) = (a.model().unwrap(), b.model().unwrap());
    let (_, outs) = ma.ports();
    for (c, s) in stim.iter().enumerate() {
        let rst = c < tb::cosim::RESET_CYCLES;
        let (x, y) = (ma.cycle(rst, s), mb.cycle(rst, s));
        if c < tb::cosim::FIRST_COMPARED {
            continue;
        }
        if let Some(k) = (0..x.len()).find(|&k| x[k] != y[k]) {
            return (c, outs[k].name.clone());
        }
    }
    panic!("no difference in {n} cycles")
}

#[test]
fn injected_bugs_are_caught_with_their_cycle_and_port() {
    let sims: Vec<Simulator> = [Simulator::Verilator, Simulator::Icarus]
        .into_iter()
        .filter(|s| available(*s))
        .collect();
    for sim in sims {
        let n = 2_000;
        // A constant changed: u0 = {1'b0, u} instead of {1'b1, u} (the 1/2 of para. 0059 lost).
        let d = dir(&format!("bug-const-{}", sim.name()));
        let m = mutant(
            &d,
            "u0_c = bypass ? {u_in, 1'b0} : {1'b1, u_in}",
            "u0_c = bypass ? {u_in, 1'b0} : {1'b0, u_in}",
        );
        let u = BlendAdjustCosim(params(8, true));
        let r = run(&u, sim, &[m], n, Seed(9), &d).unwrap();
        let diff = r.mismatch.expect("the bug is caught");
        // The first cycle after reset whose previous input was not a bypass shows it in u0.
        let stim = u.stimulus(Seed(9), n);
        let want = (tb::cosim::RESET_CYCLES..n)
            .find(|&c| stim[c - 1][1] == 0 && c > tb::cosim::RESET_CYCLES)
            .unwrap();
        assert_eq!(
            (diff.cycle, diff.port.as_str()),
            (want, "u0"),
            "{}: {diff}",
            sim.name()
        );
        // The register stage removed: the twin answers in the same cycle.
        let d = dir(&format!("bug-reg-{}", sim.name()));
        let m = mutant(
            &d,
            "if (REGISTERED != 0) begin : g_reg",
            "if (0) begin : g_reg",
        );
        let r = run(&u, sim, &[m], n, Seed(9), &d).unwrap();
        let diff = r.mismatch.expect("the bug is caught");
        let want = first_difference(params(8, true), params(8, false), n);
        assert_eq!(
            (diff.cycle, diff.port.clone()),
            want,
            "{}: {diff}",
            sim.name()
        );
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// `verilator --lint-only -Wall` is clean on every twin, in every configuration it has.
#[test]
fn every_twin_is_lint_clean() {
    if !available(Simulator::Verilator) {
        return;
    }
    let twins: Vec<(&str, Vec<&str>)> = vec![(
        "bump/blend_adjust_153.v",
        vec![
            "-GREGISTERED=1",
            "-GREGISTERED=0",
            "-GFRAC_BITS=4",
            "-GFRAC_BITS=16",
        ],
    )];
    for (f, configs) in twins {
        for g in configs {
            let o = std::process::Command::new("verilator")
                .args(["--lint-only", "-Wall", g])
                .arg(tb::cosim::rtl_dir().join(f))
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(
                o.status.success() && err.trim().is_empty(),
                "{f} {g}: {err}"
            );
        }
    }
}
