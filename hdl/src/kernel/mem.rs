//! A behavioural synchronous memory: a register file, a FIFO's storage, a line buffer.
//!
//! Two-process like every module: its owner's `eval` reads words combinationally
//! ([`Mem::read`], the contents at the last edge) and stages at most one write
//! ([`Mem::write`]) after clearing the port with [`Mem::eval`]; the clock edge commits the
//! write (none under reset; the contents survive reset, as a RAM's do). The write port is
//! traced in the memory's own scope (`we`, `waddr`, `wdata`), so a write shows in the
//! waveform and the schedule check compares it between two evaluations. A small memory can
//! show its words too ([`Mem::show_words`]: a FIFO's or a register file's contents in the
//! waveform, each word a signal `word<k>` of the memory's scope).

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
    /// Every word as a signal, when shown ([`Mem::show_words`]); else empty.
    shown: Vec<Signal>,
}

/// The most words [`Mem::show_words`] shows.
pub const MAX_SHOWN_WORDS: usize = 1024;

/// The name of shown word `k` (`word<k>`), made once for the process.
fn word_name(k: usize) -> &'static str {
    static NAMES: std::sync::OnceLock<Vec<&'static str>> = std::sync::OnceLock::new();
    NAMES.get_or_init(|| {
        (0..MAX_SHOWN_WORDS)
            .map(|k| &*Box::leak(format!("word{k}").into_boxed_str()))
            .collect()
    })[k]
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
            shown: Vec::new(),
        }
    }

    /// The same memory with every word a signal of its scope (`word0`, `word1`, ...), traced
    /// and compared by the schedule check like a register: its contents in the waveform. For
    /// memories of at most [`MAX_SHOWN_WORDS`] words; each costs a store per write and a
    /// value per traced cycle.
    #[track_caller]
    pub fn show_words(mut self) -> Mem {
        assert!(
            self.words.len() <= MAX_SHOWN_WORDS,
            "{}: {} words; show_words shows at most {MAX_SHOWN_WORDS}",
            self.name,
            self.words.len()
        );
        let fmt = self.wdata.fmt();
        self.shown = (0..self.words.len())
            .map(|k| {
                let mut s = Signal::new(word_name(k), fmt);
                s.bits = self.words[k];
                s
            })
            .collect();
        self
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
            let k = self.waddr.bits() as usize;
            self.words[k] = self.wdata.bits();
            if let Some(w) = self.shown.get_mut(k) {
                w.bits = self.wdata.bits();
            }
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.name, "mem");
        v.signal(Dir::Wire, &self.we);
        v.signal(Dir::Wire, &self.waddr);
        v.signal(Dir::Wire, &self.wdata);
        for w in &self.shown {
            v.signal(Dir::Reg, w);
        }
        v.leave();
    }
    #[inline]
    fn visit_bits<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.we.bits());
        f(self.waddr.bits());
        f(self.wdata.bits());
        for w in &self.shown {
            f(w.bits);
        }
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

    /// Shown words follow the contents, visited after the write port in the memory's scope.
    #[test]
    fn shown_words_are_the_contents() {
        use crate::kernel::signal_paths;
        let mut sim = Sim::new(Mem::new("ram", 3, Format::uint(8)).show_words());
        let paths = signal_paths(&sim.dut);
        assert_eq!(
            paths,
            [
                "ram.we",
                "ram.waddr",
                "ram.wdata",
                "ram.word0",
                "ram.word1",
                "ram.word2"
            ]
        );
        sim.dut.eval();
        sim.dut.write(2, 99);
        sim.tick();
        let mut bits = Vec::new();
        sim.dut.visit_bits(&mut |b| bits.push(b));
        assert_eq!(bits[3..], [0, 0, 99]);
        assert_eq!(word_name(1023), "word1023");
    }

    #[test]
    #[should_panic(expected = "ram: 1025 words; show_words shows at most 1024")]
    fn a_memory_too_big_to_show_is_refused() {
        let _ = Mem::new("ram", 1025, Format::uint(8)).show_words();
    }

    #[test]
    #[should_panic(expected = "word 5 of 5")]
    fn a_write_beyond_the_words_is_refused() {
        Mem::new("ram", 5, Format::uint(8)).write(5, 1);
    }
}
