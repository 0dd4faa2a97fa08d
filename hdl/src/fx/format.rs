//! Fixed-point formats: width, fraction bits, signedness.

use std::fmt;

/// Largest width a format may have (signed); unsigned formats may have one bit less, so that
/// every value fits an `i128`.
pub const MAX_WIDTH: u32 = 128;
/// Fraction bits are limited to this magnitude so that every rescaling fits a 128-bit shift.
pub const MAX_FRAC: i32 = 120;

/// A fixed-point format: `width` bits, `frac` of them fraction bits, signed or unsigned.
///
/// Written `sQ<i>.<f>` / `uQ<i>.<f>` (integer bits `i = width - frac`, fraction bits `f`) by
/// `Display`, the notation used throughout texrtl's documentation.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Format {
    width: u8,
    frac: i8,
    signed: bool,
}

/// Why a format could not be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FormatError {
    /// Width 0, or more bits than an `i128` holds.
    Width {
        /// The width asked for.
        width: u32,
        /// Whether it was to be signed.
        signed: bool,
    },
    /// Fraction bits outside `-MAX_FRAC..=MAX_FRAC`.
    Frac {
        /// The fraction bits asked for.
        frac: i32,
    },
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FormatError::Width { width, signed } => write!(
                f,
                "width {width} out of range: {} formats hold 1..={} bits",
                if *signed { "signed" } else { "unsigned" },
                if *signed { MAX_WIDTH } else { MAX_WIDTH - 1 }
            ),
            FormatError::Frac { frac } => {
                write!(
                    f,
                    "fraction bits {frac} out of range -{MAX_FRAC}..={MAX_FRAC}"
                )
            }
        }
    }
}

impl std::error::Error for FormatError {}

impl Format {
    /// A format, or why it is impossible.
    #[inline]
    pub const fn try_new(width: u32, frac: i32, signed: bool) -> Result<Format, FormatError> {
        let max = if signed { MAX_WIDTH } else { MAX_WIDTH - 1 };
        if width == 0 || width > max {
            return Err(FormatError::Width { width, signed });
        }
        if frac < -MAX_FRAC || frac > MAX_FRAC {
            return Err(FormatError::Frac { frac });
        }
        Ok(Format {
            width: width as u8,
            frac: frac as i8,
            signed,
        })
    }

    /// A format; panics (at compile time in a `const`) if it is impossible.
    pub const fn new(width: u32, frac: i32, signed: bool) -> Format {
        match Format::try_new(width, frac, signed) {
            Ok(f) => f,
            Err(_) => panic!("impossible fixed-point format"),
        }
    }

    /// Unsigned, `width` bits, `frac` fraction bits.
    pub const fn unsigned(width: u32, frac: i32) -> Format {
        Format::new(width, frac, false)
    }

    /// Signed (two's complement), `width` bits, `frac` fraction bits.
    pub const fn signed(width: u32, frac: i32) -> Format {
        Format::new(width, frac, true)
    }

    /// An unsigned integer of `width` bits.
    pub const fn uint(width: u32) -> Format {
        Format::new(width, 0, false)
    }

    /// A signed integer of `width` bits.
    pub const fn sint(width: u32) -> Format {
        Format::new(width, 0, true)
    }

    /// Bits, sign included.
    pub const fn width(self) -> u32 {
        self.width as u32
    }
    /// Fraction bits (negative: the LSB weighs more than 1).
    pub const fn frac(self) -> i32 {
        self.frac as i32
    }
    /// Two's complement or unsigned.
    pub const fn is_signed(self) -> bool {
        self.signed
    }
    /// Integer bits, `width - frac` (including the sign bit for signed formats).
    pub const fn int_bits(self) -> i32 {
        self.width as i32 - self.frac as i32
    }

    /// Smallest raw value.
    pub const fn min_raw(self) -> i128 {
        if self.signed {
            if self.width as u32 == 128 {
                i128::MIN
            } else {
                -(1i128 << (self.width - 1))
            }
        } else {
            0
        }
    }

    /// Largest raw value.
    pub const fn max_raw(self) -> i128 {
        let w = if self.signed {
            self.width as u32 - 1
        } else {
            self.width as u32
        };
        if w == 127 {
            i128::MAX
        } else {
            (1i128 << w) - 1
        }
    }

    /// Mask of `width` low bits.
    pub const fn mask(self) -> u128 {
        if self.width as u32 == 128 {
            u128::MAX
        } else {
            (1u128 << self.width) - 1
        }
    }

    /// Whether `raw` lies in this format's range (two shifts and a compare).
    #[inline]
    pub const fn contains_raw(self, raw: i128) -> bool {
        let w = self.width as u32;
        if self.signed {
            if w == 128 {
                return true;
            }
            let t = raw >> (w - 1);
            t == 0 || t == -1
        } else {
            raw >> w == 0
        }
    }

    /// Whether the value `raw * 2^-frac` lies between this format's smallest and largest
    /// values, exactly (for a bound on what reaches a narrowing: a value within them never
    /// overflows, whatever the rounding, since both ends are codes).
    pub fn holds(self, raw: i128, frac: i32) -> bool {
        let up = |x: i128, by: i32| x.checked_mul(1i128.checked_shl(by as u32)?);
        let shift = frac - self.frac();
        if shift >= 0 {
            // The ends at the value's resolution (beyond i128: past any value).
            let lo = up(self.min_raw(), shift).unwrap_or(i128::MIN);
            let hi = up(self.max_raw(), shift).unwrap_or(i128::MAX);
            lo <= raw && raw <= hi
        } else {
            up(raw, -shift).is_some_and(|v| self.min_raw() <= v && v <= self.max_raw())
        }
    }

    /// Number of hex digits that show every bit.
    pub const fn hex_digits(self) -> usize {
        (self.width as usize).div_ceil(4)
    }

    /// The format of `a + b` (and `a - b` when both are signed): full precision.
    ///
    /// Panics if the result needs more bits than an `i128` holds.
    #[inline]
    pub fn sum(a: Format, b: Format) -> Format {
        Format::grow(a, b, a.signed || b.signed, "sum")
    }

    /// The format of `a - b`: always signed, full precision.
    #[inline]
    pub fn difference(a: Format, b: Format) -> Format {
        Format::grow(a, b, true, "difference")
    }

    #[inline]
    fn grow(a: Format, b: Format, signed: bool, what: &str) -> Format {
        let frac = a.frac().max(b.frac());
        // An unsigned operand needs one more integer bit inside a signed result.
        let ia = a.int_bits() + i32::from(signed && !a.signed);
        let ib = b.int_bits() + i32::from(signed && !b.signed);
        let int = ia.max(ib) + 1;
        let width = (int + frac).max(1);
        Format::derived(width, frac, signed, what, a, b)
    }

    /// A format computed from valid ones: `frac` is one of theirs or their sum, so only the
    /// width (and a sum of fractions) can be out of range; one check, the panic out of line.
    #[inline(always)]
    fn derived(width: i32, frac: i32, signed: bool, what: &str, a: Format, b: Format) -> Format {
        let max = if signed { MAX_WIDTH } else { MAX_WIDTH - 1 } as i32;
        if width > max || frac.abs() > MAX_FRAC {
            Format::no_format(what, a, b, width, frac, signed);
        }
        Format {
            width: width as u8,
            frac: frac as i8,
            signed,
        }
    }

    #[cold]
    #[inline(never)]
    fn no_format(what: &str, a: Format, b: Format, width: i32, frac: i32, signed: bool) -> ! {
        let e = Format::try_new(width.max(0) as u32, frac, signed)
            .err()
            .map_or_else(String::new, |e| e.to_string());
        if what == "negation" {
            panic!("negation of {a} has no format: {e}")
        }
        panic!("{what} of {a} and {b} has no format: {e}")
    }

    /// The format of `a * b`: `W1 + W2` bits, `F1 + F2` fraction bits.
    #[inline]
    pub fn product(a: Format, b: Format) -> Format {
        let (width, frac) = (a.width() + b.width(), a.frac() + b.frac());
        Format::derived(width as i32, frac, a.signed || b.signed, "product", a, b)
    }

    /// The format of `-a`: signed, one bit wider.
    #[inline]
    pub fn negation(a: Format) -> Format {
        Format::derived(a.width() as i32 + 1, a.frac(), true, "negation", a, a)
    }

    /// Parses the notation of `Display`: `uQ3.5`, `sQ1.14`, `u8`, `s12`.
    pub fn parse(s: &str) -> Result<Format, String> {
        let bad = || format!("'{s}' is not a format (expected uQ<i>.<f>, sQ<i>.<f>, u<w> or s<w>)");
        let (signed, rest) = match s.as_bytes().first() {
            Some(b'u') => (false, &s[1..]),
            Some(b's') => (true, &s[1..]),
            _ => return Err(bad()),
        };
        if let Some(q) = rest.strip_prefix('Q') {
            let (i, f) = q.split_once('.').ok_or_else(bad)?;
            let i: i32 = i.parse().map_err(|_| bad())?;
            let f: i32 = f.parse().map_err(|_| bad())?;
            Format::try_new((i + f).max(0) as u32, f, signed).map_err(|e| format!("'{s}': {e}"))
        } else {
            let w: u32 = rest.parse().map_err(|_| bad())?;
            Format::try_new(w, 0, signed).map_err(|e| format!("'{s}': {e}"))
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = if self.signed { 's' } else { 'u' };
        if self.frac == 0 {
            write!(f, "{s}{}", self.width)
        } else {
            write!(f, "{s}Q{}.{}", self.int_bits(), self.frac)
        }
    }
}
