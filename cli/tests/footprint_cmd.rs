//! `texrtl footprint` run as a user runs it: results against the integer reference, the
//! statistics, the waveform's scopes, and bad input refused with one line, exit 2, no file.

mod common;

use common::{assert_refused, s, texrtl};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> common::TestDir {
    common::dir("footprint", name)
}

/// A 64 x 32 PGM and five pixels in `d`.
fn inputs(d: &Path) -> (PathBuf, PathBuf, Vec<u8>) {
    let t = d.join("t.pgm");
    let px: Vec<u8> = (0..64 * 32u32)
        .map(|k| ((k % 64) * 3 + (k / 64) * 5) as u8)
        .collect();
    std::fs::write(&t, formats::netpbm::encode(64, 32, &px)).unwrap();
    let r = d.join("r.csv");
    std::fs::write(
        &r,
        "u,v,dudx,dvdx,dudy,dvdy\n1.5,1.5,1,0,0,1\n10,7,4,0,0,1\n20,9,0.5,3.5,-1,0.25\n-3,40,0,0,0,0\n30,16,100,0,0,2\n",
    )
    .unwrap();
    (t, r, px)
}

#[test]
fn results_statistics_and_waveform() {
    let d = dir("ok");
    let (t, r, px) = inputs(&d);
    let (o, st, vcd) = (d.join("o.csv"), d.join("s.json"), d.join("w.vcd"));
    let out = texrtl(&[
        "footprint",
        "--texture",
        s(&t),
        "--requests",
        s(&r),
        "--out",
        s(&o),
        "--stats",
        s(&st),
        "--vcd",
        s(&vcd),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&o).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "u,v,dudx,dvdx,dudy,dvdy,n,lambda,value");
    assert_eq!(rows.len(), 6);
    // An isotropic one-texel footprint at a texel centre: N = 1, lambda 0, that texel.
    assert_eq!(rows[1], format!("1.5,1.5,1,0,0,1,1,0,{}", px[64 + 1]));
    // 4 x 1: four squares of one texel, lambda 0.
    assert!(rows[2].starts_with("10,7,4,0,0,1,4,0,"), "{}", rows[2]);
    // No footprint: one access at the least lambda.
    assert!(rows[4].starts_with("-3,40,0,0,0,0,1,-4,"), "{}", rows[4]);
    // 100 x 2: 50 rounds to 64 in the log domain, held to 16.
    assert!(rows[5].starts_with("30,16,100,0,0,2,16,1,"), "{}", rows[5]);
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
    assert_eq!(j["pixels"], 5);
    let n: u64 = rows[1..]
        .iter()
        .map(|r| r.split(',').nth(6).unwrap().parse::<u64>().unwrap())
        .sum();
    assert_eq!(j["accesses"].as_u64(), Some(n));
    assert_eq!(
        j["slots"].as_u64().unwrap(),
        n + j["page_faults"].as_u64().unwrap()
    );
    for k in ["mean_n", "bank_misses", "cycles", "ns", "pixels_per_second"] {
        assert!(j.get(k).is_some(), "stats lack {k}");
    }
    let rb = waves::check::read_vcd(&vcd).unwrap();
    for scope in [
        "footprint_fig12.footprint_setup",
        "footprint_fig12.footprint_assembly.generator",
        "footprint_fig12.footprint_assembly.accumulator",
        "footprint_fig12.footprint_assembly.texram_802.trilinear_818",
    ] {
        let p = format!("tb.{scope}.");
        assert!(rb.vars.keys().any(|n| n.starts_with(&p)), "no scope {p}");
    }
    waves::check::check_gtkw(&vcd, &rb).unwrap();
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_file() {
    let d = dir("bad");
    let (t, r, _) = inputs(&d);
    let far = d.join("far.csv");
    std::fs::write(&far, "u,v,dudx,dvdx,dudy,dvdy\n1,1,3000,0,0,1\n").unwrap();
    let head = d.join("head.csv");
    std::fs::write(&head, "u,v,lambda\n1,1,0\n").unwrap();
    let nan = d.join("nan.csv");
    std::fs::write(&nan, "u,v,dudx,dvdx,dudy,dvdy\n1,1,NaN,0,0,1\n").unwrap();
    let o = d.join("o.csv");
    let w = d.join("w.vcd");
    let cases: [(&Path, &[&str], &str); 9] = [
        (&r, &["--max-n", "3"], "--max-n 3"),
        (&r, &["--max-n", "128"], "--max-n 128"),
        (&r, &["--rounding", "up"], "--rounding up"),
        (&r, &["--unit", "texture"], "neither a .ccc file"),
        (&r, &["--unit", "texram2"], "--unit texram2"),
        (&r, &["--border", "edge"], "--border edge"),
        (&far, &[], "dudx 3000 outside"),
        (&head, &[], "header"),
        (&nan, &[], "dudx"),
    ];
    for (req, extra, needle) in cases {
        let mut a = vec![
            "footprint",
            "--texture",
            s(&t),
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

/// The Figure 6 texture unit (bilinear, CCC): R, G, B per pixel, the same N as on the chip,
/// an isotropic footprint at a texel is that texel's (decoded) colour.
#[test]
fn the_texture_unit_gives_rgb() {
    let d = dir("texture");
    let (_, r, _) = inputs(&d);
    let (w, h) = (32u32, 16u32);
    let rgb: Vec<u8> = (0..w * h)
        .flat_map(|k| [(k % 32 * 8) as u8, (k / 32 * 16) as u8, 128])
        .collect();
    let t = d.join("t.ppm");
    std::fs::write(&t, formats::netpbm::encode_ppm(w, h, &rgb)).unwrap();
    let (o, st) = (d.join("o.csv"), d.join("s.json"));
    let out = texrtl(&[
        "footprint",
        "--texture",
        s(&t),
        "--requests",
        s(&r),
        "--out",
        s(&o),
        "--unit",
        "texture",
        "--stats",
        s(&st),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&o).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "u,v,dudx,dvdx,dudy,dvdy,n,lambda,r,g,b");
    assert_eq!(rows.len(), 6);
    assert!(rows[2].starts_with("10,7,4,0,0,1,4,0,"), "{}", rows[2]);
    assert_eq!(rows[1].split(',').count(), 11);
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
    assert_eq!(j["pixels"], 5);
    assert!(
        j.get("slots").is_none(),
        "no TEXRAM slots on the texture unit"
    );
    assert!(j["page_faults"].as_u64().unwrap() > 0);
}
