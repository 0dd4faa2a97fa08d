//! `bench`: every twin of the project against Verilator on the same stimulus.

use super::CmdError;
use crate::bench::{check, measure_all, BenchConfig};
use crate::project::Project;
use crate::Seed;
use clap::Args;
use std::path::PathBuf;

/// Every twin against Verilator on the same stimulus: cycles per second, untraced and traced.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Cycles of the untraced runs (1..=100000000; the fastest of three passes counts).
    #[arg(long, default_value_t = 1_000_000)]
    pub cycles: usize,
    /// Cycles of the traced runs, VCD and FST (1..=10000000; the fastest of three runs counts).
    #[arg(long, default_value_t = 1_000_000)]
    pub traced_cycles: usize,
    /// Units to measure (repeatable; default every twin).
    #[arg(long)]
    pub unit: Vec<String>,
    /// Folder for the harnesses, builds, stimulus and table.md (default target/NAME-bench;
    /// traces go to /dev/shm when there is one, and are deleted).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Stimulus seed.
    #[arg(long, value_parser = Seed::parse, default_value = "0xbe7c")]
    pub seed: Seed,
}

/// Measures and prints the table.
pub fn run(project: &Project, a: &BenchArgs) -> Result<String, CmdError> {
    let cfg = BenchConfig {
        cycles: a.cycles,
        traced_cycles: a.traced_cycles,
        units: a.unit.clone(),
        out: a
            .out
            .clone()
            .unwrap_or_else(|| PathBuf::from(format!("target/{}-bench", project.name()))),
        seed: a.seed,
    };
    let units = check(project, &cfg).map_err(CmdError::Input)?;
    measure_all(&cfg, &units)
        .map(|t| t.trim_end().to_string())
        .map_err(CmdError::Failed)
}
