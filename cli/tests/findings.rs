//! Bad input that once went wrong, each reproduced as it was found by the black-box fuzz
//! campaign: now exit 0 with correct output, or exit 2 with one line naming the option or
//! file, leaving no file behind and removing none.

mod common;
use common::{dir, ran, s, small_shard, texrtl};
use std::path::{Path, PathBuf};

/// An 8x6x5 volume of `fill` and a CSV holding `ray` (three times over when `thrice`).
fn volume_inputs(d: &Path, fill: u8, ray: &str, thrice: bool) -> (PathBuf, PathBuf) {
    let raw = d.join("v.raw");
    std::fs::write(&raw, [fill; 240]).unwrap();
    let rays = d.join("r.csv");
    let n = if thrice { 3 } else { 1 };
    std::fs::write(
        &rays,
        format!("x0,y0,z0,dx,dy,dz,steps\n{}", format!("{ray}\n").repeat(n)),
    )
    .unwrap();
    (raw, rays)
}

/// `volume` on them, without its output.
fn volume_args<'a>(raw: &'a Path, rays: &'a Path) -> Vec<&'a str> {
    vec![
        "volume",
        "--volume",
        s(raw),
        "--dims",
        "8,6,5",
        "--rays",
        s(rays),
    ]
}

/// An 8x8 PGM ramp.
fn texture(d: &Path) -> PathBuf {
    let mut pgm = b"P5\n8 8\n255\n".to_vec();
    pgm.extend(0..64u8);
    let tex = d.join("t.pgm");
    std::fs::write(&tex, &pgm).unwrap();
    tex
}

/// A valid long ray whose stepper would leave its 32-bit range is refused at validation,
/// naming the file's row (it panicked in the model); the same ray, shorter, runs.
#[test]
fn a_ray_leaving_the_stepper_range_is_refused_not_a_panic() {
    let d = dir("findings", "ray");
    let (raw, rays) = volume_inputs(&d, 0, "0,0,0,511,0,0,1100", false);
    let o = d.join("o.csv");
    let args = [volume_args(&raw, &rays), vec!["--out", s(&o)]].concat();
    let out = texrtl(&args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("r.csv") && err.contains("steps 1100"), "{err}");
    assert!(!o.exists());
    // 1024 samples of 511: the position after the last, 523264 voxels, is inside (< 2^19).
    volume_inputs(&d, 0, "0,0,0,511,0,0,1024", false);
    ran(&args);
    assert_eq!(
        std::fs::read_to_string(&o).unwrap().lines().count(),
        1 + 1024
    );
}

/// `vectors --out` naming a file that exists (or a dangling link) is refused and the file
/// stays (it was removed).
#[test]
fn vectors_keeps_a_file_it_refuses_to_write_into() {
    let d = dir("findings", "vectors");
    let f = d.join("vd");
    std::fs::write(&f, "precious\n").unwrap();
    let link = d.join("dangling");
    std::os::unix::fs::symlink(d.join("nowhere"), &link).unwrap();
    for out in [&f, &link] {
        let o = texrtl(&["vectors", "--unit", "blend_adjust_153", "--out", s(out)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("exists and is not a directory"), "{err}");
    }
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "precious\n");
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
}

/// A waveform written to `/dev/stdout` (redirected into a file) or through any link gets no
/// `.gtkw` or state filter beside the name given: side files go beside a regular file named
/// as given, never into /dev.
#[test]
fn no_side_files_beside_dev_stdout_or_a_link() {
    let d = dir("findings", "stdout");
    let mut pgm = b"P5\n4 3\n255\n".to_vec();
    pgm.extend((0..12u8).map(|k| k * 20));
    std::fs::write(d.join("h.pgm"), &pgm).unwrap();
    std::fs::write(d.join("c.csv"), "u,v\n0,0\n1.5,2.25\n").unwrap();
    let run = |vcd: &str, stdout: std::process::Stdio| {
        std::process::Command::new(env!("CARGO_BIN_EXE_texrtl"))
            .args([
                "normals",
                "--height",
                s(&d.join("h.pgm")),
                "--coords",
                s(&d.join("c.csv")),
            ])
            .args(["--out", s(&d.join("n.csv")), "--vcd", vcd])
            .stdout(stdout)
            .output()
            .unwrap()
    };
    let w = std::fs::File::create(d.join("w.vcd")).unwrap();
    let o = run("/dev/stdout", w.into());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read_to_string(d.join("w.vcd"))
        .unwrap()
        .contains("$enddefinitions"));
    let in_dev: Vec<String> = std::fs::read_dir("/dev")
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("stdout."))
        .collect();
    assert!(in_dev.is_empty(), "written into /dev: {in_dev:?}");
    std::fs::create_dir_all(d.join("real")).unwrap();
    std::fs::write(d.join("real/t.vcd"), "").unwrap();
    std::os::unix::fs::symlink(d.join("real/t.vcd"), d.join("link.vcd")).unwrap();
    let o = run(s(&d.join("link.vcd")), std::process::Stdio::null());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read_to_string(d.join("real/t.vcd"))
        .unwrap()
        .contains("$enddefinitions"));
    for f in [d.join("link.gtkw"), d.join("real/t.gtkw")] {
        assert!(!f.exists(), "{} written", f.display());
    }
}

/// A face corner with more than three indices is refused, naming the corner.
#[test]
fn an_obj_corner_has_at_most_three_indices() {
    let d = dir("findings", "obj");
    let obj = d.join("m.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1/1 2/2/1/7 3/3/1/x\n",
    )
    .unwrap();
    let o = d.join("t.csv");
    let out = texrtl(&["tangents", "--mesh", s(&obj), "--out", s(&o)]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("m.obj") && err.contains("at most three"),
        "{err}"
    );
    assert!(!o.exists());
}

/// The volume size limit is the one the help states and the error names.
#[test]
fn the_volume_limit_is_stated_once() {
    let room = units::volume::layout::bank_room();
    let help = String::from_utf8_lossy(&texrtl(&["volume", "--help"]).stdout).into_owned();
    let stated = format!("at most {}", group(room));
    assert!(help.contains(&stated), "{stated} not in the help:\n{help}");
    let d = dir("findings", "limit");
    // 18 x 244 x 255: 279,990 words a bank, inside; one slice more is over.
    for (z, ok) in [
        (255u64, 9 * 122 * 255 <= room),
        (256, 9 * 122 * 256 <= room),
    ] {
        let dims = format!("18,244,{z}");
        let raw = d.join("v.raw");
        std::fs::write(&raw, vec![0u8; (18 * 244 * z) as usize]).unwrap();
        let rays = d.join("r.csv");
        std::fs::write(&rays, "x0,y0,z0,dx,dy,dz,steps\n1,1,1,0,0,1,2\n").unwrap();
        let out = texrtl(&[
            "volume",
            "--volume",
            s(&raw),
            "--dims",
            &dims,
            "--rays",
            s(&rays),
            "--out",
            s(&d.join("o.csv")),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.success(), ok, "{dims}: {err}");
        if !ok {
            assert!(err.contains(&format!("hold {room}")), "{err}");
        }
    }
}

fn group(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// A long option value is shortened in the message, and a newline in a file name is shown
/// escaped: every message stays one line.
#[test]
fn messages_stay_one_short_line() {
    let long = "u".repeat(5000);
    let out = texrtl(&["vectors", "--unit", &long, "--out", "/tmp"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.len() < 400, "{} characters", err.len());
    let out = texrtl(&[
        "tangents",
        "--mesh",
        "/tmp/no\nsuch.obj",
        "--out",
        "/tmp/texrtl-findings-t.csv",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("no\\nsuch.obj"), "{err}");
}

/// A tile border, which only a map chain's detail maps have, is refused by the commands
/// whose help lists wrap, clamp, mirror and border:N (it failed inside, or passed by chance).
#[test]
fn texram_and_footprint_refuse_a_tile_border() {
    let d = dir("findings", "tile");
    let tex = texture(&d);
    let texram_reqs = d.join("tr.csv");
    std::fs::write(&texram_reqs, "u,v,lambda\n1.5,2.5,0\n").unwrap();
    let fp_reqs = d.join("fr.csv");
    std::fs::write(&fp_reqs, "u,v,dudx,dvdx,dudy,dvdy\n1.5,2.5,1,0,0,1\n").unwrap();
    for tile in ["tile:0", "tile:4"] {
        for (cmd, reqs) in [("texram", &texram_reqs), ("footprint", &fp_reqs)] {
            let o = d.join("o.csv");
            let args = [
                cmd,
                "--texture",
                s(&tex),
                "--requests",
                s(reqs),
                "--out",
                s(&o),
                "--border",
                tile,
            ];
            common::assert_refused(&args, &format!("--border {tile}"), &d, &["o.csv"]);
        }
    }
}

/// A waveform that cannot be written is bad output naming `--vcd` (exit 2), in every command
/// that writes one (footprint and volume said exit 1 and named only the file).
#[test]
fn an_unwritable_waveform_names_vcd() {
    let d = dir("findings", "full");
    let (raw, rays) = volume_inputs(&d, 0, "0,0,0,1,0,0,3", false);
    let tex = texture(&d);
    let reqs = d.join("fr.csv");
    std::fs::write(&reqs, "u,v,dudx,dvdx,dudy,dvdy\n1.5,2.5,1,0,0,1\n").unwrap();
    let o = d.join("o.csv");
    let fp = vec!["footprint", "--texture", s(&tex), "--requests", s(&reqs)];
    for cmd in [volume_args(&raw, &rays), fp] {
        let args = [cmd, vec!["--out", s(&o), "--vcd", "/dev/full"]].concat();
        common::assert_refused(
            &args,
            "--vcd /dev/full: No space left on device",
            &d,
            &["o.csv"],
        );
    }
}

/// A render whose panels would outgrow 1024x1024 pixels is refused at once (32x32 at zoom 64
/// ran past 10 s and 860 MB); 32x32 at zoom 32 is the largest and runs.
#[test]
fn render_bounds_the_picture() {
    let d = dir("findings", "render");
    let mut pgm = b"P5\n32 32\n255\n".to_vec();
    pgm.extend((0..1024u32).map(|k| (k * 7 % 256) as u8));
    let h = d.join("m.pgm");
    std::fs::write(&h, &pgm).unwrap();
    let o = d.join("r.png");
    let t0 = std::time::Instant::now();
    common::assert_refused(
        &["render", "--height", s(&h), "--out", s(&o), "--zoom", "64"],
        "1024x1024 at most",
        &d,
        &["r.png"],
    );
    assert!(
        t0.elapsed().as_secs() < 5,
        "refused only after {:?}",
        t0.elapsed()
    );
}

/// Lights at a tiny elevation inside the documented (0, 90]: the occlusion march is bounded
/// (it ran for minutes at 1e-300 degrees), so the fit ends in a second or two.
#[test]
fn ptm_fit_at_grazing_elevations_ends() {
    let d = dir("findings", "ptm");
    let mut pgm = b"P5\n32 32\n255\n".to_vec();
    pgm.extend((0..1024u32).map(|k| ((k % 32) * 37 + (k / 32) * 91) as u8));
    let h = d.join("h.pgm");
    std::fs::write(&h, &pgm).unwrap();
    let lights = d.join("l.csv");
    std::fs::write(
        &lights,
        "elevation,azimuth\n1e-300,0\n1e-300,90\n1e-300,180\n45,0\n45,120\n45,240\n",
    )
    .unwrap();
    let t0 = std::time::Instant::now();
    ran(&[
        "ptm",
        "fit",
        "--height",
        s(&h),
        "--lights",
        s(&lights),
        "--out",
        s(&d.join("p.ptm")),
    ]);
    assert!(t0.elapsed().as_secs() < 10, "{:?}", t0.elapsed());
    assert!(d.join("p.ptm").is_file());
}

/// A moving ray costs what a standing one does, sample for sample (the reference mirrored a
/// coordinate far outside the volume step by step: quadratic in the samples).
#[test]
fn a_moving_ray_is_as_cheap_as_a_standing_one() {
    let d = dir("findings", "moving");
    let o = d.join("o.csv");
    let time = |ray: &str| {
        let (raw, rays) = volume_inputs(&d, 7, ray, true);
        let t0 = std::time::Instant::now();
        ran(&[volume_args(&raw, &rays), vec!["--out", s(&o)]].concat());
        t0.elapsed().as_secs_f64()
    };
    let still = time("1,1,1,0,0,0,65535");
    let moving = time("1,1,1,0.5,0,0,65535");
    assert!(
        moving < 3.0 * still + 1.0,
        "moving {moving:.2} s, standing {still:.2} s"
    );
}

/// An endless device given as an input file is refused at the size limit, not read forever
/// (`render --height /dev/zero` never ended).
#[test]
fn an_endless_input_is_refused() {
    let d = dir("findings", "zero");
    for (cmd, opt) in [
        ("render", "--height"),
        ("tangents", "--mesh"),
        ("ccc", "--in"),
    ] {
        let o = d.join("o.out");
        let words: Vec<&str> = if cmd == "ccc" {
            vec!["ccc", "decode"]
        } else {
            vec![cmd]
        };
        let args = [words, vec![opt, "/dev/zero", "--out", s(&o)]].concat();
        let t0 = std::time::Instant::now();
        common::assert_refused(&args, "/dev/zero: longer than", &d, &["o.out"]);
        assert!(t0.elapsed().as_secs() < 10, "{cmd}: {:?}", t0.elapsed());
    }
    // Beside valid inputs (`texread --texture /dev/zero` was read until memory ran out).
    let reqs = d.join("r.csv");
    std::fs::write(&reqs, "u,v\n1,1\n").unwrap();
    let mut pgm = b"P5\n16 16\n255\n".to_vec();
    pgm.extend([7u8; 256]);
    std::fs::write(d.join("t.pgm"), &pgm).unwrap();
    let maps = d.join("m.json");
    let drf = r#"{"drfs": [{"drf": 0, "kind": "texture", "maps": ["t.pgm"]}]}"#;
    std::fs::write(&maps, drf).unwrap();
    let o = d.join("o.out");
    let (r, m, o) = (s(&reqs), s(&maps), s(&o));
    let beside: [&[&str]; 2] = [
        &[
            "texread",
            "--texture",
            "/dev/zero",
            "--requests",
            r,
            "--out",
            o,
        ],
        &[
            "mapchain",
            "--maps",
            m,
            "--requests",
            "/dev/zero",
            "--out",
            o,
        ],
    ];
    for args in beside {
        let t0 = std::time::Instant::now();
        common::assert_refused(args, "/dev/zero: longer than", &d, &["o.out"]);
        assert!(t0.elapsed().as_secs() < 10, "{args:?}: {:?}", t0.elapsed());
    }
}

/// A folder output below a file, or one the system will not make, is refused before any work
/// (no seed line, no simulator started) in one line naming the option and the file in the
/// way; nothing is made and the file stays.
#[test]
fn a_folder_output_that_cannot_be_made_is_one_line_naming_the_option() {
    let d = dir("findings", "folder");
    let f = d.join("notes");
    std::fs::write(&f, "precious\n").unwrap();
    let (under, merged) = (f.join("x"), d.join("m.json"));
    let (u, m) = (s(&under), s(&merged));
    let in_the_way = "notes is not a directory";
    let runs: [(&[&str], &str, &str); 6] = [
        (&["regress", "--no-cosim", "--out", u], "--out", in_the_way),
        (
            &["regress", "--out", "/proc/texrtl-none/x"],
            "--out",
            "cannot make the folder",
        ),
        (
            &["cosim", "--unit", "blend_adjust_153", "--out", u],
            "--out",
            in_the_way,
        ),
        (
            &["vectors", "--unit", "blend_adjust_153", "--out", u],
            "--out",
            in_the_way,
        ),
        (&["new", "my_unit", "--dir", u], "--dir", in_the_way),
        (
            &["merge", "--out", m, "--report", u, "s.json"],
            "--report",
            in_the_way,
        ),
    ];
    for (args, opt, why) in runs {
        let o = texrtl(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.contains(&format!("{opt} ")) && err.contains(why),
            "{args:?}: {err}"
        );
    }
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "precious\n");
    let left: Vec<_> = std::fs::read_dir(&d).unwrap().collect();
    assert_eq!(left.len(), 1, "{left:?}");
}

/// Verilog that does not build is bad input: one line naming the simulator, exit 2, and the
/// co-simulation folder it had begun (given or the default one under `target/`) goes, with
/// the parents made for it. `--rtl` naming a folder or a device says so.
#[test]
fn rtl_that_does_not_build_leaves_no_folder() {
    if !common::simulator("iverilog", "-V") {
        return;
    }
    let d = dir("findings", "rtl");
    std::fs::write(d.join("bad.v"), "module blend_adjust_153(; endmodule\n").unwrap();
    let base = ["cosim", "--unit", "blend_adjust_153", "--sim", "icarus"];
    for extra in [
        &["--rtl", "bad.v"][..],
        &["--rtl", "bad.v", "--out", "runs/a"],
    ] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_texrtl"))
            .args(base)
            .args(extra)
            .current_dir(&d)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("iverilog"), "{err}");
        let left: Vec<_> = std::fs::read_dir(&d).unwrap().flatten().collect();
        assert_eq!(left.len(), 1, "{extra:?}: {left:?}");
    }
    for (rtl, why) in [(s(&d), "not a regular file"), ("none.v", "no such file")] {
        let args = [&base[..], &["--rtl", rtl]].concat();
        common::assert_refused(&args, why, &d, &["target"]);
    }
}

/// Verilog whose top is not the model's interface is refused by port before any value is
/// compared: a port of another width (found as differing values, it hid its cause), a port
/// the model lacks (a floating input is x in Icarus and 0 in Verilator; it passed), and a
/// parameter it lacks (Icarus warned and built the default configuration; it passed).
#[test]
fn rtl_whose_ports_are_not_the_models_is_refused_by_port() {
    let rtl = include_str!("../../rtl/bump/blend_adjust_153.v");
    let (bypass, u1) = ("wire                 bypass,", "wire [FRAC_BITS:0]   u1,");
    let narrow = rtl.replace(u1, "wire [FRAC_BITS-1:0] u1,");
    let extra = rtl.replace(bypass, &format!("{bypass} input wire scan_en,"));
    let renamed = rtl.replace("REGISTERED", "STAGES");
    assert!(
        narrow != rtl && extra != rtl && renamed != rtl,
        "the twin moved"
    );
    for sim in common::simulators() {
        let d = dir("findings", &format!("ports-{sim}"));
        for (file, text, needle) in [
            (
                "narrow.v",
                &narrow,
                "narrow.v): port u1 is 8 bits in the RTL, 9 in the model",
            ),
            ("extra.v", &extra, "scan_en"),
            ("renamed.v", &renamed, "REGISTERED"),
        ] {
            let (v, out) = (d.join(file), d.join("run"));
            std::fs::write(&v, text).unwrap();
            let unit = ["cosim", "--unit", "blend_adjust_153", "--count", "200"];
            let args = [&unit[..], &["--sim", sim, "--rtl", s(&v), "--out", s(&out)]].concat();
            common::assert_refused(&args, needle, &d, &["run"]);
        }
    }
}

/// Verilog that leaves a register out of its reset differs from the model, which resets it,
/// in both simulators: Icarus starts the register at x, and Verilator (whose default is zero,
/// the reset value here, so that it passed) now starts it at random. The waveform then shows
/// the RTL's internals around the difference, the register among them, sampled as the ports
/// are: the top's own copies of its ports equal the compared RTL outputs and the inputs in
/// every cycle dumped.
#[test]
fn a_register_left_out_of_reset_is_a_difference_in_both_simulators() {
    let rtl = include_str!("../../rtl/bump/blend_adjust_153.v");
    let unreset = rtl.replace("u0_r    <= {(FRAC_BITS + 1){1'b0}};", "");
    assert_ne!(unreset, rtl, "the twin's reset moved");
    for sim in common::simulators() {
        let d = dir("findings", &format!("unreset-{sim}"));
        let v = d.join("unreset.v");
        std::fs::write(&v, &unreset).unwrap();
        let unit = ["cosim", "--unit", "blend_adjust_153", "--count", "200"];
        let o = texrtl(
            &[
                &unit[..],
                &["--sim", sim, "--rtl", s(&v), "--out", s(&d.join("run"))],
            ]
            .concat(),
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{sim}: {err}");
        assert!(
            err.contains("the first at cycle 1 on port u0"),
            "{sim}: {err}"
        );
        let said = String::from_utf8_lossy(&o.stdout);
        assert!(
            said.contains("under tb.rtl_internals, cycles 0..22; the model's, 14 signals, under tb.model_internals"),
            "{sim}: {said}"
        );
        let vcd = d.join("run/blend_adjust_153_cosim.vcd");
        let rb = waves::check::read_vcd(&vcd).unwrap();
        waves::check::check_gtkw(&vcd, &rb).unwrap();
        let at = |n: &str, c: u64| match rb.value_at(n, c * 10_000) {
            Some(waves::check::Value::Bits(b)) => b.clone(),
            v => panic!("{sim}: {n}: {v:?}"),
        };
        let num = |b: String| u64::from_str_radix(b.trim_start_matches('0'), 2).unwrap_or(0);
        for c in 0..22 {
            for p in ["u0", "u1", "v0", "v1", "valid"] {
                let (inner, outer) = (format!("tb.rtl_internals.{p}"), format!("tb.rtl.{p}"));
                assert_eq!(at(&inner, c), at(&outer, c), "{sim}: {p} in cycle {c}");
            }
            for p in ["u_in", "v_in", "bypass", "valid_in"] {
                let (inner, input) = (format!("tb.rtl_internals.{p}"), format!("tb.inputs.{p}"));
                assert_eq!(num(at(&inner, c)), num(at(&input, c)), "{sim}: {p} in {c}");
            }
        }
        // The model's internals over the same cycles: its ports as compared, and the
        // register the RTL left out of reset, reset.
        for c in 0..22 {
            for p in ["u0", "u1", "v0", "v1", "valid"] {
                let (inner, outer) = (format!("tb.model_internals.{p}"), format!("tb.model.{p}"));
                assert_eq!(
                    at(&inner, c),
                    at(&outer, c),
                    "{sim}: model {p} in cycle {c}"
                );
            }
        }
        assert_eq!(
            num(at("tb.model_internals.u0_r", 1)),
            0,
            "{sim}: reset in the model"
        );
        let reg = at("tb.rtl_internals.g_reg.u0_r", 1);
        if sim == "icarus" {
            assert!(reg.contains('x'), "never reset: {reg}");
        }
        assert_eq!(reg, at("tb.rtl.u0", 1), "{sim}: the register is the port");
    }
}

/// A shard whose coverage model is not the testbench's (a coverpoint renamed) is named by
/// its file: with a hundred shards, "coverpoint 'x' differs between the models" alone does
/// not say which summary to look at. A merge that fails leaves none of its outputs.
#[test]
fn merge_names_the_summary_whose_model_differs() {
    let d = dir("findings", "merge-model");
    let (a, b) = (small_shard(1, &d.join("s1")), small_shard(2, &d.join("s2")));
    // A report that cannot be written takes the merged summary written before it with it.
    let m = d.join("m.json");
    let o = texrtl(&[
        "merge",
        "--out",
        s(&m),
        "--report",
        "/proc/texrtl-none/r",
        s(&a),
        s(&b),
    ]);
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(!m.exists(), "the summary was left behind");
    let mut j: serde_json::Value = serde_json::from_slice(&std::fs::read(&b).unwrap()).unwrap();
    j["jobs"][0]["result"]["coverage"]["points"][0]["name"] = "renamed".into();
    std::fs::write(&b, serde_json::to_vec(&j).unwrap()).unwrap();
    let o = texrtl(&["merge", "--out", s(&m), s(&a), s(&b)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains(&format!("{}: blend_adjust_153", b.display())) && err.contains("differs"),
        "{err}"
    );
    assert!(!m.exists());
}

/// Shards run one after another into one `--out` (a loop in a job script) kept only the last
/// shard's summary: the merge then found the others missing, their results gone. A shard now
/// refuses a folder holding another shard's summary of the same run, naming a folder of its
/// own, and leaves that summary whole; the same shard again (a task run anew) may overwrite its
/// own, and another run's summary is simply replaced.
#[test]
fn a_shard_does_not_overwrite_another_shards_summary() {
    let d = dir("findings", "shard-folder");
    let out = d.join("out");
    let first = small_shard(1, &out);
    let kept = std::fs::read(&first).unwrap();
    let args = common::small_shard_args("2/2", &out);
    let o = texrtl(&args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains("--out") && err.contains("shard 1/2 of this run") && err.contains("/out/2)"),
        "{err}"
    );
    assert_eq!(
        std::fs::read(&first).unwrap(),
        kept,
        "shard 1's summary is whole"
    );
    small_shard(1, &out); // the same shard again
    let other_seed = [&args[..], &["--seed", "7"]].concat();
    assert!(texrtl(&other_seed).status.code().is_some_and(|c| c <= 1));
}
