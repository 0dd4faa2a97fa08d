//! Bi-quadratic colour filtering of para. 0087 (Fenney): the B-spline surface of the height
//! path applied to a colour texture, channel by channel: over the 3 x 3 texels around the
//! sample, the weights `B0 = (1 - t)^2 / 2`, `B1 = (1 + 2t - 2t^2) / 2`, `B2 = t^2 / 2` along
//! each axis, `t` the position inside the nearest texel (1/2 at its centre).
//!
//! # Arithmetic \[C\]
//! `t` truncated to 8 bits; the weights `2 B` as exact integers over 2^16 (`(256 - t)^2`,
//! `2^16 + 512 t - 2 t^2`, `t^2`, summing to 2^17); the channel's sum of texel times both
//! axes' weights exact (over 2^34), one rounding half up to u8. One register stage.
//!
//! | port | format |
//! |---|---|
//! | `u`, `v` | `sQ15.16` texel units, texel centres at k + 1/2 |
//! | `r`, `g`, `b` | u8 |

use crate::bump::params::Border;
use crate::bump::texel_fetch_151::border_index;
use crate::fx::{quantise, Format, Narrowing, Overflow, Quant};
use crate::kernel::{Module, Reg, Signal};

/// Position fraction bits.
pub const POS_FRAC: u32 = 16;

/// An RGB8 texture, row-major.
#[derive(Clone, Debug)]
pub struct ColourMap {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
    pub border: Border,
}

impl ColourMap {
    /// Texel `(x, y)`'s channels after the border.
    pub fn texel(&self, x: i64, y: i64) -> [u8; 3] {
        match (
            border_index(x, self.width, self.border),
            border_index(y, self.height, self.border),
        ) {
            (Some(i), Some(j)) => {
                let k = 3 * (j as usize * self.width as usize + i as usize);
                [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
            }
            _ => match self.border {
                Border::Constant(c) => [c; 3],
                _ => [0; 3],
            },
        }
    }
}

/// The three weights (times 2^17) of position fraction `t` (8 bits).
pub fn weights(t: i64) -> [i64; 3] {
    [(256 - t) * (256 - t), 65536 + 512 * t - 2 * t * t, t * t]
}

/// The nearest texel and `t` (8 bits, truncated) of coordinate `c` (raw sQ15.16).
pub fn axis(c: i64) -> (i64, i64) {
    (c >> POS_FRAC, (c >> (POS_FRAC - 8)) & 255)
}

/// The exact channel sums (over 2^34) at `(u, v)`.
pub fn sums(m: &ColourMap, u: i64, v: i64) -> [i64; 3] {
    let ((i, tu), (j, tv)) = (axis(u), axis(v));
    let (wu, wv) = (weights(tu), weights(tv));
    let mut s = [0i64; 3];
    for (dy, wy) in wv.iter().enumerate() {
        for (dx, wx) in wu.iter().enumerate() {
            let t = m.texel(i + dx as i64 - 1, j + dy as i64 - 1);
            for c in 0..3 {
                s[c] += i64::from(t[c]) * wx * wy;
            }
        }
    }
    s
}

/// The filtered colour at `(u, v)`.
pub fn filter(m: &ColourMap, u: i64, v: i64) -> [u8; 3] {
    sums(m, u, v).map(|x| {
        quantise(
            x.into(),
            SUM_FRAC,
            CHANNEL,
            Quant::RoundHalfUp,
            Overflow::Saturate,
        ) as u8
    })
}

/// A channel's format, u8.
const CHANNEL: Format = Format::uint(8);
/// Fraction bits of the exact sums: the weights' 17 on each axis.
const SUM_FRAC: i32 = 34;

/// A channel's one rounding, half up, held to `0 ..= 255` (an end no sum reaches).
fn channel_narrowing(name: &'static str) -> Narrowing {
    const INSIDE: &str =
        "the B-spline weights are non-negative and sum to one: a channel lies between its texels";
    Narrowing::new(name, CHANNEL, Quant::RoundHalfUp, Overflow::Saturate).never_overflows(INSIDE)
}

/// The unit.
#[derive(Module)]
#[module(kind = "biquadratic_0087")]
pub struct Biquadratic0087 {
    map: ColourMap,
    #[input]
    pub valid_in: Signal,
    #[input]
    pub u: Signal,
    #[input]
    pub v: Signal,
    #[reg]
    pub valid: Reg,
    #[reg]
    pub rgb: [Reg; 3],
    /// Each channel's one rounding.
    #[narrow]
    round: [Narrowing; 3],
}

impl Biquadratic0087 {
    pub fn new(map: ColourMap) -> Result<Biquadratic0087, String> {
        let n = 3 * map.width as usize * map.height as usize;
        if map.width == 0 || map.height == 0 || map.rgb.len() != n {
            return Err(format!(
                "colour map {}x{}: {} bytes",
                map.width,
                map.height,
                map.rgb.len()
            ));
        }
        let pos = Format::signed(32, POS_FRAC as i32);
        Ok(Biquadratic0087 {
            map,
            valid_in: Signal::bit("valid_in"),
            u: Signal::new("u", pos),
            v: Signal::new("v", pos),
            valid: Reg::new("valid", Format::uint(1)),
            rgb: ["r", "g", "b"].map(|x| Reg::new(x, CHANNEL)),
            round: ["r", "g", "b"].map(channel_narrowing),
        })
    }
}

impl Biquadratic0087 {
    /// The filtered colour of a valid query, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.valid_in.is_high();
        self.valid.set_next_bool(valid);
        if valid {
            let sums = sums(&self.map, self.u.raw(), self.v.raw());
            let channels = self.rgb.iter_mut().zip(&mut self.round);
            for ((r, n), x) in channels.zip(sums) {
                r.set_next_raw(n.raw(x.into(), SUM_FRAC) as i64);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Outside the map: the border's texel, or the constant in every channel.
    #[test]
    fn borders_of_a_colour_map() {
        let m = |border| ColourMap {
            width: 2,
            height: 1,
            rgb: vec![1, 2, 3, 4, 5, 6],
            border,
        };
        assert_eq!(m(Border::Constant(9)).texel(-1, 0), [9; 3]);
        assert_eq!(m(Border::Constant(9)).texel(1, 0), [4, 5, 6]);
        assert_eq!(m(Border::Clamp).texel(5, -3), [4, 5, 6]);
        assert_eq!(m(Border::Wrap).texel(2, 0), [1, 2, 3]);
    }

    #[test]
    fn weights_sum_to_one_and_give_a_6_1_at_the_centre() {
        for t in 0..256 {
            assert_eq!(weights(t).iter().sum::<i64>(), 1 << 17);
        }
        // t = 1/2: (1, 6, 1)/8.
        assert_eq!(weights(128), [16384, 98304, 16384]);
    }
}
