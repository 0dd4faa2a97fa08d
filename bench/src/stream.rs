//! `bench/trace-stream`: a long traced run of the FIG. 7 pipeline in bounded memory. The
//! stimulus is drawn cycle by cycle (a fixed LCG: nothing is stored), the trace is written
//! while simulating, and the run reports its speed, value changes, file size and the
//! process's peak resident memory (`VmHWM`), which stays flat however long the run.

use clap::{Parser, ValueEnum};
use hdl::kernel::{Sim, Trace};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::BumpParams;
use waves::{FstTracer, TraceConfig, VcdTracer};

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Format {
    Fst,
    Vcd,
}

#[derive(Parser, Debug)]
#[command(about = "a long traced run of the FIG. 7 pipeline: speed and peak memory")]
struct Args {
    /// Cycles to run (1..=1000000000).
    #[arg(long, default_value_t = 10_000_000)]
    cycles: u64,
    /// Waveform format.
    #[arg(long, value_enum, default_value_t = Format::Fst)]
    format: Format,
    /// Folder for the trace (default /dev/shm when there is one, else the system's temporary
    /// folder); the trace is deleted afterwards unless --keep.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Keep the trace.
    #[arg(long)]
    keep: bool,
}

/// The pipeline's inputs for `cycles` cycles, drawn as it runs: u and v over the whole
/// coordinate range (every border case), valid always, a fixed scale.
fn run<T: Trace>(sim: &mut Sim<NormalPipeline, T>, cycles: u64) {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mask = (1u64 << sim.dut.u.width()) - 1;
    for _ in 0..cycles {
        x = x
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        sim.dut.valid_in.set_bool(true);
        sim.dut.u.set_bits((x >> 8) & mask);
        sim.dut.v.set_bits((x >> 36) & mask);
        sim.dut.scale.set_raw(256);
        sim.step();
    }
}

/// The process's peak resident memory in kB (Linux), if it can be read.
fn peak_rss_kb() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() -> ExitCode {
    let a = Args::parse();
    if !(1..=1_000_000_000).contains(&a.cycles) {
        eprintln!("trace-stream: --cycles {}: 1..=1000000000", a.cycles);
        return ExitCode::from(2);
    }
    match stream(&a) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("trace-stream: {e}");
            ExitCode::from(2)
        }
    }
}

fn stream(a: &Args) -> Result<(), String> {
    let dir = a.out.clone().unwrap_or_else(|| {
        let shm = Path::new("/dev/shm");
        if shm.is_dir() {
            shm.to_path_buf()
        } else {
            std::env::temp_dir()
        }
    });
    if !dir.exists() {
        return Err(format!("--out {}: no such folder", dir.display()));
    }
    if !dir.is_dir() {
        return Err(format!("--out {}: not a folder", dir.display()));
    }
    let p = BumpParams::default();
    let map = tb::maps::builtin("noise", 16, 16, p.texel_fmt())?;
    let dut = NormalPipeline::new("normal_pipeline_fig7", p, map, None)?;
    let cfg = TraceConfig {
        companions: false,
        ..Default::default()
    };
    let ext = match a.format {
        Format::Fst => "fst",
        Format::Vcd => "vcd",
    };
    let path = dir.join(format!("trace-stream-{}.{ext}", std::process::id()));
    let io = |e: std::io::Error| format!("{}: {e}", path.display());
    let rss0 = peak_rss_kb();
    let t0 = std::time::Instant::now();
    let changes = match a.format {
        Format::Fst => {
            let mut sim =
                Sim::traced(dut, FstTracer::create(&path, cfg).map_err(io)?).map_err(io)?;
            run(&mut sim, a.cycles);
            let c = sim.trace_mut().map_or(0, |t| t.changes());
            sim.finish().map_err(io)?;
            c
        }
        Format::Vcd => {
            let t = VcdTracer::create(&path, "trace-stream", cfg).map_err(io)?;
            let mut sim = Sim::traced(dut, t).map_err(io)?;
            run(&mut sim, a.cycles);
            let c = sim.trace_mut().map_or(0, |t| t.changes());
            sim.finish().map_err(io)?;
            c
        }
    };
    let secs = t0.elapsed().as_secs_f64();
    let bytes = std::fs::metadata(&path).map_err(io)?.len();
    let kb = |v: Option<u64>| v.map_or("?".to_string(), |k| format!("{} MB", k / 1024));
    println!(
        "{} cycles of normal_pipeline_fig7 traced to {ext} ({}): {:.2} s, {:.0} k cycles/s, \
         {changes} value changes ({:.2} M/s), {:.1} MB written, peak RSS {} (before the run {})",
        a.cycles,
        path.display(),
        secs,
        a.cycles as f64 / secs / 1e3,
        changes as f64 / secs / 1e6,
        bytes as f64 / 1e6,
        kb(peak_rss_kb()),
        kb(rss0),
    );
    if !a.keep {
        let _ = std::fs::remove_file(&path);
        let _ = std::fs::remove_file(path.with_extension("gtkw"));
    }
    Ok(())
}
