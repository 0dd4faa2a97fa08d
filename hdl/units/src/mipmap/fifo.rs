//! A synchronous FIFO of declared depth that reports overflow and underflow instead of
//! wrapping: FIFOs 1408 and 1412 of the mipmap generator (Schilling & Knittel, Figure 14).
//!
//! Two-process: the owner drives `push`, `push_data`, `pop` and `clear` in its `eval` and
//! calls [`Fifo::eval`], which drives `occupancy` and `error`; the clock edge applies clear,
//! then pop, then push. [`Fifo::front`] and [`Fifo::iter`] read the stored entries (the
//! FIFO's registered state) and may be used before the inputs are driven.

use crate::fx::Format;
use crate::kernel::{Module, Signal, Visitor};
use crate::signals;

/// What went wrong with a FIFO.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FifoError {
    /// A push into a full FIFO.
    Overflow,
    /// A pop from an empty one.
    Underflow,
}

impl FifoError {
    /// The `error` output's code: 1 overflow, 2 underflow.
    pub fn code(self) -> u64 {
        match self {
            FifoError::Overflow => 1,
            FifoError::Underflow => 2,
        }
    }
}

/// A FIFO of `depth` entries of `width` bits; its kind names the unit (`fifo_1408`).
#[derive(Clone, Debug)]
pub struct Fifo {
    name: &'static str,
    kind: &'static str,
    buf: Vec<u16>,
    head: usize,
    len: usize,
    max: usize,
    pub push: Signal,
    pub push_data: Signal,
    pub pop: Signal,
    /// Empties the FIFO at the edge (a parallel transfer of its line), before pop and push.
    pub clear: Signal,
    pub occupancy: Signal,
    /// 0 none, 1 overflow, 2 underflow (this cycle's inputs against the stored state).
    pub error: Signal,
}

impl Fifo {
    /// A FIFO of `1 <= depth` entries of `1..=16` bits; `name` is both its instance and its
    /// kind (one FIFO of each number per level).
    pub fn new(name: &'static str, depth: usize, width: u32) -> Result<Fifo, String> {
        if depth == 0 || !(1..=16).contains(&width) {
            return Err(format!(
                "{name}: depth {depth}, width {width}: depth >= 1, width 1..=16"
            ));
        }
        let bits = usize::BITS - depth.leading_zeros();
        Ok(Fifo {
            name,
            kind: name,
            buf: vec![0; depth],
            head: 0,
            len: 0,
            max: 0,
            push: Signal::bit("push"),
            push_data: Signal::new("push_data", Format::uint(width)),
            pop: Signal::bit("pop"),
            clear: Signal::bit("clear"),
            occupancy: Signal::new("occupancy", Format::uint(bits)),
            error: Signal::new("error", Format::uint(2)),
        })
    }

    pub fn depth(&self) -> usize {
        self.buf.len()
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    pub fn is_full(&self) -> bool {
        self.len == self.buf.len()
    }
    /// Largest occupancy since construction.
    pub fn max_occupancy(&self) -> usize {
        self.max
    }

    /// The oldest stored entry, if any (what a pop takes).
    #[inline]
    pub fn front(&self) -> Option<u16> {
        (self.len > 0).then(|| self.buf[self.head])
    }

    /// The stored entries, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = u16> + '_ {
        let d = self.buf.len();
        (0..self.len).map(move |i| self.buf[(self.head + i) % d])
    }

    /// The error this cycle's inputs cause: clear first, then pop, then push.
    fn fault(&self) -> Option<FifoError> {
        let len = if self.clear.is_high() { 0 } else { self.len };
        let pop = self.pop.is_high();
        if pop && len == 0 {
            return Some(FifoError::Underflow);
        }
        let after_pop = len - usize::from(pop);
        (self.push.is_high() && after_pop == self.buf.len()).then_some(FifoError::Overflow)
    }
}

impl Module for Fifo {
    fn instance(&self) -> &str {
        self.name
    }
    fn kind(&self) -> &'static str {
        self.kind
    }
    #[inline]
    fn eval(&mut self) {
        self.occupancy.set_bits(self.len as u64);
        self.error.set_bits(self.fault().map_or(0, FifoError::code));
    }
    #[inline]
    fn tick(&mut self, reset: bool) {
        if reset || self.clear.is_high() {
            self.head = 0;
            self.len = 0;
        }
        if reset {
            return;
        }
        let d = self.buf.len();
        if self.pop.is_high() && self.len > 0 {
            self.head = if self.head + 1 == d { 0 } else { self.head + 1 };
            self.len -= 1;
        }
        if self.push.is_high() && self.len < d {
            let tail = (self.head + self.len) % d;
            self.buf[tail] = self.push_data.bits() as u16;
            self.len += 1;
            self.max = self.max.max(self.len);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        signals!(v;
            Input: self.push, self.push_data, self.pop, self.clear;
            Output: self.occupancy, self.error);
        v.leave();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Sim;

    /// One cycle with the given inputs; returns the error code the FIFO reported.
    fn cycle(sim: &mut Sim<Fifo>, push: Option<u16>, pop: bool, clear: bool) -> u64 {
        let f = &mut sim.dut;
        f.push.set_bool(push.is_some());
        f.push_data.set_bits(u64::from(push.unwrap_or(0)));
        f.pop.set_bool(pop);
        f.clear.set_bool(clear);
        sim.eval();
        let e = sim.dut.error.bits();
        sim.tick();
        e
    }

    #[test]
    fn order_occupancy_and_errors() {
        let mut sim = Sim::new(Fifo::new("fifo_1408", 3, 9).unwrap()).check_schedule(true);
        assert!(sim.dut.is_empty());
        assert_eq!(cycle(&mut sim, None, true, false), 2, "pop from empty");
        for v in 1..=3 {
            assert_eq!(cycle(&mut sim, Some(v), false, false), 0);
            assert!(!sim.dut.is_empty());
        }
        assert_eq!(cycle(&mut sim, Some(4), false, false), 1, "push into full");
        assert_eq!(sim.dut.len(), 3);
        assert_eq!(
            cycle(&mut sim, Some(5), true, false),
            0,
            "pop and push when full"
        );
        assert_eq!(sim.dut.iter().collect::<Vec<_>>(), vec![2, 3, 5]);
        assert_eq!(sim.dut.front(), Some(2));
        sim.eval();
        assert_eq!(sim.dut.occupancy.bits(), 3);
        assert_eq!(cycle(&mut sim, Some(7), false, true), 0, "clear, then push");
        assert_eq!(sim.dut.iter().collect::<Vec<_>>(), vec![7]);
        // One short of full, a pop and a push together are no overflow.
        assert_eq!(cycle(&mut sim, Some(8), false, false), 0);
        assert_eq!(
            cycle(&mut sim, Some(9), true, false),
            0,
            "pop and push, one short"
        );
        assert_eq!(sim.dut.iter().collect::<Vec<_>>(), vec![8, 9]);
        assert_eq!(sim.dut.max_occupancy(), 3);
        assert_eq!(cycle(&mut sim, None, true, false), 0);
        assert!(!sim.dut.is_empty() && sim.dut.front() == Some(9));
        assert_eq!(cycle(&mut sim, None, true, false), 0);
        assert!(sim.dut.is_empty() && sim.dut.front().is_none());
        assert!(Fifo::new("fifo_1412", 0, 8).is_err());
    }
}
