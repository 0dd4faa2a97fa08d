//! Drivers, monitors and the cycle loop that runs a testbench under a watchdog.

use crate::random::{Seed, Stimulus};
use hdl::kernel::{Module, Sim, Trace};
use serde::Serialize;
use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// Turns transactions into pin activity on the DUT's inputs, one cycle at a time.
pub trait Driver<M> {
    type Txn;
    /// Drives one cycle: `Some(t)` presents transaction `t`, `None` drives the idle pattern
    /// (valid low).
    fn drive(&mut self, dut: &mut M, txn: Option<&Self::Txn>);
}

/// Turns pin activity on the DUT's outputs back into transactions.
pub trait Monitor<M> {
    type Txn;
    /// Looks at the settled outputs of the current cycle.
    fn sample(&mut self, dut: &M) -> Option<Self::Txn>;
}

/// What the cycle loop reports to the testbench.
pub enum Event<'a, I, O> {
    /// Transaction `txn` was driven in `cycle` (compute its golden result now).
    Sent { cycle: u64, txn: &'a I },
    /// The monitor saw `txn` in `cycle` (score it now).
    Received { cycle: u64, txn: O },
}

/// How often the driver presents a transaction: every cycle (full throughput), or with idle
/// cycles drawn from a seeded RNG to exercise the valid handshake.
pub struct Pacing {
    idle_per_mille: u32,
    rng: Option<Stimulus>,
}

impl Pacing {
    /// A transaction every cycle the stimulus has one.
    pub fn full() -> Pacing {
        Pacing {
            idle_per_mille: 0,
            rng: None,
        }
    }

    /// An idle cycle instead of a transaction with probability `idle_per_mille / 1000`.
    pub fn random(idle_per_mille: u32, seed: Seed) -> Pacing {
        assert!(idle_per_mille < 1000, "pacing would never send");
        Pacing {
            idle_per_mille,
            rng: Some(Stimulus::new(seed)),
        }
    }

    fn send(&mut self) -> bool {
        match self.rng.as_mut() {
            None => true,
            Some(r) => r.draw(&(0u32..1000)) >= self.idle_per_mille,
        }
    }
}

/// Stops a run that does not finish: after `max_cycles` simulated cycles or `max_wall` of
/// wall-clock time, whichever comes first. Every run has one.
#[derive(Clone, Copy, Debug)]
pub struct Watchdog {
    pub max_cycles: u64,
    pub max_wall: Duration,
}

impl Watchdog {
    /// `max_cycles` cycles and at most 10 minutes.
    pub fn cycles(max_cycles: u64) -> Watchdog {
        Watchdog {
            max_cycles,
            max_wall: Duration::from_secs(600),
        }
    }
}

/// A run the watchdog stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Timeout {
    pub cycle: u64,
    pub sent: u64,
    pub received: u64,
    pub expected: u64,
    pub reason: String,
}

impl std::fmt::Display for Timeout {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "watchdog: {} at cycle {} with {} of {} transactions received ({} sent)",
            self.reason, self.cycle, self.received, self.expected, self.sent
        )
    }
}

/// What a finished run measured.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RunStats {
    /// Cycles the run took (from its first to its last cycle).
    pub cycles: u64,
    pub sent: u64,
    pub received: u64,
    /// Cycles from a transaction's input to its output, assuming in-order completion.
    pub min_latency: Option<u64>,
    pub max_latency: Option<u64>,
    /// Cycles in which the driver presented a transaction.
    pub busy_cycles: u64,
}

impl RunStats {
    /// Received transactions per cycle over the run.
    pub fn throughput(&self) -> f64 {
        if self.cycles == 0 {
            0.0
        } else {
            self.received as f64 / self.cycles as f64
        }
    }
}

/// Runs a testbench: each cycle the driver presents the next transaction of `stimulus` (as
/// `pacing` allows), the design settles, the monitor samples the outputs, the design is
/// clocked. `on` sees every sent and received transaction (to compute golden results, score,
/// collect coverage and set trace probes). The run ends when all stimulus is sent and
/// `expected` transactions were received, or the watchdog fires.
#[allow(clippy::too_many_arguments)]
pub fn run<M, T, D, Mo, F>(
    sim: &mut Sim<M, T>,
    driver: &mut D,
    monitor: &mut Mo,
    stimulus: impl IntoIterator<Item = D::Txn>,
    expected: u64,
    pacing: &mut Pacing,
    watchdog: Watchdog,
    mut on: F,
) -> Result<RunStats, Timeout>
where
    M: Module,
    T: Trace,
    D: Driver<M>,
    Mo: Monitor<M>,
    F: FnMut(&mut Sim<M, T>, Event<'_, D::Txn, Mo::Txn>),
{
    let mut it = stimulus.into_iter().peekable();
    let start = sim.cycle();
    let t0 = Instant::now();
    let mut st = RunStats::default();
    let mut inflight: VecDeque<u64> = VecDeque::new();
    loop {
        if it.peek().is_none() && st.received >= expected {
            break;
        }
        let c = sim.cycle();
        let elapsed = c - start;
        let timeout = |reason: String, st: &RunStats| Timeout {
            cycle: c,
            sent: st.sent,
            received: st.received,
            expected,
            reason,
        };
        if elapsed >= watchdog.max_cycles {
            driver.drive(&mut sim.dut, None);
            return Err(timeout(
                format!("{} cycles elapsed", watchdog.max_cycles),
                &st,
            ));
        }
        if elapsed.is_multiple_of(1024) && t0.elapsed() > watchdog.max_wall {
            driver.drive(&mut sim.dut, None);
            return Err(timeout(
                format!("{:?} of wall time elapsed", watchdog.max_wall),
                &st,
            ));
        }
        let txn = if it.peek().is_some() && pacing.send() {
            it.next()
        } else {
            None
        };
        driver.drive(&mut sim.dut, txn.as_ref());
        sim.eval();
        if let Some(t) = &txn {
            st.sent += 1;
            st.busy_cycles += 1;
            inflight.push_back(c);
            on(sim, Event::Sent { cycle: c, txn: t });
        }
        if let Some(o) = monitor.sample(&sim.dut) {
            st.received += 1;
            if let Some(s) = inflight.pop_front() {
                let l = c - s;
                st.min_latency = Some(st.min_latency.map_or(l, |m| m.min(l)));
                st.max_latency = Some(st.max_latency.map_or(l, |m| m.max(l)));
            }
            on(sim, Event::Received { cycle: c, txn: o });
        }
        sim.tick();
    }
    driver.drive(&mut sim.dut, None);
    st.cycles = sim.cycle() - start;
    Ok(st)
}
