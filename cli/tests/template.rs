//! `texrtl new`: the crate it writes builds outside texrtl's workspace and runs as a user runs
//! it: its own `cargo test` (the testbench, the kept vectors, the twin in Verilator and Icarus
//! and an injected one-bit bug found at the predicted cycle and port) and its main job (the
//! regression with report and co-simulation rows), sharded (co-simulations too) and merged
//! equal to one run.

use std::path::{Path, PathBuf};
use std::process::Command;

fn cargo(dir: &Path, target: &Path, args: &[&str]) -> (bool, String) {
    let o = Command::new(env!("CARGO"))
        .args(args)
        .current_dir(dir)
        .env("CARGO_TARGET_DIR", target)
        .env_remove("RUSTFLAGS")
        .output()
        .expect("cargo runs");
    let text =
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    (o.status.success(), text)
}

fn summary_without_times(path: &Path) -> serde_json::Value {
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    for r in v["testbenches"].as_array_mut().unwrap() {
        let r = r.as_object_mut().unwrap();
        r.remove("vcd");
        r.remove("seconds");
    }
    v
}

#[test]
#[ignore = "slow (a user crate built from scratch, about 2 minutes): cargo test -- --ignored, as .ci/run does"]
fn a_new_crate_builds_tests_and_regresses_outside_the_workspace() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let base = std::env::temp_dir().join(format!("texrtl-new-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&base).unwrap();
    let dir = base.join("rop_blend");
    let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(["new", "rop_blend", "--dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The workspace's resolved versions, so the crate builds with what texrtl was tested with.
    std::fs::copy(root.join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
    let target: PathBuf = root.join("target/template");
    let (ok, text) = cargo(&dir, &target, &["test"]);
    assert!(ok, "cargo test of the new crate:\n{text}");
    assert!(
        text.contains("the_twin_agrees_and_a_one_bit_bug_is_found_where_predicted ... ok"),
        "{text}"
    );
    let (ok, text) = cargo(
        &dir,
        &target,
        &["run", "--", "regress", "--out", "out/whole"],
    );
    assert!(ok, "the main job:\n{text}");
    assert!(
        text.contains("rop_blend ") && text.contains("PASS"),
        "{text}"
    );
    let mut installed = Vec::new();
    for sim in ["verilator", "icarus"] {
        let here = Command::new(if sim == "icarus" { "iverilog" } else { sim })
            .arg("-V")
            .output()
            .is_ok();
        assert_eq!(
            text.contains(&format!("cosim/rop_blend/{sim}")),
            here,
            "{text}"
        );
        installed.extend(here.then_some(["--sim", sim]));
    }
    assert!(dir.join("out/whole/report.md").is_file());
    assert!(dir
        .join("out/whole/rop_blend_error_histogram.svg")
        .is_file());
    // Two shards, each with its share of the co-simulation jobs, merge to the whole run.
    let no_cosim = ["--no-cosim"];
    let sims: Vec<&str> = match installed.is_empty() {
        true => no_cosim.to_vec(),
        false => installed.concat(),
    };
    for (i, out) in [(1, "out/s1"), (2, "out/s2")] {
        let shard = format!("{i}/2");
        let args = [
            &["run", "--", "regress", "--shard", &shard, "--out", out],
            &sims[..],
        ];
        let (ok, text) = cargo(&dir, &target, &args.concat());
        assert!(ok, "{text}");
    }
    let merge = [
        "run",
        "--",
        "merge",
        "--out",
        "out/merged.json",
        "out/s1/summary.json",
        "out/s2/summary.json",
    ];
    let (ok, text) = cargo(&dir, &target, &merge);
    assert!(ok, "{text}");
    let whole = summary_without_times(&dir.join("out/whole/summary.json"));
    let merged = summary_without_times(&dir.join("out/merged.json"));
    let rows = |s: &serde_json::Value| s["testbenches"].clone();
    assert_eq!(rows(&merged), rows(&whole));
    let (ok, text) = cargo(&dir, &target, &["run", "--", "vectors", "--check"]);
    assert!(ok && text.contains("every row equal"), "{text}");
    broken_twin_is_explained(&dir, &target);
    let _ = std::fs::remove_dir_all(&base);
}

/// The twin broken (the upper rail one LSB low): the regression's co-simulation row fails
/// and names the command that runs it again alone; that command shows the RTL's internals.
fn broken_twin_is_explained(dir: &Path, target: &Path) {
    if Command::new("iverilog").arg("-V").output().is_err() {
        return;
    }
    let v = dir.join("rtl/rop_blend.v");
    let good = std::fs::read_to_string(&v).unwrap();
    let bad = good.replace("? 10'sd511 :", "? 10'sd510 :");
    assert_ne!(bad, good, "the template's rail moved");
    std::fs::write(&v, bad).unwrap();
    let (ok, text) = cargo(dir, target, &["run", "--", "--no-vcd", "--out", "out/bug"]);
    assert!(!ok, "{text}");
    let said = "cosim/rop_blend/icarus: again alone, the RTL's internals around the difference in its waveform: rop_blend ";
    let again = text.lines().find_map(|l| l.trim().strip_prefix(said));
    let again: Vec<&str> = again.expect(&text).split(' ').collect();
    let (ok, text) = cargo(dir, target, &[&["run", "--"], &again[..]].concat());
    assert!(!ok && text.contains("under tb.rtl_internals"), "{text}");
    std::fs::write(&v, good).unwrap();
}
