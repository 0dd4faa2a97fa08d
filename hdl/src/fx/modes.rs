//! Quantisation (rounding) and overflow modes, with the names of Algorithmic C in the docs.

use std::fmt;
use std::str::FromStr;

/// How dropped fraction bits are rounded. Decided, as in hardware, from the kept LSB, the first
/// dropped bit (the half bit), a sticky OR of the remaining dropped bits and the sign.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Quant {
    /// Toward minus infinity: drop the bits (AC_TRN, SC_TRN). Free in hardware.
    Trunc,
    /// Toward zero (AC_TRN_ZERO): negative values with dropped bits set move up one LSB.
    TruncZero,
    /// Nearest, ties toward plus infinity (AC_RND, SC_RND): add half an LSB, then truncate.
    RoundHalfUp,
    /// Nearest, ties toward zero (AC_RND_ZERO).
    RoundHalfZero,
    /// Nearest, ties away from zero (AC_RND_INF).
    RoundHalfAway,
    /// Nearest, ties toward minus infinity (AC_RND_MIN_INF).
    RoundHalfDown,
    /// Nearest, ties to an even LSB (AC_RND_CONV, IEEE round-to-nearest-even).
    RoundHalfEven,
}

impl Quant {
    /// Every mode, in the order the help lists them.
    pub const ALL: [Quant; 7] = [
        Quant::Trunc,
        Quant::TruncZero,
        Quant::RoundHalfUp,
        Quant::RoundHalfZero,
        Quant::RoundHalfAway,
        Quant::RoundHalfDown,
        Quant::RoundHalfEven,
    ];

    /// The mode's name as options and messages spell it.
    pub const fn name(self) -> &'static str {
        match self {
            Quant::Trunc => "trunc",
            Quant::TruncZero => "trunc-zero",
            Quant::RoundHalfUp => "round-half-up",
            Quant::RoundHalfZero => "round-half-zero",
            Quant::RoundHalfAway => "round-half-away",
            Quant::RoundHalfDown => "round-half-down",
            Quant::RoundHalfEven => "round-half-even",
        }
    }

    /// Whether to add one LSB to the truncated (floored) value.
    ///
    /// `negative`: sign of the unrounded value; `odd`: the kept LSB; `half`: the first dropped
    /// bit; `sticky`: OR of the dropped bits below it.
    #[inline]
    pub const fn increment(self, negative: bool, odd: bool, half: bool, sticky: bool) -> bool {
        // Bitwise, not short-circuit: the bits are data, and branches on them mispredict.
        let above_half = half & sticky;
        let tie = half & !sticky;
        match self {
            Quant::Trunc => false,
            Quant::TruncZero => negative & (half | sticky),
            Quant::RoundHalfUp => half,
            Quant::RoundHalfZero => above_half | (tie & negative),
            Quant::RoundHalfAway => above_half | (tie & !negative),
            Quant::RoundHalfDown => above_half,
            Quant::RoundHalfEven => above_half | (tie & odd),
        }
    }
}

/// What happens to a value outside the target format's range.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Overflow {
    /// Keep the low `width` bits (AC_WRAP, SC_WRAP). Free in hardware.
    Wrap,
    /// Clamp to the nearest of min and max (AC_SAT, SC_SAT).
    Saturate,
    /// Clamp to `-max..=max`: the most negative code is never produced, so negation never
    /// overflows (AC_SAT_SYM, SC_SAT_SYM). Same as `Saturate` for unsigned formats.
    SaturateSymmetric,
    /// Any out-of-range value becomes zero (AC_SAT_ZERO).
    SaturateZero,
}

impl Overflow {
    /// Every mode, in the order the help lists them.
    pub const ALL: [Overflow; 4] = [
        Overflow::Wrap,
        Overflow::Saturate,
        Overflow::SaturateSymmetric,
        Overflow::SaturateZero,
    ];

    /// The mode's name as options and messages spell it.
    pub const fn name(self) -> &'static str {
        match self {
            Overflow::Wrap => "wrap",
            Overflow::Saturate => "saturate",
            Overflow::SaturateSymmetric => "saturate-symmetric",
            Overflow::SaturateZero => "saturate-zero",
        }
    }
}

macro_rules! named_enum_io {
    ($t:ty) => {
        impl fmt::Display for $t {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }
        impl FromStr for $t {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                <$t>::ALL
                    .iter()
                    .copied()
                    .find(|m| m.name() == s)
                    .ok_or_else(|| {
                        let names: Vec<_> = <$t>::ALL.iter().map(|m| m.name()).collect();
                        format!("unknown mode '{s}' (one of {})", names.join(", "))
                    })
            }
        }
    };
}

named_enum_io!(Quant);
named_enum_io!(Overflow);
