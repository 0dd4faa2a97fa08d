//! Named narrowings: a unit's `convert`s as parts of the unit, each with a stable name, a
//! destination format and its modes fixed at construction, and, when numeric tracking is on,
//! counts of what it met: values narrowed, overflows above and below (saturated or wrapped,
//! as the mode says), rounding ties, values that lost fraction bits, and the range of the
//! values before narrowing.

use super::value::{dropped, quantise_wide, round_shift, rounded};
use super::{Fmt, Format, Fx, Overflow, Quant};
use crate::kernel::Signal;
use std::cell::Cell;
use std::marker::PhantomData;

thread_local! {
    static TRACKING: Cell<bool> = const { Cell::new(false) };
}

/// Turns numeric tracking on or off for every narrowing applied on this thread (off by
/// default: then a narrowing is its `quantise` and one thread-local test).
pub fn set_tracking(on: bool) {
    TRACKING.with(|t| t.set(on));
}

/// Whether numeric tracking is on for this thread.
#[inline(always)]
pub fn tracking() -> bool {
    TRACKING.with(Cell::get)
}

/// What one narrowing met while tracking was on.
#[derive(Clone, Debug, PartialEq)]
pub struct NarrowStats {
    /// Values narrowed.
    pub narrowed: u64,
    /// Values above the destination's largest (saturated, or wrapped under `Wrap`).
    pub over_high: u64,
    /// Values below the destination's smallest (below `-max` under symmetric saturation).
    pub over_low: u64,
    /// Values exactly half-way between two destination codes, under a mode with a tie rule.
    pub ties: u64,
    /// Values that lost fraction bits (not exactly representable before overflow).
    pub inexact: u64,
    /// The range before narrowing, exactly: each end a raw value and its fraction bits.
    range: Option<[(i128, i32); 2]>,
    /// The ends rounded into the destination (before any overflow rule): a value whose
    /// rounding lies strictly between them lies strictly inside the range (rounding is
    /// monotonic), so only the others are compared exactly. Empty: `MAX`, `MIN`.
    rounded: (i128, i128),
}

impl Default for NarrowStats {
    fn default() -> Self {
        NarrowStats {
            narrowed: 0,
            over_high: 0,
            over_low: 0,
            ties: 0,
            inexact: 0,
            range: None,
            rounded: (i128::MAX, i128::MIN),
        }
    }
}

impl NarrowStats {
    /// Adds another run's counts (shards of one regression, configurations of one unit).
    pub fn merge(&mut self, o: &NarrowStats) {
        self.narrowed += o.narrowed;
        self.over_high += o.over_high;
        self.over_low += o.over_low;
        self.ties += o.ties;
        self.inexact += o.inexact;
        for (raw, frac) in o.range.into_iter().flatten() {
            self.widen_slow(raw, frac);
        }
        self.rounded = (
            self.rounded.0.min(o.rounded.0),
            self.rounded.1.max(o.rounded.1),
        );
    }

    /// Widens the range to hold `raw * 2^-frac`, which rounds to `v` in the destination:
    /// exactly, where `v` is not strictly between the rounded ends (rare once a run has
    /// spread), else nothing to do.
    #[inline(always)]
    fn widen_rounded(&mut self, raw: i128, frac: i32, v: i128) {
        let (lo, hi) = self.rounded;
        if v <= lo || v >= hi {
            self.rounded = (lo.min(v), hi.max(v));
            self.widen_raw(raw, frac);
        }
    }

    /// The smallest value before narrowing, exactly (`None` before the first).
    pub fn min(&self) -> Option<Fx> {
        self.range.and_then(|[lo, _]| end(lo))
    }

    /// The largest value before narrowing, exactly.
    pub fn max(&self) -> Option<Fx> {
        self.range.and_then(|[_, hi]| end(hi))
    }

    /// Widens the range to hold `raw * 2^-frac`. Both ends are kept with the same fraction
    /// bits where they fit an i128 that way, so a value of no more fraction bits than theirs
    /// (a narrowing's source keeps its format, or varies within a few bits) is compared with
    /// one shift and two integer compares.
    #[inline(always)]
    fn widen_raw(&mut self, raw: i128, frac: i32) {
        if let Some([lo, hi]) = &mut self.range {
            let sh = lo.1 - frac;
            let aligned = match sh {
                0 => Some(raw),
                1..127 => Some(raw << sh).filter(|v| v >> sh == raw),
                _ => None,
            };
            if let Some(v) = aligned.filter(|_| lo.1 == hi.1) {
                if v < lo.0 {
                    lo.0 = v;
                } else if v > hi.0 {
                    hi.0 = v;
                }
                return;
            }
        }
        self.widen_slow(raw, frac);
    }

    /// [`NarrowStats::widen_raw`] by value, then both ends in one format where they fit it
    /// (a value whose fraction bits no format can have is left out, as it cannot be shown).
    #[cold]
    fn widen_slow(&mut self, raw: i128, frac: i32) {
        let x = (raw, frac);
        let Some(xv) = end(x) else { return };
        let [mut lo, mut hi] = self.range.unwrap_or([x, x]);
        if end(lo).is_none_or(|v| xv.cmp_value(&v).is_lt()) {
            lo = x;
        }
        if end(hi).is_none_or(|v| xv.cmp_value(&v).is_gt()) {
            hi = x;
        }
        // The most fraction bits seen, this value's included: later values with as many
        // take the direct comparison.
        let f = lo.1.max(hi.1).max(frac);
        let up = |(r, fr): (i128, i32)| {
            let s = (f - fr) as u32;
            let v = r.checked_shl(s)?;
            (v >> s == r).then_some((v, f))
        };
        if let (Some(a), Some(b)) = (up(lo), up(hi)) {
            (lo, hi) = (a, b);
        }
        self.range = Some([lo, hi]);
    }
}

/// `raw * 2^-frac` as a value, in a signed 128-bit format of its fraction bits (`None` where
/// a format cannot have that many).
fn end((raw, frac): (i128, i32)) -> Option<Fx> {
    let f = Format::try_new(128, frac, true).ok()?;
    Some(Fx::from_fitting_raw(f, raw))
}

/// A path through a narrowing that numeric coverage counts: an overflow on either side, a
/// rounding tie.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NarrowPath {
    /// A value above the destination's range (saturated, or wrapped).
    High,
    /// A value below it.
    Low,
    /// A value exactly half-way between two codes, under a mode with a tie rule.
    Tie,
}

impl NarrowPath {
    /// Its name in reports: `high`, `low`, `tie`.
    pub fn name(self) -> &'static str {
        match self {
            NarrowPath::High => "high",
            NarrowPath::Low => "low",
            NarrowPath::Tie => "tie",
        }
    }
}

/// One narrowing of a unit, named (its path in the hierarchy is the unit's instance path and
/// this name: `normal_pipeline_fig7.normal_156.nx`). `raw` and `fx` give exactly what
/// [`quantise`](super::quantise) and [`Fx::convert`] give.
///
/// While tracking is on, its flag (a one-bit wire `<name>_sat`, or `<name>_wrap` under
/// [`Overflow::Wrap`], in the unit's waveform scope) tells whether the latest value narrowed
/// overflowed: high from the evaluation that saturated (or wrapped) until one that did not.
/// A wire of the evaluation, so the kernel's schedule check holds for it (evaluating twice
/// sets it twice alike; the clock edge leaves it).
#[derive(Clone, Debug)]
pub struct Narrowing {
    name: &'static str,
    dst: Format,
    q: Quant,
    o: Overflow,
    stats: NarrowStats,
    flag: Signal,
    unreachable: Vec<(NarrowPath, &'static str)>,
    /// The destination's largest raw value and its smallest under the overflow mode (`-max`
    /// under symmetric saturation), and whether the rounding mode has a tie rule.
    top: i128,
    bottom: i128,
    /// The same range in machine words, for the fast path ([`Narrowing::in_words`]); empty
    /// (`0..=-1`) for a destination of 63 bits or more, which that path leaves to `quantise`.
    lo: i64,
    hi: i64,
    tie_rule: bool,
    /// The modes, as one of the common pairs (one byte to test where a narrowing is applied).
    modes: Modes,
}

/// [`Narrowing::record`]'s modes: round half to even, truncate, the narrowing's own.
const EVEN: u8 = 6;
const TRUNC: u8 = 0;
const ANY: u8 = u8::MAX;
const _: () = assert!(matches!(Quant::ALL[EVEN as usize], Quant::RoundHalfEven));
const _: () = assert!(matches!(Quant::ALL[TRUNC as usize], Quant::Trunc));

/// The common pairs of a rounding and an overflow mode, which a narrowing applies with the
/// modes as constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Modes {
    EvenSaturate,
    EvenSymmetric,
    TruncWrap,
    Other,
}

impl Modes {
    fn of(q: Quant, o: Overflow) -> Modes {
        match (q, o) {
            (Quant::RoundHalfEven, Overflow::Saturate) => Modes::EvenSaturate,
            (Quant::RoundHalfEven, Overflow::SaturateSymmetric) => Modes::EvenSymmetric,
            (Quant::Trunc, Overflow::Wrap) => Modes::TruncWrap,
            _ => Modes::Other,
        }
    }
}

/// A value wider than a word whose rounded result fits one (a product such as rsqrt 156's
/// `m y^2`), for [`Narrowing`]'s word path: the kept bits shifted down, the rounding bits
/// from the low word; `None` for any other. Inlined with the word path: where the value is
/// an `i64` widened, the compiler drops it; where it is wider, its rounding mode folds (rsqrt
/// 156 executed 7 % more instructions a cycle with it out of line).
#[inline]
fn wide_in_words(raw: i128, shift: i32, q: Quant) -> Option<i64> {
    if !(1..64).contains(&shift) {
        return None;
    }
    let floor = i64::try_from(raw >> shift).ok()?;
    let (low, s) = (raw as u64, shift as u32);
    let half = (low >> (s - 1)) & 1 == 1;
    let sticky = low & ((1u64 << (s - 1)) - 1) != 0;
    let inc = q.increment(raw < 0, floor & 1 == 1, half, sticky);
    floor.checked_add(i64::from(inc))
}

impl Narrowing {
    /// A narrowing named `name` into `dst`, rounding by `q`, overflow by `o`.
    pub fn new(name: &'static str, dst: Format, q: Quant, o: Overflow) -> Narrowing {
        let top = dst.max_raw();
        let bottom = if o == Overflow::SaturateSymmetric && dst.is_signed() {
            -dst.max_raw()
        } else {
            dst.min_raw()
        };
        let word = dst.width() < 63;
        Narrowing {
            name,
            dst,
            q,
            o,
            stats: NarrowStats::default(),
            flag: Signal::bit(flag_name(name, o)),
            unreachable: Vec::new(),
            top,
            bottom,
            lo: if word { bottom as i64 } else { 0 },
            hi: if word { top as i64 } else { -1 },
            tie_rule: has_tie_rule(q),
            modes: Modes::of(q, o),
        }
    }

    /// The same narrowing with `path` declared unreachable, for the reason `why` (a bound on
    /// the values that reach it): numeric coverage lists it with the reason instead of as a
    /// hole, and a run that reaches it after all says so as a failure.
    pub fn unreachable(mut self, path: NarrowPath, why: &'static str) -> Narrowing {
        self.unreachable.retain(|(p, _)| *p != path);
        self.unreachable.push((path, why));
        self
    }

    /// The same narrowing with both overflow paths declared unreachable for the reason `why`
    /// (a bound that keeps every value inside the destination).
    pub fn never_overflows(self, why: &'static str) -> Narrowing {
        self.unreachable(NarrowPath::High, why)
            .unreachable(NarrowPath::Low, why)
    }

    /// [`Narrowing::unreachable`] where `bound` holds (a bound the constructor proves from
    /// its widths, which are parameters: with other widths the path may be reachable).
    pub fn unreachable_if(self, bound: bool, path: NarrowPath, why: &'static str) -> Narrowing {
        if bound {
            self.unreachable(path, why)
        } else {
            self
        }
    }

    /// The paths declared unreachable, with their reasons.
    pub fn unreachable_paths(&self) -> &[(NarrowPath, &'static str)] {
        &self.unreachable
    }

    /// The overflow flag: whether the latest value narrowed overflowed (tracking on).
    pub fn flag(&self) -> &Signal {
        &self.flag
    }

    /// Its name within its unit.
    pub fn name(&self) -> &'static str {
        self.name
    }
    /// The destination format.
    pub fn dst(&self) -> Format {
        self.dst
    }
    /// The rounding mode.
    pub fn quant(&self) -> Quant {
        self.q
    }
    /// The overflow mode.
    pub fn overflow(&self) -> Overflow {
        self.o
    }
    /// What it met while tracking was on.
    pub fn stats(&self) -> &NarrowStats {
        &self.stats
    }

    /// `raw * 2^-src_frac` narrowed: [`quantise`](super::quantise) into the destination,
    /// counted when tracking.
    ///
    /// Inline, the count's call (when tracking) and the word path: a value and result within
    /// 64 bits, fewer than 63 bits dropped, the result inside the destination's range. The
    /// rest of `quantise` (a value out of range, a shift outside a word, a wide value) is one
    /// call out of line. The destination is a run-time value here, so `quantise` inlined in
    /// its place folded nothing and only grew the unit's `eval` around it.
    #[inline(always)]
    pub fn raw(&mut self, raw: i128, src_frac: i32) -> i128 {
        self.raw_into(raw, src_frac, |n| n.dst.frac())
    }

    /// [`Narrowing::raw`] with the destination's fraction bits from `frac`: a constant
    /// where the destination's format is one ([`NarrowingOf`]), so that the shift and its
    /// rounding fold. A closure rather than a value, so that the run-time format is read
    /// after the count's call, as `in_words` read it before: read at the call, the FIG. 7
    /// pipeline executed 15 more instructions a cycle (1899 against 1884).
    #[inline(always)]
    fn raw_into(&mut self, raw: i128, src_frac: i32, frac: impl Fn(&Self) -> i32) -> i128 {
        if tracking() {
            self.count(raw, src_frac);
        }
        let v = match self.modes {
            Modes::EvenSaturate | Modes::EvenSymmetric => {
                self.in_words(raw, src_frac, frac(self), Quant::RoundHalfEven)
            }
            Modes::TruncWrap => self.in_words(raw, src_frac, frac(self), Quant::Trunc),
            Modes::Other => self.in_words(raw, src_frac, frac(self), self.q),
        };
        match v {
            Some(v) => v,
            None => self.resolve(raw, src_frac),
        }
    }

    /// Counts one value narrowed ([`Narrowing::record`], its rounding mode a constant for the
    /// common modes).
    #[cold]
    #[inline(never)]
    fn count(&mut self, raw: i128, src_frac: i32) {
        match self.modes {
            Modes::EvenSaturate | Modes::EvenSymmetric => self.record::<EVEN>(raw, src_frac),
            Modes::TruncWrap => self.record::<TRUNC>(raw, src_frac),
            Modes::Other => self.record::<ANY>(raw, src_frac),
        }
    }

    /// The rest of [`quantise`](super::quantise), past the fast paths the word path has
    /// tried (a destination of 63 bits or more, which the word path leaves, takes `quantise`'s
    /// general path): a word value that saturates clamped in machine words, else the wide
    /// paths and the general one, with the modes constants where they are the common ones, so
    /// that their rounding and overflow logic folds as at a call site that names them.
    #[cold]
    #[inline(never)]
    fn resolve(&self, raw: i128, src_frac: i32) -> i128 {
        let dst = self.dst;
        let rest = |q, o| quantise_wide(raw, src_frac - dst.frac(), src_frac, dst, q, o);
        match self.modes {
            Modes::EvenSaturate => rest(Quant::RoundHalfEven, Overflow::Saturate),
            Modes::EvenSymmetric => rest(Quant::RoundHalfEven, Overflow::SaturateSymmetric),
            Modes::TruncWrap => rest(Quant::Trunc, Overflow::Wrap),
            Modes::Other => rest(self.q, self.o),
        }
    }

    /// [`quantise`](super::quantise)'s result where it is found in machine words with
    /// nothing to resolve: a value and result within 64 bits, fewer than 63 bits dropped,
    /// the result inside the destination's range (under the overflow mode), which the
    /// constructor worked out once. `None` where `quantise` has more to do.
    #[inline(always)]
    fn in_words(&self, raw: i128, src_frac: i32, dst_frac: i32, q: Quant) -> Option<i128> {
        let shift = src_frac - dst_frac;
        let v = match i64::try_from(raw) {
            Ok(r) => match shift {
                0 => r,
                1..63 => round_shift(r, shift as u32, q),
                _ => return None,
            },
            Err(_) => wide_in_words(raw, shift, q)?,
        };
        (v >= self.lo && v <= self.hi).then_some(i128::from(v))
    }

    /// `v` narrowed: [`Fx::convert`] into the destination, counted when tracking.
    #[inline(always)]
    pub fn fx(&mut self, v: Fx) -> Fx {
        Fx::from_fitting_raw(self.dst, self.raw(v.raw(), v.fmt().frac()))
    }

    /// Counts one value narrowed, rounding as mode `Q` (an index into [`Quant::ALL`], so
    /// that the common modes fold) or, for [`ANY`], as the narrowing's own mode.
    #[cold]
    #[inline(never)]
    fn record<const Q: u8>(&mut self, raw: i128, src_frac: i32) {
        let q = if Q == ANY {
            self.q
        } else {
            Quant::ALL[Q as usize]
        };
        let shift = src_frac - self.dst.frac();
        // The common case in 64-bit arithmetic: a value that fits an i64, rounded at a bit
        // inside it (what `quantise` computes in 64 bits too).
        let (v, huge, lost, tie) = match i64::try_from(raw) {
            Ok(r) if (1..63).contains(&shift) => {
                let s = shift as u32;
                let floor = r >> s;
                let half = (r >> (s - 1)) & 1 == 1;
                let sticky = r & ((1i64 << (s - 1)) - 1) != 0;
                let inc = q.increment(r < 0, floor & 1 == 1, half, sticky);
                let v = i128::from(floor + i64::from(inc));
                (v, false, half | sticky, half & !sticky)
            }
            _ => {
                let (v, huge) = rounded(raw, shift, q);
                let (lost, tie) = dropped(raw, shift);
                (v, huge, lost, tie)
            }
        };
        let s = &mut self.stats;
        s.narrowed += 1;
        s.inexact += u64::from(lost);
        s.ties += u64::from(tie & self.tie_rule);
        let (high, under) = if huge {
            (raw >= 0, raw < 0)
        } else {
            (v > self.top, v < self.bottom)
        };
        s.over_high += u64::from(high);
        s.over_low += u64::from(under);
        self.flag.set_flag(high | under);
        if huge {
            s.widen_raw(raw, src_frac);
        } else {
            s.widen_rounded(raw, src_frac, v);
        }
    }
}

/// A named narrowing into a format known at compile time (`F`, declared with
/// [`formats!`](crate::formats)): the typed style's [`Narrowing`]. `fx` gives what
/// `convert(F::FMT, q, o)` gives, as an `Fx` of the constant format `F::FMT`, by the same
/// word path as [`Narrowing::raw`] with the destination's fraction bits a constant: where the
/// source's are one too, the shift and its rounding fold away. It reads as a [`Narrowing`]
/// (its name, counts, flag).
///
/// ```
/// use hdl::fx::{Format, Fx, NarrowingOf, Overflow, Quant};
/// hdl::formats! {
///     Out = Format::signed(8, 4);
/// }
/// let mut n = NarrowingOf::<Out>::new("y", Quant::RoundHalfEven, Overflow::Saturate);
/// let v = Fx::from_raw(Format::signed(12, 6), 40); // 0.625
/// assert_eq!(n.fx(v), v.convert(Out::FMT, Quant::RoundHalfEven, Overflow::Saturate));
/// assert_eq!((n.name(), n.dst()), ("y", Out::FMT));
/// ```
pub struct NarrowingOf<F: Fmt> {
    inner: Narrowing,
    format: PhantomData<F>,
}

impl<F: Fmt> NarrowingOf<F> {
    /// A narrowing named `name` into `F`, rounding by `q`, overflow by `o`.
    pub fn new(name: &'static str, q: Quant, o: Overflow) -> NarrowingOf<F> {
        NarrowingOf {
            inner: Narrowing::new(name, F::FMT, q, o),
            format: PhantomData,
        }
    }

    /// The same narrowing with `path` declared unreachable ([`Narrowing::unreachable`]).
    pub fn unreachable(mut self, path: NarrowPath, why: &'static str) -> NarrowingOf<F> {
        self.inner = self.inner.unreachable(path, why);
        self
    }

    /// `v` narrowed into `F`: [`Fx::convert`], counted when tracking.
    #[inline(always)]
    pub fn fx(&mut self, v: Fx) -> Fx {
        Fx::from_fitting_raw(F::FMT, self.raw(v.raw(), v.fmt().frac()))
    }

    /// `raw * 2^-src_frac` narrowed into `F`: [`quantise`](super::quantise), counted when
    /// tracking.
    #[inline(always)]
    pub fn raw(&mut self, raw: i128, src_frac: i32) -> i128 {
        self.inner.raw_into(raw, src_frac, |_| F::FMT.frac())
    }
}

impl<F: Fmt> std::ops::Deref for NarrowingOf<F> {
    type Target = Narrowing;
    fn deref(&self) -> &Narrowing {
        &self.inner
    }
}

impl<F: Fmt> Clone for NarrowingOf<F> {
    fn clone(&self) -> Self {
        NarrowingOf {
            inner: self.inner.clone(),
            format: PhantomData,
        }
    }
}

impl<F: Fmt> std::fmt::Debug for NarrowingOf<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.inner.fmt(f)
    }
}

/// The flag's name, `<name>_sat` (`<name>_wrap` under wrapping), kept once per name for the
/// run (signal names are `&'static str`; a unit built many times names its flags once).
fn flag_name(name: &'static str, o: Overflow) -> &'static str {
    use std::collections::HashSet;
    use std::sync::{Mutex, OnceLock};
    static NAMES: OnceLock<Mutex<HashSet<&'static str>>> = OnceLock::new();
    let want = format!(
        "{name}_{}",
        if o == Overflow::Wrap { "wrap" } else { "sat" }
    );
    let mut names = NAMES
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(n) = names.get(want.as_str()) {
        return n;
    }
    let n: &'static str = Box::leak(want.into_boxed_str());
    names.insert(n);
    n
}

/// Whether the mode decides a tie by a rule of its own (the round-half modes).
fn has_tie_rule(q: Quant) -> bool {
    !matches!(q, Quant::Trunc | Quant::TruncZero)
}
