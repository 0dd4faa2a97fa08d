//! The testbench interface and the registry that `texrtl regress`, sharding, `merge`, the
//! report and the progress bar all iterate.
//!
//! A testbench is a set of named **configurations** (a width, a mode, a trace, a frame size):
//! the unit of sharding and of seeding. The framework runs each configuration the shard owns
//! with its own seed (so shards together run exactly what one unsharded run does), merges the
//! results, and decides pass or fail the same way for every testbench: no mismatch, no
//! failure, and (for a whole run) no coverage hole. The running itself, job by job, is
//! [`crate::jobs`]'s.

use crate::coverage::Coverage;
use crate::random::{Seed, Shard};
use crate::result::TbResult;
use hdl::kernel::{Module, Sim};
use std::path::PathBuf;
use waves::{TraceConfig, VcdTracer};

/// What a configuration is run with; built by [`run_testbench`](crate::run_testbench).
#[derive(Clone, Debug)]
pub struct Ctx {
    /// The configuration's index in [`Testbench::configurations`] and its label.
    pub index: usize,
    /// The configuration's label.
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

impl Ctx {
    /// A simulation of `dut` for this configuration: traced when it writes the waveform, with
    /// the schedule check when asked. `probes` declares the golden values and flags shown
    /// beside the design (called only when traced).
    pub fn sim<M: Module, P>(
        &self,
        dut: M,
        title: &str,
        own_period_ps: u64,
        probes: impl FnOnce(&mut VcdTracer) -> P,
    ) -> Result<(Sim<M, VcdTracer>, Option<P>), String> {
        let work = crate::Workload {
            wave: self.waves.clone(),
        };
        let (sim, p) = work.sim(dut, title, own_period_ps, probes)?;
        Ok((sim.check_schedule(self.check_schedule), p))
    }

    /// Ends a simulation made by [`Ctx::sim`]: the waveform is closed (and its `.gtkw`
    /// written) and named in `res`.
    pub fn finish<M: Module>(
        &self,
        sim: Sim<M, VcdTracer>,
        res: &mut TbResult,
    ) -> Result<M, String> {
        let dut = sim.finish().map_err(|e| e.to_string())?;
        res.vcd = self.waves.as_ref().map(|w| w.vcd.clone());
        if hdl::fx::tracking() {
            crate::numeric::merge(&mut res.narrowings, &crate::numeric::rows(&dut));
        }
        Ok(dut)
    }
}

/// A waveform to write: the VCD's path and what to trace.
#[derive(Clone, Debug)]
pub struct WaveOut {
    /// The VCD's path (its `.gtkw` goes beside it).
    pub vcd: PathBuf,
    /// What to trace.
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

/// What a testbench is, declared once ([`Testbench::about`]): the name it runs under, the unit
/// it verifies, how many random transactions a configuration draws when `--count` is not
/// given and what one is, and which configuration writes the waveform.
///
/// ```
/// use verif::About;
///
/// let a = About::new("blend", "a two-stage alpha blend");
/// assert_eq!((a.count, a.count_unit, a.traced), (1000, "random transactions", 0));
/// let a = a.count(500, "pixels").traced(1);
/// assert_eq!((a.name, a.count, a.count_unit, a.traced), ("blend", 500, "pixels", 1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct About {
    /// Its name in the table, in `summary.json`, in `--only` and as its waveform's file name.
    pub name: &'static str,
    /// The unit it verifies, with its number and where the document describes it.
    pub unit: &'static str,
    /// Random transactions per configuration when `--count` is not given.
    pub count: usize,
    /// What one of `--count` is, in the progress line and `--list`.
    pub count_unit: &'static str,
    /// The configuration that writes the waveform.
    pub traced: usize,
}

impl About {
    /// Testbench `name` of `unit`: 1000 random transactions a configuration, the first
    /// configuration traced.
    pub const fn new(name: &'static str, unit: &'static str) -> About {
        About {
            name,
            unit,
            count: 1000,
            count_unit: "random transactions",
            traced: 0,
        }
    }

    /// `n` of `what` per configuration when `--count` is not given.
    pub const fn count(self, n: usize, what: &'static str) -> About {
        About {
            count: n,
            count_unit: what,
            ..self
        }
    }

    /// Configuration `k` writes the waveform.
    pub const fn traced(self, k: usize) -> About {
        About { traced: k, ..self }
    }
}

/// A testbench: what it is ([`About`]), named configurations, a coverage model, and a run of
/// one configuration.
pub trait Testbench: Sync {
    /// What it is, declared once; the accessors below read it.
    fn about(&self) -> About;
    /// The labels of its configurations, in run order (by default one, `default`).
    fn configurations(&self) -> Vec<String> {
        vec!["default".into()]
    }
    /// A fresh coverage model (no hits); every configuration's result carries one like it.
    fn coverage(&self) -> Coverage;
    /// Runs one configuration. `Err` is for what stops the run (bad parameters, I/O); what the
    /// DUT got wrong goes into the result (a hang too: [`TbResult::ran`]). A panic in it (a
    /// value that does not fit its signal's format) fails this job with the panic's message
    /// and the run goes on.
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String>;
    /// After every configuration (or every shard, in `texrtl merge`): notes and tables from the
    /// merged records and extra checks across configurations.
    fn conclude(&self, _merged: &mut TbResult) {}

    /// [`About::name`].
    fn name(&self) -> &'static str {
        self.about().name
    }
    /// [`About::unit`].
    fn unit(&self) -> &'static str {
        self.about().unit
    }
    /// [`About::count`].
    fn default_count(&self) -> usize {
        self.about().count
    }
    /// [`About::count_unit`].
    fn count_unit(&self) -> &'static str {
        self.about().count_unit
    }
    /// [`About::traced`].
    fn traced(&self) -> usize {
        self.about().traced
    }
}

/// What a regression run applies to every testbench.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The run's seed.
    pub seed: Seed,
    /// Random transactions per configuration; `None`: each testbench's default.
    pub count: Option<usize>,
    /// The share of the configurations this run owns.
    pub shard: Shard,
    /// Write each testbench's waveform into this folder as `<name>.vcd` + `.gtkw`.
    pub waves: Option<(PathBuf, TraceConfig, Option<u64>)>,
    /// Run the kernel's schedule check on every cycle.
    pub check_schedule: bool,
    /// Configurations run at once, on as many threads (1: one after the other). The merged
    /// result is the same either way: configurations are merged in their order.
    pub jobs: usize,
    /// Seeds each configuration runs under ([`crate::jobs`]); 1: the run's seed alone.
    pub seeds: u32,
    /// Trace whichever job runs, not only the testbench's traced configuration under the
    /// first seed (for a run of one job: its reproduction).
    pub trace_every_job: bool,
    /// Count what every named narrowing meets (numeric coverage, in the summary and the
    /// report); off, a narrowing costs one thread-local test.
    pub numeric: bool,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            seed: Seed(0),
            count: None,
            shard: Shard::default(),
            waves: None,
            check_schedule: false,
            jobs: 1,
            seeds: 1,
            trace_every_job: false,
            numeric: true,
        }
    }
}

impl RunOptions {
    /// The defaults, writing each testbench's waveform (every signal, its own clock) into `dir`
    /// as `<name>.vcd` and `<name>.gtkw`.
    pub fn with_waves(dir: impl Into<PathBuf>) -> RunOptions {
        RunOptions {
            waves: Some((dir.into(), TraceConfig::default(), None)),
            ..RunOptions::default()
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

/// `f`'s value, or the message of a panic in it: a model's value that does not fit its
/// signal's format, say, which is a finding about the design, not the end of a regression.
/// (The panic is also printed where it happened, by the panic hook.)
pub(crate) fn unpanicked<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|p| {
        (p.downcast_ref::<&str>().copied())
            .or(p.downcast_ref::<String>().map(String::as_str))
            .unwrap_or("(no message)")
            .to_string()
    })
}

/// `f`'s value, or, when a panic ended it, the cycle of the simulation it unwound (when it
/// unwound one: [`hdl::kernel::panicked_in_cycle`]) and the panic's message.
pub(crate) fn unpanicked_sim<T>(f: impl FnOnce() -> T) -> Result<T, (Option<u64>, String)> {
    let _ = hdl::kernel::panicked_in_cycle(); // not an earlier panic's
    unpanicked(f).map_err(|said| (hdl::kernel::panicked_in_cycle(), said))
}

/// The framework's verdict on a merged result: coverage figures, the testbench's own
/// conclusions, then pass/fail (holes, and a testbench that compared nothing, fail only a
/// whole run).
pub fn conclude(tb: &dyn Testbench, merged: &mut TbResult, whole_run: bool) {
    if let Some(c) = merged.coverage.take() {
        merged.set_coverage(c);
    }
    merged.strip_conclusions();
    merged.own = Some((merged.notes.len(), merged.tables.len()));
    tb.conclude(merged);
    merged.finish_with(whole_run);
    if whole_run {
        merged.vacuous();
    }
}

/// The testbenches of a project, in run order.
#[derive(Default)]
pub struct Registry {
    tbs: Vec<Box<dyn Testbench>>,
}

impl Registry {
    /// An empty registry.
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

    /// The testbenches, in run order.
    pub fn iter(&self) -> impl Iterator<Item = &dyn Testbench> {
        self.tbs.iter().map(|b| b.as_ref())
    }

    /// The testbench named `name`.
    pub fn get(&self, name: &str) -> Option<&dyn Testbench> {
        self.iter().find(|t| t.name() == name)
    }

    /// Their names, in run order.
    pub fn names(&self) -> Vec<&'static str> {
        self.iter().map(|t| t.name()).collect()
    }

    /// The position of `name` in run order.
    pub fn position(&self, name: &str) -> Option<usize> {
        self.iter().position(|t| t.name() == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jobs::{run_jobs, run_testbench};
    use crate::Coverpoint;
    use serde::Serialize;
    use std::sync::Mutex;

    /// A testbench that runs no design: each configuration records what it was given and
    /// logs its run beside the progress calls.
    struct Toy {
        name: &'static str,
        labels: Option<Vec<String>>,
        log: Mutex<Vec<String>>,
    }

    impl Toy {
        fn new(name: &'static str, labels: &[&str]) -> Toy {
            Toy {
                name,
                labels: (!labels.is_empty())
                    .then(|| labels.iter().map(|l| l.to_string()).collect()),
                log: Mutex::new(Vec::new()),
            }
        }
    }

    #[derive(Serialize, serde::Deserialize, Debug, PartialEq)]
    struct Given {
        index: usize,
        label: String,
        count: usize,
        seed: u64,
        vcd: Option<PathBuf>,
        period_ps: Option<u64>,
    }
    impl Testbench for Toy {
        fn about(&self) -> About {
            About::new(self.name, "none")
        }
        fn configurations(&self) -> Vec<String> {
            self.labels
                .clone()
                .unwrap_or_else(|| vec!["default".into()])
        }
        fn coverage(&self) -> Coverage {
            let mut c = Coverage::new();
            c.add(Coverpoint::new("index").ranges("i", 0, 2, 3));
            c
        }
        fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
            self.log.lock().unwrap().push(format!("run {}", ctx.label));
            let mut r = TbResult::new(self.name, "none");
            r.transactions = 1;
            let mut c = self.coverage();
            c.sample(&[ctx.index as i64]);
            r.coverage = Some(c);
            r.record(&Given {
                index: ctx.index,
                label: ctx.label.clone(),
                count: ctx.count,
                seed: ctx.seed.0,
                vcd: ctx.waves.as_ref().map(|w| w.vcd.clone()),
                period_ps: ctx.waves.as_ref().map(|w| w.config(5000).period_ps),
            });
            Ok(r)
        }
    }

    /// Runs `tb` with `opts`, logging progress calls beside the runs.
    fn run_logged(tb: &Toy, opts: &RunOptions) -> (TbResult, Vec<String>) {
        let r = run_testbench(tb, opts, &mut |l| {
            tb.log.lock().unwrap().push(format!("progress {l}"))
        })
        .unwrap();
        (r, std::mem::take(&mut *tb.log.lock().unwrap()))
    }

    /// A testbench whose jobs score no transaction fails a whole run, and only a whole run:
    /// a shard's jobs may be the ones that happen to compare nothing.
    #[test]
    fn a_run_that_compared_nothing_fails() {
        struct Idle;
        impl Testbench for Idle {
            fn about(&self) -> About {
                About::new("idle", "none")
            }
            fn coverage(&self) -> Coverage {
                Coverage::new()
            }
            fn run(&self, _: &Ctx) -> Result<TbResult, String> {
                let mut r = TbResult::new("idle", "none");
                r.cycles = 100;
                Ok(r)
            }
        }
        let whole = run_testbench(&Idle, &RunOptions::default(), &mut |_| {}).unwrap();
        assert!(!whole.passed);
        assert_eq!(
            whole.failures,
            ["compared nothing: no transaction was scored in any configuration"]
        );
        let shard = RunOptions {
            shard: Shard { index: 1, count: 2 },
            ..RunOptions::default()
        };
        let part = run_testbench(&Idle, &shard, &mut |_| {}).unwrap();
        assert!(part.passed, "{:?}", part.failures);
    }

    #[test]
    fn a_testbench_s_defaults() {
        struct Plain;
        impl Testbench for Plain {
            fn about(&self) -> About {
                About::new("plain", "none")
            }
            fn coverage(&self) -> Coverage {
                Coverage::new()
            }
            fn run(&self, _: &Ctx) -> Result<TbResult, String> {
                unreachable!()
            }
        }
        assert_eq!(Plain.configurations(), ["default"]);
        assert_eq!(Plain.default_count(), 1000);
        assert_eq!(Plain.count_unit(), "random transactions");
        assert_eq!(Plain.traced(), 0);
    }

    /// A counter into a 3-bit port: counts past 7 do not fit.
    #[derive(Clone)]
    struct Narrow {
        count: hdl::kernel::Reg,
        out: hdl::kernel::Signal,
    }

    impl hdl::kernel::Module for Narrow {
        fn kind(&self) -> &'static str {
            "narrow"
        }
        fn eval(&mut self) {
            let c = self.count.q().bits();
            self.out.set_bits(c);
            self.count.set_next_bits(c + 1);
        }
        fn tick(&mut self, reset: bool) {
            self.count.tick(reset);
        }
        fn visit(&self, v: &mut dyn hdl::kernel::Visitor) {
            v.enter("narrow", "narrow");
            v.reg(&self.count);
            v.signal(hdl::kernel::Dir::Output, &self.out);
            v.leave();
        }
    }

    /// Configuration `cycles N` runs the counter N cycles (traced when it is the first).
    struct Overflowing;
    impl Testbench for Overflowing {
        fn about(&self) -> About {
            About::new("overflowing", "narrow")
        }
        fn configurations(&self) -> Vec<String> {
            vec!["cycles 12".into(), "cycles 6".into()]
        }
        fn coverage(&self) -> Coverage {
            Coverage::new()
        }
        fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
            let dut = Narrow {
                count: hdl::kernel::Reg::new("count", hdl::fx::Format::uint(8)),
                out: hdl::kernel::Signal::new("out", hdl::fx::Format::uint(3)),
            };
            let (mut sim, _) = ctx.sim(dut, "narrow", 10_000, |_| ())?;
            sim.reset(1);
            let n = if ctx.index == 0 { 12 } else { 6 };
            for _ in 0..n {
                sim.step();
            }
            let mut r = TbResult::new(self.name(), self.unit());
            r.cycles = n;
            ctx.finish(sim, &mut r)?;
            Ok(r)
        }
    }

    /// A job whose model panics (a value its signal cannot hold) fails with the panic's
    /// message and its waveform up to the panic, opened on its last cycle; the other jobs run.
    #[test]
    fn a_job_that_panics_fails_and_the_others_run() {
        let dir = std::env::temp_dir().join(format!("texrtl-panics-{}", std::process::id()));
        let opts = RunOptions {
            jobs: 2,
            seeds: 2,
            ..RunOptions::with_waves(&dir)
        };
        let jobs = crate::jobs::testbench_jobs(&Overflowing, 0, &Registry::new(), 2);
        let done = run_jobs(&Overflowing, &opts, &jobs, &mut |_| {}).unwrap();
        let failed: Vec<(usize, u32)> = (done.iter())
            .filter(|j| j.result.failed_itself())
            .map(|j| (j.configuration, j.repeat))
            .collect();
        assert_eq!(failed, [(0, 0), (0, 1)], "12 cycles overflow, 6 do not");
        let said = &done[0].result.failures[0];
        let vcd = dir.join("overflowing.vcd");
        let want = format!(
            "panicked in cycle 9: signal 'out' (u3, 3 bits): bits 0x8 does not fit (the waveform up to it: {})",
            vcd.display()
        );
        assert_eq!(*said, want);
        // Reset, then counts 0..7 sampled: the panic came in the next cycle's eval.
        let g = std::fs::read_to_string(vcd.with_extension("gtkw")).unwrap();
        assert!(
            g.contains("[*] dump 0 90000 ps") && g.contains("Abefore the panic"),
            "{g}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// One after the other: each configuration announced before it runs, with its index,
    /// label, the testbench's count, its own seed, and the waveform for the traced one only.
    #[test]
    fn configurations_run_in_order_with_their_own_seeds() {
        let tb = Toy::new("toy", &["a", "b", "c"]);
        let dir = std::env::temp_dir().join(format!("texrtl-toy-{}", std::process::id()));
        let mut opts = RunOptions::with_waves(&dir);
        opts.count = Some(7);
        let (r, log) = run_logged(&tb, &opts);
        let want = [
            "progress a",
            "run a",
            "progress b",
            "run b",
            "progress c",
            "run c",
        ];
        assert_eq!(log, want);
        assert_eq!(r.configurations, 3);
        assert!(r.passed, "every bin hit: {:?}", r.failures);
        let given = r.records_of::<Given>();
        let seeds: Vec<u64> = (0..3).map(|i| config_seed(Seed(0), "toy", i).0).collect();
        for (i, g) in given.iter().enumerate() {
            assert_eq!((g.index, g.count, g.seed), (i, 7, seeds[i]));
            let traced = (i == 0).then(|| dir.join("toy.vcd"));
            assert_eq!(g.vcd, traced, "{i}");
            assert_eq!(
                g.period_ps,
                (i == 0).then_some(5000),
                "the unit's own clock"
            );
        }
        assert!(dir.is_dir(), "the waveform folder is made");
        std::fs::remove_dir_all(&dir).unwrap();
        opts.waves = Some((dir.clone(), TraceConfig::default(), Some(2000)));
        opts.count = None;
        let (r, _) = run_logged(&tb, &opts);
        let g = &r.records_of::<Given>()[0];
        assert_eq!(
            (g.count, g.period_ps),
            (1000, Some(2000)),
            "the default, the user's clock"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// On threads: each configuration announced as it finishes, the merged result the same as
    /// one after the other. A single configuration runs on the caller's thread.
    #[test]
    fn configurations_on_threads_merge_as_one_after_the_other() {
        let tb = Toy::new("toy", &["a", "b", "c"]);
        let (serial, _) = run_logged(&tb, &RunOptions::default());
        let opts = RunOptions {
            jobs: 2,
            ..RunOptions::default()
        };
        let (parallel, log) = run_logged(&tb, &opts);
        for l in ["a", "b", "c"] {
            let at = |what: &str| {
                log.iter()
                    .position(|x| *x == format!("{what} {l}"))
                    .unwrap()
            };
            assert!(at("run") < at("progress"), "{log:?}");
        }
        assert_eq!(parallel.records, serial.records);
        assert_eq!(parallel.configurations, 3);
        let one = Toy::new("one", &[]);
        let (r, log) = run_logged(&one, &opts);
        assert_eq!(log, ["progress default", "run default"]);
        assert_eq!(r.configurations, 1);
    }

    /// Distinct testbench names give distinct seeds (FNV-1a of the name).
    #[test]
    fn every_name_seeds_its_own_stream() {
        let seeds: std::collections::HashSet<Seed> = (0..200)
            .map(|k| config_seed(Seed(5), &format!("tb{k}"), 0))
            .collect();
        assert_eq!(seeds.len(), 200);
    }

    /// The registry finds testbenches by name and position and counts what a shard runs.
    #[test]
    fn the_registry_finds_and_counts() {
        let mut reg = Registry::new();
        reg.register(Box::new(Toy::new("x", &["a", "b", "c"])))
            .register(Box::new(Toy::new("y", &[])));
        assert_eq!(reg.names(), ["x", "y"]);
        assert_eq!(reg.iter().count(), 2);
        assert_eq!(reg.get("y").map(|t| t.name()), Some("y"));
        assert!(reg.get("z").is_none());
        assert_eq!((reg.position("x"), reg.position("y")), (Some(0), Some(1)));
        assert_eq!(reg.position("z"), None);
        let all = Shard::default();
        let second = Shard::parse("2/2").unwrap();
        assert_eq!(reg.owned_configurations(all, &[]), 4);
        // The run's jobs x0 x1 x2 y0, dealt round-robin: the second of two shards has x1, y0.
        assert_eq!(reg.owned_configurations(second, &[]), 2);
        assert_eq!(reg.owned_jobs(3, second, &[]), 6);
        assert_eq!(reg.owned_configurations(all, &["y".into()]), 1);
        assert_eq!(reg.owned_configurations(all, &["x".into()]), 3);
    }

    #[test]
    #[should_panic(expected = "testbench 'x' registered twice")]
    fn a_name_is_registered_once() {
        let mut reg = Registry::new();
        reg.register(Box::new(Toy::new("x", &[])));
        reg.register(Box::new(Toy::new("x", &[])));
    }
}
