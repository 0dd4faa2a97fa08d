//! Cache 614 of the texture memory path (Schilling & Knittel, Figures 6 and 7): four entries,
//! each one decoded 4x4 block (a 64-bit [`Line`](crate::texmem::ccc_decode_608::Line)), direct mapped with
//! the interleaved assignment of Figure 7, and the lookahead that chooses which neighbours to
//! preload.
//!
//! # Mapping (Figure 7)
//! Block `(bx, by)` may live only in entry `(bx & 1) | (by & 1) << 1` (A, B, C, D =
//! 0, 1, 2, 3). The tag is `(bx >> 1, by >> 1)`, `tag_bits` bits each. The 2x2 texels of a
//! bilinear footprint lie in at most 2x2 adjacent blocks, whose parities all differ, so they
//! never compete for an entry (with clamp-to-edge addressing; a wrapped texture with an odd
//! number of blocks would break this, which is why the unit clamps).
//!
//! # Lookahead ([`Lookahead`])
//! * Quadrant (the document's scheme): for the current point `(x, y)` (integer texel
//!   position) in block `(bx, by)`, the quadrant is bit 1 of `x` and bit 1 of `y` (two bits);
//!   the three neighbours are `(bx + dx, by)`, `(bx, by + dy)` and `(bx + dx, by + dy)` with
//!   `dx = +1` in the right half and -1 in the left, likewise `dy` ([`lookahead`]).
//! * Direction (the document's "more sophisticated lookahead"): `dx`, `dy` are the signs of
//!   the motion from the previous point of the scanline to this one (`u`, `v` with their
//!   fractions); the neighbours are `(bx + dx, by)` if `dx != 0`, `(bx, by + dy)` if `dy != 0`
//!   and the diagonal if both ([`lookahead_direction`]). It preloads the next block as soon as
//!   a scanline enters a block, not only in its second half.
//!
//! Neighbours outside the texture are not fetched. They go to entries other than the current
//! block's.
//!
//! # Per-entry state (all registers, traced)
//! `valid` (1), `tag_x`, `tag_y` (`tag_bits`), `data` (64), `prefetched` (1: filled by a
//! prefetch and not yet used by a request; for the statistics only).

use crate::fx::Format;
use crate::kernel::{Module, Reg, Visitor};
use crate::signals;

/// Entry of block `(bx, by)` (Figure 7).
#[inline]
pub fn entry_of(bx: u32, by: u32) -> usize {
    (bx & 1 | (by & 1) << 1) as usize
}

/// Which blocks the unit preloads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Lookahead {
    Off,
    #[default]
    Quadrant,
    Direction,
}

impl Lookahead {
    pub fn name(self) -> &'static str {
        match self {
            Lookahead::Off => "off",
            Lookahead::Quadrant => "quadrant",
            Lookahead::Direction => "direction",
        }
    }

    pub fn parse(s: &str) -> Option<Lookahead> {
        [Lookahead::Off, Lookahead::Quadrant, Lookahead::Direction]
            .into_iter()
            .find(|l| l.name() == s)
    }
}

/// Block `b + d` (`d` in -1..=1) if inside `0..n`.
#[inline]
fn step(b: u32, d: i32, n: u32) -> Option<u32> {
    match d {
        1 => (b + 1 < n).then_some(b + 1),
        -1 => b.checked_sub(1),
        _ => None,
    }
}

/// The three neighbours to preload for point `(x, y)` of a texture of `bw x bh` blocks
/// (quadrant lookahead).
pub fn lookahead(x: u32, y: u32, bw: u32, bh: u32) -> impl Iterator<Item = (u32, u32)> {
    let dx = if x >> 1 & 1 == 1 { 1 } else { -1 };
    let dy = if y >> 1 & 1 == 1 { 1 } else { -1 };
    lookahead_direction(x >> 2, y >> 2, dx, dy, bw, bh)
}

/// The neighbours of block `(bx, by)` in direction `(dx, dy)` (each -1, 0 or 1): along x,
/// along y, diagonal; those outside the texture or with a zero step left out.
pub fn lookahead_direction(
    bx: u32,
    by: u32,
    dx: i32,
    dy: i32,
    bw: u32,
    bh: u32,
) -> impl Iterator<Item = (u32, u32)> {
    let nx = step(bx, dx, bw);
    let ny = step(by, dy, bh);
    [nx.map(|nx| (nx, by)), ny.map(|ny| (bx, ny)), nx.zip(ny)]
        .into_iter()
        .flatten()
}

/// One entry.
#[derive(Clone, Debug)]
pub struct Entry {
    name: String,
    pub valid: Reg,
    pub tag_x: Reg,
    pub tag_y: Reg,
    pub data: Reg,
    pub prefetched: Reg,
}

impl Module for Entry {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "cache_614_entry"
    }
    fn eval(&mut self) {}
    fn tick(&mut self, reset: bool) {
        self.valid.tick(reset);
        self.tag_x.tick(reset);
        self.tag_y.tick(reset);
        self.data.tick(reset);
        self.prefetched.tick(reset);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        signals!(v; Reg: self.valid, self.tag_x, self.tag_y, self.data, self.prefetched);
        v.leave();
    }
}

/// Cache 614. Reads are combinational ([`TextureCache::holds`], [`TextureCache::line`]: the
/// four 64-bit lines to colour extract 618); a write ([`TextureCache::write`]) or an
/// invalidation takes effect at the clock edge.
#[derive(Clone, Debug)]
pub struct TextureCache {
    name: String,
    pub entries: [Entry; 4],
}

impl TextureCache {
    /// `tag_bits`: width of each tag half (enough for `blocks_per_side / 2`).
    pub fn new(name: &str, tag_bits: u32) -> TextureCache {
        let e = |n: &str| Entry {
            name: n.into(),
            valid: Reg::new("valid", Format::uint(1)),
            tag_x: Reg::new("tag_x", Format::uint(tag_bits)),
            tag_y: Reg::new("tag_y", Format::uint(tag_bits)),
            data: Reg::new("data", Format::uint(64)),
            prefetched: Reg::new("prefetched", Format::uint(1)),
        };
        TextureCache {
            name: name.into(),
            entries: [e("entry_a"), e("entry_b"), e("entry_c"), e("entry_d")],
        }
    }

    /// Does entry `entry_of(bx, by)` hold block `(bx, by)`?
    #[inline]
    pub fn holds(&self, bx: u32, by: u32) -> bool {
        let e = &self.entries[entry_of(bx, by)];
        e.valid.q().is_high()
            && e.tag_x.q().bits() == u64::from(bx >> 1)
            && e.tag_y.q().bits() == u64::from(by >> 1)
    }

    #[inline]
    pub fn line(&self, entry: usize) -> u64 {
        self.entries[entry].data.q().bits()
    }

    /// Writes block `(bx, by)` into its entry at the next edge.
    pub fn write(&mut self, bx: u32, by: u32, data: u64, prefetched: bool) {
        let e = &mut self.entries[entry_of(bx, by)];
        e.valid.set_next_bool(true);
        e.tag_x.set_next_bits(u64::from(bx >> 1));
        e.tag_y.set_next_bits(u64::from(by >> 1));
        e.data.set_next_bits(data);
        e.prefetched.set_next_bool(prefetched);
    }

    /// Marks the entry of `(bx, by)` used (clears `prefetched`) at the next edge; returns
    /// whether it had been prefetched and not used before. Call before a
    /// [`write`](TextureCache::write) in the same cycle, which then wins.
    pub fn touch(&mut self, bx: u32, by: u32) -> bool {
        let e = &mut self.entries[entry_of(bx, by)];
        let was = e.prefetched.q().is_high();
        if was {
            e.prefetched.set_next_bool(false);
        }
        was
    }

    /// Invalidates every entry at the next edge (the cache-disabled mode).
    pub fn invalidate(&mut self) {
        for e in &mut self.entries {
            e.valid.set_next_bool(false);
        }
    }
}

impl Module for TextureCache {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "cache_614"
    }
    fn eval(&mut self) {}
    fn tick(&mut self, reset: bool) {
        for e in &mut self.entries {
            e.tick(reset);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        for e in &self.entries {
            e.visit(v);
        }
        v.leave();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bilinear_footprint_never_conflicts() {
        // Every 2x2 footprint (clamped) on a 5x3-block texture maps its blocks to distinct
        // entries, exhaustively.
        let (bw, bh) = (5u32, 3u32);
        for y in 0..4 * bh {
            for x in 0..4 * bw {
                let x1 = (x + 1).min(4 * bw - 1);
                let y1 = (y + 1).min(4 * bh - 1);
                let mut blocks = vec![(x >> 2, y >> 2), (x1 >> 2, y >> 2), (x >> 2, y1 >> 2)];
                blocks.push((x1 >> 2, y1 >> 2));
                blocks.sort();
                blocks.dedup();
                let mut entries: Vec<_> = blocks.iter().map(|&(a, b)| entry_of(a, b)).collect();
                entries.sort();
                entries.dedup();
                assert_eq!(entries.len(), blocks.len(), "({x},{y})");
            }
        }
    }

    #[test]
    fn lookahead_picks_the_quadrants_neighbours() {
        // Point in the lower-right quadrant of block (2, 2): right, below, diagonal.
        let n: Vec<_> = lookahead(4 * 2 + 3, 4 * 2 + 2, 8, 8).collect();
        assert_eq!(n, vec![(3, 2), (2, 3), (3, 3)]);
        // Upper-left quadrant: left, above, diagonal.
        let n: Vec<_> = lookahead(4 * 2 + 1, 4 * 2, 8, 8).collect();
        assert_eq!(n, vec![(1, 2), (2, 1), (1, 1)]);
        // At the texture's corner nothing lies outside.
        assert_eq!(lookahead(0, 0, 8, 8).count(), 0);
        assert_eq!(lookahead(31, 0, 8, 8).count(), 0);
        let n: Vec<_> = lookahead(31, 31, 8, 9).collect();
        assert_eq!(n, vec![(7, 8)]);
        // The neighbours always use the three other entries.
        for (x, y) in [(9, 10), (10, 9), (13, 14), (4, 4)] {
            let mut e: Vec<_> = lookahead(x, y, 8, 8).map(|(a, b)| entry_of(a, b)).collect();
            e.push(entry_of(x >> 2, y >> 2));
            e.sort();
            assert_eq!(e, vec![0, 1, 2, 3]);
        }
    }

    #[test]
    fn direction_lookahead_follows_the_motion() {
        let n: Vec<_> = lookahead_direction(2, 2, 1, 0, 8, 8).collect();
        assert_eq!(n, vec![(3, 2)]);
        let n: Vec<_> = lookahead_direction(2, 2, -1, 1, 8, 8).collect();
        assert_eq!(n, vec![(1, 2), (2, 3), (1, 3)]);
        assert_eq!(lookahead_direction(2, 2, 0, 0, 8, 8).count(), 0);
        assert_eq!(lookahead_direction(7, 0, 1, -1, 8, 8).count(), 0);
        for l in [Lookahead::Off, Lookahead::Quadrant, Lookahead::Direction] {
            assert_eq!(Lookahead::parse(l.name()), Some(l));
        }
    }

    #[test]
    fn write_then_hold_then_invalidate() {
        let mut c = TextureCache::new("c", 9);
        assert!(!c.holds(3, 5));
        c.write(3, 5, 0xdead_beef, true);
        c.tick(false);
        assert!(c.holds(3, 5));
        assert!(!c.holds(5, 5), "same entry, other tag");
        assert_eq!(c.line(entry_of(3, 5)), 0xdead_beef);
        assert!(c.touch(3, 5));
        c.tick(false);
        assert!(!c.touch(3, 5));
        c.invalidate();
        c.tick(false);
        assert!(!c.holds(3, 5));
    }
}
