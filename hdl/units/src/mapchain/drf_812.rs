//! The description register files of the address and control unit 812 (section 14, Fig. 16):
//! seven DRFs, each describing one map of a pixel's chain and pointing to the next.
//!
//! Fields (the document lists them; their widths are \[C\]):
//!
//! | field | format | meaning |
//! |---|---|---|
//! | `kind` | u3 | texture, u,v offset, detail, reflectance, environment |
//! | `map` | the access DRF ([`Drf`]) | size (log2 w, h: u4 each), border operation and colour, eq. 5's selection and `k_T` (u8), plane 0's bases (u19 each) |
//! | `planes` | 6 x (u19, u19) | bases of further planes: an offset DRF's v offsets (plane 1), an environment DRF's six faces (+X -X +Y -Y +Z -Z) |
//! | `link` | u3 + valid | the next DRF of the chain, none at its end |
//! | `new_coords` | u1 | the chain computes this map's coordinates before its access (detail maps from the offsets, environment maps from the vectors) |
//! | `k_s` | u8 | eq. 6's constant (environment DRF) |
//! | `detail` | u2 | how detail colour meets the texel: replace, multiply, add-signed \[C\] |
//! | `base` | u1 | eqs 6 and 7's `(C_d \| I_d)` |
//! | `light` | u1 | eq. 7's `(E \| I_s)` |
//!
//! Maps are placed by [`Placer`] at row boundaries, one after the other in each bank group,
//! so that two maps never share a DRAM row: a chain's consecutive accesses to different maps
//! then open other rows, as the document expects ("will most probably cause a page fault").

use crate::texram::banks_810::{bank_words, group_words, ROW_WORDS};
use crate::texram::{Border, Drf, DRFS};

/// What a DRF's map is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Kind {
    /// A texture (colour) map, read trilinearly at the pixel's (u, v, lambda).
    #[default]
    Texture,
    /// Two 8-bit offset maps (u in plane 0, v in plane 1) of the texture's level 0, read at
    /// the pixel's texel: the origin of its tile in the detail map (section 9).
    Offset,
    /// A detail map: levels -4 .. -1 below the texture's level 0 (its own levels 0 .. 3).
    Detail,
    /// A reflectance map: eq. 7's `R` at the pixel's (u, v, lambda).
    Reflectance,
    /// An environment map: six faces (section 7).
    Environment,
}

impl Kind {
    pub const ALL: [Kind; 5] = [
        Kind::Texture,
        Kind::Offset,
        Kind::Detail,
        Kind::Reflectance,
        Kind::Environment,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Kind::Texture => "texture",
            Kind::Offset => "offset",
            Kind::Detail => "detail",
            Kind::Reflectance => "reflectance",
            Kind::Environment => "environment",
        }
    }

    pub fn parse(s: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.name() == s)
    }
}

/// How a detail colour D meets the texel T below it (Fig. 9's text is cut off here) \[C\].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DetailMode {
    /// D replaces T (T is then read only where -1 < lambda < 0).
    #[default]
    Replace,
    /// `T . D` (eq. 5's product): T is read as a third step.
    Multiply,
    /// `T + D - 128`, held to 0 ..= 255: T is read as a third step.
    AddSigned,
}

impl DetailMode {
    pub fn name(self) -> &'static str {
        match self {
            DetailMode::Replace => "replace",
            DetailMode::Multiply => "multiply",
            DetailMode::AddSigned => "add-signed",
        }
    }

    pub fn parse(s: &str) -> Option<DetailMode> {
        [
            DetailMode::Replace,
            DetailMode::Multiply,
            DetailMode::AddSigned,
        ]
        .into_iter()
        .find(|m| m.name() == s)
    }
}

/// One description register file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChainDrf {
    pub kind: Kind,
    /// Size, border, eq. 5's selection and plane 0's bases.
    pub map: Drf,
    /// Bases (even group, odd group) of planes 1 .. 5 (plane 0 is `map`'s).
    pub planes: [(u32, u32); 5],
    pub link: Option<u8>,
    pub new_coords: bool,
    /// Eq. 6's `k_s` (environment DRF).
    pub k_s: u8,
    pub detail: DetailMode,
    /// Eqs 6 and 7: the base is the shaded texture colour `C_d` (true) or `I_d`.
    pub base_texture: bool,
    /// Eq. 7: the reflectance multiplies the environment colour (true) or `I_s`.
    pub light_env: bool,
}

impl ChainDrf {
    /// A DRF of `kind` for `map`, at the end of its chain.
    pub fn new(kind: Kind, map: Drf) -> ChainDrf {
        ChainDrf {
            kind,
            map,
            planes: [(0, 0); 5],
            link: None,
            new_coords: matches!(kind, Kind::Detail | Kind::Environment),
            k_s: 255,
            detail: DetailMode::Replace,
            base_texture: true,
            light_env: true,
        }
    }

    /// Planes the map has: two offset maps, six faces, one otherwise.
    pub fn plane_count(&self) -> usize {
        match self.kind {
            Kind::Offset => 2,
            Kind::Environment => 6,
            _ => 1,
        }
    }

    /// The access DRF of plane `p`.
    pub fn plane(&self, p: usize) -> Drf {
        if p == 0 {
            return self.map;
        }
        let (base_even, base_odd) = self.planes[p - 1];
        Drf {
            base_even,
            base_odd,
            ..self.map
        }
    }

    /// What the walker reads plane `p` through: its map with eq. 5 left to the chain's end
    /// (the bank read's own output stage passes the filtered texel unchanged).
    pub fn access(&self, p: usize) -> Drf {
        Drf {
            modulate: crate::texram::output_820::Modulate::One,
            ..self.plane(p)
        }
    }

    pub fn validate(&self) -> Result<(), String> {
        self.map.validate()?;
        if self.map.config != crate::texram::Config::Luminance {
            return Err("a chained map is one 8-bit component (one chip per colour)".into());
        }
        if let Some(l) = self.link {
            if usize::from(l) >= DRFS {
                return Err(format!("link {l}: 0..{DRFS}"));
            }
        }
        let computed = matches!(self.kind, Kind::Detail | Kind::Environment);
        if self.kind == Kind::Detail && !self.new_coords {
            return Err("a detail map is read at coordinates from the offsets: new_coords".into());
        }
        if !computed && self.new_coords {
            return Err(format!(
                "new_coords: a {} map is read at the pixel's coordinates",
                self.kind.name()
            ));
        }
        let (w, h) = (self.map.width_log2, self.map.height_log2);
        match self.kind {
            Kind::Detail if w > 8 || h > 8 => {
                Err("a detail map is at most 256 x 256 (8-bit offsets)".into())
            }
            Kind::Environment if w != h || w < 4 => {
                Err("environment faces are square, at least 16 x 16".into())
            }
            _ => Ok(()),
        }
    }
}

/// The seven DRFs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DrfFile {
    pub drfs: [Option<ChainDrf>; DRFS],
}

impl DrfFile {
    pub fn get(&self, k: u8) -> Option<&ChainDrf> {
        self.drfs.get(usize::from(k)).and_then(Option::as_ref)
    }

    /// Every DRF valid, every link to a set DRF, offset maps linked to a detail map.
    pub fn validate(&self) -> Result<(), String> {
        for (k, d) in self.drfs.iter().enumerate() {
            let Some(d) = d else { continue };
            d.validate().map_err(|e| format!("drf {k}: {e}"))?;
            if let Some(l) = d.link {
                let Some(next) = self.get(l) else {
                    return Err(format!("drf {k}: link to drf {l}, which is not set"));
                };
                if d.kind == Kind::Offset && next.kind != Kind::Detail {
                    return Err(format!(
                        "drf {k}: offsets link to a detail map, not drf {l}"
                    ));
                }
            } else if d.kind == Kind::Offset {
                return Err(format!("drf {k}: offsets link to a detail map"));
            }
        }
        Ok(())
    }
}

/// Places maps in the banks: each level group of a map starts at a row boundary after the
/// last map's, so maps never share a row.
#[derive(Clone, Copy, Debug, Default)]
pub struct Placer {
    next: [u32; 2],
}

impl Placer {
    pub fn new() -> Placer {
        Placer::default()
    }

    /// Bases for a map of `2^w x 2^h`, or an error when the banks are full.
    pub fn place(&mut self, width_log2: u32, height_log2: u32) -> Result<(u32, u32), String> {
        let d = Drf::new(width_log2, height_log2, Border::Wrap);
        d.validate()?;
        let bases = (self.next[0], self.next[1]);
        for g in 0..2 {
            let end = self.next[g] + group_words(&d, g as u32);
            if end > bank_words(4 * g) {
                return Err(format!(
                    "map {}x{}: the banks are full",
                    1u32 << width_log2,
                    1u32 << height_log2
                ));
            }
            self.next[g] = end.next_multiple_of(ROW_WORDS);
        }
        Ok(bases)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texram::Config;

    #[test]
    fn maps_placed_one_after_the_other_never_share_a_row() {
        let mut p = Placer::new();
        let a = p.place(8, 8).unwrap();
        let b = p.place(4, 4).unwrap();
        assert_eq!(a, (0, 0));
        // 256x256: 16384 words at level 0 + 1024 + 64 + 4 + 1 in the even group.
        assert_eq!(b.0, (16384 + 1024 + 64 + 4 + 1u32).next_multiple_of(512));
        assert_eq!(b.0 % ROW_WORDS, 0);
        assert_eq!(b.1 % ROW_WORDS, 0);
        // The banks take one 1024 x 1024 map and nothing more.
        let mut full = Placer::new();
        assert!(full.place(10, 10).is_ok());
        assert!(full.place(0, 0).unwrap_err().contains("full"));
        // A map that ends exactly at a bank's last word fits; one word more does not; a map
        // with no odd levels adds nothing to a full odd group.
        let (even, odd) = (bank_words(0), bank_words(4));
        assert!(Placer {
            next: [even - 1, 0]
        }
        .place(0, 0)
        .is_ok());
        assert!(Placer { next: [even, 0] }.place(0, 0).is_err());
        assert!(Placer { next: [0, odd] }.place(0, 0).is_ok());
        assert!(Placer { next: [0, odd] }.place(1, 1).is_err());
    }

    #[test]
    fn drfs_are_checked() {
        let d = Drf::new(8, 8, Border::Tile(4));
        assert!(ChainDrf::new(Kind::Detail, d).validate().is_ok());
        for (w, h, ok) in [(9, 8, false), (8, 9, false), (8, 8, true), (3, 8, true)] {
            let d = ChainDrf::new(Kind::Detail, Drf::new(w, h, Border::Wrap));
            assert_eq!(d.validate().is_ok(), ok, "detail {w} {h}");
        }
        // Faces: square, 16 x 16 the smallest.
        for (w, h, ok) in [(4, 4, true), (3, 3, false), (5, 4, false), (10, 10, true)] {
            let e = ChainDrf::new(Kind::Environment, Drf::new(w, h, Border::Clamp));
            assert_eq!(e.validate().is_ok(), ok, "faces {w} {h}");
        }
        let mut t = ChainDrf::new(Kind::Texture, d);
        t.new_coords = true;
        assert!(t.validate().unwrap_err().contains("new_coords"));
        let mut e = ChainDrf::new(Kind::Environment, Drf::new(3, 3, Border::Clamp));
        assert!(e.validate().unwrap_err().contains("16 x 16"));
        e.map = Drf::new(4, 4, Border::Clamp);
        e.link = Some(7);
        assert!(e.validate().unwrap_err().contains("link 7"));
        e.link = Some(6);
        assert_eq!(e.validate(), Ok(()));
        // One 8-bit component: every other layout refused.
        for config in [Config::Index, Config::Planar, Config::Literal] {
            let mut c = ChainDrf::new(Kind::Texture, d);
            c.map.config = config;
            let err = c.validate().unwrap_err();
            assert!(err.contains("one 8-bit component"), "{config:?}: {err}");
        }
        // A detail map needs computed coordinates, an environment map may have either, an
        // offset map has none.
        let mut dm = ChainDrf::new(Kind::Detail, d);
        dm.new_coords = false;
        assert!(dm.validate().unwrap_err().contains("from the offsets"));
        e.new_coords = false;
        assert_eq!(e.validate(), Ok(()));
        let mut o = ChainDrf::new(Kind::Offset, d);
        assert_eq!(o.validate(), Ok(()));
        o.new_coords = true;
        assert!(o.validate().unwrap_err().contains("offset map is read at"));
        let mut f = DrfFile::default();
        f.drfs[0] = Some(ChainDrf {
            link: Some(3),
            ..ChainDrf::new(Kind::Texture, d)
        });
        assert!(f.validate().unwrap_err().contains("not set"));
        // Offsets end in a detail map: unlinked, or linked to anything else, refused.
        f.drfs[3] = Some(ChainDrf::new(Kind::Offset, d));
        assert_eq!(
            f.validate().unwrap_err(),
            "drf 3: offsets link to a detail map"
        );
        f.drfs[3].as_mut().unwrap().link = Some(4);
        f.drfs[4] = Some(ChainDrf::new(Kind::Texture, d));
        let err = f.validate().unwrap_err();
        assert!(
            err.contains("drf 3: offsets link to a detail map, not drf 4"),
            "{err}"
        );
        f.drfs[4] = Some(ChainDrf::new(Kind::Detail, d));
        assert_eq!(f.validate(), Ok(()));
        for k in Kind::ALL {
            assert_eq!(Kind::parse(k.name()), Some(k));
        }
        for m in [DetailMode::Multiply, DetailMode::AddSigned] {
            assert_eq!(DetailMode::parse(m.name()), Some(m));
        }
    }
}
