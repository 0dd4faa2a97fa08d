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
use crate::kernel::{Dir, Module, Reg, Signal, Visitor};
use crate::signals;

/// The texel index along one axis of size `n` for coordinate `i`, or `None` for the
/// constant border.
#[inline]
pub fn border_index(i: i64, n: u32, border: Border) -> Option<u32> {
    let n = i64::from(n);
    match border {
        Border::Wrap => Some(i.rem_euclid(n) as u32),
        Border::Clamp => Some(i.clamp(0, n - 1) as u32),
        Border::Mirror => {
            let m = i.rem_euclid(2 * n);
            Some(if m < n { m } else { 2 * n - 1 - m } as u32)
        }
        Border::Constant(_) => (0..n).contains(&i).then_some(i as u32),
    }
}

const NAMES: [&str; 9] = ["a", "b", "c", "d", "e", "f", "g", "h", "k"];
const REG_NAMES: [&str; 9] = [
    "a_r", "b_r", "c_r", "d_r", "e_r", "f_r", "g_r", "h_r", "k_r",
];

/// Texel fetch unit 151.
#[derive(Clone, Debug)]
pub struct TexelFetch {
    name: String,
    map: HeightMap,
    border: Border,
    pub ui: Signal,
    pub vj: Signal,
    /// a, b, c, d, e, f, g, h, k.
    pub h: [Signal; 9],
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

    /// The 3x3 grid around `(ui, vj)`, a..k.
    #[inline]
    pub fn grid(&self, ui: i64, vj: i64) -> [u8; 9] {
        let (w, h) = (self.map.width(), self.map.height());
        // Inside the map every mode reads the same texels: no border logic.
        if ui >= 1 && vj >= 1 && ui + 1 < i64::from(w) && vj + 1 < i64::from(h) {
            let t = self.map.texels();
            let w = w as usize;
            let base = (vj as usize - 1) * w + ui as usize - 1;
            return [
                t[base],
                t[base + 1],
                t[base + 2],
                t[base + w],
                t[base + w + 1],
                t[base + w + 2],
                t[base + 2 * w],
                t[base + 2 * w + 1],
                t[base + 2 * w + 2],
            ];
        }
        let xs = [-1, 0, 1].map(|d| border_index(ui + d, w, self.border));
        let ys = [-1, 0, 1].map(|d| border_index(vj + d, h, self.border));
        let c = match self.border {
            Border::Constant(c) => c,
            _ => 0,
        };
        let mut out = [0u8; 9];
        for (r, y) in ys.iter().enumerate() {
            for (col, x) in xs.iter().enumerate() {
                out[3 * r + col] = match (x, y) {
                    (Some(x), Some(y)) => self.map.get(*x, *y),
                    _ => c,
                };
            }
        }
        out
    }
}

impl Module for TexelFetch {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "texel_fetch_151"
    }
    fn eval(&mut self) {
        let g = self.grid(self.ui.raw(), self.vj.raw());
        for ((r, h), g) in self.r.iter_mut().zip(&mut self.h).zip(g) {
            r.set_next_raw(i64::from(g));
            h.follow(r.q());
        }
    }
    fn tick(&mut self, reset: bool) {
        for r in &mut self.r {
            r.tick(reset);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        signals!(v; Input: self.ui, self.vj);
        for s in &self.h {
            v.signal(Dir::Output, s);
        }
        v.leave();
    }
}
