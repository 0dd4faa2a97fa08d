//! The TEXRAM chip's integer reference: plain loops over a mipmap held level by level (no
//! banks), its own border folding and its own weight arithmetic (integer division, not
//! shifts), for bit-exact comparison with `hdl::texram` (the stub now, the cycle-accurate
//! chip later). Its definitions are the module documentation of `hdl::texram`.

/// A mipmap held as levels: `levels[k]` row-major, `max(W >> k, 1) x max(H >> k, 1)`.
#[derive(Clone, Debug)]
pub struct RefMipmap {
    pub width: u32,
    pub height: u32,
    pub levels: Vec<Vec<u8>>,
}

/// The border operation by name (the reference's own enumeration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefBorder {
    Wrap,
    Clamp,
    Mirror,
    Colour(u8),
}

impl RefMipmap {
    /// Level 0 and every level above it, each texel the rounded mean of the 2x2 (or the pair,
    /// once a side is 1) below it.
    pub fn build(width: u32, height: u32, level0: &[u8]) -> RefMipmap {
        let mut levels = vec![level0.to_vec()];
        let (mut w, mut h) = (width, height);
        while w > 1 || h > 1 {
            let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
            let prev = levels.last().expect("level 0");
            let mut next = vec![0u8; (nw * nh) as usize];
            for y in 0..nh {
                for x in 0..nw {
                    let xs: Vec<u32> = if w > 1 {
                        vec![2 * x, 2 * x + 1]
                    } else {
                        vec![x]
                    };
                    let ys: Vec<u32> = if h > 1 {
                        vec![2 * y, 2 * y + 1]
                    } else {
                        vec![y]
                    };
                    let mut sum = 0u32;
                    for yy in &ys {
                        for xx in &xs {
                            sum += u32::from(prev[(yy * w + xx) as usize]);
                        }
                    }
                    let n = (xs.len() * ys.len()) as u32;
                    next[(y * nw + x) as usize] = ((2 * sum + n) / (2 * n)) as u8;
                }
            }
            levels.push(next);
            (w, h) = (nw, nh);
        }
        RefMipmap {
            width,
            height,
            levels,
        }
    }

    fn last(&self) -> i64 {
        self.levels.len() as i64 - 1
    }

    fn texel(&self, k: usize, i: i64, j: i64, border: RefBorder) -> u8 {
        let w = i64::from((self.width >> k).max(1));
        let h = i64::from((self.height >> k).max(1));
        let fold = |t: i64, n: i64| -> Option<i64> {
            match border {
                RefBorder::Wrap => Some(t.rem_euclid(n)),
                RefBorder::Clamp => Some(t.max(0).min(n - 1)),
                RefBorder::Mirror => {
                    let m = t.rem_euclid(2 * n);
                    Some(if m < n { m } else { 2 * n - 1 - m })
                }
                RefBorder::Colour(_) => (t >= 0 && t < n).then_some(t),
            }
        };
        match (fold(i, w), fold(j, h)) {
            (Some(x), Some(y)) => self.levels[k][(y * w + x) as usize],
            _ => match border {
                RefBorder::Colour(c) => c,
                _ => unreachable!(),
            },
        }
    }

    /// The access at raw sQ12.8 `u`, `v` and sQ5.8 `lambda`: the eight texels and the result.
    pub fn access(&self, u: i32, v: i32, lambda: i32, border: RefBorder) -> ([u8; 8], u8) {
        let l = i64::from(lambda).div_euclid(256);
        let (fine, f) = if l < 0 {
            (0, 0)
        } else if l >= self.last() {
            (self.last(), 0)
        } else {
            (l, i64::from(lambda).rem_euclid(256))
        };
        let coarse = (fine + 1).min(self.last());
        let mut texels = [0u8; 8];
        let mut sum: i64 = 0;
        for (n, k) in [fine, coarse].into_iter().enumerate() {
            // c / 2^k - 1/2 in units of 2^-(8 + k): c - 128 * 2^k.
            let scale = 256i64 << k;
            let x = i64::from(u) - (128i64 << k);
            let y = i64::from(v) - (128i64 << k);
            let (i, j) = (x.div_euclid(scale), y.div_euclid(scale));
            let a = x.rem_euclid(scale) * 256 / scale;
            let b = y.rem_euclid(scale) * 256 / scale;
            let wl = if n == 0 { 256 - f } else { f };
            let corners = [
                (0, 0, (256 - a) * (256 - b)),
                (1, 0, a * (256 - b)),
                (0, 1, (256 - a) * b),
                (1, 1, a * b),
            ];
            for (t, (di, dj, w)) in corners.into_iter().enumerate() {
                let tex = self.texel(k as usize, i + di, j + dj, border);
                texels[4 * n + t] = tex;
                sum += i64::from(tex) * w * wl;
            }
        }
        let value = (sum + (1 << 23)) / (1 << 24);
        (texels, value as u8)
    }
}
