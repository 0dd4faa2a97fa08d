//! A project's regression: every testbench on its built-in stimulus, the bit-accuracy vectors
//! and the co-simulation of every twin, with waveforms and `summary.json`; and the merge of
//! the summaries of a run's shards into the one an unsharded run writes.

use crate::cosim::Simulator;
use crate::jobs::{self, JobResult};
use crate::project::Project;
use crate::TbResult;
use crate::{Registry, RunOptions, Seed};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
#[cfg(feature = "read")]
use waves::check::{check_gtkw, read_vcd};
use waves::output::write_output;
use waves::TraceConfig;

/// The name of the bit-accuracy vectors row (a check of fixed stimuli, not a testbench).
pub const VECTORS: &str = "vectors";

/// The prefix of the co-simulation rows (`cosim/<unit>/<simulator>`; `--only cosim`).
pub const COSIM: &str = "cosim";

mod cosim;
mod merge;
pub(crate) use cosim::{command as cosim_command, AGAIN};
pub use cosim::{cosim_seed, CosimJob, JobCoverage, COSIM_CYCLES};
pub use merge::{merge, merge_shards, parse_summary, read_summaries};

/// `summary.json`: every result, the seed, the shard and the project's version.
#[derive(Clone, Serialize, Deserialize)]
pub struct Summary {
    /// The version of the project that wrote it (shards of different versions do not merge).
    pub texrtl: String,
    /// The run's seed, as it replays it (`--seed`).
    pub seed: String,
    /// Seeds each configuration ran under (`--seeds`; 1 is not written).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub seeds: u32,
    /// `--count`, when the run was given one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<usize>,
    /// `--only`: the testbenches the run selected (empty: all).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub only: Vec<String>,
    /// `I/N` when the run was one shard of N.
    pub shard: Option<String>,
    /// Whether every row passed.
    pub passed: bool,
    /// Every row: each testbench, the vectors, each co-simulation, in run order.
    pub testbenches: Vec<TbResult>,
    /// Every job that failed, in job order, with the command that reproduces it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub failing: Vec<FailingJob>,
    /// A shard's jobs one by one, for the merge (not in a whole run's summary).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub jobs: Vec<JobResult>,
    /// A shard's simulators, whose co-simulation jobs the run has (not in a whole run's
    /// summary).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub simulators: Vec<String>,
    /// A shard's co-simulation jobs one by one, for the merge (not in a whole run's summary).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub cosim_jobs: Vec<CosimJob>,
    /// With `--rtl-coverage`: what every co-simulation of the run reached of each RTL source
    /// file, whichever rows, instances and seeds it was reached in.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rtl_coverage: Vec<crate::cosim::FileCoverage>,
}

fn one() -> u32 {
    1
}

fn is_one(n: &u32) -> bool {
    *n == 1
}

/// A job that failed: which, under which seed, and the one command that runs it again alone
/// with its waveform (windowed around its first mismatch when the scoreboard saw its cycle).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FailingJob {
    /// The job's index (`--job` runs a testbench's; a co-simulation's runs again with its
    /// `cosim` command).
    pub job: u64,
    /// Its testbench.
    pub testbench: String,
    /// Its configuration's label.
    pub configuration: String,
    /// Which of the run's seeds, from 0.
    pub repeat: u32,
    /// The job's own seed (the configuration's under that repeat).
    pub seed: String,
    /// The cycle of its first mismatch, where the scoreboard saw one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_mismatch_cycle: Option<u64>,
    /// Its first mismatch or failure.
    pub first: String,
    /// The command that reproduces it.
    pub reproduce: String,
}

/// Cycles traced before a failing job's first mismatch, and after it, in its reproduction.
pub const WINDOW: (u64, u64) = (64, 16);

/// The failing jobs among `results` of `tb` in a run of `project` with `seed`, `seeds` and
/// `count`.
pub fn failing_jobs(
    project: &Project,
    run: (Seed, u32, Option<usize>),
    tb: &dyn crate::Testbench,
    results: &[JobResult],
) -> Vec<FailingJob> {
    let seed = run.0;
    let labels = tb.configurations();
    results
        .iter()
        .filter(|j| j.result.failed_itself())
        .map(|j| {
            let cmd = reproduce(project, run, j);
            let c = j.result.first_mismatch_cycle;
            let first = j.result.mismatch_log.first().or(j.result.failures.first());
            FailingJob {
                job: j.index,
                testbench: tb.name().to_string(),
                configuration: labels.get(j.configuration).cloned().unwrap_or_default(),
                repeat: j.repeat,
                seed: crate::jobs::job_seed(seed, tb.name(), j.configuration, j.repeat).to_string(),
                first_mismatch_cycle: c,
                first: first.cloned().unwrap_or_default(),
                reproduce: cmd,
            }
        })
        .collect()
}

/// The command that runs job `j` of a run `(seed, seeds, count)` of `project` again, alone,
/// with its waveform: traced from [`WINDOW`] before its first mismatch to after it, when the
/// scoreboard saw the mismatch's cycle.
pub fn reproduce(project: &Project, run: (Seed, u32, Option<usize>), j: &JobResult) -> String {
    let (seed, seeds, count) = run;
    let name = project.name();
    let mut cmd = format!("{name} regress --seed {seed}");
    if seeds != 1 {
        cmd.push_str(&format!(" --seeds {seeds}"));
    }
    if let Some(n) = count {
        cmd.push_str(&format!(" --count {n}"));
    }
    cmd.push_str(&format!(
        " --job {} --out target/{name}-job-{}",
        j.index, j.index
    ));
    if let Some(c) = j.result.first_mismatch_cycle {
        cmd.push_str(&format!(
            " --trace-window {}..{}",
            c.saturating_sub(WINDOW.0),
            c + WINDOW.1
        ));
    }
    cmd
}

/// What `texrtl regress` runs with.
#[derive(Clone, Debug)]
pub struct RegressConfig {
    /// The folder of the waveforms, `summary.json` and `report.md`.
    pub out: PathBuf,
    /// The run's seed (each configuration draws its own from it).
    pub seed: Seed,
    /// Write a VCD and `.gtkw` per testbench.
    pub vcd: bool,
    /// What the waveforms trace.
    pub trace: TraceConfig,
    /// The clock period of every waveform; `None`: each testbench's own clock.
    pub period_ps: Option<u64>,
    /// This run's share of the configurations.
    pub shard: crate::Shard,
    /// Random transactions per configuration (`None`: each testbench's default).
    pub count: Option<usize>,
    /// Also write each waveform as FST (the models' while simulating, the twins' from their
    /// VCD; with the `read` feature each is read back and compared with its VCD).
    pub fst: bool,
    /// Run only these testbenches (empty: all, and the vectors check).
    pub only: Vec<String>,
    /// Run the kernel's schedule check on every cycle.
    pub check_schedule: bool,
    /// Co-simulate every Verilog twin (each under each of the run's seeds, as jobs dealt to
    /// shards with the testbenches').
    pub cosim: bool,
    /// The simulators to co-simulate in (`--sim`); empty: every one installed for a whole
    /// run, both for a shard (a shard's jobs must not depend on its machine).
    pub simulators: Vec<Simulator>,
    /// Configurations run at once (threads); the results do not depend on it.
    pub jobs: usize,
    /// Seeds each configuration runs under: the run's jobs ([`crate::jobs`]).
    pub seeds: u32,
    /// Run only this job, with its waveform (a failing job's reproduction); no vectors, no
    /// co-simulation.
    pub job: Option<u64>,
    /// Also write the run's JUnit XML here ([`crate::junit`]).
    pub junit: Option<PathBuf>,
    /// Fail a testbench whose narrowings left an overflow or tie path untaken (numeric
    /// coverage holes; decided for a whole run, or by `merge` for a sharded one).
    pub require_numeric: bool,
    /// Measure the RTL's coverage in the Verilator co-simulation rows
    /// ([`crate::cosim::RtlCoverage`]), said in each row's notes.
    pub rtl_coverage: bool,
}

impl RegressConfig {
    /// What `regress` runs with when given only `--out DIR`: the default seed, waveforms
    /// traced, every testbench once under its own count, co-simulation on, one job per core.
    pub fn new(out: impl Into<PathBuf>) -> RegressConfig {
        RegressConfig {
            out: out.into(),
            seed: Seed(0x7e47),
            vcd: true,
            trace: TraceConfig::default(),
            period_ps: None,
            shard: crate::Shard::parse("1/1").expect("the whole run"),
            count: None,
            fst: false,
            only: Vec::new(),
            check_schedule: false,
            cosim: true,
            simulators: Vec::new(),
            jobs: std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get),
            seeds: 1,
            job: None,
            junit: None,
            require_numeric: false,
            rtl_coverage: false,
        }
    }

    /// Random transactions per configuration at most (`--count`).
    pub const MAX_COUNT: usize = 1_000_000;

    /// Checks the options: the names in `only` against the registry, `--count` in range.
    pub fn validate(&self, reg: &Registry) -> Result<(), String> {
        // A count of 0 leaves random testbenches nothing to compare: refused, not run.
        if let Some(n) = self.count.filter(|&n| n == 0 || n > Self::MAX_COUNT) {
            return Err(format!(
                "--count {n}: 1..={} random transactions per configuration",
                Self::MAX_COUNT
            ));
        }
        if !(1..=256).contains(&self.jobs) {
            return Err(format!("--jobs {}: 1..=256 threads", self.jobs));
        }
        // What the run writes at the end must be writable before it starts: a folder where
        // summary.json goes left every waveform behind.
        let summary = self.out.join("summary.json");
        if summary.is_dir() {
            return Err(format!("--out: {} is a folder", summary.display()));
        }
        if let Some(j) = &self.junit {
            if j.is_dir() {
                return Err(format!("--junit {}: is a folder", j.display()));
            }
            // Where the file goes must be there before the run, not found missing after it
            // (or be the output folder, which the run makes).
            let parent = j.parent().filter(|p| !p.as_os_str().is_empty());
            if let Some(p) = parent.filter(|p| !p.is_dir() && *p != self.out) {
                return Err(format!(
                    "--junit {}: no folder {}",
                    j.display(),
                    p.display()
                ));
            }
        }
        self.validate_simulators()?;
        for o in &self.only {
            if reg.get(o).is_none() && o != VECTORS && o != COSIM {
                return Err(format!(
                    "--only: no testbench '{o}' (there are: {}, {VECTORS}, {COSIM})",
                    reg.names().join(", ")
                ));
            }
        }
        self.validate_jobs(reg)
    }

    /// `--sim`: each once, installed, and not with `--no-cosim`.
    fn validate_simulators(&self) -> Result<(), String> {
        let Some(first) = self.simulators.first() else {
            return Ok(());
        };
        if !self.cosim {
            return Err(format!("--sim {}: not with --no-cosim", first.name()));
        }
        for (k, s) in self.simulators.iter().enumerate() {
            if self.simulators[..k].contains(s) {
                return Err(format!("--sim {}: given twice", s.name()));
            }
            s.check_installed()
                .map_err(|e| format!("--sim {}: {e}", s.name()))?;
        }
        Ok(())
    }

    /// `--seeds` and `--job`: in range, and a job is run alone.
    fn validate_jobs(&self, reg: &Registry) -> Result<(), String> {
        if !(1..=jobs::MAX_SEEDS).contains(&self.seeds) {
            return Err(format!(
                "--seeds {}: 1..={} seeds per configuration",
                self.seeds,
                jobs::MAX_SEEDS
            ));
        }
        let n = jobs::count(reg, self.seeds, &|t| self.selected(t));
        if n > jobs::MAX_JOBS {
            return Err(format!(
                "--seeds {}: {n} jobs; a run has at most {}",
                self.seeds,
                jobs::MAX_JOBS
            ));
        }
        let Some(j) = self.job else { return Ok(()) };
        if !self.only.is_empty() || !self.shard.is_all() {
            return Err(format!(
                "--job {j}: runs one job; give no --only or --shard"
            ));
        }
        let all = jobs::count(reg, self.seeds, &|_| true);
        if j >= all {
            return Err(format!(
                "--job {j}: the jobs are 0..{all} (with --seeds {})",
                self.seeds
            ));
        }
        Ok(())
    }

    pub(crate) fn selected(&self, name: &str) -> bool {
        self.only.is_empty() || self.only.iter().any(|o| o == name)
    }
}

/// What [`run_jobs_of`] gives: the rows, the failing jobs, the jobs' own results.
type Ran = (Vec<TbResult>, Vec<FailingJob>, Vec<JobResult>);

/// The run's jobs (the shard's, or the one `--job` names), testbench by testbench: each
/// testbench's merged row, the failing jobs, and the jobs' own results where a shard or the
/// JUnit file needs them.
fn run_jobs_of(
    project: &Project,
    cfg: &RegressConfig,
    progress: &mut dyn FnMut(&str, &str),
) -> Result<Ran, String> {
    let reg = project.registry();
    let opts = RunOptions {
        seed: cfg.seed,
        count: cfg.count,
        shard: cfg.shard,
        waves: cfg
            .vcd
            .then(|| (cfg.out.clone(), cfg.trace.clone(), cfg.period_ps)),
        check_schedule: cfg.check_schedule,
        jobs: cfg.jobs,
        seeds: cfg.seeds,
        trace_every_job: cfg.job.is_some(),
        numeric: true,
    };
    let plan = match cfg.job {
        Some(i) => jobs::find(reg, cfg.seeds, i)
            .map(|(tb, j)| vec![(tb, vec![j])])
            .unwrap_or_default(),
        None => jobs::owned(reg, cfg.seeds, cfg.shard, &|t| cfg.selected(t)),
    };
    let whole = cfg.shard.is_all() && cfg.job.is_none();
    let keep = !cfg.shard.is_all() || cfg.junit.is_some();
    let (mut rows, mut failing, mut ran) = (Vec::new(), Vec::new(), Vec::new());
    for (tb, js) in plan {
        let name = tb.name();
        let done = crate::run_jobs(tb, &opts, &js, &mut |label| progress(name, label))?;
        let mut row = crate::aggregate(tb, cfg.seed, &done, whole)?;
        if whole && cfg.require_numeric {
            row.require_numeric_coverage();
        }
        rows.push(row);
        let run = (cfg.seed, cfg.seeds, cfg.count);
        failing.extend(failing_jobs(project, run, tb, &done));
        if keep {
            ran.extend(done);
        }
    }
    Ok((rows, failing, ran))
}

/// Runs every selected testbench, checks every waveform it wrote (with the `read` feature:
/// read back with wellen, `.gtkw` checked against it), writes `summary.json` (and the JUnit
/// file). `progress` is called before each job with the testbench's name and the job's label
/// (and once with
/// `("", "vectors and waveforms")`). `Err` is for bad options and I/O failures; mismatches
/// are in the results.
pub fn regress(
    project: &Project,
    cfg: &RegressConfig,
    progress: &mut dyn FnMut(&str, &str),
) -> Result<Summary, String> {
    let reg = project.registry();
    cfg.validate(reg)?;
    #[cfg(not(feature = "read"))]
    if cfg.fst && cfg.cosim && project.twins().next().is_some() {
        return Err(
            "--fst: a twin's FST is made from its simulator's VCD, read back with \
                    texrtl-verif's `read` feature (enable it, or give --no-cosim)"
                .into(),
        );
    }
    std::fs::create_dir_all(&cfg.out).map_err(|e| format!("{}: {e}", cfg.out.display()))?;
    let (mut results, mut failing, ran) = run_jobs_of(project, cfg, progress)?;
    // A shard keeps its jobs in its summary; a whole run only for its JUnit file.
    let keep = !cfg.shard.is_all();
    let (kept, ran) = if keep {
        (ran, Vec::new())
    } else {
        (Vec::new(), ran)
    };
    progress("", "vectors and waveforms");
    // Bit-accuracy vectors of the project's source tree, when it is there (not for an
    // installed binary away from it); checked by the first shard. A tree without its vectors
    // folder fails the check, each unit's file missing, rather than skipping it.
    let first = cfg.shard.index == 1 && cfg.job.is_none();
    let tree = |d: &&Path| d.is_dir() || d.parent().is_some_and(Path::is_dir);
    let dir = project.kept_vectors().filter(tree);
    if let Some(dir) = dir.filter(|_| first && cfg.selected(VECTORS)) {
        results.push(vectors_row(project, dir));
    }
    let sims = cosim::simulators(cfg);
    let after = jobs::count(reg, cfg.seeds, &|t| cfg.selected(t));
    let cosim_jobs = cosim::run_owned(project, cfg, &sims, after, progress)?;
    let done: Vec<&CosimJob> = cosim_jobs.iter().collect();
    results.extend(cosim::rows(&done, &cfg.out.join(COSIM))?);
    failing.extend(cosim::failing(project.name(), &done, cfg.seed));
    let rtl_coverage = cosim::by_file(&done);
    let (kept_cosim, cosim_ran) = if keep {
        (cosim_jobs, Vec::new())
    } else {
        (Vec::new(), cosim_jobs)
    };
    check_waveforms(&mut results, cfg);
    let passed = results.iter().all(|r| r.passed);
    let summary = Summary {
        texrtl: project.version().to_string(),
        seed: cfg.seed.to_string(),
        seeds: cfg.seeds,
        count: cfg.count,
        only: cfg.only.clone(),
        shard: (!cfg.shard.is_all()).then(|| cfg.shard.to_string()),
        passed,
        testbenches: results,
        failing,
        jobs: kept,
        simulators: if keep {
            sims.iter().map(|s| s.name().to_string()).collect()
        } else {
            Vec::new()
        },
        cosim_jobs: kept_cosim,
        rtl_coverage,
    };
    let path = cfg.out.join("summary.json");
    let json = serde_json::to_vec_pretty(&summary).map_err(|e| e.to_string())?;
    write_output(&path, &json).map_err(|e| e.to_string())?;
    if let Some(j) = &cfg.junit {
        let (jobs, cosim_jobs) = match keep {
            true => (&summary.jobs, &summary.cosim_jobs),
            false => (&ran, &cosim_ran),
        };
        let xml = crate::junit::junit(project, &summary, jobs, cosim_jobs)?;
        write_output(j, xml.as_bytes()).map_err(|e| format!("--junit {}: {e}", j.display()))?;
    }
    Ok(summary)
}

/// The vectors check as a row of the table.
fn vectors_row(project: &Project, dir: &std::path::Path) -> TbResult {
    let mut r = TbResult::new(VECTORS, "bit-accuracy regression vectors (fixed stimuli)");
    r.coverage_percent = 100.0;
    // A model that panics on its vectors fails the row, as a job's panic fails the job.
    let checked = crate::testbench::unpanicked(|| crate::vectors::check(dir, project.vectors()));
    match checked
        .map_err(|m| format!("panicked: {m}"))
        .and_then(|c| c)
    {
        Ok(d) => {
            r.transactions = project.vectors().count() as u64;
            r.mismatches = d.len() as u64;
            r.mismatch_log = d;
        }
        Err(e) => r.failures.push(e),
    }
    r.finish_with(false);
    r
}

/// Every result's waveform focused on its first mismatch and checked, on the run's threads
/// (each result on its own: a twin's waveform is tens of megabytes to read back).
fn check_waveforms(results: &mut [TbResult], cfg: &RegressConfig) {
    let threads = cfg.jobs.clamp(1, results.len().max(1));
    let queue = std::sync::Mutex::new(results.iter_mut());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                // The lock is held while a result is taken, not while it is checked.
                let take = || queue.lock().ok()?.next();
                while let Some(r) = take() {
                    focus_on_mismatch(r);
                    check_waveform(r, cfg.fst);
                }
            });
        }
    });
}

/// A failing result's waveform opens at its first mismatch, marker A on it.
fn focus_on_mismatch(r: &mut TbResult) {
    let (Some(vcd), Some(c)) = (&r.vcd, r.first_mismatch_cycle) else {
        return;
    };
    let g = vcd.with_extension("gtkw");
    if g.is_file() {
        if let Err(e) = waves::gtkw::focus(&g, c, "first mismatch") {
            r.failures.push(format!("waveform: {e}"));
        }
    }
}

/// Without the `read` feature the waveforms are not read back.
#[cfg(not(feature = "read"))]
fn check_waveform(_: &mut TbResult, _: bool) {}

/// Reads a result's waveform back with wellen and checks its `.gtkw` against it; with `fst`,
/// also reads the FST written beside it while simulating and compares it value by value
/// (the VCD's design variables: the FST has no `real` companions and no probes).
#[cfg(feature = "read")]
fn check_waveform(r: &mut TbResult, fst: bool) {
    let Some(vcd) = &r.vcd else { return };
    let mut rb = match read_vcd(vcd).and_then(|rb| check_gtkw(vcd, &rb).map(|_| rb)) {
        Ok(rb) => rb,
        Err(e) => return fail_waveform(r, e),
    };
    if fst {
        let f = vcd.with_extension("fst");
        rb.vars
            .retain(|name, v| v.width.is_some() && !name.starts_with("tb.golden"));
        let checked = waves::check::read_fst(&f).and_then(|back| {
            waves::fst::same_values(&rb, &back)
                .map_err(|e| format!("{}: differs from {}: {e}", f.display(), vcd.display()))
        });
        if let Err(e) = checked {
            fail_waveform(r, e);
        }
    }
}

#[cfg(feature = "read")]
fn fail_waveform(r: &mut TbResult, e: String) {
    r.failures.push(format!("waveform: {e}"));
    r.passed = false;
}
