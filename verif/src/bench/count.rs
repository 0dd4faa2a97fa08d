//! `bench --instructions`: the instructions a cycle of each side, counted by callgrind: the
//! same on every run of the same builds, whatever else the machine runs, the figure to compare
//! on a shared machine, where a time ratio moves with the neighbours.
//!
//! Both sides run the same stimulus, untraced, in one pass, twice: over its first [`WARM`]
//! cycles and over `WARM + n`; a side's figure is the difference over `n`, so building the
//! design, reading the stimulus and leaving reset cancel out. The twin's harness is the timed
//! one, counted in its `main` (its clock reads and the start of Verilator's threads vary by a
//! few hundred instructions a run: a few hundredths a cycle over 10000 cycles). On the model's
//! side the program runs itself again under valgrind with its own arguments and [`CHILD`]
//! set, and callgrind counts the cycle loop alone (`--toggle-collect`), not the stimulus that
//! the child draws: exact.

use super::harness::Mode;
use crate::cosim::{BenchTrace, CosimUnit};
use crate::project::Project;
use crate::Seed;
use std::path::Path;
use std::process::Command;

/// The cycles before the counted ones: out of reset and warmed up.
pub const WARM: usize = 1000;

/// Set in the program's environment when it runs as the model's side of a count:
/// `UNIT:TOTAL:CYCLES` (run `CYCLES` cycles of the `TOTAL`-cycle stimulus).
pub const CHILD: &str = "TEXRTL_BENCH_COUNT";

/// The model's cycle loop, which callgrind counts.
const LOOP: &str = "--toggle-collect=*cosim::cycle_loop*";

/// Checks that valgrind is there.
pub fn check_valgrind() -> Result<(), String> {
    match Command::new("valgrind").arg("--version").output() {
        Ok(o) if o.status.success() => Ok(()),
        _ => {
            Err("--instructions: valgrind not found (Debian: apt-get install valgrind)".to_string())
        }
    }
}

/// What the model's side of a count runs ([`CHILD`]'s value, checked).
pub struct Child<'p> {
    unit: &'p dyn CosimUnit,
    total: usize,
    cycles: usize,
}

/// When this process is the model's side of a count ([`CHILD`] set): what it is to run, or
/// the variable's problem (bad input). `None` otherwise.
pub fn child(project: &Project) -> Option<Result<Child<'_>, String>> {
    let spec = std::env::var_os(CHILD)?;
    Some(parse_child(project, &spec.to_string_lossy()))
}

fn parse_child<'p>(project: &'p Project, spec: &str) -> Result<Child<'p>, String> {
    let bad = || {
        let shown = waves::output::shorten(spec);
        format!("{CHILD}={shown}: UNIT:TOTAL:CYCLES, CYCLES at most TOTAL, TOTAL at most 100000000")
    };
    let mut parts = spec.rsplitn(3, ':');
    let (Some(cycles), Some(total), Some(unit)) = (parts.next(), parts.next(), parts.next()) else {
        return Err(bad());
    };
    let cycles: usize = cycles.parse().map_err(|_| bad())?;
    let total: usize = total.parse().map_err(|_| bad())?;
    if cycles > total || total > 100_000_000 {
        return Err(bad());
    }
    let unit = project.twin(unit, CHILD)?;
    Ok(Child {
        unit,
        total,
        cycles,
    })
}

impl Child<'_> {
    /// Runs the model untraced over the first `cycles` cycles of the `total`-cycle stimulus.
    pub fn run(&self, seed: Seed) -> Result<(), String> {
        let stim = self.unit.stimulus(seed, self.total);
        let resets = crate::cosim::reset_cycles(self.unit);
        self.unit
            .model()?
            .bench(&stim, self.cycles, resets, BenchTrace::None)
            .map(|_| ())
    }
}

/// The instructions callgrind collected running `cmd` (its "Collected" line).
fn collected(mut cmd: Command, what: &str) -> Result<u64, String> {
    let o = cmd.output().map_err(|e| format!("valgrind: {e}"))?;
    let err = String::from_utf8_lossy(&o.stderr);
    if !o.status.success() {
        let first = err
            .lines()
            .find(|l| !l.starts_with("==") && !l.trim().is_empty())
            .unwrap_or("failed");
        return Err(format!("{what} under valgrind: {first}"));
    }
    parse_collected(&err).ok_or_else(|| format!("{what}: no count in callgrind's report"))
}

/// The number on callgrind's `==PID== Collected : N` line.
fn parse_collected(report: &str) -> Option<u64> {
    report
        .lines()
        .find_map(|l| l.split_once("Collected :"))
        .and_then(|(_, n)| n.trim().parse().ok())
}

/// `valgrind --tool=callgrind` with no output file, then `args`.
fn callgrind(args: &[&str]) -> Command {
    let mut c = Command::new("valgrind");
    c.args(["--tool=callgrind", "--callgrind-out-file=/dev/null"])
        .args(args);
    c
}

/// One unit's figures: instructions a cycle of the model and of the twin.
pub struct Counted {
    pub unit: String,
    pub model: f64,
    pub twin: f64,
}

/// Counts `unit` over `n` cycles after [`WARM`], its harness built (and checked against the
/// model, as the timing's is) and its stimulus written in `dir`.
pub fn count(unit: &dyn CosimUnit, seed: Seed, n: usize, dir: &Path) -> Result<Counted, String> {
    let total = WARM + n;
    let exes = super::harnesses(unit, &[Mode::Untraced], dir)?;
    let mut prepared = super::prepare(unit, seed, total, dir)?;
    let exe = &exes[0];
    super::check_twin(
        unit,
        &mut prepared,
        exe,
        total.min(super::CHECK_CYCLES),
        dir,
    )?;
    let bin = prepared.bin;
    let me = std::env::current_exe().map_err(|e| format!("this program: {e}"))?;
    let twin = |cycles: usize| -> Result<u64, String> {
        let mut c = callgrind(&["--toggle-collect=main"]);
        // The whole stimulus as rows: no cycle counted replays one.
        c.arg(exe)
            .arg(&bin)
            .arg(cycles.to_string())
            .arg(total.to_string());
        // Symbols bound at load, before `main`: bound lazily, the binding's instructions fell
        // inside or outside `main` as the harness's threads happened to run.
        c.current_dir(dir).env("LD_BIND_NOW", "1");
        collected(c, "the twin")
    };
    let model = |cycles: usize| -> Result<u64, String> {
        let mut c = callgrind(&[LOOP]);
        c.arg(&me).args(std::env::args_os().skip(1));
        c.env(CHILD, format!("{}:{total}:{cycles}", unit.name()));
        match collected(c, "the model")? {
            0 => Err("the model: callgrind found no cycle loop (a stripped program?)".into()),
            x => Ok(x),
        }
    };
    let per = |a: u64, b: u64| b.saturating_sub(a) as f64 / n as f64;
    Ok(Counted {
        unit: unit.name().to_string(),
        model: per(model(WARM)?, model(total)?),
        twin: per(twin(WARM)?, twin(total)?),
    })
}

/// The table of the counts.
pub fn table(seed: Seed, n: usize, rows: &[Counted]) -> String {
    let mut s = format!(
        "Instructions a cycle (callgrind), untraced, cycles {WARM}..{} of seed {seed}; ratio = Verilator / model (above 1: the model executes fewer).\n\n",
        WARM + n
    );
    s += "| unit | model | Verilator -O3 | ratio |\n|---|---:|---:|---:|\n";
    for r in rows {
        s += &line(r);
        s += "\n";
    }
    s
}

/// A row of the table.
pub fn line(r: &Counted) -> String {
    format!("| {} |{}", r.unit, cells(r))
}

/// The cells of a row after the unit's name: both counts and their ratio.
pub fn cells(r: &Counted) -> String {
    format!(
        " {:.1} | {:.1} | {:.2} |",
        r.model,
        r.twin,
        r.twin / r.model.max(f64::MIN_POSITIVE)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The count is the number on callgrind's summary line, whatever its process id.
    #[test]
    fn the_count_is_callgrinds_collected_line() {
        let report = "==123== Events    : Ir\n==123== Collected : 7683801\n==123==\n";
        assert_eq!(parse_collected(report), Some(7_683_801));
        assert_eq!(parse_collected("==1== Collected : x\n"), None);
        assert_eq!(parse_collected("no summary\n"), None);
    }

    /// A row's ratio is the twin's count over the model's.
    #[test]
    fn a_row_is_both_counts_and_their_ratio() {
        let r = Counted {
            unit: "u".into(),
            model: 800.0,
            twin: 1200.0,
        };
        assert_eq!(line(&r), "| u | 800.0 | 1200.0 | 1.50 |");
        let t = table(Seed(0xbe7c), 10_000, &[r]);
        assert!(
            t.contains("cycles 1000..11000 of seed 0x000000000000be7c"),
            "{t}"
        );
    }

    /// The child's specification is checked: three fields, numbers, the cycles within the
    /// stimulus.
    #[test]
    fn a_bad_child_specification_is_refused() {
        let p = Project::new("p", "0");
        for spec in ["u", "u:10", "u:x:1", "u:10:11", "u:10:y", "u:200000000:1"] {
            let Err(e) = parse_child(&p, spec) else {
                panic!("{spec} accepted")
            };
            assert!(e.contains("UNIT:TOTAL:CYCLES"), "{spec}: {e}");
        }
        let Err(e) = parse_child(&p, "u:10:5") else {
            panic!("a unit with no twin accepted")
        };
        assert!(e.contains("no Verilog twin"), "{e}");
    }
}
