//! What the command tests share: a fresh folder, running `texrtl`, and the bad-input check
//! (exit 2, one line naming the problem, no output left behind).

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh folder for test `name` of command `cmd`.
pub fn dir(cmd: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("texrtl-{cmd}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
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
