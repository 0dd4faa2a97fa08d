//! The voxel store: banks 0-3 of the TEXRAM (its level-0 arrays) hold 8-bit voxels in a 2x2
//! interleave, voxel `(x, y, z)` in bank `2 (y & 1) + (x & 1)` (the level-0 texel rule, so a
//! 2x2 of a slice is one access), and the accesses a resample point needs.
//!
//! # Word order inside a bank \[C\]
//! * [`Order::SliceMajor`]: `z (X/2)(Y/2) + (y >> 1)(X/2) + (x >> 1)`, slices one after the
//!   other as level 0 stores a texture;
//! * [`Order::ColumnMajor`]: `((y >> 1)(X/2) + (x >> 1)) Z + z`, a 2x2 column's slices
//!   next to each other, so the two slices of a value access share a row.
//!
//! # Borders \[C\]
//! Voxel indices outside the volume are reflected without repeating the edge voxel
//! (`-1 -> 1`, `X -> X - 2`): a reflection keeps an index's parity, so the x (and y) indices
//! of an access (`i, i+1` or `i-1, i+2`) keep different parities and every access reads four
//! different banks at every position, borders included (proved exhaustively in the tests).
//! Clamping would read `-1` and `2` both from the even bank at the volume's edge.
//!
//! # Accesses of a resample point (section 13)
//! With `(i, j, k)` the voxel below the point: value mode reads the 2x2 at slices k and k+1
//! (accesses 1-2); gradient mode adds columns i-1 and i+2 (rows j, j+1) at k and k+1
//! (3-4), rows j-1 and j+2 (columns i, i+1) at k and k+1 (5-6) and the 2x2 at k-1 and k+2
//! (7-8): the 32 voxels of the central differences at the eight corners.
//!
//! # Access order \[C\]
//! The y-row accesses (5-6) open other rows than the rest (the neighbouring 2x2 columns of y
//! lie `(X/2) Z` words away in column-major order). The sequencer alternates the order from
//! sample to sample, `1 2 7 8 3 4 5 6` then `5 6 3 4 7 8 1 2`, so that consecutive samples
//! along a ray meet in the same rows: one row switch a sample instead of two
//! ([`access_order`]).

use crate::texram::banks_810::bank_words;

/// Voxel positions: sQ9.12 (22 bits), voxel `x` at `x` exactly \[C\].
pub const POS_FRAC: u32 = 12;
pub const POS_BITS: u32 = 22;

/// Word order inside a bank.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Order {
    SliceMajor,
    ColumnMajor,
}

/// What a resample point reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Two accesses: the 2x2 at slices k and k+1.
    Value,
    /// Eight accesses: the 32 voxels of the central-difference gradient.
    Gradient,
}

impl Mode {
    pub fn accesses(self) -> usize {
        match self {
            Mode::Value => 2,
            Mode::Gradient => 8,
        }
    }
}

/// The voxel store's shape and timing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct VolumeParams {
    /// Voxels along x, y, z: x and y even, 2..=256 (a position's integer part is 9 bits);
    /// z 1..=256.
    pub dims: (u32, u32, u32),
    pub order: Order,
    /// Words of a DRAM row (page), a power of two 16..=65536 (\[C\]; the chip's texture path
    /// uses 512).
    pub row_words: u32,
    /// Clock cycles of a 30 ns access slot (5 ns clock).
    pub slot_cycles: u32,
}

impl VolumeParams {
    pub fn new(x: u32, y: u32, z: u32) -> VolumeParams {
        VolumeParams {
            dims: (x, y, z),
            order: Order::ColumnMajor,
            row_words: 512,
            slot_cycles: 6,
        }
    }

    /// Words each bank holds.
    pub fn words(&self) -> u64 {
        let (x, y, z) = self.dims;
        u64::from(x / 2) * u64::from(y / 2) * u64::from(z)
    }

    /// Checks the dimensions (x, y even 2..=256, z 1..=256, at most [`bank_room`] words a
    /// bank), the row size and the slot length.
    pub fn validate(&self) -> Result<(), String> {
        let (x, y, z) = self.dims;
        for (n, v) in [("x", x), ("y", y)] {
            if v % 2 != 0 || !(2..=256).contains(&v) {
                return Err(format!("{n} size {v}: even, 2..=256"));
            }
        }
        if !(1..=256).contains(&z) {
            return Err(format!("z size {z}: 1..=256"));
        }
        let room = bank_room();
        if self.words() > room {
            return Err(format!(
                "{x}x{y}x{z} needs {} words a bank, banks 0-3 hold {room}",
                self.words()
            ));
        }
        if !self.row_words.is_power_of_two() || !(16..=65536).contains(&self.row_words) {
            return Err(format!(
                "row_words {}: a power of two, 16..=65536",
                self.row_words
            ));
        }
        crate::pages::page_registers_824::check_slot_cycles(self.slot_cycles)
    }
}

/// Words a bank of level 0 holds for a volume: the smallest of banks 0-3 (the one limit of a
/// volume's size; `texrtl volume --help` states it).
pub fn bank_room() -> u64 {
    (0..4).map(|b| u64::from(bank_words(b))).min().unwrap_or(0)
}

/// The order of a point's accesses (0-based indices of [`access_voxels`]): value mode 0, 1;
/// gradient mode `0 1 6 7 2 3 4 5` for even samples of a ray, `4 5 2 3 6 7 0 1` for odd.
pub fn access_order(mode: Mode, k: u64) -> &'static [usize] {
    match (mode, k % 2) {
        (Mode::Value, _) => &[0, 1],
        (Mode::Gradient, 0) => &[0, 1, 6, 7, 2, 3, 4, 5],
        (Mode::Gradient, _) => &[4, 5, 2, 3, 6, 7, 0, 1],
    }
}

/// Index `i` reflected into `0..n` without repeating the edge (period `2 (n - 1)`).
pub fn fold(i: i64, n: u32) -> u32 {
    let n = i64::from(n);
    if n == 1 {
        return 0;
    }
    let m = i.rem_euclid(2 * (n - 1));
    (if m < n { m } else { 2 * (n - 1) - m }) as u32
}

/// Bank and word of voxel `(x, y, z)` (inside the volume).
pub fn locate(p: &VolumeParams, x: u32, y: u32, z: u32) -> (usize, u32) {
    let (nx, ny, nz) = p.dims;
    let bank = (2 * (y & 1) + (x & 1)) as usize;
    let column = (y >> 1) * (nx / 2) + (x >> 1);
    let word = match p.order {
        Order::SliceMajor => z * (nx / 2) * (ny / 2) + column,
        Order::ColumnMajor => column * nz + z,
    };
    (bank, word)
}

/// The four voxels of access `a` (0-based) of the point whose lower voxel is `(i, j, k)`,
/// folded into the volume.
pub fn access_voxels(
    p: &VolumeParams,
    a: usize,
    (i, j, k): (i64, i64, i64),
) -> [(u32, u32, u32); 4] {
    let (di, dj, dk): ([i64; 2], [i64; 2], i64) = match a {
        0 => ([0, 1], [0, 1], 0),
        1 => ([0, 1], [0, 1], 1),
        2 => ([-1, 2], [0, 1], 0),
        3 => ([-1, 2], [0, 1], 1),
        4 => ([0, 1], [-1, 2], 0),
        5 => ([0, 1], [-1, 2], 1),
        6 => ([0, 1], [0, 1], -1),
        _ => ([0, 1], [0, 1], 2),
    };
    let (nx, ny, nz) = p.dims;
    let v = |x: i64, y: i64| (fold(i + x, nx), fold(j + y, ny), fold(k + dk, nz));
    [
        v(di[0], dj[0]),
        v(di[1], dj[0]),
        v(di[0], dj[1]),
        v(di[1], dj[1]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_keeps_parity_and_stays_inside() {
        for n in [2u32, 3, 4, 7, 8] {
            for i in -20i64..20 {
                let f = fold(i, n);
                assert!(f < n);
                assert_eq!(i64::from(f).rem_euclid(2), i.rem_euclid(2), "n {n} i {i}");
            }
            assert_eq!(fold(-1, n), 1);
            assert_eq!(fold(i64::from(n), n), n - 2);
        }
        assert_eq!(fold(5, 1), 0);
    }

    /// Section 13's claim, exhaustively on small volumes: every access of every resample
    /// point (every voxel as the lower corner, and one beyond every face), in both modes and
    /// both word orders, reads four different banks, and different voxels never share a
    /// bank word.
    #[test]
    fn every_access_reads_four_banks() {
        for dims in [(2, 2, 1), (4, 2, 3), (6, 4, 5), (8, 8, 4)] {
            for order in [Order::SliceMajor, Order::ColumnMajor] {
                let p = VolumeParams {
                    order,
                    ..VolumeParams::new(dims.0, dims.1, dims.2)
                };
                let mut words = std::collections::HashMap::new();
                for z in 0..dims.2 {
                    for y in 0..dims.1 {
                        for x in 0..dims.0 {
                            let at = locate(&p, x, y, z);
                            assert!(u64::from(at.1) < p.words());
                            assert_eq!(words.insert(at, (x, y, z)), None, "{dims:?} {order:?}");
                        }
                    }
                }
                for k in -1..=i64::from(dims.2) {
                    for j in -1..=i64::from(dims.1) {
                        for i in -1..=i64::from(dims.0) {
                            for a in 0..Mode::Gradient.accesses() {
                                let v = access_voxels(&p, a, (i, j, k));
                                let banks: Vec<usize> =
                                    v.iter().map(|&(x, y, z)| locate(&p, x, y, z).0).collect();
                                let mut sorted = banks.clone();
                                sorted.sort_unstable();
                                assert_eq!(
                                    sorted,
                                    vec![0, 1, 2, 3],
                                    "{dims:?} ({i},{j},{k}) access {a}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// No volume fills banks 0-3 exactly: their room, 280,064 words, is 2^9 x 547 and 547 is
    /// a prime above 256, so no x/2, y/2 <= 128 and z <= 256 multiply to it, and `validate`'s
    /// `words() > room` cannot be told from `>=`. Should the banks change so one does, it
    /// must fit.
    #[test]
    fn a_volume_filling_the_banks_exactly_fits() {
        let room = (0..4).map(|b| u64::from(bank_words(b))).min().unwrap();
        assert_eq!(room, 280_064);
        for a in 1..=128u64 {
            for b in 1..=128u64 {
                let z = room / (a * b);
                if room % (a * b) == 0 && z <= 256 {
                    let p = VolumeParams::new(2 * a as u32, 2 * b as u32, z as u32);
                    assert_eq!(p.validate(), Ok(()));
                }
            }
        }
    }

    #[test]
    fn parameters_are_checked() {
        assert_eq!(VolumeParams::new(64, 128, 128).validate(), Ok(()));
        let e = |p: VolumeParams| p.validate().unwrap_err();
        assert!(e(VolumeParams::new(3, 4, 4)).contains("x size 3"));
        assert!(e(VolumeParams::new(4, 258, 4)).contains("y size 258"));
        assert!(e(VolumeParams::new(4, 4, 0)).contains("z size 0"));
        assert!(e(VolumeParams::new(256, 256, 32)).contains("needs 524288 words"));
        let mut p = VolumeParams::new(4, 4, 4);
        p.row_words = 100;
        assert!(e(p).contains("row_words 100"));
        p.row_words = 64;
        p.slot_cycles = 0;
        assert!(e(p).contains("slot_cycles 0"));
        // Each range's ends pass, one beyond fails.
        let room = (0..4).map(|b| u64::from(bank_words(b))).min().unwrap();
        let z_max = (room / (128 * 128)) as u32;
        for (x, y, z) in [(2, 2, 1), (2, 256, 256), (256, 2, 256), (256, 256, z_max)] {
            assert_eq!(VolumeParams::new(x, y, z).validate(), Ok(()), "{x}x{y}x{z}");
        }
        assert!(e(VolumeParams::new(256, 256, z_max + 1)).contains("words a bank"));
        assert!(e(VolumeParams::new(0, 4, 4)).contains("x size 0"));
        assert!(e(VolumeParams::new(4, 4, 257)).contains("z size 257"));
        let with = |rw: u32, sc: u32| {
            let mut p = VolumeParams::new(4, 4, 4);
            (p.row_words, p.slot_cycles) = (rw, sc);
            p.validate()
        };
        for (rw, sc) in [(16, 1), (65536, 15)] {
            assert_eq!(with(rw, sc), Ok(()), "{rw} {sc}");
        }
        assert!(with(8, 6).unwrap_err().contains("row_words 8"));
        assert!(with(131072, 6).unwrap_err().contains("row_words 131072"));
        assert!(with(64, 16).unwrap_err().contains("slot_cycles 16"));
    }
}
