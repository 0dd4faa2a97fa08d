//! `bench/numeric-cost`: what numeric tracking costs on the FIG. 7 pipeline. The same cycles
//! run with tracking off and on, in alternating passes; each side's fastest pass is its
//! figure (the least disturbed by whatever else the machine runs). Under `--passes 1` and
//! `valgrind --tool=callgrind`, the instruction counts of the two sides are exact and
//! repeatable (the script does that when valgrind is installed).

use clap::{Parser, ValueEnum};
use hdl::kernel::Sim;
use std::hint::black_box;
use std::time::Instant;
use tb::maps::builtin;
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::BumpParams;

#[derive(Clone, Copy, Debug, PartialEq, ValueEnum)]
enum Side {
    Both,
    Off,
    On,
}

#[derive(Parser, Debug)]
#[command(
    about = "the FIG. 7 pipeline with numeric tracking off and on: ns a cycle, and the ratio"
)]
struct Args {
    /// Cycles a pass (1..=100000000).
    #[arg(long, default_value_t = 500_000, value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    cycles: u64,
    /// Passes a side (1..=100).
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u64).range(1..=100))]
    passes: u64,
    /// Which side to run.
    #[arg(long, value_enum, default_value_t = Side::Both)]
    side: Side,
}

/// One pass: `cycles` cycles of the pipeline (the criterion benchmark's stimulus), tracking as
/// `on` says; nanoseconds a cycle.
fn pass(cycles: u64, on: bool) -> f64 {
    let p = BumpParams::default();
    let map = builtin("noise", 16, 16, p.texel_fmt()).expect("the built-in map");
    let dut = NormalPipeline::new("normal_pipeline_fig7", p, map, None).expect("defaults");
    let mut sim = Sim::new(dut);
    hdl::fx::set_tracking(on);
    let t = Instant::now();
    black_box(tb::runs::normals::bench_cycles(&mut sim, cycles));
    let ns = t.elapsed().as_secs_f64() * 1e9 / cycles as f64;
    hdl::fx::set_tracking(false);
    ns
}

fn main() {
    let a = Args::parse();
    let (mut off, mut on) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..a.passes {
        if a.side != Side::On {
            off = off.min(pass(a.cycles, false));
        }
        if a.side != Side::Off {
            on = on.min(pass(a.cycles, true));
        }
    }
    let show = |x: f64| {
        if x.is_finite() {
            format!("{x:.1} ns")
        } else {
            "-".into()
        }
    };
    print!(
        "FIG. 7 pipeline, {} cycles, fastest of {} passes: tracking off {}, on {}",
        a.cycles,
        a.passes,
        show(off),
        show(on)
    );
    if off.is_finite() && on.is_finite() {
        print!(" a cycle (on / off = {:.2})", on / off);
    }
    println!();
}
