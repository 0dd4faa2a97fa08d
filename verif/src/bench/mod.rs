//! A project's twins against Verilator on the same designs: every unit with a Verilog twin runs
//! the same seeded stimulus for the same number of cycles in its Rust model (no schedule check,
//! as in a regression) and in its twin built by Verilator -O3, untraced, traced to VCD and
//! traced to FST (written while simulating); one table gives cycles per second and the model's
//! ratio (above 1: the model is faster).

mod harness;

use crate::cosim::{BenchTrace, CosimUnit};
use crate::project::Project;
use crate::Seed;
use harness::Mode;
use std::path::{Path, PathBuf};

/// What `bench` measures.
#[derive(Clone, Debug)]
pub struct BenchConfig {
    /// Cycles of the untraced runs (1..=100000000; the fastest of at least three passes
    /// counts, and of more while they add up to less than a quarter of a second).
    pub cycles: usize,
    /// Cycles of the traced runs, VCD and FST (1..=10000000, at most `cycles`).
    pub traced_cycles: usize,
    /// The twins to measure (empty: every one).
    pub units: Vec<String>,
    /// Folder for the harnesses, builds, stimulus and `table.md`.
    pub out: PathBuf,
    /// The stimulus seed.
    pub seed: Seed,
}

/// Checks the options and the tool; the twins to measure.
pub fn check<'p>(project: &'p Project, a: &BenchConfig) -> Result<Vec<&'p dyn CosimUnit>, String> {
    if !(1..=100_000_000).contains(&a.cycles) {
        return Err(format!("--cycles {}: 1..=100000000", a.cycles));
    }
    if !(1..=10_000_000).contains(&a.traced_cycles) || a.traced_cycles > a.cycles {
        return Err(format!(
            "--traced-cycles {}: 1..=10000000 and at most --cycles",
            a.traced_cycles
        ));
    }
    let units: Vec<&dyn CosimUnit> = if a.units.is_empty() {
        project.twins().collect()
    } else {
        a.units
            .iter()
            .map(|u| project.twin(u, "--unit"))
            .collect::<Result<_, _>>()?
    };
    crate::cosim::Simulator::Verilator.check_installed()?;
    Ok(units)
}

/// Measures every unit, printing a line each on stderr as it goes; returns the table (also
/// written to `table.md` in the output folder).
pub fn measure_all(a: &BenchConfig, units: &[&dyn CosimUnit]) -> Result<String, String> {
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    let mut rows = Vec::new();
    for u in units {
        let r = measure(a, *u)?;
        eprintln!("{}", line(&r));
        rows.push(r);
    }
    let t = table(a, &rows);
    let path = a.out.join("table.md");
    std::fs::write(&path, &t).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(t)
}

/// One unit's figures: cycles per second of texrtl and Verilator in each mode.
struct Row {
    unit: String,
    ours: [f64; 3],
    theirs: [f64; 3],
}

/// Where a unit's traces go: a folder in memory (`/dev/shm`) when the machine has one, so that
/// the disk's write-back of one side's trace does not slow the other's; else `dir`.
fn trace_dir(unit: &str, dir: &Path) -> Result<PathBuf, String> {
    let shm = Path::new("/dev/shm");
    if !shm.is_dir() {
        return Ok(dir.to_path_buf());
    }
    let t = shm.join(format!("texrtl-vs-verilator-{}-{unit}", std::process::id()));
    std::fs::create_dir_all(&t).map_err(|e| format!("{}: {e}", t.display()))?;
    Ok(t)
}

/// The stimulus as the harness reads it: little-endian 64-bit words, cycle by cycle.
fn write_bin(path: &Path, stim: &[Vec<u64>]) -> Result<(), String> {
    let bytes: Vec<u8> = stim
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}

fn measure(a: &BenchConfig, unit: &dyn CosimUnit) -> Result<Row, String> {
    let name = unit.name();
    let resets = crate::cosim::reset_cycles(unit);
    let dir = std::path::absolute(a.out.join(name)).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (file, text) in unit.memories() {
        std::fs::write(dir.join(&file), text).map_err(|e| format!("{file}: {e}"))?;
    }
    let model = unit.model()?;
    let (ins, outs) = model.ports();
    let stim = unit.stimulus(a.seed, a.cycles);
    let bin = dir.join("stim.bin");
    write_bin(&bin, &stim)?;
    let traced = &stim[..a.traced_cycles];
    let tdir = trace_dir(name, &dir)?;
    let (vcd, fst) = (tdir.join("model.vcd"), tdir.join("model.fst"));
    // The fastest of `PASSES` runs of each (traces overwritten); untraced, of as many more
    // as the harness makes (`harness::enough`).
    let best = |trace: BenchTrace, stim: &[Vec<u64>]| -> Result<f64, String> {
        let (mut t, mut total, mut passes) = (f64::MAX, 0.0, 0);
        let untraced = matches!(trace, BenchTrace::None);
        while passes < harness::PASSES || (untraced && !harness::enough(passes, total)) {
            let s = model.bench(stim, resets, trace)?.as_secs_f64();
            (t, total, passes) = (t.min(s), total + s, passes + 1);
        }
        Ok(t)
    };
    let ours = [
        best(BenchTrace::None, &stim)?,
        best(BenchTrace::Vcd(&vcd), traced)?,
        best(BenchTrace::Fst(&fst), traced)?,
    ];
    let mut theirs = [0.0; 3];
    for (k, mode) in Mode::ALL.into_iter().enumerate() {
        let exe = harness::build(
            unit,
            &harness::main_cpp(unit, &ins, &outs, mode),
            mode,
            &dir,
        )?;
        let trace = tdir.join(format!("rtl.{}", mode.name()));
        let (n, t) = match mode {
            Mode::Untraced => (a.cycles, None),
            _ => (a.traced_cycles, Some(trace.as_path())),
        };
        // Untraced, the harness takes the best of its passes itself; traced, run it again.
        let runs = if mode == Mode::Untraced {
            1
        } else {
            harness::PASSES
        };
        theirs[k] = f64::MAX;
        for _ in 0..runs {
            theirs[k] = theirs[k].min(harness::time(&exe, &bin, n, t, &dir)?);
        }
        let _ = std::fs::remove_file(&trace);
    }
    for f in [&vcd, &fst, &vcd.with_extension("gtkw")] {
        let _ = std::fs::remove_file(f);
    }
    if tdir != dir {
        let _ = std::fs::remove_dir_all(&tdir);
    }
    let per_s = |secs: f64, n: usize| n as f64 / secs.max(1e-9);
    let counts = [a.cycles, a.traced_cycles, a.traced_cycles];
    Ok(Row {
        unit: name.into(),
        ours: [0, 1, 2].map(|k| per_s(ours[k], counts[k])),
        theirs: [0, 1, 2].map(|k| per_s(theirs[k], counts[k])),
    })
}

/// Cycles per second, short: `4.81 M`, `390 k`.
fn rate(x: f64) -> String {
    if x >= 1e6 {
        format!("{:.2} M", x / 1e6)
    } else if x >= 1e3 {
        format!("{:.0} k", x / 1e3)
    } else {
        format!("{x:.0}")
    }
}

fn line(r: &Row) -> String {
    let mut s = format!("| {} |", r.unit);
    for k in 0..3 {
        s += &format!(
            " {} | {} | {:.2} |",
            rate(r.ours[k]),
            rate(r.theirs[k]),
            r.ours[k] / r.theirs[k]
        );
    }
    s
}

fn table(a: &BenchConfig, rows: &[Row]) -> String {
    let mut s = format!(
        "Cycles/s: untraced over {} cycles, traced over {} (seed {}); ratio = model / Verilator.\n\n",
        a.cycles, a.traced_cycles, a.seed
    );
    s += "| unit | model | Verilator -O3 | ratio | model VCD | Verilator --trace | ratio | model FST | Verilator --trace-fst | ratio |\n";
    s += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for r in rows {
        s += &line(r);
        s += "\n";
    }
    s
}
