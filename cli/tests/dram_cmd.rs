//! The `texrtl` commands of the dram path, run as a user runs them.

mod common;

#[test]
fn dram_command() {
    let d = common::dir("dram", "command");
    let t = d.join("t.csv");
    std::fs::write(&t, "addr\n0\n1\n2\n600\n601\n3\n").unwrap();
    let vcd = d.join("d.vcd");
    let exe = env!("CARGO_BIN_EXE_texrtl");
    let o = std::process::Command::new(exe)
        .args([
            "dram",
            "--trace",
            t.to_str().unwrap(),
            "--vcd",
            vcd.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["reads"], 6);
    assert_eq!(j["page_faults"], 3);
    assert_eq!(j["page_hits"], 3);
    assert_eq!(j["ns"], 6 * 30 + 3 * 30);
    let rb = waves::check::read_vcd(&vcd).unwrap();
    for v in [
        "tb.control_607.dram_604.ras_n",
        "tb.control_607.dram_604.cas_n",
        "tb.control_607.dram_604.page_row",
        "tb.control_607.state",
    ] {
        assert!(rb.vars.contains_key(v), "{v}");
    }
    waves::check::check_gtkw(&vcd, &rb).unwrap();
    let o = std::process::Command::new(exe)
        .args(["dram", "--trace", t.to_str().unwrap(), "--t-fault-ns", "60"])
        .output()
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["ns"], 6 * 30 + 3 * 60);
    // Bad input: one line, exit 2, no output file.
    for (body, args, needle) in [
        ("addr\n999999999\n", vec![], "beyond"),
        ("address\n1\n", vec![], "header"),
        ("addr\n1x\n", vec![], "not a word address"),
        ("addr\n1\n", vec!["--t-fault-ns", "7"], "multiple"),
        ("addr\n1\n", vec!["--page-words", "3"], "page-words"),
        // Once, a fault time too long for the timing registers blamed --page-words.
        (
            "addr\n1\n",
            vec!["--t-fault-ns", "10010"],
            "--t-fault-ns 10010: t_rp",
        ),
    ] {
        std::fs::write(&t, body).unwrap();
        let out = d.join("bad.vcd");
        let mut a = vec![
            "dram",
            "--trace",
            t.to_str().unwrap(),
            "--vcd",
            out.to_str().unwrap(),
        ];
        a.extend(args);
        let o = std::process::Command::new(exe).args(&a).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{needle}: {err}");
        assert!(
            err.contains(needle) && err.trim_end().lines().count() == 1,
            "{needle}: {err}"
        );
        assert!(!out.exists());
    }
}
