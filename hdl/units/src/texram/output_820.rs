//! The output and combination stage 820 (section 6, eq. 5): the texture colour T combined
//! with the interpolated illumination, `C_d = (I_d | k_T | 1) . T`, where `|` is the DRF's
//! choice of one of the three and `.` the multiplication of two 8-bit values that stand for
//! 0 ..= 1. \[C\] `x . y = round(x y / 255)`, exactly, half up, with no division:
//! `t = x y + 128; (t + (t >> 8)) >> 8` (so 255 is the neutral element: `255 . y = y`).

use crate::fx::Format;
use crate::kernel::{Module, Reg};

/// What eq. 5 multiplies the texture colour by (a DRF field).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Modulate {
    /// The interpolated diffuse illumination `I_d` from the rasterizer.
    Illumination,
    /// The DRF's constant `k_T`.
    Constant(u8),
    /// 1: the texture colour alone.
    #[default]
    One,
}

/// `round(x y / 255)`, exact for all 8-bit x and y.
#[inline]
pub fn mul255(x: u8, y: u8) -> u8 {
    let t = u32::from(x) * u32::from(y) + 128;
    ((t + (t >> 8)) >> 8) as u8
}

/// Eq. 5 for one component: `(I_d | k_T | 1) . T`.
pub fn combine(m: Modulate, illumination: u8, texture: u8) -> u8 {
    let factor = match m {
        Modulate::Illumination => illumination,
        Modulate::Constant(k) => k,
        Modulate::One => 255,
    };
    mul255(factor, texture)
}

/// Eq. 5 on a result: R, G and B multiplied as `m` says by the illumination's (R, G, B) or
/// the constant; alpha, \[C\], the texture's.
pub fn shade(m: Modulate, illumination: [u8; 4], texture: [u8; 4]) -> [u8; 4] {
    let mut out = texture;
    for c in 0..3 {
        out[c] = combine(m, illumination[c], texture[c]);
    }
    out
}

/// `a + b` held to 255: the sums of eqs 6 and 7 saturate \[C\].
#[inline]
fn add_sat(a: u8, b: u8) -> u8 {
    a.saturating_add(b)
}

/// Eq. 6, environment mapping: `C = (C_d | I_d) + k_s . E` on R, G and B, `k_s` a DRF
/// register, `base` the DRF's choice of the shaded texture colour or the illumination; alpha,
/// \[C\], the base's.
pub fn environment(base: [u8; 4], ks: u8, env: [u8; 4]) -> [u8; 4] {
    let mut out = base;
    for c in 0..3 {
        out[c] = add_sat(base[c], mul255(ks, env[c]));
    }
    out
}

/// Eq. 7, reflectance mapping: `C = (C_d | I_d) + R . (E | I_s)` on R, G and B, `R` the
/// reflectance map's colour (the seed's `C_c` read as `C_d`, as in eq. 6), `light` the
/// environment colour or the external specular term; alpha the base's.
pub fn reflectance(base: [u8; 4], r: [u8; 4], light: [u8; 4]) -> [u8; 4] {
    let mut out = base;
    for c in 0..3 {
        out[c] = add_sat(base[c], mul255(r[c], light[c]));
    }
    out
}

/// The output registers of the chip: `out_valid` one cycle with the finished colour after
/// eq. 5 (`out_value` its top byte, `out_rgba` R, G, B, alpha from the top byte down), the
/// eight texels (texel t in bits `8t..8t+8`), whether the access faulted, and 818's exact sum
/// before its rounding (luminance: `value * 2^24`, for the footprint accumulator).
#[derive(Clone, Debug, Module)]
#[module(kind = "output_820")]
pub struct Output820 {
    #[reg]
    pub out_valid: Reg,
    #[reg]
    pub out_value: Reg,
    #[reg]
    pub out_rgba: Reg,
    #[reg]
    pub out_texels: Reg,
    #[reg]
    pub out_fault: Reg,
    #[reg]
    pub out_sum: Reg,
}

impl Default for Output820 {
    fn default() -> Self {
        Output820::new()
    }
}

impl Output820 {
    pub fn new() -> Output820 {
        let u = |name, bits| Reg::new(name, Format::uint(bits));
        Output820 {
            out_valid: u("out_valid", 1),
            out_value: u("out_value", 8),
            out_rgba: u("out_rgba", 32),
            out_texels: u("out_texels", 64),
            out_fault: u("out_fault", 1),
            out_sum: Reg::new("out_sum", Format::unsigned(32, 24)),
        }
    }

    /// No result unless one finishes this cycle.
    pub fn eval(&mut self) {
        self.out_valid.set_next_bool(false);
    }

    /// A request finished: eq. 5 on its colour `rgba` with the illumination `illum` (R top
    /// byte), out at the edge with its texels, fault and exact sum.
    pub fn finish(
        &mut self,
        m: Modulate,
        illum: u32,
        rgba: u32,
        texels: [u8; 8],
        fault: bool,
        sum: u64,
    ) {
        let rgba = u32::from_be_bytes(shade(m, illum.to_be_bytes(), rgba.to_be_bytes()));
        self.out_valid.set_next_bool(true);
        self.out_value.set_next_bits(u64::from(rgba >> 24));
        self.out_rgba.set_next_bits(u64::from(rgba));
        self.out_texels.set_next_bits(u64::from_le_bytes(texels));
        self.out_fault.set_next_bool(fault);
        self.out_sum.set_next_bits(sum);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul255_rounds_the_exact_quotient_half_up_for_every_pair() {
        for x in 0..=255u32 {
            for y in 0..=255u32 {
                // round(x y / 255) half up, as integers: floor((2 x y + 255) / 510).
                let want = (2 * x * y + 255) / 510;
                assert_eq!(u32::from(mul255(x as u8, y as u8)), want, "{x} . {y}");
            }
        }
    }

    #[test]
    fn one_is_neutral_and_the_choices_select() {
        for t in 0..=255u8 {
            assert_eq!(combine(Modulate::One, 0, t), t);
            assert_eq!(combine(Modulate::Constant(255), 0, t), t);
            assert_eq!(combine(Modulate::Illumination, 0, t), 0);
            assert_eq!(combine(Modulate::Illumination, 255, t), t);
        }
        assert_eq!(combine(Modulate::Constant(128), 0, 200), 100);
    }

    /// A constant reflectance k gives exactly eq. 6 with k_s = k; sums saturate; 0 adds
    /// nothing; alpha is the base's.
    #[test]
    fn a_constant_reflectance_is_environment_mapping() {
        let base = [10, 200, 255, 77];
        let env = [255, 100, 3, 9];
        for k in [0u8, 1, 128, 254, 255] {
            assert_eq!(reflectance(base, [k; 4], env), environment(base, k, env));
        }
        assert_eq!(environment(base, 0, env), base);
        assert_eq!(environment(base, 255, env), [255, 255, 255, 77]);
        assert_eq!(environment([0; 4], 128, [200; 4]), [100, 100, 100, 0]);
    }
}
