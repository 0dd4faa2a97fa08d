//! A regression's co-simulations as jobs. Each twin is co-simulated in each of the run's
//! simulators under each of its `--seeds` seeds: one job each, listed after the testbenches'
//! jobs (simulator by simulator, twin by twin, seed by seed) and dealt to shards with them,
//! so a farm co-simulates as one machine does and its merge is that machine's summary.
//!
//! A job's stimulus is the twin's own ([`crate::cosim::CosimUnit::stimulus`]) from the run's
//! seed for the first seed and from [`cosim_seed`] for the others; its row,
//! `cosim/<unit>/<simulator>`, adds up its jobs, the later seeds' lines tagged `[seed #r]`.
//! The first seed's job writes its waveform as a testbench's traced configuration does
//! (unless `--no-vcd`); a later seed's only when it differs, and a later seed that agrees
//! leaves no folder: its seed makes it again.

use super::{FailingJob, RegressConfig, COSIM};
use crate::cosim::{CosimUnit, RunOptions, Simulator};
use crate::project::Project;
use crate::{Seed, TbResult};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Cycles each twin is co-simulated for in a regression: Verilator / Icarus.
pub const COSIM_CYCLES: [usize; 2] = [100_000, 20_000];

/// What a failing co-simulation row says before the command that runs it again alone.
pub(crate) const AGAIN: &str =
    "again alone, the RTL's internals around the difference in its waveform: ";

/// One co-simulation job's result, as a shard keeps it for the merge.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CosimJob {
    /// Its index in the run's job list, after every testbench's jobs.
    pub job: u64,
    /// Its row, `cosim/<unit>/<simulator>`.
    pub row: String,
    /// Which of the run's seeds, from 0.
    pub repeat: u32,
    /// What it found (its lines not yet tagged with its seed).
    pub result: TbResult,
    /// Seconds it ran (not part of any result).
    #[serde(default)]
    pub seconds: f64,
    /// The RTL's coverage it measured (`--rtl-coverage`, Verilator).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rtl_coverage: Option<JobCoverage>,
}

/// The cycles a regression co-simulates in `sim` ([`COSIM_CYCLES`]).
fn cycles_in(sim: Simulator) -> usize {
    COSIM_CYCLES[usize::from(sim == Simulator::Icarus)]
}

impl CosimJob {
    /// The cycles it simulates (however many it got through).
    pub fn cycles(&self) -> usize {
        let sim = self.row.rsplit('/').next().and_then(Simulator::parse);
        cycles_in(sim.unwrap_or(Simulator::Verilator))
    }
}

/// A job's RTL coverage: its figures as said, and its data for a merge of seeds.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct JobCoverage {
    /// The figures ([`crate::cosim::RtlCoverage`]'s line).
    pub said: String,
    /// Its `coverage.dat` (an absolute path).
    pub data: PathBuf,
}

/// One job of the run's co-simulation plan.
#[derive(Clone, Copy)]
pub(super) struct Planned<'p> {
    pub(super) sim: Simulator,
    pub(super) unit: &'p dyn CosimUnit,
    pub(super) repeat: u32,
}

impl Planned<'_> {
    pub(super) fn row(&self) -> String {
        row_name(self.unit.name(), self.sim)
    }
}

fn row_name(unit: &str, sim: Simulator) -> String {
    format!("{COSIM}/{unit}/{}", sim.name())
}

/// The stimulus seed of seed #`repeat` of every twin in a run seeded `seed`: the run's own
/// for the first, derived from it for the others.
pub fn cosim_seed(seed: Seed, repeat: u32) -> Seed {
    if repeat == 0 {
        seed
    } else {
        seed.derive(u64::from(repeat))
    }
}

/// The simulators the run co-simulates in (none without co-simulation): those `--sim` names,
/// else every one installed for a whole run and both for a shard, whose jobs must be every
/// shard's alike (a machine without one fails those jobs, saying so).
pub(super) fn simulators(cfg: &RegressConfig) -> Vec<Simulator> {
    if !cfg.cosim || cfg.job.is_some() || !cfg.selected(COSIM) {
        return Vec::new();
    }
    if !cfg.simulators.is_empty() {
        return cfg.simulators.clone();
    }
    let both = [Simulator::Verilator, Simulator::Icarus];
    let whole = cfg.shard.is_all();
    both.into_iter()
        .filter(|s| !whole || s.check_installed().is_ok())
        .collect()
}

/// The plan: simulator by simulator, twin by twin in the project's order, seed by seed (so
/// that shards dealt it round-robin share each twin's seeds evenly).
pub(super) fn plan<'p>(project: &'p Project, sims: &[Simulator], seeds: u32) -> Vec<Planned<'p>> {
    let mut out = Vec::new();
    for &sim in sims {
        for unit in project.twins() {
            out.extend((0..seeds).map(|repeat| Planned { sim, unit, repeat }));
        }
    }
    out
}

/// Runs the jobs of the plan that the run's shard owns, `cfg.jobs` at a time; `first` is the
/// first job's place in the run's job list (after the testbenches' jobs). In plan order.
pub(super) fn run_owned(
    project: &Project,
    cfg: &RegressConfig,
    sims: &[Simulator],
    first: u64,
    progress: &mut dyn FnMut(&str, &str),
) -> Result<Vec<CosimJob>, String> {
    // A job's index counts every testbench's jobs, whatever the run selects, as theirs do;
    // its place in the list the shards are dealt counts the selected ones'.
    let base = crate::jobs::count(project.registry(), cfg.seeds, &|_| true);
    let mine: Vec<(u64, Planned)> = (plan(project, sims, cfg.seeds).into_iter())
        .enumerate()
        .filter(|(k, _)| cfg.shard.owns(first + *k as u64))
        .map(|(k, p)| (base + k as u64, p))
        .collect();
    if mine.is_empty() {
        return Ok(Vec::new());
    }
    progress(
        COSIM,
        &format!("{} co-simulations, {} at a time", mine.len(), cfg.jobs),
    );
    let next = AtomicUsize::new(0);
    let done: Vec<Mutex<Option<Result<CosimJob, String>>>> =
        mine.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..cfg.jobs.clamp(1, mine.len()) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some((index, p)) = mine.get(i) else { break };
                let t = std::time::Instant::now();
                let r = job(project.name(), p, cfg).map(|(result, rtl_coverage)| CosimJob {
                    job: *index,
                    row: p.row(),
                    repeat: p.repeat,
                    result,
                    seconds: t.elapsed().as_secs_f64(),
                    rtl_coverage,
                });
                *done[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
            });
        }
    });
    done.into_iter()
        .map(|m| {
            let r = m.into_inner().unwrap_or_else(|e| e.into_inner());
            r.unwrap_or_else(|| Err("a co-simulation job did not run".into()))
        })
        .collect()
}

/// One job: its twin against its model, every output port on every cycle; a difference with
/// the command that runs it again alone (`program cosim ...`), explained.
fn job(
    program: &str,
    p: &Planned,
    cfg: &RegressConfig,
) -> Result<(TbResult, Option<JobCoverage>), String> {
    let (unit, sim) = (p.unit.name(), p.sim);
    let mut r = TbResult::new(
        &p.row(),
        "the model against its Verilog twin, every output port on every cycle",
    );
    if let Err(e) = sim.check_installed() {
        r.failures
            .push(format!("{e}; or leave it out with --sim or --no-cosim"));
        r.finish_with(false);
        return Ok((r, None));
    }
    let n = cycles_in(sim);
    let mut folder = format!("{unit}-{}", sim.name());
    if p.repeat > 0 {
        folder.push_str(&format!("-seed{}", p.repeat));
    }
    let dir = cfg.out.join(COSIM).join(folder);
    let options = RunOptions {
        internals: false,
        rtl_coverage: cfg.rtl_coverage && sim == Simulator::Verilator,
        waveform_on_difference_only: p.repeat > 0 || !cfg.vcd,
    };
    let seed = cosim_seed(cfg.seed, p.repeat);
    let stim = p.unit.stimulus(seed, n);
    // The RTL not building, the simulator failing, the model panicking: this job's failure,
    // not the end of the regression.
    let run = || crate::cosim::run_with_options(p.unit, sim, &[], &stim, &dir, options);
    let ran = crate::testbench::unpanicked(run).map_err(|m| format!("panicked: {m}"));
    let c = match ran.and_then(|r| r) {
        Ok(c) => c,
        Err(e) => {
            r.failures.push(e);
            r.finish_with(false);
            return Ok((r, None));
        }
    };
    let covered = c.rtl_coverage.as_ref().map(|c| JobCoverage {
        said: c.to_string(),
        data: c.data.clone(),
    });
    r.transactions = c.cycles as u64;
    r.cycles = c.cycles as u64;
    r.mismatches = c.differences;
    r.coverage_percent = 100.0;
    if let Some(d) = c.mismatch {
        r.mismatch_log.push(d.to_string());
        r.mismatch_log
            .push(format!("{AGAIN}{}", command(program, unit, sim, seed)));
    }
    // The simulator's own VCD: with `--fst`, its FST is converted from it (the models' FSTs
    // are written while simulating).
    #[cfg(feature = "read")]
    if let Some(vcd) = c.vcd.as_ref().filter(|_| cfg.fst) {
        if let Err(e) = waves::fst::vcd_to_fst(vcd, &vcd.with_extension("fst")) {
            r.failures.push(format!("waveform: {e}"));
        }
    }
    r.vcd = c.vcd;
    r.finish_with(false);
    if p.repeat > 0 && r.passed {
        // Nothing in it to look at (its seed makes it again) but its coverage data.
        clear(&dir, covered.as_ref().map(|c| c.data.as_path()));
    }
    Ok((r, covered))
}

/// The command that runs `program`'s co-simulation of `unit` in `sim` under `seed` again
/// alone, as a regression ran it (its cycles), the RTL's internals in its waveform.
pub(crate) fn command(program: &str, unit: &str, sim: Simulator, seed: Seed) -> String {
    let n = cycles_in(sim);
    format!(
        "{program} cosim --unit {unit} --sim {} --count {n} --seed {seed}",
        sim.name()
    )
}

/// Removes `dir`, or everything in it but `keep` (a file in it).
fn clear(dir: &Path, keep: Option<&Path>) {
    let Some(keep) = keep else {
        let _ = std::fs::remove_dir_all(dir);
        return;
    };
    // By name: `dir` may be relative where `keep` is absolute.
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if Some(e.file_name().as_os_str()) != keep.file_name() {
            let _ = match e.file_type().map(|t| t.is_dir()) {
                Ok(true) => std::fs::remove_dir_all(&p),
                _ => std::fs::remove_file(&p),
            };
        }
    }
}

/// The rows of `jobs` (in plan order): one per twin and simulator, in the order of their
/// first jobs, adding up its seeds' jobs, a later seed's lines tagged with it. A failing
/// row's waveform is its first failing job's. A row's RTL coverage is its one job's, or its
/// seeds' merged into `merged/<unit>-<simulator>-all-seeds` (its figures in the note).
pub(super) fn rows(jobs: &[&CosimJob], merged: &Path) -> Result<Vec<TbResult>, String> {
    let mut rows: Vec<TbResult> = Vec::new();
    let mut covered: Vec<Vec<&JobCoverage>> = Vec::new();
    for j in jobs {
        let mut r = j.result.clone();
        if j.repeat > 0 {
            let tag = |l: &mut String| *l = format!("[seed #{}] {l}", j.repeat);
            r.mismatch_log.iter_mut().for_each(tag);
            r.failures.iter_mut().for_each(tag);
            r.notes.iter_mut().for_each(tag);
        }
        match rows.iter().position(|m| m.name == r.name) {
            Some(k) => {
                let m = &mut rows[k];
                if m.passed && !r.passed && r.vcd.is_some() {
                    m.vcd = r.vcd.take();
                }
                m.absorb(&r, None).map_err(|e| format!("{}: {e}", r.name))?;
                m.finish_with(false);
                covered[k].extend(&j.rtl_coverage);
            }
            None => {
                rows.push(r);
                covered.push(j.rtl_coverage.iter().collect());
            }
        }
    }
    for (r, c) in rows.iter_mut().zip(&covered) {
        r.notes.extend(coverage_note(&r.name, c, merged));
    }
    Ok(rows)
}

/// A row's coverage note: its one job's figures, or its seeds' merged.
fn coverage_note(row: &str, jobs: &[&JobCoverage], merged: &Path) -> Option<String> {
    match jobs {
        [] => None,
        [one] => Some(one.said.clone()),
        _ => {
            let folder = format!(
                "{}-all-seeds",
                row.trim_start_matches("cosim/").replace('/', "-")
            );
            let data: Vec<PathBuf> = jobs.iter().map(|j| j.data.clone()).collect();
            let all = match data.iter().find(|d| !d.is_file()) {
                Some(d) => Err(format!("{}: not found here", d.display())),
                None => crate::cosim::RtlCoverage::merge_files(&data, &merged.join(folder)),
            };
            Some(match all {
                // Figures only: a merge of shards says the same as the whole run.
                Ok(c) => format!("{} seeds together: {}", jobs.len(), c.figures()),
                Err(e) => format!("{} seeds: the RTL's coverage not merged: {e}", jobs.len()),
            })
        }
    }
}

/// What the covered jobs among `jobs` reached of each RTL file: none when no job was covered,
/// or when a job's data cannot be read here (a merge on a machine that does not see the
/// shards' folders; a row of several seeds says so in its note).
pub(super) fn by_file(jobs: &[&CosimJob]) -> Vec<crate::cosim::FileCoverage> {
    let data: Vec<PathBuf> = (jobs.iter())
        .filter_map(|j| j.rtl_coverage.as_ref().map(|c| c.data.clone()))
        .collect();
    if data.is_empty() {
        return Vec::new();
    }
    crate::cosim::by_file(&data).unwrap_or_default()
}

/// The failing jobs among `jobs` of `program`'s run seeded `seed`, each with its `cosim`
/// command.
pub(super) fn failing(program: &str, jobs: &[&CosimJob], seed: Seed) -> Vec<FailingJob> {
    let failed = jobs.iter().filter(|j| !j.result.passed);
    failed
        .map(|j| {
            let r = &j.result;
            FailingJob {
                job: j.job,
                testbench: j.row.clone(),
                configuration: format!("{} cycles of random stimulus", j.cycles()),
                repeat: j.repeat,
                seed: cosim_seed(seed, j.repeat).to_string(),
                first_mismatch_cycle: None,
                first: (r.mismatch_log.first().or(r.failures.first()))
                    .cloned()
                    .unwrap_or_default(),
                reproduce: crate::junit::check_command(program, cosim_seed(seed, j.repeat), r),
            }
        })
        .collect()
}
