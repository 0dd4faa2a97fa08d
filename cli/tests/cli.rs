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

mod common;

fn tmp(name: &str) -> common::TestDir {
    common::fresh("cli", name)
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
    let vcd = out.join("blend_adjust_153.vcd");
    let rb = read_vcd(&vcd).unwrap();
    assert_eq!(rb.vars["tb.blend_adjust_153.u_in"].width, Some(8));
    assert_eq!(rb.vars["tb.blend_adjust_153.u0"].width, Some(9));
    assert!(rb.vars.contains_key("tb.golden.u0_golden"));
    assert!(rb.vars.contains_key("tb.golden.mismatch"));
    check_golden_beside_companion(&rb);
    assert!(check_gtkw(&vcd, &rb).unwrap() > 10);
    check_summary_report_and_pictures(&out);
    // With Verilator installed, every twin is co-simulated as a row of the table.
    if std::process::Command::new("verilator")
        .arg("-V")
        .output()
        .is_ok()
    {
        for u in tb::project::project().twins() {
            let row = format!("cosim/{}/verilator", u.name());
            assert!(stdout.contains(&row), "{stdout}");
        }
    }
    check_state_names(&out);
    // A whole regression's outputs are half a gigabyte: not left in the temporary folder.
    let _ = std::fs::remove_dir_all(&out);
}

/// The golden value equals the DUT's companion real wherever the output is valid.
fn check_golden_beside_companion(rb: &waves::check::Readback) {
    let valid = &rb.vars["tb.blend_adjust_153.valid"];
    let mut checked = 0;
    for (t, v) in &valid.changes {
        if v.as_u64() == Some(1) {
            let d = rb
                .value_at("tb.blend_adjust_153.u0_real", *t)
                .unwrap()
                .as_f64()
                .unwrap();
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
}

/// `summary.json`, `report.md` with its links, the pictures and the other waveforms.
fn check_summary_report_and_pictures(out: &Path) {
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["passed"], true);
    assert_eq!(s["testbenches"][0]["mismatches"], 0);
    assert!(no_partials(out));
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    for link in [
        "normals_render.png",
        "mipmap_levels.png",
        "blend_adjust_153.gtkw",
        "| normal_pipeline_fig7 |",
        "| mipmap_gen_816 |",
    ] {
        assert!(report.contains(link), "report lacks {link}");
    }
    for png in ["normals_render.png", "mipmap_levels.png"] {
        assert!(std::fs::read(out.join(png))
            .unwrap()
            .starts_with(b"\x89PNG"));
    }
    for svg in [
        "normal_pipeline_fig7_error_histogram.svg",
        "mipmap_gen_816_error_histogram.svg",
    ] {
        let text = std::fs::read_to_string(out.join(svg)).unwrap();
        assert!(
            text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
            "{svg}"
        );
        assert!(report.contains(svg), "report lacks {svg}");
    }
    for vcd in ["normal_pipeline_fig7.vcd", "mipmap_gen_816.vcd"] {
        let p = out.join(vcd);
        check_gtkw(&p, &read_vcd(&p).unwrap()).unwrap();
    }
}

/// FSM states by name: a translate filter file per state register, referenced from the
/// `.gtkw` by its file name just before the trace it names.
fn check_state_names(out: &Path) {
    let filter = out.join("texture_unit_602.fill_engine_607.state.txt");
    let names = std::fs::read_to_string(&filter).unwrap();
    assert!(names.contains("0 IDLE\n1 FETCH\n2 DECODE\n"), "{names}");
    let g = std::fs::read_to_string(out.join("texture_unit_602.gtkw")).unwrap();
    // Beside the save file, by file name: a copied folder keeps its state names.
    let line = " texture_unit_602.fill_engine_607.state.txt\ntb.texture_unit_602.fill_engine_607.state[1:0]";
    assert!(
        g.contains(line),
        "the .gtkw does not name the state filter: {g}"
    );
    let p = out.join("texture_unit_602.vcd");
    check_gtkw(&p, &read_vcd(&p).unwrap()).unwrap();
}

#[test]
fn trace_options_apply() {
    let out = tmp("filter");
    let o = texrtl(&[
        "--fst",
        "--no-cosim",
        "--out",
        out.to_str().unwrap(),
        "--trace-filter",
        "tb.blend_adjust_153.u*",
        "--trace-window",
        "10..50",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rb = read_vcd(&out.join("blend_adjust_153.vcd")).unwrap();
    assert!(rb.vars.contains_key("tb.blend_adjust_153.u0"));
    assert!(!rb.vars.contains_key("tb.blend_adjust_153.v0"));
    assert_eq!(rb.times.first(), Some(&100_000));
    assert_eq!(rb.times.last(), Some(&500_000));
    // The FST is written while simulating: the design's variables, without the VCD's `real`
    // companions and probes.
    let fst = waves::check::read_fst(&out.join("blend_adjust_153.fst")).unwrap();
    let mut design = rb;
    design
        .vars
        .retain(|n, v| v.width.is_some() && !n.starts_with("tb.golden"));
    assert!(design.vars.contains_key("tb.blend_adjust_153.u0"));
    waves::fst::same_values(&design, &fst).unwrap();
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
    let file_dir = common::dir("cli", "file");
    let file = file_dir.join("file");
    std::fs::write(&file, "x").unwrap();
    let o_s = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--bogus"], "--bogus"),
        (vec!["regress", "--out", o_s, "--seed", "zz"], "zz"),
        (vec!["--out", o_s, "--trace-window", "5..3"], "5..3"),
        (vec!["--out", o_s, "--period-ps", "3"], "period 3 ps"),
        (vec!["--out", file.to_str().unwrap()], "not a directory"),
        (vec!["frobnicate"], "frobnicate"),
        (vec!["bench", "--out", o_s, "--rounds", "0"], "--rounds 0"),
        (vec!["bench", "--out", o_s, "--rounds", "21"], "--rounds 21"),
        (
            vec!["bench", "--out", o_s, "--traced-cycles", "0"],
            "--traced-cycles 0",
        ),
        (
            vec!["bench", "--out", o_s, "--stimulus-rows", "0"],
            "--stimulus-rows 0: 1..=100000000",
        ),
        (vec!["bench", "--out", o_s, "--unit", "nope"], "nope"),
        (
            vec!["bench", "--out", o_s, "--instructions", "10000001"],
            "--instructions 10000001",
        ),
        (vec!["bench", "--out", o_s, "--instructions", "x"], "'x'"),
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

fn write(dir: &Path, name: &str, data: &[u8]) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, data).unwrap();
    p
}

fn normals_args<'a>(h: &'a Path, c: &'a Path, out: &'a Path, vcd: &'a Path) -> Vec<&'a str> {
    let s = |p: &'a Path| p.to_str().unwrap();
    vec![
        "normals",
        "--height",
        s(h),
        "--coords",
        s(c),
        "--out",
        s(out),
        "--vcd",
        s(vcd),
    ]
}

#[test]
fn normals_render_and_sweep_commands() {
    let d = tmp("normals");
    let mut pgm = b"P5\n4 3\n255\n".to_vec();
    pgm.extend((0..12u8).map(|k| k * 20));
    let h = write(&d, "h.pgm", &pgm);
    let c = write(&d, "c.csv", b"u,v\n0,0\n1.5,2.25\n-0.5,0.125\n");
    let out = d.join("n.csv");
    let vcd = d.join("n.vcd");
    let o = texrtl(&normals_args(&h, &c, &out, &vcd));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(&out).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "u,v,nx,ny,nz");
    assert_eq!(rows.len(), 4);
    assert!(rows[2].starts_with("1.5,2.25,"), "{csv}");
    // Components are exact decimals of sQ2.16 values: at most 16 fraction digits, |n| ~ 1.
    for r in &rows[1..] {
        let n: Vec<f64> = r.split(',').skip(2).map(|x| x.parse().unwrap()).collect();
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-4, "{r}");
    }
    let rb = read_vcd(&vcd).unwrap();
    assert!(rb
        .vars
        .contains_key("tb.normal_pipeline_fig7.normal_156.nx"));
    assert!(rb.vars.contains_key("tb.golden.nx_golden"));
    check_gtkw(&vcd, &rb).unwrap();

    let png = d.join("r.png");
    let o = texrtl(&[
        "render",
        "--height",
        h.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--zoom",
        "2",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));

    let o = texrtl(&["sweep", "normals", "--samples", "50"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("blend\\table"));
}

/// The normals command's bad inputs: height map, coordinates, extra options, and what the
/// one-line refusal must say.
fn normals_bad_cases(d: &Path) -> Vec<(PathBuf, PathBuf, Vec<&'static str>, &'static str)> {
    let good_h = write(d, "h.pgm", b"P2\n2 2\n255\n1 2 3 4\n");
    let good_c = write(d, "c.csv", b"u,v\n0.5,0.5\n");
    vec![
        // Once, a plain header declaring 65535x65535 aborted on its allocation.
        (
            write(d, "huge.pgm", b"P2\n65535 65535\n255\n1 2 3\n"),
            good_c.clone(),
            vec![],
            "hold at most",
        ),
        // Once, --scale out of range blamed the coordinates file in 309 digits.
        (
            good_h.clone(),
            good_c.clone(),
            vec!["--scale", "1e308"],
            "--scale 1e308 outside",
        ),
        (
            write(d, "a.pgm", b"P6\n2 2\n255\n"),
            good_c.clone(),
            vec![],
            "not a PGM",
        ),
        (
            write(d, "b.pgm", b"P2\n1 1\n255\n7\n"),
            good_c.clone(),
            vec![],
            "1x1",
        ),
        (
            good_h.clone(),
            write(d, "nan.csv", b"u,v\nNaN,0\n"),
            vec![],
            "not a finite number",
        ),
        (
            good_h.clone(),
            write(d, "bad.csv", b"u,v\n1;2\n"),
            vec![],
            "1 fields, the header has 2",
        ),
        (
            good_h.clone(),
            write(d, "hdr.csv", b"x,y\n1,2\n"),
            vec![],
            "not 'u,v'",
        ),
        (
            good_h.clone(),
            write(d, "far.csv", b"u,v\n1e9,0\n"),
            vec![],
            "outside",
        ),
        (
            good_h.clone(),
            good_c.clone(),
            vec!["--filter", "cubic"],
            "cubic",
        ),
        (
            good_h.clone(),
            good_c.clone(),
            vec!["--blend-bits", "3"],
            "--blend-bits 3",
        ),
        (
            good_h.clone(),
            good_c.clone(),
            vec!["--scale", "inf"],
            "inf",
        ),
        (good_h.clone(), good_c.clone(), vec!["--bogus"], "--bogus"),
    ]
}

#[test]
fn normals_bad_input_is_one_line_exit_2_and_no_output() {
    let d = tmp("normals-bad");
    for (h, c, extra, needle) in normals_bad_cases(&d) {
        let out = d.join("out.csv");
        let vcd = d.join("out.vcd");
        let mut args = normals_args(&h, &c, &out, &vcd);
        args.extend(extra);
        let o = texrtl(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{needle}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{needle}: {err}");
        assert!(err.contains(needle), "{needle}: {err}");
        assert!(
            !out.exists() && !vcd.exists() && !d.join("out.gtkw").exists(),
            "{needle}: output written"
        );
        assert!(no_partials(&d));
    }
    let o = texrtl(&[
        "render",
        "--height",
        d.join("h.pgm").to_str().unwrap(),
        "--out",
        d.join("r.png").to_str().unwrap(),
        "--light",
        "0,0,0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!d.join("r.png").exists());
}

#[test]
fn shards_merge_into_the_whole_run() {
    let d = tmp("shards");
    let run = |args: &[&str], out: &Path| {
        let mut a = vec![
            "regress",
            "--no-vcd",
            "--no-cosim",
            "--seeds",
            "2",
            "--out",
            out.to_str().unwrap(),
        ];
        a.extend(args);
        let o = texrtl(&a);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let s: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        s
    };
    let full = run(&[], &d.join("full"));
    let s1 = d.join("s1");
    let s2 = d.join("s2");
    run(&["--shard", "1/2"], &s1);
    run(&["--shard", "2/2"], &s2);
    let merged = d.join("merged.json");
    let o = texrtl(&[
        "merge",
        "--out",
        merged.to_str().unwrap(),
        s1.join("summary.json").to_str().unwrap(),
        s2.join("summary.json").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(&merged).unwrap()).unwrap();
    assert_eq!(m["passed"], true);
    assert_eq!(
        full["testbenches"].as_array().map(Vec::len),
        m["testbenches"].as_array().map(Vec::len)
    );
    // The merge is the unsharded run's summary, byte for byte.
    assert!(
        std::fs::read(&merged).unwrap() == std::fs::read(d.join("full/summary.json")).unwrap(),
        "the merged summary differs from the unsharded run's"
    );
    // One shard alone is not a whole run; garbage is refused.
    let o = texrtl(&[
        "merge",
        "--out",
        merged.to_str().unwrap(),
        s1.join("summary.json").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("shard 2/2 is missing"));
    let junk = d.join("junk.json");
    std::fs::write(&junk, "{").unwrap();
    let o = texrtl(&[
        "merge",
        "--out",
        merged.to_str().unwrap(),
        junk.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&o.stderr)
            .trim_end()
            .lines()
            .count(),
        1
    );
    assert_eq!(
        texrtl(&["regress", "--shard", "3/2"]).status.code(),
        Some(2)
    );
}

/// The framework applies `--count` to every testbench, `--only` selects, `--list` lists, and
/// an unknown testbench name is refused.
#[test]
fn count_only_and_list_apply_to_every_testbench() {
    let d = tmp("count");
    let summary = |count: &str| {
        let out = d.join(count);
        let o = texrtl(&[
            "regress",
            "--no-vcd",
            "--count",
            count,
            "--only",
            "blend_adjust_153",
            "--only",
            "normal_pipeline_fig7",
            "--only",
            "mipmap_gen_816",
            "--only",
            "control_607",
            "--only",
            "texture_unit_602",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
        let s: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        s["testbenches"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| {
                (
                    t["name"].as_str().unwrap().to_string(),
                    t["transactions"].as_u64().unwrap(),
                )
            })
            .collect::<Vec<_>>()
    };
    let (a, b) = (summary("3"), summary("6"));
    assert_eq!(
        a.len(),
        5,
        "--only ran the five testbenches and no vectors row: {a:?}"
    );
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(
            y > x,
            "{name}: --count 6 ran {y} transactions, --count 3 ran {x}"
        );
    }
    let o = texrtl(&["regress", "--list"]);
    let list = String::from_utf8_lossy(&o.stdout);
    for name in [
        "blend_adjust_153",
        "normal_pipeline_fig7",
        "mipmap_gen_816",
        "control_607",
        "texture_unit_602",
        "--count",
        "cosim: 17 twins (",
    ] {
        assert!(list.contains(name), "{list}");
    }
    let o = texrtl(&[
        "regress",
        "--only",
        "nonesuch",
        "--out",
        d.join("x").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--only") && err.contains("nonesuch"), "{err}");
    assert!(!d.join("x").exists());
}

/// `--trace-filter` shapes every testbench's waveform: with a filter on state registers, every
/// VCD holds only the clock, the reset, the golden probes and the signals it matches.
#[test]
fn trace_filter_applies_to_every_waveform() {
    let out = tmp("every-filter");
    let o = texrtl(&[
        "regress",
        "--no-cosim",
        "--count",
        "2",
        "--out",
        out.to_str().unwrap(),
        "--trace-filter",
        "*.state",
        "--trace-filter",
        "*valid*",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
    assert!(!String::from_utf8_lossy(&o.stderr).contains("warning"));
    let names = [
        "blend_adjust_153",
        "normal_pipeline_fig7",
        "mipmap_gen_816",
        "control_607",
        "texture_unit_602",
    ];
    for n in names {
        let rb = read_vcd(&out.join(format!("{n}.vcd"))).unwrap();
        let design: Vec<&String> = rb
            .vars
            .keys()
            .filter(|k| !k.starts_with("tb.golden.") && *k != "tb.clk" && *k != "tb.rst")
            .collect();
        assert!(!design.is_empty(), "{n}: nothing traced");
        for k in design {
            let leaf = k.rsplit('.').next().unwrap();
            assert!(
                leaf == "state" || leaf.contains("valid"),
                "{n}: {k} is not matched by the filters"
            );
        }
    }
}

/// A filter that matches no signal of any design (without the `tb.` every name starts with)
/// still runs, and says so: a waveform of clock, reset and probes alone is not what was meant.
#[test]
fn a_trace_filter_matching_nothing_is_warned_of() {
    let out = tmp("unmatched-filter");
    let run = |filter: &str| {
        let o = texrtl(&[
            "regress",
            "--no-cosim",
            "--only",
            "blend_adjust_153",
            "--count",
            "2",
            "--out",
            out.to_str().unwrap(),
            "--trace-filter",
            filter,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let e = run("blend_adjust_153.u*");
    assert!(
        e.contains("warning: --trace-filter blend_adjust_153.u* matched no signal of any design")
            && e.contains("e.g. tb.blend_adjust_153.*"),
        "{e}"
    );
    assert!(!run("tb.blend_adjust_153.u*").contains("warning"));
}

/// `regress -j N` gives the same results byte for byte as `-j 1`: the summary, the report and
/// the table, with waveforms on (the traced configuration writes the same VCD). Each
/// testbench's own counts: one `--count` for all is a unit of each one's own (frames for the
/// mipmap generator, where 60 is thirty times its default and most of such a run).
#[test]
fn parallel_regress_is_byte_identical_to_one_thread() {
    let d = tmp("jobs");
    let run = |jobs: &str| {
        let out = d.join(format!("j{jobs}"));
        let o = texrtl(&[
            "regress",
            "--no-cosim",
            "--seed",
            "0x51",
            "-j",
            jobs,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        // The output folder's own name aside (it is in the summary's waveform paths).
        let dir = out.to_str().unwrap();
        let text = |f: &str| {
            std::fs::read_to_string(out.join(f))
                .unwrap()
                .replace(dir, "OUT")
        };
        let stdout = String::from_utf8_lossy(&o.stdout).replace(dir, "OUT");
        let vcd = std::fs::read(out.join("blend_adjust_153.vcd")).unwrap();
        (text("summary.json"), text("report.md"), vcd, stdout)
    };
    let one = run("1");
    for jobs in ["2", "5"] {
        let many = run(jobs);
        assert!(one.0 == many.0, "-j {jobs}: summary.json differs");
        assert!(one.1 == many.1, "-j {jobs}: report.md differs");
        assert!(one.2 == many.2, "-j {jobs}: the VCD differs");
        assert_eq!(one.3, many.3, "-j {jobs}: the table differs");
    }
    let o = texrtl(&[
        "regress",
        "-j",
        "0",
        "--out",
        d.join("j0").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&d);
}

/// Once, with `summary.json` a folder, regress ran every testbench and left the waves
/// and pictures behind before failing. Now it refuses before any work.
#[test]
fn regress_refuses_an_unwritable_summary_before_running() {
    let out = tmp("summary-dir");
    std::fs::create_dir_all(out.join("summary.json")).unwrap();
    let o = texrtl(&[
        "--no-cosim",
        "--only",
        "blend_adjust_153",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("summary.json is a folder"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
    assert_eq!(left.len(), 1, "only the folder that was there: {left:?}");
}

/// Once, `merge` of a shard declaring 1/4294967295 allocated a 4 G-entry vector (the
/// shard syntax now stops at 4096, and merge keeps a set of the shards given, not a vector
/// of the count), and shards of different texrtl versions merged silently. Both are refused
/// with one line.
#[test]
fn merge_refuses_huge_counts_and_mixed_versions_without_allocating() {
    let d = tmp("merge17");
    let (s1, s2) = (d.join("s1"), d.join("s2"));
    common::small_shard(1, &s1);
    common::small_shard(2, &s2);
    let read = |p: &Path| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(p.join("summary.json")).unwrap()).unwrap()
    };
    let (j, j2) = (read(&s1), read(&s2));
    let variant_of =
        |base: &serde_json::Value, name: &str, edit: &dyn Fn(&mut serde_json::Value)| {
            let mut v = base.clone();
            edit(&mut v);
            let p = d.join(name);
            std::fs::write(&p, serde_json::to_vec(&v).unwrap()).unwrap();
            p
        };
    let variant = |name: &str, edit: &dyn Fn(&mut serde_json::Value)| variant_of(&j, name, edit);
    let huge = variant("huge.json", &|v| v["shard"] = "1/4294967295".into());
    let other = variant_of(&j2, "other.json", &|v| v["texrtl"] = "0.0.0".into());
    // The other half, with one coverage bin deleted in a job: a different coverage model.
    let nobin = variant_of(&j2, "nobin.json", &|v| {
        let bins = &mut v["jobs"][0]["result"]["coverage"]["points"][0]["bins"];
        bins.as_array_mut().unwrap().pop();
    });
    // The other half of a run whose model names a bin differently: whole, but another model.
    let renamed = variant_of(&j2, "renamed.json", &|v| {
        v["jobs"][0]["result"]["coverage"]["points"][0]["bins"][0]["name"] = "other".into();
    });
    // Both halves with a sum near the largest double: their sum is not finite.
    let big = |base: &serde_json::Value, name: &str| {
        variant_of(base, name, &|v| {
            v["jobs"][0]["result"]["stats"]["sum_sq_signal"] = 1e308.into();
        })
    };
    let (big1, big2) = (big(&j, "big1.json"), big(&j2, "big2.json"));
    let merged = d.join("m.json");
    for (files, needle) in [
        (vec![&huge], "N <= 4096"),
        (vec![&s1.join("summary.json"), &other], "texrtl 0.0.0"),
        (
            vec![&s1.join("summary.json"), &nobin],
            "like its coverpoints",
        ),
        (
            vec![&s1.join("summary.json"), &renamed],
            "differs between the models",
        ),
        (vec![&big1, &big2], "finite"),
    ] {
        let mut a = vec!["merge", "--out", merged.to_str().unwrap()];
        a.extend(files.iter().map(|p| p.to_str().unwrap()));
        let o = texrtl(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{needle}: {err}");
        assert!(!merged.exists());
    }
}
