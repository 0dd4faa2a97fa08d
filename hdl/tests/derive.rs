//! `#[derive(Module)]`: what it generates is what a hand-written module declares — every
//! marked field visited in order (so traced and schedule-checked), every register and child
//! ticked, collections of them one attribute each, the constructor from the declared formats.

use hdl::fx::{Format, Fx};
use hdl::kernel::{instances, signal_dirs, signal_paths, Dir, Module, Reg, Signal, Sim};

const BYTE: Format = Format::uint(8);
const BIT: Format = Format::uint(1);

/// A shift register of three taps behind an enable: registers, a wire, an output.
#[derive(Module)]
#[module(kind = "taps", new)]
struct Taps {
    #[input(fmt = BIT)]
    en: Signal,
    #[input(fmt = BYTE)]
    d: Signal,
    #[wire(fmt = BYTE)]
    first: Signal,
    #[output(fmt = BYTE)]
    q: Signal,
    #[reg(fmt = BYTE, reset = Fx::from_raw(BYTE, 7))]
    t0: Reg,
    #[reg(fmt = BYTE)]
    t1: Reg,
    #[reg(fmt = BYTE)]
    t2: Reg,
}

impl Taps {
    fn eval(&mut self) {
        self.first.follow(self.t0.q());
        self.q.follow(self.t2.q());
        if self.en.is_high() {
            self.t0.set_next(self.d.fx());
            self.t1.set_next(self.t0.q().fx());
            self.t2.set_next(self.t1.q().fx());
        }
    }
}

/// A parent with an array, a vector and an optional child, its own instance name and a
/// register bank as an array; an unmarked field is left alone.
#[derive(Module)]
#[module(kind = "bank")]
struct Bank {
    #[instance]
    name: &'static str,
    #[child]
    pair: [Taps; 2],
    #[child]
    more: Vec<Taps>,
    #[child]
    spare: Option<Taps>,
    #[reg]
    count: [Reg; 2],
    gain: u32,
}

impl Bank {
    fn eval(&mut self) {
        for t in self
            .pair
            .iter_mut()
            .chain(&mut self.more)
            .chain(&mut self.spare)
        {
            t.en.set_bool(true);
            t.d.set_bits(u64::from(self.gain));
            t.eval();
        }
        let n = (self.count[0].q().bits() + 1) & 255;
        self.count[0].set_next_bits(n);
        self.count[1].set_next_bits(self.count[0].q().bits());
    }
}

fn bank(spare: bool) -> Bank {
    Bank {
        name: "bank_a",
        pair: [Taps::new(), Taps::new()],
        more: vec![Taps::new()],
        spare: spare.then(Taps::new),
        count: [Reg::new("count0", BYTE), Reg::new("count1", BYTE)],
        gain: 5,
    }
}

#[test]
fn every_marked_field_is_visited_in_order_with_its_direction() {
    let t = Taps::new();
    assert_eq!(
        signal_paths(&t),
        [
            "taps.en",
            "taps.d",
            "taps.first",
            "taps.q",
            "taps.t0",
            "taps.t1",
            "taps.t2"
        ]
    );
    use Dir::*;
    assert_eq!(signal_dirs(&t), [Input, Input, Wire, Output, Reg, Reg, Reg]);
    assert_eq!((t.kind(), t.instance()), ("taps", "taps"));
    assert_eq!(
        t.d.fmt(),
        BYTE,
        "the constructor gives each signal its declared format"
    );
    assert_eq!(t.t0.q().name(), "t0", "named after its field");
}

#[test]
fn collections_of_children_and_registers_are_one_attribute_each() {
    let b = bank(true);
    assert_eq!(b.instance(), "bank_a");
    let inst: Vec<String> = instances(&b).into_iter().map(|(i, _)| i).collect();
    assert_eq!(inst.len(), 5, "{inst:?}");
    let paths = signal_paths(&b);
    assert_eq!(paths.len(), 4 * 7 + 2);
    assert_eq!(&paths[28..], ["bank_a.count0", "bank_a.count1"]);
    assert_eq!(
        signal_paths(&bank(false)).len(),
        3 * 7 + 2,
        "no spare, not visited"
    );
}

#[test]
fn the_generated_edge_commits_every_register_and_child_and_resets_them() {
    let mut sim = Sim::new(bank(true)).check_schedule(true);
    sim.reset(1);
    assert_eq!(
        sim.dut.pair[1].t0.q().bits(),
        7,
        "t0's declared reset value"
    );
    for _ in 0..3 {
        sim.step();
    }
    sim.eval();
    for t in sim
        .dut
        .pair
        .iter()
        .chain(&sim.dut.more)
        .chain(&sim.dut.spare)
    {
        assert_eq!(
            t.q.bits(),
            5,
            "three enabled edges: the input reached the last tap"
        );
    }
    assert_eq!(
        (sim.dut.count[0].q().bits(), sim.dut.count[1].q().bits()),
        (3, 2)
    );
    sim.reset(1);
    assert_eq!(sim.dut.more[0].t2.q().bits(), 0);
}

/// Ports a configuration may leave out: a bundle of two inputs.
#[derive(hdl::kernel::Signals)]
struct Extra {
    x: Signal,
    y: Signal,
}

/// Two sets of taps sharing their owner's scope.
#[derive(hdl::kernel::Group)]
struct Pair {
    a: Taps,
    b: Taps,
}

#[derive(Module)]
#[module(kind = "grouped")]
struct Grouped {
    #[input]
    extra: Option<Extra>,
    #[child]
    pairs: Vec<Pair>,
}

impl Grouped {
    fn eval(&mut self) {
        for p in &mut self.pairs {
            p.a.eval();
            p.b.eval();
        }
    }
}

#[test]
fn an_optional_bundle_and_a_group_add_no_scope_and_are_visited_when_present() {
    let pair = || Pair {
        a: Taps::new(),
        b: Taps::new(),
    };
    let extra = Extra {
        x: Signal::new("x", BIT),
        y: Signal::new("y", BIT),
    };
    let g = Grouped {
        extra: Some(extra),
        pairs: vec![pair(), pair()],
    };
    let paths = signal_paths(&g);
    assert_eq!(&paths[..3], ["grouped.x", "grouped.y", "grouped.taps.en"]);
    assert_eq!(
        paths.len(),
        2 + 4 * 7,
        "four sets of taps straight under the owner"
    );
    let inst: Vec<String> = instances(&g).into_iter().map(|(i, _)| i).collect();
    assert_eq!(
        inst.len(),
        5,
        "the owner and four taps, no scope for a pair: {inst:?}"
    );
    let bare = Grouped {
        extra: None,
        pairs: vec![pair()],
    };
    assert_eq!(signal_paths(&bare).len(), 2 * 7, "no bundle, not visited");
}

hdl::formats! {
    Wide = Format::signed(10, 4);
    Narrow = Format::signed(6, 2);
}

/// Narrowings declared in the struct: `new` builds them named after their fields, typed
/// (`NarrowingOf<F>`: the format is the type) or run-time (`fmt = ...`).
#[derive(Module)]
#[module(kind = "clip", new)]
struct Clip {
    #[input]
    x: hdl::kernel::SignalOf<Wide>,
    #[reg]
    y: hdl::kernel::RegOf<Narrow>,
    #[narrow(quant = hdl::fx::Quant::RoundHalfEven, overflow = hdl::fx::Overflow::Saturate)]
    to_y: hdl::fx::NarrowingOf<Narrow>,
    #[narrow(fmt = Format::signed(4, 0), quant = hdl::fx::Quant::Trunc, overflow = hdl::fx::Overflow::Wrap)]
    whole: hdl::fx::Narrowing,
}

impl Clip {
    fn eval(&mut self) {
        let y = self.to_y.fx(self.x.fx());
        self.whole.fx(y);
        self.y.set_next(y);
    }
}

#[test]
fn new_declares_narrowings_with_their_modes_and_the_visitor_sees_them() {
    let mut c = Clip::new();
    let found = hdl::kernel::narrowings(&c);
    let names: Vec<&str> = found.iter().map(|(p, _)| p.as_str()).collect();
    assert_eq!(names, ["clip.to_y", "clip.whole"]);
    assert_eq!(found[0].1.dst(), Narrow::FMT);
    assert_eq!(found[1].1.overflow(), hdl::fx::Overflow::Wrap);
    // Their flags are wires of the unit's scope, traced with its signals.
    let paths = signal_paths(&c);
    assert!(paths.iter().any(|p| p == "clip.to_y_sat"), "{paths:?}");
    assert!(paths.iter().any(|p| p == "clip.whole_wrap"), "{paths:?}");
    hdl::fx::set_tracking(true);
    c.x.set_raw(511); // 31.9375: saturates at sQ4.2's 7.75
    c.eval();
    hdl::fx::set_tracking(false);
    assert_eq!(c.y.next_bits(), 31, "7.75 in sQ4.2");
    assert_eq!(c.to_y.stats().over_high, 1);
    assert_eq!(c.whole.stats().narrowed, 1);
}

/// A counter behind a clock enable; `leak` writes the count's next value even when the
/// enable is low, which the enable must not allow.
#[derive(Module)]
#[module(kind = "gated", enable = self.en.is_high())]
struct Gated {
    #[input]
    en: Signal,
    #[input]
    leak: Signal,
    #[reg]
    count: Reg,
    #[child]
    inner: Taps,
}

impl Gated {
    fn new() -> Gated {
        Gated {
            en: Signal::bit("en"),
            leak: Signal::bit("leak"),
            count: Reg::new("count", BYTE),
            inner: Taps::new(),
        }
    }

    fn eval(&mut self) {
        if self.en.is_high() || self.leak.is_high() {
            let n = (self.count.q().bits() + 1) & 0xff;
            self.count.set_next_bits(n);
        }
        self.inner.en.set_bool(self.en.is_high());
        self.inner.d.set_bits(self.count.q().bits());
        self.inner.eval();
    }
}

fn run_gated(pattern: &[(bool, bool)]) -> Sim<Gated> {
    let mut sim = Sim::new(Gated::new()).check_schedule(true);
    sim.reset(1);
    for &(en, leak) in pattern {
        sim.dut.en.set_bool(en);
        sim.dut.leak.set_bool(leak);
        sim.step();
    }
    sim
}

#[test]
fn a_clock_enable_skips_the_edge_of_every_register_and_child_while_low() {
    let sim = run_gated(&[(true, false), (false, false), (true, false), (false, false)]);
    assert_eq!(sim.dut.count.q().bits(), 2, "two enabled edges");
    // The child's taps moved on the two enabled edges only (0 then 1 shifted in; reset 7).
    let t = &sim.dut.inner;
    let taps = [t.t0.q().bits(), t.t1.q().bits(), t.t2.q().bits()];
    assert_eq!(taps, [1, 0, 7]);
}

#[test]
#[should_panic(
    expected = "clock enable of 'gated': the edge was skipped while 'gated.count' holds 0x1 with the next value 0x2 pending"
)]
fn a_write_while_the_enable_is_low_is_refused_at_the_skipped_edge() {
    run_gated(&[(true, false), (false, true)]);
}

#[test]
#[should_panic(expected = "'gated.taps.t0'")]
fn a_childs_pending_write_under_a_low_enable_is_refused_too() {
    let mut sim = Sim::new(Gated::new());
    sim.reset(1);
    sim.dut.en.set_bool(false);
    sim.eval();
    // A write into the child behind the parent's back, the enable low.
    sim.dut.inner.t0.set_next_bits(9);
    sim.tick();
}
