//! Drivers, monitors and the cycle loop that runs a testbench under a watchdog.

use crate::random::{Seed, Stimulus};
use hdl::kernel::{Module, Sim, Trace};
use serde::Serialize;
use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// Turns transactions into pin activity on the DUT's inputs, one cycle at a time, with a
/// ready/valid handshake: a transaction stays presented (valid held, data unchanged) until the
/// cycle in which the DUT accepts it.
pub trait Driver<M> {
    /// The transaction it drives.
    type Txn;
    /// Drives one cycle: `Some(t)` presents transaction `t`, `None` drives the idle pattern
    /// (valid low).
    fn drive(&mut self, dut: &mut M, txn: Option<&Self::Txn>);
    /// After the design settled: whether the DUT takes the presented transaction in this
    /// cycle (its `ready`). A DUT without backpressure always does.
    fn accepted(&self, _dut: &M) -> bool {
        true
    }
}

/// Turns pin activity on the DUT's outputs back into transactions. A monitor only reports a
/// transfer (valid, and ready where the DUT has an output handshake), so stalls in either
/// direction are tolerated.
pub trait Monitor<M> {
    /// The transaction it collects.
    type Txn;
    /// Drives the DUT's output `ready` for this cycle, before the design settles (output
    /// backpressure). A DUT without an output handshake ignores it.
    fn ready(&mut self, _dut: &mut M, _ready: bool) {}
    /// Looks at the settled outputs of the current cycle.
    fn sample(&mut self, dut: &M) -> Option<Self::Txn>;
}

/// What the cycle loop reports to the testbench.
// Each variant's line names its fields.
#[allow(missing_docs)]
pub enum Event<'a, I, O> {
    /// Transaction `txn` was accepted by the DUT in `cycle` (compute its golden result now).
    Sent { cycle: u64, txn: &'a I },
    /// The monitor saw `txn` in `cycle` (score it now).
    Received { cycle: u64, txn: O },
    /// Every cycle, after the design settled and the above were reported (to sample internal
    /// state: cache lookups, completed frames).
    Settled { cycle: u64 },
}

/// What a scored run ([`run_scored`]) reports: the two events a scoreboard needs.
// Each variant's line names its fields.
#[allow(missing_docs)]
pub enum Scored<'a, I, O> {
    /// Transaction `txn` was accepted by the DUT in `cycle` (compute its golden result now).
    Sent { cycle: u64, txn: &'a I },
    /// The monitor saw `txn` in `cycle` (score it now).
    Received { cycle: u64, txn: O },
}

/// When a side of the handshake is willing: every cycle, at a fixed interval after each
/// transfer, or with random idle cycles drawn from a seeded RNG.
pub struct Pacing {
    idle_per_mille: u32,
    rng: Option<Stimulus>,
    /// Cycles between the transfers (1: back to back).
    interval: u32,
    wait: u32,
}

impl Pacing {
    /// Willing every cycle (full throughput).
    pub fn full() -> Pacing {
        Pacing::every(1)
    }

    /// Willing again `interval` cycles after each transfer (1: every cycle); `interval` >= 1.
    pub fn every(interval: u32) -> Pacing {
        Pacing {
            idle_per_mille: 0,
            rng: None,
            interval: interval.max(1),
            wait: 0,
        }
    }

    /// Unwilling in a cycle with probability `idle_per_mille / 1000` (at most 999).
    pub fn random(idle_per_mille: u32, seed: Seed) -> Pacing {
        Pacing {
            idle_per_mille: idle_per_mille.min(999),
            rng: Some(Stimulus::new(seed)),
            interval: 1,
            wait: 0,
        }
    }

    /// Whether this side is willing in the current cycle.
    #[inline]
    fn willing(&mut self) -> bool {
        if self.wait > 0 {
            self.wait -= 1;
            return false;
        }
        match self.rng.as_mut() {
            None => true,
            Some(r) => r.draw(&(0u32..1000)) >= self.idle_per_mille,
        }
    }

    /// A transfer happened: wait out the interval.
    #[inline]
    fn transferred(&mut self) {
        self.wait = self.interval - 1;
    }
}

/// Stops a run that does not finish: after `max_cycles` simulated cycles or `max_wall` of
/// wall-clock time, whichever comes first. Every run has one.
#[derive(Clone, Copy, Debug)]
pub struct Watchdog {
    /// The cycles a run may take.
    pub max_cycles: u64,
    /// The wall-clock time a run may take.
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

    /// `Err` with the reason once `elapsed` cycles or the wall time since `t0` are used up
    /// (the clock is read every 1024 cycles).
    #[inline]
    pub fn check(&self, elapsed: u64, t0: &Instant) -> Result<(), String> {
        if elapsed >= self.max_cycles {
            return Err(self.expired(false));
        }
        if elapsed.is_multiple_of(1024) && t0.elapsed() > self.max_wall {
            return Err(self.expired(true));
        }
        Ok(())
    }

    #[cold]
    fn expired(&self, wall: bool) -> String {
        if wall {
            format!("{:?} of wall time elapsed", self.max_wall)
        } else {
            format!("{} cycles elapsed", self.max_cycles)
        }
    }
}

/// A run the watchdog stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Timeout {
    /// The cycle it stopped at.
    pub cycle: u64,
    /// Transactions sent by then.
    pub sent: u64,
    /// Transactions received by then.
    pub received: u64,
    /// Transactions the run waited for.
    pub expected: u64,
    /// Why it stopped.
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
    /// Transactions the driver handed over.
    pub sent: u64,
    /// Transactions the monitor collected.
    pub received: u64,
    /// Cycles from a transaction's input to its output, assuming in-order completion.
    pub min_latency: Option<u64>,
    /// The longest of them.
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

/// How a run is paced and when it ends.
pub struct RunSpec {
    /// Output transactions to wait for after all stimulus is sent.
    pub expected: u64,
    /// When the driver offers a transaction.
    pub pacing: Pacing,
    /// When the monitor is ready for one (output backpressure).
    pub sink: Pacing,
    /// When the run gives up.
    pub watchdog: Watchdog,
}

impl RunSpec {
    /// `expected` outputs, full rate on both sides, at most `max_cycles` cycles.
    pub fn new(expected: u64, max_cycles: u64) -> RunSpec {
        RunSpec {
            expected,
            pacing: Pacing::full(),
            sink: Pacing::full(),
            watchdog: Watchdog::cycles(max_cycles),
        }
    }

    /// The driver's pacing.
    pub fn pacing(mut self, p: Pacing) -> RunSpec {
        self.pacing = p;
        self
    }

    /// The monitor's pacing (output backpressure).
    pub fn sink(mut self, p: Pacing) -> RunSpec {
        self.sink = p;
        self
    }
}

/// Runs a testbench: each cycle the driver presents the current transaction of `stimulus` (as
/// the pacing allows; a transaction not accepted stays presented), the monitor sets the output
/// `ready` (as the sink pacing allows), the design settles, accepted and received
/// transactions are reported to `on`, the design is clocked. The run ends when all stimulus is
/// accepted and `spec.expected` transactions were received, or the watchdog fires.
pub fn run<M, T, D, Mo, F>(
    sim: &mut Sim<M, T>,
    driver: &mut D,
    monitor: &mut Mo,
    stimulus: impl IntoIterator<Item = D::Txn>,
    spec: &mut RunSpec,
    on: F,
) -> Result<RunStats, Timeout>
where
    M: Module,
    T: Trace,
    D: Driver<M>,
    Mo: Monitor<M>,
    F: FnMut(&mut Sim<M, T>, Event<'_, D::Txn, Mo::Txn>),
{
    run_beside(sim, driver, monitor, stimulus, spec, &mut (), on)
}

/// [`run`] for a testbench that scores and needs nothing else: `on` hears each accepted and
/// each received transaction, not every settled cycle.
pub fn run_scored<M, T, D, Mo, F>(
    sim: &mut Sim<M, T>,
    driver: &mut D,
    monitor: &mut Mo,
    stimulus: impl IntoIterator<Item = D::Txn>,
    spec: &mut RunSpec,
    on: F,
) -> Result<RunStats, Timeout>
where
    M: Module,
    T: Trace,
    D: Driver<M>,
    Mo: Monitor<M>,
    F: FnMut(&mut Sim<M, T>, Scored<'_, D::Txn, Mo::Txn>),
{
    run_scored_beside(sim, driver, monitor, stimulus, spec, &mut (), on)
}

/// [`run_beside`] as [`run_scored`]: with a second port, `on` hearing the scored events only.
pub fn run_scored_beside<M, T, D, Mo, B, F>(
    sim: &mut Sim<M, T>,
    driver: &mut D,
    monitor: &mut Mo,
    stimulus: impl IntoIterator<Item = D::Txn>,
    spec: &mut RunSpec,
    side: &mut B,
    mut on: F,
) -> Result<RunStats, Timeout>
where
    M: Module,
    T: Trace,
    D: Driver<M>,
    Mo: Monitor<M>,
    B: Background<M> + ?Sized,
    F: FnMut(&mut Sim<M, T>, Scored<'_, D::Txn, Mo::Txn>),
{
    run_beside(
        sim,
        driver,
        monitor,
        stimulus,
        spec,
        side,
        |sim, ev| match ev {
            Event::Sent { cycle, txn } => on(sim, Scored::Sent { cycle, txn }),
            Event::Received { cycle, txn } => on(sim, Scored::Received { cycle, txn }),
            Event::Settled { .. } => {}
        },
    )
}

/// A port driven on its own schedule beside the transaction stream of [`run`] (a video
/// source beside a request port): it sets its inputs every cycle before the design settles
/// and may look at the settled design after. It does not end the run; the main stream does.
pub trait Background<M> {
    /// Sets its inputs for `cycle`, before the design settles.
    fn drive(&mut self, dut: &mut M, cycle: u64);
    /// Looks at the settled design in `cycle`.
    fn settled(&mut self, _dut: &M, _cycle: u64) {}
}

/// No second port.
impl<M> Background<M> for () {
    fn drive(&mut self, _dut: &mut M, _cycle: u64) {}
}

/// [`run`] with a second port, `side`, driven every cycle on its own schedule.
pub fn run_beside<M, T, D, Mo, B, F>(
    sim: &mut Sim<M, T>,
    driver: &mut D,
    monitor: &mut Mo,
    stimulus: impl IntoIterator<Item = D::Txn>,
    spec: &mut RunSpec,
    side: &mut B,
    mut on: F,
) -> Result<RunStats, Timeout>
where
    M: Module,
    T: Trace,
    D: Driver<M>,
    Mo: Monitor<M>,
    B: Background<M> + ?Sized,
    F: FnMut(&mut Sim<M, T>, Event<'_, D::Txn, Mo::Txn>),
{
    let mut it = stimulus.into_iter().peekable();
    let mut current: Option<D::Txn> = None;
    let start = sim.cycle();
    let t0 = Instant::now();
    let mut st = RunStats::default();
    let mut inflight: VecDeque<u64> = VecDeque::new();
    loop {
        if current.is_none() && it.peek().is_some() && spec.pacing.willing() {
            current = it.next();
        }
        if current.is_none() && it.peek().is_none() && st.received >= spec.expected {
            break;
        }
        let c = sim.cycle();
        if let Err(reason) = spec.watchdog.check(c - start, &t0) {
            driver.drive(&mut sim.dut, None);
            return Err(Timeout {
                cycle: c,
                sent: st.sent,
                received: st.received,
                expected: spec.expected,
                reason,
            });
        }
        driver.drive(&mut sim.dut, current.as_ref());
        side.drive(&mut sim.dut, c);
        let ready = spec.sink.willing();
        monitor.ready(&mut sim.dut, ready);
        sim.eval();
        side.settled(&sim.dut, c);
        if current.is_some() {
            st.busy_cycles += 1;
            if driver.accepted(&sim.dut) {
                let t = current.take().expect("presented");
                st.sent += 1;
                inflight.push_back(c);
                spec.pacing.transferred();
                on(sim, Event::Sent { cycle: c, txn: &t });
            }
        }
        if let Some(o) = monitor.sample(&sim.dut) {
            st.received += 1;
            spec.sink.transferred();
            if let Some(s) = inflight.pop_front() {
                let l = c - s;
                st.min_latency = Some(st.min_latency.map_or(l, |m| m.min(l)));
                st.max_latency = Some(st.max_latency.map_or(l, |m| m.max(l)));
            }
            on(sim, Event::Received { cycle: c, txn: o });
        }
        on(sim, Event::Settled { cycle: c });
        sim.tick();
    }
    driver.drive(&mut sim.dut, None);
    st.cycles = sim.cycle() - start;
    Ok(st)
}
