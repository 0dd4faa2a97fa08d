//! Building a co-simulation testbench with Verilator, reusing its runtime library.
//!
//! `verilator --binary` compiles Verilator's own runtime (`verilated.cpp`, its threads and
//! timing support) into every build: about 4 of a build's 5 seconds on this machine. These
//! objects depend only on Verilator, the C++ compiler and the options, which are the same for
//! every co-simulation, so the first build leaves them in the simulator cache (a folder of its
//! own there, `.verilator-runtime-<hash>`, keyed by both tools' version lines; the cache's
//! pruning passes over it, and deleting the cache clears it) and later builds copy them into
//! their build folder, where `make` finds them newer than their sources and does not compile
//! them again. With the cache off (`TEXRTL_SIM_CACHE=off`) every build compiles them. The
//! testbench and the design are always compiled anew.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// The options of every build (the cached runtime objects are only valid for these).
pub(super) const OPTIONS: [&str; 7] = [
    "--cc",
    "--exe",
    "--main",
    "--timing",
    "-Wno-fatal",
    "-Wno-lint",
    "-Wno-style",
];

/// The runtime cache's folder in the simulator cache: one per Verilator and C++ compiler
/// version, and for builds with and without `--trace` (whose runtime differs); `None` with the
/// cache off.
fn cache_dir(trace: bool) -> &'static Option<PathBuf> {
    static DIRS: [OnceLock<Option<PathBuf>>; 2] = [OnceLock::new(), OnceLock::new()];
    DIRS[usize::from(trace)].get_or_init(|| {
        let first_line = |exe: &str, arg: &str| -> Option<String> {
            let o = Command::new(exe).arg(arg).output().ok()?;
            let text = String::from_utf8_lossy(&o.stdout).into_owned();
            Some(text.lines().next()?.to_string())
        };
        let key = format!(
            "{}\n{}\n{}{}",
            first_line("verilator", "--version")?,
            first_line("c++", "--version").unwrap_or_default(),
            OPTIONS.join(" "),
            if trace { " --trace" } else { "" }
        );
        // FNV-1a: a stable name for the key.
        let h = key.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
        });
        // A dot-name: not an entry of the cache's, so never pruned (it is a few hundred kB).
        Some(super::cache::root()?.join(format!(".verilator-runtime-{h:016x}")))
    })
}

/// Verilator's runtime objects in `dir` (`verilated*.o`).
fn runtime_objects(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut v: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
            name.is_some_and(|n| n.starts_with("verilated") && n.ends_with(".o"))
        })
        .collect();
    v.sort();
    v
}

/// Copies `from` to `to` through a temporary name, so a concurrent reader never sees half a
/// file.
fn copy_whole(from: &Path, to: &Path) -> std::io::Result<()> {
    let tmp = to.with_extension(format!("tmp{}", std::process::id()));
    std::fs::copy(from, &tmp)?;
    std::fs::rename(&tmp, to)
}

/// What a build adds to [`OPTIONS`]: VCD tracing (`--trace`), and line and toggle coverage
/// (`--coverage-line --coverage-toggle`, with a main of texrtl's that writes `coverage.dat`
/// where the run is, in place of `--main`'s, which writes none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Flavour {
    pub trace: bool,
    pub coverage: bool,
}

impl Flavour {
    /// The options it adds (for a cache key).
    pub fn options(self) -> &'static str {
        match (self.trace, self.coverage) {
            (false, false) => "",
            (true, false) => " --trace",
            (false, true) => " --coverage-line --coverage-toggle",
            (true, true) => " --trace --coverage-line --coverage-toggle",
        }
    }
}

/// The main of a coverage build: `--main`'s loop, then the coverage written.
const COVERAGE_MAIN: &str = "#include \"verilated.h\"\n#include \"verilated_cov.h\"\n#include \"Vtb.h\"\n\nint main(int argc, char** argv, char**) {\n    const std::unique_ptr<VerilatedContext> contextp{new VerilatedContext};\n    contextp->commandArgs(argc, argv);\n    const std::unique_ptr<Vtb> topp{new Vtb{contextp.get()}};\n    while (!contextp->gotFinish()) {\n        topp->eval();\n        if (!topp->eventsPending()) break;\n        contextp->time(topp->nextTimeSlot());\n    }\n    topp->final();\n    contextp->coveragep()->write(\"coverage.dat\");\n    return 0;\n}\n";

/// Builds `tb` (top module `tb`) with `sources` (the preprocessor's options first) into
/// `mdir`, as `flavour` says; returns the executable. `run` runs a command, turning a failure
/// into the tool's first message. A coverage build compiles Verilator's runtime anew (its
/// objects differ), others reuse the cached one.
pub fn build(
    tb: &Path,
    sources: &[String],
    mdir: &Path,
    flavour: Flavour,
    run: &dyn Fn(&mut Command, &str) -> Result<(), String>,
) -> Result<PathBuf, String> {
    // In the run's folder: Verilator also looks for modules in its current folder, which is
    // then the run's (no user's file is taken from wherever texrtl was started).
    let absolute = |p: &Path| std::path::absolute(p).map_err(|e| format!("{}: {e}", p.display()));
    let (tb, mdir) = (&absolute(tb)?, &absolute(mdir)?);
    let here = tb.parent().unwrap_or(Path::new("/"));
    let mut c = Command::new("verilator");
    c.current_dir(here)
        .args(
            OPTIONS
                .iter()
                .filter(|o| !(flavour.coverage && **o == "--main")),
        )
        .args(flavour.options().split_whitespace())
        .args(["--top-module", "tb", "-o", "simv", "--Mdir"])
        .arg(mdir)
        .arg(tb)
        .args(sources);
    if flavour.coverage {
        let main = here.join("texrtl_main.cpp");
        std::fs::write(&main, COVERAGE_MAIN).map_err(|e| format!("{}: {e}", main.display()))?;
        c.arg(main);
    }
    run(&mut c, "verilator")?;
    if flavour.coverage {
        return make(mdir, run);
    }
    let cache = cache_dir(flavour.trace);
    let cached = cache.as_deref().map(runtime_objects).unwrap_or_default();
    for obj in &cached {
        if let Some(name) = obj.file_name() {
            // A failed copy only costs the compilation it would have saved.
            let _ = copy_whole(obj, &mdir.join(name));
        }
    }
    make(mdir, run)?;
    if let (Some(cache), true) = (cache, cached.is_empty()) {
        if std::fs::create_dir_all(cache).is_ok() {
            for obj in runtime_objects(mdir) {
                if let Some(name) = obj.file_name() {
                    let _ = copy_whole(&obj, &cache.join(name));
                }
            }
        }
    }
    Ok(mdir.join("simv"))
}

/// Verilator's C++ build in `mdir`; returns the executable.
fn make(
    mdir: &Path,
    run: &dyn Fn(&mut Command, &str) -> Result<(), String>,
) -> Result<PathBuf, String> {
    run(
        Command::new("make")
            .args(["-s", "-C"])
            .arg(mdir)
            .args(["-f", "Vtb.mk"]),
        "make (Verilator's C++ build)",
    )?;
    Ok(mdir.join("simv"))
}
