//! The colour look-up table 814 (section 6, configuration 2): 256 entries of 32 bits (R in
//! bits 24-31, G 16-23, B 8-15, alpha 0-7), eight read ports, so the eight indices of one
//! trilinear access are looked up at once; the interpolator 818 then filters each component
//! of the looked-up colours (post-lookup filtering: filtering indices would mix unrelated
//! colours). \[C\] 818 handles the four components in the same slot.

use super::trilinear_818::trilinear;
use crate::fx::Format;
use crate::kernel::{Module, Signal};

/// The table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Clut {
    pub entries: [u32; 256],
}

impl Default for Clut {
    fn default() -> Self {
        Clut::identity()
    }
}

impl Clut {
    /// Entry i = (i, i, i, i): index mode then equals luminance mode.
    pub fn identity() -> Clut {
        Clut {
            entries: std::array::from_fn(|i| (i as u32) * 0x0101_0101),
        }
    }

    /// The four components of entry `i`: R, G, B, alpha.
    pub fn rgba(&self, i: u8) -> [u8; 4] {
        self.entries[usize::from(i)].to_be_bytes()
    }

    /// Eight indices looked up and filtered per component with the access's weights.
    pub fn filter(&self, indices: &[u8; 8], a: [u8; 2], b: [u8; 2], f: u8) -> [u8; 4] {
        let colours = indices.map(|i| self.rgba(i));
        std::array::from_fn(|c| trilinear(&colours.map(|x| x[c]), a, b, f))
    }
}

/// The table in the chip, its eight read ports traced: the entries an index access's texels
/// look up, as it finishes (0 otherwise).
#[derive(Clone, Debug, Module)]
#[module(kind = "clut_814")]
pub struct Clut814 {
    pub table: Clut,
    #[wire]
    pub entries: [Signal; 8],
}

impl Default for Clut814 {
    fn default() -> Self {
        Clut814::new()
    }
}

impl Clut814 {
    pub fn new() -> Clut814 {
        let names = [
            "entry0", "entry1", "entry2", "entry3", "entry4", "entry5", "entry6", "entry7",
        ];
        Clut814 {
            table: Clut::identity(),
            entries: names.map(|n| Signal::new(n, Format::uint(32))),
        }
    }

    /// No look-up unless an index access finishes.
    pub fn eval(&mut self) {
        for e in &mut self.entries {
            e.set_bits(0);
        }
    }

    /// The eight indices looked up and filtered per component: the colour (R top byte).
    pub fn look_up(&mut self, indices: &[u8; 8], a: [u8; 2], b: [u8; 2], f: u8) -> u32 {
        for (e, &i) in self.entries.iter_mut().zip(indices) {
            e.set_bits(u64::from(u32::from_be_bytes(self.table.rgba(i))));
        }
        u32::from_be_bytes(self.table.filter(indices, a, b, f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_identity_table_filters_like_luminance() {
        let c = Clut::identity();
        let t = [3, 250, 17, 99, 0, 255, 128, 64];
        for (a, b, f) in [
            ([0, 0], [0, 0], 0),
            ([77, 200], [13, 255], 99),
            ([255; 2], [128; 2], 255),
        ] {
            let v = trilinear(&t, a, b, f);
            assert_eq!(c.filter(&t, a, b, f), [v; 4]);
        }
    }

    #[test]
    fn components_are_filtered_apart() {
        let mut c = Clut::identity();
        c.entries[1] = 0xFF00_8010;
        c.entries[2] = 0x00FF_0030;
        // Half way between index 1 and index 2 along u, at level 0 only.
        let t = [1, 2, 1, 2, 1, 2, 1, 2];
        assert_eq!(c.filter(&t, [128, 128], [0, 0], 0), [128, 128, 64, 32]);
    }
}
