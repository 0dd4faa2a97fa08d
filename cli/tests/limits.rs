//! Every command with every numeric or enumerated option at its limits and one past them:
//! the program answers with exit 0 (or 1, a failed testbench, for `regress`) or with exit 2
//! and one line naming the problem, never with a panic (101) or an abort.

mod common;

use std::path::Path;
use std::process::Command;

/// A fresh folder for `test`, removed when it passes.
fn dir(test: &str) -> common::TestDir {
    common::dir("limits", test)
}

fn write(d: &Path, name: &str, data: &[u8]) -> String {
    let p = d.join(name);
    std::fs::write(&p, data).unwrap();
    p.to_string_lossy().into_owned()
}

/// Runs `texrtl args`; checks the exit status is allowed and a refusal is one line.
fn check(args: &[String], allow_fail: bool) -> i32 {
    let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .expect("runs");
    let code = o.status.code().unwrap_or(-1);
    let err = String::from_utf8_lossy(&o.stderr);
    let ok = code == 0 || code == 2 || (allow_fail && code == 1);
    assert!(ok, "texrtl {}: exit {code}\n{err}", args.join(" "));
    if code == 2 {
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "texrtl {}: not one line: {err}",
            args.join(" ")
        );
        assert!(
            err.len() < 400,
            "texrtl {}: long message: {err}",
            args.join(" ")
        );
    }
    code
}

/// `base` with `--opt value` for every value; each value's expected exit (0 or 2).
fn sweep(base: &[String], opt: &str, cases: &[(&str, i32)], allow_fail: bool) {
    for (v, want) in cases {
        let mut a = base.to_vec();
        a.push(opt.to_string());
        a.push(v.to_string());
        let got = check(&a, allow_fail);
        let got = if allow_fail && got == 1 { 0 } else { got };
        assert_eq!(got, *want, "texrtl {} exits {got}", a.join(" "));
    }
}

fn s(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}

#[test]
fn normals_options_at_their_limits() {
    let d = dir("normals");
    let h = write(
        &d,
        "h.pgm",
        b"P2\n4 4\n15\n1 2 3 4\n5 6 7 8\n9 10 11 12\n13 14 15 0\n",
    );
    let c = write(&d, "c.csv", b"u,v\n1.5,2.25\n0,0\n");
    let out = d.join("n.csv").to_string_lossy().into_owned();
    let base = s(&["normals", "--height", &h, "--coords", &c, "--out", &out]);
    let widths: [(&str, &[(&str, i32)]); 6] = [
        (
            "--blend-bits",
            &[
                ("4", 0),
                ("16", 0),
                ("3", 2),
                ("17", 2),
                ("-1", 2),
                ("99999999999", 2),
            ],
        ),
        ("--texel-bits", &[("4", 0), ("8", 0), ("5", 2), ("0", 2)]),
        (
            "--rsqrt-table-bits",
            &[("3", 0), ("14", 0), ("2", 2), ("15", 2)],
        ),
        ("--rsqrt-iterations", &[("0", 0), ("3", 0), ("4", 2)]),
        ("--out-frac", &[("8", 0), ("24", 0), ("7", 2), ("25", 2)]),
        (
            "--tangent-frac",
            &[("8", 0), ("24", 0), ("7", 2), ("25", 2)],
        ),
    ];
    for (opt, cases) in widths {
        sweep(&base, opt, cases, false);
    }
    sweep(
        &base,
        "--scale",
        &[
            ("0", 0),
            ("255.99", 0),
            ("256", 2),
            ("-1", 2),
            ("1e308", 2),
            ("nan", 2),
        ],
        false,
    );
    sweep(
        &base,
        "--border",
        &[
            ("constant:0", 0),
            ("constant:255", 0),
            ("constant:256", 2),
            ("constant:-1", 2),
            ("bogus", 2),
        ],
        false,
    );
    let mut b4 = base.clone();
    b4.extend(s(&["--texel-bits", "4"]));
    sweep(
        &b4,
        "--border",
        &[("constant:15", 0), ("constant:16", 2), ("constant:200", 2)],
        false,
    );
    let mut tri = base.clone();
    tri.push("--trilinear".into());
    sweep(
        &tri,
        "--lod",
        &[("0", 0), ("0.99", 0), ("1", 2), ("-0.1", 2), ("inf", 2)],
        false,
    );
    sweep(&base, "--lod", &[("0.5", 2)], false);
}

#[test]
fn render_options_at_their_limits() {
    let d = dir("render");
    let h = write(
        &d,
        "h.pgm",
        b"P2\n4 4\n15\n1 2 3 4\n5 6 7 8\n9 10 11 12\n13 14 15 0\n",
    );
    let png = d.join("r.png").to_string_lossy().into_owned();
    let base = s(&["render", "--height", &h, "--out", &png]);
    sweep(
        &base,
        "--zoom",
        &[
            ("1", 0),
            ("64", 0),
            ("0", 2),
            ("3", 2),
            ("128", 2),
            ("-1", 2),
        ],
        false,
    );
    sweep(
        &base,
        "--light",
        &[
            ("-1,1,2", 0),
            ("0,0,1", 0),
            ("0,0,0", 2),
            ("1e200,0,0", 0),
            ("nan,0,1", 2),
            ("1,2", 2),
        ],
        false,
    );
    sweep(
        &base,
        "--scale",
        &[("0", 0), ("1e308", 2), ("-1", 2)],
        false,
    );
}

#[test]
fn memory_path_options_at_their_limits() {
    let d = dir("memory");
    let t = write(&d, "t.csv", b"addr\n0\n1\n700\n262143\n");
    let base = s(&["dram", "--trace", &t]);
    // 256K words: 128..=2048 words per page keep the rows within 11 address pins.
    sweep(
        &base,
        "--page-words",
        &[
            ("128", 0),
            ("512", 0),
            ("2048", 0),
            ("64", 2),
            ("3", 2),
            ("4096", 2),
            ("0", 2),
        ],
        false,
    );
    sweep(
        &base,
        "--t-fault-ns",
        &[
            ("10", 0),
            ("60", 0),
            ("5", 2),
            ("7", 2),
            ("10010", 2),
            ("0", 2),
        ],
        false,
    );
    sweep(&base, "--size", &[("256k", 0), ("1m", 0), ("2m", 2)], false);
    // A 16x16 texture and a few requests, including the last texel.
    let ppm: Vec<u8> = b"P6\n16 16\n255\n"
        .iter()
        .copied()
        .chain((0..16 * 16 * 3).map(|i| (i * 7 % 256) as u8))
        .collect();
    let tex = write(&d, "t.ppm", &ppm);
    let req = write(&d, "r.csv", b"u,v\n0,0\n15.5,15.5\n3.25,7\n");
    let out = d.join("o.csv").to_string_lossy().into_owned();
    let base = s(&[
        "texread",
        "--texture",
        &tex,
        "--requests",
        &req,
        "--out",
        &out,
    ]);
    sweep(
        &base,
        "--interval",
        &[("1", 0), ("1000", 0), ("0", 2), ("1001", 2)],
        false,
    );
    sweep(
        &base,
        "--frac-bits",
        &[("1", 0), ("8", 0), ("0", 2), ("9", 2)],
        false,
    );
    sweep(
        &base,
        "--lookahead",
        &[("off", 0), ("quadrant", 0), ("direction", 0), ("bogus", 2)],
        false,
    );
    sweep(
        &base,
        "--layout",
        &[("row-major", 0), ("tiled", 0), ("bogus", 2)],
        false,
    );
    sweep(&base, "--dram", &[("256k", 0), ("1m", 0), ("4m", 2)], false);
    let ccc = d.join("t.ccc").to_string_lossy().into_owned();
    check(&s(&["ccc", "encode", "--in", &tex, "--out", &ccc]), false);
    // Sides must be multiples of 4 up to 4096; a header declaring more is refused unread.
    for (hdr, want) in [
        ("P6\n4 4\n255\n", 0),
        ("P6\n4 6\n255\n", 2),
        ("P6\n8192 4\n255\n", 2),
        ("P3\n46341 46341\n255\n", 2),
    ] {
        let mut b = hdr.as_bytes().to_vec();
        b.extend(std::iter::repeat_n(b'\x10', 4 * 4 * 3));
        let p = write(&d, "s.ppm", &b);
        let code = check(&s(&["ccc", "encode", "--in", &p, "--out", &ccc]), false);
        assert_eq!(code, want, "{hdr:?}");
    }
}

#[test]
fn mipmap_sweep_and_vectors_options_at_their_limits() {
    let d = dir("mipmap");
    let one = write(&d, "one.pgm", b"P2\n1 1\n255\n7\n");
    let big = write(&d, "big.pgm", b"P2\n2048 2\n255\n");
    let huge = write(&d, "huge.pgm", b"P2\n65535 65535\n255\n1\n");
    let two = write(&d, "two.pgm", b"P2\n2 2\n255\n1 2 3 4\n");
    let out = d.join("m").to_string_lossy().into_owned();
    for (f, scan, want) in [
        (&one, "progressive", 0),
        (&one, "interlaced-top", 2),
        (&two, "interlaced-bottom", 0),
        (&two, "bogus", 2),
        (&big, "progressive", 2),
        (&huge, "progressive", 2),
    ] {
        let code = check(
            &s(&["mipmap", "--in", f, "--out", &out, "--scan", scan]),
            false,
        );
        assert_eq!(code, want, "{f} {scan}");
    }
    sweep(
        &s(&["mipmap", "--in", &two, "--out", &out]),
        "--rounding",
        &[("round", 0), ("truncate", 0), ("bogus", 2)],
        false,
    );
    let base = s(&["sweep", "normals"]);
    sweep(
        &base,
        "--samples",
        &[("1", 0), ("0", 2), ("1000001", 2), ("-3", 2)],
        false,
    );
    sweep(&base, "--map", &[("flat", 0), ("bogus", 2)], false);
    let base = s(&["cosim", "--unit", "blend_adjust_153"]);
    sweep(
        &base,
        "--count",
        &[("0", 2), ("10000001", 2), ("-1", 2)],
        false,
    );
    sweep(&base, "--sim", &[("bogus", 2)], false);
    sweep(&base, "--stimulus", &[("bogus", 2)], false);
    sweep(&s(&["cosim"]), "--unit", &[("bogus", 2)], false);
    // Regression vectors exist for three of the twins only.
    sweep(
        &s(&["cosim", "--stimulus", "vectors"]),
        "--unit",
        &[("cache_614", 2)],
        false,
    );
    let v = d.join("v").to_string_lossy().into_owned();
    let base = s(&["vectors", "--out", &v]);
    sweep(
        &base,
        "--unit",
        &[("blend_adjust_153", 0), ("mipmap_gen_816", 0), ("bogus", 2)],
        false,
    );
}

#[test]
fn regress_options_at_their_limits() {
    let d = dir("regress");
    let out = d.join("r").to_string_lossy().into_owned();
    let base = s(&[
        "regress",
        "--only",
        "blend_adjust_153",
        "--no-vcd",
        "--out",
        &out,
    ]);
    sweep(
        &base,
        "--count",
        &[
            ("0", 2),
            ("1", 0),
            ("1000001", 2),
            ("18446744073709551615", 2),
            ("-1", 2),
        ],
        true,
    );
    sweep(
        &base,
        "--jobs",
        &[("1", 0), ("256", 0), ("0", 2), ("257", 2), ("-1", 2)],
        true,
    );
    sweep(
        &base,
        "--shard",
        &[
            ("1/1", 0),
            ("13/13", 0),
            ("0/1", 2),
            ("3/2", 2),
            ("1/4294967295", 2),
            ("1/0", 2),
        ],
        true,
    );
    sweep(
        &base,
        "--seed",
        &[
            ("0", 0),
            ("0xffffffffffffffff", 0),
            ("0x1ffffffffffffffff", 2),
            ("seed", 2),
        ],
        true,
    );
    let base = s(&[
        "regress",
        "--only",
        "blend_adjust_153",
        "--count",
        "1",
        "--out",
        &out,
    ]);
    sweep(
        &base,
        "--period-ps",
        &[
            ("2", 0),
            ("1000000000", 0),
            ("1", 2),
            ("3", 2),
            ("1000000002", 2),
            ("18446744073709551614", 2),
        ],
        true,
    );
    sweep(
        &base,
        "--trace-window",
        &[
            ("0..1", 0),
            ("10..20", 0),
            ("5..5", 2),
            ("9..3", 2),
            ("100000000..100000001", 0),
        ],
        true,
    );
    sweep(
        &base,
        "--trace-depth",
        &[("0", 0), ("99", 0), ("-1", 2)],
        true,
    );
    sweep(&base, "--only", &[("vectors", 0), ("bogus", 2)], true);
}

#[test]
fn regress_sim_option_at_its_limits() {
    let d = dir("regress-sim");
    let out = d.join("r").to_string_lossy().into_owned();
    let base = s(&[
        "regress",
        "--only",
        "blend_adjust_153",
        "--count",
        "1",
        "--no-vcd",
        "--out",
        &out,
    ]);
    let installed = |exe: &str| Command::new(exe).arg("-V").output().is_ok();
    let (v, i) = (installed("verilator"), installed("iverilog"));
    let code = |found: bool| if found { 0 } else { 2 };
    sweep(
        &base,
        "--sim",
        &[
            ("verilator", code(v)),
            ("icarus", code(i)),
            ("iverilog", 2),
            ("", 2),
        ],
        true,
    );
    // Refused before anything is written.
    let refused = d.join("refused").to_string_lossy().into_owned();
    let base = s(&["regress", "--only", "blend_adjust_153", "--out", &refused]);
    for bad in [
        &["--sim", "icarus", "--sim", "icarus"][..],
        &["--no-cosim", "--sim", "verilator"],
    ] {
        let a = [base.clone(), s(bad)].concat();
        assert_eq!(check(&a, false), 2, "{a:?}");
    }
    assert!(!Path::new(&refused).exists());
}
