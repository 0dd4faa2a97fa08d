//! What a command leaves behind when it fails. Every output is checked before any work
//! ([`super::check_outputs`]); then [`Outputs`] notes which files are there, and when the
//! command fails on bad input or I/O (exit 2) it removes every file the command created: the
//! outputs, the files written beside them (a VCD's `.gtkw`, state filters and `.fst`) and,
//! for a folder output, whatever it made inside. A failed testbench (exit 1) keeps its files:
//! the waveform is the evidence. A file that existed before is never removed (it may have
//! been replaced by a complete new version: outputs are never left half written).

use super::CmdError;
use std::collections::BTreeSet;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// One output: a file (and the files beside it sharing its stem) or a folder.
#[derive(Debug)]
enum Watch {
    /// Files in `dir` whose names start with `stem`, and which of them were there.
    File {
        dir: PathBuf,
        stem: OsString,
        before: BTreeSet<OsString>,
    },
    /// A folder: whether it was there, and its entries then.
    Folder {
        path: PathBuf,
        existed: bool,
        before: BTreeSet<OsString>,
    },
}

/// The outputs of one command, watched from before its work to its end.
#[derive(Debug, Default)]
pub struct Outputs {
    watched: Vec<Watch>,
}

fn entries(dir: &Path, keep: impl Fn(&OsString) -> bool) -> BTreeSet<OsString> {
    std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.file_name()))
                .filter(|n| keep(n))
                .collect()
        })
        .unwrap_or_default()
}

/// Whether `name` is the output (stem `stem`) or a file beside it: `STEM` or `STEM.*`.
fn starts_with(name: &OsString, stem: &OsString) -> bool {
    let (n, s) = (name.as_encoded_bytes(), stem.as_encoded_bytes());
    n.starts_with(s) && (n.len() == s.len() || n[s.len()] == b'.')
}

/// Removes one created entry (a file, or a folder with what it holds); a symlink is removed
/// as a link, never followed.
fn remove(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => drop(std::fs::remove_dir_all(path)),
        Ok(_) => drop(std::fs::remove_file(path)),
        Err(_) => {}
    }
}

impl Outputs {
    /// Checks the outputs against each other and the inputs ([`super::check_outputs`]), then
    /// starts watching them.
    pub fn check(outs: &[(&str, &Path)], ins: &[(&str, &Path)]) -> Result<Outputs, CmdError> {
        super::check_outputs(outs, ins)?;
        let mut o = Outputs::default();
        for (_, p) in outs {
            o.file(p);
        }
        Ok(o)
    }

    /// Watches a file output and the files beside it (same folder, named `STEM` or
    /// `STEM.*` for the output's file stem). Devices and pipes are not watched: nothing is created for them.
    pub fn file(&mut self, path: &Path) {
        if std::fs::symlink_metadata(path).is_ok_and(|m| !m.is_file()) {
            return;
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let Some(stem) = path.file_stem().map(OsString::from) else {
            return;
        };
        let before = entries(&dir, |n| starts_with(n, &stem));
        self.watched.push(Watch::File { dir, stem, before });
    }

    /// Watches a folder output: on failure, what the command made in it goes (and the folder,
    /// when the command made it, with the parents it made for it).
    pub fn folder(&mut self, path: &Path) {
        let missing = |p: &&Path| !p.as_os_str().is_empty() && p.symlink_metadata().is_err();
        let made = path.ancestors().take_while(missing).last();
        self.watched.push(Watch::Folder {
            path: made.unwrap_or(path).to_path_buf(),
            existed: made.is_none(),
            before: entries(path, |_| true),
        });
    }

    /// Removes what the command created.
    pub fn remove_new(&self) {
        for w in &self.watched {
            match w {
                Watch::File { dir, stem, before } => {
                    for n in entries(dir, |n| starts_with(n, stem) && !before.contains(n)) {
                        remove(&dir.join(n));
                    }
                }
                Watch::Folder {
                    path,
                    existed: false,
                    ..
                } => remove(path),
                Watch::Folder { path, before, .. } => {
                    for n in entries(path, |n| !before.contains(n)) {
                        remove(&path.join(n));
                    }
                }
            }
        }
    }

    /// The command's result, after removing what it created when it failed on bad input or
    /// I/O (exit 2).
    pub fn settle<T>(self, r: Result<T, CmdError>) -> Result<T, CmdError> {
        if matches!(r, Err(CmdError::Input(_))) {
            self.remove_new();
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scratch folder, removed when the test ends.
    fn dir(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("texrtl-outputs-{name}-"))
            .tempdir()
            .unwrap()
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = entries(d, |_| true)
            .into_iter()
            .map(|n| n.to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn bad_input_removes_new_files_and_their_companions_only() {
        let d = dir("files");
        std::fs::write(d.path().join("w.old"), "keep").unwrap();
        std::fs::write(d.path().join("other.txt"), "keep").unwrap();
        let o = Outputs::check(&[("--vcd", &d.path().join("w.vcd"))], &[]).unwrap();
        for f in [
            "w.vcd",
            "w.gtkw",
            "w.tb.state.txt",
            "w.vcd.partial",
            "w2.vcd",
        ] {
            std::fs::write(d.path().join(f), "new").unwrap();
        }
        let r: Result<(), _> = o.settle(Err(CmdError::Input("x".into())));
        assert!(r.is_err());
        assert_eq!(names(d.path()), ["other.txt", "w.old", "w2.vcd"]);
    }

    #[test]
    fn success_and_a_failed_testbench_keep_everything() {
        let d = dir("keep");
        for r in [Ok(()), Err(CmdError::Failed("tb".into()))] {
            let o = Outputs::check(&[("--out", &d.path().join("o.csv"))], &[]).unwrap();
            std::fs::write(d.path().join("o.csv"), "new").unwrap();
            let _ = o.settle(r);
            assert_eq!(names(d.path()), ["o.csv"]);
            std::fs::remove_file(d.path().join("o.csv")).unwrap();
        }
    }

    #[test]
    fn a_new_folder_goes_and_an_old_one_keeps_its_old_entries() {
        let d = dir("folder");
        let mut o = Outputs::default();
        o.folder(&d.path().join("new"));
        o.folder(d.path());
        std::fs::create_dir_all(d.path().join("new/frame0")).unwrap();
        std::fs::write(d.path().join("new/frame0/level0.pgm"), "x").unwrap();
        std::fs::write(d.path().join("stats.json"), "x").unwrap();
        o.remove_new();
        assert!(names(d.path()).is_empty(), "{:?}", names(d.path()));
    }

    #[test]
    fn the_parents_made_for_a_new_folder_go_with_it() {
        let d = dir("parents");
        std::fs::create_dir(d.path().join("old")).unwrap();
        let mut o = Outputs::default();
        o.folder(&d.path().join("old/a/b/c"));
        std::fs::create_dir_all(d.path().join("old/a/b/c")).unwrap();
        std::fs::write(d.path().join("old/a/b/c/report.md"), "x").unwrap();
        o.remove_new();
        assert_eq!(names(d.path()), ["old"]);
        assert!(names(&d.path().join("old")).is_empty());
    }
}
