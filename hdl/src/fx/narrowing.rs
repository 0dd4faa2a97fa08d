//! Named narrowings: a unit's `convert`s as parts of the unit, each with a stable name, a
//! destination format and its modes fixed at construction, and, when numeric tracking is on,
//! counts of what it met: values narrowed, overflows above and below (saturated or wrapped,
//! as the mode says), rounding ties, values that lost fraction bits, and the range of the
//! values before narrowing.

use super::value::{dropped, rounded};
use super::{quantise, Fmt, Format, Fx, Overflow, Quant};
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
#[derive(Clone, Debug, Default, PartialEq)]
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
    /// The smallest value before narrowing, exactly (`None` before the first).
    pub min: Option<Fx>,
    /// The largest.
    pub max: Option<Fx>,
}

impl NarrowStats {
    /// Adds another run's counts (shards of one regression, configurations of one unit).
    pub fn merge(&mut self, o: &NarrowStats) {
        self.narrowed += o.narrowed;
        self.over_high += o.over_high;
        self.over_low += o.over_low;
        self.ties += o.ties;
        self.inexact += o.inexact;
        self.widen(o.min);
        self.widen(o.max);
    }

    /// Widens the range to hold `x`.
    fn widen(&mut self, x: Option<Fx>) {
        let Some(x) = x else { return };
        if self.min.is_none_or(|m| x < m) {
            self.min = Some(x);
        }
        if self.max.is_none_or(|m| x > m) {
            self.max = Some(x);
        }
    }
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
/// [`quantise`] and [`Fx::convert`] give.
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
}

impl Narrowing {
    /// A narrowing named `name` into `dst`, rounding by `q`, overflow by `o`.
    pub fn new(name: &'static str, dst: Format, q: Quant, o: Overflow) -> Narrowing {
        Narrowing {
            name,
            dst,
            q,
            o,
            stats: NarrowStats::default(),
            flag: Signal::bit(flag_name(name, o)),
            unreachable: Vec::new(),
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

    /// `raw * 2^-src_frac` narrowed: [`quantise`] into the destination, counted when tracking.
    #[inline(always)]
    pub fn raw(&mut self, raw: i128, src_frac: i32) -> i128 {
        let dst = self.dst;
        self.raw_to(dst, raw, src_frac)
    }

    /// [`Narrowing::raw`] into `dst`, which is the destination (a constant where the caller
    /// knows it at compile time, so the narrowing folds as a `convert` naming it does).
    #[inline(always)]
    fn raw_to(&mut self, dst: Format, raw: i128, src_frac: i32) -> i128 {
        debug_assert_eq!(dst, self.dst);
        if tracking() {
            self.record(raw, src_frac);
        }
        // The modes as constants where they are the common ones, so `quantise`'s rounding and
        // overflow logic folds as it does at a call site that names them (one predictable
        // branch here instead of a run-time match inside).
        match (self.q, self.o) {
            (Quant::RoundHalfEven, Overflow::Saturate) => {
                quantise(raw, src_frac, dst, Quant::RoundHalfEven, Overflow::Saturate)
            }
            (Quant::RoundHalfEven, Overflow::SaturateSymmetric) => quantise(
                raw,
                src_frac,
                dst,
                Quant::RoundHalfEven,
                Overflow::SaturateSymmetric,
            ),
            (Quant::Trunc, Overflow::Wrap) => {
                quantise(raw, src_frac, dst, Quant::Trunc, Overflow::Wrap)
            }
            (q, o) => quantise(raw, src_frac, dst, q, o),
        }
    }

    /// `v` narrowed: [`Fx::convert`] into the destination, counted when tracking.
    #[inline(always)]
    pub fn fx(&mut self, v: Fx) -> Fx {
        Fx::from_fitting_raw(self.dst, self.raw(v.raw(), v.fmt().frac()))
    }

    #[cold]
    #[inline(never)]
    fn record(&mut self, raw: i128, src_frac: i32) {
        let (d, s) = (self.dst, &mut self.stats);
        let shift = src_frac - d.frac();
        let (v, huge) = rounded(raw, shift, self.q);
        let (lost, tie) = dropped(raw, shift);
        s.narrowed += 1;
        s.inexact += u64::from(lost);
        s.ties += u64::from(tie && has_tie_rule(self.q));
        let low = if self.o == Overflow::SaturateSymmetric && d.is_signed() {
            -d.max_raw()
        } else {
            d.min_raw()
        };
        let (high, under) = if huge {
            (raw >= 0, raw < 0)
        } else {
            (v > d.max_raw(), v < low)
        };
        s.over_high += u64::from(high);
        s.over_low += u64::from(under);
        self.flag.set_raw(i64::from(high || under));
        // The value exactly: every i128 fits a signed 128-bit format of the source's fraction.
        if let Ok(f) = Format::try_new(128, src_frac, true) {
            s.widen(Some(Fx::from_raw(f, raw)));
        }
    }
}

/// A named narrowing into a format known at compile time (`F`, declared with
/// [`formats!`](crate::formats)): the typed style's [`Narrowing`]. Its destination is a
/// constant, so `fx` compiles to what `convert(F::FMT, q, o)` does, plus the one thread-local
/// test of numeric tracking. It reads as a [`Narrowing`] (its name, counts, flag).
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
        let raw = self.inner.raw_to(F::FMT, v.raw(), v.fmt().frac());
        Fx::from_fitting_raw(F::FMT, raw)
    }

    /// `raw * 2^-src_frac` narrowed into `F`: [`quantise`], counted when tracking.
    #[inline(always)]
    pub fn raw(&mut self, raw: i128, src_frac: i32) -> i128 {
        self.inner.raw_to(F::FMT, raw, src_frac)
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
