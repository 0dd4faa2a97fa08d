//! One untraced run of a twin's model on its seeded stimulus, nothing else: what
//! `bench/model-instructions` counts under callgrind, to compare two builds of a unit (the
//! derive against a hand-written `Module`, say) exactly, whatever else the machine runs.
//! Usage: model-cycles UNIT CYCLES

use std::process::ExitCode;
use verif::cosim::BenchTrace;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [unit, cycles] = args.as_slice() else {
        eprintln!("model-cycles: usage: model-cycles UNIT CYCLES");
        return ExitCode::from(2);
    };
    let Ok(cycles) = cycles.parse::<usize>() else {
        eprintln!("model-cycles: CYCLES {cycles}: a number");
        return ExitCode::from(2);
    };
    let project = tb::project::project();
    let run = || -> Result<(), String> {
        let u = project.twin(unit, "UNIT")?;
        let stim = u.stimulus(verif::Seed(0xbe7c), cycles);
        let resets = verif::cosim::reset_cycles(u);
        u.model()?.bench(&stim, resets, BenchTrace::None)?;
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
