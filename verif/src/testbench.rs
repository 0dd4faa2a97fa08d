//! The testbench interface and the registry that `texrtl regress`, sharding, `merge`, the
//! report and the progress bar all iterate.
//!
//! A testbench is a set of named **configurations** (a width, a mode, a trace, a frame size):
//! the unit of sharding and of seeding. The framework runs each configuration the shard owns
//! with its own seed (so shards together run exactly what one unsharded run does), merges the
//! results, and decides pass or fail the same way for every testbench: no mismatch, no
//! failure, and (for a whole run) no coverage hole.

use crate::coverage::Coverage;
use crate::random::{Seed, Shard};
use crate::result::TbResult;
use std::path::PathBuf;
use waves::TraceConfig;

/// What a configuration is run with; built by [`run_testbench`].
#[derive(Clone, Debug)]
pub struct Ctx {
    /// The configuration's index in [`Testbench::configurations`] and its label.
    pub index: usize,
    pub label: String,
    /// This configuration's own seed (derived from the run's seed, the testbench's name and
    /// the index).
    pub seed: Seed,
    /// Random transactions to run (the testbench's default unless `--count` set it).
    pub count: usize,
    /// Where to write the waveform, when this is the traced configuration and waves are on.
    pub waves: Option<WaveOut>,
    /// Run the kernel's schedule check on every cycle.
    pub check_schedule: bool,
}

/// A waveform to write: the VCD's path and what to trace.
#[derive(Clone, Debug)]
pub struct WaveOut {
    pub vcd: PathBuf,
    pub trace: TraceConfig,
    /// The clock period the user asked for; `None`: the testbench's own clock.
    pub period_ps: Option<u64>,
}

impl WaveOut {
    /// The trace configuration for a design clocked at `own_period_ps` unless the user set one.
    pub fn config(&self, own_period_ps: u64) -> TraceConfig {
        TraceConfig {
            period_ps: self.period_ps.unwrap_or(own_period_ps),
            ..self.trace.clone()
        }
    }
}

/// A testbench: named configurations, a coverage model, and a run of one configuration.
pub trait Testbench: Sync {
    /// Its name in the table, in `summary.json`, in `--only` and as its waveform's file name.
    fn name(&self) -> &'static str;
    /// The unit it verifies, with its number and where the document describes it.
    fn unit(&self) -> &'static str;
    /// The labels of its configurations, in run order.
    fn configurations(&self) -> Vec<String>;
    /// Random transactions per configuration when `--count` is not given, and what one is.
    fn default_count(&self) -> usize;
    fn count_unit(&self) -> &'static str {
        "random transactions"
    }
    /// The configuration that writes the waveform.
    fn traced(&self) -> usize {
        0
    }
    /// A fresh coverage model (no hits); every configuration's result carries one like it.
    fn coverage(&self) -> Coverage;
    /// Runs one configuration. `Err` is for what stops the run (bad parameters, I/O); what the
    /// DUT got wrong goes into the result.
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String>;
    /// After every configuration (or every shard, in `texrtl merge`): notes and tables from the
    /// merged records and extra checks across configurations.
    fn conclude(&self, _merged: &mut TbResult) {}
}

/// What a regression run applies to every testbench.
#[derive(Clone, Debug)]
pub struct RunOptions {
    pub seed: Seed,
    /// Random transactions per configuration; `None`: each testbench's default.
    pub count: Option<usize>,
    pub shard: Shard,
    /// Write each testbench's waveform into this folder as `<name>.vcd` + `.gtkw`.
    pub waves: Option<(PathBuf, TraceConfig, Option<u64>)>,
    pub check_schedule: bool,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            seed: Seed(0),
            count: None,
            shard: Shard::default(),
            waves: None,
            check_schedule: false,
        }
    }
}

/// The seed of configuration `index` of testbench `name` in a run seeded `seed`.
pub fn config_seed(seed: Seed, name: &str, index: usize) -> Seed {
    // FNV-1a of the name: stable across builds and platforms.
    let h = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    seed.derive(h).derive(index as u64)
}

/// Runs every configuration of `tb` that the shard owns, calling `progress` with each label
/// before it runs, and merges the results; pass/fail as the module says.
pub fn run_testbench(
    tb: &dyn Testbench,
    opts: &RunOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<TbResult, String> {
    let mut merged = TbResult::new(tb.name(), tb.unit());
    merged.seed = Some(opts.seed.to_string());
    merged.coverage = Some(tb.coverage());
    for (index, label) in tb.configurations().into_iter().enumerate() {
        if !opts.shard.owns(index as u64) {
            continue;
        }
        progress(&label);
        let waves = opts.waves.as_ref().filter(|_| index == tb.traced());
        let ctx = Ctx {
            index,
            seed: config_seed(opts.seed, tb.name(), index),
            count: opts.count.unwrap_or_else(|| tb.default_count()),
            waves: waves.map(|(dir, trace, period_ps)| WaveOut {
                vcd: dir.join(format!("{}.vcd", tb.name())),
                trace: trace.clone(),
                period_ps: *period_ps,
            }),
            check_schedule: opts.check_schedule,
            label,
        };
        let r = tb
            .run(&ctx)
            .map_err(|e| format!("{} [{}]: {e}", tb.name(), ctx.label))?;
        merged
            .absorb(&r, Some(&ctx.label))
            .map_err(|e| format!("{} [{}]: {e}", tb.name(), ctx.label))?;
    }
    conclude(tb, &mut merged, opts.shard.is_all());
    Ok(merged)
}

/// The framework's verdict on a merged result: coverage figures, the testbench's own
/// conclusions, then pass/fail (holes fail only a whole run).
pub fn conclude(tb: &dyn Testbench, merged: &mut TbResult, whole_run: bool) {
    if let Some(c) = merged.coverage.take() {
        merged.set_coverage(c);
    }
    merged.strip_conclusions();
    merged.own = Some((merged.notes.len(), merged.tables.len()));
    tb.conclude(merged);
    merged.finish_with(whole_run);
}

/// The testbenches of a project, in run order.
#[derive(Default)]
pub struct Registry {
    tbs: Vec<Box<dyn Testbench>>,
}

impl Registry {
    pub fn new() -> Registry {
        Registry::default()
    }

    /// Adds a testbench; its name must be new.
    pub fn register(&mut self, tb: Box<dyn Testbench>) -> &mut Self {
        assert!(
            self.get(tb.name()).is_none(),
            "testbench '{}' registered twice",
            tb.name()
        );
        self.tbs.push(tb);
        self
    }

    pub fn iter(&self) -> impl Iterator<Item = &dyn Testbench> {
        self.tbs.iter().map(|b| b.as_ref())
    }

    pub fn get(&self, name: &str) -> Option<&dyn Testbench> {
        self.iter().find(|t| t.name() == name)
    }

    pub fn names(&self) -> Vec<&'static str> {
        self.iter().map(|t| t.name()).collect()
    }

    /// The position of `name` in run order.
    pub fn position(&self, name: &str) -> Option<usize> {
        self.iter().position(|t| t.name() == name)
    }

    /// Configurations a shard runs, over every testbench (for a progress bar).
    pub fn owned_configurations(&self, shard: Shard, only: &[String]) -> u64 {
        self.iter()
            .filter(|t| only.is_empty() || only.iter().any(|o| o == t.name()))
            .map(|t| {
                (0..t.configurations().len() as u64)
                    .filter(|&i| shard.owns(i))
                    .count() as u64
            })
            .sum()
    }
}
