//! `bench/vs-verilator`: the texture units' twins against Verilator, the same measurement as
//! `texrtl bench` (the framework's `bench` command on the texture project).

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
    verif::cli::finish(
        "vs-verilator",
        verif::cli::bench(&tb::project::project(), &a.bench),
    )
}
