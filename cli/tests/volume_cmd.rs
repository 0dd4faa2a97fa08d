//! `texrtl volume` run as a user runs it: samples of a linear field, the statistics, the
//! waveform, and bad input refused with one line, exit 2 and no file.

mod common;

use common::{assert_refused, s, texrtl};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> common::TestDir {
    common::dir("volume", name)
}

/// An 8x6x5 volume of the linear field 3x + 5y + 7z + 9, and two rays.
fn inputs(d: &Path) -> (PathBuf, PathBuf) {
    let v = d.join("v.raw");
    let vox: Vec<u8> = (0..8 * 6 * 5u32)
        .map(|n| (3 * (n % 8) + 5 * (n / 8 % 6) + 7 * (n / 48) + 9) as u8)
        .collect();
    std::fs::write(&v, vox).unwrap();
    let r = d.join("r.csv");
    std::fs::write(
        &r,
        "x0,y0,z0,dx,dy,dz,steps\n2,2,1,0.5,0,0.25,4\n3.25,1.5,2,0,0,0,1\n",
    )
    .unwrap();
    (v, r)
}

#[test]
fn samples_statistics_and_waveform() {
    let d = dir("ok");
    let (v, r) = inputs(&d);
    let (o, st, w) = (d.join("o.csv"), d.join("s.json"), d.join("w.vcd"));
    let out = texrtl(&[
        "volume",
        "--volume",
        s(&v),
        "--dims",
        "8,6,5",
        "--rays",
        s(&r),
        "--out",
        s(&o),
        "--gradient",
        "--stats",
        s(&st),
        "--vcd",
        s(&w),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&o).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "ray,k,x,y,z,value,gx,gy,gz");
    assert_eq!(rows.len(), 6);
    // At voxel (2, 2, 1) the field is 6 + 10 + 7 + 9 = 32; its gradient (6, 10, 14).
    assert_eq!(rows[1], "0,0,2,2,1,32,6,10,14");
    // Half a voxel on: 3 * 2.5 + 10 + 7 * 1.25 + 9 = 35.25 -> 35.
    assert_eq!(rows[2], "0,1,2.5,2,1.25,35,6,10,14");
    assert!(rows[5].starts_with("1,0,3.25,1.5,2,"), "{}", rows[5]);
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&st).unwrap()).unwrap();
    assert_eq!(j["rays"], 2);
    assert_eq!(j["samples"], 5);
    assert_eq!(j["accesses"], 40);
    let slots = j["slots"].as_u64().unwrap();
    assert_eq!(slots, 40 + j["fault_slots"].as_u64().unwrap());
    let rb = waves::check::read_vcd(&w).unwrap();
    assert!(rb
        .vars
        .keys()
        .any(|n| n.starts_with("tb.ray_caster_fig15.page_registers_824.")));
    waves::check::check_gtkw(&w, &rb).unwrap();
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_file() {
    let d = dir("bad");
    let (v, r) = inputs(&d);
    let far = d.join("far.csv");
    std::fs::write(&far, "x0,y0,z0,dx,dy,dz,steps\n600,0,0,0,0,0,1\n").unwrap();
    let zero = d.join("zero.csv");
    std::fs::write(&zero, "x0,y0,z0,dx,dy,dz,steps\n1,1,1,0,0,0,0\n").unwrap();
    let head = d.join("head.csv");
    std::fs::write(&head, "x,y,z\n1,1,1\n").unwrap();
    let o = d.join("o.csv");
    let w = d.join("w.vcd");
    let cases: [(&Path, &[&str], &str); 8] = [
        (
            &r,
            &["--dims", "8,6,4"],
            "240 bytes, --dims 8,6,4 needs 192",
        ),
        (&r, &["--dims", "7,6,5"], "x size 7"),
        (&r, &["--dims", "8,6"], "--dims 8,6: X,Y,Z"),
        (
            &r,
            &["--dims", "8,6,5", "--row-words", "100"],
            "row_words 100",
        ),
        (
            &r,
            &["--dims", "8,6,5", "--order", "diagonal"],
            "--order diagonal",
        ),
        (&far, &["--dims", "8,6,5"], "x0 600 outside"),
        (&zero, &["--dims", "8,6,5"], "steps 0"),
        (&head, &["--dims", "8,6,5"], "header"),
    ];
    for (rays, extra, needle) in cases {
        let mut a = vec![
            "volume",
            "--volume",
            s(&v),
            "--rays",
            s(rays),
            "--out",
            s(&o),
        ];
        a.extend_from_slice(extra);
        a.extend(["--vcd", s(&w)]);
        assert_refused(&a, needle, &d, &["o.", "w."]);
    }
}
