//! The address and control unit 812's arithmetic for one trilinear access: the two levels
//! and the weight between them from lambda, the 2x2 at each level and its weights from u, v,
//! and the border operation that brings each texel index into the map (section 6: the
//! OpenGL operations plus mirroring).
//!
//! With L = floor(lambda) clamped to `0 ..= Lmax` and f its fraction (0 when lambda < 0, as
//! there is no detail map here, or at the last level), each level k of {L, L + 1} reads at
//! `u_k = u * 2^-k - 1/2`: `i = floor(u_k)`, `a = frac(u_k)` truncated to 8 bits (v alike).
//! All of it is exact integer arithmetic on the raw sQ12.8 / sQ5.8 values.

use super::banks_810::{locate, AccessRegs, ROUNDS};
use super::output_820::Modulate;
use super::{Config, Drf, FRAC, UV_BITS};
use crate::fx::Format;
use crate::kernel::{Module, Reg, Regs};

/// What a texel index outside `0 .. size` becomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Border {
    /// `i mod size`.
    #[default]
    Wrap,
    /// The nearest edge texel.
    Clamp,
    /// Reflected at the edges: `..., 1, 0, 0, 1, ..., size-1, size-1, ...`.
    Mirror,
    /// The DRF's border colour; no bank is read.
    Colour(u8),
    /// Wrapped inside aligned tiles of `2^t` texels at level 0 (`2^(t-k)` at level k, at
    /// least 1), the tile being the one the sample point lies in; then wrapped at the map's
    /// edge. A detail map's tiles (section 9): each level-0 texel of the texture owns one
    /// tile of the detail map, which repeats inside it \[C\].
    Tile(u8),
}

impl Border {
    pub fn name(self) -> String {
        match self {
            Border::Wrap => "wrap".into(),
            Border::Clamp => "clamp".into(),
            Border::Mirror => "mirror".into(),
            Border::Colour(c) => format!("border:{c}"),
            Border::Tile(t) => format!("tile:{t}"),
        }
    }

    /// `wrap`, `clamp`, `mirror`, `border:N` (N 0..=255) or `tile:T` (T 0..=10).
    pub fn parse(s: &str) -> Option<Border> {
        match s {
            "wrap" => Some(Border::Wrap),
            "clamp" => Some(Border::Clamp),
            "mirror" => Some(Border::Mirror),
            _ => {
                if let Some(t) = s.strip_prefix("tile:") {
                    return t.parse().ok().filter(|t| *t <= 10).map(Border::Tile);
                }
                s.strip_prefix("border:")
                    .and_then(|n| n.parse().ok())
                    .map(Border::Colour)
            }
        }
    }

    /// The texel index `i` of an axis of `size` texels (a power of two) becomes, or `None`
    /// for the border colour. A tile border here is the map's wrap (the tile needs the
    /// sample point: [`Border::pair`]).
    pub fn remap(self, i: i32, size: u32) -> Option<u32> {
        let n = size as i32;
        match self {
            Border::Wrap | Border::Tile(_) => Some((i & (n - 1)) as u32),
            Border::Clamp => Some(i.clamp(0, n - 1) as u32),
            Border::Mirror => {
                let m = i & (2 * n - 1);
                Some(if m < n { m } else { 2 * n - 1 - m } as u32)
            }
            Border::Colour(_) => (0..n).contains(&i).then_some(i as u32),
        }
    }
}

impl Border {
    /// The pair `i`, `i + 1` of an axis of `size` texels at level `k`, whose weight toward
    /// `i + 1` is `a` (the sample point is at `i + 1/2 + a/256`).
    pub fn pair(self, i: i32, a: u8, size: u32, k: u32) -> [Option<u32>; 2] {
        let Border::Tile(t) = self else {
            return [self.remap(i, size), self.remap(i + 1, size)];
        };
        let tile = 1i32 << u32::from(t).saturating_sub(k);
        // The tile the sample point lies in: i's when a < 1/2, else i + 1's.
        let base = (i + i32::from(a >= 128)) & !(tile - 1);
        [i, i + 1].map(|x| self.remap(base + ((x - base) & (tile - 1)), size))
    }
}

/// The two levels of an access and the weight of the coarser one.
pub fn levels(lambda: i32, max_level: u32) -> (u32, u32, u8) {
    let l = lambda >> FRAC;
    if l < 0 {
        return (0, 1.min(max_level), 0);
    }
    let l = l as u32;
    if l >= max_level {
        return (max_level, max_level, 0);
    }
    (l, l + 1, (lambda & 0xFF) as u8)
}

/// Index and weight along one axis at level `k`: `c * 2^-k - 1/2` split into its floor and
/// its fraction's top 8 bits.
pub fn axis(c: i32, k: u32) -> (i32, u8) {
    let x = c - ((1 << (FRAC - 1)) << k);
    (x >> (FRAC + k), ((x >> k) & 0xFF) as u8)
}

/// Where one access reads: per level, the four texels (i, j), (i+1, j), (i, j+1),
/// (i+1, j+1) after the border operation (`None`: the border colour), and the weights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Footprint {
    pub fine: u32,
    pub coarse: u32,
    pub texels: [[Option<(u32, u32)>; 4]; 2],
    pub a: [u8; 2],
    pub b: [u8; 2],
    pub f: u8,
}

impl Footprint {
    /// The footprint of `(u, v, lambda)` (raw sQ12.8, sQ12.8, sQ5.8) on the map of `drf`.
    pub fn of(drf: &Drf, u: i32, v: i32, lambda: i32) -> Footprint {
        let (fine, coarse, f) = levels(lambda, drf.max_level());
        let mut fp = Footprint {
            fine,
            coarse,
            texels: [[None; 4]; 2],
            a: [0; 2],
            b: [0; 2],
            f,
        };
        for (n, k) in [fine, coarse].into_iter().enumerate() {
            let (w, h) = drf.level_size(k);
            let (i, a) = axis(u, k);
            let (j, b) = axis(v, k);
            let xs = drf.border.pair(i, a, w, k);
            let ys = drf.border.pair(j, b, h, k);
            for (t, (dx, dy)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
                fp.texels[n][t] = xs[dx].zip(ys[dy]);
            }
            (fp.a[n], fp.b[n]) = (a, b);
        }
        fp
    }
}

/// The request 812 is splitting into component accesses (a colour request of the planar or
/// literal layout): its DRF, `u`, `v`, `lambda`.
#[derive(Clone, Debug, Regs)]
struct Held {
    drf: Reg,
    u: Reg,
    v: Reg,
    lambda: Reg,
}

/// The address and control unit 812: the access it computes from a request, or from the next
/// component of the colour request it holds, registered for the banks. The chip drives it
/// ([`Address812::take`], [`Address812::next_part`]) in its own `eval`.
#[derive(Clone, Debug, Module)]
#[module(kind = "address_812")]
pub struct Address812 {
    #[reg]
    pub access: AccessRegs,
    #[reg]
    held: Held,
    /// Accesses whose 2x2 took a bank more than one round (the literal layout), since reset.
    #[reg]
    pub conflicts: Reg,
}

impl Default for Address812 {
    fn default() -> Self {
        Address812::new()
    }
}

impl Address812 {
    pub fn new() -> Address812 {
        Address812 {
            access: AccessRegs::new(None),
            held: Held {
                drf: Reg::new("held_drf", Format::uint(3)),
                u: Reg::new("held_u", Format::signed(UV_BITS, 8)),
                v: Reg::new("held_v", Format::signed(UV_BITS, 8)),
                lambda: Reg::new("held_lambda", Format::signed(14, 8)),
            },
            conflicts: Reg::new("conflicts", Format::uint(40)),
        }
    }

    /// Nothing of its own: its registers are set by the chip's `eval` through `take` and
    /// `next_part`.
    pub fn eval(&mut self) {}

    /// A request taken: `k` (DRF number, `d` its descriptor), raw `u`, `v`, `lambda` and the
    /// illumination, held, and its first access (part 0) addressed.
    pub fn take(&mut self, k: u64, d: Option<Drf>, (u, v, l): (i32, i32, i32), illum: u64) {
        let h = &mut self.held;
        h.drf.set_next_bits(k);
        h.u.set_next_raw(i64::from(u));
        h.v.set_next_raw(i64::from(v));
        h.lambda.set_next_raw(i64::from(l));
        self.address(0, d, (u, v, l));
        self.access.illum.set_next_bits(illum);
    }

    /// The DRF number of the request held.
    pub fn held_drf(&self) -> usize {
        self.held.drf.q().bits() as usize
    }

    /// The held request's next component addressed (`d` the held DRF's descriptor).
    pub fn next_part(&mut self, d: Option<Drf>) {
        let h = &self.held;
        let uvl = [&h.u, &h.v, &h.lambda].map(|r| r.q().raw() as i32);
        let part = self.access.part.q().bits() as u32 + 1;
        self.address(part, d, (uvl[0], uvl[1], uvl[2]));
    }

    /// Part `part` of a request on the map of `d` into the access registers: its footprint,
    /// on the component's map for the colour layouts. An unset DRF reads nothing: every texel
    /// is the border colour 0 (the testbench checks DRFs are set).
    fn address(&mut self, part: u32, d: Option<Drf>, (u, v, l): (i32, i32, i32)) {
        let colour_map = d.is_some_and(|d| matches!(d.config, Config::Planar | Config::Literal));
        let a = &mut self.access;
        a.part.set_next_bits(u64::from(part));
        a.last.set_next_bool(!colour_map || part == 3);
        let Some(d) = d else {
            a.words.read.set_next_bits(0);
            a.border.set_next_bits(0xFF);
            a.colour.set_next_bits(0);
            return;
        };
        let plane = if colour_map { d.component_map() } else { d };
        let fp = Footprint::of(&plane, u, v, l);
        let (mut read, mut src, mut border, mut rounds) = (0u64, 0u64, 0u64, 1);
        for (n, lv) in [fp.fine, fp.coarse].into_iter().enumerate() {
            for (t, at) in fp.texels[n].iter().enumerate() {
                let texel = 4 * n + t;
                let Some((x, y)) = at else {
                    border |= 1 << texel;
                    continue;
                };
                let (gx, gy) = d.config.place(&plane, part, lv, *x, *y);
                let (bank, word) = locate(&d, lv, gx, gy);
                let round = a.words.round_for(bank, u64::from(word), &mut read);
                rounds = rounds.max(round + 1);
                src |= ((bank * ROUNDS + round) as u64) << (5 * texel);
            }
        }
        a.words.read.set_next_bits(read);
        a.src.set_next_bits(src);
        a.border.set_next_bits(border);
        // Only the literal colour layout asks a bank for more than one word.
        self.conflicts
            .set_next_bits(self.conflicts.q().bits() + u64::from(rounds > 1));
        let w = [fp.a[0], fp.b[0], fp.a[1], fp.b[1], fp.f];
        let packed =
            (w.iter().enumerate()).fold(0u64, |acc, (i, x)| acc | u64::from(*x) << (8 * i));
        let a = &mut self.access;
        a.weights.set_next_bits(packed);
        let colour = match d.border {
            Border::Colour(c) => c,
            _ => 0,
        };
        a.colour.set_next_bits(u64::from(colour));
        a.index.set_next_bool(d.config == Config::Index);
        let m = match d.modulate {
            Modulate::Illumination => 0,
            Modulate::Constant(k) => 1 << 8 | u64::from(k),
            Modulate::One => 2 << 8,
        };
        a.modulate.set_next_bits(m);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The border operations as written in the notes, on plain integers.
    fn reference(border: Border, i: i64, n: i64) -> Option<i64> {
        match border {
            Border::Wrap => Some(i.rem_euclid(n)),
            Border::Clamp => Some(i.max(0).min(n - 1)),
            Border::Mirror => {
                let m = i.rem_euclid(2 * n);
                Some(if m < n { m } else { 2 * n - 1 - m })
            }
            Border::Colour(_) => (0 <= i && i < n).then_some(i),
            Border::Tile(_) => Some(i.rem_euclid(n)),
        }
    }

    /// A tile border keeps both texels in the tile of the sample point, whatever the level
    /// and weight: exhaustively over a 64-texel axis with 16-texel tiles at levels 0-5.
    #[test]
    fn a_tile_border_wraps_inside_the_sample_points_tile() {
        let b = Border::Tile(4);
        for k in 0..=5u32 {
            let size = 64 >> k;
            let tile = (16i64 >> k).max(1);
            for i in -3..size as i32 + 3 {
                for a in [0u8, 1, 127, 128, 200, 255] {
                    // The sample point's texel: floor(i + 1/2 + a/256).
                    let at = (256 * i64::from(i) + 128 + i64::from(a)).div_euclid(256);
                    let t0 = at.div_euclid(tile) * tile;
                    let got = b.pair(i, a, size, k);
                    for (n, x) in [i, i + 1].into_iter().enumerate() {
                        let want =
                            (t0 + (i64::from(x) - t0).rem_euclid(tile)).rem_euclid(size.into());
                        assert_eq!(got[n].map(i64::from), Some(want), "k {k} i {i} a {a}");
                    }
                    // Two texels of one tile differ in parity (no bank conflict) unless the
                    // tile is a single texel.
                    let same = got[0] == got[1];
                    assert_eq!(same, tile == 1, "k {k} i {i} a {a}");
                }
            }
        }
        // The printed pairs: level 0, texel 15 of tile 0 at weight < 1/2 pairs with texel 0.
        assert_eq!(b.pair(15, 10, 64, 0), [Some(15), Some(0)]);
        assert_eq!(b.pair(15, 130, 64, 0), [Some(31), Some(16)]);
        assert_eq!(Border::Wrap.pair(63, 10, 64, 0), [Some(63), Some(0)]);
    }

    #[test]
    fn border_operations_match_their_definitions_exhaustively() {
        for border in [
            Border::Wrap,
            Border::Clamp,
            Border::Mirror,
            Border::Colour(7),
        ] {
            for log in 0..=10 {
                let n = 1u32 << log;
                for i in -3000..3000 {
                    let got = border.remap(i, n).map(i64::from);
                    assert_eq!(
                        got,
                        reference(border, i.into(), n.into()),
                        "{border:?} {i} {n}"
                    );
                }
            }
        }
    }

    #[test]
    fn axis_is_floor_and_fraction_of_the_scaled_coordinate() {
        for k in 0..=10u32 {
            for c in (-(1 << 20)..(1 << 20)).step_by(997) {
                // c / 2^(8+k) - 1/2 as a fraction over 2^(8+k): floor and remainder.
                let (num, den) = (i64::from(c) - (128i64 << k), 256i64 << k);
                let (i, a) = axis(c, k);
                assert_eq!(i64::from(i), num.div_euclid(den), "c {c} k {k}");
                assert_eq!(i64::from(a), num.rem_euclid(den) * 256 / den, "c {c} k {k}");
            }
        }
        // Texel centres: u = 2.5 at level 0 is texel 2 with weight 0.
        assert_eq!(axis(2 * 256 + 128, 0), (2, 0));
        assert_eq!(axis(3 * 256, 0), (2, 128));
    }

    #[test]
    fn levels_clamp_and_the_fraction_weighs_the_coarser_level() {
        assert_eq!(levels(-4 << 8, 10), (0, 1, 0));
        assert_eq!(levels(-1, 10), (0, 1, 0));
        assert_eq!(levels(0, 10), (0, 1, 0));
        assert_eq!(levels((2 << 8) + 64, 10), (2, 3, 64));
        assert_eq!(levels((9 << 8) + 255, 10), (9, 10, 255));
        assert_eq!(levels(10 << 8, 10), (10, 10, 0));
        assert_eq!(levels(10 << 8, 3), (3, 3, 0));
        assert_eq!(levels(100, 0), (0, 0, 0));
    }

    #[test]
    fn names_parse_back() {
        for b in [
            Border::Wrap,
            Border::Clamp,
            Border::Mirror,
            Border::Colour(200),
            Border::Tile(4),
        ] {
            assert_eq!(Border::parse(&b.name()), Some(b));
        }
        assert_eq!(Border::parse("tile:11"), None);
        assert_eq!(Border::parse("border:256"), None);
        assert_eq!(Border::parse("repeat"), None);
    }
}
