//! Module libraries: [`Library`], the `-y`, `-v` and `+libext+` of a file list.

use super::Simulator;
use std::path::{Path, PathBuf};
use std::time::UNIX_EPOCH;

/// Where the simulators look for a module the sources instantiate but do not define, as a
/// file list gives it: library folders (`-y DIR`, `+libdir+DIR`), library files (`-v FILE`,
/// whose modules are compiled only where instantiated) and file name extensions
/// (`+libext+EXT[+EXT]`).
///
/// Both simulators search alike, as Verilator does: the build's include folders (each
/// source's own first), then the library folders, each for `NAME.v`, `NAME.sv`, then `NAME`
/// with each of the list's extensions; then the library files. Verilator is given the folders
/// as `-I` and `-y` and runs in the run's folder (its own default, the current folder, is then
/// the run's); Icarus is given every folder as `-y` and every extension as `-Y`, in the same
/// order.
///
/// A build's cache key reads the library files and what they include, and the name, size
/// and time of change of each module file in the folders searched, so an edited library
/// module builds anew.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Library {
    /// Library folders, absolute, in search order (after the include folders).
    pub dirs: Vec<PathBuf>,
    /// Library files, absolute.
    pub files: Vec<PathBuf>,
    /// File name extensions tried after `.v` and `.sv`, in order.
    pub exts: Vec<String>,
}

/// The extensions always tried, first.
const DEFAULT_EXTS: [&str; 2] = [".v", ".sv"];

/// More files than this in the folders a build searches are refused: its key lists each.
const MAX_FILES: usize = 100_000;

impl Library {
    /// The extensions tried, in order: `.v`, `.sv`, then the list's.
    pub fn extensions(&self) -> Vec<&str> {
        let mut out = DEFAULT_EXTS.to_vec();
        for e in &self.exts {
            if !out.contains(&e.as_str()) {
                out.push(e);
            }
        }
        out
    }

    /// Adds `other`'s folders, files and extensions after this library's, each once.
    pub fn extend(&mut self, other: Library) {
        other
            .dirs
            .into_iter()
            .for_each(|d| push_once(&mut self.dirs, d));
        other
            .files
            .into_iter()
            .for_each(|f| push_once(&mut self.files, f));
        other
            .exts
            .into_iter()
            .for_each(|e| push_once(&mut self.exts, e));
    }

    /// The flags that give the library to `sim`, after the preprocessor's flags and a build
    /// with `include_dirs`: Verilator's `-y`, `-v`, `+libext+` (it searches its `-I`
    /// folders itself); Icarus' `-y` for each include folder and library folder, `-l` and
    /// `-Y`.
    pub fn flags(&self, sim: Simulator, include_dirs: &[PathBuf]) -> Vec<String> {
        let y = |d: &PathBuf| ["-y".to_string(), shown(d)];
        match sim {
            Simulator::Verilator => {
                let files = self.files.iter().flat_map(|f| ["-v".into(), shown(f)]);
                let mut out: Vec<String> = self.dirs.iter().flat_map(y).chain(files).collect();
                if !self.exts.is_empty() {
                    out.push(format!("+libext+{}", self.exts.join("+")));
                }
                out
            }
            Simulator::Icarus => {
                let dirs = include_dirs.iter().chain(&self.dirs).flat_map(y);
                let files = self.files.iter().map(|f| format!("-l{}", f.display()));
                let exts = self.extensions().into_iter().map(|e| format!("-Y{e}"));
                dirs.chain(files).chain(exts).collect()
            }
        }
    }

    /// The module files a build with `include_dirs` may be given from its folders, in search
    /// order, each as a line of its path, size and time of change (for a cache key). More
    /// than 100 000 are refused, naming the folder.
    pub fn listing(&self, include_dirs: &[PathBuf]) -> Result<String, String> {
        let exts = self.extensions();
        let (mut out, mut count) = (String::new(), 0);
        for d in include_dirs.iter().chain(&self.dirs) {
            let rd = std::fs::read_dir(d).map_err(|e| format!("folder {}: {e}", d.display()))?;
            let mut found: Vec<(PathBuf, std::fs::Metadata)> = rd
                .flatten()
                .filter(|e| is_module_file(&e.file_name(), &exts))
                .filter_map(|e| Some((e.path(), e.metadata().ok()?)))
                .filter(|(_, m)| m.is_file())
                .collect();
            count += found.len();
            if count > MAX_FILES {
                return Err(format!(
                    "folder {}: the folders a build searches for modules hold more than {MAX_FILES} Verilog files",
                    d.display()
                ));
            }
            found.sort_by(|a, b| a.0.cmp(&b.0));
            for (p, m) in found {
                let changed = m
                    .modified()
                    .ok()
                    .and_then(|t| t.duration_since(UNIX_EPOCH).ok());
                let ns = changed.map_or(0, |t| t.as_nanos());
                out.push_str(&format!("{} {} {ns}\n", p.display(), m.len()));
            }
        }
        Ok(out)
    }
}

/// Adds `x` to `v` unless it is there.
pub(super) fn push_once<T: PartialEq>(v: &mut Vec<T>, x: T) {
    if !v.contains(&x) {
        v.push(x);
    }
}

fn shown(p: &Path) -> String {
    p.display().to_string()
}

/// Whether `name` ends in one of `exts`, with a module name before it.
fn is_module_file(name: &std::ffi::OsStr, exts: &[&str]) -> bool {
    let Some(name) = name.to_str() else {
        return false;
    };
    exts.iter()
        .any(|e| name.len() > e.len() && name.ends_with(e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_simulator_is_given_the_same_search_in_its_own_flags() {
        let lib = Library {
            dirs: vec!["/l/a".into(), "/l/b".into()],
            files: vec!["/l/cells.v".into()],
            exts: Vec::new(),
        };
        let inc = [PathBuf::from("/src")];
        assert_eq!(
            lib.flags(Simulator::Verilator, &inc),
            ["-y", "/l/a", "-y", "/l/b", "-v", "/l/cells.v"]
        );
        assert_eq!(
            lib.flags(Simulator::Icarus, &inc),
            [
                "-y",
                "/src",
                "-y",
                "/l/a",
                "-y",
                "/l/b",
                "-l/l/cells.v",
                "-Y.v",
                "-Y.sv"
            ]
        );
        let more = Library {
            exts: vec![".vlib".into(), ".v".into()],
            ..Library::default()
        };
        assert_eq!(more.flags(Simulator::Verilator, &inc), ["+libext+.vlib+.v"]);
        assert_eq!(
            more.flags(Simulator::Icarus, &inc),
            ["-y", "/src", "-Y.v", "-Y.sv", "-Y.vlib"]
        );
    }

    /// The include folders' module files, then the library folders', each by name, with size
    /// and time; a file named only the extension, another extension and a folder are not
    /// module files; an edit changes the listing.
    #[test]
    fn a_listing_names_each_module_file_searched() {
        let t = tempfile::tempdir().unwrap();
        let (inc, lib) = (t.path().join("inc"), t.path().join("lib"));
        for (d, f) in [
            (&lib, "b.v"),
            (&lib, "a.sv"),
            (&lib, "c.vh"),
            (&lib, ".v"),
            (&inc, "z.v"),
        ] {
            std::fs::create_dir_all(d).unwrap();
            std::fs::write(d.join(f), "").unwrap();
        }
        std::fs::create_dir(lib.join("d.v")).unwrap();
        let library = Library {
            dirs: vec![lib.clone()],
            ..Library::default()
        };
        let listed = library.listing(std::slice::from_ref(&inc)).unwrap();
        let names: Vec<&str> = listed
            .lines()
            .map(|l| l.split(' ').next().unwrap())
            .collect();
        let want = [inc.join("z.v"), lib.join("a.sv"), lib.join("b.v")];
        assert_eq!(names, want.map(|p| p.display().to_string()));
        std::fs::write(lib.join("b.v"), "module b; endmodule\n").unwrap();
        assert_ne!(library.listing(&[inc]).unwrap(), listed);
        let gone = Library {
            dirs: vec![t.path().join("gone")],
            ..Library::default()
        };
        assert!(gone.listing(&[]).unwrap_err().starts_with("folder "));
    }
}
