//! The `texrtl` commands of the mipmap path, run as a user runs them.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
fn dir(name: &str) -> common::TestDir {
    common::dir("mip", name)
}
fn pgm(d: &Path, name: &str, w: u32, h: u32) -> PathBuf {
    let p = d.join(name);
    let mut v = format!("P5\n{w} {h}\n255\n").into_bytes();
    v.extend((0..w * h).map(|k| (k * 37 % 256) as u8));
    std::fs::write(&p, v).unwrap();
    p
}
fn texrtl(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .unwrap()
}
#[test]
fn mipmap_command() {
    let d = dir("ok");
    let f = pgm(&d, "f.pgm", 16, 8);
    let out = d.join("out");
    let vcd = d.join("m.vcd");
    let o = texrtl(&[
        "mipmap",
        "--in",
        f.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--scan",
        "interlaced-top",
        "--vcd",
        vcd.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for k in 0..5 {
        assert!(out.join(format!("level{k}.pgm")).exists(), "level {k}");
    }
    let l4 = formats::netpbm::read(&out.join("level4.pgm")).unwrap();
    assert_eq!((l4.width, l4.height), (1, 1));
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("stats.json")).unwrap()).unwrap();
    assert_eq!(s["fifo_max_occupancy"].as_array().unwrap().len(), 4);
    assert!(s["cycles"].as_u64().unwrap() >= 128);
    let rb = waves::check::read_vcd(&vcd).unwrap();
    assert!(rb
        .vars
        .contains_key("tb.mipmap_gen_816.level1.fifo_1408.occupancy"));
    assert!(rb
        .vars
        .contains_key("tb.mipmap_gen_816.page_registers_824.open0"));
    waves::check::check_gtkw(&vcd, &rb).unwrap();
    // Several frames: one directory each.
    let out2 = d.join("out2");
    let o = texrtl(&[
        "mipmap",
        "--in",
        f.to_str().unwrap(),
        "--in",
        f.to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert!(out2.join("frame1/level3.pgm").exists());
}
#[test]
fn mipmap_bad_input() {
    let d = dir("bad");
    let good = pgm(&d, "g.pgm", 8, 8);
    let odd = pgm(&d, "odd.pgm", 6, 8);
    let other = pgm(&d, "o.pgm", 8, 4);
    let notpgm = d.join("n.pgm");
    std::fs::write(&notpgm, "hello").unwrap();
    let out = d.join("out");
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec![s(&notpgm)], "not a PGM"),
        (vec![s(&odd)], "not a power of two"),
        (vec![s(&good), s(&other)], "differs"),
    ];
    for (ins, needle) in cases {
        let mut args = vec!["mipmap".to_string()];
        for i in &ins {
            args.extend(["--in".to_string(), i.clone()]);
        }
        args.extend(["--out".to_string(), s(&out)]);
        let o = texrtl(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{needle}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1);
        assert!(err.contains(needle), "{needle}: {err}");
        assert!(!out.exists(), "{needle}: output written");
    }
    let o = texrtl(&[
        "mipmap",
        "--in",
        &s(&good),
        "--out",
        &s(&out),
        "--scan",
        "sideways",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
}
