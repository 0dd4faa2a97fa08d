//! `bench/vs-verilator`: the texture units' twins against Verilator, the same measurement as
//! `texrtl bench` (the framework's `bench` command on the texture project), plus the worked
//! example's unit in the documented style and the same logic on raw integers.

mod styles;

use clap::Parser;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "vs-verilator",
    about = "texrtl against Verilator on every unit with a Verilog twin"
)]
struct Args {
    #[command(flatten)]
    bench: verif::cli::BenchArgs,
}

fn main() -> ExitCode {
    let a = Args::parse();
    let project = styles::units()
        .into_iter()
        .fold(tb::project::project(), |p, u| p.unit(u));
    verif::cli::finish("vs-verilator", verif::cli::bench(&project, &a.bench))
}
