//! Named narrowings: the same bits as `quantise` whether tracking is on or off, counts that
//! match a count made from the definitions, and the hierarchy's paths from the derive.

use hdl::fx::{quantise, set_tracking, Format, Fx, Narrowing, Overflow, Quant};
use hdl::kernel::{narrowings, Module, RegOf, SignalOf};

/// Every raw value of 10-bit sources with 0..=5 fraction bits into a signed 4-bit, 1-fraction
/// destination, every mode: the result is `quantise`'s, on or off; on, each count equals the
/// one computed from exact rationals.
#[test]
fn results_are_quantise_and_counts_are_the_definitions() {
    let dst = Format::signed(4, 1); // -4 ..= 3.5 in steps of 0.5
    for &q in Quant::ALL.iter() {
        for &o in Overflow::ALL.iter() {
            for frac in 0..=5 {
                let mut n = Narrowing::new("y", dst, q, o);
                set_tracking(false);
                for raw in -512i128..512 {
                    assert_eq!(n.raw(raw, frac), quantise(raw, frac, dst, q, o));
                }
                assert_eq!(n.stats().narrowed, 0, "off: nothing counted");
                set_tracking(true);
                let (mut high, mut low, mut ties, mut inexact) = (0, 0, 0, 0);
                for raw in -512i128..512 {
                    assert_eq!(n.raw(raw, frac), quantise(raw, frac, dst, q, o));
                    // In halves of the destination LSB's quarter: exact integer arithmetic.
                    let scaled = raw << (6 - frac); // units of 2^-6
                    let rem = scaled.rem_euclid(32); // within one destination LSB (2^-1)
                    inexact += u64::from(rem != 0);
                    let tie = rem == 16 && !matches!(q, Quant::Trunc | Quant::TruncZero);
                    ties += u64::from(tie);
                    let r = quantise(raw, frac, Format::signed(20, 1), q, Overflow::Wrap);
                    let lo = if o == Overflow::SaturateSymmetric {
                        -7
                    } else {
                        -8
                    };
                    high += u64::from(r > 7);
                    low += u64::from(r < lo);
                }
                let s = n.stats();
                assert_eq!(s.narrowed, 1024);
                assert_eq!((s.over_high, s.over_low), (high, low), "{q:?} {o:?} {frac}");
                assert_eq!((s.ties, s.inexact), (ties, inexact), "{q:?} {o:?} {frac}");
                let src = Format::signed(10, frac);
                let (lo, hi) = (Fx::from_raw(src, -512), Fx::from_raw(src, 511));
                let (min, max) = (s.min().unwrap(), s.max().unwrap());
                assert!(min.cmp_value(&lo).is_eq() && max.cmp_value(&hi).is_eq());
                set_tracking(false);
            }
        }
    }
}

hdl::formats! {
    Wide = Format::signed(12, 4);
    Out = Format::signed(8, 4);
}

hdl::formats! {
    Half = Format::signed(4, 1);
    Quarter = Format::unsigned(5, 2);
    Twos = Format::signed(6, -1);
    Word = Format::signed(62, 3);
}

/// The typed narrowing, whose destination's fraction bits are a constant that its shift and
/// rounding fold with, gives what `quantise` gives: every raw value of 12-bit sources with
/// -2..=7 fraction bits, and values around every power of two up to 2^70, into destinations
/// with positive, zero-shift, negative and word-sized formats, every mode, tracking off and on.
#[test]
fn a_typed_narrowing_is_quantise() {
    fn check<F: hdl::fx::Fmt>(cases: &[(i128, i32)]) {
        for q in Quant::ALL {
            for o in Overflow::ALL {
                let mut n = hdl::fx::NarrowingOf::<F>::new("y", q, o);
                for on in [false, true] {
                    set_tracking(on);
                    for &(raw, frac) in cases {
                        let want = quantise(raw, frac, F::FMT, q, o);
                        assert_eq!(
                            n.raw(raw, frac),
                            want,
                            "{raw} >> {frac} into {} {q} {o}",
                            F::FMT
                        );
                    }
                }
                set_tracking(false);
            }
        }
    }
    let mut cases: Vec<(i128, i32)> = (-2..=7)
        .flat_map(|frac| (-2048i128..2048).map(move |raw| (raw, frac)))
        .collect();
    for k in 0..70 {
        for d in [-1i128, 0, 1] {
            for frac in [0, 1, 3, 4, 40, 62, 63, 65] {
                cases.extend([((1i128 << k) + d, frac), (-(1i128 << k) + d, frac)]);
            }
        }
    }
    check::<Half>(&cases);
    check::<Quarter>(&cases);
    check::<Twos>(&cases);
    check::<Word>(&cases);
    check::<Out>(&cases);
}

/// A unit with a narrowing: its path in the hierarchy, and its counts after a run.
#[derive(Module)]
#[module(kind = "clip")]
struct Clip {
    #[input]
    x: SignalOf<Wide>,
    #[reg]
    y: RegOf<Out>,
    #[narrow]
    round: Narrowing,
}

impl Clip {
    fn eval(&mut self) {
        let v = self.round.fx(self.x.fx());
        self.y.set_next(v);
    }
}

#[test]
fn the_hierarchy_names_each_narrowing() {
    let mut c = Clip {
        x: SignalOf::new("x"),
        y: RegOf::new("y"),
        round: Narrowing::new("y", Out::FMT, Quant::RoundHalfEven, Overflow::Saturate),
    };
    set_tracking(true);
    for raw in [-2048, -100, 0, 100, 2047] {
        c.x.set_raw(raw);
        c.eval();
        c.tick(false);
    }
    set_tracking(false);
    let found = narrowings(&c);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].0, "clip.y");
    let s = found[0].1.stats();
    assert_eq!((s.narrowed, s.over_high, s.over_low), (5, 1, 1));
    assert_eq!(c.y.q().fx(), Fx::from_raw(Out::FMT, 127));
}

/// The overflow flag: a one-bit wire `y_sat` of the unit's scope (so every tracer shows it),
/// high while the latest value narrowed saturated, which the kernel's schedule check accepts;
/// with tracking off it stays low.
#[test]
fn the_flag_is_a_wire_that_shows_the_latest_saturation() {
    use hdl::kernel::{signal_paths, Sim};
    let clip = || Clip {
        x: SignalOf::new("x"),
        y: RegOf::new("y"),
        round: Narrowing::new("y", Out::FMT, Quant::RoundHalfEven, Overflow::Saturate),
    };
    assert_eq!(signal_paths(&clip()), ["clip.x", "clip.y", "clip.y_sat"]);
    let mut sim = Sim::new(clip()).check_schedule(true);
    set_tracking(true);
    let mut flags = Vec::new();
    for raw in [0, 2047, 2047, 100, -2048, -100] {
        sim.dut.x.set_raw(raw);
        sim.step();
        flags.push(sim.dut.round.flag().raw());
    }
    set_tracking(false);
    assert_eq!(flags, [0, 1, 1, 0, 1, 0]);
    sim.dut.x.set_raw(2047);
    sim.step();
    assert_eq!(sim.dut.round.flag().raw(), 0, "off: not set");
}

proptest::proptest! {
    /// The range kept while tracking is the exact smallest and largest value narrowed, for
    /// sources whose fraction bits vary from value to value (normal 156's `2^-k` does), wide
    /// values included, and two runs merged hold both runs' ends.
    #[test]
    fn the_range_is_exact_whatever_the_fraction_bits(
        values in proptest::collection::vec((proptest::num::i128::ANY, -20i32..60), 1..40),
        split in 0usize..40,
    ) {
        let as_fx = |(raw, frac): (i128, i32)| Fx::from_raw(Format::new(128, frac, true), raw);
        let run = |vs: &[(i128, i32)]| {
            let mut n = Narrowing::new("x", Format::signed(8, 2), Quant::RoundHalfEven, Overflow::Saturate);
            set_tracking(true);
            for &(raw, frac) in vs {
                n.raw(raw >> (raw.unsigned_abs().leading_zeros() % 100), frac);
            }
            set_tracking(false);
            n.stats().clone()
        };
        let narrowed: Vec<(i128, i32)> = values
            .iter()
            .map(|&(raw, frac)| (raw >> (raw.unsigned_abs().leading_zeros() % 100), frac))
            .collect();
        let want_min = narrowed.iter().map(|&v| as_fx(v)).min_by(|a, b| a.cmp_value(b)).unwrap();
        let want_max = narrowed.iter().map(|&v| as_fx(v)).max_by(|a, b| a.cmp_value(b)).unwrap();
        let whole = run(&values);
        proptest::prop_assert!(whole.min().unwrap().cmp_value(&want_min).is_eq());
        proptest::prop_assert!(whole.max().unwrap().cmp_value(&want_max).is_eq());
        let k = split.min(values.len());
        let mut merged = run(&values[..k]);
        merged.merge(&run(&values[k..]));
        proptest::prop_assert!(merged.min().unwrap().cmp_value(&want_min).is_eq());
        proptest::prop_assert!(merged.max().unwrap().cmp_value(&want_max).is_eq());
        proptest::prop_assert_eq!(merged.narrowed, values.len() as u64);
    }
}
