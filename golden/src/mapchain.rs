//! Golden model of a pixel's linked maps (Schilling & Knittel sections 5-9 and 14), in f64
//! from the equations, sharing nothing with `hdl`: what the pixel's colour is, not how a
//! walker gets it.
//!
//! * A map's value: the trilinear filter of [`crate::texram`] with the chip's declared weight
//!   quantisation (8-bit truncation), so that each map value is within half an LSB of the chip's.
//! * Detail (section 9): for lambda < 0 the tile of the pixel's level-0 texel `(floor u,
//!   floor v)`, its origin `(ou, ov)` from the offset maps; the detail map at `o + frac(u) 16`
//!   with lambda `max(lambda, -4) + 4` (3 above -1), repeating inside the tile at each level;
//!   combined with the texel by replace, multiply (`T D / 255`) or add-signed (`T + D - 128`),
//!   faded into the texel over `-1 < lambda < 0` by `lambda + 1`.
//! * Environment (section 7): eq. 4 with the perturbed normal, the cube face and `(s, t)`,
//!   the face at `(s W, t W)` and lambda `max(lambda, 0)`.
//! * Output (eqs 5-7): `C_d = m T / 255`, `C = base + k_s E / 255` or `base + R L / 255`,
//!   held to 255.
//!
//! Every stage carries a bound on the chip's distance from it, derived from its inputs'
//! bounds (first-order terms plus their product) and the stage's one rounding (half an LSB);
//! the environment's bound adds the face coordinate's error times the face's steepest texel
//! step. A pixel whose two largest reflection components are within 2^-12 may take either
//! face and is flagged, not bounded.

use crate::envmap::{face_st, reflect};
use crate::texram::{trilinear, Border, Mipmap, Weights};

/// A map's levels (row-major, level k of `max(W >> k, 1) x max(H >> k, 1)`), as stored.
#[derive(Clone, Debug)]
pub struct GMap {
    pub width: usize,
    pub height: usize,
    pub levels: Vec<Vec<u8>>,
    pub border: Border,
}

impl GMap {
    fn mipmap(&self) -> Mipmap<'_> {
        Mipmap {
            width: self.width,
            height: self.height,
            levels: &self.levels,
            border: self.border,
        }
    }

    fn lmax(&self) -> usize {
        self.levels.len() - 1
    }

    /// The map's trilinear value at `(u, v, lambda)` with the chip's truncated weights.
    pub fn value(&self, u: f64, v: f64, lambda: f64) -> f64 {
        let w = Weights::truncated(u, v, lambda, self.lmax());
        trilinear(&self.mipmap(), &w)
    }

    /// Level-0 texel `(i, j)` after the border.
    fn texel0(&self, i: i64, j: i64) -> f64 {
        self.mipmap().texel(0, i, j)
    }

    /// The largest step between neighbouring texels of levels `k` and `k + 1`.
    fn steepest(&self, k: usize) -> f64 {
        let mut g = 0.0f64;
        for lv in k..=(k + 1).min(self.lmax()) {
            let (w, h) = ((self.width >> lv).max(1), (self.height >> lv).max(1));
            let t = &self.levels[lv];
            for y in 0..h {
                for x in 0..w {
                    let c = f64::from(t[y * w + x]);
                    let r = f64::from(t[y * w + (x + 1) % w]);
                    let d = f64::from(t[((y + 1) % h) * w + x]);
                    g = g.max((c - r).abs()).max((c - d).abs());
                }
            }
        }
        g
    }
}

/// How detail meets the texel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Replace,
    Multiply,
    AddSigned,
}

/// A map's detail: offset maps (level 0 read, their border), the detail map and its tile
/// (`None`: continued into the map).
#[derive(Clone, Debug)]
pub struct GDetail {
    pub offsets: [GMap; 2],
    pub detail: GMap,
    pub tile_log2: Option<u32>,
    pub mode: Mode,
}

/// A texture or reflectance map, with or without detail.
#[derive(Clone, Debug)]
pub struct GLayer {
    pub map: GMap,
    pub detail: Option<GDetail>,
}

/// An environment map: six faces and eq. 6's constant.
#[derive(Clone, Debug)]
pub struct GEnv {
    pub faces: Vec<GMap>,
    pub k_s: f64,
}

/// A pixel's maps and the output stage's selections.
#[derive(Clone, Debug)]
pub struct GChain {
    pub texture: Option<GLayer>,
    /// Eq. 5's factor: `None` for I_d, else the constant (255 for one).
    pub modulate: Option<f64>,
    pub reflectance: Option<GLayer>,
    pub env: Option<GEnv>,
    /// Eqs 6 and 7: base C_d (true) or I_d.
    pub base_texture: bool,
    /// Eq. 7: R lights E (true) or I_s.
    pub light_env: bool,
}

/// A pixel: coordinates and level of detail as reals, vectors, illumination.
#[derive(Clone, Copy, Debug)]
pub struct GPixel {
    pub u: f64,
    pub v: f64,
    pub lambda: f64,
    pub n: [f64; 3],
    pub eye: [f64; 3],
    pub i_d: f64,
    pub i_s: f64,
}

/// A value and the bound on the chip's distance from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounded {
    pub x: f64,
    pub e: f64,
}

impl Bounded {
    fn exact(x: f64) -> Bounded {
        Bounded { x, e: 0.0 }
    }

    /// `x y / 255` with one rounding.
    fn mul(self, o: Bounded) -> Bounded {
        let e = (self.e * o.x.abs() + o.e * self.x.abs() + self.e * o.e) / 255.0 + 0.5;
        Bounded {
            x: self.x * o.x / 255.0,
            e,
        }
    }

    /// `x + y` held to 0 ..= 255 (no rounding).
    fn add(self, o: Bounded) -> Bounded {
        Bounded {
            x: (self.x + o.x).clamp(0.0, 255.0),
            e: self.e + o.e,
        }
    }
}

/// Half an LSB: one rounding of an exact value.
const HALF: f64 = 0.5 + 1e-9;

/// The detail colour of a pixel at `lambda < 0`.
fn detail_value(d: &GDetail, px: &GPixel) -> f64 {
    let (i, j) = (px.u.floor(), px.v.floor());
    let o = [&d.offsets[0], &d.offsets[1]].map(|m| m.texel0(i as i64, j as i64));
    let uu = o[0] + (px.u - i) * 16.0;
    let vv = o[1] + (px.v - j) * 16.0;
    let ld = if px.lambda > -1.0 {
        3.0
    } else {
        px.lambda.max(-4.0) + 4.0
    };
    let map = &d.detail;
    let w = Weights::truncated(uu, vv, ld, map.lmax());
    let Some(t) = d.tile_log2 else {
        return trilinear(&map.mipmap(), &w);
    };
    // Inside the tile: the sample point's tile at each level, the pair folded into it.
    let mut out = 0.0;
    for (n, (k, wf)) in [(w.fine, 1.0 - w.f), (w.coarse, w.f)]
        .into_iter()
        .enumerate()
    {
        let tile = 2f64.powi(t as i32 - k as i32).max(1.0);
        let s = 2f64.powi(k as i32);
        let base = |c: f64| ((c / s).floor() / tile).floor() * tile;
        let fold = |x: i64, b: f64| (b + (x as f64 - b).rem_euclid(tile)) as i64;
        let (bu, bv) = (base(uu), base(vv));
        let (i0, j0) = (w.i[n], w.j[n]);
        let tx = |di: i64, dj: i64| map.mipmap().texel(k, fold(i0 + di, bu), fold(j0 + dj, bv));
        let (a, b) = (w.a[n], w.b[n]);
        out += wf
            * ((1.0 - a) * (1.0 - b) * tx(0, 0)
                + a * (1.0 - b) * tx(1, 0)
                + (1.0 - a) * b * tx(0, 1)
                + a * b * tx(1, 1));
    }
    out
}

/// A layer's value at the pixel, with its detail below level 0.
fn layer(l: &GLayer, px: &GPixel) -> Bounded {
    let t = Bounded {
        x: l.map.value(px.u, px.v, px.lambda),
        e: HALF,
    };
    let Some(d) = l.detail.as_ref().filter(|_| px.lambda < 0.0) else {
        return t;
    };
    let dv = Bounded {
        x: detail_value(d, px),
        e: HALF,
    };
    let x = match d.mode {
        Mode::Replace => dv,
        Mode::Multiply => t.mul(dv),
        Mode::AddSigned => Bounded {
            x: (t.x + dv.x - 128.0).clamp(0.0, 255.0),
            e: t.e + dv.e,
        },
    };
    if px.lambda <= -1.0 {
        return x;
    }
    // The fade's weight is lambda + 1 in 8 bits (lambda has 8 fraction bits: exact).
    let f = px.lambda + 1.0;
    Bounded {
        x: x.x * (1.0 - f) + t.x * f,
        e: x.e * (1.0 - f) + t.e * f + HALF,
    }
}

/// The environment colour and whether the face is ambiguous.
fn environment(env: &GEnv, px: &GPixel) -> (Bounded, bool) {
    let w = reflect(px.n, px.eye);
    let mut a = w.map(f64::abs);
    a.sort_by(|x, y| y.total_cmp(x));
    let ambiguous = a[0] - a[1] <= a[0] * 2f64.powi(-12);
    let (face, s, t) = face_st(w);
    let map = &env.faces[usize::from(face)];
    let side = map.width as f64;
    let lambda = px.lambda.max(0.0);
    let x = map.value(s * side, t * side, lambda);
    // s, t: within 3/4 LSB of 2^-12 from the unit (its derived bound), plus 2^-17 per
    // component of w over |ma| >= |w|/sqrt 3; in texels of level 0, then one step of weight
    // truncation on each axis, times the steepest texel step.
    let mag = w.iter().map(|c| c * c).sum::<f64>().sqrt();
    let st = (0.75 + 2f64.powi(-17) * 3f64.sqrt() / mag.max(1e-9) * 4096.0) / 4096.0;
    let texels = st * side + 2.0 / 256.0;
    let g = map.steepest(lambda.floor().min(map.lmax() as f64) as usize);
    (
        Bounded {
            x,
            e: HALF + 2.0 * texels * g,
        },
        ambiguous,
    )
}

/// The pixel's colour and the chip's bound, and whether the cube face is ambiguous.
pub fn pixel(c: &GChain, px: &GPixel) -> (Bounded, bool) {
    let i_d = Bounded::exact(px.i_d);
    let cd = match &c.texture {
        Some(t) => layer(t, px).mul(Bounded::exact(c.modulate.unwrap_or(px.i_d))),
        None => i_d,
    };
    let base = if c.base_texture { cd } else { i_d };
    let (env, ambiguous) = match &c.env {
        Some(e) => {
            let (x, amb) = environment(e, px);
            (Some(x), amb)
        }
        None => (None, false),
    };
    let out = match (&c.reflectance, env) {
        (Some(r), env) => {
            let light = if c.light_env {
                env.unwrap_or(Bounded::exact(0.0))
            } else {
                Bounded::exact(px.i_s)
            };
            base.add(layer(r, px).mul(light))
        }
        (None, Some(e)) => {
            let ks = c.env.as_ref().map_or(0.0, |e| e.k_s);
            base.add(Bounded::exact(ks).mul(e))
        }
        (None, None) => cd,
    };
    (out, ambiguous)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(n: usize, v: u8, border: Border) -> GMap {
        let mut levels = Vec::new();
        let mut s = n;
        loop {
            levels.push(vec![v; s * s]);
            if s == 1 {
                break;
            }
            s /= 2;
        }
        GMap {
            width: n,
            height: n,
            levels,
            border,
        }
    }

    #[test]
    fn constant_maps_give_the_equations_values() {
        let px = GPixel {
            u: 3.3,
            v: 7.9,
            lambda: -0.5,
            n: [0.0, 0.0, 1.0],
            eye: [0.0, 0.6, 0.8],
            i_d: 200.0,
            i_s: 0.0,
        };
        let chain = GChain {
            texture: Some(GLayer {
                map: flat(16, 100, Border::Wrap),
                detail: Some(GDetail {
                    offsets: [flat(16, 0, Border::Wrap), flat(16, 16, Border::Wrap)],
                    detail: flat(64, 50, Border::Wrap),
                    tile_log2: Some(4),
                    mode: Mode::Multiply,
                }),
            }),
            modulate: Some(255.0),
            reflectance: None,
            env: Some(GEnv {
                faces: (0..6).map(|_| flat(16, 40, Border::Clamp)).collect(),
                k_s: 127.5,
            }),
            base_texture: true,
            light_env: true,
        };
        let (c, amb) = pixel(&chain, &px);
        // Detail 100 * 50 / 255 faded halfway to 100, plus half of 40.
        let want = (100.0 * 50.0 / 255.0 + 100.0) / 2.0 + 20.0;
        assert!((c.x - want).abs() < 1e-9, "{c:?}");
        assert!(!amb);
        assert!(c.e > 1.0 && c.e < 4.0, "{c:?}");
    }
}
