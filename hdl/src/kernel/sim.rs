//! The cycle-based simulator: one evaluation and one clock edge per cycle, no event queue.

use super::module::{Dir, Module, Visitor};
use super::signal::Signal;
use crate::fx::Narrowing;

/// Something that records the design every cycle (a VCD writer, for instance).
///
/// The simulator calls `sample` once per cycle, just before the clock edge, when inputs,
/// outputs, register values and anything the testbench set during the cycle are all settled.
pub trait Trace {
    /// Called once before the first cycle with the whole hierarchy.
    fn start(&mut self, top: &dyn Module) -> std::io::Result<()>;
    /// Records cycle `cycle` (reset asserted or not). `top` is the design's own type, so
    /// that [`Module::visit_bits`] reads every signal without dynamic dispatch.
    fn sample<M: Module>(&mut self, cycle: u64, reset: bool, top: &M) -> std::io::Result<()>;
    /// Ends the recording after `cycles` cycles.
    fn finish(&mut self, cycles: u64) -> std::io::Result<()>;
}

/// No tracing: every call compiles to nothing.
pub struct NoTrace;

impl Trace for NoTrace {
    fn start(&mut self, _: &dyn Module) -> std::io::Result<()> {
        Ok(())
    }
    #[inline(always)]
    fn sample<M: Module>(&mut self, _: u64, _: bool, _: &M) -> std::io::Result<()> {
        Ok(())
    }
    fn finish(&mut self, _: u64) -> std::io::Result<()> {
        Ok(())
    }
}

/// Simulates a top module `M` cycle by cycle, optionally traced by `T`.
///
/// Per cycle: the testbench drives inputs, calls [`Sim::eval`] (combinational settle), reads
/// outputs, then [`Sim::tick`] (sample for tracing, clock edge, cycle count + 1).
/// [`Sim::step`] does both when nothing needs to be read in between.
pub struct Sim<M: Module, T: Trace = NoTrace> {
    /// The design under test: set its inputs between cycles, read its outputs after `eval`.
    pub dut: M,
    trace: Option<T>,
    /// After `dut` and `trace`: on a panic it is dropped last, so the outermost simulation's
    /// cycle is the one [`panicked_in_cycle`] gives.
    cycle: Cycle,
    reset: bool,
    check: bool,
    snap: (Vec<u64>, Vec<u64>),
    /// Whether each signal (in visit order) is a register's value, for the edge check.
    is_reg: Vec<bool>,
    trace_error: Option<std::io::Error>,
}

/// A [`Sim`]'s count of clock edges. A simulation that a panic unwinds (a value that does not
/// fit its signal's format, in some cycle's `eval`) leaves its cycle for
/// [`panicked_in_cycle`].
struct Cycle(u64);

impl Drop for Cycle {
    fn drop(&mut self) {
        if std::thread::panicking() {
            PANICKED_IN.with(|c| c.set(Some(self.0)));
        }
    }
}

thread_local! {
    static PANICKED_IN: std::cell::Cell<Option<u64>> = const { std::cell::Cell::new(None) };
}

/// The cycle ([`Sim::cycle`]: the edges before it) in which the last simulation that a panic
/// unwound on this thread was, taken: a regression says it of a job whose model panicked.
/// `None` when none has been since the last call.
pub fn panicked_in_cycle() -> Option<u64> {
    PANICKED_IN.with(std::cell::Cell::take)
}

impl<M: Module> Sim<M, NoTrace> {
    /// An untraced simulation of `dut`.
    pub fn new(dut: M) -> Self {
        Sim::build(dut, None)
    }
}

impl<M: Module, T: Trace> Sim<M, T> {
    fn build(dut: M, trace: Option<T>) -> Self {
        Sim {
            dut,
            trace,
            cycle: Cycle(0),
            reset: false,
            check: false,
            snap: (Vec::new(), Vec::new()),
            is_reg: Vec::new(),
            trace_error: None,
        }
    }

    /// A simulation traced by `trace` (whose `start` is called now).
    pub fn traced(dut: M, mut trace: T) -> std::io::Result<Self> {
        trace.start(&dut)?;
        Ok(Sim::build(dut, Some(trace)))
    }

    /// A simulation traced when `trace` is `Some`.
    pub fn maybe_traced(dut: M, trace: Option<T>) -> std::io::Result<Self> {
        match trace {
            Some(t) => Sim::traced(dut, t),
            None => Ok(Sim::build(dut, None)),
        }
    }

    /// Turns on the schedule check: every `eval` runs twice and every signal must come out the
    /// same. A module that reads a child's output before evaluating that child, or an `eval`
    /// that changes state, fails it, with the name of the first signal that differs. Doubles
    /// the cost of `eval`; on in tests, off in benchmarks.
    pub fn check_schedule(mut self, on: bool) -> Self {
        self.check = on;
        self
    }

    /// Cycles completed (clock edges so far).
    #[inline]
    pub fn cycle(&self) -> u64 {
        self.cycle.0
    }

    /// Asserts or releases the synchronous reset (sampled at the next edge).
    #[inline]
    pub fn set_reset(&mut self, r: bool) {
        self.reset = r;
    }

    /// Holds reset for `cycles` cycles, then releases it.
    pub fn reset(&mut self, cycles: u32) {
        self.reset = true;
        for _ in 0..cycles {
            self.step();
        }
        self.reset = false;
    }

    /// The combinational process of the whole design.
    #[inline]
    pub fn eval(&mut self) {
        self.dut.eval();
        if self.check {
            self.verify_schedule();
        }
    }

    /// The clock edge: the cycle is traced, then registers commit.
    #[inline]
    pub fn tick(&mut self) {
        if let Some(t) = self.trace.as_mut() {
            if let Err(e) = t.sample(self.cycle.0, self.reset, &self.dut) {
                self.trace_error.get_or_insert(e);
            }
        }
        if self.check {
            self.checked_edge();
        } else {
            self.dut.tick(self.reset);
        }
        self.cycle.0 += 1;
    }

    /// The clock edge, with the check that it changes registers only.
    fn checked_edge(&mut self) {
        let (mut a, mut b) = std::mem::take(&mut self.snap);
        snapshot(&self.dut, &mut a);
        if self.is_reg.len() != a.len() {
            // The hierarchy is fixed: which signals are registers is found once, and once
            // that `visit_bits` lists what `visit` lists (a hand-written one could differ).
            assert_eq!(
                visited_bits(&self.dut),
                a,
                "'{}': visit_bits lists other values than visit",
                self.dut.instance()
            );
            self.is_reg = signal_dirs(&self.dut)
                .iter()
                .map(|&d| d == Dir::Reg)
                .collect();
        }
        self.dut.tick(self.reset);
        snapshot(&self.dut, &mut b);
        let is_reg = &self.is_reg;
        let bad = (0..a.len()).find(|&i| a[i] != b[i] && !is_reg[i]);
        if let Some(i) = bad {
            let path = signal_paths(&self.dut).swap_remove(i);
            let dir = signal_dirs(&self.dut)[i];
            panic!(
                "two-process error at cycle {}: '{path}' ({dir:?}) changed from {:#x} to {:#x} at \
                 the clock edge (only registers change in tick; drive signals in eval)",
                self.cycle.0, a[i], b[i]
            );
        }
        self.snap = (a, b);
    }

    /// One whole cycle: `eval` then `tick`.
    #[inline]
    pub fn step(&mut self) {
        self.eval();
        self.tick();
    }

    /// The tracer, e.g. to set a golden value shown beside the DUT's.
    pub fn trace_mut(&mut self) -> Option<&mut T> {
        self.trace.as_mut()
    }

    /// Ends tracing (writing the final timestamp) and returns the design.
    pub fn finish(mut self) -> std::io::Result<M> {
        if let Some(e) = self.trace_error.take() {
            return Err(e);
        }
        if let Some(t) = self.trace.as_mut() {
            t.finish(self.cycle.0)?;
        }
        Ok(self.dut)
    }

    fn verify_schedule(&mut self) {
        let (mut a, mut b) = std::mem::take(&mut self.snap);
        snapshot(&self.dut, &mut a);
        self.dut.eval();
        snapshot(&self.dut, &mut b);
        if let Some(i) = a.iter().zip(&b).position(|(x, y)| x != y) {
            let path = signal_paths(&self.dut).swap_remove(i);
            panic!(
                "schedule error at cycle {}: '{path}' changed from {:#x} to {:#x} on a second \
                 evaluation (a value was read before it was computed, or eval changed state)",
                self.cycle.0, a[i], b[i]
            );
        }
        self.snap = (a, b);
    }
}

fn snapshot<M: Module>(top: &M, out: &mut Vec<u64>) {
    out.clear();
    top.visit_bits(&mut |b| out.push(b));
}

/// Every signal's bits as [`Module::visit`] lists them.
pub(super) fn visited_bits(top: &dyn Module) -> Vec<u64> {
    let mut out = Vec::new();
    top.visit(&mut super::module::BitsOf(&mut |b| out.push(b)));
    out
}

/// What every signal is to its module, in visit order.
pub fn signal_dirs(top: &dyn Module) -> Vec<Dir> {
    struct Dirs(Vec<Dir>);
    impl Visitor for Dirs {
        fn enter(&mut self, _: &str, _: &str) {}
        fn leave(&mut self) {}
        fn signal(&mut self, d: Dir, _: &Signal) {
            self.0.push(d);
        }
    }
    let mut d = Dirs(Vec::new());
    top.visit(&mut d);
    d.0
}

/// Every instance in the hierarchy as `(path, kind)`, in visit order (for tests that every
/// module's `visit` reaches every child).
pub fn instances(top: &dyn Module) -> Vec<(String, String)> {
    #[derive(Default)]
    struct Inst {
        scope: Vec<String>,
        out: Vec<(String, String)>,
    }
    impl Visitor for Inst {
        fn enter(&mut self, instance: &str, kind: &str) {
            self.scope.push(instance.to_string());
            self.out.push((self.scope.join("."), kind.to_string()));
        }
        fn leave(&mut self) {
            self.scope.pop();
        }
        fn signal(&mut self, _: Dir, _: &Signal) {}
    }
    let mut i = Inst::default();
    top.visit(&mut i);
    i.out
}

/// Hierarchical names (`top.child.signal`) of every signal, in visit order.
pub fn signal_paths(top: &dyn Module) -> Vec<String> {
    #[derive(Default)]
    struct Paths {
        scope: Vec<String>,
        out: Vec<String>,
    }
    impl Visitor for Paths {
        fn enter(&mut self, instance: &str, _: &str) {
            self.scope.push(instance.to_string());
        }
        fn leave(&mut self) {
            self.scope.pop();
        }
        fn signal(&mut self, _: Dir, s: &Signal) {
            self.out
                .push(format!("{}.{}", self.scope.join("."), s.name()));
        }
    }
    let mut p = Paths::default();
    top.visit(&mut p);
    p.out
}

/// Every named narrowing of `top`, by its path (`instance.child.name`), with what it met.
pub fn narrowings(top: &dyn Module) -> Vec<(String, Narrowing)> {
    #[derive(Default)]
    struct Found {
        scope: Vec<String>,
        out: Vec<(String, Narrowing)>,
    }
    impl Visitor for Found {
        fn enter(&mut self, instance: &str, _: &str) {
            self.scope.push(instance.to_string());
        }
        fn leave(&mut self) {
            self.scope.pop();
        }
        fn signal(&mut self, _: Dir, _: &Signal) {}
        fn narrowing(&mut self, n: &Narrowing) {
            let path = format!("{}.{}", self.scope.join("."), n.name());
            self.out.push((path, n.clone()));
        }
    }
    let mut f = Found::default();
    top.visit(&mut f);
    f.out
}
