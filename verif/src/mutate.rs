//! Malformed inputs for fuzzing parsers and command front ends: a valid file with a few
//! byte-level mutations. Bit flips and byte changes, truncation, deletion and duplication of
//! a range, and insertion of the tokens parsers tend to mishandle (huge and negative numbers,
//! NaN and infinities, separators, NUL, magic numbers). Positions are taken modulo the input's
//! current length, so any list of mutations applies to any input, and a failing case printed
//! by proptest replays as it is.

use proptest::collection::vec;
use proptest::prelude::*;

/// Tokens inserted by [`Mutation::Insert`].
pub const TOKENS: &[&[u8]] = &[
    b"0",
    b"-1",
    b"255",
    b"256",
    b"65535",
    b"65536",
    b"4294967295",
    b"4294967296",
    b"18446744073709551616",
    b"99999999999999999999999999999999999999",
    b"1e308",
    b"-1e308",
    b"1e-320",
    b"NaN",
    b"inf",
    b"-inf",
    b"0x10",
    b"1.5",
    b"\n",
    b"\r\n",
    b",",
    b" ",
    b"\t",
    b"\0",
    b"#",
    b"\"",
    b"{",
    b"}",
    b"[",
    b"null",
    b"P2",
    b"P3",
    b"P5",
    b"P6",
    b"\xff\xfe",
];

/// One change to an input.
// Each variant's line names its fields.
#[allow(missing_docs)]
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Mutation {
    /// Flips bit `bit` of byte `at`.
    Flip { at: usize, bit: u8 },
    /// Sets byte `at`.
    Set { at: usize, byte: u8 },
    /// Keeps the first `at` bytes.
    Truncate { at: usize },
    /// Removes `len` bytes from `at`.
    Delete { at: usize, len: usize },
    /// Repeats the `len` bytes from `at` right after them.
    Duplicate { at: usize, len: usize },
    /// Inserts `TOKENS[token % TOKENS.len()]` at `at`.
    Insert { at: usize, token: usize },
}

impl Mutation {
    /// Applies the change to `b` (positions modulo its length; an empty input only grows: a
    /// range of it is empty, so deleting or repeating one changes nothing).
    pub fn apply(&self, b: &mut Vec<u8>) {
        let n = b.len();
        let pos = |at: usize| if n == 0 { 0 } else { at % n };
        match *self {
            Mutation::Flip { at, bit } if n > 0 => b[pos(at)] ^= 1 << (bit % 8),
            Mutation::Set { at, byte } if n > 0 => b[pos(at)] = byte,
            Mutation::Truncate { at } => b.truncate(if n == 0 { 0 } else { at % (n + 1) }),
            Mutation::Delete { at, len } => {
                let a = pos(at);
                b.drain(a..(a + len).min(n));
            }
            Mutation::Duplicate { at, len } => {
                let a = pos(at);
                let piece = b[a..(a + len).min(n)].to_vec();
                let end = a + piece.len();
                b.splice(end..end, piece);
            }
            Mutation::Insert { at, token } => {
                let t = TOKENS[token % TOKENS.len()];
                let a = if n == 0 { 0 } else { at % (n + 1) };
                b.splice(a..a, t.iter().copied());
            }
            _ => {}
        }
    }
}

/// `input` with `muts` applied in order.
pub fn mutated(input: &[u8], muts: &[Mutation]) -> Vec<u8> {
    let mut b = input.to_vec();
    for m in muts {
        m.apply(&mut b);
    }
    b
}

/// One mutation: every kind equally likely, ranges up to 64 bytes.
pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 0..8u8).prop_map(|(at, bit)| Mutation::Flip { at, bit }),
        (any::<usize>(), any::<u8>()).prop_map(|(at, byte)| Mutation::Set { at, byte }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        (any::<usize>(), 1..64usize).prop_map(|(at, len)| Mutation::Delete { at, len }),
        (any::<usize>(), 1..64usize).prop_map(|(at, len)| Mutation::Duplicate { at, len }),
        (any::<usize>(), any::<usize>()).prop_map(|(at, token)| Mutation::Insert { at, token }),
    ]
}

/// One to `max` mutations.
pub fn mutations(max: usize) -> impl Strategy<Value = Vec<Mutation>> {
    vec(mutation(), 1..=max.max(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_does_what_it_says() {
        let b = b"abcdef".to_vec();
        let m = |x: Mutation| mutated(&b, &[x]);
        assert_eq!(m(Mutation::Flip { at: 7, bit: 0 }), b"accdef");
        assert_eq!(
            m(Mutation::Flip { at: 0, bit: 5 }),
            b"Abcdef",
            "a set bit cleared"
        );
        assert_eq!(
            m(Mutation::Flip { at: 2, bit: 12 }),
            b"absdef",
            "bit 12 is bit 4"
        );
        assert_eq!(m(Mutation::Set { at: 0, byte: b'z' }), b"zbcdef");
        assert_eq!(m(Mutation::Truncate { at: 3 }), b"abc");
        assert_eq!(m(Mutation::Truncate { at: 6 }), b"abcdef");
        assert_eq!(m(Mutation::Delete { at: 4, len: 9 }), b"abcd");
        assert_eq!(m(Mutation::Delete { at: 1, len: 2 }), b"adef");
        assert_eq!(m(Mutation::Duplicate { at: 1, len: 2 }), b"abcbcdef");
        assert_eq!(m(Mutation::Insert { at: 6, token: 1 }), b"abcdef-1");
    }

    #[test]
    fn any_mutation_applies_to_an_empty_input() {
        for x in [
            Mutation::Flip { at: 3, bit: 9 },
            Mutation::Set { at: 3, byte: 1 },
            Mutation::Truncate { at: 3 },
            Mutation::Delete { at: 3, len: 3 },
            Mutation::Duplicate { at: 3, len: 3 },
        ] {
            assert!(mutated(b"", &[x]).is_empty());
        }
        assert_eq!(mutated(b"", &[Mutation::Insert { at: 5, token: 0 }]), b"0");
    }
}
