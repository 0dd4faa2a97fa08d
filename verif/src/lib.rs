//! texrtl's testbench framework, in the style of UVM but cycle-based and small:
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
//! * [`run`]: the cycle loop that ties them together, under a [`Watchdog`].

pub mod coverage;
mod random;
mod run;
mod scoreboard;
mod stats;

pub use coverage::{Coverage, Coverpoint, Cross};
pub use random::{seeded_runner, seeded_stimulus, Seed, Shard, Stimulus, SEED_ENV};
pub use run::{run, Driver, Event, Monitor, Pacing, RunStats, Timeout, Watchdog};
pub use scoreboard::{Mismatch, Outcome, Scoreboard};
pub use stats::ErrorStats;

#[cfg(test)]
mod tests;
