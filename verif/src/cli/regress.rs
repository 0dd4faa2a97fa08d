//! `regress` (the default command): every testbench of the project on built-in stimulus, the
//! vectors check, the co-simulation of every twin, the table, `summary.json`, the pictures
//! and `report.md`.

use super::args::{all, clap_args, flag, given, one, path, value, values};
use super::{fail, say};
use crate::project::Project;
use crate::regress::{regress, RegressConfig};
use crate::{Seed, Shard};
use clap::{value_parser, ArgMatches, Command};
use std::path::PathBuf;
use std::process::ExitCode;
use waves::TraceConfig;

/// Run every testbench on built-in stimulus (the default command).
#[derive(Clone, Debug)]
pub struct RegressArgs {
    out: Option<PathBuf>,
    seed: Seed,
    no_vcd: bool,
    trace_depth: Option<usize>,
    trace_filter: Vec<String>,
    trace_hex: Vec<String>,
    trace_window: Option<(u64, u64)>,
    period_ps: Option<u64>,
    bless: bool,
    shard: Shard,
    pub(super) count: Option<usize>,
    fst: bool,
    only: Vec<String>,
    list: bool,
    check_schedule: bool,
    no_cosim: bool,
    sim: Vec<crate::cosim::Simulator>,
    pub(super) jobs: Option<usize>,
    seeds: u32,
    job: Option<u64>,
    junit: Option<PathBuf>,
    require_numeric: bool,
    rtl_coverage: bool,
}

clap_args!(RegressArgs);

impl RegressArgs {
    pub(super) fn augment(c: Command) -> Command {
        c.args([
            path("out", "OUT", "Directory for VCDs, .gtkw files, summary.json and report.md (default target/NAME, NAME the program's)"),
            value("seed", "SEED", Seed::parse, "Stimulus seed (hex 0x... or decimal); the run prints it, and the same seed replays it").default_value("0x7e47"),
            flag("no-vcd", "Write no waveforms"),
            value("trace-depth", "TRACE_DEPTH", value_parser!(usize), "Trace scopes down to this depth (0 = clock, reset and golden probes only; 1 = each testbench's top unit; ...)"),
            values("trace-filter", "TRACE_FILTER", value_parser!(String), "Trace only signals whose hierarchical name (e.g. tb.top.u0) matches this glob; repeatable"),
            values("trace-hex", "GLOB", value_parser!(String), "Show the vectors whose hierarchical name matches this glob in hexadecimal (the others show as unsigned or signed decimal, by their format); repeatable"),
            value("trace-window", "TRACE_WINDOW", parse_window, "Trace only cycles START..END"),
            value("period-ps", "PERIOD_PS", value_parser!(u64), "Clock period in picoseconds shown in every waveform (even, >= 2; default: each testbench's own clock)"),
            flag("bless", "Rewrite the kept bit-accuracy vectors after a deliberate change, and print what changed"),
            value("shard", "SHARD", Shard::parse, "Run only shard I of N (the run's jobs dealt round-robin; merge the summaries with `merge`)").default_value("1/1"),
            value("count", "COUNT", value_parser!(usize), "Random transactions per configuration, 1..=1000000 (default: each testbench's own)"),
            flag("fst", "Also write every waveform as FST, directly while simulating (compact; open with `gtkwave X.fst X.gtkw`)"),
            values("only", "ONLY", value_parser!(String), "Run only this testbench (repeatable; `vectors` is the bit-accuracy check)"),
            flag("list", "List the testbenches with their configurations and what --count counts, and exit"),
            flag("check-schedule", "Run the kernel's schedule check (every cycle evaluated twice) in every testbench"),
            flag("no-cosim", "Skip the co-simulation of the Verilog twins (run by default when Verilator or Icarus is installed, as rows cosim/UNIT/SIMULATOR)"),
            values("sim", "SIM", parse_simulator, "Co-simulate in this simulator only, verilator or icarus (repeatable; default: every one installed, and both in a shard, whose jobs must not depend on its machine)"),
            value("jobs", "JOBS", value_parser!(usize), "Configurations run at once, 1..=256 threads (default: the machine's cores); the results are the same for any number").short('j'),
            value("seeds", "SEEDS", value_parser!(u32), "Run every configuration, and every twin's co-simulation, under this many seeds (the first is --seed's): seeds x configurations, and seeds x twins x simulators, are the run's jobs, which --shard deals out").default_value("1"),
            value("job", "JOB", value_parser!(u64), "Run only this job, with its waveform: what a failing job's line in the report runs (no vectors, no co-simulation)"),
            path("junit", "FILE", "Also write the run's JUnit XML (one test case per job, with its seed and the command that reproduces it) for a CI server"),
            flag("require-numeric-coverage", "Fail a testbench whose named narrowings left a saturation, wrap or rounding tie never reached (unless the unit declares it unreachable); a sharded run decides at `merge`"),
            flag("rtl-coverage", "Measure the RTL's line and toggle coverage in the Verilator co-simulation rows (as `cosim --rtl-coverage`): a note per row, and its files in the row's folder"),
        ])
    }

    pub(super) fn read(m: &ArgMatches) -> Self {
        RegressArgs {
            out: one(m, "out"),
            seed: given(m, "seed"),
            no_vcd: m.get_flag("no-vcd"),
            trace_depth: one(m, "trace-depth"),
            trace_filter: all(m, "trace-filter"),
            trace_hex: all(m, "trace-hex"),
            trace_window: one(m, "trace-window"),
            period_ps: one(m, "period-ps"),
            bless: m.get_flag("bless"),
            shard: given(m, "shard"),
            count: one(m, "count"),
            fst: m.get_flag("fst"),
            only: all(m, "only"),
            list: m.get_flag("list"),
            check_schedule: m.get_flag("check-schedule"),
            no_cosim: m.get_flag("no-cosim"),
            sim: all(m, "sim"),
            jobs: one(m, "jobs"),
            seeds: given(m, "seeds"),
            job: one(m, "job"),
            junit: one(m, "junit"),
            require_numeric: m.get_flag("require-numeric-coverage"),
            rtl_coverage: m.get_flag("rtl-coverage"),
        }
    }
}

fn parse_simulator(s: &str) -> Result<crate::cosim::Simulator, String> {
    crate::cosim::Simulator::parse(s).ok_or_else(|| "verilator or icarus".to_string())
}

fn parse_window(s: &str) -> Result<(u64, u64), String> {
    let bad = || format!("'{s}' is not a window START..END of cycles");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let (a, b): (u64, u64) = (a.parse().map_err(|_| bad())?, b.parse().map_err(|_| bad())?);
    if a >= b {
        return Err(format!("window {a}..{b} is empty"));
    }
    Ok((a, b))
}

/// A shard's `--out` must not hold another shard's summary of the same run (seed and shard
/// count): the run would overwrite it, and a loop of shards into one folder would keep only
/// the last. The same shard again (a task run anew) overwrites its own.
fn check_shard_folder(cfg: &RegressConfig) -> Result<(), String> {
    let path = cfg.out.join("summary.json");
    if cfg.shard.is_all() || !path.is_file() {
        return Ok(());
    }
    let b = waves::output::read_bounded(&path, 256 << 20)?;
    let Ok(theirs) = crate::regress::parse_summary(&path, &b) else {
        return Ok(());
    };
    let mine = cfg.shard.to_string();
    let Some(shard) = theirs.shard.filter(|s| *s != mine) else {
        return Ok(());
    };
    let of = |s: &str| s.split('/').nth(1).map(str::to_string);
    if theirs.seed != cfg.seed.to_string() || of(&shard) != of(&mine) {
        return Ok(());
    }
    let out = cfg.out.display();
    Err(format!(
        "--out {out}: holds the summary of shard {shard} of this run; give each shard a folder of its own (--out {out}/{})",
        cfg.shard.index
    ))
}

/// Runs the regression; exit 0 all passed, 1 a testbench failed, 2 bad input.
pub fn run(project: &Project, a: RegressArgs) -> ExitCode {
    let name = project.name();
    if a.list {
        say(&list_testbenches(project));
        return ExitCode::SUCCESS;
    }
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("target").join(name));
    let bless = a.bless;
    let cfg = RegressConfig {
        out,
        seed: a.seed,
        vcd: !a.no_vcd,
        trace: TraceConfig {
            period_ps: a.period_ps.unwrap_or(10_000),
            max_depth: a.trace_depth,
            filters: a.trace_filter,
            window: a.trace_window,
            companions: true,
            hex: a.trace_hex,
            fst: a.fst,
        },
        period_ps: a.period_ps,
        shard: a.shard,
        count: a.count,
        fst: a.fst,
        only: a.only,
        check_schedule: a.check_schedule,
        cosim: !a.no_cosim,
        simulators: a.sim,
        jobs: a.jobs.unwrap_or_else(|| {
            std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
        }),
        seeds: a.seeds,
        job: a.job,
        junit: a.junit,
        require_numeric: a.require_numeric,
        rtl_coverage: a.rtl_coverage,
    };
    if let Err(e) = cfg.trace.validate() {
        return fail(name, format!("--period-ps/--trace-window: {e}"));
    }
    if let Err(e) = cfg.validate(project.registry()) {
        return fail(name, e);
    }
    if let Err(e) = check_shard_folder(&cfg) {
        return fail(name, e);
    }
    if bless && project.kept_vectors().is_none() {
        return fail(
            name,
            "--bless: the project keeps no vectors (Project::vectors_dir)",
        );
    }
    // On an I/O error, what this run made in the output folder goes (a failed testbench
    // keeps its waves and report).
    let mut made = super::Outputs::default();
    made.folder(&cfg.out);
    if let Some(j) = &cfg.junit {
        made.file(j);
    }
    // Made before the run starts: a folder that cannot be made is bad input, said alone.
    if let Err(e) = super::make_folder("--out", &cfg.out) {
        made.remove_new();
        return fail(name, e);
    }
    eprintln!(
        "{name} regress: seed {} (replay with --seed {})",
        cfg.seed, cfg.seed
    );
    run_checked(project, &cfg, bless, &made)
}

/// The regression once its options are checked: the run, the report, the table and the
/// blessing; exit 0 all passed, 1 a testbench failed, 2 bad input or an I/O error (which
/// removes what the run made in the output folder: a failed testbench keeps its waves).
fn run_checked(
    project: &Project,
    cfg: &RegressConfig,
    bless: bool,
    made: &super::Outputs,
) -> ExitCode {
    let name = project.name();
    // A progress bar on stderr, one step per job (hidden when stderr is not a terminal).
    let reg = project.registry();
    let steps = match cfg.job {
        Some(_) => 1,
        None => reg.owned_jobs(cfg.seeds, cfg.shard, &cfg.only),
    };
    let bar = indicatif::ProgressBar::new(steps);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let done = regress(project, cfg, &mut |tb, label| {
        bar.set_message(format!("{tb}: {label}"));
        if !tb.is_empty() {
            bar.inc(1);
        }
    })
    .and_then(|s| crate::report::write_report(project, &cfg.out, &s).map(|_| s));
    bar.finish_and_clear();
    match done {
        Ok(summary) => {
            say(&crate::report::failing_lines(&summary, 10));
            say(&crate::report::render(&summary.testbenches, cfg));
            say(&crate::report::rtl_coverage_lines(&summary, 10));
            let results = summary.testbenches;
            if let Some(w) = unmatched_filters(cfg, &results) {
                eprintln!("{name}: warning: {w}");
            }
            if let Some(dir) = project.kept_vectors().filter(|_| bless) {
                match crate::vectors::bless(dir, project.vectors()) {
                    Ok(changed) if changed.is_empty() => say("vectors: unchanged\n"),
                    Ok(changed) => {
                        for c in changed {
                            say(&format!("vectors blessed: {c}\n"));
                        }
                    }
                    Err(e) => return fail(name, e),
                }
            }
            if results.iter().all(|r| r.passed) {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Err(e) => {
            made.remove_new();
            fail(name, e)
        }
    }
}

/// A warning when `--trace-filter` matched no signal of any testbench's design (a pattern
/// without the `tb.` every name starts with, say): its waveforms hold only the clock, reset
/// and probes. The co-simulation rows' waveforms are not filtered.
fn unmatched_filters(cfg: &RegressConfig, results: &[crate::TbResult]) -> Option<String> {
    let filters = &cfg.trace.filters;
    if filters.is_empty() {
        return None;
    }
    let cosim = format!("{}/", crate::regress::COSIM);
    let traced: Vec<&crate::TbResult> = results
        .iter()
        .filter(|r| r.vcd.is_some() && !r.name.starts_with(&cosim))
        .collect();
    // A waveform that cannot be read back is another matter (its row says so).
    let holds_design = |r: &&crate::TbResult| {
        r.vcd
            .as_deref()
            .is_some_and(|v| waves::design_variables(v).map_or(true, |n| n > 0))
    };
    if traced.is_empty() || traced.iter().any(holds_design) {
        return None;
    }
    let example = &traced[0].name;
    Some(format!(
        "--trace-filter {} matched no signal of any design: the waveforms hold the clock, reset \
         and probes only (names start with {}., e.g. {}.{}.*)",
        filters.join(" "),
        waves::ROOT,
        waves::ROOT,
        example
    ))
}

/// `regress --list`.
fn list_testbenches(project: &Project) -> String {
    let mut s = String::new();
    for tb in project.registry().iter() {
        let c = tb.configurations();
        s.push_str(&format!(
            "{}: {}
  --count: {} (default {})
  {} configurations; traced: {}
",
            tb.name(),
            tb.unit(),
            tb.count_unit(),
            tb.default_count(),
            c.len(),
            c.get(tb.traced()).map_or("none", String::as_str)
        ));
        for (i, l) in c.iter().enumerate() {
            s.push_str(&format!(
                "    {i:>3}  {l}
"
            ));
        }
    }
    if let Some(dir) = project.kept_vectors() {
        s.push_str(&format!(
            "{}: the bit-accuracy vectors kept in {} (fixed stimuli)\n",
            crate::regress::VECTORS,
            dir.display()
        ));
    }
    let twins: Vec<&str> = project.twins().map(|t| t.name()).collect();
    if !twins.is_empty() {
        let [v, i] = crate::regress::COSIM_CYCLES;
        s.push_str(&format!(
            "{}: {} twins ({}), each co-simulated in Verilator ({v} cycles) and Icarus ({i} \
             cycles) under every seed: --seeds S adds S x {} x simulators jobs\n",
            crate::regress::COSIM,
            twins.len(),
            twins.join(", "),
            twins.len()
        ));
    }
    s
}
