//! `texrtl cosim`: a unit's model against its Verilog twin, or against your own Verilog with
//! the same ports, on every output port of every cycle.

use super::CmdError;
use clap::Args;
use std::path::PathBuf;
use tb::cosim::{self, Simulator};
use verif::Seed;

/// Co-simulate a unit's model and Verilog (its twin in rtl/, or --rtl FILE.v of yours).
#[derive(Args, Debug)]
pub struct CosimArgs {
    /// The unit (its Verilog module name): address_150, replicate_152, blend_adjust_153,
    /// bilinear_65_68, tangent_155, rsqrt_156, normal_156.
    #[arg(long)]
    pub unit: String,
    /// verilator or icarus.
    #[arg(long, default_value = "verilator")]
    pub sim: String,
    /// Verilog sources of the unit to check instead of its twin (repeatable; they replace all
    /// of the twin's files, so a unit built on another, as normal_156 on rsqrt_156, needs both).
    #[arg(long)]
    pub rtl: Vec<PathBuf>,
    /// Cycles to simulate (1..=10000000), random inputs every cycle after 2 cycles of reset.
    #[arg(long, default_value_t = 100_000)]
    pub count: usize,
    /// Stimulus seed.
    #[arg(long, value_parser = Seed::parse, default_value = "0xc051")]
    pub seed: Seed,
    /// Folder for the testbench, stimulus, RTL outputs and the waveform (default
    /// target/texrtl-cosim/UNIT-SIM).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Runs it: exit 0 when every port agrees on every cycle, 1 at a difference, 2 bad input.
pub fn run(a: &CosimArgs) -> Result<String, CmdError> {
    let unit = cosim::unit(&a.unit)?;
    let sim = Simulator::parse(&a.sim)
        .ok_or_else(|| format!("--sim {}: verilator or icarus", formats::shorten(&a.sim)))?;
    if !(1..=10_000_000).contains(&a.count) {
        return Err(format!("--count {}: 1..=10000000 cycles", a.count).into());
    }
    if let Some(f) = a.rtl.iter().find(|f| !f.is_file()) {
        return Err(format!("--rtl {}: no such file", f.display()).into());
    }
    sim.check_installed()?;
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("target/texrtl-cosim/{}-{}", a.unit, sim.name())));
    let r =
        cosim::run(unit.as_ref(), sim, &a.rtl, a.count, a.seed, &dir).map_err(CmdError::Failed)?;
    let view = r.vcd.with_extension("gtkw");
    match &r.mismatch {
        None => Ok(format!(
            "{} in {}: {} cycles, every output port equal on every cycle (seed {}); waveform: gtkwave {}",
            a.unit,
            sim.name(),
            r.cycles,
            a.seed,
            view.display()
        )),
        Some(d) => {
            crate::say(&format!("{d}\n"));
            Err(CmdError::Failed(format!(
                "{} in {}: {} differences in {} cycles, the first at cycle {} on port {} (seed {}); waveform: gtkwave {}",
                a.unit,
                sim.name(),
                r.differences,
                r.cycles,
                d.cycle,
                d.port,
                a.seed,
                view.display()
            )))
        }
    }
}
