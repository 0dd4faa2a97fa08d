//! Signals (wires and ports) and registers: a declared format, a value that must fit it.

use crate::fx::{Format, Fx};

/// A wire or port: up to 64 bits, with a declared [`Format`] (width, fraction bits,
/// signedness). The value is stored as its two's complement bit pattern.
///
/// Every computed write is checked: a value that does not fit the declared format panics with
/// the signal's name, width and value. The check is one compare, so it stays on in release
/// builds. A copy between two signals ([`Signal::follow`], a wire) is checked in debug builds
/// only, which every `cargo test` is: its source was checked when it was written, and the
/// debug check that both ends share one format makes the release check redundant.
#[derive(Clone, Debug)]
pub struct Signal {
    pub(super) bits: u64,
    /// `width` low bits set.
    pub(super) mask: u64,
    /// Range of raw values: `lo ..= lo + span` (one unsigned compare checks a value).
    pub(super) lo: i64,
    pub(super) span: u64,
    /// The shift that sign-extends the bits: `64 - width` for a signed format, else 0.
    sx: u32,
    fmt: Format,
    name: &'static str,
    /// Names of the values of an enumerated signal (a state register), by value.
    states: Option<&'static [&'static str]>,
}

impl Signal {
    /// A signal of `fmt` named `name` (local to its module), initially zero.
    #[track_caller]
    pub fn new(name: &'static str, fmt: Format) -> Signal {
        assert!(
            fmt.width() <= 64,
            "signal '{name}': {fmt} is {} bits; signals hold at most 64",
            fmt.width()
        );
        Signal {
            bits: 0,
            mask: fmt.mask() as u64,
            lo: fmt.min_raw().max(i128::from(i64::MIN)) as i64,
            span: (fmt.max_raw().min(i128::from(i64::MAX))
                - fmt.min_raw().max(i128::from(i64::MIN))) as u64,
            sx: if fmt.is_signed() { 64 - fmt.width() } else { 0 },
            fmt,
            name,
            states: None,
        }
    }

    /// The same signal with named values (an FSM state: `states[v]` names value `v`), shown
    /// by name in GTKWave. Every name must fit the width: at most `2^width` of them.
    #[track_caller]
    pub fn with_states(mut self, states: &'static [&'static str]) -> Signal {
        assert!(
            self.fmt.width() < 16 && states.len() <= 1 << self.fmt.width(),
            "signal '{}': {} state names for {} bits",
            self.name,
            states.len(),
            self.fmt.width()
        );
        self.states = Some(states);
        self
    }

    /// The names of the values, for an enumerated signal.
    pub fn states(&self) -> Option<&'static [&'static str]> {
        self.states
    }

    /// The name of the current value, for an enumerated signal.
    pub fn state_name(&self) -> Option<&'static str> {
        self.states?.get(self.bits as usize).copied()
    }

    /// A one-bit unsigned signal.
    pub fn bit(name: &'static str) -> Signal {
        Signal::new(name, Format::uint(1))
    }

    /// The signal's name (its waveform variable's).
    pub fn name(&self) -> &'static str {
        self.name
    }
    /// Its format.
    pub fn fmt(&self) -> Format {
        self.fmt
    }
    /// Its width in bits.
    pub fn width(&self) -> u32 {
        self.fmt.width()
    }

    /// The bit pattern (zero above `width`).
    #[inline]
    pub fn bits(&self) -> u64 {
        self.bits
    }

    /// The value as a signed integer (sign-extended for signed formats).
    #[inline]
    pub fn raw(&self) -> i64 {
        // One shift pair for every format: a shift of 0 leaves an unsigned value (or a
        // 64-bit signed one) as it is.
        ((self.bits << self.sx) as i64) >> self.sx
    }

    /// The value as an unsigned integer (for unsigned formats; panics on a negative value).
    #[inline]
    pub fn uint(&self) -> u64 {
        let r = self.raw();
        assert!(r >= 0, "signal '{}' holds negative {r}", self.name);
        r as u64
    }

    /// A one-bit signal as a bool.
    #[inline]
    pub fn is_high(&self) -> bool {
        self.bits & 1 == 1
    }

    /// The value as a fixed-point number of the signal's format.
    #[inline]
    pub fn fx(&self) -> Fx {
        // The bits were checked against the format when written; an unsigned value is its
        // bits (all 64 of them for a 64-bit format).
        let raw = if self.fmt.is_signed() {
            i128::from(self.raw())
        } else {
            i128::from(self.bits)
        };
        Fx::from_fitting_raw(self.fmt, raw)
    }

    /// Writes a bit pattern; panics if bits above `width` are set.
    #[inline]
    #[track_caller]
    pub fn set_bits(&mut self, bits: u64) {
        // `mask` is the low `width` bits: a value has a bit above them exactly when it is
        // greater (one compare, where `bits & !mask` takes three instructions).
        if bits > self.mask {
            self.misfit(Misfit::Bits(bits));
        }
        self.bits = bits;
    }

    /// Writes the first `N` bit patterns of `row` into `signals`, in order (one cycle of a
    /// stimulus row into a unit's input ports); panics if `row` is shorter or a pattern does
    /// not fit its signal. The row's length is checked once and the writes unroll, where a
    /// `zip` over a slice of unknown length runs as a loop (a quarter of a small unit's cycle).
    ///
    /// ```
    /// use hdl::fx::Format;
    /// use hdl::kernel::Signal;
    /// let (mut valid, mut x) = (Signal::bit("valid_in"), Signal::new("x", Format::signed(8, 4)));
    /// Signal::set_row([&mut valid, &mut x], &[1, 0xf8]);
    /// assert_eq!((valid.is_high(), x.raw()), (true, -8));
    /// ```
    #[inline]
    #[track_caller]
    pub fn set_row<const N: usize>(signals: [&mut Signal; N], row: &[u64]) {
        let row: &[u64; N] = row[..N].try_into().expect("a slice of N");
        for (s, x) in signals.into_iter().zip(row) {
            s.set_bits(*x);
        }
    }

    /// Writes a raw integer (value `raw * 2^-frac`); panics if it is out of range.
    #[inline]
    #[track_caller]
    pub fn set_raw(&mut self, raw: i64) {
        if self.out_of_range(raw) {
            self.misfit(Misfit::Raw(raw));
        }
        self.bits = (raw as u64) & self.mask;
    }

    /// Whether a raw value is outside the format's range: below `lo` it wraps to above
    /// `span`.
    #[inline(always)]
    pub(super) fn out_of_range(&self, raw: i64) -> bool {
        raw.wrapping_sub(self.lo) as u64 > self.span
    }

    /// Copies another signal's value (a wire between two ports); the formats must agree.
    #[inline]
    #[track_caller]
    pub fn follow(&mut self, src: &Signal) {
        // Checked in debug builds (and so in every test): the two ends must share a format,
        // and the value must fit. In release builds the copy is unchecked: a source value
        // always fits its own (equal) format, and a design's wires are the same in every run;
        // this was 7 % of the FIG. 7 pipeline's cycle, which copies about 250 wires.
        debug_assert_eq!(self.fmt, src.fmt, "'{}' <- '{}'", self.name, src.name);
        if cfg!(debug_assertions) && src.bits & !self.mask != 0 {
            self.overflow(format!("'{}' of {}", src.name, src.fmt));
        }
        self.bits = src.bits;
    }

    /// Writes bits already checked against this signal's format (kernel storage such as a
    /// delay line's ring, which only ever holds values its inputs of the same format held).
    #[inline]
    pub(super) fn set_checked_bits(&mut self, bits: u64) {
        debug_assert_eq!(bits & !self.mask, 0, "'{}': unchecked bits", self.name);
        self.bits = bits;
    }

    /// Writes a bool to a signal known to be one bit wide (a narrowing's flag), unchecked.
    #[inline]
    pub(crate) fn set_flag(&mut self, b: bool) {
        debug_assert_eq!(self.mask, 1, "'{}' is not one bit", self.name);
        self.bits = u64::from(b);
    }

    /// Writes a bool to a one-bit signal (as the bit pattern 0 or 1, which fits every
    /// format: none is narrower than one bit, so nothing is checked).
    #[inline]
    pub fn set_bool(&mut self, b: bool) {
        self.bits = u64::from(b);
    }

    /// Writes a fixed-point value, which must be exactly representable in the signal's format
    /// (quantise explicitly with [`Fx::convert`] first: a signal never rounds or wraps).
    #[inline]
    #[track_caller]
    pub fn set(&mut self, v: Fx) {
        self.bits = self.encode(v);
    }

    /// The bit pattern of `v` in this signal's format; panics unless exactly representable.
    #[inline]
    #[track_caller]
    pub(super) fn encode(&self, v: Fx) -> u64 {
        if v.fmt() == self.fmt {
            // In range by construction: the low `width` bits of the raw integer.
            return (v.raw() as u64) & self.mask;
        }
        match v.try_exact(self.fmt) {
            Ok(x) => x.bits() as u64,
            Err(_) => self.overflow(format!("{v} ({})", v.fmt())),
        }
    }

    /// [`Signal::overflow`] for a value that did not fit: the message is formatted here, on
    /// the cold path, so a checked write inlines as a compare and a call.
    #[cold]
    #[inline(never)]
    #[track_caller]
    pub(super) fn misfit(&self, m: Misfit) -> ! {
        self.overflow(m.to_string())
    }

    #[cold]
    #[track_caller]
    pub(super) fn overflow(&self, what: String) -> ! {
        panic!(
            "signal '{}' ({}, {} bits): {what} does not fit",
            self.name,
            self.fmt,
            self.fmt.width()
        )
    }
}

/// A value a checked write found out of its signal's format.
#[derive(Clone, Copy, Debug)]
pub(super) enum Misfit {
    Bits(u64),
    Raw(i64),
    NextBits(u64),
    NextRaw(i64),
}

impl std::fmt::Display for Misfit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Misfit::Bits(b) => write!(f, "bits {b:#x}"),
            Misfit::Raw(r) => write!(f, "raw {r}"),
            Misfit::NextBits(b) => write!(f, "next bits {b:#x}"),
            Misfit::NextRaw(r) => write!(f, "next raw {r}"),
        }
    }
}

/// A clocked register: current value `q`, next value `d`, synchronous reset value.
///
/// Two-process style: combinational logic reads `q()` and writes `set_next*`; the clock edge
/// ([`Reg::tick`]) commits `d` to `q`, or the reset value when reset is asserted. A register
/// whose next value is not written in a cycle holds its value.
#[derive(Clone, Debug)]
pub struct Reg {
    q: Signal,
    d: u64,
    reset: u64,
}

impl Reg {
    /// A register of `fmt` that resets to zero.
    pub fn new(name: &'static str, fmt: Format) -> Reg {
        Reg {
            q: Signal::new(name, fmt),
            d: 0,
            reset: 0,
        }
    }

    /// A register that resets to `value` (which must fit `fmt`).
    #[track_caller]
    pub fn with_reset(name: &'static str, fmt: Format, value: Fx) -> Reg {
        let mut q = Signal::new(name, fmt);
        q.set(value);
        let bits = q.bits();
        Reg {
            q,
            d: bits,
            reset: bits,
        }
    }

    /// The same register resetting to `value` (which must fit its format).
    #[track_caller]
    pub fn reset_to(mut self, value: Fx) -> Reg {
        self.q.set(value);
        self.d = self.q.bits;
        self.reset = self.q.bits;
        self
    }

    /// The same register with named values (an FSM state register; see
    /// [`Signal::with_states`]).
    #[track_caller]
    pub fn with_states(mut self, states: &'static [&'static str]) -> Reg {
        self.q = self.q.with_states(states);
        self
    }

    /// The current (registered) value.
    #[inline]
    pub fn q(&self) -> &Signal {
        &self.q
    }

    /// Writes the next value; checked like [`Signal::set`].
    #[inline]
    #[track_caller]
    pub fn set_next(&mut self, v: Fx) {
        self.d = self.q.encode(v);
    }

    /// Writes the next value as a raw integer; checked like [`Signal::set_raw`].
    #[inline]
    #[track_caller]
    pub fn set_next_raw(&mut self, raw: i64) {
        if self.q.out_of_range(raw) {
            self.q.misfit(Misfit::NextRaw(raw));
        }
        self.d = (raw as u64) & self.q.mask;
    }

    /// Writes the next value as a bit pattern; checked like [`Signal::set_bits`].
    #[inline]
    #[track_caller]
    pub fn set_next_bits(&mut self, bits: u64) {
        if bits > self.q.mask {
            self.q.misfit(Misfit::NextBits(bits));
        }
        self.d = bits;
    }

    /// Writes the next value of a one-bit register.
    #[inline]
    #[track_caller]
    pub fn set_next_bool(&mut self, b: bool) {
        // As `set_next_raw` checks it: 0 fits every format, 1 all but a signed bit's (the
        // one whose sign extension shifts by 63). The format is tested first: it is the same
        // every cycle, so the branch is always predicted, where a branch on the value is
        // mispredicted as often as the value changes.
        if self.q.sx == 63 && b {
            self.q.misfit(Misfit::NextRaw(1));
        }
        self.d = u64::from(b);
    }

    /// The pending next value's bits (what the edge will commit unless reset).
    #[inline]
    pub fn next_bits(&self) -> u64 {
        self.d
    }

    /// The clock edge: commit `d`, or the reset value under synchronous reset.
    #[inline]
    pub fn tick(&mut self, reset: bool) {
        if reset {
            self.d = self.reset;
        }
        // `d` keeps its value: a register not written next cycle holds.
        self.q.bits = self.d;
    }
}
