//! A synchronous FIFO of declared depth that reports overflow and underflow instead of
//! wrapping: FIFOs 1408 and 1412 of the mipmap generator (Schilling & Knittel, Figure 14).
//!
//! Two-process: the owner drives `push`, `push_data`, `pop` and `clear` in its `eval` and
//! calls [`Fifo::eval`], which drives `occupancy` and `error`; the clock edge applies clear,
//! then pop, then push. [`Fifo::front`] and [`Fifo::iter`] read the stored entries (the
//! FIFO's registered state) and may be used before the inputs are driven.

use crate::fx::{Bit, Format};
use crate::kernel::{Mem, Module, Reg, Signal, SignalOf};

hdl::formats! {
    /// A FIFO error code ([`FifoError::code`]): 0 none, 1 overflow, 2 underflow.
    pub ErrCode = Format::uint(2);
}

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

/// `i % d` for `i < 2 d` (a place past the head, which is below `d`): a compare, not a
/// division.
#[inline(always)]
fn wrap(i: usize, d: usize) -> usize {
    debug_assert!(i < 2 * d);
    if i >= d {
        i - d
    } else {
        i
    }
}

/// A FIFO of `depth` entries of `width` bits; its kind names the unit (`fifo_1408`).
#[derive(Clone, Debug, Module)]
#[module(kind = self.kind)]
pub struct Fifo {
    #[instance]
    name: &'static str,
    kind: &'static str,
    #[input]
    pub push: SignalOf<Bit>,
    #[input]
    pub push_data: Signal,
    #[input]
    pub pop: SignalOf<Bit>,
    /// Empties the FIFO at the edge (a parallel transfer of its line), before pop and push.
    #[input]
    pub clear: SignalOf<Bit>,
    #[output]
    pub occupancy: Signal,
    /// 0 none, 1 overflow, 2 underflow (this cycle's inputs against the stored state).
    #[output]
    pub error: SignalOf<ErrCode>,
    /// The oldest entry's place, the entries held, the most ever held.
    #[reg]
    head: Reg,
    #[reg]
    len: Reg,
    #[reg]
    max: Reg,
    /// The entries.
    #[child]
    buf: Mem,
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
        let count = Format::uint(bits);
        Ok(Fifo {
            name,
            kind: name,
            push: SignalOf::new("push"),
            push_data: Signal::new("push_data", Format::uint(width)),
            pop: SignalOf::new("pop"),
            clear: SignalOf::new("clear"),
            occupancy: Signal::new("occupancy", count),
            error: SignalOf::new("error"),
            head: Reg::new("head", count),
            len: Reg::new("len", count),
            max: Reg::new("max_occupancy", count),
            buf: Mem::new("entries", depth, Format::uint(width)),
        })
    }

    pub fn depth(&self) -> usize {
        self.buf.depth()
    }
    pub fn len(&self) -> usize {
        self.len.q().bits() as usize
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    pub fn is_full(&self) -> bool {
        self.len() == self.depth()
    }
    /// Largest occupancy since reset.
    pub fn max_occupancy(&self) -> usize {
        self.max.q().bits() as usize
    }

    /// The oldest stored entry, if any (what a pop takes).
    #[inline]
    pub fn front(&self) -> Option<u16> {
        (!self.is_empty()).then(|| self.buf.read(self.head.q().bits() as usize) as u16)
    }

    /// The stored entries, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = u16> + '_ {
        let (d, head) = (self.depth(), self.head.q().bits() as usize);
        (0..self.len()).map(move |i| self.buf.read(wrap(head + i, d)) as u16)
    }

    /// The outputs from the stored state and this cycle's inputs; the edge's clear, then pop,
    /// then push. A pop from empty (underflow) or a push into full (overflow) does nothing
    /// but report itself on `error`.
    #[inline(always)]
    pub fn eval(&mut self) {
        self.occupancy.set_bits(self.len.q().bits());
        self.buf.eval();
        let d = self.depth();
        let (mut head, mut len) = (self.head.q().bits() as usize, self.len());
        if self.clear.is_high() {
            (head, len) = (0, 0);
        }
        let mut fault = None;
        if self.pop.is_high() {
            if len > 0 {
                head = if head + 1 == d { 0 } else { head + 1 };
                len -= 1;
            } else {
                fault = Some(FifoError::Underflow);
            }
        }
        if self.push.is_high() {
            if len < d {
                self.buf.write(wrap(head + len, d), self.push_data.bits());
                len += 1;
                if len > self.max_occupancy() {
                    self.max.set_next_bits(len as u64);
                }
            } else {
                fault = fault.or(Some(FifoError::Overflow));
            }
        }
        self.error.set_bits(fault.map_or(0, FifoError::code));
        self.head.set_next_bits(head as u64);
        self.len.set_next_bits(len as u64);
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
