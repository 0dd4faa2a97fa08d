//! One run of a twin's model on its seeded stimulus, nothing else: what
//! `bench/model-instructions` counts under callgrind, to compare two builds of a unit (the
//! derive against a hand-written `Module`, say) exactly, whatever else the machine runs.
//! Untraced, or traced to the VCD or FST file named third (to count a tracer's cost). Prints
//! the cycle loop's time (one run: a rough figure; the benchmark's are best of several).
//! Like `bench`, it replays at most [`RING`] rows of stimulus in a ring, so that a sampling
//! profile of a long run (`perf record`) shows the cycles, not the drawing of the stimulus.
//! Usage: model-cycles UNIT CYCLES [FILE.vcd|FILE.fst]

#[path = "styles.rs"]
mod styles;

use std::process::ExitCode;
use verif::cosim::BenchTrace;

/// The rows drawn and replayed in a ring: `bench`'s default `--stimulus-rows`.
const RING: usize = 16_384;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (unit, cycles, file) = match args.as_slice() {
        [u, c] => (u, c, None),
        [u, c, f] => (u, c, Some(std::path::Path::new(f))),
        _ => {
            eprintln!("model-cycles: usage: model-cycles UNIT CYCLES [FILE.vcd|FILE.fst]");
            return ExitCode::from(2);
        }
    };
    let trace = match file {
        None => BenchTrace::None,
        Some(f) if f.extension().is_some_and(|e| e == "vcd") => BenchTrace::Vcd(f),
        Some(f) if f.extension().is_some_and(|e| e == "fst") => BenchTrace::Fst(f),
        Some(f) => {
            eprintln!("model-cycles: {}: a .vcd or .fst file", f.display());
            return ExitCode::from(2);
        }
    };
    let Ok(cycles) = cycles.parse::<usize>() else {
        eprintln!("model-cycles: CYCLES {cycles}: a number");
        return ExitCode::from(2);
    };
    // The units of `bench/vs-verilator`: the texture project's and the four style units.
    let project = styles::units()
        .into_iter()
        .fold(tb::project::project(), |p, u| p.unit(u));
    let run = || -> Result<(), String> {
        let u = project.twin(unit, "UNIT")?;
        let stim = u.stimulus(verif::Seed(0xbe7c), cycles.min(RING));
        let resets = verif::cosim::reset_cycles(u);
        let t = u.model()?.bench(&stim, cycles, resets, trace)?;
        let secs = t.as_secs_f64();
        let rate = cycles as f64 / secs.max(1e-9);
        eprintln!("model-cycles: {cycles} cycles in {secs:.3} s ({rate:.0} cycles/s)");
        Ok(())
    };
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("model-cycles: {e}");
            ExitCode::from(2)
        }
    }
}
