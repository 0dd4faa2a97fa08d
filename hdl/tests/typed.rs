//! Signals and registers whose type is their format: the same values, bit for bit, as the
//! run-time-format ones, on every value of small formats and at the 64-bit edges where the
//! arithmetic leaves machine words; the derive builds them from their types.

use hdl::fx::{Bit, Format, Fx, Overflow, Quant};
use hdl::kernel::{signal_dirs, signal_paths, Dir, Module, Reg, RegOf, Signal, SignalOf, Sim};

hdl::formats! {
    /// sQ4.4
    X = Format::signed(8, 4);
    /// uQ2.6
    U = Format::unsigned(8, 6);
    /// sQ6.4
    Acc = Format::signed(10, 4);
    /// uQ1.7
    Out = Format::unsigned(8, 7);
}

/// Every (x, u) pair: sums, differences, products and narrowings from typed signals equal the
/// same operations from run-time-format signals, value and format.
#[test]
fn typed_arithmetic_is_the_run_time_arithmetic_on_every_value() {
    let (mut tx, mut tu) = (SignalOf::<X>::new("x"), SignalOf::<U>::new("u"));
    let (mut dx, mut du) = (Signal::new("x", X::FMT), Signal::new("u", U::FMT));
    for x in -128..128 {
        tx.set_raw(x);
        dx.set_raw(x);
        for u in 0..256 {
            tu.set_raw(u);
            du.set_raw(u);
            let (a, b) = (tx.fx(), tu.fx());
            let (c, d) = (dx.fx(), du.fx());
            assert_eq!(
                (a + b, a - b, a * b, -a),
                (c + d, c - d, c * d, -c),
                "{x} {u}"
            );
            for (q, o) in [
                (Quant::RoundHalfEven, Overflow::Saturate),
                (Quant::Trunc, Overflow::Wrap),
                (Quant::RoundHalfAway, Overflow::SaturateSymmetric),
            ] {
                let t = (a * b + a).convert(Out::FMT, q, o);
                assert_eq!(
                    t,
                    (c * d + c).convert(Out::FMT, q, o),
                    "{x} {u} {q:?} {o:?}"
                );
                let mut r = RegOf::<Out>::new("r");
                r.set_next(t);
                r.tick(false);
                assert_eq!(r.q().fx(), t);
                assert_eq!(r.q().bits(), t.bits() as u64);
            }
        }
    }
}

/// Results of exactly 64 bits: a signed one is computed in a machine word, an unsigned one
/// (whose top values do not fit an `i64`) is not; both exact.
#[test]
fn results_at_the_word_edge_are_exact() {
    let u32f = Format::uint(32);
    let max = Fx::from_raw(u32f, (1 << 32) - 1);
    assert_eq!((max * max).raw(), ((1i128 << 32) - 1).pow(2));
    let s32 = Format::sint(32);
    let min = Fx::from_raw(s32, -(1 << 31));
    assert_eq!((min * min).raw(), 1i128 << 62);
    assert_eq!((min * min).fmt(), Format::sint(64));
    let u63 = Format::uint(63);
    let top = Fx::from_raw(u63, (1 << 63) - 1);
    assert_eq!((top + top).raw(), ((1i128 << 63) - 1) * 2);
    let s63 = Format::sint(63);
    let low = Fx::from_raw(s63, -(1 << 62));
    assert_eq!((low + low).raw(), -(1i128 << 63));
    assert_eq!((low - top).raw(), -(1i128 << 62) - ((1i128 << 63) - 1));
    // A 64-bit unsigned signal with its top bit set reads as the positive value it holds.
    let mut s = Signal::new("wide", Format::uint(64));
    s.set_bits(u64::MAX);
    assert_eq!(s.fx().raw(), i128::from(u64::MAX));
}

/// Writes out of the type's range panic with the signal's name.
#[test]
fn typed_writes_are_checked() {
    let r = std::panic::catch_unwind(|| SignalOf::<Acc>::new("acc").set_raw(512));
    let msg = *r.unwrap_err().downcast::<String>().unwrap();
    assert!(msg.contains("'acc'") && msg.contains("raw 512"), "{msg}");
    let r = std::panic::catch_unwind(|| {
        let wide = Fx::from_raw(Format::signed(12, 4), 600);
        RegOf::<Acc>::new("acc").set_next(wide)
    });
    let msg = *r.unwrap_err().downcast::<String>().unwrap();
    assert!(
        msg.contains("'acc'") && msg.contains("does not fit"),
        "{msg}"
    );
}

/// A typed bit-pattern write takes exactly the patterns of its width, at every width and both
/// signednesses (as the run-time signal does), and may read the signal in its argument.
#[test]
fn typed_bit_writes_take_the_width_exactly() {
    hdl::formats! {
        S1 = Format::signed(1, 0);
        U7 = Format::uint(7);
        S12 = Format::signed(12, 4);
        U64 = Format::uint(64);
    }
    fn check<F: hdl::fx::Fmt>(top: u64) {
        let mut s = SignalOf::<F>::new("s");
        let mut d = Signal::new("s", F::FMT);
        s.set_bits(top);
        d.set_bits(top);
        assert_eq!((s.bits(), s.raw()), (d.bits(), d.raw()));
        s.set_bits(0);
        s.set_bits(s.bits() | 1);
        assert_eq!(s.bits(), 1);
        if let Some(over) = top.checked_add(1) {
            let r = std::panic::catch_unwind(|| SignalOf::<F>::new("s").set_bits(over));
            let msg = *r.unwrap_err().downcast::<String>().unwrap();
            assert!(
                msg.contains("'s'") && msg.contains(&format!("bits {over:#x}")),
                "{msg}"
            );
        }
    }
    check::<S1>(1);
    check::<U7>(127);
    check::<S12>(0xfff);
    check::<U64>(u64::MAX);
}

/// A derived module of typed fields: built from the types alone (a reset value and state
/// names too), visited like a run-time-format one, and a `fmt` that contradicts a type fails.
#[derive(Clone, Module)]
#[module(kind = "typed_acc", new)]
struct TypedAcc {
    #[input]
    en: SignalOf<Bit>,
    #[input]
    x: SignalOf<X>,
    #[output(fmt = Acc::FMT)]
    acc: SignalOf<Acc>,
    #[reg(reset = Fx::from_raw(Acc::FMT, -3))]
    acc_r: RegOf<Acc>,
    #[reg(states = &["IDLE", "RUN"])]
    state: RegOf<Bit>,
    #[reg(fmt = Format::uint(4))]
    count: Reg,
}

impl TypedAcc {
    fn eval(&mut self) {
        self.acc.follow(self.acc_r.q());
        if self.en.is_high() {
            let sum = self.acc_r.q().fx() + self.x.fx();
            self.acc_r
                .set_next(sum.convert(Acc::FMT, Quant::Trunc, Overflow::Saturate));
            self.state.set_next_bool(true);
        }
    }
}

#[test]
fn derived_typed_module() {
    let m = TypedAcc::new();
    use Dir::{Input, Output, Reg as R};
    assert_eq!(signal_dirs(&m), [Input, Input, Output, R, R, R]);
    assert_eq!(
        signal_paths(&m),
        [
            "typed_acc.en",
            "typed_acc.x",
            "typed_acc.acc",
            "typed_acc.acc_r",
            "typed_acc.state",
            "typed_acc.count"
        ]
    );
    assert_eq!(
        m.acc_r.q().raw(),
        -3,
        "starts at its reset value, as a `Reg` does"
    );
    assert_eq!(m.state.q().states(), Some(&["IDLE", "RUN"][..]));
    let mut sim = Sim::new(m).check_schedule(true);
    sim.reset(1);
    assert_eq!(sim.dut.acc_r.q().raw(), -3, "the declared reset value");
    sim.dut.en.set_bool(true);
    sim.dut.x.set_raw(127);
    for _ in 0..10 {
        sim.step();
    }
    assert_eq!(sim.dut.acc.raw(), 511, "saturated at the top of sQ6.4");
    assert_eq!(sim.dut.state.q().state_name(), Some("RUN"));
}

#[derive(Module)]
#[module(kind = "contradiction", new)]
struct Contradiction {
    #[input(fmt = Format::uint(2))]
    x: SignalOf<Bit>,
}

impl Contradiction {
    fn eval(&mut self) {}
}

#[test]
fn a_fmt_that_contradicts_the_type_fails() {
    let r = std::panic::catch_unwind(Contradiction::new);
    let msg = *r.err().expect("panics").downcast::<String>().unwrap();
    assert!(
        msg.contains("'x'") && msg.contains("u2") && msg.contains("u1"),
        "{msg}"
    );
}
