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

use super::ccc_decode_608::LineWord;
use crate::fx::{Bit, Format};
use crate::kernel::{Module, Reg, RegOf, Signal, SignalOf};

hdl::formats! {
    /// The entries a request used, one bit each (A-D).
    pub EntryMask = Format::uint(4);
}

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
    // A chain, not an array of the three: the array's pairs were written a word at a time
    // and read back two words at once before the writes had landed, a stall in every
    // lookahead of the texture unit.
    (nx.map(|nx| (nx, by)).into_iter())
        .chain(ny.map(|ny| (bx, ny)))
        .chain(nx.zip(ny))
}

/// One entry.
#[derive(Clone, Debug, Module)]
#[module(kind = "cache_614_entry")]
pub struct Entry {
    #[instance]
    name: String,
    #[reg]
    pub valid: RegOf<Bit>,
    #[reg]
    pub tag_x: Reg,
    #[reg]
    pub tag_y: Reg,
    #[reg]
    pub data: RegOf<LineWord>,
    #[reg]
    pub prefetched: RegOf<Bit>,
}

impl Entry {
    /// The owning cache writes the entry's next values.
    fn eval(&mut self) {}
}

/// Cache 614. Reads are combinational ([`TextureCache::holds`], [`TextureCache::line`]: the
/// four 64-bit lines to colour extract 618); a write ([`TextureCache::write`]) or an
/// invalidation takes effect at the clock edge.
/// Cache 614: four entries A-D (Figure 7).
///
/// Ports, driven by the unit in its `eval` and applied by [`TextureCache::eval`] in this
/// order: `touch` (entries a request used: their `prefetched` bits clear), `invalidate` (every
/// entry, for the cache-off mode), `write` with `write_bx`, `write_by`, `write_data`,
/// `write_prefetched` (a filled line; it wins over the others for its entry). Lookups read
/// the registered state ([`TextureCache::holds`], [`TextureCache::line`]). The entries change
/// only on a touch, an invalidation or a write, the cache's clock enable: in a cycle without
/// one its edge is skipped.
#[derive(Clone, Debug, Module)]
#[module(
    kind = "cache_614",
    enable = self.touch.bits() != 0 || self.invalidate.is_high() || self.write.is_high()
)]
pub struct TextureCache {
    #[instance]
    name: String,
    #[input]
    pub touch: SignalOf<EntryMask>,
    #[input]
    pub invalidate: SignalOf<Bit>,
    #[input]
    pub write: SignalOf<Bit>,
    #[input]
    pub write_bx: Signal,
    #[input]
    pub write_by: Signal,
    #[input]
    pub write_data: SignalOf<LineWord>,
    #[input]
    pub write_prefetched: SignalOf<Bit>,
    #[child]
    pub entries: [Entry; 4],
}

impl TextureCache {
    /// A cache with tags of `tag_bits` bits per coordinate (block coordinates have one more).
    pub fn new(name: &str, tag_bits: u32) -> TextureCache {
        let e = |n: &str| Entry {
            name: n.into(),
            valid: RegOf::new("valid"),
            tag_x: Reg::new("tag_x", Format::uint(tag_bits)),
            tag_y: Reg::new("tag_y", Format::uint(tag_bits)),
            data: RegOf::new("data"),
            prefetched: RegOf::new("prefetched"),
        };
        let b = Format::uint(tag_bits + 1);
        TextureCache {
            name: name.into(),
            touch: SignalOf::new("touch"),
            invalidate: SignalOf::new("invalidate"),
            write: SignalOf::new("write"),
            write_bx: Signal::new("write_bx", b),
            write_by: Signal::new("write_by", b),
            write_data: SignalOf::new("write_data"),
            write_prefetched: SignalOf::new("write_prefetched"),
            entries: [e("entry_a"), e("entry_b"), e("entry_c"), e("entry_d")],
        }
    }

    /// Whether block `(bx, by)` is in its entry.
    #[inline]
    pub fn holds(&self, bx: u32, by: u32) -> bool {
        let e = &self.entries[entry_of(bx, by)];
        e.valid.q().is_high()
            && e.tag_x.q().bits() == u64::from(bx >> 1)
            && e.tag_y.q().bits() == u64::from(by >> 1)
    }

    /// The line in entry `entry` (0..4).
    #[inline]
    pub fn line(&self, entry: usize) -> u64 {
        self.entries[entry].data.q().bits()
    }

    /// Whether entry `entry` holds a prefetched line no request has used yet.
    #[inline]
    pub fn prefetched(&self, entry: usize) -> bool {
        self.entries[entry].prefetched.q().is_high()
    }
}

impl TextureCache {
    /// The entries' next values from this cycle's touch, invalidation and write.
    #[inline]
    pub fn eval(&mut self) {
        let touch = self.touch.bits();
        let inval = self.invalidate.is_high();
        for (k, e) in self.entries.iter_mut().enumerate() {
            if touch >> k & 1 == 1 {
                e.prefetched.set_next_bool(false);
            }
            if inval {
                e.valid.set_next_bool(false);
            }
        }
        if self.write.is_high() {
            let (bx, by) = (self.write_bx.bits() as u32, self.write_by.bits() as u32);
            let e = &mut self.entries[entry_of(bx, by)];
            e.valid.set_next_bool(true);
            e.tag_x.set_next_bits(u64::from(bx >> 1));
            e.tag_y.set_next_bits(u64::from(by >> 1));
            e.data.set_next_bits(self.write_data.bits());
            e.prefetched.set_next_bool(self.write_prefetched.is_high());
        }
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

    /// One cycle of the cache with its ports driven (none: all ports idle).
    fn cycle(
        sim: &mut crate::kernel::Sim<TextureCache>,
        write: Option<(u32, u32, u64)>,
        touch: u64,
        inval: bool,
    ) {
        let c = &mut sim.dut;
        c.write.set_bool(write.is_some());
        let (bx, by, data) = write.unwrap_or((0, 0, 0));
        c.write_bx.set_bits(u64::from(bx));
        c.write_by.set_bits(u64::from(by));
        c.write_data.set_bits(data);
        c.write_prefetched.set_bool(true);
        c.touch.set_bits(touch);
        c.invalidate.set_bool(inval);
        sim.step();
    }

    #[test]
    fn write_then_hold_then_invalidate() {
        let mut sim = crate::kernel::Sim::new(TextureCache::new("c", 9)).check_schedule(true);
        assert!(!sim.dut.holds(3, 5));
        cycle(&mut sim, Some((3, 5, 0xdead_beef)), 0, false);
        let e = entry_of(3, 5);
        assert!(sim.dut.holds(3, 5));
        assert!(!sim.dut.holds(5, 5), "same entry, other tag");
        assert_eq!(sim.dut.line(e), 0xdead_beef);
        assert!(sim.dut.prefetched(e));
        cycle(&mut sim, None, 1 << e, false);
        assert!(!sim.dut.prefetched(e), "touched");
        cycle(&mut sim, None, 0, false);
        assert!(sim.dut.holds(3, 5), "holds when the ports are idle");
        // A write wins over an invalidation of the same cycle for its entry.
        cycle(&mut sim, Some((1, 0, 7)), 0, true);
        assert!(!sim.dut.holds(3, 5));
        assert!(sim.dut.holds(1, 0));
    }
}
