//! The `texrtl` commands of the texture path, run as a user runs them.

use formats::ccc::Ccc;
use tb::texture::reference_filter;
mod common;

fn dir(name: &str) -> common::TestDir {
    common::dir("tex", name)
}
fn ppm(w: u32, h: u32) -> Vec<u8> {
    let mut px = Vec::new();
    for y in 0..h {
        for x in 0..w {
            px.extend_from_slice(&[(x * 8) as u8, (y * 8) as u8, ((x ^ y) * 4) as u8]);
        }
    }
    formats::netpbm::encode_ppm(w, h, &px)
}
fn texrtl(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .expect("runs")
}
/// A folder with the test texture as `t.ppm`, encoded by `texrtl ccc encode` into `t.ccc`.
fn encoded(name: &str) -> (common::TestDir, std::path::PathBuf, std::path::PathBuf) {
    let d = dir(name);
    let (t, c) = (d.join("t.ppm"), d.join("t.ccc"));
    std::fs::write(&t, ppm(32, 16)).unwrap();
    let o = texrtl(&["ccc", "encode", "--in", &s(&t), "--out", &s(&c)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("PSNR"));
    (d, t, c)
}

fn s(p: &std::path::Path) -> String {
    p.to_str().unwrap().to_string()
}

/// `texrtl texread --texture T --requests R --out O` with `extra` options.
fn texread(
    texture: &std::path::Path,
    requests: &std::path::Path,
    out: &std::path::Path,
    extra: &[&str],
) -> std::process::Output {
    let (t, r, o) = (s(texture), s(requests), s(out));
    let mut a = vec!["texread", "--texture", &t, "--requests", &r, "--out", &o];
    a.extend(extra);
    texrtl(&a)
}

#[test]
fn ccc_decode_gives_the_encoded_texture() {
    let (d, _, c) = encoded("decode");
    let dec = d.join("d.ppm");
    let o = texrtl(&["ccc", "decode", "--in", &s(&c), "--out", &s(&dec)]);
    assert!(o.status.success());
    let tex = Ccc::read(&c).unwrap();
    let img = formats::netpbm::read_ppm(&dec).unwrap();
    assert_eq!(img.pixels, tex.decode());
}

/// Every cache and layout mode gives the integer reference's colours, with its statistics
/// and a waveform; a PPM texture encoded on the fly gives the same.
#[test]
fn texread_modes_agree_with_the_reference() {
    let (d, t, c) = encoded("modes");
    let tex = Ccc::read(&c).unwrap();
    let r = d.join("r.csv");
    std::fs::write(
        &r,
        "u,v,newline\n0,0,1\n1.5,2.25,0\n31.9375,15.5,0\n3.03,3.97,1\n",
    )
    .unwrap();
    let (out, stats, vcd) = (d.join("o.csv"), d.join("s.json"), d.join("w.vcd"));
    let mut outs = Vec::new();
    for extra in [
        vec![],
        vec!["--no-cache"],
        vec!["--no-lookahead", "--layout", "tiled"],
        vec!["--interval", "5"],
    ] {
        let (st, w) = (s(&stats), s(&vcd));
        let mut a = vec!["--stats", &st, "--vcd", &w];
        a.extend(extra);
        let o = texread(&c, &r, &out, &a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        outs.push(std::fs::read_to_string(&out).unwrap());
        let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
        for k in [
            "hits",
            "page_faults",
            "cycles",
            "ns",
            "pixels_per_second",
            "dram_reads",
        ] {
            assert!(j.get(k).is_some(), "{k}");
        }
        assert_eq!(j["requests"], 4);
    }
    assert!(outs.iter().all(|o| *o == outs[0]), "modes differ");
    let rows: Vec<&str> = outs[0].lines().collect();
    assert_eq!(rows[0], "u,v,r,g,b");
    assert_eq!(rows.len(), 5);
    // 3.03 and 3.97 are rounded to sixteenths; the results equal the integer reference.
    assert!(
        rows[4].starts_with("3,4,") || rows[4].starts_with("3.0625,3.9375,"),
        "{}",
        rows[4]
    );
    for (row, (u, v)) in rows[1..]
        .iter()
        .zip([(0, 0), (24, 36), (511, 248), (48, 64)])
    {
        let f: Vec<u32> = row.split(',').skip(2).map(|x| x.parse().unwrap()).collect();
        let want = reference_filter(&tex, u, v, 4);
        assert_eq!(f, vec![want >> 16, want >> 8 & 0xff, want & 0xff], "{row}");
    }
    check_texread_waveform(&vcd);
    // A PPM texture is encoded on the fly: the same results as its .ccc.
    let o = texread(&t, &r, &out, &[]);
    assert!(o.status.success());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), outs[0]);
}

/// The waveform of `texread --vcd`: DRAM pins, page register, cache tags and valid bits,
/// controller states.
fn check_texread_waveform(vcd: &std::path::Path) {
    let rb = waves::check::read_vcd(vcd).unwrap();
    for v in [
        "tb.texture_unit_602.control_607.dram_604.ras_n",
        "tb.texture_unit_602.control_607.dram_604.cas_n",
        "tb.texture_unit_602.control_607.dram_604.addr",
        "tb.texture_unit_602.control_607.dram_604.page_row",
        "tb.texture_unit_602.control_607.state",
        "tb.texture_unit_602.fill_engine_607.state",
        "tb.texture_unit_602.cache_614.entry_a.tag_x",
        "tb.texture_unit_602.cache_614.entry_d.valid",
        "tb.texture_unit_602.ccc_decode_608.reg_608",
        "tb.texture_unit_602.bilinear_622.rgb",
    ] {
        assert!(
            rb.vars.contains_key(v),
            "{v}: {:?}",
            rb.vars.keys().take(60).collect::<Vec<_>>()
        );
    }
    assert_eq!(
        rb.vars["tb.texture_unit_602.ccc_decode_608.reg_608"].width,
        Some(32)
    );
    waves::check::check_gtkw(vcd, &rb).unwrap();
}

/// Bad input: one line naming the file, exit 2, nothing written.
#[test]
fn texread_refuses_bad_textures_and_requests() {
    let (d, _, c) = encoded("bad");
    let r = d.join("r.csv");
    let bad_out = d.join("bad.csv");
    let good = std::fs::read(&c).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str, &str)> = vec![
        (
            "trunc.ccc",
            good[..good.len() - 3].to_vec(),
            "u,v\n1,1\n",
            "truncated",
        ),
        (
            "magic.ccc",
            b"XEXRTLCC0000000000000000".to_vec(),
            "u,v\n1,1\n",
            "neither",
        ),
        (
            "odd.ppm",
            {
                let mut b = b"P6\n6 4\n255\n".to_vec();
                b.extend(vec![0u8; 72]);
                b
            },
            "u,v\n1,1\n",
            "multiples of 4",
        ),
        (
            "short.ppm",
            b"P6\n8 4\n255\n\0\0".to_vec(),
            "u,v\n1,1\n",
            "raster",
        ),
        ("t.ccc", good.clone(), "u,v\n32,1\n", "outside"),
        ("t.ccc", good.clone(), "u,v\nNaN,1\n", "NaN"),
        ("t.ccc", good.clone(), "x,y\n1,1\n", "header"),
        ("t.ccc", good.clone(), "u,v,newline\n1,1,2\n", "newline"),
        ("t.ccc", good.clone(), "u,v\n1\n", "fields"),
    ];
    for (name, bytes, req, needle) in cases {
        let tp = d.join(format!("bad-{name}"));
        std::fs::write(&tp, &bytes).unwrap();
        std::fs::write(&r, req).unwrap();
        let o = texread(&tp, &r, &bad_out, &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains(needle) && err.trim_end().lines().count() == 1,
            "{needle}: {err}"
        );
        assert!(!bad_out.exists(), "{name}");
    }
}

/// texread's bad-output reproducers: every output checked before any work (a missing folder
/// for the second output left the first behind), outputs distinct from each other and from
/// the inputs, and a bad --lookahead refused even beside --no-lookahead. Each exits 2 with
/// one line naming the option, and leaves no file.
#[test]
fn texread_checks_every_output_before_any_work() {
    let (d, _, c) = encoded("outs");
    let r = d.join("r.csv");
    std::fs::write(&r, "u,v\n1,1\n2,2\n").unwrap();
    let out = d.join("o.csv");
    let (st, nodir) = (s(&out), s(&d.join("nodir").join("s.json")));
    let cases: Vec<(std::path::PathBuf, Vec<&str>, &str)> = vec![
        (out.clone(), vec!["--stats", &nodir], "--stats"),
        (out.clone(), vec!["--vcd", &nodir], "--vcd"),
        (
            out.clone(),
            vec!["--stats", &st],
            "the same file as the output --out",
        ),
        (r.clone(), vec![], "the same file as the input --requests"),
        (c.clone(), vec![], "the same file as the input --texture"),
        (
            out.clone(),
            vec!["--no-lookahead", "--lookahead", "bogus"],
            "--lookahead bogus",
        ),
        (
            out.clone(),
            vec!["--no-lookahead", "--lookahead", "direction"],
            "choose one",
        ),
    ];
    let texture = std::fs::read(&c).unwrap();
    for (o_path, extra, needle) in cases {
        let o = texread(&c, &r, &o_path, &extra);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(
            err.contains(needle) && err.trim_end().lines().count() == 1,
            "{needle}: {err}"
        );
        assert!(!out.exists(), "{extra:?} left {}", out.display());
        assert_eq!(
            std::fs::read(&r).unwrap(),
            b"u,v\n1,1\n2,2\n",
            "requests kept"
        );
        assert_eq!(std::fs::read(&c).unwrap(), texture, "texture kept");
    }
}

/// A texture beyond the DRAM is refused until the larger part is chosen; bad options and a
/// non-CCC file given to `ccc decode` are refused.
#[test]
fn texread_sizes_and_options() {
    let (d, t, c) = encoded("big");
    let r = d.join("r.csv");
    let bad_out = d.join("bad.csv");
    // A texture beyond the DRAM: 2048 x 2048 needs 512K words; the 1M x 16 part holds it.
    let big = d.join("big.ccc");
    std::fs::write(&big, tb::texture::test_pattern(2048, 2048).to_bytes()).unwrap();
    std::fs::write(&r, "u,v\n2047.5,1\n").unwrap();
    let o = texread(&big, &r, &bad_out, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("big.ccc") && err.contains("the DRAM has 262144"),
        "{err}"
    );
    assert!(!bad_out.exists());
    for bad in [
        &["--frac-bits", "9"][..],
        &["--interval", "0"],
        &["--lookahead", "sideways"],
        &["--dram", "2m"],
    ] {
        let o = texread(&big, &r, &bad_out, bad);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        assert!(!bad_out.exists());
    }
    let o = texread(&big, &r, &bad_out, &["--dram", "1m"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::remove_file(&bad_out).unwrap();

    let o = texrtl(&["ccc", "decode", "--in", &s(&t), "--out", &s(&bad_out)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("magic"));
    let o = texread(&c, &r, &bad_out, &["--layout", "zigzag"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!bad_out.exists());
}

/// Every field of `texread --stats` is documented in `texrtl texread --help` and in the
/// documented table, and `--frac-bits 0` names the option.
#[test]
fn every_stats_field_is_documented() {
    let s = serde_json::to_value(
        tb::runs::texture::run_texread(
            &tb::texture::test_pattern(16, 16),
            units::texmem::texture_unit_602::TexParams::new(16, 16),
            &[],
            1,
            None,
        )
        .unwrap()
        .stats,
    )
    .unwrap();
    let help = texrtl(&["texread", "--help"]);
    let help = String::from_utf8_lossy(&help.stdout);
    let readme = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../hdl/units/src/texmem/mod.rs"
    ))
    .unwrap();
    let fields = s.as_object().unwrap();
    assert_eq!(fields.len(), 29);
    for k in fields.keys() {
        assert!(
            help.lines().any(|l| l.trim_start().starts_with(k.as_str())),
            "--help lacks {k}"
        );
        assert!(
            readme.contains(&format!("`{k}`")),
            "the texmem docs lack {k}"
        );
    }
    let d = dir("frac-bits-message");
    let t = d.join("t.ccc");
    std::fs::write(&t, tb::texture::test_pattern(16, 16).to_bytes()).unwrap();
    let r = d.join("r.csv");
    std::fs::write(&r, "u,v\n1,1\n").unwrap();
    let s = |p: &std::path::Path| p.to_string_lossy().into_owned();
    let o = texrtl(&[
        "texread",
        "--texture",
        &s(&t),
        "--requests",
        &s(&r),
        "--out",
        &s(&d.join("o.csv")),
        "--frac-bits",
        "0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim(),
        "texrtl: --frac-bits 0: 1..=8"
    );
}

/// A waveform that cannot be written is bad output naming `--vcd` (exit 2, one line), and
/// leaves no result behind.
#[cfg(target_os = "linux")]
#[test]
fn texread_refuses_a_waveform_that_cannot_be_written() {
    let (d, _, c) = encoded("vcd_full");
    let r = d.join("r.csv");
    std::fs::write(&r, "u,v\n1,1\n2,2\n").unwrap();
    let (c, r, o) = (s(&c), s(&r), s(&d.join("o.csv")));
    let io = ["--texture", &c, "--requests", &r, "--out", &o];
    common::assert_vcd_full_refused("texread", &io, &d);
}
