//! A delay line: a bundle of signals delayed by a fixed number of register stages, the
//! pipeline registers that carry values alongside a datapath.

use super::module::{Dir, Module, Visitor};
use super::signal::{Reg, Signal};
use crate::fx::Format;

/// `depth` register stages for each of a bundle of signals. Depth 0 is a wire.
#[derive(Clone, Debug)]
pub struct Delay {
    name: String,
    pub i: Vec<Signal>,
    pub o: Vec<Signal>,
    stages: Vec<Vec<Reg>>,
}

impl Delay {
    /// Signals named and formatted by `sigs`; each output is named `<name>_d<depth>`.
    pub fn new(
        name: &str,
        sigs: &[(&'static str, Format)],
        depth: usize,
        out_names: &[&'static str],
    ) -> Delay {
        assert_eq!(sigs.len(), out_names.len());
        Delay {
            name: name.into(),
            i: sigs.iter().map(|(n, f)| Signal::new(n, *f)).collect(),
            o: sigs
                .iter()
                .zip(out_names)
                .map(|((_, f), n)| Signal::new(n, *f))
                .collect(),
            stages: (0..depth)
                .map(|_| sigs.iter().map(|(n, f)| Reg::new(n, *f)).collect())
                .collect(),
        }
    }

    pub fn depth(&self) -> usize {
        self.stages.len()
    }
}

impl Module for Delay {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "delay"
    }
    fn eval(&mut self) {
        let n = self.i.len();
        match self.stages.len() {
            0 => {
                for k in 0..n {
                    let b = self.i[k].bits();
                    self.o[k].set_bits(b);
                }
            }
            d => {
                for k in 0..n {
                    let b = self.i[k].bits();
                    self.stages[0][k].set_next_bits(b);
                }
                for s in 1..d {
                    for k in 0..n {
                        let b = self.stages[s - 1][k].q().bits();
                        self.stages[s][k].set_next_bits(b);
                    }
                }
                for k in 0..n {
                    let b = self.stages[d - 1][k].q().bits();
                    self.o[k].set_bits(b);
                }
            }
        }
    }
    fn tick(&mut self, reset: bool) {
        for r in self.stages.iter_mut().flatten() {
            r.tick(reset);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        for s in &self.i {
            v.signal(Dir::Input, s);
        }
        for s in &self.o {
            v.signal(Dir::Output, s);
        }
        v.leave();
    }
}
