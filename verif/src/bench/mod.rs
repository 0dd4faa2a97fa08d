//! A project's twins against Verilator on the same designs: every unit with a Verilog twin runs
//! the same seeded stimulus for the same number of cycles in its Rust model (no schedule check,
//! as in a regression) and in its twin built by Verilator -O3, untraced, traced to VCD and
//! traced to FST (written while simulating); one table gives cycles per second and the model's
//! ratio (above 1: the model is faster). Measurements alternate between the two sides, pass by
//! pass untraced, in rounds, and a unit's row is its median round, with the range of the ratios
//! over all rounds: the machine's speed drifts over minutes, and a ratio of two runs minutes
//! apart drifts with it.

pub(crate) mod count;
mod harness;

use crate::cosim::{BenchTrace, CosimUnit};
use crate::project::Project;
use crate::Seed;
use harness::Mode;
use std::path::{Path, PathBuf};

/// What `bench` measures.
#[derive(Clone, Debug)]
pub struct BenchConfig {
    /// Cycles of the untraced runs (1..=100000000; in each round the two sides' passes take
    /// turns, at least three each and more until each side's add up to a second,
    /// and each side's fastest counts).
    pub cycles: usize,
    /// Cycles of the traced runs, VCD and FST (1..=10000000, at most `cycles`; one run a
    /// round).
    pub traced_cycles: usize,
    /// Rows of seeded stimulus (1..=100000000; at most `cycles` are drawn), which every run,
    /// on both sides, replays in a ring: cycle `c` drives row `c % rows`. Rows that fit the
    /// core's cache measure the two simulators; a row a cycle streamed from memory measures
    /// the memory too, and caps the faster side (see the user guide's speed chapter).
    pub stimulus_rows: usize,
    /// The twins to measure (empty: every one).
    pub units: Vec<String>,
    /// Folder for the harnesses, builds, stimulus and `table.md`.
    pub out: PathBuf,
    /// The stimulus seed.
    pub seed: Seed,
    /// Rounds (1..=20). A round measures each mode on both sides, the model and then the twin;
    /// a unit's figures are those of the round with the median ratio.
    pub rounds: usize,
    /// Count instructions a cycle over this many cycles (1..=10000000) instead of timing:
    /// both sides untraced under callgrind (needs valgrind), after the first 1000 cycles.
    pub instructions: Option<usize>,
}

/// Checks the options and the tool; the twins to measure.
pub fn check<'p>(project: &'p Project, a: &BenchConfig) -> Result<Vec<&'p dyn CosimUnit>, String> {
    if !(1..=100_000_000).contains(&a.cycles) {
        return Err(format!("--cycles {}: 1..=100000000", a.cycles));
    }
    if !(1..=100_000_000).contains(&a.stimulus_rows) {
        return Err(format!(
            "--stimulus-rows {}: 1..=100000000",
            a.stimulus_rows
        ));
    }
    if !(1..=20).contains(&a.rounds) {
        return Err(format!("--rounds {}: 1..=20", a.rounds));
    }
    if !(1..=10_000_000).contains(&a.traced_cycles) || a.traced_cycles > a.cycles {
        return Err(format!(
            "--traced-cycles {}: 1..=10000000 and at most --cycles",
            a.traced_cycles
        ));
    }
    if let Some(n) = a.instructions {
        if !(1..=10_000_000).contains(&n) {
            return Err(format!("--instructions {n}: 1..=10000000"));
        }
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
    if a.instructions.is_some() {
        count::check_valgrind()?;
    }
    Ok(units)
}

/// Measures every unit, printing a line each on stderr as it goes; returns the table (also
/// written to `table.md` in the output folder).
pub fn measure_all(a: &BenchConfig, units: &[&dyn CosimUnit]) -> Result<String, String> {
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    if let Some(n) = a.instructions {
        return count_all(a, n, units);
    }
    // Every twin's harnesses first, so that no build runs between two units' rounds (and a
    // build that fails, or a twin that disagrees with its model, does so before the timing
    // starts).
    let mut ready = Vec::with_capacity(units.len());
    for u in units {
        ready.push(make_ready(a, *u).map_err(|e| format!("{}: {e}", u.name()))?);
    }
    let mut rows = Vec::new();
    for (u, r) in units.iter().zip(ready) {
        let r = measure(a, *u, r)?;
        // Not a table row (those are on stdout): a copy of both streams keeps one table.
        eprintln!("{}: measured |{}", r.unit, cells(&r));
        rows.push(r);
    }
    let t = table(a, &rows);
    let path = a.out.join("table.md");
    std::fs::write(&path, &t).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(t)
}

/// `measure_all` counting instructions: the table also in `instructions.md`.
fn count_all(a: &BenchConfig, n: usize, units: &[&dyn CosimUnit]) -> Result<String, String> {
    let mut rows = Vec::new();
    for u in units {
        let dir = unit_dir(a, *u)?;
        let r = count::count(*u, a.seed, n, &dir).map_err(|e| format!("{}: {e}", u.name()))?;
        eprintln!("{}: counted |{}", r.unit, count::cells(&r));
        rows.push(r);
    }
    let t = count::table(a.seed, n, &rows);
    let path = a.out.join("instructions.md");
    std::fs::write(&path, &t).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(t)
}

/// A unit's folder in the output folder, with its memory images.
fn unit_dir(a: &BenchConfig, unit: &dyn CosimUnit) -> Result<PathBuf, String> {
    let dir = std::path::absolute(a.out.join(unit.name())).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (file, text) in unit.memories() {
        std::fs::write(dir.join(&file), text).map_err(|e| format!("{file}: {e}"))?;
    }
    Ok(dir)
}

/// Cycles of the check of a twin's harness against its model ([`check_twin`]).
const CHECK_CYCLES: usize = 16_384;

/// A unit ready to time: its folder ([`unit_dir`]) and its twin's harnesses (one for each of
/// [`Mode::ALL`]), checked against its model.
struct Ready {
    dir: PathBuf,
    exes: Vec<PathBuf>,
}

/// Builds or takes `unit`'s harnesses and checks the twin's harness against the model on the
/// stimulus. The stimulus is drawn again for the unit's rounds, so that no more than one
/// unit's is held at a time (a million rows of their own take up to a hundred megabytes).
fn make_ready(a: &BenchConfig, unit: &dyn CosimUnit) -> Result<Ready, String> {
    let dir = unit_dir(a, unit)?;
    let exes = harnesses(unit, &Mode::ALL, &dir)?;
    let mut prepared = prepare(unit, a.seed, a.stimulus_rows.min(a.cycles), &dir)?;
    check_twin(
        unit,
        &mut prepared,
        &exes[0],
        a.cycles.min(CHECK_CYCLES),
        &dir,
    )?;
    Ok(Ready { dir, exes })
}

/// The twin's harness computes what the model does on the bench's stimulus: the
/// co-simulation's comparison as a checksum ([`crate::cosim::compared_checksum`]) over
/// `cycles` cycles of the rows, on both sides. A harness that drove the twin otherwise than
/// the model is driven, or a twin that computes something else, would time another
/// computation. The check runs `p`'s model, which is left as the check leaves it (a benchmark
/// run starts from the design as built).
fn check_twin(
    unit: &dyn CosimUnit,
    p: &mut Prepared,
    exe: &Path,
    cycles: usize,
    dir: &Path,
) -> Result<(), String> {
    let ours = crate::cosim::compared_checksum(unit, p.model.as_mut(), &p.stim, cycles)?;
    let theirs = harness::check(exe, &p.bin, cycles, p.stim.len(), dir)?;
    if ours != theirs {
        return Err(format!(
            "the twin and the model disagree on the bench's stimulus (the compared outputs of {cycles} cycles sum to {theirs} in the twin's harness, {ours} in the model); `cosim --unit {}` shows the first difference",
            unit.name()
        ));
    }
    Ok(())
}

/// What both sides of a unit's measurement run besides the twin's harnesses: its model and
/// `rows` rows of its seeded stimulus, also in the harnesses' file `bin`.
struct Prepared {
    model: Box<dyn crate::cosim::CosimModel>,
    stim: Vec<Vec<u64>>,
    bin: PathBuf,
}

/// The twin's harness of `unit` for each of `modes`, built in `dir` or kept from an earlier
/// build ([`harness::build`]); says on stderr how many of each.
fn harnesses(unit: &dyn CosimUnit, modes: &[Mode], dir: &Path) -> Result<Vec<PathBuf>, String> {
    let model = unit.model()?;
    let (ins, outs) = model.ports();
    let mut exes = Vec::with_capacity(modes.len());
    let mut kept = 0;
    for &mode in modes {
        let cpp = harness::main_cpp(unit, &ins, &outs, mode)?;
        let h = harness::build(unit, &cpp, mode, dir)?;
        kept += usize::from(h.kept);
        exes.push(h.exe);
    }
    eprintln!(
        "{}: harnesses built {}, kept {kept}",
        unit.name(),
        exes.len() - kept
    );
    Ok(exes)
}

fn prepare(unit: &dyn CosimUnit, seed: Seed, rows: usize, dir: &Path) -> Result<Prepared, String> {
    let model = unit.model()?;
    let stim = unit.stimulus(seed, rows);
    let bin = dir.join("stim.bin");
    write_bin(&bin, &stim)?;
    Ok(Prepared { model, stim, bin })
}

/// One unit's figures in each mode: the round with the median ratio (both sides' cycles per
/// second in it) and the lowest and highest ratio of all rounds.
struct Row {
    unit: String,
    ours: [f64; 3],
    theirs: [f64; 3],
    range: [(f64, f64); 3],
}

impl Row {
    /// From each round's seconds, `[(model, Verilator); 3]` by mode, over `counts` cycles.
    fn from_rounds(unit: &str, counts: [usize; 3], rounds: &[[(f64, f64); 3]]) -> Row {
        let per_s = |secs: f64, n: usize| n as f64 / secs.max(1e-9);
        let mut row = Row {
            unit: unit.into(),
            ours: [0.0; 3],
            theirs: [0.0; 3],
            range: [(0.0, 0.0); 3],
        };
        for k in 0..3 {
            let mut r: Vec<(f64, f64, f64)> = rounds
                .iter()
                .map(|x| {
                    let (o, t) = (per_s(x[k].0, counts[k]), per_s(x[k].1, counts[k]));
                    (o / t, o, t)
                })
                .collect();
            r.sort_by(|a, b| a.0.total_cmp(&b.0));
            // The lower middle of an even count: the claim errs towards Verilator.
            let (_, o, t) = r[(r.len() - 1) / 2];
            (row.ours[k], row.theirs[k]) = (o, t);
            row.range[k] = (r[0].0, r[r.len() - 1].0);
        }
        row
    }
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

/// The model's seconds for one pass of `cycles` cycles over `stim`, untraced or traced (its
/// trace for the caller to delete).
fn model_pass(
    model: &dyn crate::cosim::CosimModel,
    stim: &[Vec<u64>],
    cycles: usize,
    resets: usize,
    trace: BenchTrace,
) -> Result<f64, String> {
    let timed = crate::testbench::unpanicked_sim(|| model.bench(stim, cycles, resets, trace));
    let timed = timed.map_err(|(cycle, said)| match cycle {
        Some(c) => format!("{}{c}: {said}", crate::cosim::MODEL_PANICKED),
        None => format!("the model panicked: {said}"),
    })?;
    Ok(timed?.as_secs_f64())
}

/// One unit's rounds, made ready by [`make_ready`].
fn measure(a: &BenchConfig, unit: &dyn CosimUnit, ready: Ready) -> Result<Row, String> {
    let name = unit.name();
    let resets = crate::cosim::reset_cycles(unit);
    let Ready { dir, exes } = ready;
    let dir = dir.as_path();
    let rows = a.stimulus_rows.min(a.cycles);
    let Prepared { model, stim, bin } = prepare(unit, a.seed, rows, dir)?;
    let tdir = trace_dir(name, dir)?;
    let counts = [a.cycles, a.traced_cycles, a.traced_cycles];
    let run = Run {
        model: model.as_ref(),
        stim: &stim,
        resets,
        exes: &exes,
        bin: &bin,
        dir,
        tdir: &tdir,
        counts,
    };
    let rounds: Result<Vec<_>, String> = (0..a.rounds).map(|_| run.round()).collect();
    // The traces' folder goes whether the rounds ran or one failed.
    let gtkw = tdir.join("model.gtkw");
    let _ = std::fs::remove_file(gtkw);
    if tdir != dir {
        let _ = std::fs::remove_dir_all(&tdir);
    }
    Ok(Row::from_rounds(
        name,
        counts,
        &rounds.map_err(|e| format!("{name}: {e}"))?,
    ))
}

/// What one unit's rounds run: its model and stimulus (its rows, replayed in a ring), the
/// twin's three builds, and where the stimulus, the memory images and the traces are.
struct Run<'a> {
    model: &'a dyn crate::cosim::CosimModel,
    stim: &'a [Vec<u64>],
    resets: usize,
    exes: &'a [PathBuf],
    bin: &'a Path,
    dir: &'a Path,
    tdir: &'a Path,
    counts: [usize; 3],
}

impl Run<'_> {
    /// One round: mode by mode, the model and then the twin, so that a slow stretch of the
    /// machine falls on both sides of one round's ratio, or on one round of several; untraced,
    /// pass by pass ([`Run::untraced`]). Each trace is deleted as soon as it is written: a run
    /// that overwrote the last one's file (350 MB for replicate 152) ran at a third of the
    /// speed of a run into a new file, the kernel freeing the old pages while the new ones
    /// were written.
    fn round(&self) -> Result<[(f64, f64); 3], String> {
        let mut secs = [(0.0, 0.0); 3];
        secs[0] = self.untraced()?;
        for (k, mode) in Mode::ALL.into_iter().enumerate().skip(1) {
            let file = |side: &str| self.tdir.join(format!("{side}.{}", mode.name()));
            let (ours, theirs) = (file("model"), file("rtl"));
            let trace = match mode {
                Mode::Fst => BenchTrace::Fst(&ours),
                _ => BenchTrace::Vcd(&ours),
            };
            let n = self.counts[k];
            let model = model_pass(self.model, self.stim, n, self.resets, trace);
            let _ = std::fs::remove_file(&ours);
            secs[k].0 = model?;
            let rows = self.stim.len();
            let twin = harness::time(&self.exes[k], self.bin, n, rows, Some(&theirs), self.dir);
            let _ = std::fs::remove_file(&theirs);
            secs[k].1 = twin?;
        }
        Ok(secs)
    }

    /// The untraced seconds of a round, `(model, twin)`: passes of the two sides in turn, the
    /// model's and then the twin's, at least [`harness::PASSES`] and more until each side's
    /// add up to [`harness::MIN_SECONDS`]; each side's fastest. Passes a fraction of a second
    /// apart see the same machine, where one side's passes and then the other's (a second or
    /// more each) saw different ones on a busy day.
    fn untraced(&self) -> Result<(f64, f64), String> {
        let n = self.counts[0];
        let (mut best, mut total) = ((f64::MAX, f64::MAX), (0.0, 0.0));
        let mut passes = 0;
        while !harness::enough(passes, f64::min(total.0, total.1)) {
            let m = model_pass(self.model, self.stim, n, self.resets, BenchTrace::None)?;
            let t = harness::time(&self.exes[0], self.bin, n, self.stim.len(), None, self.dir)?;
            best = (best.0.min(m), best.1.min(t));
            total = (total.0 + m, total.1 + t);
            passes += 1;
        }
        Ok(best)
    }
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

/// A unit's row of the table.
fn line(r: &Row) -> String {
    format!("| {} |{}", r.unit, cells(r))
}

/// The cells of a unit's row after its name: each mode's two rates and their ratio.
fn cells(r: &Row) -> String {
    let mut s = String::new();
    for k in 0..3 {
        let (lo, hi) = r.range[k];
        let spread = if lo < hi {
            format!(" ({lo:.2}-{hi:.2})")
        } else {
            String::new()
        };
        s += &format!(
            " {} | {} | {:.2}{spread} |",
            rate(r.ours[k]),
            rate(r.theirs[k]),
            r.ours[k] / r.theirs[k]
        );
    }
    s
}

fn table(a: &BenchConfig, rows: &[Row]) -> String {
    let rounds = if a.rounds == 1 {
        "one round".to_string()
    } else {
        format!(
            "{} rounds, each side in turn in every mode; the round with the median ratio, the lowest and highest ratio in brackets",
            a.rounds
        )
    };
    let mut s = format!(
        "Cycles/s: untraced over {} cycles, traced over {}, both replaying {} rows of stimulus (seed {}); {rounds}; ratio = model / Verilator.\n\n",
        a.cycles, a.traced_cycles, a.stimulus_rows.min(a.cycles), a.seed
    );
    s += "| unit | model | Verilator -O3 | ratio | model VCD | Verilator --trace | ratio | model FST | Verilator --trace-fst | ratio |\n";
    s += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for r in rows {
        s += &line(r);
        s += "\n";
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model that panics while it is timed is named with the cycle it panicked in, traced
    /// or not: the benchmark stops with that line, not with the panic.
    #[test]
    fn a_model_that_panics_while_timed_says_in_which_cycle() {
        use crate::cosim::tests::Echo;
        use hdl::fx::Format;
        use hdl::kernel::Signal;
        let make = || Echo {
            x: Signal::new("x", Format::uint(4)),
            y: Signal::new("y", Format::uint(3)),
        };
        let model = crate::cosim::Twin::new(make, |d, v| d.x.set_bits(v[0]))
            .model()
            .unwrap();
        let stim: Vec<Vec<u64>> = [1, 2, 7, 8, 3].iter().map(|&x| vec![x]).collect();
        let dir = std::env::temp_dir().join(format!("texrtl-bench-panics-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let vcd = dir.join("model.vcd");
        for trace in [BenchTrace::None, BenchTrace::Vcd(&vcd)] {
            let e = model_pass(model.as_ref(), &stim, 5, 1, trace).unwrap_err();
            let want =
                "the model panicked in cycle 3: signal 'y' (u3, 3 bits): bits 0x8 does not fit";
            assert_eq!(e, want);
        }
        assert!(model_pass(model.as_ref(), &stim[..3], 3, 1, BenchTrace::None).is_ok());
        // Replayed in a ring, the good rows run as long as asked.
        assert!(model_pass(model.as_ref(), &stim[..3], 100, 1, BenchTrace::None).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Adds one and its inputs into a 6-bit register each cycle: the cycle whose sum does not
    /// fit says how many rows, in which order, the run drove.
    #[derive(Clone, hdl::kernel::Module)]
    #[module(kind = "count")]
    struct Count {
        #[input]
        xs: Vec<hdl::kernel::Signal>,
        #[reg]
        acc: hdl::kernel::Reg,
    }

    impl Count {
        fn eval(&mut self) {
            let sum = self.xs.iter().map(|x| x.bits()).sum::<u64>();
            self.acc.set_next_bits(self.acc.q().bits() + 1 + sum);
        }
    }

    /// The rows replayed in a ring, in order: rows 2, 0, 0 add 3, 1, 1, so the sum reaches 64
    /// in cycle 37 (in order backwards, in cycle 38; three rows alone stop at cycle 2); with no
    /// inputs, every row the empty one, in cycle 63.
    #[test]
    fn the_model_replays_its_rows_in_a_ring() {
        use hdl::fx::Format;
        use hdl::kernel::{Reg, Signal};
        let cases = [
            (1, vec![vec![2], vec![0], vec![0]], 37),
            (0, vec![vec![]; 5], 63),
        ];
        for (inputs, rows, panics) in cases {
            let dut = Count {
                xs: (0..inputs)
                    .map(|_| Signal::new("x", Format::uint(2)))
                    .collect(),
                acc: Reg::new("acc", Format::uint(6)),
            };
            let drive = |d: &mut Count, v: &[u64]| {
                for (x, b) in d.xs.iter_mut().zip(v) {
                    x.set_bits(*b);
                }
            };
            let model = crate::cosim::ModelSim::new(dut, drive);
            let at = |cycles| model_pass(&model, &rows, cycles, 0, BenchTrace::None);
            assert!(at(panics).is_ok());
            let e = at(panics + 1).unwrap_err();
            let want = format!("{}{panics}:", crate::cosim::MODEL_PANICKED);
            assert!(e.starts_with(&want), "{e}");
        }
    }

    /// A row is the round with the median ratio, both sides' rates from that round; the
    /// range is the lowest and highest ratio; an even count takes the lower middle.
    #[test]
    fn a_row_is_its_median_round() {
        // Seconds over 100 cycles; ratios by round in the untraced mode: 2, 0.5, 1.
        let round = |o: f64, t: f64| [(o, t), (1.0, 1.0), (1.0, 2.0)];
        let rounds = [round(1.0, 2.0), round(4.0, 2.0), round(3.0, 3.0)];
        let r = Row::from_rounds("u", [100; 3], &rounds);
        assert_eq!((r.ours[0], r.theirs[0]), (100.0 / 3.0, 100.0 / 3.0));
        assert_eq!(r.range[0], (0.5, 2.0));
        assert_eq!(
            (r.ours[2], r.theirs[2], r.range[2]),
            (100.0, 50.0, (2.0, 2.0))
        );
        let r = Row::from_rounds("u", [100; 3], &rounds[..2]);
        assert_eq!((r.ours[0], r.theirs[0]), (25.0, 50.0));
        assert!(line(&r).contains("| 0.50 (0.50-2.00) |"), "{}", line(&r));
        assert!(line(&r).contains("| 2.00 |"), "{}", line(&r));
    }
}
