//! texrtl's verification framework: testbenches in the style of UVM but cycle-based and small,
//! and everything a project of units runs on them (co-simulation, vectors, regression, report,
//! the command line).
//!
//! The testbench side:
//!
//! * [`Driver`]s turn transactions into pin activity on a module's inputs; [`Monitor`]s turn
//!   pin activity on its outputs back into transactions.
//! * A [`Scoreboard`] compares the DUT's transactions with the golden model's, in order, and
//!   records every mismatch with the cycle it was seen in.
//! * [`coverage`]: coverpoints with bins, crosses, and a report of the bins never hit.
//! * [`ErrorStats`]: error against the golden model in output LSBs: max, mean, histogram,
//!   exact and +-1 LSB counts, SQNR.
//! * [`Stimulus`]: constrained-random values from proptest strategies, from a printed seed
//!   that replays the run (`TEXRTL_SEED=0x...`).
//! * [`run()`]: the cycle loop that ties them together, with ready/valid backpressure on both
//!   sides ([`Pacing`]), under a [`Watchdog`].
//! * [`Testbench`]: named configurations, a coverage model and a run of one configuration;
//!   [`run_testbench`] runs the configurations a [`Shard`] owns, each with its own seed, merges
//!   the [`TbResult`]s and decides pass/fail the same way for every testbench; a [`Registry`]
//!   lists a project's testbenches for regress, merge, the report and the progress bar.
//! * [`Handshake`]: the valid/ready rules checked at the pins (valid held, payload unchanged,
//!   until ready), for the handshakes inside a design that no driver or monitor owns.
//! * [`ProbeSink`]: golden values and mismatch flags shown beside the design in a waveform.
//! * [`mutate`]: malformed inputs (a valid file with byte-level mutations) for fuzzing.
//!
//! The project side, for any set of units:
//!
//! * [`project`]: a [`project::Unit`] says everything about a unit once (its testbenches, its
//!   Verilog twin, its vectors, its report pictures); a [`project::Project`] is a list of them.
//! * [`cosim`]: a unit's model against its Verilog in Verilator or Icarus, cycle by cycle,
//!   under the unit's clocking and compare rules ([`cosim::CosimUnit`], [`cosim::Twin`]).
//! * [`vectors`]: bit-accuracy vectors kept, checked to the row, blessed and exported.
//! * [`jobs`]: a regression as a list of jobs (configuration x seed) that shards deal out.
//! * [`regress`]: every testbench, the vectors and every twin, in shards, and the merge;
//!   [`report`] and [`plot`]: the table, `report.md` and its pictures; [`junit`]: the JUnit
//!   XML CI servers read.
//! * [`bench`](mod@bench): every twin against Verilator, untraced and traced.
//! * [`cli`]: the command line (`regress`, `merge`, `cosim`, `vectors`, `bench`, `list`) for
//!   any project: a program's `main` is one call.
//!
//! Feature `read` (off by default, to keep a user crate's first build short): a regression
//! reads back every waveform it writes with `wellen` and checks it (and `--fst` converts the
//! twins' VCDs); it enables `texrtl-waves/read`.

#![warn(missing_docs)]

pub mod bench;
pub mod cli;
pub mod cosim;
pub mod coverage;
pub mod jobs;
pub mod junit;
pub mod mutate;
pub mod numeric;
mod pins;
pub mod plot;
mod probe;
pub mod project;
mod protocol;
mod random;
pub mod regress;
pub mod report;
mod result;
mod run;
mod scoreboard;
mod stats;
mod stream;
mod testbench;
pub mod vectors;
mod workload;

pub use coverage::{Coverage, Coverpoint, Cross};
pub use jobs::{aggregate, run_jobs, run_testbench};
pub use pins::{PinDriver, PinMonitor};
pub use probe::ProbeSink;
pub use protocol::{Handshake, Violation};
pub use random::{seeded_runner, seeded_stimulus, Seed, Shard, Stimulus, SEED_ENV};
pub use result::TbResult;
pub use run::{
    run, run_beside, run_scored, run_scored_beside, Background, Driver, Event, Monitor, Pacing,
    RunSpec, RunStats, Scored, Timeout, Watchdog,
};
pub use scoreboard::{within, Mismatch, Outcome, Scoreboard};
pub use stats::ErrorStats;
pub use stream::{StreamAt, StreamDriver, StreamMonitor};
pub use testbench::{conclude, config_seed, About, Ctx, Registry, RunOptions, Testbench, WaveOut};
pub use workload::Workload;

#[cfg(test)]
mod tests;
