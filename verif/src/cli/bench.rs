//! `bench`: every twin of the project against Verilator on the same stimulus.

use super::args::{all, clap_args, given, one, path, value, values};
use super::CmdError;
use crate::bench::{check, measure_all, BenchConfig};
use crate::project::Project;
use crate::Seed;
use clap::{value_parser, ArgMatches, Command};
use std::path::PathBuf;

/// Every twin against Verilator on the same stimulus: cycles per second, untraced and traced.
#[derive(Debug)]
pub struct BenchArgs {
    /// Cycles of the untraced runs.
    pub cycles: usize,
    /// Cycles of the traced runs, VCD and FST.
    pub traced_cycles: usize,
    /// Rows of stimulus, replayed in a ring.
    pub stimulus_rows: usize,
    /// Units to measure (default every twin).
    pub unit: Vec<String>,
    /// Folder for the harnesses, builds, stimulus and table.md.
    pub out: Option<PathBuf>,
    /// Stimulus seed.
    pub seed: Seed,
    /// Rounds, alternating between the two sides.
    pub rounds: usize,
    /// Count instructions a cycle over this many cycles instead of timing.
    pub instructions: Option<usize>,
}

clap_args!(BenchArgs);

impl BenchArgs {
    pub(super) fn augment(c: Command) -> Command {
        c.args([
            value("cycles", "CYCLES", value_parser!(usize), "Cycles of the untraced runs (1..=100000000; in each round the two sides' passes take turns, at least three each, more until each side's take a second, and each side's fastest counts)").default_value("1000000"),
            value("traced-cycles", "TRACED_CYCLES", value_parser!(usize), "Cycles of the traced runs, VCD and FST (1..=10000000; one run a round)").default_value("1000000"),
            value("stimulus-rows", "ROWS", value_parser!(usize), "Rows of seeded stimulus (1..=100000000; at most CYCLES are drawn) that both sides replay in a ring, cycle c driving row c % ROWS: rows in the core's cache time the simulators, a row a cycle streamed from memory times the memory too").default_value("16384"),
            value("rounds", "ROUNDS", value_parser!(usize), "Rounds (1..=20), each measuring every mode on both sides in turn; a unit's row is its round with the median ratio, the range of the ratios beside it").default_value("3"),
            values("unit", "UNIT", value_parser!(String), "Units to measure (repeatable; default every twin)"),
            path("out", "OUT", "Folder for the harnesses, builds, stimulus and table.md (default target/NAME-bench; traces go to /dev/shm when there is one, and are deleted). Every harness is built, and checked to compute what its model does on the stimulus, before any unit is timed, and kept in the simulator cache (TEXRTL_SIM_CACHE; off: build every time)"),
            value("seed", "SEED", Seed::parse, "Stimulus seed").default_value("0xbe7c"),
            value("instructions", "CYCLES", value_parser!(usize), "Count instead of timing: instructions a cycle of each side, untraced, over CYCLES cycles after the first 1000 (1..=10000000; default 10000), under callgrind (needs valgrind; a count, which a busy machine does not move; the model's side runs this program again). The table also in instructions.md").num_args(0..=1).default_missing_value("10000"),
        ])
    }

    pub(super) fn read(m: &ArgMatches) -> Self {
        BenchArgs {
            cycles: given(m, "cycles"),
            traced_cycles: given(m, "traced-cycles"),
            stimulus_rows: given(m, "stimulus-rows"),
            unit: all(m, "unit"),
            out: one(m, "out"),
            seed: given(m, "seed"),
            rounds: given(m, "rounds"),
            instructions: one(m, "instructions"),
        }
    }
}

/// Measures and prints the table.
pub fn run(project: &Project, a: &BenchArgs) -> Result<String, CmdError> {
    // Run again by `--instructions` as the model's side of a count: that alone.
    if let Some(child) = crate::bench::count::child(project) {
        let child = child.map_err(CmdError::Input)?;
        return child
            .run(a.seed)
            .map(|()| String::new())
            .map_err(CmdError::Failed);
    }
    let cfg = BenchConfig {
        cycles: a.cycles,
        traced_cycles: a.traced_cycles,
        stimulus_rows: a.stimulus_rows,
        units: a.unit.clone(),
        out: a
            .out
            .clone()
            .unwrap_or_else(|| PathBuf::from(format!("target/{}-bench", project.name()))),
        seed: a.seed,
        rounds: a.rounds,
        instructions: a.instructions,
    };
    let units = check(project, &cfg).map_err(CmdError::Input)?;
    if let Some(w) = build_warning(cfg!(debug_assertions)) {
        eprintln!("{}: warning: {w}", project.name());
    }
    measure_all(&cfg, &units)
        .map(|t| t.trim_end().to_string())
        .map_err(CmdError::Failed)
}

/// What a benchmark of a debug build says before it starts: its model's figures are the
/// unoptimised code's (unit 602: 15 times slower), not the model's. A warning, not a refusal:
/// the build's profile is known only by what this library was compiled with, which a build
/// setting of the program's own (a release profile with debug assertions on) can belie.
fn build_warning(debug_assertions: bool) -> Option<&'static str> {
    debug_assertions.then_some(
        "a debug build (debug assertions on): the model's figures are its unoptimised code's; \
         measure a release build (cargo run --release -- bench)",
    )
}

#[cfg(test)]
mod tests {
    use super::build_warning;

    #[test]
    fn a_debug_build_is_named_as_one_a_release_build_is_not() {
        let w = build_warning(true).unwrap();
        assert!(w.contains("debug build") && w.contains("--release"), "{w}");
        assert_eq!(build_warning(false), None);
    }
}
