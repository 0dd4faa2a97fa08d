//! Formats known at compile time: a type per format, so that a signal declared with one folds
//! its format into the code that reads and writes it.

use super::Format;

/// A format as a type: `FMT` is a constant, so arithmetic on values of a signal of this type
/// ([`crate::kernel::SignalOf`]) computes its result formats, alignments and range checks at
/// compile time. Declare one with [`formats!`](crate::formats).
pub trait Fmt: 'static {
    /// The format.
    const FMT: Format;
}

/// One unsigned bit: a valid, a flag, a select.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Bit;

impl Bit {
    /// The format (also [`Fmt::FMT`]).
    pub const FMT: Format = Format::uint(1);
}

impl Fmt for Bit {
    const FMT: Format = Format::uint(1);
}

/// Declares formats as types ([`Fmt`]), each a unit struct whose `FMT` is the format (an
/// associated constant, usable without the trait in scope):
///
/// ```
/// use hdl::fx::Format;
/// hdl::formats! {
///     /// Input, sQ4.4: [-8, 8).
///     pub X = Format::signed(8, 4);
///     /// Accumulator, sQ6.4.
///     pub Acc = Format::signed(10, 4);
/// }
/// assert_eq!(Acc::FMT.to_string(), "sQ6.4");
/// ```
#[macro_export]
macro_rules! formats {
    ($($(#[$meta:meta])* $vis:vis $name:ident = $fmt:expr;)*) => {
        $(
            $(#[$meta])*
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
            $vis struct $name;
            impl $name {
                /// The format (also [`Fmt::FMT`](crate::fx::Fmt), without the trait in scope).
                pub const FMT: $crate::fx::Format = $fmt;
            }
            impl $crate::fx::Fmt for $name {
                const FMT: $crate::fx::Format = $fmt;
            }
        )*
    };
}
