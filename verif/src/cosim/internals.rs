//! What an explained run shows around a difference: the RTL's internals, dumped by a second
//! run of the same build and sampled as the ports are, and the model's, every signal of its
//! hierarchy from a fresh run of the same stimulus.

use super::{rtl, Simulator, INTERNALS_AFTER, INTERNALS_BEFORE};
use hdl::kernel::{Dir, Module, Signal, Sim, Visitor};
use std::ops::Range;

/// The cycles shown around a first difference at `first` in a run of `cycles`.
pub(super) fn window(first: usize, cycles: usize) -> Range<usize> {
    first.saturating_sub(INTERNALS_BEFORE)..(first + INTERNALS_AFTER + 1).min(cycles)
}

/// The RTL's internals around cycle `first`, sampled as the ports are.
pub(super) fn internals(
    sim: Simulator,
    run: &rtl::RtlRun,
    got: &[Vec<Option<u64>>],
    first: usize,
) -> Result<Internals, String> {
    let Range {
        start: from,
        end: to,
    } = window(first, run.cycles);
    let vcd = rtl::internals(sim, run, got, (from, to))
        .map_err(|e| format!("the RTL's internals are not in the waveform: {e}"))?;
    let mut sampled = waves::sample::sample(&vcd, &["tb", "dut"], from..to, rtl::sampled_before_ps)
        .map_err(|e| format!("the RTL's internals are not in the waveform: {e}"))?;
    // The clock is sampled before its edge: always low, nothing to see.
    if let Some(k) =
        (run.clocking.as_ref()).and_then(|c| sampled.signals.iter().position(|s| s.0 == c.clock))
    {
        sampled.signals.remove(k);
        sampled.values.iter_mut().for_each(|v| _ = v.remove(k));
    }
    ordered(&mut sampled);
    Ok(Internals { sampled })
}

/// Orders the signals by scope and name, numbers by value (`mem[2]` before `mem[10]`),
/// whatever order the simulator dumped them in, so both simulators show one view (a scope's
/// signals together, as [`waves::sample::Sampled`] has them); the top's parameters go
/// last, so the view opens on signals: a constant named in capitals (Verilator dumps
/// parameters as wires; Icarus leaves them out).
fn ordered(s: &mut waves::sample::Sampled) {
    let parameter = |k: usize| {
        let name = &s.signals[k].0;
        let capitals = |c: char| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_';
        let constant = s.values.windows(2).all(|w| w[0][k] == w[1][k]);
        !name.contains('.') && name.chars().all(capitals) && constant
    };
    let mut order: Vec<usize> = (0..s.signals.len()).collect();
    // By scope, then name: a scope's signals stay together.
    let key = |k: usize| {
        let path: Vec<Vec<Part>> = s.signals[k].0.split('.').map(natural).collect();
        (parameter(k), path)
    };
    order.sort_by_cached_key(|&k| key(k));
    s.signals = order.iter().map(|&k| s.signals[k].clone()).collect();
    for row in &mut s.values {
        *row = order.iter().map(|&k| row[k]).collect();
    }
}

/// A part of a name for [`natural`]: a run of digits, by value, before any text.
#[derive(PartialEq, Eq, PartialOrd, Ord)]
enum Part {
    Number(u128, usize),
    Text(String),
}

/// `name` as runs of digits and of other characters: the key of a natural order.
fn natural(name: &str) -> Vec<Part> {
    let mut parts = Vec::new();
    let mut rest = name;
    while let Some(c) = rest.chars().next() {
        let digit = c.is_ascii_digit();
        let end = rest
            .find(|x: char| x.is_ascii_digit() != digit)
            .unwrap_or(rest.len());
        let (run, after) = rest.split_at(end);
        parts.push(match run.parse::<u128>() {
            // Its length too: `07` and `7` are different names.
            Ok(n) if digit => Part::Number(n, run.len()),
            _ => Part::Text(run.to_string()),
        });
        rest = after;
    }
    parts
}

/// The RTL's internals read back.
pub(super) struct Internals {
    /// The signals and their values.
    pub(super) sampled: waves::sample::Sampled,
}

impl Internals {
    pub(super) fn said(&self) -> String {
        let s = &self.sampled;
        let skipped = match s.skipped {
            0 => String::new(),
            n => format!(
                " ({n} more left out: wider than 64 bits, real, or beyond the first {})",
                waves::sample::MAX_SIGNALS
            ),
        };
        format!(
            "the RTL's internals, {} signals{skipped}, are in the waveform under tb.rtl_internals, cycles {}..{}",
            s.signals.len(),
            s.cycles.start,
            s.cycles.end
        )
    }
}

/// Every signal of a model's hierarchy over a window of cycles, as an explained run shows it
/// beside the RTL's internals ([`super::CosimModel::internals`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelInternals {
    /// Each signal's path below the top (`wptr`, `ram.word0`), width and signedness, in the
    /// order the model visits them: its ports, registers and wires, then its children's.
    pub signals: Vec<(String, u32, bool)>,
    /// The signals with named values (FSM states): each one's index in `signals` and its
    /// names, shown by name in the waveform's view.
    pub states: Vec<(usize, &'static [&'static str])>,
    /// The cycles shown.
    pub cycles: Range<usize>,
    /// `values[i][k]`: signal `k` in cycle `cycles.start + i`, read when the outputs are
    /// (inputs settled, the clock edge not yet taken).
    pub values: Vec<Vec<u64>>,
}

impl ModelInternals {
    /// Runs `dut` as built on the first `cycles.end` cycles of `stim` (the first `resets` in
    /// reset), each cycle's inputs set by `drive`, and keeps every signal's value in `cycles`.
    pub fn of<M: Module>(
        dut: M,
        drive: &dyn Fn(&mut M, &[u64]),
        stim: &[Vec<u64>],
        resets: usize,
        cycles: Range<usize>,
    ) -> ModelInternals {
        let mut paths = Paths::default();
        dut.visit(&mut paths);
        let mut sim = Sim::new(dut);
        let mut values = Vec::with_capacity(cycles.len());
        for (c, inputs) in stim.iter().enumerate().take(cycles.end) {
            sim.set_reset(c < resets);
            drive(&mut sim.dut, inputs);
            sim.eval();
            if c >= cycles.start {
                let mut row = Vec::with_capacity(paths.signals.len());
                sim.dut.visit_bits(&mut |b| row.push(b));
                values.push(row);
            }
            sim.tick();
        }
        let cycles = cycles.start..cycles.start + values.len();
        ModelInternals {
            signals: paths.signals,
            states: paths.states,
            cycles,
            values,
        }
    }

    /// What the waveform shows of them.
    pub(super) fn said(&self) -> String {
        format!(
            "the model's, {} signals, under tb.model_internals",
            self.signals.len()
        )
    }
}

/// The path below the top, width and signedness of every signal a module visits.
#[derive(Default)]
struct Paths {
    scopes: Vec<String>,
    signals: Vec<(String, u32, bool)>,
    states: Vec<(usize, &'static [&'static str])>,
}

impl Visitor for Paths {
    fn enter(&mut self, instance: &str, _: &str) {
        self.scopes.push(instance.to_string());
    }
    fn leave(&mut self) {
        self.scopes.pop();
    }
    fn signal(&mut self, _: Dir, s: &Signal) {
        // The top's own scope is the waveform's `model_internals`.
        let below: Vec<&str> = (self.scopes.iter().skip(1).map(String::as_str))
            .chain([s.name()])
            .collect();
        if let Some(names) = s.states() {
            self.states.push((self.signals.len(), names));
        }
        let f = s.fmt();
        self.signals
            .push((below.join("."), f.width(), f.is_signed()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hdl::fx::Format;
    use hdl::kernel::{Mem, Reg};

    /// A counter whose count is also written into a two-word memory, a child.
    #[derive(Clone)]
    struct Counter {
        en: Signal,
        count: Reg,
        ram: Mem,
    }

    impl Module for Counter {
        fn kind(&self) -> &'static str {
            "counter"
        }
        fn eval(&mut self) {
            self.ram.eval();
            if self.en.is_high() {
                let next = (self.count.q().bits() + 1) & 7;
                self.count.set_next_bits(next);
                self.ram.write((next & 1) as usize, next);
            }
        }
        fn tick(&mut self, reset: bool) {
            self.count.tick(reset);
            self.ram.tick(reset);
        }
        fn visit(&self, v: &mut dyn Visitor) {
            v.enter("counter", "counter");
            v.signal(Dir::Input, &self.en);
            v.reg(&self.count);
            self.ram.visit(v);
            v.leave();
        }
    }

    /// Every signal below the top by its path, each cycle's values as the outputs are read:
    /// the register before its edge, the memory's words as the last edge left them.
    #[test]
    fn a_model_s_internals_are_every_signal_in_the_window() {
        let dut = counter();
        let drive = |d: &mut Counter, v: &[u64]| d.en.set_bits(v[0]);
        let stim: Vec<Vec<u64>> = [1, 1, 1, 0, 1, 1, 1, 1].iter().map(|&e| vec![e]).collect();
        let m = ModelInternals::of(dut, &drive, &stim, 1, 3..6);
        let names: Vec<&str> = m.signals.iter().map(|s| s.0.as_str()).collect();
        let want = [
            "en",
            "count",
            "ram.we",
            "ram.waddr",
            "ram.wdata",
            "ram.word0",
            "ram.word1",
        ];
        assert_eq!(names, want);
        assert_eq!(m.signals[1], ("count".to_string(), 3, false));
        assert_eq!(
            m.states,
            [(0, &["OFF", "ON"][..])],
            "named values, by index"
        );
        assert_eq!(m.cycles, 3..6);
        // Reset in cycle 0; counts 1 and 2 in cycles 1 and 2 (word 1, then word 0); cycle 3
        // holds, its port idle; cycles 4 and 5 count on.
        assert_eq!(m.values[0], [0, 2, 0, 0, 2, 2, 1]);
        assert_eq!(m.values[1], [1, 2, 1, 1, 3, 2, 1]);
        assert_eq!(m.values[2], [1, 3, 1, 0, 4, 2, 3]);
        assert_eq!(m.said(), "the model's, 7 signals, under tb.model_internals");
        // A stimulus shorter than the window: the cycles it has.
        let short = ModelInternals::of(counter(), &drive, &stim[..4], 1, 3..6);
        assert_eq!((short.cycles, short.values.len()), (3..4, 1));
    }

    fn counter() -> Counter {
        Counter {
            en: Signal::bit("en").with_states(&["OFF", "ON"]),
            count: Reg::new("count", Format::uint(3)),
            ram: Mem::new("ram", 2, Format::uint(3)).show_words(),
        }
    }

    #[test]
    fn names_are_ordered_with_their_numbers_by_value() {
        let mut names = ["mem[10]", "mem[2]", "b", "a10", "a9", "mem[1]", "a09"];
        names.sort_by_cached_key(|n| natural(n));
        assert_eq!(
            names,
            ["a9", "a09", "a10", "b", "mem[1]", "mem[2]", "mem[10]"]
        );
        let mut s = waves::sample::Sampled {
            signals: vec![
                ("WIDTH".into(), 32),
                ("x10".into(), 1),
                ("g.b".into(), 1),
                ("g_h".into(), 1),
                ("x2".into(), 1),
                ("g.a".into(), 1),
            ],
            cycles: 0..2,
            values: vec![vec![Some(8), Some(0), Some(3), Some(4), Some(1), Some(5)]; 2],
            skipped: 0,
        };
        ordered(&mut s);
        let names: Vec<&str> = s.signals.iter().map(|s| s.0.as_str()).collect();
        assert_eq!(
            names,
            ["g.a", "g.b", "g_h", "x2", "x10", "WIDTH"],
            "a parameter last"
        );
        let values = [Some(5), Some(3), Some(4), Some(1), Some(0), Some(8)];
        assert_eq!(s.values[1], values);
    }
}
