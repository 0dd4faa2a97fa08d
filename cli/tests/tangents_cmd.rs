//! `texrtl tangents` run as a user runs it; bad input refused with one line, exit 2, no file.

mod common;

use common::{assert_refused, csv_lines, ran, s};

#[test]
fn a_quad_in_every_mode_and_bad_input() {
    let d = common::dir("tangents", "all");
    let m = d.join("q.obj");
    std::fs::write(
        &m,
        "v 0 0 0\nv 2 0 0\nv 2 0 -2\nv 0 0 -2\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\nf 1/1/1 2/2/1 3/3/1 4/4/1\n",
    )
    .unwrap();
    let o = d.join("t.csv");
    for mode in ["max", "maya", "directx"] {
        ran(&["tangents", "--mesh", s(&m), "--out", s(&o), "--mode", mode]);
        let rows = csv_lines(&o);
        assert_eq!(rows[0], "face,corner,tx,ty,tz,bx,by,bz,nx,ny,nz,zero");
        assert_eq!(rows.len(), 5);
        // u along +x, v along -z, the normal +y.
        for r in &rows[1..] {
            assert!(r.contains(",1.000000,0.000000,0.000000,0.000000,0.000000,-1.000000,0.000000,1.000000,0.000000,0"), "{mode}: {r}");
        }
    }
    let bad = d.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let o2 = d.join("o2.csv");
    assert_refused(
        &["tangents", "--mesh", s(&bad), "--out", s(&o2)],
        "bad.obj:4: corner '1' has no texture coordinate",
        &d,
        &["o2."],
    );
    assert_refused(
        &[
            "tangents",
            "--mesh",
            s(&m),
            "--out",
            s(&o2),
            "--mode",
            "blender",
        ],
        "--mode blender: max, maya or directx",
        &d,
        &["o2."],
    );
}
