//! The bit widths of the FIG. 7 pipeline an architect sets on the command line.

use clap::Args;
use units::bump::params::{BumpParams, HeightTexel, RsqrtParams};

/// Bit widths of the FIG. 7 pipeline.
#[derive(Args, Clone, Debug)]
pub struct Widths {
    /// Blend-factor fraction bits F (4..=16).
    #[arg(long = "blend-bits", default_value_t = 8)]
    pub blend_bits: u32,
    /// Height texel bits: 8 (uQ6.2) or 4 (uQ3.1).
    #[arg(long, default_value_t = 8)]
    pub texel_bits: u32,
    /// Inverse-square-root table index bits (3..=14).
    #[arg(long = "rsqrt-table-bits", default_value_t = 8)]
    pub table_bits: u32,
    /// Newton-Raphson iterations after the table (0..=3).
    #[arg(long = "rsqrt-iterations", default_value_t = 1)]
    pub iterations: u32,
    /// Fraction bits of the normal components (8..=24).
    #[arg(long, default_value_t = 16)]
    pub out_frac: u32,
    /// Fraction bits of the tangents (8..=24).
    #[arg(long, default_value_t = 16)]
    pub tangent_frac: u32,
}

impl Default for Widths {
    fn default() -> Self {
        let p = BumpParams::default();
        Widths {
            blend_bits: p.blend_bits,
            texel_bits: 8,
            table_bits: p.rsqrt.table_bits,
            iterations: p.rsqrt.iterations,
            out_frac: p.out_frac,
            tangent_frac: p.tangent_frac,
        }
    }
}

impl Widths {
    /// The pipeline parameters of these widths, validated.
    pub fn params(&self) -> Result<BumpParams, String> {
        let height = match self.texel_bits {
            8 => HeightTexel::Bits8,
            4 => HeightTexel::Bits4,
            b => return Err(format!("--texel-bits {b}: 8 or 4")),
        };
        let p = BumpParams {
            blend_bits: self.blend_bits,
            pos_frac: self.blend_bits.max(16),
            height,
            tangent_frac: self.tangent_frac,
            rsqrt: RsqrtParams {
                table_bits: self.table_bits,
                iterations: self.iterations,
                ..RsqrtParams::default()
            },
            out_frac: self.out_frac,
            ..BumpParams::default()
        };
        // A refusal names the option, not the parameter it sets.
        p.validate().map_err(|e| {
            match OPTIONS
                .iter()
                .find(|(f, _)| e.starts_with(&format!("{f} ")))
            {
                Some((f, o)) => format!("{o}{}", &e[f.len()..]),
                None => e,
            }
        })?;
        Ok(p)
    }
}

/// The parameters these options set, as [`BumpParams::validate`] names them.
const OPTIONS: [(&str, &str); 5] = [
    ("blend_bits", "--blend-bits"),
    ("rsqrt.table_bits", "--rsqrt-table-bits"),
    ("rsqrt.iterations", "--rsqrt-iterations"),
    ("out_frac", "--out-frac"),
    ("tangent_frac", "--tangent-frac"),
];
