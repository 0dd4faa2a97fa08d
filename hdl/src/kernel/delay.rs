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

/// `depth` register stages for each of a bundle of `N` signals. Depth 0 is a wire.
///
/// The bundle's size is a type parameter, so the per-signal copies of `eval` and `tick`
/// unroll into straight-line code (no loop or bounds check per signal).
#[derive(Clone, Debug)]
pub struct Delay<const N: usize> {
    name: String,
    /// The inputs, one a signal.
    pub i: [Signal; N],
    /// The outputs, each its input `depth` cycles later.
    pub o: [Signal; N],
    depth: usize,
    /// `depth` slots of `N` values; `head` is the oldest (the stage the outputs show).
    ring: Vec<[u64; N]>,
    head: usize,
}

impl<const N: usize> Delay<N> {
    /// Inputs named and formatted by `sigs`, outputs named by `out_names`.
    pub fn new(
        name: &str,
        sigs: [(&'static str, Format); N],
        depth: usize,
        out_names: [&'static str; N],
    ) -> Delay<N> {
        Delay {
            name: name.into(),
            i: sigs.map(|(n, f)| Signal::new(n, f)),
            o: std::array::from_fn(|k| Signal::new(out_names[k], sigs[k].1)),
            depth,
            ring: vec![[0; N]; depth],
            head: 0,
        }
    }

    /// Cycles of delay.
    pub fn depth(&self) -> usize {
        self.depth
    }
}

impl<const N: usize> Module for Delay<N> {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "delay"
    }
    #[inline(always)]
    fn eval(&mut self) {
        let Some(oldest) = self.ring.get(self.head) else {
            // Depth 0: a wire.
            for (o, i) in self.o.iter_mut().zip(&self.i) {
                o.follow(i);
            }
            return;
        };
        // The ring holds only values the inputs held, each checked against the format that
        // the output shares, so the outputs take them without a second check.
        for (o, &old) in self.o.iter_mut().zip(oldest) {
            o.set_checked_bits(old);
        }
    }
    #[inline(always)]
    fn tick(&mut self, reset: bool) {
        if reset {
            self.ring.fill([0; N]);
            self.head = 0;
            return;
        }
        let Some(slot) = self.ring.get_mut(self.head) else {
            return;
        };
        // The oldest slot takes the inputs and becomes the youngest stage.
        *slot = std::array::from_fn(|k| self.i[k].bits());
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
