//! The `texrtl` command line. With no arguments it runs `texrtl regress`.

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use tb::regress::{regress, render, RegressConfig};
use verif::Seed;
use waves::TraceConfig;

#[derive(Parser)]
#[command(
    name = "texrtl",
    version,
    about = "Bit-exact, cycle-accurate models of texture-mapping hardware: testbenches, waveforms, golden models",
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    cmd: Option<Cmd>,
    #[command(flatten)]
    regress: RegressArgs,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run every testbench on built-in stimulus (the default command).
    Regress(RegressArgs),
}

#[derive(Args, Clone)]
struct RegressArgs {
    /// Directory for VCDs, .gtkw files and summary.json.
    #[arg(long, default_value = "target/texrtl")]
    out: PathBuf,
    /// Stimulus seed (hex 0x... or decimal); the run prints it, and the same seed replays it.
    #[arg(long, value_parser = Seed::parse, default_value = "0x7e47")]
    seed: Seed,
    /// Write no waveforms.
    #[arg(long)]
    no_vcd: bool,
    /// Trace scopes down to this depth (0 = clock, reset and golden probes only; 1 = each
    /// testbench's top unit; ...).
    #[arg(long)]
    trace_depth: Option<usize>,
    /// Trace only signals whose hierarchical name (e.g. tb.ba.u0) matches this glob; repeatable.
    #[arg(long = "trace-filter")]
    trace_filter: Vec<String>,
    /// Trace only cycles START..END.
    #[arg(long, value_parser = parse_window)]
    trace_window: Option<(u64, u64)>,
    /// Clock period in picoseconds shown in the waveforms (even, >= 2).
    #[arg(long, default_value_t = 10_000)]
    period_ps: u64,
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

/// Bad input: one line, exit status 2.
fn fail(msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("texrtl: {msg}");
    ExitCode::from(2)
}

fn run_regress(a: RegressArgs) -> ExitCode {
    if a.out.exists() && !a.out.is_dir() {
        return fail(format!(
            "--out {}: exists and is not a directory",
            a.out.display()
        ));
    }
    let cfg = RegressConfig {
        out: a.out,
        seed: a.seed,
        vcd: !a.no_vcd,
        trace: TraceConfig {
            period_ps: a.period_ps,
            max_depth: a.trace_depth,
            filters: a.trace_filter,
            window: a.trace_window,
            companions: true,
        },
    };
    if let Err(e) = cfg.trace.validate() {
        return fail(format!("--period-ps/--trace-window: {e}"));
    }
    eprintln!(
        "texrtl regress: seed {} (replay with --seed {})",
        cfg.seed, cfg.seed
    );
    match regress(&cfg) {
        Ok(results) => {
            print!("{}", render(&results, &cfg));
            if results.iter().all(|r| r.passed) {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Err(e) => fail(e),
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("bad arguments");
            let first = first.strip_prefix("error: ").unwrap_or(first);
            return fail(format!("{first} (see texrtl --help)"));
        }
    };
    match cli.cmd {
        Some(Cmd::Regress(a)) => run_regress(a),
        None => run_regress(cli.regress),
    }
}
