//! Cube-face selection for environment maps (Schilling & Knittel section 7, "divide by the
//! largest component"): from the reflection vector `w` (eq. 4, not normalised) the face of the
//! cube its major axis points to, and the face coordinates `s = (sc/|ma| + 1)/2`,
//! `t = (tc/|ma| + 1)/2` with the OpenGL cube-map table \[C\]. `1/|ma|` comes from a table and
//! one Newton step, the structure of the inverse square root of unit 156.
//!
//! # Arithmetic (\[C\], `../shared/notes/seed-systems.md` section 4)
//! * Major axis: the largest `|w_i|` by exact compares, ties to x, then y.
//! * `|ma| = 2^e m` with `m` in [1, 2) (`uQ1.16`, exact: `|ma|` has 16 fraction bits);
//!   `r0` = the table entry for the six bits after the leading one, `1/m` at the interval's
//!   midpoint rounded to `uQ1.16`; `r1 = round(r0 (2 - round(m r0)))` in `uQ1.16`, ties to even.
//! * `s = round((sc r1 2^-e + 1) / 2)` in `uQ0.12`: the product `sc r1` exact, its shift by
//!   `e` floored to units of 2^-32 (an error under 2^-20 LSB), then one rounding, ties to
//!   even, held to `0 ..= 1 - 2^-12` (`sc = |ma|` would give 1). The same for `t`.
//! * A zero vector has no face: +Z with `s = t = 1/2` \[C\].
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `wx`, `wy`, `wz` | sQ3.16 (eq. 4's `w`, `|w| < 8`) |
//! | `face` | u3: +X 0, -X 1, +Y 2, -Y 3, +Z 4, -Z 5 |
//! | `s`, `t` | uQ0.12 |
//!
//! Error of `s`, `t` against the exact `(sc/|ma| + 1)/2`: at most [`ST_BOUND_LSB`] LSBs
//! (derived in the tests from the reciprocal's). One register stage.

use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

/// Fraction bits of `w`, the mantissa and the reciprocal.
pub const W_FRAC: u32 = 16;
/// Bits of `w`'s components: sQ3.16.
pub const W_BITS: u32 = 20;
/// Fraction bits of `s`, `t`.
pub const ST_FRAC: u32 = 12;
const TABLE_BITS: u32 = 6;

/// Bound of the reciprocal's relative error after the Newton step, in units of 2^-16 (an
/// integer multiple, so that hdl holds no floating point): the table's error at most
/// `2^-7 + 2^-17` relative squares to under 2^-13.9, plus two roundings of half a unit.
pub const RECIP_BOUND_UNITS: u64 = 5;
/// `s`, `t` within this many LSBs (times 4) of the exact value: half of the reciprocal's
/// 5/65536 relative error (the ratio is at most 1) is 0.16 LSB of 2^-12, plus the final
/// rounding's half: 0.66 LSB, so 3/4 LSB as a whole number of quarters.
pub const ST_BOUND_LSB: u64 = 3;

/// The six faces.
pub const FACES: [&str; 6] = ["+x", "-x", "+y", "-y", "+z", "-z"];

/// `round(2^32 / mid)` for the midpoints `mid` of the table's intervals of [1, 2) (uQ1.16).
fn table() -> [u64; 1 << TABLE_BITS] {
    std::array::from_fn(|i| {
        // Midpoint 1 + (2i + 1)/128 in units of 2^-17: 2^17 + (2i + 1) 2^10.
        let mid = (1u64 << 17) + ((2 * i as u64 + 1) << 10);
        // 1/mid in units of 2^-16: 2^33 / mid, rounded half up.
        ((1u64 << 34) / mid + 1) >> 1
    })
}

/// Round `x / 2^sh` to nearest, ties to even (`sh` >= 1).
fn round_even(x: u128, sh: u32) -> u128 {
    let q = x >> sh;
    let rem = x & ((1 << sh) - 1);
    let half = 1 << (sh - 1);
    if rem > half || (rem == half && q & 1 == 1) {
        q + 1
    } else {
        q
    }
}

/// The reciprocal of `a` (raw, 16 fraction bits, > 0): `(r1, e)` with `1/a ~ r1 2^-16 2^-e`.
pub fn reciprocal(a: u64, tab: &[u64; 64]) -> (u64, i32) {
    let lead = 63 - a.leading_zeros() as i32;
    // m = a 2^-(lead - 16), in uQ1.16: exact (a has at most 19 integer + fraction bits).
    let m = if lead >= 16 {
        a >> (lead - 16)
    } else {
        a << (16 - lead)
    };
    let e = lead - 16;
    let r0 = tab[((m >> (16 - TABLE_BITS)) & 63) as usize];
    // m r0 in units of 2^-32, rounded to 2^-16.
    let mr = round_even(u128::from(m) * u128::from(r0), 16) as i64;
    let two = 2i64 << 16;
    let r1 = round_even(u128::from(r0) * (two - mr) as u128, 16) as u64;
    (r1, e)
}

/// The face and `(s, t)` (raw uQ0.12) of `w` (raw sQ3.16).
pub fn face_st(w: [i64; 3], tab: &[u64; 64]) -> (u8, u64, u64) {
    let a = w.map(i64::unsigned_abs);
    let axis = if a[0] >= a[1] && a[0] >= a[2] {
        0
    } else if a[1] >= a[2] {
        1
    } else {
        2
    };
    if a[axis] == 0 {
        return (4, 1 << (ST_FRAC - 1), 1 << (ST_FRAC - 1));
    }
    let neg = w[axis] < 0;
    let (x, y, z) = (w[0], w[1], w[2]);
    let (sc, tc) = match (axis, neg) {
        (0, false) => (-z, -y),
        (0, true) => (z, -y),
        (1, false) => (x, z),
        (1, true) => (x, -z),
        (_, false) => (x, -y),
        (_, true) => (-x, -y),
    };
    let (r1, e) = reciprocal(a[axis], tab);
    let coord = |c: i64| -> u64 {
        // c r1 2^-e in units of 2^-32 (c: 2^-16, r1: 2^-16), plus 1, halved: units of 2^-33.
        let p = i128::from(c) * i128::from(r1);
        let scaled = if e >= 0 { p >> e } else { p << -e };
        let v = scaled + (1i128 << 32);
        let max = (1i128 << 33) - (1 << (33 - ST_FRAC));
        // Held below 1: the largest value rounds to 1 - 2^-12.
        round_even(v.clamp(0, max) as u128, 33 - ST_FRAC) as u64
    };
    let face = 2 * axis as u8 + u8::from(neg);
    (face, coord(sc), coord(tc))
}

/// The unit: one register stage.
#[derive(Clone, Debug, Module)]
#[module(kind = "cube_face")]
pub struct CubeFace {
    tab: [u64; 64],
    #[input]
    pub w: [Signal; 3],
    #[input]
    pub valid_in: Signal,
    #[reg]
    pub valid: Reg,
    #[reg]
    pub face: Reg,
    #[reg]
    pub s: Reg,
    #[reg]
    pub t: Reg,
}

impl Default for CubeFace {
    fn default() -> Self {
        CubeFace::new()
    }
}

impl CubeFace {
    pub fn new() -> CubeFace {
        let w = Format::signed(W_BITS, W_FRAC as i32);
        let st = Format::unsigned(ST_FRAC, ST_FRAC as i32);
        CubeFace {
            tab: table(),
            w: ["wx", "wy", "wz"].map(|n| Signal::new(n, w)),
            valid_in: Signal::bit("valid_in"),
            valid: Reg::new("valid", Format::uint(1)),
            face: Reg::new("face", Format::uint(3)),
            s: Reg::new("s", st),
            t: Reg::new("t", st),
        }
    }

    /// The reciprocal table (for models of the same arithmetic).
    pub fn table(&self) -> &[u64; 64] {
        &self.tab
    }
}

impl CubeFace {
    /// The face and face coordinates of a valid vector, into the output registers.
    pub fn eval(&mut self) {
        let v = self.valid_in.is_high();
        self.valid.set_next_bool(v);
        if v {
            let (f, s, t) = face_st(self.w.each_ref().map(|x| x.raw()), &self.tab);
            self.face.set_next_bits(u64::from(f));
            self.s.set_next_bits(s);
            self.t.set_next_bits(t);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reciprocal against the exact integer quotient over every mantissa of 16 fraction
    /// bits: within its bound.
    #[test]
    fn the_reciprocal_is_within_its_bound_for_every_mantissa() {
        let tab = table();
        let mut worst = 0u64;
        for m in (1u64 << 16)..(2u64 << 16) {
            let (r1, e) = reciprocal(m, &tab);
            assert_eq!(e, 0);
            // Exact 2^32 / m against r1, in units of 2^-16, scaled by m/2^16 (relative).
            let exact = (1u128 << 48) / u128::from(m); // 2^-32 units
            let got = u128::from(r1) << 16;
            let diff = exact.abs_diff(got);
            // Relative error in units of 2^-16: diff / exact * 2^16.
            let rel = (diff << 16) / exact;
            worst = worst.max(rel as u64);
        }
        assert!(worst <= RECIP_BOUND_UNITS, "{worst}");
        assert!(worst >= 1, "a bound that is never approached");
    }

    /// Every table entry is 2^33 / midpoint rounded half up, by quotient and remainder.
    #[test]
    fn the_table_holds_the_rounded_reciprocals_of_the_midpoints() {
        for (i, e) in table().iter().enumerate() {
            let mid = (1u64 << 17) + ((2 * i as u64 + 1) << 10);
            let (q, r) = ((1u64 << 33) / mid, (1u64 << 33) % mid);
            assert_eq!(*e, q + u64::from(2 * r >= mid), "entry {i}");
        }
    }

    /// Ties go to the even neighbour; anything else to the nearest.
    #[test]
    fn round_even_rounds_ties_to_even() {
        // 2.5 -> 2, 3.5 -> 4, 2.25 -> 2, 2.75 -> 3, 5.5 -> 6, 4.5 -> 4 (halves of 4 bits).
        assert_eq!(round_even(0b101, 1), 2);
        assert_eq!(round_even(0b111, 1), 4);
        assert_eq!(round_even(0b1001, 2), 2);
        assert_eq!(round_even(0b1011, 2), 3);
        assert_eq!(round_even(0b1011, 1), 6);
        assert_eq!(round_even(0b1001, 1), 4);
        assert_eq!(round_even(0b1000, 3), 1);
        assert_eq!(round_even(0b11000, 4), 2);
    }

    #[test]
    fn faces_follow_the_major_axis_with_ties_to_x_then_y() {
        let tab = table();
        let one = 1i64 << 16;
        let f = |w: [i64; 3]| face_st(w, &tab).0;
        assert_eq!(f([one, 0, 0]), 0);
        assert_eq!(f([-one, 0, 0]), 1);
        assert_eq!(f([0, one, 0]), 2);
        assert_eq!(f([0, -one, 0]), 3);
        assert_eq!(f([0, 0, one]), 4);
        assert_eq!(f([0, 0, -one]), 5);
        assert_eq!(f([one, -one, one]), 0);
        assert_eq!(f([1, -one, one]), 3);
        assert_eq!(face_st([0, 0, 0], &tab), (4, 2048, 2048));
        // The centre of a face is (1/2, 1/2); +X at (1, 0, -1/2): s = (1/2 + 1)/2 = 3/4.
        assert_eq!(face_st([one, 0, 0], &tab), (0, 2048, 2048));
        assert_eq!(face_st([one, 0, -one / 2], &tab), (0, 3072, 2048));
    }
}
