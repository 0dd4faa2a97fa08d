//! `merge`: the summaries of a run's shards combined into the summary the unsharded run
//! writes, byte for byte. Each shard keeps its jobs one by one; the merge takes them all,
//! refuses a job given twice and names the first one missing, and merges each testbench's
//! jobs in job order, as the unsharded run does. The co-simulation jobs alike: their rows,
//! failing jobs and RTL coverage are made again from the jobs of every shard.

use super::cosim::{by_file, failing, plan, rows};
use super::{failing_jobs, CosimJob, FailingJob, Summary};
use crate::cosim::Simulator;
use crate::jobs::{self, JobResult};
use crate::project::Project;
use crate::{Registry, Seed, Shard, TbResult};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use waves::output::shorten;

/// `texrtl merge`: combines the `summary.json` of every shard of one run into one: counts and
/// error statistics add up, coverage is merged bin by bin (a hole fails only if no shard hit
/// it). Errors name the file and the problem.
pub fn merge(project: &Project, paths: &[PathBuf]) -> Result<Summary, String> {
    merge_shards(project, &read_summaries(paths)?)
}

/// The summaries at `paths`, read and parsed, each with its path.
pub fn read_summaries(paths: &[PathBuf]) -> Result<Vec<(PathBuf, Summary)>, String> {
    paths
        .iter()
        .map(|p| {
            // A summary of 2,000 jobs is a few MB; 256 MiB bounds an endless device.
            let b = waves::output::read_bounded(p, 256 << 20)?;
            Ok((p.clone(), parse_summary(p, &b)?))
        })
        .collect()
}

/// A `summary.json`'s bytes (`path` names it in the message).
pub fn parse_summary(path: &Path, b: &[u8]) -> Result<Summary, String> {
    let s: Summary = serde_json::from_slice(b).map_err(|e| {
        let e = shorten(&e.to_string());
        format!("{}: not a texrtl summary.json: {e}", path.display())
    })?;
    let rows = s.testbenches.iter().chain(s.jobs.iter().map(|j| &j.result));
    for r in rows {
        if let Some(c) = &r.coverage {
            c.validate()
                .map_err(|e| format!("{}: {}: {e}", path.display(), shorten(&r.name)))?;
        }
    }
    Ok(s)
}

/// The shard a summary says it is.
fn shard_of(p: &Path, s: &Summary) -> Result<Shard, String> {
    match &s.shard {
        Some(x) => Shard::parse(x).map_err(|e| format!("{}: {e}", p.display())),
        None => Err(format!(
            "{}: not a shard (run with --shard I/N)",
            p.display()
        )),
    }
}

/// Every summary a shard of the same run as the first: version, seed, seeds, count and
/// selection; no shard twice.
fn check_same_run(shards: &[(PathBuf, Summary)]) -> Result<(), String> {
    let (first_path, first) = &shards[0];
    let mut seen = std::collections::BTreeSet::new();
    for (p, s) in shards {
        let sh = shard_of(p, s)?;
        if s.texrtl != first.texrtl {
            return Err(format!(
                "{}: written by texrtl {}, {} by texrtl {}: merge the shards of one version",
                p.display(),
                shorten(&s.texrtl),
                first_path.display(),
                shorten(&first.texrtl)
            ));
        }
        let same = s.seed == first.seed
            && s.seeds == first.seeds
            && s.count == first.count
            && s.only == first.only
            && s.simulators == first.simulators;
        if !same {
            return Err(format!(
                "{}: shard {sh} of another run than {} (its seed, --seeds, --count, --only or \
                 --sim differ)",
                p.display(),
                first_path.display()
            ));
        }
        if !seen.insert((sh.index, sh.count)) {
            return Err(format!("{}: shard {sh} given twice", p.display()));
        }
    }
    Ok(())
}

/// The shards' jobs by index: each once, each one of this run's.
fn gather<'s>(
    reg: &Registry,
    shards: &'s [(PathBuf, Summary)],
    selected: &dyn Fn(&str) -> bool,
) -> Result<BTreeMap<u64, (&'s Path, &'s JobResult)>, String> {
    let seeds = shards[0].1.seeds;
    let mut all: BTreeMap<u64, (&Path, &JobResult)> = BTreeMap::new();
    for (p, s) in shards {
        for j in &s.jobs {
            let ours = jobs::find(reg, seeds, j.index).filter(|(tb, r)| {
                // A configuration's own result may carry any name; its place says whose it is.
                selected(tb.name()) && (r.configuration, r.repeat) == (j.configuration, j.repeat)
            });
            let Some((tb, r)) = ours else {
                return Err(format!(
                    "{}: job {} (configuration {}, seed #{}) is not one of this run's jobs",
                    p.display(),
                    j.index,
                    j.configuration,
                    j.repeat
                ));
            };
            if let Some((q, _)) = all.insert(j.index, (p, j)) {
                return Err(format!(
                    "{}: job {} ({}) is in {} too",
                    p.display(),
                    j.index,
                    jobs::describe(tb, &r),
                    q.display()
                ));
            }
        }
    }
    Ok(all)
}

/// The first job of the run that no shard has, named by its shard when every summary is a
/// shard of the same N.
fn first_missing(
    reg: &Registry,
    shards: &[(PathBuf, Summary)],
    have: &BTreeMap<u64, (&Path, &JobResult)>,
    selected: &dyn Fn(&str) -> bool,
) -> Result<(), String> {
    let seeds = shards[0].1.seeds;
    let mut position = 0u64;
    for (p, tb) in reg.iter().enumerate().filter(|(_, t)| selected(t.name())) {
        for j in jobs::testbench_jobs(tb, p, reg, seeds) {
            if !have.contains_key(&j.index) {
                let what = format!("job {} ({})", j.index, jobs::describe(tb, &j));
                return Err(missing(shards, position, &what));
            }
            position += 1;
        }
    }
    Ok(())
}

/// A merge's message for the job `what`, at `position` in the list the shards were dealt,
/// in no summary: named by its shard when every summary is a shard of the same N.
pub(super) fn missing(shards: &[(PathBuf, Summary)], position: u64, what: &str) -> String {
    let counts: Vec<u32> = shards
        .iter()
        .filter_map(|(p, s)| shard_of(p, s).ok())
        .map(|s| s.count)
        .collect();
    match counts.first() {
        Some(&n) if counts.iter().all(|&c| c == n) => format!(
            "merge: shard {}/{n} is missing (its first job: {what})",
            position % u64::from(n) + 1
        ),
        _ => format!("merge: {what} is in no summary"),
    }
}

/// [`merge`] of summaries already read, each with the path its messages name.
pub fn merge_shards(project: &Project, shards: &[(PathBuf, Summary)]) -> Result<Summary, String> {
    let (_, first) = shards.first().ok_or("merge: no summary.json given")?;
    check_same_run(shards)?;
    let reg = project.registry();
    let selected = |n: &str| first.only.is_empty() || first.only.iter().any(|o| o == n);
    let have = gather(reg, shards, &selected)?;
    first_missing(reg, shards, &have, &selected)?;
    let seed = Seed::parse(&first.seed).map_err(|e| format!("merge: seed {e}"))?;
    let mut rows = Vec::new();
    let mut failing = Vec::new();
    for (p, tb) in reg.iter().enumerate().filter(|(_, t)| selected(t.name())) {
        let (files, done): (Vec<&Path>, Vec<JobResult>) =
            jobs::testbench_jobs(tb, p, reg, first.seeds)
                .iter()
                .filter_map(|j| have.get(&j.index).map(|(f, r)| (*f, (*r).clone())))
                .unzip();
        if done.is_empty() {
            continue;
        }
        let row = crate::aggregate(tb, seed, &done, true).map_err(|e| {
            // The summary that holds the job that does not merge (a coverage model of
            // another shape, say), found again job by job.
            let alone = |j: &JobResult| crate::aggregate(tb, seed, std::slice::from_ref(j), true);
            match done.iter().position(|j| alone(j).is_err()) {
                Some(k) => format!("{}: {e}", files[k].display()),
                None => e,
            }
        })?;
        rows.push(row);
        failing.extend(failing_jobs(
            project,
            (seed, first.seeds, first.count),
            tb,
            &done,
        ));
    }
    rows.extend(other_rows(reg, shards)?);
    let after = jobs::count(reg, first.seeds, &selected);
    let cosim = merged_rows(project, shards, after)?;
    rows.extend(cosim.rows);
    failing.extend(cosim.failing);
    Ok(Summary {
        texrtl: first.texrtl.clone(),
        seed: first.seed.clone(),
        seeds: first.seeds,
        count: first.count,
        only: first.only.clone(),
        shard: None,
        passed: rows.iter().all(|m| m.passed),
        testbenches: rows,
        failing,
        jobs: Vec::new(),
        simulators: Vec::new(),
        cosim_jobs: Vec::new(),
        rtl_coverage: cosim.rtl_coverage,
    })
}

/// The rows that are neither a testbench's nor a co-simulation's (the vectors check), in the
/// order the shards have them, each concluded as a whole run's.
fn other_rows(reg: &Registry, shards: &[(PathBuf, Summary)]) -> Result<Vec<TbResult>, String> {
    let mut rows: Vec<TbResult> = Vec::new();
    for (p, s) in shards {
        // The co-simulation rows are made again from the jobs.
        let cosim = |r: &&TbResult| r.name.starts_with(&format!("{}/", super::COSIM));
        let others = s.testbenches.iter().filter(|r| reg.get(&r.name).is_none());
        for r in others.filter(|r| !cosim(r)) {
            let mut r = r.clone();
            r.strip_conclusions();
            match rows.iter_mut().find(|m| m.name == r.name) {
                Some(m) => m
                    .absorb(&r, None)
                    .map_err(|e| format!("{}: {}: {e}", p.display(), shorten(&r.name)))?,
                None => rows.push(r),
            }
        }
    }
    for m in &mut rows {
        m.finish_with(true);
    }
    Ok(rows)
}

/// The co-simulation rows, failing jobs and RTL coverage by file of a merge of `shards` (the
/// run's shards, checked alike): every job of the plan once, the first missing named by its
/// shard, then [`rows`](super::cosim::rows).
pub(super) fn merged_rows(
    project: &Project,
    shards: &[(PathBuf, Summary)],
    after: u64,
) -> Result<Merged, String> {
    let (first_path, first) = &shards[0];
    let sims: Vec<Simulator> = (first.simulators.iter())
        .map(|n| {
            Simulator::parse(n)
                .ok_or_else(|| format!("{}: simulator '{}'", first_path.display(), shorten(n)))
        })
        .collect::<Result<_, _>>()?;
    let plan = plan(project, &sims, first.seeds);
    let keys: Vec<(String, u32)> = plan.iter().map(|q| (q.row(), q.repeat)).collect();
    let ours: std::collections::BTreeSet<&(String, u32)> = keys.iter().collect();
    let mut have: BTreeMap<(String, u32), (&Path, &CosimJob)> = BTreeMap::new();
    for (p, s) in shards {
        for j in &s.cosim_jobs {
            let key = (j.row.clone(), j.repeat);
            if !ours.contains(&key) {
                return Err(format!(
                    "{}: co-simulation {} seed #{} is not one of this run's jobs",
                    p.display(),
                    shorten(&j.row),
                    j.repeat
                ));
            }
            if let Some((q, _)) = have.insert(key, (p, j)) {
                return Err(format!(
                    "{}: co-simulation {} seed #{} is in {} too",
                    p.display(),
                    j.row,
                    j.repeat,
                    q.display()
                ));
            }
        }
    }
    let mut ordered = Vec::new();
    for (k, (q, key)) in plan.iter().zip(&keys).enumerate() {
        match have.get(key) {
            Some((_, j)) => ordered.push(*j),
            None => {
                let what = format!("co-simulation {} seed #{}", q.row(), q.repeat);
                return Err(missing(shards, after + k as u64, &what));
            }
        }
    }
    // The merged coverage's files are the whole run's to keep; a merge keeps its figures.
    static MERGES: AtomicUsize = AtomicUsize::new(0);
    let k = MERGES.fetch_add(1, Ordering::Relaxed);
    let scratch = std::env::temp_dir().join(format!("texrtl-merge-{}-{k}", std::process::id()));
    let r = rows(&ordered, &scratch);
    let _ = std::fs::remove_dir_all(&scratch);
    let seed = Seed::parse(&first.seed)?;
    Ok(Merged {
        rows: r?,
        failing: failing(project.name(), &ordered, seed),
        rtl_coverage: by_file(&ordered),
    })
}

/// What a merge makes again from the shards' co-simulation jobs.
pub(super) struct Merged {
    pub(super) rows: Vec<TbResult>,
    pub(super) failing: Vec<FailingJob>,
    pub(super) rtl_coverage: Vec<crate::cosim::FileCoverage>,
}
