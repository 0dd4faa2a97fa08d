//! Parameters of the FIG. 7 normal pipeline (US 2004/0207631), shared by its units.
//!
//! Every width an architect might want to change is here; [`BumpParams::validate`] checks
//! them, and every unit derives its formats from them once, at construction.

use crate::fx::{Format, Overflow, Quant};
use std::fmt;
use std::str::FromStr;

/// Which height function the pipeline evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Filter {
    /// Bi-quadratic B-spline via the blend-factor adjust unit 153 (para. 0058-0061).
    BSpline,
    /// The same surface via Bezier control points made in a modified replicate unit 152
    /// (Equation 1, para. 0083); unit 153 bypassed. Gives bit-identical normals.
    Bezier,
    /// Blinn's height function (para. 0031, 0085): unit 153 bypassed, three bilinear units,
    /// tangents G-R and B-R.
    Blinn,
}

/// What the texel fetch unit 151 does with coordinates outside the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Border {
    /// Repeat: `i mod size`.
    Wrap,
    /// Clamp to the edge texel.
    Clamp,
    /// Mirrored repeat with period `2 * size` (the edge texel is repeated once).
    Mirror,
    /// Outside texels read as this raw height value.
    Constant(u8),
}

parse_names!(Filter, "bspline" => Filter::BSpline, "bezier" => Filter::Bezier, "blinn" => Filter::Blinn);

impl FromStr for Border {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "wrap" => Ok(Border::Wrap),
            "clamp" => Ok(Border::Clamp),
            "mirror" => Ok(Border::Mirror),
            _ => match s.strip_prefix("constant") {
                Some("") => Ok(Border::Constant(0)),
                Some(v) => v
                    .strip_prefix(':')
                    .and_then(|v| v.parse().ok())
                    .map(Border::Constant)
                    .ok_or_else(|| format!("bad border '{s}' (constant:N with N in 0..=255)")),
                None => Err(format!(
                    "unknown border '{s}' (one of wrap, clamp, mirror, constant[:N])"
                )),
            },
        }
    }
}

impl fmt::Display for Filter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Filter::BSpline => "bspline",
            Filter::Bezier => "bezier",
            Filter::Blinn => "blinn",
        })
    }
}

impl fmt::Display for Border {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Border::Wrap => f.write_str("wrap"),
            Border::Clamp => f.write_str("clamp"),
            Border::Mirror => f.write_str("mirror"),
            Border::Constant(v) => write!(f, "constant:{v}"),
        }
    }
}

/// Height texel format (para. 0050): `bits` per texel, a quarter of them fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HeightTexel {
    /// 8 bits, 2 fraction bits: `uQ6.2` (the default).
    Bits8,
    /// 4 bits, 1 fraction bit: `uQ3.1`.
    Bits4,
}

impl HeightTexel {
    pub fn format(self) -> Format {
        match self {
            HeightTexel::Bits8 => Format::unsigned(8, 2),
            HeightTexel::Bits4 => Format::unsigned(4, 1),
        }
    }
}

/// The inverse-square-root unit inside normal unit 156.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RsqrtParams {
    /// Table index bits (one selects [1,2) or [2,4), the rest are the mantissa's leading
    /// fraction bits). 3..=14.
    pub table_bits: u32,
    /// Newton-Raphson iterations after the table, 0..=3 (one pipeline stage each).
    pub iterations: u32,
    /// Fraction bits of the mantissa fed to the unit (`uQ2.M`), 8..=40.
    pub mant_frac: u32,
    /// Fraction bits of the table entries and of every iterate (`uQ1.Y`), 8..=40.
    pub y_frac: u32,
}

impl Default for RsqrtParams {
    fn default() -> Self {
        RsqrtParams {
            table_bits: 8,
            iterations: 1,
            mant_frac: 22,
            y_frac: 24,
        }
    }
}

/// Every parameter of the pipeline. `Default` gives the documented defaults.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BumpParams {
    /// Blend-factor fraction bits F (sub-texel precision), 4..=16. Default 8 (the D3D11 minimum).
    pub blend_bits: u32,
    /// Integer bits of the signed position `sQ<pos_int>.<pos_frac>`, 4..=24. Default 16.
    pub pos_int: u32,
    /// Fraction bits of the position, `blend_bits..=24`; the address unit truncates (floors)
    /// the bits below `blend_bits`. Default = `blend_bits`.
    pub pos_frac: u32,
    pub height: HeightTexel,
    /// Fraction bits kept at the bilinear units' outputs; `None` keeps them all (exact).
    pub bilinear_frac: Option<u32>,
    /// Fraction bits of the tangents (and the interpolated height) out of unit 155, 8..=24.
    /// Default 16.
    pub tangent_frac: u32,
    /// Integer and fraction bits of the unsigned height-scale factor (para. 0082).
    /// Default `uQ8.8`.
    pub scale_int: u32,
    pub scale_frac: u32,
    pub rsqrt: RsqrtParams,
    /// Fraction bits of the normal's components, `sQ2.<out_frac>`, 8..=24. Default 16.
    pub out_frac: u32,
    pub filter: Filter,
    pub border: Border,
    /// Trilinear normals from two MIP levels (para. 0081).
    pub trilinear: bool,
}

impl Default for BumpParams {
    fn default() -> Self {
        BumpParams {
            blend_bits: 8,
            pos_int: 16,
            pos_frac: 8,
            height: HeightTexel::Bits8,
            bilinear_frac: None,
            tangent_frac: 16,
            scale_int: 8,
            scale_frac: 8,
            rsqrt: RsqrtParams::default(),
            out_frac: 16,
            filter: Filter::BSpline,
            border: Border::Wrap,
            trilinear: false,
        }
    }
}

/// Rounding of every narrowing in the pipeline (tangents, mantissa aside, normal): nearest,
/// ties to even. The mantissa fed to the rsqrt unit is truncated (documented there).
pub const ROUND: Quant = Quant::RoundHalfEven;
/// Overflow of every narrowing: saturate.
pub const SAT: Overflow = Overflow::Saturate;

impl BumpParams {
    /// Checks every parameter's range.
    pub fn validate(&self) -> Result<(), String> {
        let chk = |name: &str, v: u32, lo: u32, hi: u32| {
            if (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(format!("{name} {v} outside {lo}..={hi}"))
            }
        };
        chk("blend_bits", self.blend_bits, 4, 16)?;
        chk("pos_int", self.pos_int, 4, 24)?;
        chk("pos_frac", self.pos_frac, self.blend_bits, 24)?;
        if let Some(b) = self.bilinear_frac {
            chk("bilinear_frac", b, self.replicate_fmt().frac() as u32, 40)?;
        }
        chk("tangent_frac", self.tangent_frac, 8, 24)?;
        chk("scale_int", self.scale_int, 1, 12)?;
        chk("scale_frac", self.scale_frac, 0, 16)?;
        chk("rsqrt.table_bits", self.rsqrt.table_bits, 3, 14)?;
        chk("rsqrt.iterations", self.rsqrt.iterations, 0, 3)?;
        chk("rsqrt.mant_frac", self.rsqrt.mant_frac, 8, 40)?;
        chk("rsqrt.y_frac", self.rsqrt.y_frac, 8, 40)?;
        chk("out_frac", self.out_frac, 8, 24)?;
        if let Border::Constant(c) = self.border {
            let t = self.texel_fmt();
            if !t.contains_raw(i128::from(c)) {
                return Err(format!(
                    "border constant:{c} does not fit the {}-bit texels (0..={})",
                    t.width(),
                    t.max_raw()
                ));
            }
        }
        Ok(())
    }

    /// Position `sQ<pos_int>.<pos_frac>`.
    pub fn pos_fmt(&self) -> Format {
        Format::signed(self.pos_int + self.pos_frac, self.pos_frac as i32)
    }
    /// Integer texel coordinate out of the address unit: one bit more than the position's
    /// integer part (the colour-mode half-texel subtraction can reach one below its minimum).
    pub fn coord_fmt(&self) -> Format {
        Format::sint(self.pos_int + 1)
    }
    /// Blend factor `uQ0.F`.
    pub fn blend_fmt(&self) -> Format {
        Format::unsigned(self.blend_bits, self.blend_bits as i32)
    }
    /// Adjusted blend factor `uQ0.(F+1)`.
    pub fn adj_fmt(&self) -> Format {
        Format::unsigned(self.blend_bits + 1, self.blend_bits as i32 + 1)
    }
    /// Height texel.
    pub fn texel_fmt(&self) -> Format {
        self.height.format()
    }
    /// Replicate outputs: a height with two more fraction bits, room for the Bezier averages.
    pub fn replicate_fmt(&self) -> Format {
        let t = self.texel_fmt();
        Format::unsigned(t.width() + 2, t.frac() + 2)
    }
    /// Exact bilinear result: replicate format with two `F+1`-bit blends' worth of fraction.
    pub fn bilinear_exact_frac(&self) -> u32 {
        self.replicate_fmt().frac() as u32 + 2 * (self.blend_bits + 1)
    }
    /// Bilinear unit output (unsigned, within the range of the texels).
    pub fn bilinear_fmt(&self) -> Format {
        let f = self.bilinear_frac.unwrap_or(self.bilinear_exact_frac());
        Format::unsigned(self.texel_fmt().int_bits() as u32 + f, f as i32)
    }
    /// Height-scale factor `uQ<scale_int>.<scale_frac>`.
    pub fn scale_fmt(&self) -> Format {
        Format::unsigned(self.scale_int + self.scale_frac, self.scale_frac as i32)
    }
    /// Tangent `dH/du`, `dH/dv` out of unit 155: signed, enough integer bits for the steepest
    /// B-spline slope (one texel's full range per texel, twice that for the trilinear blend
    /// headroom) times the largest scale.
    pub fn tangent_fmt(&self) -> Format {
        let int = self.texel_fmt().int_bits() as u32 + self.scale_int + 2;
        Format::signed(int + self.tangent_frac, self.tangent_frac as i32)
    }
    /// Interpolated height out of unit 155 (para. 0084), scaled.
    pub fn height_out_fmt(&self) -> Format {
        let int = self.texel_fmt().int_bits() as u32 + self.scale_int;
        Format::unsigned(int + self.tangent_frac, self.tangent_frac as i32)
    }
    /// Normal component `sQ2.<out_frac>`.
    pub fn normal_fmt(&self) -> Format {
        Format::signed(2 + self.out_frac, self.out_frac as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every derived format against the notation its doc comment gives.
    fn formats(p: &BumpParams) -> Vec<String> {
        [
            p.pos_fmt(),
            p.coord_fmt(),
            p.blend_fmt(),
            p.adj_fmt(),
            p.texel_fmt(),
            p.replicate_fmt(),
            p.bilinear_fmt(),
            p.scale_fmt(),
            p.tangent_fmt(),
            p.height_out_fmt(),
            p.normal_fmt(),
        ]
        .iter()
        .map(|f| f.to_string())
        .collect()
    }

    #[test]
    fn the_default_format_table() {
        let p = BumpParams::default();
        assert_eq!(p.bilinear_exact_frac(), 4 + 2 * 9);
        let want = [
            "sQ16.8", "s17", "uQ0.8", "uQ0.9", "uQ6.2", "uQ6.4", "uQ6.22", "uQ8.8", "sQ16.16",
            "uQ14.16", "sQ2.16",
        ];
        assert_eq!(formats(&p), want);
    }

    #[test]
    fn the_format_table_follows_every_width_parameter() {
        let p = BumpParams {
            blend_bits: 4,
            pos_int: 10,
            pos_frac: 6,
            height: HeightTexel::Bits4,
            bilinear_frac: Some(5),
            tangent_frac: 12,
            scale_int: 3,
            scale_frac: 5,
            out_frac: 10,
            ..BumpParams::default()
        };
        assert_eq!(p.bilinear_exact_frac(), 3 + 2 * 5);
        // Tangent: texel 3 + scale 3 + 2 headroom integer bits; height: 3 + 3.
        let want = [
            "sQ10.6", "s11", "uQ0.4", "uQ0.5", "uQ3.1", "uQ3.3", "uQ3.5", "uQ3.5", "sQ8.12",
            "uQ6.12", "sQ2.10",
        ];
        assert_eq!(formats(&p), want);
    }

    #[test]
    fn filter_and_border_names_read_back() {
        for f in [Filter::BSpline, Filter::Bezier, Filter::Blinn] {
            assert_eq!(f.to_string().parse::<Filter>(), Ok(f));
        }
        let borders = [
            Border::Wrap,
            Border::Clamp,
            Border::Mirror,
            Border::Constant(0),
            Border::Constant(255),
        ];
        for b in borders {
            assert_eq!(b.to_string().parse::<Border>(), Ok(b));
        }
        assert_eq!("constant".parse::<Border>(), Ok(Border::Constant(0)));
        assert_eq!("constant:7".parse::<Border>(), Ok(Border::Constant(7)));
        for bad in ["constant:256", "constant7", "constant:", "repeat", ""] {
            assert!(bad.parse::<Border>().is_err(), "{bad}");
        }
        assert!("gauss".parse::<Filter>().unwrap_err().contains("bspline"));
    }

    /// Each range at both ends: its bounds pass, one beyond fails naming the parameter.
    #[test]
    fn validate_takes_each_range_at_both_ends() {
        type Set = fn(&mut BumpParams, u32);
        let ranges: [(&str, Set, u32, u32); 11] = [
            (
                "blend_bits",
                |p, v| (p.blend_bits, p.pos_frac) = (v, v.max(8)),
                4,
                16,
            ),
            ("pos_int", |p, v| p.pos_int = v, 4, 24),
            ("pos_frac", |p, v| p.pos_frac = v, 8, 24),
            ("tangent_frac", |p, v| p.tangent_frac = v, 8, 24),
            ("scale_int", |p, v| p.scale_int = v, 1, 12),
            ("scale_frac", |p, v| p.scale_frac = v, 0, 16),
            ("rsqrt.table_bits", |p, v| p.rsqrt.table_bits = v, 3, 14),
            ("rsqrt.iterations", |p, v| p.rsqrt.iterations = v, 0, 3),
            ("rsqrt.mant_frac", |p, v| p.rsqrt.mant_frac = v, 8, 40),
            ("rsqrt.y_frac", |p, v| p.rsqrt.y_frac = v, 8, 40),
            ("out_frac", |p, v| p.out_frac = v, 8, 24),
        ];
        let with = |set: Set, v: u32| {
            let mut p = BumpParams::default();
            set(&mut p, v);
            p.validate()
        };
        assert_eq!(BumpParams::default().validate(), Ok(()));
        for (name, set, lo, hi) in ranges {
            assert_eq!(with(set, lo), Ok(()), "{name} {lo}");
            assert_eq!(with(set, hi), Ok(()), "{name} {hi}");
            let e = with(set, hi + 1).unwrap_err();
            assert_eq!(e, format!("{name} {} outside {lo}..={hi}", hi + 1));
            if lo > 0 {
                assert!(with(set, lo - 1).unwrap_err().starts_with(name), "{name}");
            }
        }
        // pos_frac's floor is blend_bits; bilinear_frac's the replicate format's fraction (4).
        let p = BumpParams {
            blend_bits: 10,
            pos_frac: 9,
            ..BumpParams::default()
        };
        assert_eq!(p.validate().unwrap_err(), "pos_frac 9 outside 10..=24");
        for (b, ok) in [(3, false), (4, true), (40, true), (41, false)] {
            let p = BumpParams {
                bilinear_frac: Some(b),
                ..BumpParams::default()
            };
            assert_eq!(p.validate().is_ok(), ok, "bilinear_frac {b}");
        }
        // A border constant must fit the texels: 15 fits 4 bits, 16 does not.
        for (c, ok) in [(15, true), (16, false)] {
            let p = BumpParams {
                height: HeightTexel::Bits4,
                border: Border::Constant(c),
                ..BumpParams::default()
            };
            assert_eq!(p.validate().is_ok(), ok, "constant {c}");
        }
    }
}
