//! The mipmap generator of FIG. 14: bit-identical to the integer reference in every scan order
//! and rounding, sizes down to one texel, FIFOs within their depths, one texel per clock with
//! frames back to back, errors reported; and the `texrtl mipmap` command.

use hdl::kernel::Sim;
use hdl::mipmap::{MipmapGen, MipmapParams, Rounding, Scan};
use std::path::{Path, PathBuf};
use std::process::Command;
use tb::mipmap::{reference, run_mipmap, synthetic_video};
use verif::{seeded_stimulus, Seed};

const SCANS: [Scan; 3] = [
    Scan::Progressive,
    Scan::InterlacedTop,
    Scan::InterlacedBottom,
];

#[test]
fn every_scan_order_gives_the_reference_bit_for_bit() {
    let mut stim = seeded_stimulus("mipmap sizes");
    let mut sizes: Vec<(u32, u32)> = vec![
        (1, 1),
        (1, 2),
        (2, 1),
        (2, 2),
        (4, 1),
        (1, 8),
        (8, 2),
        (32, 16),
        (16, 64),
    ];
    for _ in 0..6 {
        let (a, b) = stim.draw(&(0u32..8, 1u32..8));
        sizes.push((1 << a, 1 << b));
    }
    for (w, h) in sizes {
        let frames = synthetic_video(w, h, 3, Seed(u64::from(w * 131 + h)));
        for rounding in [Rounding::Round, Rounding::Truncate] {
            let mut results = Vec::new();
            for scan in SCANS {
                if h < 2 && scan != Scan::Progressive {
                    continue;
                }
                let p = MipmapParams {
                    width: w,
                    height: h,
                    scan,
                    rounding,
                };
                let o = run_mipmap(p, &frames, None).unwrap();
                assert_eq!(o.error, 0, "{w}x{h} {scan:?}");
                for (f, frame) in frames.iter().enumerate() {
                    assert_eq!(
                        o.frames[f],
                        reference(frame, w, h, rounding),
                        "{w}x{h} {scan:?} {rounding:?} frame {f}"
                    );
                }
                let s = &o.stats;
                assert_eq!(s.texels_per_clock, 1.0, "back to back, one texel per clock");
                for (k, (&m, &d)) in s.fifo_max_occupancy.iter().zip(&s.fifo_depth).enumerate() {
                    assert!(m <= d, "{w}x{h} level {}: occupancy {m} > depth {d}", k + 1);
                    // Depths halve from level to level: half a level-0 line at level 1.
                    assert_eq!(d as u32, (w >> (k + 1)).max(1));
                }
                assert!(s.latency_after_last_texel <= p.levels().len() as u64 + 2);
                results.push(o.frames);
            }
            assert!(
                results.windows(2).all(|p| p[0] == p[1]),
                "scan order changed a bit at {w}x{h}"
            );
        }
    }
}

#[test]
fn sync_errors_are_reported() {
    let p = MipmapParams {
        width: 4,
        height: 4,
        scan: Scan::InterlacedTop,
        rounding: Rounding::Round,
    };
    let mut sim = Sim::new(MipmapGen::new("mip", p).unwrap()).check_schedule(true);
    sim.reset(1);
    for k in 0..6 {
        sim.dut.valid.set_bool(true);
        sim.dut.sof.set_bool(k == 3); // sof in the middle of a line
        sim.dut.texel.set_bits(k);
        sim.step();
    }
    sim.eval();
    assert!(sim.dut.error.is_high());
    assert_eq!(sim.dut.err_code.bits(), 3);
}

#[test]
fn sizes_are_checked() {
    for (w, h, scan) in [
        (3, 4, Scan::Progressive),
        (4, 2048, Scan::Progressive),
        (8, 1, Scan::InterlacedTop),
        (0, 4, Scan::Progressive),
    ] {
        let p = MipmapParams {
            width: w,
            height: h,
            scan,
            rounding: Rounding::Round,
        };
        assert!(MipmapGen::new("m", p).is_err(), "{w}x{h}");
    }
}

fn texrtl(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .unwrap()
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("texrtl-mip-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn pgm(d: &Path, name: &str, w: u32, h: u32) -> PathBuf {
    let p = d.join(name);
    let mut v = format!("P5\n{w} {h}\n255\n").into_bytes();
    v.extend((0..w * h).map(|k| (k * 37 % 256) as u8));
    std::fs::write(&p, v).unwrap();
    p
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
    let l4 = tb::pgm::read(&out.join("level4.pgm")).unwrap();
    assert_eq!((l4.width, l4.height), (1, 1));
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("stats.json")).unwrap()).unwrap();
    assert_eq!(s["fifo_max_occupancy"].as_array().unwrap().len(), 4);
    assert!(s["cycles"].as_u64().unwrap() >= 128);
    let rb = waves::check::read_vcd(&vcd).unwrap();
    assert!(rb.vars.contains_key("tb.mip.level1.fifo1408_occupancy"));
    assert!(rb.vars.contains_key("tb.mip.page_row_bank0"));
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
