//! A project's regression: every testbench on its built-in stimulus, the bit-accuracy vectors
//! and the co-simulation of every twin, with waveforms and `summary.json`; and the merge of
//! the summaries of a run's shards into the one an unsharded run writes.

use crate::cosim::Simulator;
use crate::project::Project;
use crate::TbResult;
use crate::{Registry, RunOptions, Seed};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
#[cfg(feature = "read")]
use waves::check::{check_gtkw, read_vcd};
use waves::output::write_output;
use waves::TraceConfig;

/// The name of the bit-accuracy vectors row (a check of fixed stimuli, not a testbench).
pub const VECTORS: &str = "vectors";

/// The prefix of the co-simulation rows (`cosim/<unit>/<simulator>`; `--only cosim`).
pub const COSIM: &str = "cosim";

/// `summary.json`: every result, the seed, the shard and the project's version.
#[derive(Clone, Serialize, Deserialize)]
pub struct Summary {
    /// The version of the project that wrote it (shards of different versions do not merge).
    pub texrtl: String,
    /// The run's seed, as it replays it (`--seed`).
    pub seed: String,
    /// `I/N` when the run was one shard of N.
    pub shard: Option<String>,
    /// Whether every row passed.
    pub passed: bool,
    /// Every row: each testbench, the vectors, each co-simulation, in run order.
    pub testbenches: Vec<TbResult>,
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
    /// Co-simulate every Verilog twin in every simulator that is installed.
    pub cosim: bool,
    /// Configurations run at once (threads); the results do not depend on it.
    pub jobs: usize,
}

impl RegressConfig {
    /// Random transactions per configuration at most (`--count`).
    pub const MAX_COUNT: usize = 1_000_000;

    /// Checks the options: the names in `only` against the registry, `--count` in range.
    pub fn validate(&self, reg: &Registry) -> Result<(), String> {
        if let Some(n) = self.count.filter(|&n| n > Self::MAX_COUNT) {
            return Err(format!(
                "--count {n}: 0..={} random transactions per configuration",
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
        for o in &self.only {
            if reg.get(o).is_none() && o != VECTORS && o != COSIM {
                return Err(format!(
                    "--only: no testbench '{o}' (there are: {}, {VECTORS}, {COSIM})",
                    reg.names().join(", ")
                ));
            }
        }
        Ok(())
    }

    fn selected(&self, name: &str) -> bool {
        self.only.is_empty() || self.only.iter().any(|o| o == name)
    }
}

/// Runs every selected testbench, checks every waveform it wrote (with the `read` feature:
/// read back with wellen, `.gtkw` checked against it), writes `summary.json`. `progress` is called before each
/// configuration with the testbench's name and the configuration's label (and once with
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
    let opts = RunOptions {
        seed: cfg.seed,
        count: cfg.count,
        shard: cfg.shard,
        waves: cfg
            .vcd
            .then(|| (cfg.out.clone(), cfg.trace.clone(), cfg.period_ps)),
        check_schedule: cfg.check_schedule,
        jobs: cfg.jobs,
    };
    let mut results = Vec::new();
    for tb in reg.iter().filter(|t| cfg.selected(t.name())) {
        let name = tb.name();
        let r = crate::run_testbench(tb, &opts, &mut |label| progress(name, label))?;
        results.push(r);
    }
    progress("", "vectors and waveforms");
    // Bit-accuracy vectors of the project's source tree, when it is there (not for an
    // installed binary); checked by the first shard.
    let dir = project.kept_vectors().filter(|d| d.is_dir());
    if let Some(dir) = dir.filter(|_| cfg.shard.index == 1 && cfg.selected(VECTORS)) {
        results.push(vectors_row(project, dir));
    }
    if cfg.cosim && cfg.shard.index == 1 && cfg.selected(COSIM) {
        for sim in [Simulator::Verilator, Simulator::Icarus] {
            if sim.check_installed().is_err() {
                continue;
            }
            for unit in project.twins() {
                progress(COSIM, &format!("{} in {}", unit.name(), sim.name()));
                results.push(cosim_row(unit, sim, cfg)?);
            }
        }
    }
    for r in &mut results {
        check_waveform(r, cfg.fst);
    }
    let summary = Summary {
        texrtl: project.version().to_string(),
        seed: cfg.seed.to_string(),
        shard: (!cfg.shard.is_all()).then(|| cfg.shard.to_string()),
        passed: results.iter().all(|r| r.passed),
        testbenches: results.clone(),
    };
    let path = cfg.out.join("summary.json");
    let json = serde_json::to_vec_pretty(&summary).map_err(|e| e.to_string())?;
    write_output(&path, &json).map_err(|e| e.to_string())?;
    Ok(summary)
}

/// Cycles each twin is co-simulated for in a regression: Verilator / Icarus.
const COSIM_CYCLES: [usize; 2] = [100_000, 20_000];

/// A twin against its model as a row of the table: `cosim/<unit>/<simulator>`.
fn cosim_row(
    u: &dyn crate::cosim::CosimUnit,
    sim: Simulator,
    cfg: &RegressConfig,
) -> Result<TbResult, String> {
    let unit = u.name();
    let name = format!("{COSIM}/{unit}/{}", sim.name());
    let mut r = TbResult::new(
        &name,
        "the model against its Verilog twin, every output port on every cycle",
    );
    let n = COSIM_CYCLES[usize::from(sim == Simulator::Icarus)];
    let dir = cfg.out.join(COSIM).join(format!("{unit}-{}", sim.name()));
    let c = crate::cosim::run(u, sim, &[], n, cfg.seed, &dir)?;
    r.transactions = c.cycles as u64;
    r.cycles = c.cycles as u64;
    r.mismatches = c.differences;
    r.coverage_percent = 100.0;
    if let Some(d) = c.mismatch {
        r.mismatch_log.push(d.to_string());
    }
    // The simulator's own VCD: with `--fst`, its FST is converted from it (the models' FSTs
    // are written while simulating).
    #[cfg(feature = "read")]
    if cfg.fst {
        let f = c.vcd.with_extension("fst");
        if let Err(e) = waves::fst::vcd_to_fst(&c.vcd, &f) {
            r.failures.push(format!("waveform: {e}"));
        }
    }
    r.vcd = Some(c.vcd);
    r.finish_with(false);
    Ok(r)
}

/// The vectors check as a row of the table.
fn vectors_row(project: &Project, dir: &std::path::Path) -> TbResult {
    let mut r = TbResult::new(VECTORS, "bit-accuracy regression vectors (fixed stimuli)");
    r.coverage_percent = 100.0;
    match crate::vectors::check(dir, project.vectors()) {
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

/// `texrtl merge`: combines the `summary.json` of every shard of one run into one: counts and
/// error statistics add up, coverage is merged bin by bin (a hole fails only if no shard hit
/// it). Errors name the file and the problem.
pub fn merge(project: &Project, paths: &[PathBuf]) -> Result<Summary, String> {
    let mut shards: Vec<(PathBuf, Summary)> = Vec::new();
    for p in paths {
        let b = std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()))?;
        shards.push((p.clone(), parse_summary(p, &b)?));
    }
    merge_shards(project, &shards)
}

/// A `summary.json`'s bytes (`path` names it in the message).
pub fn parse_summary(path: &std::path::Path, b: &[u8]) -> Result<Summary, String> {
    let s: Summary = serde_json::from_slice(b).map_err(|e| {
        let e = waves::output::shorten(&e.to_string());
        format!("{}: not a texrtl summary.json: {e}", path.display())
    })?;
    for r in &s.testbenches {
        if let Some(c) = &r.coverage {
            c.validate().map_err(|e| {
                format!(
                    "{}: {}: {e}",
                    path.display(),
                    waves::output::shorten(&r.name)
                )
            })?;
        }
    }
    Ok(s)
}

/// [`merge`] of summaries already read, each with the path its messages name.
pub fn merge_shards(project: &Project, shards: &[(PathBuf, Summary)]) -> Result<Summary, String> {
    let (first_path, first) = shards.first().ok_or("merge: no summary.json given")?;
    let parse = |p: &PathBuf, s: &Summary| -> Result<crate::Shard, String> {
        match &s.shard {
            Some(x) => crate::Shard::parse(x).map_err(|e| format!("{}: {e}", p.display())),
            None => Err(format!(
                "{}: not a shard (run with --shard I/N)",
                p.display()
            )),
        }
    };
    let n = parse(first_path, first)?.count;
    // The shards given, as a set: nothing is allocated for the count a file declares.
    let mut seen = std::collections::BTreeSet::new();
    for (p, s) in shards {
        let sh = parse(p, s)?;
        if s.texrtl != first.texrtl {
            return Err(format!(
                "{}: written by texrtl {}, {} by texrtl {}: merge the shards of one version",
                p.display(),
                waves::output::shorten(&s.texrtl),
                first_path.display(),
                waves::output::shorten(&first.texrtl)
            ));
        }
        if s.seed != first.seed || sh.count != n {
            return Err(format!(
                "{}: shard {sh} of seed {} does not belong with {}/{n} of seed {}",
                p.display(),
                s.seed,
                1,
                first.seed
            ));
        }
        if !seen.insert(sh.index) {
            return Err(format!("{}: shard {sh} given twice", p.display()));
        }
    }
    // The first gap is at most one past the shards given, however large the count.
    if let Some(i) = (1..=n).find(|i| !seen.contains(i)) {
        return Err(format!("merge: shard {i}/{n} is missing"));
    }
    let reg = project.registry();
    let mut merged: Vec<TbResult> = Vec::new();
    for (p, s) in shards {
        for r in &s.testbenches {
            let mut r = r.clone();
            r.strip_conclusions();
            match merged.iter_mut().find(|m| m.name == r.name) {
                Some(m) => m
                    .absorb(&r, None)
                    .map_err(|e| format!("{}: {}: {e}", p.display(), r.name))?,
                None => merged.push(r),
            }
        }
    }
    // The order of an unsharded run (shards see different subsets).
    merged.sort_by_key(|m| reg.position(&m.name).unwrap_or(usize::MAX));
    for m in &mut merged {
        match reg.get(&m.name) {
            Some(tb) => crate::conclude(tb, m, true),
            None => m.finish_with(true),
        }
    }
    Ok(Summary {
        texrtl: first.texrtl.clone(),
        seed: first.seed.clone(),
        shard: None,
        passed: merged.iter().all(|m| m.passed),
        testbenches: merged,
    })
}
