//! Fixed-point values: full-precision arithmetic, explicit quantisation.

use super::format::Format;
use super::modes::{Overflow, Quant};
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

/// A fixed-point value: `raw * 2^-frac` in a [`Format`].
///
/// `raw` always lies in the format's range: every constructor checks it.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Fx {
    raw: i128,
    fmt: Format,
}

/// Why a value could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum FxError {
    /// The raw integer is outside the format's range.
    OutOfRange {
        /// The raw integer.
        raw: i128,
        /// The format it does not fit.
        fmt: Format,
    },
    /// The value is not exactly representable (bits would be lost).
    Inexact {
        /// The value.
        value: Fx,
        /// The format that cannot hold it exactly.
        fmt: Format,
    },
    /// A floating-point input was NaN or infinite.
    NotFinite,
}

impl fmt::Display for FxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FxError::OutOfRange { raw, fmt } => write!(
                f,
                "raw value {raw} does not fit {fmt} ({}..={})",
                fmt.min_raw(),
                fmt.max_raw()
            ),
            FxError::Inexact { value, fmt } => write!(
                f,
                "{value} ({}) is not exactly representable in {fmt}",
                value.fmt
            ),
            FxError::NotFinite => f.write_str("NaN or infinite input"),
        }
    }
}

impl std::error::Error for FxError {}

/// Bit `i` of `raw`, two's complement, sign-extended to infinity.
#[inline]
fn bit(raw: i128, i: u32) -> bool {
    if i >= 127 {
        raw < 0
    } else {
        (raw >> i) & 1 == 1
    }
}

/// Whether any of bits `0..n` of `raw` (sign-extended) is set.
#[inline]
fn any_low(raw: i128, n: u32) -> bool {
    if n == 0 {
        false
    } else if n >= 128 {
        raw != 0
    } else {
        raw & ((1i128 << n) - 1) != 0
    }
}

// Which path the last `quantise` of this thread took (tests only, to hold the fast paths
// to the inputs they are meant to cover): 1 nothing dropped, 2 the 64-bit path, 3 a wide
// value with a word-sized result, 4 the i128 path, 5 the general one, 6 a word value
// saturated.
#[cfg(test)]
thread_local! {
    pub(crate) static PATH: std::cell::Cell<u8> = const { std::cell::Cell::new(0) };
}

#[inline(always)]
fn took(_path: u8) {
    #[cfg(test)]
    PATH.with(|p| p.set(_path));
}

/// The core of every narrowing: `raw * 2^-src_frac` into `dst`, rounding by `q`, then
/// resolving overflow by `o`; returns the raw integer of `dst`. Works for any shift, so floats
/// with tiny or huge exponents quantise exactly too. Datapath models call it directly on raw
/// integers whose formats they computed once, at construction.
#[inline(always)]
pub fn quantise(raw: i128, src_frac: i32, dst: Format, q: Quant, o: Overflow) -> i128 {
    let shift = src_frac - dst.frac();
    // Fast paths: nothing dropped, or fewer than 127 bits dropped, with the result in range.
    // The most negative code is out of range under symmetric saturation.
    let in_range = |v: i128| {
        dst.contains_raw(v)
            && !(o == Overflow::SaturateSymmetric && dst.is_signed() && v == dst.min_raw())
    };
    if shift == 0 && in_range(raw) {
        took(1);
        return raw;
    }
    // 64-bit path for values and shifts that fit a machine word.
    if shift > 0 && shift < 63 && dst.width() < 63 && raw == i128::from(raw as i64) {
        let v = round_shift(raw as i64, shift as u32, q);
        let w = dst.width();
        let fits = if dst.is_signed() {
            let t = v >> (w - 1);
            (t == 0 || t == -1) && !(o == Overflow::SaturateSymmetric && v == -(1i64 << (w - 1)))
        } else {
            v >> w == 0
        };
        if fits {
            took(2);
            return i128::from(v);
        }
    }
    quantise_wide(raw, shift, src_frac, dst, q, o)
}

/// [`quantise`] beyond machine words. First a raw value wider than 64 bits whose rounded
/// result fits one (a product such as rsqrt 156's `m y^2`, 74 bits): the rounding bits come
/// from the low word; then the same in i128; then the general case.
#[inline]
pub(crate) fn quantise_wide(
    raw: i128,
    shift: i32,
    src_frac: i32,
    dst: Format,
    q: Quant,
    o: Overflow,
) -> i128 {
    if let Some(v) = saturated_in_words(raw, shift, dst, q, o) {
        took(6);
        return v;
    }
    let in_range = |v: i128| {
        dst.contains_raw(v)
            && !(o == Overflow::SaturateSymmetric && dst.is_signed() && v == dst.min_raw())
    };
    if (1..64).contains(&shift) && dst.width() < 63 {
        let floor = raw >> shift;
        if floor == i128::from(floor as i64) {
            let low = raw as u64;
            let inc = q.increment(
                raw < 0,
                floor & 1 == 1,
                (low >> (shift - 1)) & 1 == 1,
                low & ((1u64 << (shift - 1)) - 1) != 0,
            );
            let v = floor + i128::from(inc);
            if in_range(v) {
                took(3);
                return v;
            }
        }
    }
    if shift > 0 && shift < 127 {
        let v = round_shift(raw, shift as u32, q);
        if in_range(v) {
            took(4);
            return v;
        }
    }
    took(5);
    quantise_general(raw, src_frac, dst, q, o)
}

/// A value of a word narrowed by fewer than 63 bits into a destination of fewer than 63,
/// under saturation: its rounded value clamped to the destination's range (from `-max` under
/// symmetric saturation of a signed one). `None` for any other mode or input.
#[inline]
fn saturated_in_words(raw: i128, shift: i32, dst: Format, q: Quant, o: Overflow) -> Option<i128> {
    let symmetric = match o {
        Overflow::Saturate => false,
        Overflow::SaturateSymmetric => dst.is_signed(),
        _ => return None,
    };
    if dst.width() >= 63 {
        return None;
    }
    let r = i64::try_from(raw).ok()?;
    let v = match shift {
        0 => r,
        1..63 => round_shift(r, shift as u32, q),
        _ => return None,
    };
    let top = dst.max_raw() as i64;
    let bottom = if symmetric {
        -top
    } else {
        dst.min_raw() as i64
    };
    Some(i128::from(v.clamp(bottom, top)))
}

/// `r >> s` (1 <= s < bits - 1) rounded by `q`, in any signed machine integer.
///
/// The dropped bits plus an offset that carries into the kept bits exactly when the mode
/// rounds up: for round half to even, `half - 1` plus the kept LSB (a tie carries only from
/// an odd value). The sum is below `2^(s+1)`, so it never overflows.
#[inline]
pub(crate) fn round_shift<T: num_traits::PrimInt + num_traits::Signed>(
    r: T,
    s: u32,
    q: Quant,
) -> T {
    let (zero, one) = (T::zero(), T::one());
    let floor = r >> s as usize;
    let low = (one << s as usize) - one;
    let half_less = low >> 1;
    let negative = if r < zero { one } else { zero };
    let offset = match q {
        Quant::Trunc => return floor,
        Quant::TruncZero => low & (zero - negative),
        Quant::RoundHalfUp => half_less + one,
        Quant::RoundHalfZero => half_less + negative,
        Quant::RoundHalfAway => half_less + one - negative,
        Quant::RoundHalfDown => half_less,
        Quant::RoundHalfEven => half_less + (floor & one),
    };
    floor + (((r & low) + offset) >> s as usize)
}

/// `raw * 2^-src_frac` rounded by `q` to units of `2^-dst_frac`, before any overflow rule;
/// `huge` marks a value that does not fit an i128 (then only its sign and low bits matter).
#[inline]
pub(crate) fn rounded(raw: i128, shift: i32, q: Quant) -> (i128, bool) {
    if shift > 0 {
        let s = shift as u32;
        let floor = if s >= 127 { raw >> 127 } else { raw >> s };
        let inc = q.increment(
            raw < 0,
            floor & 1 == 1,
            bit(raw, s - 1),
            any_low(raw, s - 1),
        );
        (floor + i128::from(inc), false)
    } else {
        let s = (-shift) as u32;
        if s == 0 {
            (raw, false)
        } else if s >= 127 {
            (if s >= 128 { 0 } else { raw.wrapping_shl(s) }, raw != 0)
        } else {
            let v = raw.wrapping_shl(s);
            (v, (v >> s) != raw)
        }
    }
}

/// What dropping `shift` bits of `raw` meets: whether any dropped bit is set, and whether the
/// dropped bits are exactly one half of the kept LSB (a tie).
#[inline]
pub(crate) fn dropped(raw: i128, shift: i32) -> (bool, bool) {
    if shift <= 0 {
        return (false, false);
    }
    let s = shift as u32;
    let (half, sticky) = (bit(raw, s - 1), any_low(raw, s - 1));
    (half || sticky, half && !sticky)
}

#[cold]
fn quantise_general(raw: i128, src_frac: i32, dst: Format, q: Quant, o: Overflow) -> i128 {
    let negative = raw < 0;
    let (value, huge) = rounded(raw, src_frac - dst.frac(), q);
    if !huge && dst.contains_raw(value) {
        if o == Overflow::SaturateSymmetric && dst.is_signed() && value == dst.min_raw() {
            return -dst.max_raw();
        }
        return value;
    }
    let below = if huge { negative } else { value < 0 };
    match o {
        Overflow::Wrap => {
            let bits = (value as u128) & dst.mask();
            sign_extend(bits, dst)
        }
        Overflow::Saturate => {
            if below {
                dst.min_raw()
            } else {
                dst.max_raw()
            }
        }
        Overflow::SaturateSymmetric => {
            if below {
                if dst.is_signed() {
                    -dst.max_raw()
                } else {
                    0
                }
            } else {
                dst.max_raw()
            }
        }
        Overflow::SaturateZero => 0,
    }
}

/// Interprets the low `width` bits as a value of `fmt` (sign-extending signed formats).
#[inline]
fn sign_extend(bits: u128, fmt: Format) -> i128 {
    let w = fmt.width();
    if fmt.is_signed() && w < 128 && (bits >> (w - 1)) & 1 == 1 {
        (bits | !fmt.mask()) as i128
    } else {
        bits as i128
    }
}

impl Fx {
    /// The value `raw * 2^-frac`; panics if `raw` does not fit `fmt`.
    #[track_caller]
    #[inline]
    pub fn from_raw(fmt: Format, raw: i128) -> Fx {
        Fx::try_from_raw(fmt, raw).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The value `raw * 2^-frac`, or an error if `raw` does not fit `fmt`.
    #[inline]
    pub fn try_from_raw(fmt: Format, raw: i128) -> Result<Fx, FxError> {
        if fmt.contains_raw(raw) {
            Ok(Fx { raw, fmt })
        } else {
            Err(FxError::OutOfRange { raw, fmt })
        }
    }

    /// The value whose two's complement bits are the low `width` bits of `bits` (higher bits
    /// must be zero: panics otherwise).
    #[track_caller]
    #[inline]
    pub fn from_bits(fmt: Format, bits: u128) -> Fx {
        assert!(
            bits & !fmt.mask() == 0,
            "bits {bits:#x} wider than {} bits of {fmt}",
            fmt.width()
        );
        Fx {
            raw: sign_extend(bits, fmt),
            fmt,
        }
    }

    /// A value whose raw integer the caller knows fits `fmt` (a signal's, checked when it was
    /// written): no check, no 128-bit mask.
    #[inline(always)]
    pub(crate) fn from_fitting_raw(fmt: Format, raw: i128) -> Fx {
        debug_assert!(fmt.contains_raw(raw), "{raw} does not fit {fmt}");
        Fx { raw, fmt }
    }

    /// The integer `v` in `fmt` (panics unless exactly representable).
    #[track_caller]
    pub fn from_int(fmt: Format, v: i128) -> Fx {
        Fx::from_raw(Format::sint(128), v).exact(fmt)
    }

    /// Zero in `fmt`.
    #[inline]
    pub fn zero(fmt: Format) -> Fx {
        Fx { raw: 0, fmt }
    }

    /// A float quantised into `fmt` by `q` and `o`, exactly as an integer would be (the float's
    /// mantissa and exponent are converted without any intermediate rounding).
    pub fn from_f64(fmt: Format, x: f64, q: Quant, o: Overflow) -> Result<Fx, FxError> {
        if !x.is_finite() {
            return Err(FxError::NotFinite);
        }
        if x == 0.0 {
            return Ok(Fx::zero(fmt));
        }
        let b = x.to_bits();
        let exp = ((b >> 52) & 0x7ff) as i32;
        let man = b & ((1u64 << 52) - 1);
        let (m, e) = if exp == 0 {
            (man, -1074)
        } else {
            (man | (1u64 << 52), exp - 1075)
        };
        let m = if x < 0.0 { -(m as i128) } else { m as i128 };
        Ok(Fx {
            raw: quantise(m, -e, fmt, q, o),
            fmt,
        })
    }

    /// The nearest f64 (exact for widths up to 53 bits). For display and golden comparison at
    /// the edges of a model, never inside one.
    #[inline]
    pub fn to_f64(self) -> f64 {
        (self.raw as f64) * 2f64.powi(-self.fmt.frac())
    }

    /// The raw integer: the value times 2^frac.
    pub const fn raw(self) -> i128 {
        self.raw
    }
    /// The value's format.
    pub const fn fmt(self) -> Format {
        self.fmt
    }

    /// The `width` bits of the value, two's complement.
    pub const fn bits(self) -> u128 {
        (self.raw as u128) & self.fmt.mask()
    }

    /// Bit `i` (0 = LSB) of the two's complement pattern.
    pub fn bit(self, i: u32) -> bool {
        assert!(
            i < self.fmt.width(),
            "bit {i} of a {}-bit value",
            self.fmt.width()
        );
        bit(self.raw, i)
    }

    /// The bits as a `bitvec` vector, LSB first, exactly `width` long.
    pub fn to_bitvec(self) -> bitvec::vec::BitVec<u64, bitvec::order::Lsb0> {
        (0..self.fmt.width()).map(|i| bit(self.raw, i)).collect()
    }

    /// Narrowing (or widening) conversion into `fmt`, rounding by `q`, overflow by `o`.
    #[inline]
    pub fn convert(self, fmt: Format, q: Quant, o: Overflow) -> Fx {
        Fx {
            raw: quantise(self.raw, self.fmt.frac(), fmt, q, o),
            fmt,
        }
    }

    /// Conversion that must not lose anything: panics if the value is not exactly
    /// representable in `fmt`.
    #[track_caller]
    #[inline]
    pub fn exact(self, fmt: Format) -> Fx {
        self.try_exact(fmt).unwrap_or_else(|e| panic!("{e}"))
    }

    /// Conversion that must not lose anything.
    #[inline]
    pub fn try_exact(self, fmt: Format) -> Result<Fx, FxError> {
        let t = self.convert(fmt, Quant::Trunc, Overflow::Wrap);
        if t.cmp_value(&self) == Ordering::Equal {
            Ok(t)
        } else {
            Err(FxError::Inexact { value: self, fmt })
        }
    }

    /// Whether the value is exactly representable in `fmt`.
    #[inline]
    pub fn fits(self, fmt: Format) -> bool {
        self.try_exact(fmt).is_ok()
    }

    /// Multiplies by `2^n` exactly: the raw bits stay, the binary point moves (a wire shift).
    #[track_caller]
    pub fn scale_pow2(self, n: i32) -> Fx {
        let fmt = Format::try_new(self.fmt.width(), self.fmt.frac() - n, self.fmt.is_signed())
            .unwrap_or_else(|e| panic!("{self} scaled by 2^{n}: {e}"));
        Fx { raw: self.raw, fmt }
    }

    /// Reinterprets the same bits as unsigned / signed (a wire relabel, as in Verilog
    /// `$unsigned` / `$signed`).
    pub fn reinterpret(self, signed: bool) -> Fx {
        let fmt = Format::new(self.fmt.width(), self.fmt.frac(), signed);
        Fx::from_bits(fmt, self.bits())
    }

    /// Compares the values (not the formats).
    #[inline]
    pub fn cmp_value(&self, other: &Fx) -> Ordering {
        let f = self.fmt.frac().max(other.fmt.frac());
        let a = align(self.raw, (f - self.fmt.frac()) as u32);
        let b = align(other.raw, (f - other.fmt.frac()) as u32);
        match (a, b) {
            (Some(a), Some(b)) => a.cmp(&b),
            // A value that overflows the alignment is larger in magnitude than the other.
            (None, _) => self.raw.cmp(&0),
            (_, None) => 0.cmp(&other.raw),
        }
    }

    /// Below zero.
    #[inline]
    pub fn is_negative(self) -> bool {
        self.raw < 0
    }
    /// Exactly zero.
    #[inline]
    pub fn is_zero(self) -> bool {
        self.raw == 0
    }

    /// Hex of the `width` bits, zero-padded to whole digits, e.g. `0x1f4`.
    pub fn to_hex(self) -> String {
        format!("{self:#x}")
    }
}

#[inline]
fn align(raw: i128, s: u32) -> Option<i128> {
    if s == 0 || raw == 0 {
        return Some(raw);
    }
    if s >= 127 {
        return None;
    }
    let v = raw.wrapping_shl(s);
    ((v >> s) == raw).then_some(v)
}

/// Whether every value of `fmt` fits an `i64` (then so does every value of a narrower operand).
#[inline(always)]
fn word(fmt: Format) -> bool {
    fmt.width() < 64 || (fmt.width() == 64 && fmt.is_signed())
}

/// `raw << s` for a left alignment `s`: in a machine word when the result's format fits one
/// (its value then does too), else in i128.
#[inline(always)]
fn aligned(raw: i128, s: i32, word: bool) -> i128 {
    if word {
        i128::from((raw as i64) << s)
    } else {
        raw << s
    }
}

impl Add for Fx {
    type Output = Fx;
    /// Full-precision sum: one bit wider than the wider operand.
    #[inline]
    fn add(self, rhs: Fx) -> Fx {
        let fmt = Format::sum(self.fmt, rhs.fmt);
        let word = word(fmt);
        let a = aligned(self.raw, fmt.frac() - self.fmt.frac(), word);
        let b = aligned(rhs.raw, fmt.frac() - rhs.fmt.frac(), word);
        Fx { raw: a + b, fmt }
    }
}

impl Sub for Fx {
    type Output = Fx;
    /// Full-precision difference: signed, one bit wider than the wider operand.
    #[inline]
    fn sub(self, rhs: Fx) -> Fx {
        let fmt = Format::difference(self.fmt, rhs.fmt);
        let word = word(fmt);
        let a = aligned(self.raw, fmt.frac() - self.fmt.frac(), word);
        let b = aligned(rhs.raw, fmt.frac() - rhs.fmt.frac(), word);
        Fx { raw: a - b, fmt }
    }
}

impl Mul for Fx {
    type Output = Fx;
    /// Full-precision product: `W1 + W2` bits, `F1 + F2` fraction bits.
    #[inline]
    fn mul(self, rhs: Fx) -> Fx {
        let fmt = Format::product(self.fmt, rhs.fmt);
        let raw = if word(fmt) {
            i128::from((self.raw as i64) * (rhs.raw as i64))
        } else {
            self.raw * rhs.raw
        };
        Fx { raw, fmt }
    }
}

impl Neg for Fx {
    type Output = Fx;
    /// Full-precision negation: signed, one bit wider.
    #[inline]
    fn neg(self) -> Fx {
        Fx {
            raw: -self.raw,
            fmt: Format::negation(self.fmt),
        }
    }
}

impl PartialOrd for Fx {
    /// Orders by value, whatever the formats.
    #[inline]
    fn partial_cmp(&self, other: &Fx) -> Option<Ordering> {
        Some(self.cmp_value(other))
    }
}

impl fmt::Display for Fx {
    /// The exact decimal value (a fixed-point number with F fraction bits has at most F
    /// decimal fraction digits).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let neg = self.raw < 0;
        let m = self.raw.unsigned_abs();
        let sign = if neg { "-" } else { "" };
        let fr = self.fmt.frac();
        if fr <= 0 {
            let s = (-fr) as u32;
            return match m.checked_mul(1u128.checked_shl(s).unwrap_or(0)) {
                Some(v) if s < 128 => write!(f, "{sign}{v}"),
                _ => write!(f, "{sign}{m}*2^{s}"),
            };
        }
        let fr = fr as u32;
        let (int, mut rest) = if fr >= 128 {
            (0, m)
        } else {
            (m >> fr, m & ((1u128 << fr) - 1))
        };
        write!(f, "{sign}{int}")?;
        if rest == 0 {
            return Ok(());
        }
        f.write_str(".")?;
        // rest / 2^fr, one decimal digit at a time; rest * 10 < 2^(fr+4) fits for fr <= 120.
        while rest != 0 {
            rest *= 10;
            let d = rest >> fr;
            rest &= (1u128 << fr) - 1;
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

/// `{:x}` / `{:X}`: the `width` bits zero-padded to whole hex digits; `{:#x}` adds `0x`.
macro_rules! hex_impl {
    ($tr:ident, $spec:literal, $alt:literal) => {
        impl fmt::$tr for Fx {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                let d = self.fmt.hex_digits();
                if f.alternate() {
                    write!(f, $alt, self.bits(), d = d)
                } else {
                    write!(f, $spec, self.bits(), d = d)
                }
            }
        }
    };
}

hex_impl!(LowerHex, "{:0d$x}", "0x{:0d$x}");
hex_impl!(UpperHex, "{:0d$X}", "0x{:0d$X}");

impl fmt::Binary for Fx {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let d = self.fmt.width() as usize;
        write!(f, "{:0d$b}", self.bits())
    }
}

/// Interoperation with the `fixed` crate where a standard width fits.
impl Fx {
    /// The exact value of a `fixed` number (e.g. `I8F8` becomes `sQ8.8`).
    pub fn from_fixed<F: fixed::traits::Fixed>(x: F) -> Fx {
        let fmt = Format::new(
            F::INT_NBITS + F::FRAC_NBITS,
            F::FRAC_NBITS as i32,
            F::IS_SIGNED,
        );
        let raw: i128 = x
            .to_bits()
            .try_into()
            .unwrap_or_else(|_| panic!("u128 fixed value beyond i128"));
        Fx::from_raw(fmt, raw)
    }

    /// The value as a `fixed` number, if it is exactly representable there.
    pub fn to_fixed<F: fixed::traits::Fixed>(self) -> Option<F> {
        let fmt = Format::try_new(
            F::INT_NBITS + F::FRAC_NBITS,
            F::FRAC_NBITS as i32,
            F::IS_SIGNED,
        )
        .ok()?;
        let v = self.try_exact(fmt).ok()?;
        F::Bits::try_from(v.raw).ok().map(F::from_bits)
    }
}

#[cfg(test)]
mod bit_tests {
    use super::*;

    /// Bits past the 127th are the sign, and "any low bit" over the whole width is "not zero".
    #[test]
    fn bits_beyond_the_word_are_the_sign() {
        for i in [127, 128, 200, u32::MAX] {
            assert!(bit(-1, i));
            assert!(bit(i128::MIN, i));
            assert!(!bit(0, i));
            assert!(!bit(5, i));
        }
        assert!(bit(4, 2) && !bit(4, 1));
        for n in [128, 129, 1000] {
            assert!(!any_low(0, n));
            assert!(any_low(1, n));
            assert!(any_low(-1, n));
        }
        assert!(!any_low(8, 3) && any_low(9, 3) && !any_low(9, 0));
    }

    /// The errors' messages name the value and the format.
    #[test]
    fn error_messages() {
        let f = Format::sint(4);
        let e = FxError::OutOfRange { raw: 9, fmt: f };
        assert_eq!(e.to_string(), "raw value 9 does not fit s4 (-8..=7)");
        assert_eq!(FxError::NotFinite.to_string(), "NaN or infinite input");
        let v = Fx::from_raw(Format::unsigned(2, 1), 1);
        let e = FxError::Inexact {
            value: v,
            fmt: Format::uint(4),
        };
        assert!(
            e.to_string()
                .ends_with("is not exactly representable in u4"),
            "{e}"
        );
    }
}
