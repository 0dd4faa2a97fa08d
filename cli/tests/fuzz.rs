//! Fuzzing every command's front end, as a user meets it: the program run on a valid input
//! file with up to eight byte-level mutations ([`verif::mutate`]), and on valid arguments with
//! one option's value replaced (numbers at and past their limits, junk, long values, control
//! characters), under a 2 GiB address-space limit (an allocation by a declared size aborts
//! there) and a time bound (a slow path is a failure). Every run must exit 0, or 2 with one
//! line and no new file (1 only where a check can fail); never a panic (101) or an abort
//! (134). Seeds are printed; replay with `TEXRTL_SEED`. `TEXRTL_FUZZ_CASES=N` runs N cases a
//! front end (a campaign; the default is what `cargo test` runs).

mod common;

use proptest::test_runner::TestCaseError;
use std::path::Path;
use std::process::Command;
use verif::mutate::{mutated, mutations};

/// Runs per command in `cargo test` (each is a process; a campaign sets
/// `TEXRTL_FUZZ_CASES`).
fn cases() -> u32 {
    std::env::var("TEXRTL_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40)
}

/// Seconds one case may take (the program is killed at twice its CPU time).
const CASE_SECONDS: u64 = 10;

fn dir(name: &str) -> common::TestDir {
    common::dir("fuzz", name)
}

fn names(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// One command with its input files: `{NAME}` in an argument is the path of file NAME in the
/// case's folder, `{out}` a path for an output there.
struct Front {
    name: &'static str,
    args: &'static [&'static str],
    files: Vec<(&'static str, Vec<u8>)>,
}

fn pgm() -> Vec<u8> {
    let px: Vec<u8> = (0..64u8).map(|k| k.wrapping_mul(29)).collect();
    formats::netpbm::encode(8, 8, &px)
}

fn ppm() -> Vec<u8> {
    let rgb: Vec<u8> = (0..16 * 16 * 3).map(|k| (k * 7 % 256) as u8).collect();
    formats::netpbm::encode_ppm(16, 16, &rgb)
}

/// The TEXRAM front ends.
fn texram_fronts() -> Vec<Front> {
    vec![
        Front {
            name: "volume",
            args: &[
                "volume",
                "--volume",
                "{v.raw}",
                "--dims",
                "4,2,3",
                "--rays",
                "{r.csv}",
                "--out",
                "{out}.csv",
                "--stats",
                "{out}.json",
            ],
            files: vec![
                ("v.raw", (0..24u8).map(|k| k.wrapping_mul(37)).collect()),
                (
                    "r.csv",
                    b"x0,y0,z0,dx,dy,dz,steps\n1,0.5,1,0.25,0,0.5,3\n".to_vec(),
                ),
            ],
        },
        Front {
            name: "texram",
            args: &[
                "texram",
                "--texture",
                "{h.pgm}",
                "--requests",
                "{q.csv}",
                "--out",
                "{out}.csv",
                "--stats",
                "{out}.json",
            ],
            files: vec![
                ("h.pgm", pgm()),
                ("q.csv", b"u,v,lambda\n1.5,2,0.5\n-3,9,2\n".to_vec()),
            ],
        },
        Front {
            name: "footprint",
            args: &[
                "footprint",
                "--texture",
                "{h.pgm}",
                "--requests",
                "{f.csv}",
                "--out",
                "{out}.csv",
                "--stats",
                "{out}.json",
            ],
            files: vec![
                ("h.pgm", pgm()),
                (
                    "f.csv",
                    b"u,v,dudx,dvdx,dudy,dvdy\n1.5,2,4,0.5,-0.25,1\n-3,9,0,0,0,0\n".to_vec(),
                ),
            ],
        },
    ]
}

/// The map chain, PTM and tangent front ends.
fn later_fronts() -> Vec<Front> {
    vec![
        Front {
            name: "mapchain",
            args: &[
                "mapchain",
                "--maps",
                "{m.json}",
                "--requests",
                "{r.csv}",
                "--out",
                "{out}.csv",
                "--stats",
                "{out}.json",
            ],
            files: vec![
                (
                    "m.json",
                    br#"{"drfs": [{"drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 1},
 {"drf": 1, "kind": "offset", "maps": ["t.pgm", "t.pgm"], "link": 2},
 {"drf": 2, "kind": "detail", "maps": ["t.pgm"], "detail": "add-signed"}]}"#
                        .to_vec(),
                ),
                ("t.pgm", pgm()),
                (
                    "r.csv",
                    b"drf,u,v,lambda,nx,ny,nz,id\n0,1.5,2,-2.5,0,0.5,1,200\n0,-3,9,1,0,0,1,9\n"
                        .to_vec(),
                ),
            ],
        },
        Front {
            name: "ptm fit",
            args: &[
                "ptm",
                "fit",
                "--height",
                "{h.pgm}",
                "--lights",
                "{l.csv}",
                "--out",
                "{out}.ptm",
                "--stats",
                "{out}.json",
            ],
            files: vec![
                ("h.pgm", pgm()),
                (
                    "l.csv",
                    b"elevation,azimuth\n20,0\n20,120\n20,240\n60,60\n60,180\n60,300\n80,0\n"
                        .to_vec(),
                ),
            ],
        },
        Front {
            name: "ptm eval",
            args: &[
                "ptm",
                "eval",
                "--ptm",
                "{t.ptm}",
                "--queries",
                "{q.csv}",
                "--out",
                "{out}.csv",
            ],
            files: vec![
                ("t.ptm", {
                    let f = units::ptm::texture_612::PtmFormat {
                        bits: 8,
                        exp: [9, 8, 9, 8, 9, 7],
                        bias: [-70_000, -60_000, -90_000, -60_000, -70_000, -20_000],
                    };
                    let q = (0..4 * 4 * 6u64).map(|k| k * 37 % 256).collect();
                    formats::ptm::Ptm {
                        width: 4,
                        height: 4,
                        format: f,
                        q,
                    }
                    .to_bytes()
                }),
                ("q.csv", b"x,y,lu,lv\n1,2,0.5,-0.25\n3,0,0,0\n".to_vec()),
            ],
        },
        Front {
            name: "tangents",
            args: &["tangents", "--mesh", "{m.obj}", "--out", "{out}.csv", "--mode", "directx"],
            files: vec![(
                "m.obj",
                b"v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\ns 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n".to_vec(),
            )],
        },
    ]
}

fn fronts() -> Vec<Front> {
    let ccc = {
        let img = formats::netpbm::parse_ppm(&ppm()).unwrap();
        formats::ccc::encode(&img).unwrap().to_bytes()
    };
    let coords = b"u,v\n1.5,1.5\n3,2.25\n".to_vec();
    let reqs = b"u,v\n1,1\n2.5,3.5\n".to_vec();
    vec![
        Front {
            name: "normals",
            args: &[
                "normals",
                "--height",
                "{h.pgm}",
                "--coords",
                "{c.csv}",
                "--out",
                "{out}.csv",
                "--vcd",
                "{out}.vcd",
            ],
            files: vec![("h.pgm", pgm()), ("c.csv", coords)],
        },
        Front {
            name: "render",
            args: &["render", "--height", "{h.pgm}", "--out", "{out}.png"],
            files: vec![("h.pgm", pgm())],
        },
        Front {
            name: "mipmap",
            args: &["mipmap", "--in", "{f.pgm}", "--out", "{out}"],
            files: vec![("f.pgm", pgm())],
        },
        Front {
            name: "ccc-encode",
            args: &["ccc", "encode", "--in", "{t.ppm}", "--out", "{out}.ccc"],
            files: vec![("t.ppm", ppm())],
        },
        Front {
            name: "ccc-decode",
            args: &["ccc", "decode", "--in", "{t.ccc}", "--out", "{out}.ppm"],
            files: vec![("t.ccc", ccc)],
        },
        Front {
            name: "texread",
            args: &[
                "texread",
                "--texture",
                "{t.ppm}",
                "--requests",
                "{r.csv}",
                "--out",
                "{out}.csv",
                "--stats",
                "{out}.json",
            ],
            files: vec![("t.ppm", ppm()), ("r.csv", reqs)],
        },
        Front {
            name: "dram",
            args: &["dram", "--trace", "{a.csv}"],
            files: vec![("a.csv", b"addr\n0\n1\n2\n600\n601\n3\n".to_vec())],
        },
    ]
}

/// The arguments with the case folder's paths filled in.
fn args(f: &Front, d: &Path) -> Vec<String> {
    f.args
        .iter()
        .map(|a| {
            let a = a.replace("{out}", &d.join("out").to_string_lossy());
            match a.strip_prefix('{').and_then(|x| x.strip_suffix('}')) {
                Some(file) => d.join(file).to_string_lossy().into_owned(),
                None => a,
            }
        })
        .collect()
}

/// Runs the program under the address-space limit and a CPU-time limit; its output and the
/// wall-clock seconds it took.
fn run_limited(args: &[String], cwd: &Path) -> (std::process::Output, f64) {
    let t0 = std::time::Instant::now();
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 2097152; ulimit -t {}; exec \"$0\" \"$@\"",
            2 * CASE_SECONDS
        ))
        .arg(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("runs");
    (o, t0.elapsed().as_secs_f64())
}

/// One case: the command's file `which` mutated; checks the exit, the message and the folder.
fn case(
    f: &Front,
    n: usize,
    which: usize,
    muts: &[verif::mutate::Mutation],
) -> Result<(), TestCaseError> {
    let d = dir(&format!("{}-{n}", f.name));
    let which = which % f.files.len();
    for (k, (name, bytes)) in f.files.iter().enumerate() {
        let b = if k == which {
            mutated(bytes, muts)
        } else {
            bytes.clone()
        };
        std::fs::write(d.join(name), b).unwrap();
    }
    // A refusal names a file of the case (the mutated one, or one it names) or an option.
    judge(f, &d, args(f, &d), Some("--"))
}

/// Runs `a` in the case folder `d` and judges the exit, the message, the folder and the time;
/// a refusal names `opt` (the option whose value the case set, or `--` for any option), a file
/// of the case, or how to give a value clap took for options.
fn judge(f: &Front, d: &Path, a: Vec<String>, opt: Option<&str>) -> Result<(), TestCaseError> {
    let before = names(d);
    let (o, secs) = run_limited(&a, d);
    let err = String::from_utf8_lossy(&o.stderr);
    let code = o.status.code().unwrap_or(-1);
    let fail = |m: String| {
        Err(TestCaseError::fail(format!(
            "texrtl {}: {m}\n{err}",
            a.join(" ")
        )))
    };
    if secs > CASE_SECONDS as f64 {
        return fail(format!("took {secs:.1} s"));
    }
    match code {
        0 => {}
        2 => {
            if err.trim_end().lines().count() != 1 || err.len() > 400 {
                return fail("not one short line".into());
            }
            if names(d) != before {
                return fail(format!("left {:?}", names(d)));
            }
            // Naming the option, a file of the case (a valid value the file does not suit), or
            // (a value clap reads as short options) how to give it.
            let file = err.contains(d.to_str().unwrap_or("/"));
            let told = |o: &str| err.contains(o) || file || err.contains("written --OPTION=VALUE");
            if let Some(o) = opt.filter(|o| !told(o)) {
                return fail(format!("does not name {o}"));
            }
        }
        // A merged run that failed (a mutation can mark a shard failed), a vectors check
        // or a co-simulation that found a difference.
        1 if ["merge", "vectors", "cosim", "cosim -F"].contains(&f.name) => {}
        c => return fail(format!("exit {c}")),
    }
    let _ = std::fs::remove_dir_all(d);
    Ok(())
}

#[test]
fn every_command_front_end_survives_mutated_inputs() {
    let n = std::sync::atomic::AtomicUsize::new(0);
    for f in fronts()
        .into_iter()
        .chain(texram_fronts())
        .chain(later_fronts())
    {
        let mut runner = verif::seeded_runner(&format!("fuzz {}", f.name), cases());
        let strat = (0..f.files.len(), mutations(8));
        runner
            .run(&strat, |(which, muts)| {
                let k = n.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                case(&f, k, which, &muts)
            })
            .unwrap();
    }
}

/// A shard summary of a small real run (`--shard K/2`).
fn shard_summary(k: u32) -> Vec<u8> {
    let d = dir(&format!("summary{k}"));
    std::fs::read(common::small_shard(k, &d)).unwrap()
}

#[test]
fn merge_survives_mutated_summaries() {
    let f = Front {
        name: "merge",
        args: &["merge", "--out", "{out}.json", "{s1.json}", "{s2.json}"],
        files: vec![("s1.json", shard_summary(1)), ("s2.json", shard_summary(2))],
    };
    let n = std::sync::atomic::AtomicUsize::new(0);
    let mut runner = verif::seeded_runner("fuzz merge", cases());
    runner
        .run(&(0..2usize, mutations(8)), |(which, muts)| {
            let k = n.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            case(&f, k, which, &muts)
        })
        .unwrap();
}

/// Fronts without an input file of their own: vectors, sweep, and co-simulation against the
/// user's Verilog (`--rtl`, the twin's source mutated; `-F`, a file list naming it, the list
/// or the source mutated; Icarus, when installed).
fn tool_fronts() -> Vec<Front> {
    let mut v = vec![
        Front {
            name: "vectors",
            args: &["vectors", "--unit", "blend_adjust_153", "--out", "{out}"],
            files: vec![],
        },
        Front {
            name: "sweep",
            args: &["sweep", "normals", "--samples", "20", "--map", "bumps"],
            files: vec![],
        },
    ];
    if Command::new("iverilog").arg("-V").output().is_ok() {
        let rtl = Path::new(env!("CARGO_MANIFEST_DIR")).join("../rtl/bump/blend_adjust_153.v");
        v.push(Front {
            name: "cosim",
            args: &[
                "cosim",
                "--unit",
                "blend_adjust_153",
                "--sim",
                "icarus",
                "--count",
                "40",
                "--rtl",
                "{u.v}",
                "--out",
                "{out}",
            ],
            files: vec![("u.v", std::fs::read(&rtl).unwrap())],
        });
        // A file list naming the source (relative to the list) with a folder and a macro.
        let list = b"// the unit\n+incdir+.\n+define+CHECKED=1\n-F empty.f\nu.v\n";
        v.push(Front {
            name: "cosim -F",
            args: &[
                "cosim",
                "--unit",
                "blend_adjust_153",
                "--sim",
                "icarus",
                "--count",
                "40",
                "-F",
                "{l.f}",
                "--out",
                "{out}",
            ],
            files: vec![
                ("l.f", list.to_vec()),
                ("empty.f", b"# nothing\n".to_vec()),
                ("u.v", std::fs::read(rtl).unwrap()),
            ],
        });
    }
    v
}

/// The options of a command that take a value, from its `--help`, but those naming an output
/// (a junk value there would only be a file name).
fn value_options(f: &Front) -> Vec<String> {
    let words: Vec<&str> = f
        .args
        .iter()
        .take_while(|a| !a.starts_with("--"))
        .copied()
        .collect();
    let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(&words)
        .arg("--help")
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&o.stdout).into_owned();
    let outputs = ["--out", "--stats", "--vcd", "--fst", "--dir"];
    help.lines()
        .filter_map(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            if !words.first()?.starts_with('-') {
                return None;
            }
            let k = words.iter().position(|w| w.starts_with("--"))?;
            let takes_value = words.get(k + 1).is_some_and(|w| w.starts_with('<'));
            takes_value.then(|| words[k].trim_end_matches(',').to_string())
        })
        .filter(|o| !outputs.contains(&o.as_str()))
        .collect()
}

/// Values a user might give: numbers at and past every limit, specials, junk, long values,
/// control characters (never a `/`: a relative path lands in the case's folder).
fn value() -> impl proptest::strategy::Strategy<Value = String> {
    use proptest::prelude::*;
    let special = proptest::sample::select(vec![
        "nan",
        "inf",
        "-inf",
        "-0",
        "1e308",
        "1e-300",
        "0x10",
        "1,2",
        "1,2,3",
        "0,0,0",
        "1..2",
        "0..0",
        "",
        " ",
        "tile:0",
        "border:256",
        "wrap",
        "16,16,16",
        "65535",
        "65536",
        "4294967296",
    ]);
    prop_oneof![
        any::<i64>().prop_map(|v| v.to_string()),
        (0u32..70).prop_map(|k| (1u128 << k).to_string()),
        (-3i64..4).prop_map(|d| d.to_string()),
        any::<f64>().prop_map(|x| x.to_string()),
        special.prop_map(String::from),
        "[ -.0-~]{0,12}",
        "[a-z0-9\n\t,.:]{0,8}",
        (0usize..6000).prop_map(|n| "9".repeat(n)),
    ]
}

/// `f`'s arguments with option `opt` set to `v` (replaced where the front gives it, else added).
fn with_value(f: &Front, d: &Path, opt: &str, v: &str) -> Vec<String> {
    let mut a = args(f, d);
    match a.iter().position(|x| x == opt) {
        Some(i) if i + 1 < a.len() => a[i + 1] = v.to_string(),
        _ => a.extend([opt.to_string(), v.to_string()]),
    }
    a
}

/// Options whose largest valid values are long runs by design (10 M co-simulated cycles, a
/// million sweep samples): their limits are tested in `limits.rs`, not under the time bound.
fn long_by_design(f: &Front, opt: &str) -> bool {
    matches!(
        (f.name, opt),
        ("cosim" | "cosim -F", "--count") | ("sweep", "--samples")
    )
}

#[test]
fn the_value_fronts_read_the_options_from_the_help() {
    let fronts = tool_fronts();
    assert_eq!(value_options(&fronts[0]), ["--unit"], "vectors");
    let volume = texram_fronts()
        .into_iter()
        .find(|f| f.name == "volume")
        .unwrap();
    let opts = value_options(&volume);
    assert!(
        opts.iter().any(|o| o == "--dims") && !opts.iter().any(|o| o == "--out"),
        "{opts:?}"
    );
}

#[test]
fn every_option_value_is_checked() {
    let n = std::sync::atomic::AtomicUsize::new(0);
    let all = fronts()
        .into_iter()
        .chain(texram_fronts())
        .chain(later_fronts())
        .chain(tool_fronts());
    for f in all {
        let opts: Vec<String> = value_options(&f)
            .into_iter()
            .filter(|o| !long_by_design(&f, o))
            .collect();
        assert!(
            !opts.is_empty(),
            "{}: no option with a value in its help",
            f.name
        );
        let mut runner =
            verif::seeded_runner(&format!("fuzz values {}", f.name), cases().div_ceil(2));
        runner
            .run(&(0..opts.len(), value()), |(k, v)| {
                let d = dir(&format!(
                    "{}-v{}",
                    f.name,
                    n.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
                ));
                for (name, bytes) in &f.files {
                    std::fs::write(d.join(name), bytes).unwrap();
                }
                let a = with_value(&f, &d, &opts[k], &v);
                // A file option's refusal may name the file instead.
                let file = f
                    .args
                    .windows(2)
                    .any(|w| w[0] == opts[k] && w[1].starts_with('{'));
                judge(&f, &d, a, (!file).then_some(opts[k].as_str()))
            })
            .unwrap();
    }
}

#[test]
fn vectors_sweep_and_cosim_survive_mutated_inputs() {
    let n = std::sync::atomic::AtomicUsize::new(0);
    for f in tool_fronts().into_iter().filter(|f| !f.files.is_empty()) {
        let mut runner = verif::seeded_runner(&format!("fuzz {}", f.name), cases());
        runner
            .run(&(0..f.files.len(), mutations(8)), |(which, muts)| {
                case(
                    &f,
                    n.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
                    which,
                    &muts,
                )
            })
            .unwrap();
    }
}
