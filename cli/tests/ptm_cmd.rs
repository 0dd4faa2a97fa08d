//! `texrtl ptm fit|eval` run as a user runs them; bad input refused with one line, exit 2,
//! no file.

mod common;

use common::{assert_refused, csv_lines, ran, s};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> common::TestDir {
    common::dir("ptm", name)
}

/// A 16x16 height map of bumps, a dome of 3 x 8 lights, three queries.
fn inputs(d: &Path) -> (PathBuf, PathBuf, PathBuf) {
    let h = d.join("h.pgm");
    let px: Vec<u8> = (0..256u32)
        .map(|k| {
            if (k % 16) % 4 == 0 && (k / 16) % 4 == 0 {
                200
            } else {
                20
            }
        })
        .collect();
    std::fs::write(&h, formats::netpbm::encode(16, 16, &px)).unwrap();
    let l = d.join("l.csv");
    let mut lights = String::from("elevation,azimuth\n");
    for e in [20, 45, 70] {
        for a in (0..360).step_by(45) {
            lights.push_str(&format!("{e},{a}\n"));
        }
    }
    std::fs::write(&l, lights).unwrap();
    let q = d.join("q.csv");
    std::fs::write(&q, "x,y,lu,lv\n1,0,0.9,0\n5,5,0,0\n15,15,-0.5,0.5\n").unwrap();
    (h, l, q)
}

#[test]
fn fit_then_eval() {
    let d = dir("ok");
    let (h, l, q) = inputs(&d);
    let (t, st, o) = (d.join("t.ptm"), d.join("s.json"), d.join("o.csv"));
    ran(&[
        "ptm",
        "fit",
        "--height",
        s(&h),
        "--lights",
        s(&l),
        "--out",
        s(&t),
        "--stats",
        s(&st),
    ]);
    let ptm = formats::ptm::Ptm::read(&t).unwrap();
    assert_eq!((ptm.width, ptm.height, ptm.format.bits), (16, 16, 8));
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
    assert_eq!(j["lights"], 24);
    assert_eq!(j["ptm_bytes"], 6 * 256);
    assert!(j["rmse_mean"].as_f64().unwrap() < 0.5);
    ran(&[
        "ptm",
        "eval",
        "--ptm",
        s(&t),
        "--queries",
        s(&q),
        "--out",
        s(&o),
    ]);
    let rows = csv_lines(&o);
    assert_eq!(rows[0], "x,y,lu,lv,k,visibility");
    assert_eq!(rows.len(), 4);
    for r in &rows[1..] {
        let f: Vec<u32> = r.split(',').skip(4).map(|x| x.parse().unwrap()).collect();
        assert_eq!(f[0] + f[1], 255, "{r}");
    }
    // A bump's top (texel 0,0 is one) sees every light: K = 0 from straight above.
    assert!(rows[2].starts_with("5,5,0,0,"));
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_file() {
    let d = dir("bad");
    let (h, l, q) = inputs(&d);
    let write = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let ring = write(
        "ring.csv",
        "elevation,azimuth\n30,0\n30,60\n30,120\n30,180\n30,240\n30,300\n30,30\n",
    );
    let few = write("few.csv", "elevation,azimuth\n30,0\n60,60\n");
    let low = write("low.csv", "elevation,azimuth\n0,0\n");
    let t = d.join("t.ptm");
    let fits: [(&Path, &[&str], &str); 5] = [
        (&ring, &[], "one elevation"),
        (&few, &[], "at least 6"),
        (&low, &[], "elevation 0: not in (0, 90]"),
        (&l, &["--bits", "12"], "--bits 12: 8 or 16"),
        (&l, &["--height-scale", "4"], "--height-scale 4"),
    ];
    for (lights, extra, needle) in fits {
        let mut a = vec![
            "ptm",
            "fit",
            "--height",
            s(&h),
            "--lights",
            s(lights),
            "--out",
            s(&t),
        ];
        a.extend_from_slice(extra);
        assert_refused(&a, needle, &d, &["t."]);
    }
    ran(&[
        "ptm",
        "fit",
        "--height",
        s(&h),
        "--lights",
        s(&l),
        "--out",
        s(&t),
    ]);
    let out = d.join("o.csv");
    let outside = write("outside.csv", "x,y,lu,lv\n16,0,0,0\n");
    let disc = write("disc.csv", "x,y,lu,lv\n0,0,0.9,0.9\n");
    let junk = write(
        "junk.ptm",
        "texrtl-ptm 1\n4096 4096 16\n0 0 0 0 0 0 0 0 0 0 0 0\n",
    );
    let evals: [(&Path, &Path, &str); 3] = [
        (&t, &outside, "x 16: outside 0..16"),
        (&t, &disc, "outside the unit disc"),
        (&junk, &q, "need"),
    ];
    for (ptm, queries, needle) in evals {
        let a = [
            "ptm",
            "eval",
            "--ptm",
            s(ptm),
            "--queries",
            s(queries),
            "--out",
            s(&out),
        ];
        assert_refused(&a, needle, &d, &["o."]);
    }
}
