//! `texrtl texram` run as a user runs it: results against the chip's testbench reference,
//! the statistics, the waveform's scopes, and bad input refused with one line, exit 2 and no
//! file.

mod common;

use common::{assert_refused, s, texrtl};
use std::path::{Path, PathBuf};
use std::process::Output;

fn dir(name: &str) -> common::TestDir {
    common::dir("texram", name)
}

/// `texrtl texram --texture t --requests r --out o --config config`.
fn texram(t: &Path, r: &Path, o: &Path, config: &str) -> Output {
    texrtl(&[
        "texram",
        "--texture",
        s(t),
        "--requests",
        s(r),
        "--out",
        s(o),
        "--config",
        config,
    ])
}

/// A 64 x 32 PGM and four requests in `d`.
fn inputs(d: &Path) -> (PathBuf, PathBuf) {
    let t = d.join("t.pgm");
    let px: Vec<u8> = (0..64 * 32u32)
        .map(|k| ((k % 64) * 3 + (k / 64) * 5) as u8)
        .collect();
    std::fs::write(&t, formats::netpbm::encode(64, 32, &px)).unwrap();
    let r = d.join("r.csv");
    std::fs::write(
        &r,
        "u,v,lambda\n1.5,1.5,0\n10.25,7.75,1.5\n-3,40,2\n63.9,31.9,10\n",
    )
    .unwrap();
    (t, r)
}

#[test]
fn results_statistics_and_waveform() {
    let d = dir("ok");
    let (t, r) = inputs(&d);
    let (o, st, vcd) = (d.join("o.csv"), d.join("s.json"), d.join("w.vcd"));
    let args = [
        "texram",
        "--texture",
        s(&t),
        "--requests",
        s(&r),
        "--out",
        s(&o),
    ];
    let mut a = args.to_vec();
    a.extend(["--stats", s(&st), "--vcd", s(&vcd), "--border", "mirror"]);
    let out = texrtl(&a);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&o).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "u,v,lambda,r,g,b,a");
    assert_eq!(rows.len(), 5);
    // At a texel centre with lambda 0 the result is that texel: (1, 1) = 3 + 5.
    assert_eq!(rows[1], "1.5,1.5,0,8,8,8,8");
    assert!(
        rows[4].starts_with("63.8984375,31.8984375,10,"),
        "{}",
        rows[4]
    );
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
    for k in [
        "accesses",
        "slots",
        "page_faults",
        "bank_misses",
        "bank_conflicts",
        "video_slots",
        "cycles",
        "ns",
        "pixels_per_second",
    ] {
        assert!(j.get(k).is_some(), "stats lack {k}");
    }
    assert_eq!(j["requests"], 4);
    assert_eq!(j["accesses"], 4);
    assert_eq!(j["bank_conflicts"], 0);
    let slots = j["slots"].as_u64().unwrap();
    assert_eq!(slots, 4 + j["page_faults"].as_u64().unwrap());
    assert!(j["bank_misses"].as_u64().unwrap() >= j["page_faults"].as_u64().unwrap());
    let rb = waves::check::read_vcd(&vcd).unwrap();
    assert!(rb
        .vars
        .keys()
        .any(|n| n.starts_with("tb.texram_802.page_registers_824.")));
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_file() {
    let d = dir("bad");
    let (t, r) = inputs(&d);
    let odd = d.join("odd.pgm");
    std::fs::write(&odd, formats::netpbm::encode(3, 2, &[0; 6])).unwrap();
    let far = d.join("far.csv");
    std::fs::write(&far, "u,v,lambda\n1,1,11\n").unwrap();
    let head = d.join("head.csv");
    std::fs::write(&head, "u,v\n1,1\n").unwrap();
    let o = d.join("o.csv");
    let w = d.join("w.vcd");
    let cases: [(&Path, &Path, &[&str], &str); 6] = [
        (&t, &r, &["--config", "index"], "not a PPM"),
        (&t, &r, &["--config", "bogus"], "--config bogus"),
        (&t, &r, &["--border", "border:256"], "--border border:256"),
        (&odd, &r, &[], "width 3 is not a power of two"),
        (&t, &far, &[], "lambda 11 outside"),
        (&t, &head, &[], "header"),
    ];
    for (tex, req, extra, needle) in cases {
        let mut a = vec![
            "texram",
            "--texture",
            s(tex),
            "--requests",
            s(req),
            "--out",
            s(&o),
        ];
        a.extend_from_slice(extra);
        a.extend(["--vcd", s(&w)]);
        assert_refused(&a, needle, &d, &["o.", "w."]);
    }
}

#[test]
fn colour_textures_planar_and_truecolor() {
    let d = dir("colour");
    let (w, h) = (16u32, 16u32);
    let rgb: Vec<u8> = (0..w * h)
        .flat_map(|k| [(k % 16 * 9) as u8, (k / 16 * 11) as u8, (k * 7 % 256) as u8])
        .collect();
    let t = d.join("c.ppm");
    std::fs::write(&t, formats::netpbm::encode_ppm(w, h, &rgb)).unwrap();
    let r = d.join("r.csv");
    std::fs::write(&r, "u,v,lambda\n3.5,5.5,0\n8,8,0.5\n").unwrap();
    for (config, conflicts) in [("planar", false), ("truecolor", true)] {
        let (o, st) = (
            d.join(format!("{config}.csv")),
            d.join(format!("{config}.json")),
        );
        let a = [
            "texram",
            "--texture",
            s(&t),
            "--requests",
            s(&r),
            "--out",
            s(&o),
        ];
        let mut a = a.to_vec();
        a.extend(["--config", config, "--stats", s(&st)]);
        let out = texrtl(&a);
        assert!(
            out.status.success(),
            "{config}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let csv = std::fs::read_to_string(&o).unwrap();
        // Texel (3, 5) at its centre, level 0: the PPM's colour, opaque.
        let k = 3 * (5 * 16 + 3) as usize;
        let want = format!("3.5,5.5,0,{},{},{},255", rgb[k], rgb[k + 1], rgb[k + 2]);
        assert_eq!(csv.lines().nth(1), Some(want.as_str()), "{config}");
        let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
        assert_eq!(
            j["accesses"], 8,
            "{config}: four component accesses a pixel"
        );
        assert_eq!(
            j["bank_conflicts"].as_u64().unwrap() > 0,
            conflicts,
            "{config}"
        );
    }
    let wide = d.join("wide.ppm");
    std::fs::write(
        &wide,
        formats::netpbm::encode_ppm(32, 16, &[0; 32 * 16 * 3]),
    )
    .unwrap();
    let o = d.join("x.csv");
    let out = texram(&wide, &r, &o, "planar");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("square"));
    assert!(!o.exists());
}

/// Index mode: a PPM of a few colours becomes a palette (the CLUT) and indices; at a texel
/// centre of level 0 the result is the texel's colour; more than 256 colours are refused.
#[test]
fn index_textures_through_the_clut() {
    let d = dir("index");
    let cols = [[255u8, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0]];
    let rgb: Vec<u8> = (0..16 * 16u32)
        .flat_map(|k| cols[((k % 16 / 4 + k / 64) % 4) as usize])
        .collect();
    let t = d.join("p.ppm");
    std::fs::write(&t, formats::netpbm::encode_ppm(16, 16, &rgb)).unwrap();
    let r = d.join("r.csv");
    std::fs::write(&r, "u,v,lambda\n5.5,1.5,0\n8,8,2.5\n").unwrap();
    let o = d.join("o.csv");
    let out = texram(&t, &r, &o, "index");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&o).unwrap();
    // Texel (5, 1): colour (5 / 4 + 1 / 4) % 4 = 1, green.
    assert_eq!(csv.lines().nth(1), Some("5.5,1.5,0,0,255,0,255"));
    let many: Vec<u8> = (0..32 * 32u32)
        .flat_map(|k| [(k % 32 * 8) as u8, (k / 32 * 8) as u8, 0])
        .collect();
    let t2 = d.join("many.ppm");
    std::fs::write(&t2, formats::netpbm::encode_ppm(32, 32, &many)).unwrap();
    let o2 = d.join("o2.csv");
    let out = texram(&t2, &r, &o2, "index");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("more than 256 colours"));
    assert!(!o2.exists());
}

/// A waveform that cannot be written is bad output naming `--vcd` (exit 2, one line), and
/// leaves no result behind.
#[cfg(target_os = "linux")]
#[test]
fn a_waveform_that_cannot_be_written_is_refused() {
    let d = dir("vcd_full");
    let (t, r) = inputs(&d);
    let o = d.join("o.csv");
    let io = ["--texture", s(&t), "--requests", s(&r), "--out", s(&o)];
    common::assert_vcd_full_refused("texram", &io, &d);
}
