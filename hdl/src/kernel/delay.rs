//! A delay line: a bundle of signals delayed by a fixed number of register stages, the
//! pipeline registers that carry values alongside a datapath.
//!
//! Modelled as the shift register it is, but stored as a ring buffer: one write and one read
//! per signal per cycle, whatever the depth. The edge stores the inputs as `eval` left them
//! (a module's inputs do not change between its `eval` and the edge), so no next-value copy
//! is kept.

use super::module::{Dir, Module, Visitor};
use super::signal::Signal;
use crate::fx::Format;

/// `depth` register stages for each of a bundle of signals. Depth 0 is a wire.
#[derive(Clone, Debug)]
pub struct Delay {
    name: String,
    /// The inputs, one a signal.
    pub i: Vec<Signal>,
    /// The outputs, each its input `depth` cycles later.
    pub o: Vec<Signal>,
    depth: usize,
    /// `depth` slots of `n` values; `head` is the oldest (the stage the outputs show).
    ring: Vec<u64>,
    head: usize,
}

impl Delay {
    /// Inputs named and formatted by `sigs`, outputs named by `out_names`.
    pub fn new(
        name: &str,
        sigs: &[(&'static str, Format)],
        depth: usize,
        out_names: &[&'static str],
    ) -> Delay {
        assert_eq!(sigs.len(), out_names.len());
        let n = sigs.len();
        Delay {
            name: name.into(),
            i: sigs.iter().map(|(n, f)| Signal::new(n, *f)).collect(),
            o: sigs
                .iter()
                .zip(out_names)
                .map(|((_, f), n)| Signal::new(n, *f))
                .collect(),
            depth,
            ring: vec![0; depth * n],
            head: 0,
        }
    }

    /// Cycles of delay.
    pub fn depth(&self) -> usize {
        self.depth
    }
}

impl Module for Delay {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "delay"
    }
    #[inline(always)]
    fn eval(&mut self) {
        let n = self.i.len();
        if self.depth == 0 {
            for (o, i) in self.o.iter_mut().zip(&self.i) {
                o.follow(i);
            }
            return;
        }
        // The ring holds only values the inputs held, each checked against the format that
        // the output shares, so the outputs take them without a second check.
        let oldest = &self.ring[self.head * n..(self.head + 1) * n];
        for (o, &old) in self.o.iter_mut().zip(oldest) {
            o.set_checked_bits(old);
        }
    }
    #[inline(always)]
    fn tick(&mut self, reset: bool) {
        if self.depth == 0 {
            return;
        }
        let n = self.i.len();
        if reset {
            self.ring.fill(0);
            self.head = 0;
            return;
        }
        // The oldest slot takes the inputs and becomes the youngest stage.
        let slot = &mut self.ring[self.head * n..(self.head + 1) * n];
        for (r, i) in slot.iter_mut().zip(&self.i) {
            *r = i.bits();
        }
        self.head += 1;
        if self.head == self.depth {
            self.head = 0;
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        for s in &self.i {
            v.signal(Dir::Input, s);
        }
        for s in &self.o {
            v.signal(Dir::Output, s);
        }
        v.leave();
    }
    #[inline]
    fn visit_bits<F: FnMut(u64)>(&self, f: &mut F) {
        self.i.iter().chain(&self.o).for_each(|s| f(s.bits()));
    }
}
