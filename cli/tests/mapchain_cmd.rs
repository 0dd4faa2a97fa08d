//! `texrtl mapchain` run as a user runs it: a texture with detail and an environment map,
//! the results, statistics and waveform; bad input refused with one line, exit 2, no file.

mod common;

use common::{assert_refused, csv_lines, ran, s};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> common::TestDir {
    common::dir("mapchain", name)
}

fn pgm(d: &Path, name: &str, side: u32, f: impl Fn(u32, u32) -> u8) {
    let px: Vec<u8> = (0..side * side).map(|k| f(k % side, k / side)).collect();
    std::fs::write(d.join(name), formats::netpbm::encode(side, side, &px)).unwrap();
}

/// A 16x16 texture of 100, offsets to tile (16, 32), a 64x64 detail map of 50, six 16x16
/// faces (face k all 20 k + 10); the chain texture -> offsets -> detail (multiply) ->
/// environment (k_s 255); requests at lambda 0.5 and -2.
fn inputs(d: &Path) -> (PathBuf, PathBuf) {
    pgm(d, "t.pgm", 16, |_, _| 100);
    pgm(d, "ou.pgm", 16, |_, _| 16);
    pgm(d, "ov.pgm", 16, |_, _| 32);
    pgm(d, "d.pgm", 64, |_, _| 50);
    let faces = ["px", "nx", "py", "ny", "pz", "nz"];
    for (k, f) in faces.iter().enumerate() {
        pgm(d, &format!("{f}.pgm"), 16, |_, _| 20 * k as u8 + 10);
    }
    let m = d.join("m.json");
    std::fs::write(
        &m,
        r#"{"drfs": [
  {"drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 1},
  {"drf": 1, "kind": "offset", "maps": ["ou.pgm", "ov.pgm"], "link": 2},
  {"drf": 2, "kind": "detail", "maps": ["d.pgm"], "detail": "multiply", "link": 6},
  {"drf": 6, "kind": "environment", "k_s": 255,
   "maps": ["px.pgm", "nx.pgm", "py.pgm", "ny.pgm", "pz.pgm", "nz.pgm"]}
]}"#,
    )
    .unwrap();
    let r = d.join("r.csv");
    // Seen along +z on a normal along +z, the reflection points to the eye: face +z (4).
    std::fs::write(
        &r,
        "drf,u,v,lambda,nx,ny,nz,vx,vy,vz\n0,3.5,7.25,0.5,0,0,1,0,0,1\n0,3.5,7.25,-2,0,0,1,0,0,1\n",
    )
    .unwrap();
    (m, r)
}

#[test]
fn colours_statistics_and_waveform() {
    let d = dir("ok");
    let (m, r) = inputs(&d);
    let (o, st, w) = (d.join("o.csv"), d.join("s.json"), d.join("w.vcd"));
    ran(&[
        "mapchain",
        "--maps",
        s(&m),
        "--requests",
        s(&r),
        "--out",
        s(&o),
        "--stats",
        s(&st),
        "--vcd",
        s(&w),
    ]);
    let rows = csv_lines(&o);
    assert_eq!(rows[0], "drf,u,v,lambda,colour,accesses,faults,error");
    // lambda 0.5: texture 100 + environment face +z (90): 190, two accesses.
    assert!(rows[1].starts_with("0,3.5,7.25,0.5,190,2,"), "{}", rows[1]);
    // lambda -2: 100 . 50 = round(5000/255) = 20, + 90: five accesses (offsets, detail,
    // texel, face).
    assert!(rows[2].starts_with("0,3.5,7.25,-2,110,5,"), "{}", rows[2]);
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
    assert_eq!(j["pixels"], 2);
    assert_eq!(j["accesses"], 7);
    assert_eq!(j["errors"], 0);
    let slots = j["slots"].as_u64().unwrap();
    assert_eq!(slots, 7 + j["page_faults"].as_u64().unwrap());
    assert!(j["ns_per_pixel"].as_f64().unwrap() > 0.0);
    let rb = waves::check::read_vcd(&w).unwrap();
    assert!(rb.vars.contains_key("tb.walker_812.state"));
    waves::check::check_gtkw(&w, &rb).unwrap();
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_file() {
    let d = dir("bad");
    let (m, r) = inputs(&d);
    let write = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let unknown = write(
        "unknown.json",
        r#"{"drfs": [{"drf": 0, "kind": "texture", "maps": ["t.pgm"], "colour": 3}]}"#,
    );
    let kind = write(
        "kind.json",
        r#"{"drfs": [{"drf": 0, "kind": "bump", "maps": ["t.pgm"]}]}"#,
    );
    let link = write(
        "link.json",
        r#"{"drfs": [{"drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 4}]}"#,
    );
    let off = write(
        "off.json",
        r#"{"drfs": [{"drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 1},
           {"drf": 1, "kind": "offset", "maps": ["ou.pgm", "ov.pgm"], "link": 0}]}"#,
    );
    let planes = write(
        "planes.json",
        r#"{"drfs": [{"drf": 1, "kind": "offset", "maps": ["ou.pgm"]}]}"#,
    );
    let drf = write(
        "drf.json",
        r#"{"drfs": [{"drf": 7, "kind": "texture", "maps": ["t.pgm"]}]}"#,
    );
    pgm(&d, "odd.pgm", 12, |_, _| 0);
    let odd = write(
        "odd.json",
        r#"{"drfs": [{"drf": 0, "kind": "texture", "maps": ["odd.pgm"]}]}"#,
    );
    let face = write(
        "face.json",
        r#"{"drfs": [{"drf": 0, "kind": "environment", "maps": ["odd.pgm","t.pgm","t.pgm","t.pgm","t.pgm","t.pgm"]}]}"#,
    );
    let head = write("head.csv", "u,v,lambda\n1,1,0\n");
    let lam = write("lam.csv", "drf,u,v,lambda\n0,1,1,10.5\n");
    let vec = write("vec.csv", "drf,u,v,lambda,nx\n0,1,1,0,4\n");
    let dup = write("dup.csv", "drf,u,v,lambda,id,id\n0,1,1,0,3,3\n");
    let frac = write("frac.csv", "drf,u,v,lambda,face\n0,1,1,0,2.5\n");
    let cases: [(&Path, &Path, &str); 13] = [
        (&unknown, &r, "unknown field `colour`"),
        (&kind, &r, "kind 'bump'"),
        (&link, &r, "link to drf 4, which is not set"),
        (&off, &r, "offsets link to a detail map"),
        (&planes, &r, "names 2 maps, 1 given"),
        (&drf, &r, "drf 7: 0..7"),
        (&odd, &r, "width 12 is not a power of two"),
        (&face, &r, "width 12 is not a power of two"),
        (&m, &head, "header 'u,v,lambda'"),
        (&m, &lam, "lambda 10.5: not in [-4, 10]"),
        (&m, &vec, "nx 4: not in [-4, 4)"),
        (&m, &dup, "header"),
        (&m, &frac, "face 2.5: not an integer in [0, 5]"),
    ];
    let (o, w) = (d.join("o.csv"), d.join("w.vcd"));
    for (maps, reqs, needle) in cases {
        let a = [
            "mapchain",
            "--maps",
            s(maps),
            "--requests",
            s(reqs),
            "--out",
            s(&o),
            "--vcd",
            s(&w),
        ];
        assert_refused(&a, needle, &d, &["o.", "w."]);
    }
    // An output over one of the maps.
    let t = d.join("t.pgm");
    let a = [
        "mapchain",
        "--maps",
        s(&m),
        "--requests",
        s(&r),
        "--out",
        s(&t),
    ];
    assert_refused(&a, "the same file as the map", &d, &[]);
}

/// A waveform that cannot be written is bad output naming `--vcd` (exit 2, one line), and
/// leaves no result behind.
#[cfg(target_os = "linux")]
#[test]
fn a_waveform_that_cannot_be_written_is_refused() {
    let d = dir("vcd_full");
    let (m, r) = inputs(&d);
    let o = d.join("o.csv");
    let io = ["--maps", s(&m), "--requests", s(&r), "--out", s(&o)];
    common::assert_vcd_full_refused("mapchain", &io, &d);
}
