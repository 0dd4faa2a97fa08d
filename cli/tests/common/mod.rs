//! What the command tests share: a fresh folder, running `texrtl`, and the bad-input check
//! (exit 2, one line naming the problem, no output left behind).

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh folder for test `name` of command `cmd`, removed when the test passes (kept, to
/// look at, when it fails).
pub fn dir(cmd: &str, name: &str) -> TestDir {
    let d = std::env::temp_dir().join(format!("texrtl-{cmd}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    TestDir(d)
}

/// The path of a folder for test `name` of command `cmd`, not created (for a command that
/// must create it, or must not), removed as [`TestDir`] is.
pub fn fresh(cmd: &str, name: &str) -> TestDir {
    let d = dir(cmd, name);
    std::fs::remove_dir(&d.0).unwrap();
    d
}

/// A test's folder: a path, removed on drop unless the test is failing.
pub struct TestDir(PathBuf);

impl std::ops::Deref for TestDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TestDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// Whether the simulator `tool` runs (`tool arg`); when it does not, says so on stderr, and
/// fails the test if `TEXRTL_REQUIRE_COSIM=1` (as `.ci/run` sets).
pub fn simulator(tool: &str, arg: &str) -> bool {
    if Command::new(tool).arg(arg).output().is_ok() {
        return true;
    }
    assert!(
        std::env::var("TEXRTL_REQUIRE_COSIM").as_deref() != Ok("1"),
        "TEXRTL_REQUIRE_COSIM=1 and no {tool}"
    );
    eprintln!("{tool} not installed: the test is skipped");
    false
}

/// The co-simulators installed, by their `--sim` names (each missing one said as
/// [`simulator`] says it).
pub fn simulators() -> Vec<&'static str> {
    [("icarus", "iverilog"), ("verilator", "verilator")]
        .into_iter()
        .filter(|(_, tool)| simulator(tool, "-V"))
        .map(|(sim, _)| sim)
        .collect()
}

pub fn texrtl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(args)
        .output()
        .expect("runs")
}

pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The `summary.json` of shard `k` of 2 of a small run (blend adjust 153, 10 transactions a
/// configuration, no waveforms) written into folder `out`.
pub fn small_shard(k: u32, out: &Path) -> PathBuf {
    let shard = format!("{k}/2");
    let o = texrtl(&small_shard_args(&shard, out));
    assert!(o.status.code().is_some_and(|c| c <= 1), "{o:?}");
    out.join("summary.json")
}

/// The arguments of [`small_shard`]'s run as shard `shard` (`I/N`).
pub fn small_shard_args<'a>(shard: &'a str, out: &'a Path) -> Vec<&'a str> {
    vec![
        "--no-cosim",
        "--no-vcd",
        "--only",
        "blend_adjust_153",
        "--count",
        "10",
        "--shard",
        shard,
        "--out",
        s(out),
    ]
}

/// `texrtl CMD ARGS --vcd /dev/full` is refused (a waveform that cannot be written is bad
/// output): exit 2, one line naming `--vcd /dev/full`, no `o.*` output left in `d`.
pub fn assert_vcd_full_refused(cmd: &str, args: &[&str], d: &Path) {
    let mut a = vec![cmd];
    a.extend_from_slice(args);
    a.extend(["--vcd", "/dev/full"]);
    assert_refused(&a, "--vcd /dev/full", d, &["o."]);
}

/// `args` are refused: exit 2, one line containing `needle`, and no file in `d` whose name
/// starts with one of `outputs`.
pub fn assert_refused(args: &[&str], needle: &str, d: &Path, outputs: &[&str]) {
    let out = texrtl(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(needle), "{needle}: {err}");
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| outputs.iter().any(|o| n.starts_with(o)))
        .collect();
    assert!(left.is_empty(), "{args:?} left {left:?}");
}

/// Runs `texrtl` with `args`, which must succeed (stderr shown otherwise).
pub fn ran(args: &[&str]) -> Output {
    let out = texrtl(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The lines of the CSV at `path`.
pub fn csv_lines(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}
