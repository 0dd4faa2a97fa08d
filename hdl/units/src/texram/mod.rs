//! Schilling & Knittel's TEXRAM chip (Figure 8): eight banks 810 holding a mipmap in the
//! two-level layout, so that the eight texels of any trilinear footprint (a 2x2 at level L and
//! a 2x2 at level L+1) are read in one access slot of 30 ns.
//!
//! The chip's transaction-level interface, the arithmetic its units share, the cycle-accurate
//! chip built on them and a behavioural stub:
//!
//! * [`TexramAccess`](crate::texram::TexramAccess): one access, `(DRF, u, v, lambda) -> 8 texels, weights, slots, faults`,
//!   the interface the footprint assembly, the volume stepper and the map chain are written
//!   against;
//! * [`address_812`](crate::texram::address_812): the address and control unit's arithmetic: level, weights and the
//!   border operations (wrap, clamp, mirror, border colour) of one access;
//! * [`banks_810`](crate::texram::banks_810): the two-level layout, texel `(level, x, y)` to bank and word (the bank
//!   address decoders 822), proved conflict-free by exhaustive tests;
//! * [`page_registers_824`](crate::texram::page_registers_824): one open row per bank; an access costs one slot, two if any bank
//!   it reads misses its open row;
//! * [`trilinear_818`](crate::texram::trilinear_818): the trilinear interpolator, one rounding of the exact weighted sum;
//! * [`clut_814`](crate::texram::clut_814): the colour look-up table of the index configuration, filtered after look-up;
//! * [`output_820`](crate::texram::output_820): the output stage's eq. 5, `C_d = (I_d | k_T | 1) . T`;
//! * [`video_port_808`](crate::texram::video_port_808): the video port with the mipmap generator 816 on the banks and the
//!   shift registers 826, stealing slots from the rasterizer;
//! * [`texram_802`](crate::texram::texram_802): the chip cycle by cycle (request port, 812, 824, 810, 818, 820, the video
//!   port), and `Texram802Access`, the chip behind [`TexramAccess`](crate::texram::TexramAccess);
//! * [`lockstep`](crate::texram::lockstep): one colour component per chip, four chips in lock-step;
//! * [`stub`](crate::texram::stub): [`stub::TexramStub`](crate::texram::stub::TexramStub), a behavioural model of the chip made of the above, exact
//!   in its texels, weights, result and slot count but not cycle by cycle (every
//!   configuration; the video port as single row transfers).
//!
//! Formats (\[C\] marks the project's choices where the document is silent, see
//! `../shared/notes/seed-systems.md`):
//!
//! | value | format | note |
//! |---|---|---|
//! | u, v | sQ12.8 (21 bits, two's complement) | level-0 texel units, \[C\] |
//! | lambda | sQ5.8 (14 bits) | level of detail, \[C\]; `-4.0 ..= 10.0` |
//! | texel | u8 | the document's 8-bit texels (section 6) |
//! | a, b, f | u8 (Q0.8, truncated) | weights, \[C\] |
//! | result of 818 | u8 | `(sum + 2^23) >> 24` of the exact sum, round half up |

pub mod address_812;
pub mod banks_810;
pub mod clut_814;
pub mod lockstep;
pub mod output_820;
pub mod page_registers_824;
pub mod stub;
pub mod texram_802;
pub mod trilinear_818;
pub mod video_port_808;

pub use address_812::{Border, Footprint};

/// Fraction bits of u, v and lambda.
pub const FRAC: u32 = 8;
/// u and v: sQ12.8, `-2^20 ..= 2^20 - 1` raw.
pub const UV_BITS: u32 = 21;
/// lambda: sQ5.8 raw, limited to `-4.0 ..= 10.0`.
pub const LAMBDA_MIN: i32 = -4 << FRAC;
pub const LAMBDA_MAX: i32 = 10 << FRAC;
/// Description register files: seven (DRF 7 holds the cube faces of an environment map).
pub const DRFS: usize = 7;

/// A description register file (DRF) as far as one texture access needs it: where the map
/// is, its size and its border operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Drf {
    /// log2 of the level-0 width and height (0 ..= 10: up to 1024 x 1024).
    pub width_log2: u32,
    pub height_log2: u32,
    /// First word of the even levels (banks 0-3) and of the odd levels (banks 4-7).
    pub base_even: u32,
    pub base_odd: u32,
    pub border: Border,
    /// How the stored texels are read (section 6).
    pub config: Config,
    /// Eq. 5 in the output stage 820: what multiplies the texture colour.
    pub modulate: output_820::Modulate,
}

/// The configurations of section 6 modelled so far.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Config {
    /// 8-bit luminance: the result in all four components.
    #[default]
    Luminance,
    /// 8-bit indices into the CLUT 814, filtered per component after the look-up.
    Index,
    /// True colour, \[C\] the conflict-free reading: the DRF's space holds four component
    /// planes of half its width and height in its quadrants (R top left, G top right, B
    /// bottom left, alpha bottom right); four accesses per pixel.
    Planar,
    /// True colour as section 6 prints it: R, G, B, alpha of a texel in one 2x2 cell, so the
    /// neighbours of a component sit in the same bank: every access conflicts (reported).
    Literal,
}

impl Config {
    /// Where texel (x, y) of level `k` of component `c`'s map (`plane`) is stored, in the
    /// level-k coordinates of the DRF's whole space.
    pub fn place(self, plane: &Drf, c: u32, k: u32, x: u32, y: u32) -> (u32, u32) {
        let (w, h) = plane.level_size(k);
        match self {
            Config::Luminance | Config::Index => (x, y),
            Config::Planar => (x + w * (c & 1), y + h * (c >> 1)),
            Config::Literal => (2 * x + (c & 1), 2 * y + (c >> 1)),
        }
    }
}

impl Drf {
    /// The map of one colour component (planar, literal): half the width and height.
    pub fn component_map(&self) -> Drf {
        Drf {
            width_log2: self.width_log2.saturating_sub(1),
            height_log2: self.height_log2.saturating_sub(1),
            config: Config::Luminance,
            ..*self
        }
    }
}

impl Drf {
    /// A map of `2^w x 2^h` texels at word 0 of both bank groups.
    pub fn new(width_log2: u32, height_log2: u32, border: Border) -> Drf {
        Drf {
            width_log2,
            height_log2,
            base_even: 0,
            base_odd: 0,
            border,
            config: Config::Luminance,
            modulate: output_820::Modulate::One,
        }
    }

    /// The coarsest level: the chain ends at 1 x 1.
    pub fn max_level(&self) -> u32 {
        self.width_log2.max(self.height_log2)
    }

    /// Width and height of level `k` (each at least 1).
    pub fn level_size(&self, k: u32) -> (u32, u32) {
        (
            1 << self.width_log2.saturating_sub(k),
            1 << self.height_log2.saturating_sub(k),
        )
    }

    pub fn validate(&self) -> Result<(), String> {
        let colour = matches!(self.config, Config::Planar | Config::Literal);
        // [C] Square: a component's levels then stay apart down to 1 x 1 (a rectangular
        // space's smaller side would reach 1 while the planes still need two rows).
        if colour && (self.width_log2 == 0 || self.width_log2 != self.height_log2) {
            return Err(format!(
                "map {}x{}: a planar or literal colour space is square, at least 2 x 2",
                1u64 << self.width_log2,
                1u64 << self.height_log2
            ));
        }
        if self.width_log2 > 10 || self.height_log2 > 10 {
            return Err(format!(
                "map {}x{}: at most 1024 x 1024 per chip",
                1u64 << self.width_log2,
                1u64 << self.height_log2
            ));
        }
        Ok(())
    }
}

/// One texture access as the rasterizer (or the footprint generator) sends it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexramRequest {
    /// Which DRF (0 .. [`DRFS`]).
    pub drf: u8,
    /// sQ12.8 raw, level-0 texel units.
    pub u: i32,
    pub v: i32,
    /// sQ5.8 raw.
    pub lambda: i32,
}

impl TexramRequest {
    /// Checks the fields against their formats.
    pub fn validate(&self) -> Result<(), String> {
        let lim = 1i32 << (UV_BITS - 1);
        if usize::from(self.drf) >= DRFS {
            return Err(format!("drf {}: 0..{DRFS}", self.drf));
        }
        for (n, x) in [("u", self.u), ("v", self.v)] {
            if !(-lim..lim).contains(&x) {
                return Err(format!("{n} raw {x}: outside sQ12.8"));
            }
        }
        if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&self.lambda) {
            return Err(format!("lambda raw {}: outside -4.0 ..= 10.0", self.lambda));
        }
        Ok(())
    }
}

/// What one access gives back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexramReply {
    /// The two levels read (`fine + 1 == coarse`, or both the last level).
    pub fine: u32,
    pub coarse: u32,
    /// Texels: the fine 2x2 as (i, j), (i+1, j), (i, j+1), (i+1, j+1), then the coarse 2x2.
    /// A border-colour texel holds the DRF's border colour.
    pub texels: [u8; 8],
    /// Weights of the fine and coarse levels (a along u, b along v) and between them (f).
    pub a: [u8; 2],
    pub b: [u8; 2],
    pub f: u8,
    /// The trilinear interpolator 818's result (luminance; R in index mode).
    pub value: u8,
    /// The result's R, G, B and alpha (luminance: the value four times).
    pub rgba: [u8; 4],
    /// Access slots taken (1, or 2 after a page fault).
    pub slots: u32,
    /// Banks whose open row missed.
    pub faults: u32,
}

/// The chip seen from outside: one trilinear access per call.
pub trait TexramAccess {
    /// Sets DRF `k`; the map it describes must then be loaded.
    fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String>;
    /// One access; `Err` names the field that is out of its format or an unset DRF.
    fn access(&mut self, req: TexramRequest) -> Result<TexramReply, String>;
    /// Slots taken since the start (accesses, their faults and anything else the chip did).
    fn slots(&self) -> u64;
    /// Writes the map `drf` describes (level 0 given, the levels above made as
    /// [`stub::next_level`] makes them) wherever its bases say, with or without a DRF
    /// pointing at it (an offset map's second plane, a cube face).
    fn load_map(&mut self, drf: &Drf, level0: &[u8]) -> Result<(), String>;
    /// One access through 812's working descriptor [`WORKING`]: the map the chain walker
    /// selected (a cube face, an offset plane, a detail map) loaded for this access only.
    fn access_with(
        &mut self,
        drf: &Drf,
        u: i32,
        v: i32,
        lambda: i32,
    ) -> Result<TexramReply, String>;
}

/// The request pointer of 812's working descriptor: the DRF the chain walker fills for one
/// access. The rasterizer's requests name DRFs `0 .. DRFS` only.
pub const WORKING: u8 = DRFS as u8;

/// Writes every level of `drf`'s map, from level 0 up, with `store`.
pub fn load_levels(
    drf: &Drf,
    level0: &[u8],
    mut store: impl FnMut(u32, &[u8]) -> Result<(), String>,
) -> Result<(), String> {
    drf.validate()?;
    // Each level's size is checked where it is stored (`banks_810::store_level`).
    let mut level = level0.to_vec();
    for k in 0..=drf.max_level() {
        store(k, &level)?;
        let (w, h) = drf.level_size(k);
        level = stub::next_level(w, h, &level);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_maps_are_square_and_their_components_luminance() {
        for config in [Config::Planar, Config::Literal] {
            let mut d = Drf::new(3, 3, Border::Wrap);
            d.config = config;
            assert!(d.validate().is_ok());
            let c = d.component_map();
            assert_eq!(
                (c.width_log2, c.height_log2, c.config),
                (2, 2, Config::Luminance)
            );
            for (w, h) in [(0, 0), (3, 2), (2, 3), (0, 3)] {
                let e = Drf {
                    width_log2: w,
                    height_log2: h,
                    ..d
                };
                assert!(e.validate().unwrap_err().contains("square"), "{w} {h}");
            }
        }
        // Luminance maps may be rectangular and 1 x 1; nothing past 1024.
        assert!(Drf::new(0, 0, Border::Wrap).validate().is_ok());
        assert!(Drf::new(10, 2, Border::Wrap).validate().is_ok());
        assert!(Drf::new(11, 2, Border::Wrap).validate().is_err());
    }

    #[test]
    fn requests_are_checked_against_their_formats() {
        let ok = TexramRequest {
            drf: 6,
            u: (1 << 20) - 1,
            v: -(1 << 20),
            lambda: LAMBDA_MAX,
        };
        assert!(ok.validate().is_ok());
        let bad = [
            TexramRequest { drf: 7, ..ok },
            TexramRequest { u: 1 << 20, ..ok },
            TexramRequest {
                v: -(1 << 20) - 1,
                ..ok
            },
            TexramRequest {
                lambda: LAMBDA_MAX + 1,
                ..ok
            },
            TexramRequest {
                lambda: LAMBDA_MIN - 1,
                ..ok
            },
        ];
        for r in bad {
            assert!(r.validate().is_err(), "{r:?}");
        }
        assert!(TexramRequest {
            lambda: LAMBDA_MIN,
            ..ok
        }
        .validate()
        .is_ok());
    }

    #[test]
    fn the_slot_is_one_to_fifteen_cycles() {
        use texram_802::TexramParams;
        for (c, ok) in [(0, false), (1, true), (6, true), (15, true), (16, false)] {
            let p = TexramParams { slot_cycles: c };
            assert_eq!(p.validate().is_ok(), ok, "{c}");
            assert_eq!(texram_802::Texram802::new(p).is_ok(), ok, "{c}");
        }
    }

    #[test]
    fn level_sizes_stop_at_one() {
        let d = Drf::new(4, 1, Border::Wrap);
        assert_eq!(d.max_level(), 4);
        assert_eq!(d.level_size(0), (16, 2));
        assert_eq!(d.level_size(1), (8, 1));
        assert_eq!(d.level_size(4), (1, 1));
    }
}
