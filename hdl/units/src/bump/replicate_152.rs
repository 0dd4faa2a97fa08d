//! Replicate unit 152 of US 2004/0207631 (FIG. 7, para. 0056-0057), and its modified form
//! that converts the B-spline control points to Bezier points (Equation 1, para. 0083).
//!
//! The four overlapping 2x2 windows of the 3x3 grid go to the four bilinear units:
//! red `[a b; d e]`, green `[b c; e f]`, blue `[d e; g h]`, alpha `[e f; h k]`, each as
//! `[top-left, top-right, bottom-left, bottom-right]` (right = +u, down = +v).
//!
//! In Bezier mode the grid is first replaced by Equation 1's Bezier points:
//! `a' = (a+b+d+e)/4`, `b' = (b+e)/2`, `e' = e`, ... All are exact with two more fraction
//! bits, so every output has the format of a texel widened by two fraction bits
//! (`uQ6.4` for 8-bit texels). Purely combinational (wiring and adders): latency 0.

use crate::fx::Format;
use crate::kernel::{Module, Signal};

/// Indices into a..k of each window: red, green, blue, alpha.
pub const WINDOWS: [[usize; 4]; 4] = [[0, 1, 3, 4], [1, 2, 4, 5], [3, 4, 6, 7], [4, 5, 7, 8]];

const IN: [&str; 9] = ["a", "b", "c", "d", "e", "f", "g", "h", "k"];
const OUT: [[&str; 4]; 4] = [
    ["r00", "r10", "r01", "r11"],
    ["g00", "g10", "g01", "g11"],
    ["b00", "b10", "b01", "b11"],
    ["a00", "a10", "a01", "a11"],
];

/// The grid in units of the output format: `4 * p`, or Equation 1's Bezier points times 4.
#[inline]
pub fn control_points(mut h: [u64; 9], bezier: bool) -> [u64; 9] {
    if !bezier {
        for x in &mut h {
            *x <<= 2;
        }
        return h;
    }
    let [a, b, c, d, e, f, g, hh, k] = h;
    [
        a + b + d + e,
        2 * (b + e),
        b + c + e + f,
        2 * (d + e),
        4 * e,
        2 * (e + f),
        d + e + g + hh,
        2 * (e + hh),
        e + f + hh + k,
    ]
}

/// Replicate unit 152.
#[derive(Clone, Debug, Module)]
#[module(kind = "replicate_152")]
pub struct Replicate {
    #[instance]
    name: String,
    bezier: bool,
    /// The 3 x 3 height texels.
    #[input]
    pub h: [Signal; 9],
    /// Windows red, green, blue, alpha.
    #[output]
    pub w: [[Signal; 4]; 4],
}

impl Replicate {
    /// `texel`: the height texel format; `bezier`: Equation 1 mode.
    pub fn new(name: &str, texel: Format, bezier: bool) -> Replicate {
        let out = Format::unsigned(texel.width() + 2, texel.frac() + 2);
        Replicate {
            name: name.into(),
            bezier,
            h: IN.map(|n| Signal::new(n, texel)),
            w: OUT.map(|ws| ws.map(|n| Signal::new(n, out))),
        }
    }
}

impl Replicate {
    #[inline]
    /// The combinational unit: the four windows' control points from the nine texels.
    pub fn eval(&mut self) {
        let mut h = [0; 9];
        for (x, s) in h.iter_mut().zip(&self.h) {
            *x = s.bits();
        }
        let p = control_points(h, self.bezier);
        for (wi, idx) in WINDOWS.iter().enumerate() {
            for (k, &i) in idx.iter().enumerate() {
                self.w[wi][k].set_bits(p[i]);
            }
        }
    }
}
