//! `cosim`: a unit's model against its Verilog twin, or against your own Verilog with the same
//! ports, on every output port of every cycle (under the unit's compare rules).

use super::args::{all, clap_args, flag, given, one, path, value, values};
use super::CmdError;
use crate::cosim::{self, FileList, PathsFrom, Simulator};
use crate::project::Project;
use crate::Seed;
use clap::{value_parser, ArgMatches, Command};
use std::path::{Path, PathBuf};
use waves::output::shorten;

/// Co-simulate a unit's model and Verilog (its twin, or --rtl FILE.v of yours).
#[derive(Debug)]
pub struct CosimArgs {
    /// The unit (its Verilog module name; `list` names the units with a twin).
    pub unit: String,
    /// verilator or icarus.
    pub sim: String,
    /// Verilog sources of the unit to check instead of its twin.
    pub rtl: Vec<PathBuf>,
    /// Cycles to simulate.
    pub count: usize,
    /// Stimulus seed.
    pub seed: Seed,
    /// random or vectors.
    pub stimulus: String,
    /// Folder for the testbench, stimulus, RTL outputs and the waveform.
    pub out: Option<PathBuf>,
    /// Folders searched for `include files, besides the unit's.
    pub incdir: Vec<PathBuf>,
    /// Preprocessor macros, besides the unit's.
    pub define: Vec<String>,
    /// The Verilog module to instantiate instead of the unit's top.
    pub top: Option<String>,
    /// File lists of the sources to check instead of the twin's, in command-line order:
    /// `-f` (relative paths from the current folder) and `-F` (from the list's folder).
    pub filelist: Vec<(PathBuf, PathsFrom)>,
    /// Leave the RTL's internals out: no dump compiled in, no second run at a difference.
    pub no_internals: bool,
    /// Measure the RTL's line and toggle coverage (Verilator's).
    pub rtl_coverage: bool,
}

clap_args!(CosimArgs);

impl CosimArgs {
    pub(super) fn augment(c: Command) -> Command {
        c.args([
            value("unit", "UNIT", value_parser!(String), "The unit (its Verilog module name; `list` names the units with a twin)").required(true),
            value("sim", "SIM", value_parser!(String), "verilator or icarus").default_value("verilator"),
            values("rtl", "RTL", value_parser!(PathBuf), "Verilog sources of the unit to check instead of its twin (repeatable; they replace all of the twin's own files, so a unit built on another needs both; the testbench-side sources, such as behavioural memories, stay)"),
            value("count", "COUNT", value_parser!(usize), "Cycles to simulate (1..=10000000): the unit's seeded stimulus, after its reset cycles").default_value("100000"),
            value("seed", "SEED", Seed::parse, "Stimulus seed").default_value("0xc051"),
            value("stimulus", "STIMULUS", value_parser!(String), "random (seeded, --count cycles) or vectors: the unit's directed runs (the transactions of its regression vectors, in their configuration; one run per configuration, in folders under --out)").default_value("random"),
            path("out", "OUT", "Folder for the testbench, stimulus, RTL outputs and the waveform (default target/NAME-cosim/UNIT-SIM, NAME the program's)"),
            values("incdir", "DIR", value_parser!(PathBuf), "A folder searched for `include files, after each source's own folder and the unit's (repeatable)"),
            values("define", "MACRO", value_parser!(String), "A preprocessor macro for the build, NAME or NAME=VALUE (repeatable; after the unit's)"),
            value("top", "MODULE", value_parser!(String), "The Verilog module the testbench instantiates, when yours is not named as the unit's top (its ports and parameters the same)"),
            values("filelist", "LIST", value_parser!(PathBuf), "A file list of Verilog sources to check instead of the twin's, with +incdir+, +define+, -I, -D, libraries (-y, -v, +libext+) and nested -f/-F; relative paths from the current folder (repeatable; its sources after --rtl's)").short('f'),
            values("filelist-relative", "LIST", value_parser!(PathBuf), "As -f, relative paths taken from the list's own folder").short('F'),
            flag("no-internals", "Leave the RTL's internal signals out of the waveform: by default a difference is run again, dumping them around it, on a build with the dump compiled in (Verilator's with --trace, slower to build)"),
            flag("rtl-coverage", "Measure which of the RTL's blocks the stimulus reached and which of its signal bits toggled (Verilator's line and toggle coverage; a build of its own, never taken from the cache): a summary line, OUT/coverage.dat, an lcov file (coverage.info) and annotated sources"),
        ])
    }

    pub(super) fn read(m: &ArgMatches) -> Self {
        CosimArgs {
            unit: given(m, "unit"),
            sim: given(m, "sim"),
            rtl: all(m, "rtl"),
            count: given(m, "count"),
            seed: given(m, "seed"),
            stimulus: given(m, "stimulus"),
            out: one(m, "out"),
            incdir: all(m, "incdir"),
            define: all(m, "define"),
            top: one(m, "top"),
            filelist: file_lists(m),
            no_internals: m.get_flag("no-internals"),
            rtl_coverage: m.get_flag("rtl-coverage"),
        }
    }
}

/// `-f` and `-F` lists in command-line order.
fn file_lists(m: &ArgMatches) -> Vec<(PathBuf, PathsFrom)> {
    let mut lists: Vec<(usize, PathBuf, PathsFrom)> = Vec::new();
    for (id, from) in [
        ("filelist", PathsFrom::Cwd),
        ("filelist-relative", PathsFrom::List),
    ] {
        let at = m.indices_of(id).into_iter().flatten();
        let paths = all::<PathBuf>(m, id);
        lists.extend(at.zip(paths).map(|(k, p)| (k, p, from)));
    }
    lists.sort_by_key(|l| l.0);
    lists.into_iter().map(|(_, p, from)| (p, from)).collect()
}

/// Runs it: exit 0 when every port agrees on every cycle, 1 at a difference, 2 bad input.
pub fn run(project: &Project, a: &CosimArgs) -> Result<String, CmdError> {
    let vectors = match a.stimulus.as_str() {
        "random" => false,
        "vectors" => true,
        s => return Err(format!("--stimulus {}: random or vectors", shorten(s)).into()),
    };
    let unit = project.twin(&a.unit, "--unit")?;
    let sim = Simulator::parse(&a.sim)
        .ok_or_else(|| format!("--sim {}: verilator or icarus", shorten(&a.sim)))?;
    if a.rtl_coverage && sim != Simulator::Verilator {
        return Err(String::from(
            "--rtl-coverage: the coverage is Verilator's; not with --sim icarus",
        )
        .into());
    }
    if !(1..=10_000_000).contains(&a.count) {
        return Err(format!("--count {}: 1..=10000000 cycles", a.count).into());
    }
    if let Some(m) = a.define.iter().find(|m| !cosim::is_define(m)) {
        return Err(format!("--define {}: not NAME or NAME=VALUE", shorten(m)).into());
    }
    if let Some(t) = a.top.as_deref().filter(|t| !cosim::is_identifier(t)) {
        return Err(format!("--top {}: not a Verilog module name", shorten(t)).into());
    }
    if let Some(d) = a.incdir.iter().find(|d| !d.is_dir()) {
        return Err(format!("--incdir {}: no such folder", d.display()).into());
    }
    if let Some(f) = a.rtl.iter().find(|f| !f.is_file()) {
        let why = if f.symlink_metadata().is_ok() {
            "not a regular file"
        } else {
            "no such file"
        };
        return Err(format!("--rtl {}: {why}", f.display()).into());
    }
    for (list, from) in &a.filelist {
        let option = match from {
            PathsFrom::Cwd => "-f/--filelist",
            PathsFrom::List => "-F/--filelist-relative",
        };
        FileList::read(list, *from).map_err(|e| format!("{option} {e}"))?;
    }
    let runs = match project.get(&a.unit).and_then(|u| u.directed_runs()) {
        Some(f) if vectors => f()?,
        None if vectors => {
            let with: Vec<&str> = project
                .units()
                .filter(|u| u.twin_unit().is_some() && u.directed_runs().is_some())
                .map(|u| u.name())
                .collect();
            return Err(format!(
                "--unit {}: no directed runs with a twin (there are: {})",
                shorten(&a.unit),
                with.join(", ")
            )
            .into());
        }
        _ => Vec::new(),
    };
    sim.check_installed()?;
    let name = project.name();
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("target/{name}-cosim/{}-{}", a.unit, sim.name())));
    super::check_folder("--out", &dir)?;
    // Watched given or not: RTL that does not build leaves nothing behind.
    let mut made = super::Outputs::default();
    made.folder(&dir);
    made.settle(simulate(a, sim, unit, &runs, &dir))
}

/// The co-simulation runs once the options are checked.
fn simulate(
    a: &CosimArgs,
    sim: Simulator,
    unit: &dyn cosim::CosimUnit,
    runs: &[cosim::Directed],
    dir: &Path,
) -> Result<String, CmdError> {
    let vectors = a.stimulus == "vectors";
    let with = |unit| Preprocessed { unit, a };
    let options = cosim::RunOptions {
        internals: !a.no_internals,
        rtl_coverage: a.rtl_coverage,
        waveform_on_difference_only: false,
    };
    let go = |unit: &dyn cosim::CosimUnit, stim: &[Vec<u64>], dir: &Path| {
        cosim::run_with_options(unit, sim, &[], stim, dir, options).map_err(|e| {
            // The model panicking is a finding (exit 1); the rest, the RTL and the options.
            match e.contains(cosim::MODEL_PANICKED) {
                true => CmdError::Failed(e),
                false => CmdError::Input(e),
            }
        })
    };
    if !vectors {
        let unit = &with(unit);
        let stim = cosim::CosimUnit::stimulus(unit, a.seed, a.count);
        let r = go(unit, &stim, dir)?;
        let what = format!("{} in {} (seed {})", a.unit, sim.name(), a.seed);
        return report(&what, &r);
    }
    let (mut lines, mut covered) = (Vec::new(), Vec::new());
    for d in runs {
        let r = go(&with(d.unit.as_ref()), &d.stimulus, &dir.join(&d.label))?;
        let what = format!("{} in {} ({})", a.unit, sim.name(), d.label);
        lines.push(report(&what, &r)?);
        covered.extend(r.rtl_coverage);
    }
    if covered.len() > 1 {
        let all: Vec<&cosim::RtlCoverage> = covered.iter().collect();
        let merged = cosim::RtlCoverage::merge(&all, dir).map_err(CmdError::Input)?;
        super::say(&format!("the {} runs together: {merged}\n", all.len()));
    }
    Ok(lines.join("\n"))
}

/// The run's one line: agreement, or the first difference (printed in full) as a failure.
fn report(what: &str, r: &cosim::CosimResult) -> Result<String, CmdError> {
    // `cosim` always writes the waveform (its options never leave it out).
    let view = r
        .vcd
        .as_deref()
        .unwrap_or(Path::new(""))
        .with_extension("gtkw");
    if let Some(c) = &r.rtl_coverage {
        super::say(&format!("{c}\n"));
    }
    match &r.mismatch {
        None => Ok(format!(
            "{what}: {} cycles, every output port equal on every cycle; waveform: gtkwave {}",
            r.cycles,
            view.display()
        )),
        Some(d) => {
            super::say(&format!("{d}\n"));
            if let Some(note) = &r.internals {
                super::say(&format!("{note}\n"));
            }
            Err(CmdError::Failed(format!(
                "{what}: {} differences in {} cycles, the first at cycle {} on port {}; waveform: gtkwave {}",
                r.differences,
                r.cycles,
                d.cycle,
                d.port,
                view.display()
            )))
        }
    }
}

/// A unit with the command line's `--incdir` and `--define` after its own, its `--top`, and
/// its `--rtl` and file lists in place of the unit's own sources.
struct Preprocessed<'a> {
    unit: &'a dyn cosim::CosimUnit,
    a: &'a CosimArgs,
}

impl Preprocessed<'_> {
    /// Whether the command line gives the sources.
    fn replaced(&self) -> bool {
        !self.a.rtl.is_empty() || !self.a.filelist.is_empty()
    }
}

impl cosim::CosimUnit for Preprocessed<'_> {
    fn name(&self) -> &str {
        self.unit.name()
    }
    fn top(&self) -> &str {
        self.a.top.as_deref().unwrap_or(self.unit.top())
    }
    fn rtl(&self) -> Vec<PathBuf> {
        if self.replaced() {
            self.a.rtl.clone()
        } else {
            self.unit.rtl()
        }
    }
    fn file_lists(&self) -> Vec<(PathBuf, PathsFrom)> {
        if self.replaced() {
            self.a.filelist.clone()
        } else {
            self.unit.file_lists()
        }
    }
    fn bench_rtl(&self) -> Vec<PathBuf> {
        self.unit.bench_rtl()
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        self.unit.parameters()
    }
    fn model(&self) -> Result<Box<dyn cosim::CosimModel>, String> {
        self.unit.model()
    }
    fn stimulus(&self, seed: Seed, cycles: usize) -> Vec<Vec<u64>> {
        self.unit.stimulus(seed, cycles)
    }
    fn clocking(&self) -> Option<cosim::Clocking> {
        self.unit.clocking()
    }
    fn compare(&self) -> Vec<cosim::Compare> {
        self.unit.compare()
    }
    fn history(&self) -> usize {
        self.unit.history()
    }
    fn memories(&self) -> Vec<(String, String)> {
        self.unit.memories()
    }
    fn unmodelled(&self) -> Vec<cosim::Unmodelled> {
        self.unit.unmodelled()
    }
    fn include_dirs(&self) -> Vec<PathBuf> {
        [self.unit.include_dirs(), self.a.incdir.clone()].concat()
    }
    fn defines(&self) -> Vec<String> {
        [self.unit.defines(), self.a.define.clone()].concat()
    }
}
