//! Signals and registers whose format is a type ([`Fmt`]): the same storage, tracing and
//! checks as [`Signal`] and [`Reg`], with every read, write and range check computed from a
//! constant format, so the fixed-point arithmetic on their values folds at compile time.

use super::declared::{Regs, Signals};
use super::module::{Dir, Visitor};
use super::signal::{Misfit, Reg, Signal};
use crate::fx::{Fmt, Format, Fx};
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};

/// A [`Signal`] of format `F`. Everything a `Signal` offers is there (it dereferences to one);
/// `fx`, `raw`, `set`, `set_raw` and `set_bits` use `F::FMT` as a constant.
#[repr(transparent)]
pub struct SignalOf<F> {
    s: Signal,
    _fmt: PhantomData<fn() -> F>,
}

/// The raw integer of `bits` in `F` (sign-extended for a signed format), folded per format.
#[inline(always)]
fn raw_of<F: Fmt>(bits: u64) -> i64 {
    let w = F::FMT.width();
    if F::FMT.is_signed() && w < 64 {
        ((bits << (64 - w)) as i64) >> (64 - w)
    } else {
        bits as i64
    }
}

/// The low `width` bits of `F`.
#[inline(always)]
fn mask_of<F: Fmt>() -> u64 {
    F::FMT.mask() as u64
}

impl<F: Fmt> SignalOf<F> {
    /// A signal of `F` named `name`, initially zero.
    #[track_caller]
    pub fn new(name: &'static str) -> Self {
        SignalOf {
            s: Signal::new(name, F::FMT),
            _fmt: PhantomData,
        }
    }

    /// The same signal with named values (see [`Signal::with_states`]).
    #[track_caller]
    pub fn with_states(self, states: &'static [&'static str]) -> Self {
        SignalOf {
            s: self.s.with_states(states),
            _fmt: PhantomData,
        }
    }

    /// The format, a constant.
    #[inline(always)]
    pub fn fmt(&self) -> Format {
        F::FMT
    }

    /// The value as a signed integer (sign-extended for signed formats).
    #[inline(always)]
    pub fn raw(&self) -> i64 {
        raw_of::<F>(self.s.bits)
    }

    /// The value as a fixed-point number of `F`.
    #[inline(always)]
    pub fn fx(&self) -> Fx {
        let raw = if F::FMT.is_signed() {
            i128::from(self.raw())
        } else {
            i128::from(self.s.bits)
        };
        Fx::from_fitting_raw(F::FMT, raw)
    }

    /// Writes a fixed-point value, exactly representable in `F` (see [`Signal::set`]).
    #[inline(always)]
    #[track_caller]
    pub fn set(&mut self, v: Fx) {
        self.s.bits = encode::<F>(&self.s, v);
    }

    /// Writes a raw integer; panics if it is out of `F`'s range.
    #[inline(always)]
    #[track_caller]
    pub fn set_raw(&mut self, raw: i64) {
        if !F::FMT.contains_raw(i128::from(raw)) {
            self.s.misfit(Misfit::Raw(raw));
        }
        self.s.bits = (raw as u64) & mask_of::<F>();
    }

    /// Writes a bit pattern; panics if bits above `F`'s width are set (one compare with a
    /// constant). An inherent method, so that `s.set_bits(s.bits() | b)` borrows as it does
    /// on a [`Signal`] (a write through `DerefMut` could not read `s` in its argument).
    #[inline(always)]
    #[track_caller]
    pub fn set_bits(&mut self, bits: u64) {
        if bits > mask_of::<F>() {
            self.s.misfit(Misfit::Bits(bits));
        }
        self.s.bits = bits;
    }

    /// Writes a bool as the bit pattern 0 or 1 (see [`Signal::set_bool`]).
    #[inline(always)]
    pub fn set_bool(&mut self, b: bool) {
        self.s.set_bool(b);
    }
}

/// `v`'s bits in `F`: no check when `v` is of `F` (the common case, folded away when `v`'s
/// format is a constant too), else [`Signal::set`]'s exactness check.
#[inline(always)]
#[track_caller]
fn encode<F: Fmt>(s: &Signal, v: Fx) -> u64 {
    if v.fmt() == F::FMT {
        (v.raw() as u64) & mask_of::<F>()
    } else {
        s.encode(v)
    }
}

impl<F> Deref for SignalOf<F> {
    type Target = Signal;
    #[inline(always)]
    fn deref(&self) -> &Signal {
        &self.s
    }
}

impl<F> DerefMut for SignalOf<F> {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut Signal {
        &mut self.s
    }
}

impl<F> Clone for SignalOf<F> {
    fn clone(&self) -> Self {
        SignalOf {
            s: self.s.clone(),
            _fmt: PhantomData,
        }
    }
}

impl<F> std::fmt::Debug for SignalOf<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Debug::fmt(&self.s, f)
    }
}

impl<F> Signals for SignalOf<F> {
    #[inline]
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        v.signal(dir, &self.s);
    }
    #[inline]
    fn bits_signals<G: FnMut(u64)>(&self, f: &mut G) {
        f(self.s.bits());
    }
}

/// A [`Reg`] of format `F`: `q()` is a [`SignalOf<F>`], and every next-value write is checked
/// against the constant format.
pub struct RegOf<F> {
    q: SignalOf<F>,
    d: u64,
    reset: u64,
}

impl<F: Fmt> RegOf<F> {
    /// A register of `F` that resets to zero.
    #[track_caller]
    pub fn new(name: &'static str) -> Self {
        RegOf {
            q: SignalOf::new(name),
            d: 0,
            reset: 0,
        }
    }

    /// The same register resetting to `value` (which must fit `F`).
    #[track_caller]
    pub fn reset_to(mut self, value: Fx) -> Self {
        self.q.set(value);
        self.d = self.q.bits();
        self.reset = self.d;
        self
    }

    /// The same register with named values (an FSM state register).
    #[track_caller]
    pub fn with_states(mut self, states: &'static [&'static str]) -> Self {
        self.q = self.q.with_states(states);
        self
    }

    /// The current (registered) value.
    #[inline(always)]
    pub fn q(&self) -> &SignalOf<F> {
        &self.q
    }

    /// Writes the next value; checked like [`SignalOf::set`].
    #[inline(always)]
    #[track_caller]
    pub fn set_next(&mut self, v: Fx) {
        self.d = encode::<F>(&self.q.s, v);
    }

    /// Writes the next value as a raw integer; checked against `F`'s range.
    #[inline(always)]
    #[track_caller]
    pub fn set_next_raw(&mut self, raw: i64) {
        if !F::FMT.contains_raw(i128::from(raw)) {
            self.q.s.misfit(Misfit::NextRaw(raw));
        }
        self.d = (raw as u64) & mask_of::<F>();
    }

    /// Writes the next value as a bit pattern; panics if bits above the width are set.
    #[inline(always)]
    #[track_caller]
    pub fn set_next_bits(&mut self, bits: u64) {
        if bits & !mask_of::<F>() != 0 {
            self.q.s.misfit(Misfit::NextBits(bits));
        }
        self.d = bits;
    }

    /// Writes the next value of a one-bit register.
    #[inline(always)]
    #[track_caller]
    pub fn set_next_bool(&mut self, b: bool) {
        self.set_next_bits(u64::from(b));
    }

    /// The pending next value's bits.
    #[inline(always)]
    pub fn next_bits(&self) -> u64 {
        self.d
    }

    /// The clock edge: commit the next value, or the reset value under synchronous reset.
    #[inline(always)]
    pub fn tick(&mut self, reset: bool) {
        if reset {
            self.d = self.reset;
        }
        self.q.s.set_checked_bits(self.d);
    }
}

impl<F> Clone for RegOf<F> {
    fn clone(&self) -> Self {
        RegOf {
            q: self.q.clone(),
            d: self.d,
            reset: self.reset,
        }
    }
}

impl<F> std::fmt::Debug for RegOf<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RegOf")
            .field("q", &self.q)
            .field("d", &self.d)
            .field("reset", &self.reset)
            .finish()
    }
}

impl<F: Fmt> Regs for RegOf<F> {
    #[inline]
    fn tick_regs(&mut self, reset: bool) {
        self.tick(reset);
    }
    /// Visited as a register, its current value and the next one, as [`Visitor::reg`] visits a
    /// [`Reg`].
    fn visit_regs(&self, v: &mut dyn Visitor) {
        v.register(&self.q.s, self.d);
    }
    #[inline]
    fn bits_regs<G: FnMut(u64)>(&self, f: &mut G) {
        f(self.q.s.bits());
    }
}

/// What `#[derive(Module)]`'s constructor builds a field with: a name and, for a
/// run-time-format field, its `fmt = ...`.
pub trait Declare: Sized {
    /// The field named `name` of format `fmt` (a typed field checks that `fmt` is its own).
    fn declare(name: &'static str, fmt: Format) -> Self;
}

/// A field whose format is its type: built from its name alone.
pub trait DeclareTyped: Sized {
    /// The field named `name`.
    fn declare_typed(name: &'static str) -> Self;
}

impl Declare for Signal {
    #[track_caller]
    fn declare(name: &'static str, fmt: Format) -> Self {
        Signal::new(name, fmt)
    }
}

impl Declare for Reg {
    #[track_caller]
    fn declare(name: &'static str, fmt: Format) -> Self {
        Reg::new(name, fmt)
    }
}

/// A typed field with a `fmt = ...` too: the two must agree.
#[track_caller]
fn same_format<F: Fmt>(name: &str, fmt: Format) {
    assert!(
        fmt == F::FMT,
        "'{name}': fmt = {fmt} but its type's format is {}",
        F::FMT
    );
}

impl<F: Fmt> Declare for SignalOf<F> {
    #[track_caller]
    fn declare(name: &'static str, fmt: Format) -> Self {
        same_format::<F>(name, fmt);
        SignalOf::new(name)
    }
}

impl<F: Fmt> Declare for RegOf<F> {
    #[track_caller]
    fn declare(name: &'static str, fmt: Format) -> Self {
        same_format::<F>(name, fmt);
        RegOf::new(name)
    }
}

impl<F: Fmt> DeclareTyped for SignalOf<F> {
    #[track_caller]
    fn declare_typed(name: &'static str) -> Self {
        SignalOf::new(name)
    }
}

impl<F: Fmt> DeclareTyped for RegOf<F> {
    #[track_caller]
    fn declare_typed(name: &'static str) -> Self {
        RegOf::new(name)
    }
}
