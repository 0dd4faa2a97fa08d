//! `texrtl bench` as a user runs it: one small twin against Verilator in two rounds of a few
//! thousand cycles, replaying a ring of fewer stimulus rows. One row, every rate positive,
//! every ratio its row's quotient and inside the range of its rounds, the table also in
//! `table.md`, no trace left behind. Without Verilator the test says so and passes, unless
//! `TEXRTL_REQUIRE_COSIM=1`.

mod common;
use common::dir;
use std::path::Path;
use std::process::{Command, Stdio};

/// Cycles per second as the table prints them: `4.81 M`, `390 k`, `950`.
fn rate(cell: &str) -> f64 {
    let (num, scale) = match cell.split_once(' ') {
        Some((n, "M")) => (n, 1e6),
        Some((n, "k")) => (n, 1e3),
        _ => (cell, 1.0),
    };
    num.parse::<f64>()
        .unwrap_or_else(|_| panic!("rate '{cell}'"))
        * scale
}

/// A ratio cell: the median round's ratio and the range of the rounds, `1.22 (1.15-1.28)`
/// (the range alone when every round gave the same, `1.22`).
fn ratio(cell: &str) -> (f64, f64, f64) {
    let num = |s: &str| {
        s.parse::<f64>()
            .unwrap_or_else(|_| panic!("ratio '{cell}'"))
    };
    match cell.split_once(" (") {
        Some((r, range)) => {
            let (lo, hi) = range.trim_end_matches(')').split_once('-').unwrap();
            (num(r), num(lo), num(hi))
        }
        None => (num(cell), num(cell), num(cell)),
    }
}

#[test]
fn bench_measures_a_twin_in_alternating_rounds() {
    if !common::simulator("verilator", "--version") {
        return;
    }
    let d = dir("bench", "rounds");
    let cache = d.join("cache");
    // A second run builds nothing: its three harnesses are the first run's, kept.
    for (run, said) in [("first", "built 3, kept 0"), ("second", "built 0, kept 3")] {
        let (o, pid) = bench(&d.join(run), &cache);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{err}");
        assert!(
            err.contains(&format!("address_150: harnesses {said}")),
            "{err}"
        );
        // Progress on stderr names its unit first: a copy of both streams has one table.
        assert!(err.contains("\naddress_150: measured | "), "{err}");
        assert!(!err.lines().any(|l| l.starts_with('|')), "{err}");
        check_table(o, pid, &d.join(run));
    }
    assert!(!d.join("second/address_150/obj_untraced").exists());
}

/// `texrtl bench` of address unit 150 into `out`, with the simulator cache `cache`: its output
/// and process id.
fn bench(out: &Path, cache: &Path) -> (std::process::Output, u32) {
    let child = Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(["bench", "--unit", "address_150", "--cycles", "5000"])
        .args([
            "--traced-cycles",
            "2000",
            "--rounds",
            "2",
            "--stimulus-rows",
            "700",
        ])
        .arg("--out")
        .arg(out)
        .env("TEXRTL_SIM_CACHE", cache)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    (child.wait_with_output().unwrap(), pid)
}

/// The table of a bench run `o` (process `pid`) into `d`, and what it leaves behind.
fn check_table(o: std::process::Output, pid: u32, d: &Path) {
    let err = String::from_utf8_lossy(&o.stderr);
    // This test's program is built as the test is: a debug build says so.
    let warned = err.contains("texrtl: warning: a debug build (debug assertions on)");
    assert_eq!(warned, cfg!(debug_assertions), "{err}");
    let table = String::from_utf8(o.stdout).unwrap();
    assert!(
        table.contains("over 5000 cycles, traced over 2000, both replaying 700 rows"),
        "{table}"
    );
    // The stimulus file holds the 700 rows the harness replays, a 64-bit word an input.
    let stim = std::fs::metadata(d.join("address_150/stim.bin"))
        .unwrap()
        .len();
    assert!(stim > 0 && stim.is_multiple_of(700 * 8), "{stim} bytes");
    assert!(table.contains("2 rounds, each side in turn"), "{table}");
    let rows: Vec<&str> = table
        .lines()
        .filter(|l| l.starts_with("| address"))
        .collect();
    assert_eq!(rows.len(), 1, "{table}");
    let cells: Vec<&str> = rows[0].split('|').map(str::trim).collect();
    assert_eq!(cells.len(), 12, "{}", rows[0]);
    for mode in 0..3 {
        let (ours, theirs) = (rate(cells[2 + 3 * mode]), rate(cells[3 + 3 * mode]));
        let (r, lo, hi) = ratio(cells[4 + 3 * mode]);
        assert!(ours > 0.0 && theirs > 0.0, "{}", rows[0]);
        // The rates are printed to three or four digits, the ratio to two decimals.
        assert!((r - ours / theirs).abs() <= 0.01 + 0.01 * r, "{}", rows[0]);
        assert!(lo <= r && r <= hi, "{}", rows[0]);
    }
    let md = std::fs::read_to_string(d.join("table.md")).unwrap();
    assert_eq!(md.trim_end(), table.trim_end());
    // The traces went to a folder of the process's own, removed with them.
    let shm = Path::new("/dev/shm").join(format!("texrtl-vs-verilator-{pid}-address_150"));
    assert!(!shm.exists(), "{} left behind", shm.display());
    let unit = d.join("address_150");
    for f in ["model.vcd", "model.fst", "rtl.vcd", "rtl.fst"] {
        assert!(!unit.join(f).exists(), "{f} left behind");
    }
}

/// `bench --instructions` as a user runs it on a shared machine: both sides' instructions a
/// cycle under callgrind, the ratio their quotient, the table also in `instructions.md`, and
/// the same figures on a second run (a count, not a timing: the model's exactly, the twin's
/// within its clock reads).
#[test]
fn bench_counts_instructions_the_same_on_every_run() {
    if !common::simulator("verilator", "--version") || !common::simulator("valgrind", "--version") {
        return;
    }
    let d = dir("bench", "instructions");
    let run = || {
        let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
            .args(["bench", "--unit", "address_150", "--instructions", "5000"])
            .arg("--out")
            .arg(d.as_os_str())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{err}");
        assert!(err.contains("\naddress_150: counted | "), "{err}");
        assert!(!err.lines().any(|l| l.starts_with('|')), "{err}");
        String::from_utf8(o.stdout).unwrap()
    };
    let figures = |table: &str| -> [f64; 3] {
        assert!(table.contains("cycles 1000..6000 of seed"), "{table}");
        let row = table
            .lines()
            .find(|l| l.starts_with("| address_150 |"))
            .unwrap_or_else(|| panic!("{table}"));
        let cells: Vec<f64> = row
            .split('|')
            .map(str::trim)
            .skip(2)
            .filter(|c| !c.is_empty())
            .map(|c| c.parse().unwrap())
            .collect();
        cells.try_into().unwrap_or_else(|_| panic!("{row}"))
    };
    let table = run();
    let [model, twin, ratio] = figures(&table);
    assert!(model > 0.0 && twin > 0.0, "{table}");
    assert!(
        (ratio - twin / model).abs() <= 0.005 + 0.001 * ratio,
        "{table}"
    );
    let md = std::fs::read_to_string(d.join("instructions.md")).unwrap();
    assert_eq!(md.trim_end(), table.trim_end());
    let [again, twin_again, _] = figures(&run());
    assert_eq!(again, model, "the model's count differs on a second run");
    assert!(
        (twin_again - twin).abs() <= 0.2,
        "the twin's: {twin} then {twin_again}"
    );
}

/// A count with no cycles, or without valgrind, is bad input naming `--instructions`, before
/// anything is built; so is a model's side of a count asked for wrongly (its variable named).
#[test]
fn bench_instructions_refuses_bad_input() {
    let d = common::fresh("bench", "no-valgrind");
    for (spec, said) in [
        (
            "address_150:10:11",
            "TEXRTL_BENCH_COUNT=address_150:10:11: UNIT:TOTAL:CYCLES",
        ),
        ("nope:10:5", "TEXRTL_BENCH_COUNT nope: no Verilog twin"),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
            .args(["bench", "--out", common::s(&d)])
            .env("TEXRTL_BENCH_COUNT", spec)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.starts_with(&format!("texrtl: {said}")), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    if !common::simulator("verilator", "--version") {
        return;
    }
    let o = common::texrtl(&["bench", "--instructions", "0", "--out", common::s(&d)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err, "texrtl: --instructions 0: 1..=10000000\n");
    // A PATH with Verilator on it and no valgrind.
    let bin = dir("bench", "path");
    let verilator = std::env::split_paths(&std::env::var_os("PATH").unwrap())
        .map(|p| p.join("verilator"))
        .find(|p| p.is_file())
        .unwrap();
    std::os::unix::fs::symlink(&verilator, bin.join("verilator")).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(["bench", "--instructions", "--out", common::s(&d)])
        .env("PATH", bin.as_os_str())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(
        err,
        "texrtl: --instructions: valgrind not found (Debian: apt-get install valgrind)\n"
    );
    assert!(!d.exists(), "the output folder was made for bad input");
}
