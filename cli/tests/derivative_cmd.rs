//! `texrtl normals --filter` with para. 0086's derivative filters.

mod common;

use common::{assert_refused, csv_lines, ran, s};

#[test]
fn derivative_filters_through_normals() {
    let d = common::dir("derivative", "all");
    let h = d.join("h.pgm");
    // A ramp along x of 4 raw levels a texel (1 texel unit of height: uQ6.2).
    let px: Vec<u8> = (0..16 * 16u32).map(|k| (k % 16 * 4) as u8).collect();
    std::fs::write(&h, formats::netpbm::encode(16, 16, &px)).unwrap();
    let c = d.join("c.csv");
    std::fs::write(&c, "u,v\n5.5,7.25\n8,3\n").unwrap();
    let o = d.join("n.csv");
    for f in ["central", "sobel", "prewitt"] {
        ran(&[
            "normals",
            "--height",
            s(&h),
            "--coords",
            s(&c),
            "--out",
            s(&o),
            "--filter",
            f,
            "--border",
            "clamp",
        ]);
        // Slope 1 along x at scale 1: n = (-1, 0, 1)/sqrt 2 = -0.7071..: sQ1.14 -11585.
        for r in csv_lines(&o).iter().skip(1) {
            assert!(
                r.ends_with(",-0.70709228515625,0,0.70709228515625"),
                "{f}: {r}"
            );
        }
    }
    let o2 = d.join("m.csv");
    assert_refused(
        &[
            "normals",
            "--height",
            s(&h),
            "--coords",
            s(&c),
            "--out",
            s(&o2),
            "--filter",
            "table:1,2,3,4,5",
        ],
        "unknown filter",
        &d,
        &["m."],
    );
    assert_refused(
        &[
            "normals",
            "--height",
            s(&h),
            "--coords",
            s(&c),
            "--out",
            s(&o2),
            "--filter",
            "sobel",
            "--trilinear",
        ],
        "--trilinear: the derivative filter sobel reads one level",
        &d,
        &["m."],
    );
}
