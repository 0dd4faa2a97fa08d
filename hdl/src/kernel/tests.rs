//! Kernel tests on a small nested design: a combinational incrementer feeding a combinational
//! doubler feeding a registered accumulator.

use super::*;
use crate::fx::{Format, Fx};
use crate::signals;

struct Inc {
    a: Signal,
    y: Signal,
}
impl Module for Inc {
    fn instance(&self) -> &str {
        "inc"
    }
    fn kind(&self) -> &'static str {
        "inc"
    }
    fn eval(&mut self) {
        self.y.set_raw(self.a.raw() + 1);
    }
    fn tick(&mut self, _: bool) {}
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter("inc", "inc");
        signals!(v; Input: self.a; Output: self.y);
        v.leave();
    }
}

struct Top {
    x: Signal,
    acc_out: Signal,
    inc: Inc,
    dbl: Signal,
    acc: Reg,
    good_order: bool,
}

impl Top {
    fn new(good_order: bool) -> Top {
        Top {
            x: Signal::new("x", Format::uint(4)),
            acc_out: Signal::new("acc_out", Format::uint(12)),
            inc: Inc {
                a: Signal::new("a", Format::uint(4)),
                y: Signal::new("y", Format::uint(5)),
            },
            dbl: Signal::new("dbl", Format::uint(6)),
            acc: Reg::new("acc", Format::uint(12)),
            good_order,
        }
    }
}

impl Module for Top {
    fn instance(&self) -> &str {
        "top"
    }
    fn kind(&self) -> &'static str {
        "top"
    }
    fn eval(&mut self) {
        if self.good_order {
            self.inc.a.set_bits(self.x.bits());
            self.inc.eval();
            self.dbl.set_raw(self.inc.y.raw() * 2);
        } else {
            // Reads the child's output before evaluating it: a schedule bug.
            self.dbl.set_raw(self.inc.y.raw() * 2);
            self.inc.a.set_bits(self.x.bits());
            self.inc.eval();
        }
        let sum = self.acc.q().fx() + self.dbl.fx();
        self.acc.set_next(sum.convert(
            Format::uint(12),
            crate::fx::Quant::Trunc,
            crate::fx::Overflow::Wrap,
        ));
        self.acc_out.set_bits(self.acc.q().bits());
    }
    fn tick(&mut self, reset: bool) {
        self.acc.tick(reset);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter("top", "top");
        signals!(v; Input: self.x; Output: self.acc_out; Wire: self.dbl; Reg: self.acc);
        self.inc.visit(v);
        v.leave();
    }
}

/// A simulation a panic unwinds leaves the cycle it was in, once; one that finishes, none.
#[test]
fn a_simulation_that_panics_says_in_which_cycle() {
    let _ = panicked_in_cycle();
    let run = |cycles: u64| {
        std::panic::catch_unwind(move || {
            let mut sim = Sim::new(Top::new(true));
            sim.reset(2);
            for c in 0..cycles {
                // x is 4 bits: 16 does not fit, in the cycle after 16 edges of x = c.
                sim.dut.x.set_bits(c);
                sim.step();
            }
        })
    };
    assert!(run(16).is_ok());
    assert_eq!(panicked_in_cycle(), None);
    assert!(run(40).is_err());
    assert_eq!(
        panicked_in_cycle(),
        Some(2 + 16),
        "two cycles of reset, then x = 0..15"
    );
    assert_eq!(panicked_in_cycle(), None, "taken");
}

#[test]
fn nested_design_accumulates_and_resets() {
    let mut sim = Sim::new(Top::new(true)).check_schedule(true);
    sim.reset(2);
    let mut model = 0u64;
    for c in 0..40u64 {
        sim.dut.x.set_bits(c % 16);
        sim.eval();
        assert_eq!(sim.dut.acc_out.bits(), model, "cycle {c}");
        model = (model + 2 * (c % 16 + 1)) % 4096;
        sim.tick();
    }
    sim.set_reset(true);
    sim.step();
    sim.set_reset(false);
    sim.eval();
    assert_eq!(sim.dut.acc_out.bits(), 0);
    assert_eq!(sim.cycle(), 43);
}

#[test]
#[should_panic(expected = "schedule error")]
fn wrong_evaluation_order_is_caught() {
    let mut sim = Sim::new(Top::new(false)).check_schedule(true);
    for c in 0..4 {
        sim.dut.x.set_bits(c);
        sim.step();
    }
}

#[test]
fn paths_are_hierarchical() {
    let p = signal_paths(&Top::new(true));
    assert_eq!(
        p,
        [
            "top.x",
            "top.acc_out",
            "top.dbl",
            "top.acc",
            "top.inc.a",
            "top.inc.y"
        ]
    );
}

#[test]
fn register_holds_when_not_written() {
    let mut r = Reg::with_reset("r", Format::sint(6), Fx::from_int(Format::sint(6), -5));
    assert_eq!(r.q().raw(), -5);
    r.set_next_raw(7);
    r.tick(false);
    assert_eq!(r.q().raw(), 7);
    r.tick(false);
    assert_eq!(r.q().raw(), 7, "hold");
    r.tick(true);
    assert_eq!(r.q().raw(), -5, "reset value");
}

#[test]
fn signals_check_every_write() {
    let mut s = Signal::new("s", Format::signed(6, 2));
    s.set_raw(-32);
    assert_eq!(s.bits(), 0x20);
    assert_eq!(s.raw(), -32);
    assert_eq!(s.fx().to_string(), "-8");
    s.set(Fx::from_raw(Format::signed(3, 0), 3));
    assert_eq!(s.raw(), 12);
    type Write = fn(&mut Signal);
    let cases: [(&str, Write); 4] = [
        ("raw 32", |s| s.set_raw(32)),
        ("bits 0x40", |s| s.set_bits(0x40)),
        ("inexact", |s| s.set(Fx::from_raw(Format::signed(4, 3), 1))),
        ("too big", |s| s.set(Fx::from_int(Format::sint(8), 8))),
    ];
    for (what, f) in cases {
        let mut t = s.clone();
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(&mut t)));
        assert!(r.is_err(), "{what} was accepted");
    }
    let mut r = Reg::new("r", Format::uint(3));
    let e = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| r.set_next_raw(8)));
    assert!(e.is_err());
    assert!(std::panic::catch_unwind(|| Signal::new("w", Format::uint(65))).is_err());
}

/// The one-compare checks take exactly the values the full ones take, at every width: a
/// pattern fits up to `2^width - 1`, a raw value the format's range; a bool always (as bits),
/// and as a next raw value 1 is refused only by a signed bit.
#[test]
fn bit_pattern_and_bool_checks_at_every_width() {
    let fits = |f: &(dyn Fn() + std::panic::RefUnwindSafe)| std::panic::catch_unwind(f).is_ok();
    for width in 1..=64u32 {
        for signed in [false, true] {
            let fmt = Format::new(width, 0, signed);
            let top = u64::MAX >> (64 - width);
            // A write to a signal and the same to a register's next value: both fit or not.
            let both = |sig: &(dyn Fn(&mut Signal) + std::panic::RefUnwindSafe),
                        reg: &(dyn Fn(&mut Reg) + std::panic::RefUnwindSafe),
                        ok: bool,
                        what: String| {
                assert_eq!(
                    fits(&|| sig(&mut Signal::new("s", fmt))),
                    ok,
                    "{fmt} {what}"
                );
                assert_eq!(
                    fits(&|| reg(&mut Reg::new("r", fmt))),
                    ok,
                    "{fmt} next {what}"
                );
            };
            for bits in [0, 1, top, top.wrapping_add(1), top << 1, u64::MAX] {
                let ok = bits & !top == 0;
                both(
                    &|s| s.set_bits(bits),
                    &|r| r.set_next_bits(bits),
                    ok,
                    format!("{bits:#x}"),
                );
            }
            let (lo, hi) = (fmt.min_raw(), fmt.max_raw());
            for raw in [lo - 1, lo, lo + 1, -1, 0, 1, hi - 1, hi, hi + 1] {
                let ok = raw >= lo && raw <= hi;
                // A raw value is an i64: outside it there is nothing to write.
                let Ok(r) = i64::try_from(raw) else { continue };
                both(
                    &|s| s.set_raw(r),
                    &|g| g.set_next_raw(r),
                    ok,
                    format!("raw {r}"),
                );
            }
            for b in [false, true] {
                let mut s = Signal::new("s", fmt);
                s.set_bool(b);
                assert_eq!(s.bits(), u64::from(b));
                let ok = !(b && signed && width == 1);
                let mut r = Reg::new("r", fmt);
                let set = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    r.set_next_bool(b);
                }));
                assert_eq!(set.is_ok(), ok, "{fmt} next {b}");
                if ok {
                    r.tick(false);
                    assert_eq!(r.q().bits(), u64::from(b));
                }
            }
        }
    }
}

/// A counter whose `tick` also writes its output port: the two-process rule broken at the
/// edge.
struct EdgeWriter {
    count: Reg,
    out: Signal,
}
impl Module for EdgeWriter {
    fn instance(&self) -> &str {
        "edge_writer"
    }
    fn kind(&self) -> &'static str {
        "edge_writer"
    }
    fn eval(&mut self) {
        let n = (self.count.q().bits() + 1) & 0xf;
        self.count.set_next_bits(n);
    }
    fn tick(&mut self, reset: bool) {
        self.count.tick(reset);
        // Wrong: a port driven at the clock edge instead of in eval.
        self.out.set_bits(self.count.q().bits());
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter("edge_writer", "edge_writer");
        signals!(v; Output: self.out; Reg: self.count);
        v.leave();
    }
}

#[test]
#[should_panic(expected = "two-process error at cycle 0: 'edge_writer.out' (Output)")]
fn a_tick_that_writes_a_signal_is_caught() {
    let mut sim = Sim::new(EdgeWriter {
        count: Reg::new("count", Format::uint(4)),
        out: Signal::new("out", Format::uint(4)),
    })
    .check_schedule(true);
    for _ in 0..3 {
        sim.step();
    }
}

#[test]
fn registers_may_change_at_the_edge() {
    // The same counter without the port write passes both checks.
    let mut sim = Sim::new(Top::new(true)).check_schedule(true);
    sim.reset(1);
    for _ in 0..5 {
        sim.step();
    }
    assert_eq!(instances(&sim.dut).len(), 2);
}

/// A wire between two formats is caught wherever the tests run (debug builds): the format
/// check, and the value check behind it, are what let release builds copy unchecked.
#[test]
#[cfg(debug_assertions)]
#[should_panic(expected = "'narrow' <- 'wide'")]
fn follow_between_formats_panics_in_debug_builds() {
    let mut wide = Signal::new("wide", Format::uint(9));
    wide.set_bits(0x1ff);
    let mut narrow = Signal::new("narrow", Format::uint(8));
    narrow.follow(&wide);
}

/// A delay line is named as its parent asked: its waveform scope is that name.
#[test]
fn a_delay_line_is_the_instance_it_was_named() {
    let d = Delay::new("align_3", [("x", Format::uint(4))], 3, ["x_out"]);
    assert_eq!(d.instance(), "align_3");
    assert_eq!(d.kind(), "delay");
    assert_eq!(
        instances(&d),
        [("align_3".to_string(), "delay".to_string())]
    );
}

/// A state register's names: each value's name while it holds it, none past the list or for a
/// plain signal; and the declared width, whatever the value.
#[test]
fn state_names_follow_the_value_and_width_is_declared() {
    let mut s = Signal::new("state", Format::uint(2)).with_states(&["IDLE", "RUN", "DONE"]);
    assert_eq!(s.width(), 2);
    assert_eq!(s.states().map(<[_]>::len), Some(3));
    for (v, name) in [
        (0, Some("IDLE")),
        (1, Some("RUN")),
        (2, Some("DONE")),
        (3, None),
    ] {
        s.set_raw(v);
        assert_eq!(s.state_name(), name, "value {v}");
    }
    let plain = Signal::new("p", Format::signed(13, 4));
    assert_eq!((plain.width(), plain.state_name()), (13, None));
    assert_eq!(Signal::bit("b").width(), 1);
}

/// Every width of both signednesses: a raw value written is read back, the ends of the range
/// and the values around zero included (the sign extension is one shift pair for all).
#[test]
fn raw_values_read_back_at_every_width() {
    for w in 1..=64u32 {
        for fmt in [Format::uint(w), Format::signed(w, 0)] {
            let mut s = Signal::new("s", fmt);
            let (lo, hi) = (
                fmt.min_raw().max(i128::from(i64::MIN)) as i64,
                fmt.max_raw().min(i128::from(i64::MAX)) as i64,
            );
            for raw in [lo, lo.saturating_add(1), 0, 1, -1, hi.saturating_sub(1), hi] {
                if raw < lo || raw > hi {
                    continue;
                }
                s.set_raw(raw);
                assert_eq!(s.raw(), raw, "{fmt}");
                assert_eq!(
                    s.bits() & !(fmt.mask() as u64),
                    0,
                    "{fmt}: bits above the width"
                );
            }
        }
    }
}

/// A hand-written `visit_bits` that lists the signals in another order than its `visit` is
/// caught by the first checked edge (a tracer would show each value under another's name).
#[test]
#[should_panic(expected = "'swapped': visit_bits lists other values than visit")]
fn a_visit_bits_out_of_step_with_visit_is_caught() {
    struct Swapped(Signal, Signal);
    impl Module for Swapped {
        fn instance(&self) -> &str {
            "swapped"
        }
        fn kind(&self) -> &'static str {
            "swapped"
        }
        fn eval(&mut self) {
            self.1.set_raw(self.0.raw() + 1);
        }
        fn tick(&mut self, _: bool) {}
        fn visit(&self, v: &mut dyn Visitor) {
            v.enter("swapped", "swapped");
            signals!(v; Input: self.0; Output: self.1);
            v.leave();
        }
        fn visit_bits<F: FnMut(u64)>(&self, f: &mut F) {
            f(self.1.bits());
            f(self.0.bits());
        }
    }
    let f = Format::uint(4);
    let mut sim = Sim::new(Swapped(Signal::new("a", f), Signal::new("b", f))).check_schedule(true);
    sim.step();
}

/// The derive's `visit_bits` lists what its `visit` lists, in order, through every kind of
/// field: ports, a register bundle, a narrowing, children in a collection and a hand-written
/// child (which takes the default, through its `visit`).
#[test]
fn derived_visit_bits_follows_visit() {
    use crate::fx::{Narrowing, Overflow, Quant};
    #[derive(Module)]
    #[module(kind = "leaf")]
    struct Leaf {
        #[input]
        a: Signal,
        #[reg]
        r: [Reg; 2],
        #[narrow]
        n: Narrowing,
    }
    impl Leaf {
        fn eval(&mut self) {}
    }
    #[derive(Module)]
    #[module(kind = "outer")]
    struct Outer {
        #[output]
        y: Option<Signal>,
        #[child]
        leaves: Vec<Leaf>,
        #[child]
        inc: Inc,
        #[wire]
        w: Signal,
    }
    impl Outer {
        fn eval(&mut self) {}
    }
    let f = Format::uint(8);
    let leaf = |k: u64| {
        let mut l = Leaf {
            a: Signal::new("a", f),
            r: [Reg::new("r0", f), Reg::new("r1", f)],
            n: Narrowing::new("n", f, Quant::Trunc, Overflow::Wrap),
        };
        l.a.set_bits(k);
        l.r[1].set_next_bits(k + 1);
        l.r[1].tick(false);
        l
    };
    let mut top = Outer {
        y: Some(Signal::new("y", f)),
        leaves: vec![leaf(3), leaf(5)],
        inc: Inc {
            a: Signal::new("a", Format::uint(4)),
            y: Signal::new("y", Format::uint(5)),
        },
        w: Signal::new("w", f),
    };
    top.w.set_bits(9);
    top.inc.a.set_bits(7);
    let mut listed = Vec::new();
    top.visit_bits(&mut |b| listed.push(b));
    assert_eq!(listed, [0, 3, 0, 4, 0, 5, 0, 6, 0, 7, 0, 9]);
    assert_eq!(listed, sim::visited_bits(&top));
}

/// A delay line of each depth shows each input `depth` cycles later (depth 0: the same
/// cycle), every signal of the bundle on its own, and zeros after reset until its inputs
/// reach the outputs again.
#[test]
fn a_delay_line_shows_each_input_depth_cycles_later() {
    for depth in 0..5 {
        let d = Delay::new(
            "line",
            [("a", Format::uint(8)), ("b", Format::signed(5, 0))],
            depth,
            ["a_d", "b_d"],
        );
        let mut sim = Sim::new(d).check_schedule(true);
        let input = |c: usize| ((c * 37 + 11) as u64 % 256, (c as i64 * 7) % 16 - 8);
        let mut seen = Vec::new();
        for c in 0..40 {
            // The edge of cycle 20 is a reset edge.
            sim.set_reset(c == 20);
            let (a, b) = input(c);
            sim.dut.i[0].set_bits(a);
            sim.dut.i[1].set_raw(b);
            sim.eval();
            seen.push((sim.dut.o[0].bits(), sim.dut.o[1].raw()));
            sim.tick();
        }
        for (c, &got) in seen.iter().enumerate() {
            // The input `depth` cycles ago, unless that was before the start or the reset
            // edge came in between.
            let from = c.checked_sub(depth);
            let cleared = from.is_none_or(|f| depth > 0 && f <= 20 && c > 20);
            let want = if cleared {
                (0, 0)
            } else {
                input(from.unwrap())
            };
            assert_eq!(got, want, "depth {depth}, cycle {c}");
        }
    }
}

/// A stimulus row goes into the signals in order; the values past them are not read.
#[test]
fn a_row_sets_each_signal_in_order() {
    let mut a = Signal::new("a", Format::uint(4));
    let mut b = Signal::new("b", Format::signed(6, 2));
    let mut c = Signal::bit("c");
    Signal::set_row([&mut a, &mut b, &mut c], &[9, 0x3f, 1, 77]);
    assert_eq!((a.bits(), b.raw(), c.is_high()), (9, -1, true));
}

/// A pattern wider than its signal is refused, naming the signal, as `set_bits` refuses it.
#[test]
#[should_panic(expected = "signal 'c' (u1")]
fn a_row_refuses_a_pattern_its_signal_cannot_hold() {
    let mut a = Signal::new("a", Format::uint(4));
    let mut c = Signal::bit("c");
    Signal::set_row([&mut a, &mut c], &[3, 2]);
}

/// A row shorter than the signals is refused before any is written.
#[test]
#[should_panic(expected = "out of range")]
fn a_short_row_is_refused() {
    let mut a = Signal::new("a", Format::uint(4));
    let mut b = Signal::new("b", Format::uint(4));
    Signal::set_row([&mut a, &mut b], &[3]);
}
