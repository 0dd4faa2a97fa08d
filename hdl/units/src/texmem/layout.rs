//! Texture layout in DRAM 604 (Schilling & Knittel, Figure 6): where the control unit 607
//! finds the two 16-bit words of a 4x4 CCC block.
//!
//! A `width x height` texture (both multiples of 4) is `bw x bh` blocks of 4x4 texels,
//! `bw = width / 4`, `bh = height / 4`. Each block takes two consecutive words, word 0 the two
//! CLUT indices and word 1 the 16 decision bits (see [`crate::texmem::ccc_decode_608`]); a block never
//! straddles a page because pages hold an even number of words.
//!
//! * [`Layout::RowMajor`] (default): block `(bx, by)` at `base + 2 (by * bw + bx)`. With
//!   512-word pages one page holds 256 blocks, i.e. 256 / `bw` block rows.
//! * [`Layout::Tiled`]: the texture is cut into tiles of `tw x th` blocks that fill exactly one
//!   page (`tw * th = page_words / 2`, `tw = th` or `tw = 2 th`, both powers of two), so a 2D
//!   neighbourhood stays in one page. Tiles are stored row-major, `ceil(bw / tw)` per tile row;
//!   inside a tile the blocks are row-major. Block `(bx, by)` is at
//!   `base + page_words (ty * tiles_x + tx) + 2 ((by % th) tw + bx % tw)`, `tx = bx / tw`,
//!   `ty = by / th`. Partial tiles at the right and bottom edges waste the rest of their page.
//!
//! Addresses are word addresses into the DRAM (`rows * page_words` words); [`BlockMap::words`]
//! says how many words a texture needs, so a caller can check it fits before loading.

/// How blocks are placed in DRAM words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Layout {
    #[default]
    RowMajor,
    Tiled,
}

impl Layout {
    pub fn name(self) -> &'static str {
        match self {
            Layout::RowMajor => "row-major",
            Layout::Tiled => "tiled",
        }
    }

    pub fn parse(s: &str) -> Option<Layout> {
        match s {
            "row-major" => Some(Layout::RowMajor),
            "tiled" => Some(Layout::Tiled),
            _ => None,
        }
    }
}

/// The address calculation of one texture: its block grid, page size and layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockMap {
    pub layout: Layout,
    /// Blocks per row and per column.
    pub bw: u32,
    pub bh: u32,
    pub page_words: u32,
    /// First word of the texture.
    pub base: u64,
    tw: u32,
    th: u32,
    /// log2 of `tw` and `th` (both powers of two), kept beside them, set once in `new`: the
    /// tile arithmetic of every address is shifts and masks (recomputing them there cost the
    /// fill engine 4 of its 112 instructions a cycle).
    tw_log: u32,
    th_log: u32,
}

impl BlockMap {
    /// `page_words` must be a power of two >= 2.
    pub fn new(layout: Layout, bw: u32, bh: u32, page_words: u32, base: u64) -> BlockMap {
        let blocks = (page_words / 2).max(1);
        let lg = blocks.trailing_zeros();
        let tw = 1u32 << lg.div_ceil(2);
        let th = blocks / tw;
        BlockMap {
            layout,
            bw,
            bh,
            page_words,
            base,
            tw,
            th,
            tw_log: tw.trailing_zeros(),
            th_log: th.trailing_zeros(),
        }
    }

    /// Tile size in blocks (width, height); meaningful for [`Layout::Tiled`].
    pub fn tile(&self) -> (u32, u32) {
        (self.tw, self.th)
    }

    /// Word address of word 0 of block `(bx, by)`.
    #[inline]
    pub fn block_addr(&self, bx: u32, by: u32) -> u64 {
        match self.layout {
            Layout::RowMajor => {
                self.base + 2 * (u64::from(by) * u64::from(self.bw) + u64::from(bx))
            }
            Layout::Tiled => {
                let tiles_x = u64::from((self.bw + self.tw - 1) >> self.tw_log);
                let (tx, ty) = (u64::from(bx >> self.tw_log), u64::from(by >> self.th_log));
                let inner = u64::from((by & (self.th - 1)) << self.tw_log | bx & (self.tw - 1));
                self.base + u64::from(self.page_words) * (ty * tiles_x + tx) + 2 * inner
            }
        }
    }

    /// Words the texture occupies from `base` (the end of the last page used when tiled).
    pub fn words(&self) -> u64 {
        match self.layout {
            Layout::RowMajor => 2 * u64::from(self.bw) * u64::from(self.bh),
            Layout::Tiled => {
                u64::from(self.bw.div_ceil(self.tw))
                    * u64::from(self.bh.div_ceil(self.th))
                    * u64::from(self.page_words)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// Each layout's name parses back to it; other names to nothing.
    #[test]
    fn layout_names_parse_back() {
        for l in [Layout::RowMajor, Layout::Tiled] {
            assert_eq!(Layout::parse(l.name()), Some(l));
        }
        assert_eq!(Layout::parse("Tiled"), None);
    }

    #[test]
    fn layouts_are_injective_and_inside_the_footprint() {
        for layout in [Layout::RowMajor, Layout::Tiled] {
            for (bw, bh, pw) in [
                (64, 64, 512),
                (5, 3, 8),
                (12, 20, 16),
                (1, 1, 2),
                (7, 9, 1024),
            ] {
                let m = BlockMap::new(layout, bw, bh, pw, 10);
                let mut seen = HashSet::new();
                for by in 0..bh {
                    for bx in 0..bw {
                        let a = m.block_addr(bx, by);
                        assert!(a >= 10 && a + 2 <= 10 + m.words(), "{layout:?} {bx},{by}");
                        assert_eq!((a - 10) % 2, 0);
                        // Both words in one page (base 10 is not page aligned, so check
                        // relative to base).
                        assert_eq!((a - 10) / u64::from(pw), (a - 10 + 1) / u64::from(pw));
                        assert!(seen.insert(a), "{layout:?} {bx},{by} collides");
                    }
                }
            }
        }
    }

    #[test]
    fn tiles_fill_one_page() {
        let m = BlockMap::new(Layout::Tiled, 64, 64, 512, 0);
        assert_eq!(m.tile(), (16, 16));
        let m = BlockMap::new(Layout::Tiled, 64, 64, 1024, 0);
        assert_eq!(m.tile(), (32, 16));
        // Every block of a tile is in the same page.
        let m = BlockMap::new(Layout::Tiled, 64, 64, 512, 0);
        for by in 0..16 {
            for bx in 0..16 {
                assert_eq!(m.block_addr(bx, by) / 512, 0);
            }
        }
        assert_eq!(m.block_addr(16, 0) / 512, 1);
        assert_eq!(m.block_addr(0, 16) / 512, 4);
    }
}
