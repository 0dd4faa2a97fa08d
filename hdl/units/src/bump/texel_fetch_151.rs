//! Texel fetch unit 151 of US 2004/0207631 (FIG. 7, para. 0053): the 3x3 grid of height
//! texels around `(Ui, Vj)`, with a border mode for coordinates outside the map.
//!
//! ```text
//! a = (Ui-1, Vj-1)  b = (Ui, Vj-1)  c = (Ui+1, Vj-1)
//! d = (Ui-1, Vj  )  e = (Ui, Vj  )  f = (Ui+1, Vj  )
//! g = (Ui-1, Vj+1)  h = (Ui, Vj+1)  k = (Ui+1, Vj+1)
//! ```
//!
//! Border modes: wrap (`i mod n`), clamp (`0..=n-1`), mirror (mirrored repeat of period
//! `2n`: `n-1, ..., 0, 0, ..., n-1, n-1, ...`), constant (a fixed raw value outside).
//!
//! # Formats
//! `ui`, `vj`: `s<pos_int+1>` from address unit 150; `h[0..9]` (a..k in the order above):
//! the height texel format, `uQ6.2` (8-bit) or `uQ3.1` (4-bit) (para. 0050). The memory is a
//! behavioural ROM holding the [`HeightMap`]. One register stage: latency 1.

use crate::bump::height_map::HeightMap;
use crate::bump::params::Border;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

/// The texel index along one axis of size `n` for coordinate `i`, or `None` for the
/// constant border.
#[inline]
pub fn border_index(i: i64, n: u32, border: Border) -> Option<u32> {
    let n = i64::from(n);
    match border {
        Border::Wrap => Some(modulo(i, n) as u32),
        Border::Clamp => Some(i.clamp(0, n - 1) as u32),
        Border::Mirror => {
            let m = modulo(i, 2 * n);
            Some(if m < n { m } else { 2 * n - 1 - m } as u32)
        }
        Border::Constant(_) => (0..n).contains(&i).then_some(i as u32),
    }
}

/// `i mod m` in `0..m`: for a power-of-two `m` (the usual side, and what the hardware does
/// with the low address bits) the two's complement mask, otherwise a division.
#[inline]
fn modulo(i: i64, m: i64) -> i64 {
    if m & (m - 1) == 0 {
        i & (m - 1)
    } else {
        i.rem_euclid(m)
    }
}

const NAMES: [&str; 9] = ["a", "b", "c", "d", "e", "f", "g", "h", "k"];
const REG_NAMES: [&str; 9] = [
    "a_r", "b_r", "c_r", "d_r", "e_r", "f_r", "g_r", "h_r", "k_r",
];

/// Texel fetch unit 151.
#[derive(Clone, Debug, Module)]
#[module(kind = "texel_fetch_151")]
pub struct TexelFetch {
    #[instance]
    name: String,
    map: HeightMap,
    border: Border,
    #[input]
    pub ui: Signal,
    #[input]
    pub vj: Signal,
    /// a, b, c, d, e, f, g, h, k.
    #[output]
    pub h: [Signal; 9],
    #[reg]
    r: [Reg; 9],
}

impl TexelFetch {
    /// A fetch unit on `map`; a constant border value must fit the texel format.
    pub fn new(
        name: &str,
        map: HeightMap,
        border: Border,
        coord: Format,
    ) -> Result<TexelFetch, String> {
        let t = map.fmt();
        if let Border::Constant(c) = border {
            if !t.contains_raw(i128::from(c)) {
                return Err(format!("border value {c} does not fit the texels' {t}"));
            }
        }
        Ok(TexelFetch {
            name: name.into(),
            map,
            border,
            ui: Signal::new("ui", coord),
            vj: Signal::new("vj", coord),
            h: NAMES.map(|n| Signal::new(n, t)),
            r: REG_NAMES.map(|n| Reg::new(n, t)),
        })
    }

    pub fn map(&self) -> &HeightMap {
        &self.map
    }

    /// The 3x3 grid around `(ui, vj)`, a..k: three column and three row addresses through
    /// the border mode, then nine reads (the constant border's value where either is outside).
    #[inline]
    pub fn grid(&self, ui: i64, vj: i64) -> [u8; 9] {
        let (w, h, b) = (self.map.width(), self.map.height(), self.border);
        let x = |i| border_index(i, w, b);
        let row = |j| border_index(j, h, b).map(|y| y as usize * w as usize);
        let xs = [x(ui - 1), x(ui), x(ui + 1)];
        let rows = [row(vj - 1), row(vj), row(vj + 1)];
        let mut out = [match b {
            Border::Constant(c) => c,
            _ => 0,
        }; 9];
        let t = self.map.texels();
        for (r, row) in rows.iter().enumerate() {
            for (col, x) in xs.iter().enumerate() {
                if let (Some(row), Some(x)) = (row, x) {
                    out[3 * r + col] = t[row + *x as usize];
                }
            }
        }
        out
    }
}

impl TexelFetch {
    #[inline]
    /// Reads the 3x3 grid around the texel coordinates into the output registers.
    pub fn eval(&mut self) {
        let g = self.grid(self.ui.raw(), self.vj.raw());
        for ((r, h), g) in self.r.iter_mut().zip(&mut self.h).zip(g) {
            r.set_next_raw(i64::from(g));
            h.follow(r.q());
        }
    }
}
