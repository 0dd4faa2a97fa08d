//! A behavioural synchronous memory: a register file, a FIFO's storage, a line buffer.
//!
//! Two-process like every module: its owner's `eval` reads words combinationally
//! ([`Mem::read`], the contents at the last edge) and stages at most one write
//! ([`Mem::write`]) after clearing the port with [`Mem::eval`]; the clock edge commits the
//! write (none under reset; the contents survive reset, as a RAM's do). The write port is
//! traced in the memory's own scope (`we`, `waddr`, `wdata`), so a write shows in the
//! waveform and the schedule check compares it between two evaluations.

use super::module::{Dir, Module, Visitor};
use super::signal::Signal;
use crate::fx::Format;

/// `depth` words of a declared format, one write port.
#[derive(Clone, Debug)]
pub struct Mem {
    name: &'static str,
    words: Vec<u64>,
    we: Signal,
    waddr: Signal,
    wdata: Signal,
}

impl Mem {
    /// `depth >= 1` words of `fmt`, all zero; `name` is its scope in the waveform.
    pub fn new(name: &'static str, depth: usize, fmt: Format) -> Mem {
        assert!(depth >= 1, "{name}: a memory of no words");
        let abits = (usize::BITS - (depth - 1).leading_zeros()).max(1);
        Mem {
            name,
            words: vec![0; depth],
            we: Signal::bit("we"),
            waddr: Signal::new("waddr", Format::uint(abits)),
            wdata: Signal::new("wdata", fmt),
        }
    }

    /// Words held.
    #[inline]
    pub fn depth(&self) -> usize {
        self.words.len()
    }

    /// Word `addr`'s bits as the last edge left them.
    #[inline]
    pub fn read(&self, addr: usize) -> u64 {
        self.words[addr]
    }

    /// This cycle's port: no write (call first in the owner's `eval`).
    #[inline]
    pub fn eval(&mut self) {
        self.we.set_bool(false);
    }

    /// Writes `bits` into word `addr` at the coming edge (checked against the word's format;
    /// the last write of a cycle wins).
    #[inline]
    #[track_caller]
    pub fn write(&mut self, addr: usize, bits: u64) {
        assert!(
            addr < self.words.len(),
            "{}: word {addr} of {}",
            self.name,
            self.words.len()
        );
        self.we.set_bool(true);
        self.waddr.set_bits(addr as u64);
        self.wdata.set_bits(bits);
    }
}

impl Module for Mem {
    fn instance(&self) -> &str {
        self.name
    }
    fn kind(&self) -> &'static str {
        "mem"
    }
    #[inline]
    fn eval(&mut self) {
        Mem::eval(self);
    }
    #[inline]
    fn tick(&mut self, reset: bool) {
        if !reset && self.we.is_high() {
            self.words[self.waddr.bits() as usize] = self.wdata.bits();
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.name, "mem");
        v.signal(Dir::Wire, &self.we);
        v.signal(Dir::Wire, &self.waddr);
        v.signal(Dir::Wire, &self.wdata);
        v.leave();
    }
    #[inline]
    fn visit_bits<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.we.bits());
        f(self.waddr.bits());
        f(self.wdata.bits());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Sim;

    #[test]
    fn a_write_lands_at_the_edge_and_survives_reset() {
        let mut sim = Sim::new(Mem::new("ram", 5, Format::uint(8))).check_schedule(true);
        assert_eq!(sim.dut.waddr.width(), 3);
        sim.dut.eval();
        sim.dut.write(4, 200);
        assert_eq!(sim.dut.read(4), 0, "not before the edge");
        sim.tick();
        assert_eq!(sim.dut.read(4), 200);
        // A cycle with no write keeps every word; a write under reset is dropped.
        sim.step();
        assert_eq!(sim.dut.read(4), 200);
        sim.dut.eval();
        sim.dut.write(0, 7);
        sim.dut.tick(true);
        assert_eq!((sim.dut.read(0), sim.dut.read(4)), (0, 200));
    }

    #[test]
    #[should_panic(expected = "word 5 of 5")]
    fn a_write_beyond_the_words_is_refused() {
        Mem::new("ram", 5, Format::uint(8)).write(5, 1);
    }
}
