//! Named narrowings: a unit's `convert`s as parts of the unit, each with a stable name, a
//! destination format and its modes fixed at construction, and, when numeric tracking is on,
//! counts of what it met: values narrowed, overflows above and below (saturated or wrapped,
//! as the mode says), rounding ties, values that lost fraction bits, and the range of the
//! values before narrowing.

use super::value::{dropped, rounded};
use super::{quantise, Format, Fx, Overflow, Quant};
use std::cell::Cell;

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

/// One narrowing of a unit, named (its path in the hierarchy is the unit's instance path and
/// this name: `normal_pipeline_fig7.normal_156.nx`). `raw` and `fx` give exactly what
/// [`quantise`] and [`Fx::convert`] give.
#[derive(Clone, Debug)]
pub struct Narrowing {
    name: &'static str,
    dst: Format,
    q: Quant,
    o: Overflow,
    stats: NarrowStats,
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
        }
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
        if tracking() {
            self.record(raw, src_frac);
        }
        // The modes as constants where they are the common ones, so `quantise`'s rounding and
        // overflow logic folds as it does at a call site that names them (one predictable
        // branch here instead of a run-time match inside).
        let dst = self.dst;
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
        if huge {
            if raw < 0 {
                s.over_low += 1;
            } else {
                s.over_high += 1;
            }
        } else if v > d.max_raw() {
            s.over_high += 1;
        } else if v < low {
            s.over_low += 1;
        }
        // The value exactly: every i128 fits a signed 128-bit format of the source's fraction.
        if let Ok(f) = Format::try_new(128, src_frac, true) {
            s.widen(Some(Fx::from_raw(f, raw)));
        }
    }
}

/// Whether the mode decides a tie by a rule of its own (the round-half modes).
fn has_tie_rule(q: Quant) -> bool {
    !matches!(q, Quant::Trunc | Quant::TruncZero)
}
