//! Exhaustive checks of every quantisation and overflow mode on small widths, against a
//! reference that works on exact rationals (numerator over a power of two) with plain integer
//! division, not with the shift-and-sticky-bit logic of the implementation.

use super::*;
use proptest::prelude::*;

/// All formats of width 1..=max_w with fraction bits in `fracs`.
fn formats(max_w: u32, fracs: std::ops::RangeInclusive<i32>) -> Vec<Format> {
    let mut v = Vec::new();
    for w in 1..=max_w {
        for f in fracs.clone() {
            for s in [false, true] {
                v.push(Format::new(w, f, s));
            }
        }
    }
    v
}

fn all_raw(fmt: Format) -> impl Iterator<Item = i128> {
    fmt.min_raw()..=fmt.max_raw()
}

/// Reference rounding of `num / den` (den > 0) to an integer.
fn ref_round(num: i128, den: i128, q: Quant) -> i128 {
    let fl = num.div_euclid(den);
    let rem = num.rem_euclid(den); // 0 <= rem < den
    if rem == 0 {
        return fl;
    }
    let up = fl + 1;
    let twice = 2 * rem;
    let neg = num < 0;
    match q {
        Quant::Trunc => fl,
        Quant::TruncZero => {
            if neg {
                up
            } else {
                fl
            }
        }
        _ if twice > den => up,
        _ if twice < den => fl,
        // exact tie
        Quant::RoundHalfUp => up,
        Quant::RoundHalfDown => fl,
        Quant::RoundHalfZero => {
            if neg {
                up
            } else {
                fl
            }
        }
        Quant::RoundHalfAway => {
            if neg {
                fl
            } else {
                up
            }
        }
        Quant::RoundHalfEven => {
            if fl.rem_euclid(2) == 0 {
                fl
            } else {
                up
            }
        }
    }
}

/// Reference overflow handling of integer `v` into `dst` (raw units).
fn ref_overflow(v: i128, dst: Format, o: Overflow) -> i128 {
    let w = dst.width();
    let lo = if dst.is_signed() {
        -(1i128 << (w - 1))
    } else {
        0
    };
    let hi = if dst.is_signed() {
        (1i128 << (w - 1)) - 1
    } else {
        (1i128 << w) - 1
    };
    match o {
        Overflow::Wrap => {
            let m = v.rem_euclid(1i128 << w);
            if m > hi {
                m - (1i128 << w)
            } else {
                m
            }
        }
        Overflow::Saturate => v.clamp(lo, hi),
        Overflow::SaturateSymmetric => {
            let lo = if dst.is_signed() { -hi } else { 0 };
            v.clamp(lo, hi)
        }
        Overflow::SaturateZero => {
            if v < lo || v > hi {
                0
            } else {
                v
            }
        }
    }
}

fn ref_convert(raw: i128, src: Format, dst: Format, q: Quant, o: Overflow) -> i128 {
    // value = raw * 2^-fs; in dst LSBs: raw * 2^(fd - fs)
    let d = dst.frac() - src.frac();
    let v = if d >= 0 {
        raw * (1i128 << d)
    } else {
        ref_round(raw, 1i128 << (-d), q)
    };
    ref_overflow(v, dst, o)
}

#[test]
fn convert_exhaustive_small_widths() {
    let srcs = formats(7, -2..=6);
    let dsts = formats(5, -2..=6);
    let mut checked = 0u64;
    for &src in &srcs {
        for raw in all_raw(src) {
            let x = Fx::from_raw(src, raw);
            for &dst in &dsts {
                for q in Quant::ALL {
                    for o in Overflow::ALL {
                        let got = x.convert(dst, q, o).raw();
                        let want = ref_convert(raw, src, dst, q, o);
                        assert_eq!(
                            got, want,
                            "{x} ({src}, raw {raw}) -> {dst} with {q}/{o}: got raw {got}, want {want}"
                        );
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(checked > 1_000_000, "sweep too small: {checked}");
}

#[test]
fn convert_wide_shifts_and_extremes() {
    // Shifts of 127 bits and more, and 128-bit formats, where the fast path cannot be used.
    let src = Format::signed(64, 100);
    let dst = Format::signed(8, -20);
    for raw in [i64::MIN as i128, -1, 0, 1, i64::MAX as i128] {
        let x = Fx::from_raw(src, raw);
        for q in Quant::ALL {
            let got = x.convert(dst, q, Overflow::Saturate).raw();
            // |value| < 2^-36: rounds to 0, or to -1 (Trunc / ties impossible) for negatives.
            let want = match q {
                Quant::Trunc if raw < 0 => -1,
                _ => 0,
            };
            assert_eq!(got, want, "{q} raw {raw}");
        }
    }
    let big = Fx::from_raw(Format::sint(128), i128::MIN);
    assert_eq!(
        big.convert(Format::sint(8), Quant::Trunc, Overflow::Saturate)
            .raw(),
        -128
    );
    assert_eq!(
        big.convert(Format::sint(8), Quant::Trunc, Overflow::Wrap)
            .raw(),
        0
    );
    // Widening far to the left overflows every format.
    let one = Fx::from_int(Format::uint(2), 1);
    let far = one.convert(Format::signed(16, 120), Quant::Trunc, Overflow::Saturate);
    assert_eq!(far.raw(), i16::MAX as i128);
}

#[test]
fn arithmetic_is_full_precision_exhaustive() {
    let fs = formats(4, -1..=3);
    for &a in &fs {
        for &b in &fs {
            for ra in all_raw(a) {
                for rb in all_raw(b) {
                    let x = Fx::from_raw(a, ra);
                    let y = Fx::from_raw(b, rb);
                    // Exact rational reference with denominator 2^8.
                    let sc = |r: i128, f: &Format| r * (1i128 << (8 - f.frac()));
                    let (vx, vy) = (sc(ra, &a), sc(rb, &b));
                    let s = x + y;
                    assert_eq!(sc(s.raw(), &s.fmt()), vx + vy, "{x}+{y}");
                    let d = x - y;
                    assert_eq!(sc(d.raw(), &d.fmt()), vx - vy, "{x}-{y}");
                    assert!(d.fmt().is_signed());
                    let p = x * y;
                    assert_eq!(p.fmt().width(), a.width() + b.width());
                    assert_eq!(p.fmt().frac(), a.frac() + b.frac());
                    assert_eq!(
                        p.raw() * (1i128 << (16 - p.fmt().frac())),
                        vx * vy,
                        "{x}*{y}"
                    );
                    let n = -x;
                    assert_eq!(n.raw(), -ra);
                    assert_eq!(x.partial_cmp(&y), vx.partial_cmp(&vy));
                }
            }
        }
    }
}

#[test]
fn sum_grows_one_bit_product_adds_widths() {
    let a = Format::signed(8, 4);
    let b = Format::signed(8, 4);
    assert_eq!(Format::sum(a, b), Format::signed(9, 4));
    assert_eq!(Format::product(a, b), Format::signed(16, 8));
    let u = Format::unsigned(8, 8);
    assert_eq!(Format::sum(u, u), Format::unsigned(9, 8));
    // unsigned inside a signed result gains its sign bit
    assert_eq!(Format::sum(u, a), Format::signed(13, 8));
    assert_eq!(Format::difference(u, u), Format::signed(10, 8));
    assert_eq!(
        Format::product(Format::sint(64), Format::sint(64)),
        Format::sint(128)
    );
}

#[test]
fn formats_are_checked() {
    assert!(Format::try_new(0, 0, false).is_err());
    assert!(Format::try_new(128, 0, false).is_err());
    assert!(Format::try_new(128, 0, true).is_ok());
    assert!(Format::try_new(8, 121, true).is_err());
    assert!(std::panic::catch_unwind(|| Fx::from_raw(Format::uint(4), 16)).is_err());
    assert!(std::panic::catch_unwind(|| Fx::from_raw(Format::sint(4), -9)).is_err());
    assert!(
        std::panic::catch_unwind(|| Format::product(Format::uint(64), Format::uint(64))).is_err()
    );
    for s in ["uQ1.7", "sQ2.14", "u8", "s12", "uQ0.9"] {
        assert_eq!(Format::parse(s).unwrap().to_string(), s);
    }
    for s in ["", "x8", "u0", "uQ1", "sQa.b", "u200"] {
        assert!(Format::parse(s).is_err(), "{s}");
    }
}

#[test]
fn formatting_is_exact() {
    let f = Format::signed(10, 4);
    assert_eq!(Fx::from_raw(f, -1).to_string(), "-0.0625");
    assert_eq!(format!("{:#x}", Fx::from_raw(f, -1)), "0x3ff");
    assert_eq!(format!("{:x}", Fx::from_raw(f, 0x25)), "025");
    assert_eq!(format!("{:b}", Fx::from_raw(f, 5)), "0000000101");
    assert_eq!(
        Fx::from_raw(Format::unsigned(9, 9), 257).to_string(),
        "0.501953125"
    );
    assert_eq!(Fx::from_raw(Format::signed(6, -3), -3).to_string(), "-24");
    assert_eq!(Fx::from_bits(f, 0x3ff).raw(), -1);
    assert_eq!(Fx::from_raw(f, 5).to_bitvec().len(), 10);
}

#[test]
fn fixed_crate_interop() {
    use fixed::types::{I16F0, I8F8, U0F16};
    let x = Fx::from_fixed(I8F8::from_num(-1.25));
    assert_eq!(x.fmt(), Format::signed(16, 8));
    assert_eq!(x.raw(), -320);
    assert_eq!(x.to_fixed::<I8F8>(), Some(I8F8::from_num(-1.25)));
    assert_eq!(x.to_fixed::<U0F16>(), None);
    // The width is the integer bits plus the fraction bits (a type without fraction bits too).
    let five = Fx::from_int(Format::signed(8, 0), 5);
    assert_eq!(five.to_fixed::<I16F0>(), Some(I16F0::from_num(5)));
}

#[test]
fn from_f64_rejects_nan_and_quantises_exactly() {
    let f = Format::signed(8, 4);
    assert_eq!(
        Fx::from_f64(f, f64::NAN, Quant::Trunc, Overflow::Wrap),
        Err(FxError::NotFinite)
    );
    let r = |x: f64, q| Fx::from_f64(f, x, q, Overflow::Saturate).unwrap().raw();
    assert_eq!(r(0.03125, Quant::RoundHalfEven), 0); // tie at 0.5 LSB -> even
    assert_eq!(r(0.09375, Quant::RoundHalfEven), 2); // 1.5 LSB -> 2
    assert_eq!(r(-0.03125, Quant::RoundHalfUp), 0);
    assert_eq!(r(-0.03125, Quant::Trunc), -1);
    assert_eq!(r(1e300, Quant::Trunc), 127);
    assert_eq!(r(5e-324, Quant::RoundHalfUp), 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    /// Wide formats: conversion agrees with the rational reference where it can be computed.
    #[test]
    fn convert_random_wide(
        sw in 1u32..=60, sf in -8i32..=60, ss: bool,
        dw in 1u32..=60, df in -8i32..=60, ds: bool,
        seed: i128, qi in 0usize..7, oi in 0usize..4,
    ) {
        let src = Format::new(sw, sf, ss);
        let dst = Format::new(dw, df, ds);
        let span = src.max_raw() - src.min_raw() + 1;
        let raw = src.min_raw() + seed.rem_euclid(span);
        let (q, o) = (Quant::ALL[qi], Overflow::ALL[oi]);
        let d = df - sf;
        prop_assume!(d.abs() < 60);
        let got = Fx::from_raw(src, raw).convert(dst, q, o).raw();
        prop_assert_eq!(got, ref_convert(raw, src, dst, q, o));
    }
}

#[test]
fn upper_hex() {
    let x = Fx::from_raw(Format::signed(10, 4), -2);
    assert_eq!(format!("{x:X}"), "3FE");
    assert_eq!(format!("{x:#X}"), "0x3FE");
}

/// The modes' names are the ones the command line and the format tables use, and they
/// parse back (a mutated name would break `--rounding`-style options and the tables).
#[test]
fn mode_names_are_fixed_and_parse_back() {
    let q: Vec<&str> = Quant::ALL.iter().map(|m| m.name()).collect();
    assert_eq!(
        q,
        [
            "trunc",
            "trunc-zero",
            "round-half-up",
            "round-half-zero",
            "round-half-away",
            "round-half-down",
            "round-half-even"
        ]
    );
    let o: Vec<&str> = Overflow::ALL.iter().map(|m| m.name()).collect();
    assert_eq!(
        o,
        ["wrap", "saturate", "saturate-symmetric", "saturate-zero"]
    );
    for m in Quant::ALL {
        assert_eq!(m.name().parse::<Quant>(), Ok(m));
        assert_eq!(m.to_string(), m.name());
    }
    for m in Overflow::ALL {
        assert!(!m.name().is_empty());
        assert_eq!(m.name().parse::<Overflow>(), Ok(m));
    }
    assert!("xyzzy".parse::<Quant>().is_err());
}

/// Mixed signedness: an unsigned operand gains a sign bit inside a signed result, whichever
/// side it is on; a product is signed if either factor is; a negation is one bit wider.
#[test]
fn mixed_signedness_widths() {
    let (u4, s4) = (Format::uint(4), Format::sint(4));
    assert_eq!(Format::sum(u4, s4), Format::sint(6));
    assert_eq!(Format::sum(s4, u4), Format::sint(6));
    assert_eq!(Format::sum(u4, u4), Format::uint(5));
    assert_eq!(Format::difference(u4, u4), Format::sint(6));
    assert_eq!(Format::product(u4, s4), Format::sint(8));
    assert_eq!(Format::product(s4, u4), Format::sint(8));
    assert_eq!(Format::product(u4, u4), Format::uint(8));
    assert_eq!(Format::negation(Format::uint(8)), Format::sint(9));
    assert_eq!(Format::negation(Format::signed(3, 2)), Format::signed(4, 2));
}

/// The limits of a format, and the messages that name them.
#[test]
fn format_limits_and_their_messages() {
    let m = super::format::MAX_FRAC;
    assert!(Format::try_new(8, -m, true).is_ok());
    assert!(Format::try_new(8, m, true).is_ok());
    let e = Format::try_new(8, -m - 1, true).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("fraction bits {} out of range -{m}..={m}", -m - 1)
    );
    assert!(Format::try_new(8, m + 1, true).is_err());
    let e = Format::try_new(0, 0, false).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("width 0 out of range: unsigned formats hold 1..="),
        "{e}"
    );
}

/// The machine-word fast paths of `quantise` at their edges: powers of two and their
/// neighbours (values whose low bits are all zero are where a wrong shift looks like a fit),
/// destination widths below 64 and three wider (which must not take the 64-bit path), shifts
/// up to 66, every mode, against the reference.
#[test]
fn quantise_fast_paths_at_their_edges() {
    let mut values = vec![0i128];
    for k in 0..70 {
        for d in [-1i128, 0, 1] {
            values.push((1i128 << k) + d);
            values.push(-(1i128 << k) + d);
        }
    }
    for w in (1..=64u32).step_by(3).chain([62, 63, 64, 65, 100, 126]) {
        for signed in [false, true] {
            let dst = Format::new(w, 0, signed);
            for shift in [1, 2, 31, 61, 62, 63, 64, 66] {
                let src = Format::new(127, shift, true);
                for &raw in &values {
                    for q in Quant::ALL {
                        for o in Overflow::ALL {
                            let got = quantise(raw, shift, dst, q, o);
                            let want = ref_convert(raw, src, dst, q, o);
                            assert_eq!(got, want, "raw {raw} >> {shift} into {dst} {q} {o}");
                        }
                    }
                }
            }
        }
    }
}

/// The shift-and-round of the word paths, in both machine words, at every shift it is used
/// with, on values around every power of two (ties, one either side of them, the extremes),
/// every mode, against the reference.
#[test]
fn round_shift_at_every_shift() {
    let mut values = vec![0i128, i128::from(i64::MIN), i128::from(i64::MAX)];
    for k in 0..63 {
        for d in [-1i128, 0, 1] {
            values.push((1i128 << k) + d);
            values.push(-(1i128 << k) + d);
            values.push(3 * (1i128 << k) + d);
            values.push(-3 * (1i128 << k) + d);
        }
    }
    for q in Quant::ALL {
        for s in 1..63u32 {
            for &r in values.iter().filter(|&&r| i64::try_from(r).is_ok()) {
                let want = ref_round(r, 1i128 << s, q);
                let got = super::value::round_shift(r as i64, s, q);
                assert_eq!(i128::from(got), want, "i64 {r} >> {s} {q}");
            }
        }
        for s in 1..127u32 {
            for &r in &values {
                for v in [r, r << 60, i128::MIN + r.abs(), i128::MAX - r.abs()] {
                    let want = ref_round(v, 1i128 << s, q);
                    let got = super::value::round_shift(v, s, q);
                    assert_eq!(got, want, "i128 {v} >> {s} {q}");
                }
            }
        }
    }
}

/// Widening by 128 fraction bits or more: every bit of the value is above the destination's
/// width, so wrapping leaves zero and saturation the extreme of the value's sign.
#[test]
fn widening_past_the_word() {
    let src = Format::signed(8, -120);
    let dst = Format::signed(16, 8);
    for raw in [3i128, -3, 1, 127] {
        let x = Fx::from_raw(src, raw);
        assert_eq!(
            x.convert(dst, Quant::Trunc, Overflow::Wrap).raw(),
            0,
            "{raw}"
        );
        let sat = x.convert(dst, Quant::Trunc, Overflow::Saturate).raw();
        assert_eq!(
            sat,
            if raw < 0 {
                dst.min_raw()
            } else {
                dst.max_raw()
            }
        );
    }
}

/// The fast paths of `quantise` cover what they are meant to, no more and no less (a path
/// that is taken too rarely is still exact, so only the path shows it): each case with its
/// value (against the reference) and its path.
#[test]
fn quantise_takes_the_path_meant_for_each_input() {
    use crate::fx::value::{quantise, PATH};
    let s = |w, f| Format::signed(w, f);
    let u = |w, f| Format::unsigned(w, f);
    let (q, sym, sat) = (
        Quant::RoundHalfUp,
        Overflow::SaturateSymmetric,
        Overflow::Saturate,
    );
    // (raw, source fraction bits, destination, overflow, path)
    let cases: [(i128, i32, Format, Overflow, u8); 18] = [
        (5, 4, s(12, 4), sym, 1),
        (0, 4, u(12, 4), sym, 1),
        (-7, 4, s(12, 4), sat, 1),
        (1234, 14, s(16, 4), sat, 2),
        (1234, 14, s(16, 4), sym, 2),
        (-1234, 73, s(16, 10), sat, 3),
        (99_999, 16, s(62, 8), sat, 2),
        (99_999, 16, s(63, 8), sat, 4),
        ((1 << 70) + 12345, 40, s(40, 0), sym, 3),
        ((1 << 70) + 12345, 40, s(40, 0), sat, 3),
        (-(1 << 70), 40, s(63, 0), sat, 4),
        ((1 << 120) + 3, 100, s(40, 0), sat, 4),
        ((1 << 126) + 3, 127, s(8, 0), sat, 5),
        (77, -3, s(40, 0), sat, 5),
        (1234, 4, s(8, 4), sat, 6),
        (-1234, 4, s(8, 4), sym, 6),
        (-1_000_000, 14, s(8, 4), sym, 6),
        (1_000_000, 14, u(8, 4), sym, 6),
    ];
    for (raw, frac, dst, o, path) in cases {
        let v = quantise(raw, frac, dst, q, o);
        let d = dst.frac() - frac;
        let want = if d >= 0 {
            ref_overflow(raw << d, dst, o)
        } else if d > -127 {
            ref_overflow(ref_round(raw, 1i128 << -d, q), dst, o)
        } else {
            // 2^126 + 3 in units of 2^-127: just over one half, which rounds up to 1.
            1
        };
        assert_eq!(v, want, "{raw} {frac} {dst} {o:?}");
        assert_eq!(PATH.with(|p| p.get()), path, "{raw} {frac} {dst} {o:?}");
    }
}

/// The small accessors, exhaustively over 6-bit formats: sign, zero, each bit of the two's
/// complement pattern, hex as `{:#x}` prints it, and `fits` against conversion.
#[test]
fn accessors_agree_with_the_raw_value() {
    for f in formats(6, -2..=3) {
        for raw in all_raw(f) {
            let x = Fx::from_raw(f, raw);
            assert_eq!(x.is_negative(), raw < 0, "{f} {raw}");
            assert_eq!(x.is_zero(), raw == 0, "{f} {raw}");
            for i in 0..f.width() {
                assert_eq!(x.bit(i), (raw >> i) & 1 == 1, "{f} {raw} bit {i}");
            }
            assert_eq!(x.to_hex(), format!("{x:#x}"), "{f} {raw}");
            for g in [
                Format::signed(4, 1),
                Format::unsigned(3, 0),
                Format::signed(8, 4),
            ] {
                // Exactly representable: truncation and saturation leave the value as it is.
                let kept = x.convert(g, Quant::Trunc, Overflow::Saturate);
                let fits = kept.cmp_value(&x) == std::cmp::Ordering::Equal;
                assert_eq!(x.fits(g), fits, "{x} ({f}) in {g}");
            }
        }
    }
    let s = Format::signed(4, 1);
    assert!(Fx::from_f64(s, 0.5, Quant::Trunc, Overflow::Wrap)
        .unwrap()
        .fits(s));
    assert!(!Fx::from_raw(Format::signed(4, 2), 1).fits(s)); // 0.25: a bit too fine
    assert!(!Fx::from_int(Format::signed(8, 0), 4).fits(s)); // 4: out of range
    assert_eq!(Fx::from_raw(Format::unsigned(9, 0), 500).to_hex(), "0x1f4");
}

/// Zero prints without a sign, and compares by value with operands whose binary points are
/// far apart (alignment by 130 bits and more cannot be done in an i128: zero still can).
#[test]
fn zero_prints_unsigned_and_compares_across_far_binary_points() {
    assert_eq!(Fx::zero(Format::signed(8, 4)).to_string(), "0");
    assert_eq!(Fx::zero(Format::signed(8, -4)).to_string(), "0");
    let zero = Fx::zero(Format::signed(8, -10));
    let tiny = Fx::from_raw(Format::signed(8, 120), 1);
    use std::cmp::Ordering::{Greater, Less};
    // Both operand orders: the alignment of either side is tried.
    assert_eq!(
        (zero.cmp_value(&tiny), tiny.cmp_value(&zero)),
        (Less, Greater)
    );
    assert_eq!(
        (zero.cmp_value(&-tiny), (-tiny).cmp_value(&zero)),
        (Greater, Less)
    );
    assert_eq!(
        zero.cmp_value(&Fx::zero(Format::signed(8, 120))),
        std::cmp::Ordering::Equal
    );
    let big = Fx::from_raw(Format::signed(8, -120), 1);
    assert_eq!(
        (tiny.cmp_value(&big), big.cmp_value(&tiny)),
        (Less, Greater)
    );
}

/// A named narrowing gives exactly what `quantise` gives (its machine-word path included),
/// with tracking off and on: every value of the small source formats into the small
/// destinations, and the edges of the word path (destinations of 1 to 65 bits, shifts up to
/// 66, values around every power of two up to 2^69), in every mode.
#[test]
fn a_narrowing_is_quantise() {
    let check = |raws: &mut dyn Iterator<Item = (i128, i32)>, dst: Format| {
        let cases: Vec<(i128, i32)> = raws.collect();
        for q in Quant::ALL {
            for o in Overflow::ALL {
                let mut n = Narrowing::new("n", dst, q, o);
                for tracked in [false, true] {
                    set_tracking(tracked);
                    for &(raw, frac) in &cases {
                        let want = quantise(raw, frac, dst, q, o);
                        assert_eq!(n.raw(raw, frac), want, "{raw} >> {frac} into {dst} {q} {o}");
                    }
                }
                set_tracking(false);
            }
        }
    };
    for dst in formats(5, -2..=6) {
        for src in formats(7, -2..=6) {
            check(&mut all_raw(src).map(|r| (r, src.frac())), dst);
        }
    }
    let mut values = vec![0i128];
    for k in 0..70 {
        for d in [-1i128, 0, 1] {
            values.extend([(1i128 << k) + d, -(1i128 << k) + d]);
        }
    }
    for w in (1..=65u32).step_by(4).chain([61, 62, 63, 64]) {
        for signed in [false, true] {
            let shifts = [0, 1, 2, 31, 61, 62, 63, 64, 66];
            let mut cases = values.iter().flat_map(|&r| shifts.map(|s| (r, s)));
            check(&mut cases, Format::new(w, 0, signed));
        }
    }
    // Values wider than a word with every pattern of rounding bits (a product such as rsqrt
    // 156's `m y^2`, whose rounded result the word path finds from the low word): seeded
    // pseudo-random 65- to 127-bit values of both signs, every shift that path takes and
    // either side of it, into destinations whose range holds some results and not others.
    let mut x = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let wide: Vec<i128> = (0..400)
        .map(|_| (i128::from(next()) << 64 | i128::from(next())) >> (next() % 63))
        .collect();
    for w in [8, 33, 62, 63, 64] {
        for signed in [false, true] {
            let mut cases = wide.iter().flat_map(|&r| (0..=65).map(move |s| (r, s)));
            check(&mut cases, Format::new(w, 0, signed));
        }
    }
}
