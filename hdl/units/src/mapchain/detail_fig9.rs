//! Detail maps (section 9, Figs 9a and 9b): the arithmetic of the detail path, units 902-914.
//!
//! Below level 0 of a texture, lambda < 0, each level-0 texel owns a 16 x 16 tile of a
//! detail map of at most 256 x 256 texels (levels -4 .. -1 of the texture are the detail
//! map's levels 0 .. 3). The tile's origin is read from two 8-bit offset maps 902 (u and v)
//! at the pixel's level-0 texel, nearest neighbour (access 904); the detail colour is the
//! trilinear 914 of the detail map 906 in that tile (access 908); the texture map 910 is read
//! as a third step when -1 < lambda < 0 or when the detail colour modulates the texel; the
//! step 912 combines them. The document's text stops at "texture map 910 and": the
//! combination is \[C\].
//!
//! # Arithmetic (\[C\], all exact on the raw sQ12.8 / sQ5.8 values)
//! * Offset texel: `(floor u, floor v)`, read at its centre, lambda 0 (weights 0: the texel
//!   itself, exactly).
//! * Detail coordinate (the detail map's level-0 units): `o + frac(u) * 16`, raw
//!   `o * 256 + frac_raw(u) * 16`: u's 8 fraction bits give the detail map 4 (a level -4
//!   texel in 16 steps); wrapped inside the tile by the detail DRF's `tile:4` border (or
//!   continued into the map with any other border).
//! * Detail lambda: `max(lambda, -4) + 4`, and `3` (level -1, bilinear) for `-1 < lambda < 0`.
//! * Step 912: `X = D` (replace), `T . D` (multiply, 820's product) or `T + D - 128` held to
//!   0 ..= 255 (add-signed); for `-1 < lambda < 0` then `(X (256 - f) + T f + 128) >> 8` with
//!   `f = (lambda + 1) * 256`, one rounding half up: continuous at -1 (f = 0 gives X) and
//!   reaching T at 0.
//!
//! | value | format |
//! |---|---|
//! | offsets `ou`, `ov` | u8 (level -4 texels) |
//! | detail u, v | sQ12.8 in the detail map's level 0 (4 fraction bits used) |
//! | detail lambda | sQ5.8, 0 ..= 3 |
//! | D, T, result | u8 |

use super::drf_812::DetailMode;
use crate::texram::output_820::mul255;
use crate::texram::FRAC;

/// The detail path's lambdas: at most 0 raw is level 0 of the texture.
const ONE: i32 = 1 << FRAC;

/// Where the offset maps are read (904): the centre of the pixel's level-0 texel.
pub fn offset_point(c: i32) -> i32 {
    (c & !(ONE - 1)) | (ONE / 2)
}

/// The detail map coordinate (908) of pixel coordinate `c` in the tile at offset `o`.
pub fn detail_coord(o: u8, c: i32) -> i32 {
    (i32::from(o) << FRAC) + ((c & (ONE - 1)) << 4)
}

/// The detail map's lambda for the texture's `lambda` (< 0).
pub fn detail_lambda(lambda: i32) -> i32 {
    lambda.clamp(-4 * ONE, -ONE) + 4 * ONE
}

/// Whether the texel T below the detail is read (the third step).
pub fn needs_texel(mode: DetailMode, lambda: i32) -> bool {
    mode != DetailMode::Replace || lambda > -ONE
}

/// Step 912: detail colour `d` with texel `t` (only read when [`needs_texel`]) at `lambda`.
pub fn step_912(mode: DetailMode, lambda: i32, d: u8, t: u8) -> u8 {
    let x = match mode {
        DetailMode::Replace => d,
        DetailMode::Multiply => mul255(t, d),
        DetailMode::AddSigned => (i32::from(t) + i32::from(d) - 128).clamp(0, 255) as u8,
    };
    if lambda <= -ONE {
        return x;
    }
    let f = (lambda + ONE) as u32;
    ((u32::from(x) * (256 - f) + u32::from(t) * f + 128) >> 8) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_are_read_at_the_texel_centre() {
        assert_eq!(offset_point(5 * ONE + 3), 5 * ONE + 128);
        assert_eq!(offset_point(5 * ONE + 255), 5 * ONE + 128);
        // Negative coordinates floor.
        assert_eq!(offset_point(-1), -ONE + 128);
    }

    #[test]
    fn the_tile_spans_sixteen_detail_texels_per_texture_texel() {
        assert_eq!(detail_coord(32, 7 * ONE), 32 * ONE);
        assert_eq!(detail_coord(32, 7 * ONE + 128), 40 * ONE);
        assert_eq!(detail_coord(32, 7 * ONE + 255), 32 * ONE + 255 * 16);
        assert_eq!(detail_coord(255, -1), 255 * ONE + 255 * 16);
    }

    #[test]
    fn detail_lambda_spans_the_four_levels() {
        assert_eq!(detail_lambda(-4 * ONE), 0);
        assert_eq!(detail_lambda(-3 * ONE - 128), 128);
        assert_eq!(detail_lambda(-ONE), 3 * ONE);
        assert_eq!(detail_lambda(-1), 3 * ONE);
    }

    /// Exhaustive over D, T: continuous at -1, the texel at the top, modes as defined.
    #[test]
    fn step_912_is_continuous_and_reaches_the_texel() {
        for mode in [
            DetailMode::Replace,
            DetailMode::Multiply,
            DetailMode::AddSigned,
        ] {
            for d in 0..=255u8 {
                for t in 0..=255u8 {
                    let x = step_912(mode, -ONE, d, t);
                    let want = match mode {
                        DetailMode::Replace => d,
                        DetailMode::Multiply => {
                            ((u32::from(t) * u32::from(d) * 2 + 255) / 510) as u8
                        }
                        DetailMode::AddSigned => {
                            (i32::from(t) + i32::from(d) - 128).clamp(0, 255) as u8
                        }
                    };
                    assert_eq!(x, want, "{mode:?} {d} {t}");
                    // Just above -1 the fade starts from X; just below 0 it is within a
                    // step of T.
                    assert!(step_912(mode, -ONE + 1, d, t).abs_diff(x) <= 1);
                    assert!(step_912(mode, -1, d, t).abs_diff(t) <= 1);
                    assert!(step_912(mode, -4 * ONE, d, t) == x);
                }
            }
        }
        assert!(!needs_texel(DetailMode::Replace, -ONE));
        assert!(needs_texel(DetailMode::Replace, -ONE + 1));
        assert!(needs_texel(DetailMode::Multiply, -4 * ONE));
    }
}
