//! The `texrtl` program: the main job writes valid waveforms and a summary; bad input gets one
//! line, exit status 2 and no output.

use std::path::{Path, PathBuf};
use std::process::Command;
use waves::check::{check_gtkw, read_vcd};

fn texrtl(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .expect("runs")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("texrtl-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn regress_writes_valid_waveforms_and_summary() {
    let out = tmp("ok");
    let o = texrtl(&[
        "regress",
        "--out",
        out.to_str().unwrap(),
        "--seed",
        "0x1234",
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        stdout.contains("blend_adjust") && stdout.contains("PASS"),
        "{stdout}"
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("seed 0x0000000000001234"));
    let vcd = out.join("blend_adjust.vcd");
    let rb = read_vcd(&vcd).unwrap();
    assert_eq!(rb.vars["tb.ba.u_in"].width, Some(8));
    assert_eq!(rb.vars["tb.ba.u0"].width, Some(9));
    assert!(rb.vars.contains_key("tb.golden.u0_golden"));
    assert!(rb.vars.contains_key("tb.golden.mismatch"));
    // The golden value equals the DUT's companion real wherever the output is valid.
    let valid = &rb.vars["tb.ba.valid"];
    let mut checked = 0;
    for (t, v) in &valid.changes {
        if v.as_u64() == Some(1) {
            let d = rb.value_at("tb.ba.u0_real", *t).unwrap().as_f64().unwrap();
            let g = rb
                .value_at("tb.golden.u0_golden", *t)
                .unwrap()
                .as_f64()
                .unwrap();
            assert_eq!(d, g, "at {t}");
            checked += 1;
        }
    }
    assert!(checked > 0);
    assert!(check_gtkw(&vcd, &rb).unwrap() > 10);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["passed"], true);
    assert_eq!(s["testbenches"][0]["mismatches"], 0);
    assert!(no_partials(&out));
}

#[test]
fn trace_options_apply() {
    let out = tmp("filter");
    let o = texrtl(&[
        "--out",
        out.to_str().unwrap(),
        "--trace-filter",
        "tb.ba.u*",
        "--trace-window",
        "10..50",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rb = read_vcd(&out.join("blend_adjust.vcd")).unwrap();
    assert!(rb.vars.contains_key("tb.ba.u0"));
    assert!(!rb.vars.contains_key("tb.ba.v0"));
    assert_eq!(rb.times.first(), Some(&100_000));
    assert_eq!(rb.times.last(), Some(&500_000));
}

fn no_partials(dir: &Path) -> bool {
    std::fs::read_dir(dir).unwrap().all(|e| {
        !e.unwrap()
            .file_name()
            .to_string_lossy()
            .ends_with(".partial")
    })
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_output() {
    let out = tmp("bad");
    let file = std::env::temp_dir().join(format!("texrtl-cli-{}-file", std::process::id()));
    std::fs::write(&file, "x").unwrap();
    let o_s = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--bogus"], "--bogus"),
        (vec!["regress", "--out", o_s, "--seed", "zz"], "zz"),
        (vec!["--out", o_s, "--trace-window", "5..3"], "5..3"),
        (vec!["--out", o_s, "--period-ps", "3"], "period 3 ps"),
        (vec!["--out", file.to_str().unwrap()], "not a directory"),
        (vec!["frobnicate"], "frobnicate"),
    ];
    for (args, needle) in cases {
        let o = texrtl(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
        assert!(!out.exists(), "{args:?} created output");
    }
}
