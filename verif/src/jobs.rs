//! A regression as a list of jobs. A job is one configuration of one testbench under one of
//! the run's seeds: with `seeds` S, testbench `t` with C configurations has S x C jobs, and
//! the run's jobs are every selected testbench's, in registry order, seed by seed,
//! configuration by configuration. A [`Shard`] takes every N-th job of that list, so any
//! testbench spreads over any number of machines, and the jobs of every shard together are
//! the run's, each with the same seed.
//!
//! A job's index counts over every testbench of the registry (whatever the run selects), so
//! that `--job INDEX` names the same job in any run of the same project and seeds. Seed 0 of
//! a configuration is the seed a run with one seed gives it ([`crate::config_seed`]); seed `r`
//! derives from it.
//!
//! [`run_jobs`] runs jobs of a testbench on the run's threads (a panic fails its job, not the
//! run), [`aggregate`] merges their results in job order and concludes them, and
//! [`run_testbench`] does both for the jobs a shard owns.

use crate::random::{Seed, Shard};
use crate::result::TbResult;
use crate::testbench::{
    conclude, config_seed, unpanicked_sim, Ctx, Registry, RunOptions, Testbench, WaveOut,
};
use serde::{Deserialize, Serialize};

/// Seeds of a run at most (`--seeds`).
pub const MAX_SEEDS: u32 = 100_000;
/// Jobs of a run at most (seeds x configurations, over the selected testbenches).
pub const MAX_JOBS: u64 = 10_000_000;

/// One job: a configuration of a testbench under one of the run's seeds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JobRef {
    /// The job's index over every testbench of the registry.
    pub index: u64,
    /// The configuration (an index into the testbench's configurations).
    pub configuration: usize,
    /// Which of the run's seeds, from 0.
    pub repeat: u32,
}

/// A job's result as a shard keeps it for the merge.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct JobResult {
    /// The job's index.
    pub index: u64,
    /// Its configuration's index.
    pub configuration: usize,
    /// Which seed, from 0.
    pub repeat: u32,
    /// What the configuration found under that seed (before any merging).
    pub result: TbResult,
    /// Seconds it ran (for the JUnit file; not part of any result).
    #[serde(default)]
    pub seconds: f64,
}

/// The seed of job (`configuration`, `repeat`) of testbench `name` in a run seeded `seed`.
pub fn job_seed(seed: Seed, name: &str, configuration: usize, repeat: u32) -> Seed {
    let s = config_seed(seed, name, configuration);
    if repeat == 0 {
        s
    } else {
        s.derive(u64::from(repeat))
    }
}

/// The label a job's messages are tagged with: its configuration's, and the seed when it is
/// not the first.
pub fn job_label(label: &str, repeat: u32) -> String {
    if repeat == 0 {
        label.to_string()
    } else {
        format!("{label}, seed #{repeat}")
    }
}

/// The index of the first job of the testbench at `position` in the registry.
fn base(reg: &Registry, position: usize, seeds: u32) -> u64 {
    reg.iter()
        .take(position)
        .map(|t| t.configurations().len() as u64 * u64::from(seeds))
        .sum()
}

/// The jobs of a testbench with `configurations` configurations under `seeds` seeds, seed by
/// seed, configuration by configuration, numbered from `first`.
pub fn numbered(first: u64, configurations: usize, seeds: u32) -> Vec<JobRef> {
    (0..seeds)
        .flat_map(|r| (0..configurations).map(move |c| (r, c)))
        .enumerate()
        .map(|(k, (repeat, configuration))| JobRef {
            index: first + k as u64,
            configuration,
            repeat,
        })
        .collect()
}

/// Every job of testbench `tb` (at `position` in the registry), in order.
pub fn testbench_jobs(
    tb: &dyn Testbench,
    position: usize,
    reg: &Registry,
    seeds: u32,
) -> Vec<JobRef> {
    numbered(base(reg, position, seeds), tb.configurations().len(), seeds)
}

/// How many jobs the selected testbenches have (`selected` says which).
pub fn count(reg: &Registry, seeds: u32, selected: &dyn Fn(&str) -> bool) -> u64 {
    reg.iter()
        .filter(|t| selected(t.name()))
        .map(|t| t.configurations().len() as u64 * u64::from(seeds))
        .sum()
}

/// The jobs of the selected testbenches that `shard` owns, per testbench (registry order; a
/// testbench it owns no job of is left out). Shards deal the run's job list round-robin.
pub fn owned<'r>(
    reg: &'r Registry,
    seeds: u32,
    shard: Shard,
    selected: &dyn Fn(&str) -> bool,
) -> Vec<(&'r dyn Testbench, Vec<JobRef>)> {
    let mut position = 0u64;
    let mut out = Vec::new();
    for (p, tb) in reg.iter().enumerate() {
        if !selected(tb.name()) {
            continue;
        }
        let mine: Vec<JobRef> = testbench_jobs(tb, p, reg, seeds)
            .into_iter()
            .filter(|_| {
                let k = position;
                position += 1;
                shard.owns(k)
            })
            .collect();
        if !mine.is_empty() {
            out.push((tb, mine));
        }
    }
    out
}

/// The job with index `index`: its testbench and place, or `None` past the last.
pub fn find(reg: &Registry, seeds: u32, index: u64) -> Option<(&dyn Testbench, JobRef)> {
    let mut first = 0u64;
    for tb in reg.iter() {
        let n = tb.configurations().len() as u64 * u64::from(seeds);
        if index < first + n {
            let k = index - first;
            let per = tb.configurations().len() as u64;
            return Some((
                tb,
                JobRef {
                    index,
                    configuration: (k % per) as usize,
                    repeat: (k / per) as u32,
                },
            ));
        }
        first += n;
    }
    None
}

/// A job for a person: `testbench [configuration]`, with the seed when it is not the first.
pub fn describe(tb: &dyn Testbench, j: &JobRef) -> String {
    let labels = tb.configurations();
    let label = labels.get(j.configuration).map_or("?", String::as_str);
    format!("{} [{}]", tb.name(), job_label(label, j.repeat))
}

/// What a shard of a run holds, counted for a progress bar.
impl Registry {
    /// Configurations a shard runs under one seed, over the selected testbenches (`only`,
    /// empty: all).
    pub fn owned_configurations(&self, shard: Shard, only: &[String]) -> u64 {
        self.owned_jobs(1, shard, only)
    }

    /// Jobs a shard runs under `seeds` seeds (numbered as above), for a progress bar.
    pub fn owned_jobs(&self, seeds: u32, shard: Shard, only: &[String]) -> u64 {
        let selected = |n: &str| only.is_empty() || only.iter().any(|o| o == n);
        owned(self, seeds, shard, &selected)
            .iter()
            .map(|(_, j)| j.len() as u64)
            .sum()
    }
}

/// Runs every configuration of `tb` that the shard owns (under each of `opts.seeds` seeds:
/// the testbench's jobs, dealt round-robin), calling `progress` with each label before it
/// runs, and merges the results; pass/fail as the module says. The waveform folder is made if
/// it is not there.
pub fn run_testbench(
    tb: &dyn Testbench,
    opts: &RunOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<TbResult, String> {
    let mine: Vec<JobRef> = numbered(0, tb.configurations().len(), opts.seeds)
        .into_iter()
        .filter(|j| opts.shard.owns(j.index))
        .collect();
    let results = run_jobs(tb, opts, &mine, progress)?;
    aggregate(tb, opts.seed, &results, opts.shard.is_all())
}

/// Runs `jobs` of `tb` (on `opts.jobs` threads), each result in its job's place.
pub fn run_jobs(
    tb: &dyn Testbench,
    opts: &RunOptions,
    jobs: &[JobRef],
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<JobResult>, String> {
    if let Some((dir, _, _)) = &opts.waves {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let labels = tb.configurations();
    let label = |j: &JobRef| job_label(&labels[j.configuration], j.repeat);
    let results = if opts.jobs > 1 && jobs.len() > 1 {
        run_parallel(tb, opts, jobs, &labels, progress)
    } else {
        jobs.iter()
            .map(|j| {
                progress(&label(j));
                timed(|| run_job(tb, opts, j, &labels[j.configuration]))
            })
            .collect()
    };
    jobs.iter()
        .zip(results)
        .map(|(j, (r, seconds))| {
            Ok(JobResult {
                index: j.index,
                configuration: j.configuration,
                repeat: j.repeat,
                result: r?,
                seconds,
            })
        })
        .collect()
}

/// `f`'s result and the seconds it took.
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = std::time::Instant::now();
    let r = f();
    (r, t.elapsed().as_secs_f64())
}

/// The jobs' results of `tb` merged in the order given (a run's, or a merge's sorted by job
/// index: the same result), then concluded; `whole_run` decides whether coverage holes fail.
pub fn aggregate(
    tb: &dyn Testbench,
    seed: Seed,
    results: &[JobResult],
    whole_run: bool,
) -> Result<TbResult, String> {
    let labels = tb.configurations();
    let mut merged = TbResult::new(tb.name(), tb.unit());
    merged.seed = Some(seed.to_string());
    merged.coverage = Some(tb.coverage());
    for j in results {
        let l = labels
            .get(j.configuration)
            .ok_or_else(|| format!("{}: no configuration {}", tb.name(), j.configuration))?;
        let label = job_label(l, j.repeat);
        merged
            .absorb(&j.result, Some(&label))
            .map_err(|e| format!("{} [{label}]: {e}", tb.name()))?;
    }
    conclude(tb, &mut merged, whole_run);
    Ok(merged)
}

/// One job of `tb`.
fn run_job(
    tb: &dyn Testbench,
    opts: &RunOptions,
    job: &JobRef,
    label: &str,
) -> Result<TbResult, String> {
    let traced = opts.trace_every_job || (job.configuration == tb.traced() && job.repeat == 0);
    let waves = opts.waves.as_ref().filter(|_| traced);
    let ctx = Ctx {
        index: job.configuration,
        seed: job_seed(opts.seed, tb.name(), job.configuration, job.repeat),
        count: opts.count.unwrap_or_else(|| tb.default_count()),
        waves: waves.map(|(dir, trace, period_ps)| WaveOut {
            vcd: dir.join(format!("{}.vcd", tb.name())),
            trace: trace.clone(),
            period_ps: *period_ps,
        }),
        check_schedule: opts.check_schedule,
        label: label.to_string(),
    };
    // Tracking is per thread: on for this job's run, as it was after.
    let was = hdl::fx::tracking();
    hdl::fx::set_tracking(opts.numeric);
    let r = unpanicked_sim(|| tb.run(&ctx));
    hdl::fx::set_tracking(was);
    let r = r.unwrap_or_else(|(cycle, p)| {
        let said = match cycle {
            Some(c) => format!("panicked in cycle {c}: {p}"),
            None => format!("panicked: {p}"),
        };
        Ok(panicked(tb, &ctx, &said))
    });
    r.map_err(|e| format!("{} [{}]: {e}", tb.name(), job_label(label, job.repeat)))
}

/// The result of a job whose run panicked: failed, with the panic's message and, when it was
/// traced, its waveform as far as it got (its view opens on the last cycle before the panic).
fn panicked(tb: &dyn Testbench, ctx: &Ctx, said: &str) -> TbResult {
    let mut r = TbResult::new(tb.name(), tb.unit());
    let wave = ctx.waves.as_ref().map(|w| &w.vcd).filter(|v| v.is_file());
    r.failures.push(match wave {
        Some(v) => format!("{said} (the waveform up to it: {})", v.display()),
        None => said.to_string(),
    });
    r.finish_with(false);
    r
}

/// The `jobs` on `opts.jobs` threads, each result in its job's place; `progress` is told of
/// each as it finishes.
fn run_parallel(
    tb: &dyn Testbench,
    opts: &RunOptions,
    jobs: &[JobRef],
    labels: &[String],
    progress: &mut dyn FnMut(&str),
) -> Vec<(Result<TbResult, String>, f64)> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    type Timed = (Result<TbResult, String>, f64);
    let next = AtomicUsize::new(0);
    let (tx, rx) = std::sync::mpsc::channel();
    let mut results: Vec<Option<Timed>> = jobs.iter().map(|_| None).collect();
    std::thread::scope(|s| {
        for _ in 0..opts.jobs.min(jobs.len()) {
            let tx = tx.clone();
            let next = &next;
            s.spawn(move || loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(j) = jobs.get(k) else {
                    break;
                };
                if tx
                    .send((k, timed(|| run_job(tb, opts, j, &labels[j.configuration]))))
                    .is_err()
                {
                    break;
                }
            });
        }
        drop(tx);
        for (k, r) in rx {
            let j = &jobs[k];
            progress(&job_label(&labels[j.configuration], j.repeat));
            results[k] = Some(r);
        }
    });
    results
        .into_iter()
        .map(|r| {
            r.unwrap_or_else(|| {
                let e = format!("{}: a configuration did not finish", tb.name());
                (Err(e), 0.0)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{Project, Unit};
    use crate::regress::{merge_shards, regress, RegressConfig, Summary};
    use crate::{About, Coverage, Coverpoint, Ctx};
    use std::path::PathBuf;

    /// A testbench of no design whose figures depend on its seed in floating point (so an
    /// order-dependent merge would show) and whose seed fails one job in `fail_one_in`.
    struct Dice {
        name: &'static str,
        labels: usize,
        fail_one_in: u64,
    }

    impl Testbench for Dice {
        fn about(&self) -> About {
            About::new(self.name, "dice")
        }
        fn configurations(&self) -> Vec<String> {
            (0..self.labels).map(|i| format!("c{i}")).collect()
        }
        fn coverage(&self) -> Coverage {
            let mut c = Coverage::new();
            c.add(Coverpoint::new("face").ranges("f", 0, 5, 6));
            c
        }
        fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
            let mut r = TbResult::new(self.name, "dice");
            let mut cov = self.coverage();
            let mut x = ctx.seed.0;
            for k in 0..ctx.count as u64 {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let golden = (x >> 11) as f64 / (1u64 << 53) as f64;
                r.stats
                    .record(golden + 1e-3 * golden.sin(), golden, 1.0 / 256.0);
                cov.sample(&[(x >> 61) as i64 % 6]);
                r.transactions += 1;
                r.cycles += 3;
                if (x >> 20).is_multiple_of(self.fail_one_in) {
                    r.mismatches += 1;
                    r.mismatch_log.push(format!("transaction {k}: a six"));
                    r.first_mismatch_cycle = r.first_mismatch_cycle.or(Some(3 * k));
                }
            }
            r.coverage = Some(cov);
            r.record(&ctx.seed.0);
            Ok(r)
        }
    }

    fn project(fail_one_in: u64) -> Project {
        Project::new("dice", "1")
            .unit(Unit::new("a", "three configurations").testbench(Dice {
                name: "a",
                labels: 3,
                fail_one_in,
            }))
            .unit(Unit::new("b", "one").testbench(Dice {
                name: "b",
                labels: 1,
                fail_one_in,
            }))
    }

    fn config(out: PathBuf, seeds: u32, shard: &str) -> RegressConfig {
        RegressConfig {
            out,
            seed: Seed(0x5eed),
            vcd: false,
            trace: Default::default(),
            period_ps: None,
            shard: Shard::parse(shard).unwrap(),
            count: Some(40),
            fst: false,
            only: Vec::new(),
            check_schedule: false,
            cosim: false,
            simulators: Vec::new(),
            jobs: 2,
            seeds,
            job: None,
            junit: None,
            require_numeric: false,
            rtl_coverage: false,
        }
    }

    /// The folder of one test's runs (removed by [`clean`]).
    fn folder(tag: &str) -> PathBuf {
        std::env::temp_dir().join(format!("texrtl-jobs-{}-{tag}", std::process::id()))
    }

    fn clean(tag: &str) {
        let _ = std::fs::remove_dir_all(folder(tag));
    }

    fn run(p: &Project, seeds: u32, shard: &str, tag: &str) -> (PathBuf, Summary) {
        let out = folder(tag).join(shard.replace('/', "of"));
        let s = regress(p, &config(out.clone(), seeds, shard), &mut |_, _| {}).unwrap();
        (out.join("summary.json"), s)
    }

    /// Runs `parts` (shards) and reads each summary back as a merge reads it.
    fn shards(p: &Project, seeds: u32, parts: &[&str], tag: &str) -> Vec<(PathBuf, Summary)> {
        parts
            .iter()
            .map(|s| {
                let (path, _) = run(p, seeds, s, tag);
                let back = reread(&path);
                (path, back)
            })
            .collect()
    }

    /// The file as it was written, read back as a merge reads it.
    fn reread(path: &PathBuf) -> Summary {
        crate::regress::parse_summary(path, &std::fs::read(path).unwrap()).unwrap()
    }

    #[test]
    fn every_job_has_one_index_and_every_partition_runs_each_once() {
        let p = project(u64::MAX);
        let reg = p.registry();
        for seeds in [1, 2, 5] {
            let total = count(reg, seeds, &|_| true);
            assert_eq!(total, 4 * u64::from(seeds));
            for i in 0..total {
                let (tb, j) = find(reg, seeds, i).unwrap();
                let pos = reg.position(tb.name()).unwrap();
                assert!(testbench_jobs(tb, pos, reg, seeds).contains(&j));
            }
            assert!(find(reg, seeds, total).is_none());
            for n in 1..=7u32 {
                let mut seen = vec![0u32; total as usize];
                for i in 1..=n {
                    let shard = Shard { index: i, count: n };
                    for (_, js) in owned(reg, seeds, shard, &|_| true) {
                        js.iter().for_each(|j| seen[j.index as usize] += 1);
                    }
                }
                assert!(seen.iter().all(|&k| k == 1), "{seeds} seeds, {n} shards");
            }
        }
        let b = |t: &str| t == "b";
        assert_eq!(count(reg, 3, &b), 3);
        let only_b = owned(reg, 3, Shard { index: 2, count: 3 }, &b);
        assert_eq!(only_b[0].1[0].index, 9 + 1);
    }

    #[test]
    fn the_first_seed_is_the_configuration_seed_and_the_others_differ() {
        let s = Seed(7);
        assert_eq!(job_seed(s, "a", 2, 0), config_seed(s, "a", 2));
        assert_ne!(job_seed(s, "a", 2, 1), job_seed(s, "a", 2, 0));
        assert_ne!(job_seed(s, "a", 2, 1), job_seed(s, "a", 2, 2));
    }

    #[test]
    fn merged_shards_are_the_unsharded_summary_byte_for_byte() {
        let p = project(300);
        let (whole_path, whole) = run(&p, 6, "1/1", "bytes");
        assert!(!whole.failing.is_empty(), "the test needs a failing job");
        let whole_bytes = std::fs::read(&whole_path).unwrap();
        // Two partitions: four equal shards, and halves and quarters mixed.
        for parts in [
            &["1/4", "2/4", "3/4", "4/4"][..],
            &["1/2", "2/4", "4/4"][..],
        ] {
            let merged = merge_shards(&p, &shards(&p, 6, parts, "bytes")).unwrap();
            let bytes = serde_json::to_vec_pretty(&merged).unwrap();
            assert!(bytes == whole_bytes, "{parts:?} merged differently");
        }
        clean("bytes");
    }

    #[test]
    fn a_missing_or_doubled_job_is_named() {
        let p = project(u64::MAX);
        let halves = shards(&p, 2, &["1/2", "2/2"], "gaps");
        let e = merge_shards(&p, &halves[..1]).err().unwrap();
        assert!(
            e.starts_with("merge: shard 2/2 is missing (its first job: job 1 (a [c1]))"),
            "{e}"
        );
        let (q, quarter) = run(&p, 2, "2/4", "gaps");
        let mixed = vec![halves[0].clone(), halves[1].clone(), (q, quarter)];
        let e = merge_shards(&p, &mixed).err().unwrap();
        assert!(e.contains("job 1 (a [c1]) is in"), "{e}");
        let e = merge_shards(&p, &[halves[0].clone()][..]).err().unwrap();
        assert!(e.contains("missing"), "{e}");
        clean("gaps");
    }

    #[test]
    fn a_failing_job_is_listed_with_the_command_that_runs_it_alone() {
        let p = project(97);
        let (_, whole) = run(&p, 3, "1/1", "repro");
        let f = whole.failing.first().expect("a failing job");
        let c = f.first_mismatch_cycle.unwrap();
        let window = format!("--trace-window {}..{}", c.saturating_sub(64), c + 16);
        let start = format!(
            "dice regress --seed {} --seeds 3 --count 40 --job ",
            Seed(0x5eed)
        );
        assert!(f.reproduce.starts_with(&start), "{}", f.reproduce);
        assert!(f.reproduce.ends_with(&window), "{}", f.reproduce);
        // The job alone fails the same way.
        let mut cfg = config(folder("repro").join("alone"), 3, "1/1");
        cfg.job = Some(f.job);
        let alone = regress(&p, &cfg, &mut |_, _| {}).unwrap();
        assert_eq!(alone.failing.len(), 1);
        assert_eq!(alone.failing[0].first, f.first);
        assert_eq!(alone.failing[0].seed, f.seed);
        clean("repro");
    }

    /// Validates `xml` against the JUnit schema the strictest reader accepts, with libxml2's
    /// `xmllint` (Debian's libxml2-utils, which `.ci/run` installs). Without it the check is
    /// skipped with a note, unless `CI` is set.
    fn schema_valid(xml: &str) -> Result<(), String> {
        use std::io::Write;
        let xsd = concat!(env!("CARGO_MANIFEST_DIR"), "/schema/junit.xsd");
        let child = std::process::Command::new("xmllint")
            .args(["--noout", "--schema", xsd, "-"])
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn();
        let mut child = match child {
            Ok(c) => c,
            Err(e) if std::env::var_os("CI").is_none() => {
                eprintln!(
                    "note: JUnit schema not checked: xmllint: {e} (apt-get install libxml2-utils)"
                );
                return Ok(());
            }
            Err(e) => panic!("xmllint: {e} (apt-get install libxml2-utils)"),
        };
        child
            .stdin
            .take()
            .unwrap()
            .write_all(xml.as_bytes())
            .unwrap();
        let o = child.wait_with_output().unwrap();
        match o.status.success() {
            true => Ok(()),
            false => Err(String::from_utf8_lossy(&o.stderr).into_owned()),
        }
    }

    fn which_xmllint() -> bool {
        std::process::Command::new("xmllint")
            .arg("--version")
            .output()
            .is_ok()
    }

    /// The schema check itself can fail: a case property and a total `skipped` are refused.
    #[test]
    fn the_schema_refuses_what_the_strictest_reader_refuses() {
        let ok = r#"<testsuites name="p" tests="1" failures="0" errors="0"><testsuite name="a" tests="1" failures="0" errors="0" skipped="0"><testcase name="c" time="0.001"><system-out>seed 1</system-out></testcase></testsuite></testsuites>"#;
        schema_valid(ok).unwrap();
        for bad in [
            ok.replace(
                r#"errors="0"><testsuite"#,
                r#"errors="0" skipped="0"><testsuite"#,
            ),
            ok.replace(
                "<system-out>seed 1</system-out>",
                r#"<properties><property name="seed" value="1"/></properties>"#,
            ),
            ok.replace(r#"time="0.001""#, r#"time="1.0001""#)
                .replace("<testcase name=\"c\"", "<testcase name=\"c\" ")
                .replace(
                    r#"<testsuite name="a""#,
                    r#"<testsuite time="1.0001" name="a""#,
                ),
        ] {
            if which_xmllint() {
                assert!(schema_valid(&bad).is_err(), "accepted: {bad}");
            }
        }
    }

    /// A passing run's JUnit file validates too.
    #[test]
    fn a_passing_run_s_junit_file_is_valid() {
        let p = project(u64::MAX);
        let (path, whole) = run(&p, 1, "1/1", "junit-pass");
        assert!(whole.passed, "{:?}", whole.failing);
        let mut cfg = config(path.parent().unwrap().to_path_buf(), 1, "1/1");
        cfg.junit = Some(path.with_file_name("junit.xml"));
        regress(&p, &cfg, &mut |_, _| {}).unwrap();
        let xml = std::fs::read_to_string(path.with_file_name("junit.xml")).unwrap();
        assert!(!xml.contains("<failure"), "{xml}");
        schema_valid(&xml).unwrap();
        clean("junit-pass");
    }

    /// The JUnit file may go into the output folder the run makes (`--out results --junit
    /// results/junit.xml`), not into another folder that is not there.
    #[test]
    fn a_junit_file_may_go_into_the_output_folder_the_run_makes() {
        let p = project(u64::MAX);
        let out = folder("junit-new").join("results");
        let mut cfg = config(out.clone(), 1, "1/1");
        cfg.junit = Some(folder("junit-new").join("elsewhere/junit.xml"));
        let Err(e) = regress(&p, &cfg, &mut |_, _| {}) else {
            panic!("a JUnit file in a missing folder was taken");
        };
        assert!(e.contains("no folder") && e.contains("elsewhere"), "{e}");
        assert!(!out.exists());
        cfg.junit = Some(out.join("junit.xml"));
        regress(&p, &cfg, &mut |_, _| {}).unwrap();
        schema_valid(&std::fs::read_to_string(out.join("junit.xml")).unwrap()).unwrap();
        clean("junit-new");
    }

    #[test]
    fn the_junit_file_has_a_case_per_job_and_merges_as_the_summary_does() {
        let p = project(50);
        let (path, whole) = run(&p, 2, "1/1", "junit");
        let mut cfg = config(path.parent().unwrap().to_path_buf(), 2, "1/1");
        cfg.junit = Some(path.with_file_name("junit.xml"));
        regress(&p, &cfg, &mut |_, _| {}).unwrap();
        let xml = std::fs::read_to_string(path.with_file_name("junit.xml")).unwrap();
        let report = quick_junit::Report::deserialize_from_str(&xml).unwrap();
        // Two seeds of 3 + 1 configurations, and each testbench's merged verdict.
        assert_eq!(report.tests, 8 + 2);
        let failing_rows = whole.testbenches.iter().filter(|r| !r.passed).count();
        assert_eq!(report.failures, whole.failing.len() + failing_rows);
        let f = &whole.failing[0];
        // A case's job, seed and command: the lines of its system-out.
        let out = |c: &quick_junit::TestCase| {
            c.system_out
                .as_ref()
                .map(|o| o.as_str().to_string())
                .unwrap_or_default()
        };
        let case = report
            .test_suites
            .iter()
            .flat_map(|s| &s.test_cases)
            .find(|c| out(c).starts_with(&format!("job {}\n", f.job)))
            .expect("the failing job's case");
        let seed = Seed::parse(&f.seed).unwrap();
        assert_eq!(
            out(case),
            crate::junit::case_output(f.job, seed, &f.reproduce)
        );
        match &case.status {
            quick_junit::TestCaseStatus::NonSuccess { description, .. } => {
                let d = description.as_ref().unwrap().as_str();
                assert!(d.ends_with(&format!("reproduce: {}", f.reproduce)), "{d}");
            }
            s => panic!("the failing job passed: {s:?}"),
        }
        schema_valid(&xml).unwrap();
        // The shards' JUnit, merged: the whole run's but for the times.
        let thirds = shards(&p, 2, &["1/3", "2/3", "3/3"], "junit");
        let merged = merge_shards(&p, &thirds).unwrap();
        let jobs: Vec<JobResult> = thirds.iter().flat_map(|(_, s)| s.jobs.clone()).collect();
        let again = crate::junit::junit(&p, &merged, &jobs, &[]).unwrap();
        assert_eq!(crate::junit::timeless(&again), crate::junit::timeless(&xml));
        clean("junit");
    }
}
