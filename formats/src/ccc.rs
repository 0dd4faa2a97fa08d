//! Colour cell compression (CCC, Schilling & Knittel, section 3, Figures 4-5): the offline
//! encoder, the `.ccc` file format, and the reference decode of a texel (written independently
//! of `hdl`'s decode unit, for the testbenches).
//!
//! # Encoder
//! Per 4x4 block, on the 16 colours `x_j` (RGB, reals):
//! 1. The tensor of inertia (Eq. 1) of the colours about their mean `m`,
//!    `Θ = Σ_j (|d_j|² I - d_j d_jᵀ)`, `d_j = x_j - m`. (The document writes Eq. 1 on `x_j`; it
//!    puts the mean in the cutting plane, so the tensor is taken about the mean.)
//! 2. Its eigenvector `e` of the smallest eigenvalue (cyclic Jacobi rotations): the axis the
//!    colours spread along.
//! 3. The plane through `m` perpendicular to `e` splits the block: `d_j · e > 10^-6` gives
//!    cluster b (decision bit 1), else cluster a (bit 0, so a texel on the plane goes to a).
//!    The cluster means are colours a and b. A block of one colour has an empty cluster: both
//!    colours are its mean and every bit is 0.
//! 4. Global quantisation of all blocks' colours (two per block, weighted by their texel
//!    counts) to a 256-entry CLUT by median cut (Heckbert 1982) with one refinement: the box
//!    to split next is the one with the largest weighted squared error (not the largest
//!    range), cut at the weighted median of its axis of largest variance. Entries are the
//!    rounded weighted means of the boxes; unused entries are black.
//! 5. Indices a and b are the nearest CLUT entries (Euclidean RGB, lowest index on a tie).
//! 6. "Or better": each texel's decision bit is chosen again against the two quantised
//!    colours (the nearer one, a on a tie), which can only reduce the error.
//!
//! # File format (`.ccc`, little-endian)
//! | offset | size | field |
//! |---|---|---|
//! | 0 | 8 | magic `TEXRTLCC` |
//! | 8 | 2 | version, 1 |
//! | 10 | 2 | width in texels (multiple of 4, 4..=4096) |
//! | 12 | 2 | height in texels (same) |
//! | 14 | 2 | CLUT entries, 256 |
//! | 16 | 768 | CLUT: 256 x (r, g, b) bytes |
//! | 784 | 4 per block | blocks row-major (left to right, top to bottom): index a (1 byte), index b (1 byte), decision bits (2 bytes; bit `4y+x` for texel `(x, y)`, 1 = colour b) |
//!
//! The file must be exactly `784 + 4 (width/4) (height/4)` bytes.

use crate::netpbm::Ppm;
use std::path::Path;
use units::texmem::ccc_decode_608::CccBlock;
use units::texmem::layout::BlockMap;

pub const MAGIC: &[u8; 8] = b"TEXRTLCC";
pub const VERSION: u16 = 1;
const HEADER: usize = 16 + 768;

/// A CCC-encoded texture.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ccc {
    pub width: u32,
    pub height: u32,
    /// 256 entries of `r << 16 | g << 8 | b`.
    pub clut: Vec<u32>,
    /// Row-major blocks.
    pub blocks: Vec<CccBlock>,
}

/// Checks a texture size.
pub fn check_size(w: u32, h: u32) -> Result<(), String> {
    if !w.is_multiple_of(4)
        || !h.is_multiple_of(4)
        || !(4..=4096).contains(&w)
        || !(4..=4096).contains(&h)
    {
        return Err(format!(
            "texture size {w}x{h}: width and height must be multiples of 4 in 4..=4096"
        ));
    }
    Ok(())
}

impl Ccc {
    pub fn blocks_wide(&self) -> u32 {
        self.width / 4
    }

    /// Reference decode of texel `(x, y)`: the CLUT entry its decision bit selects.
    pub fn texel(&self, x: u32, y: u32) -> u32 {
        let blk = self.blocks[((y / 4) * self.blocks_wide() + x / 4) as usize];
        let bit = blk.bits >> (4 * (y % 4) + x % 4) & 1;
        self.clut[usize::from(if bit == 1 { blk.b } else { blk.a })]
    }

    /// The decoded image, RGB bytes.
    pub fn decode(&self) -> Vec<u8> {
        let mut v = Vec::with_capacity((self.width * self.height * 3) as usize);
        for y in 0..self.height {
            for x in 0..self.width {
                let c = self.texel(x, y);
                v.extend_from_slice(&[(c >> 16) as u8, (c >> 8) as u8, c as u8]);
            }
        }
        v
    }

    /// The DRAM image of the texture under `map` (words from `map.base`, `map.words()` long;
    /// gaps of partial tiles are zero).
    pub fn dram_words(&self, map: &BlockMap) -> Vec<u16> {
        let mut w = vec![0u16; map.words() as usize];
        let bw = self.blocks_wide();
        for (i, blk) in self.blocks.iter().enumerate() {
            let (bx, by) = (i as u32 % bw, i as u32 / bw);
            let a = (map.block_addr(bx, by) - map.base) as usize;
            w[a..a + 2].copy_from_slice(&blk.words());
        }
        w
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let mut v = Vec::with_capacity(HEADER + 4 * self.blocks.len());
        v.extend_from_slice(MAGIC);
        for x in [VERSION, self.width as u16, self.height as u16, 256] {
            v.extend_from_slice(&x.to_le_bytes());
        }
        for c in &self.clut {
            v.extend_from_slice(&[(c >> 16) as u8, (c >> 8) as u8, *c as u8]);
        }
        for b in &self.blocks {
            v.extend_from_slice(&[b.a, b.b]);
            v.extend_from_slice(&b.bits.to_le_bytes());
        }
        v
    }

    /// Parses a `.ccc` file's bytes; the error says what is wrong.
    pub fn parse(b: &[u8]) -> Result<Ccc, String> {
        if b.len() < 16 {
            return Err(format!(
                "truncated: {} bytes, the header alone is 16",
                b.len()
            ));
        }
        if &b[..8] != MAGIC {
            return Err("wrong magic (not a texrtl .ccc file)".into());
        }
        let half = |o: usize| u16::from_le_bytes([b[o], b[o + 1]]);
        if half(8) != VERSION {
            return Err(format!("version {}, this reader knows {VERSION}", half(8)));
        }
        let (w, h) = (u32::from(half(10)), u32::from(half(12)));
        check_size(w, h)?;
        if half(14) != 256 {
            return Err(format!("CLUT has {} entries, must be 256", half(14)));
        }
        let nblocks = (w / 4 * (h / 4)) as usize;
        let want = HEADER + 4 * nblocks;
        if b.len() != want {
            return Err(format!(
                "{} bytes, a {w}x{h} texture needs {want} ({})",
                b.len(),
                if b.len() < want {
                    "truncated"
                } else {
                    "trailing data"
                }
            ));
        }
        let clut = b[16..HEADER]
            .chunks_exact(3)
            .map(|c| u32::from(c[0]) << 16 | u32::from(c[1]) << 8 | u32::from(c[2]))
            .collect();
        let blocks = b[HEADER..]
            .chunks_exact(4)
            .map(|c| CccBlock {
                a: c[0],
                b: c[1],
                bits: u16::from_le_bytes([c[2], c[3]]),
            })
            .collect();
        Ok(Ccc {
            width: w,
            height: h,
            clut,
            blocks,
        })
    }

    pub fn read(path: &Path) -> Result<Ccc, String> {
        let b = crate::read_bounded(path, crate::MAX_INPUT_BYTES)?;
        Ccc::parse(&b).map_err(|e| format!("{}: {e}", path.display()))
    }
}

type Rgb = [f64; 3];

fn dot(a: Rgb, b: Rgb) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: Rgb, b: Rgb) -> Rgb {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Eigenvector of the smallest eigenvalue of a symmetric 3x3 matrix (cyclic Jacobi).
pub fn smallest_eigenvector(mut a: [[f64; 3]; 3]) -> Rgb {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off < 1e-12 * (a[0][0].abs() + a[1][1].abs() + a[2][2].abs() + 1e-300) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q].abs() < 1e-300 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A <- Jᵀ A J, V <- V J.
            for row in &mut a {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (rp, rq) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * rp[k] - s * rq[k];
                a[q][k] = s * rp[k] + c * rq[k];
            }
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let k = (0..3)
        .min_by(|&i, &j| a[i][i].total_cmp(&a[j][j]))
        .unwrap_or(0);
    [v[0][k], v[1][k], v[2][k]]
}

/// One block split into two colours: (colour a, texels of a, colour b, texels of b, bits).
fn split_block(px: &[Rgb; 16]) -> (Rgb, f64, Rgb, f64, u16) {
    let mut m = [0.0; 3];
    for p in px {
        for c in 0..3 {
            m[c] += p[c] / 16.0;
        }
    }
    let mut th = [[0.0; 3]; 3];
    for p in px {
        let d = sub(*p, m);
        let n2 = dot(d, d);
        for i in 0..3 {
            for k in 0..3 {
                let diag = if i == k { n2 } else { 0.0 };
                th[i][k] += diag - d[i] * d[k];
            }
        }
    }
    let e = smallest_eigenvector(th);
    let (mut sa, mut sb, mut na, mut nb, mut bits) = ([0.0; 3], [0.0; 3], 0.0, 0.0, 0u16);
    for (j, p) in px.iter().enumerate() {
        let d = sub(*p, m);
        // Distances below a millionth of a level are on the plane (float noise on flat blocks).
        if dot(d, e) > 1e-6 {
            bits |= 1 << j;
            nb += 1.0;
            (0..3).for_each(|c| sb[c] += p[c]);
        } else {
            na += 1.0;
            (0..3).for_each(|c| sa[c] += p[c]);
        }
    }
    let mean = |s: Rgb, n: f64| if n > 0.0 { s.map(|x| x / n) } else { m };
    (mean(sa, na), na, mean(sb, nb), nb, bits)
}

/// Median cut of weighted colours to at most `n` entries (see the module documentation).
pub fn median_cut(points: &[(Rgb, f64)], n: usize) -> Vec<u32> {
    let mut boxes: Vec<Vec<(Rgb, f64)>> =
        vec![points.iter().copied().filter(|p| p.1 > 0.0).collect()];
    let stats = |b: &[(Rgb, f64)]| {
        let w: f64 = b.iter().map(|p| p.1).sum();
        let mut m = [0.0; 3];
        for (p, pw) in b {
            (0..3).for_each(|c| m[c] += p[c] * pw / w.max(1e-300));
        }
        let mut var = [0.0; 3];
        for (p, pw) in b {
            (0..3).for_each(|c| var[c] += pw * (p[c] - m[c]).powi(2));
        }
        (m, var)
    };
    while boxes.len() < n {
        let (k, sse, axis) = boxes
            .iter()
            .enumerate()
            .map(|(k, b)| {
                let (_, var) = stats(b);
                let axis = (0..3)
                    .max_by(|&i, &j| var[i].total_cmp(&var[j]))
                    .unwrap_or(0);
                (k, var[0] + var[1] + var[2], axis)
            })
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .unwrap_or((0, 0.0, 0));
        if sse <= 1e-9 || boxes[k].len() < 2 {
            break;
        }
        let mut b = std::mem::take(&mut boxes[k]);
        b.sort_by(|x, y| x.0[axis].total_cmp(&y.0[axis]));
        let total: f64 = b.iter().map(|p| p.1).sum();
        let (mut acc, mut cut) = (0.0, 1);
        for (i, p) in b.iter().enumerate() {
            acc += p.1;
            if acc >= total / 2.0 {
                cut = (i + 1).clamp(1, b.len() - 1);
                break;
            }
        }
        // Keep equal values on one side, so both halves are non-empty and distinct.
        while cut < b.len() && b[cut].0[axis] == b[cut - 1].0[axis] {
            cut += 1;
        }
        if cut == b.len() {
            cut = b.len() - 1;
            while cut > 1 && b[cut].0[axis] == b[cut - 1].0[axis] {
                cut -= 1;
            }
        }
        let hi = b.split_off(cut);
        boxes[k] = b;
        boxes.push(hi);
    }
    let mut clut: Vec<u32> = boxes
        .iter()
        .filter(|b| !b.is_empty())
        .map(|b| {
            let (m, _) = stats(b);
            let q = m.map(|x| x.round().clamp(0.0, 255.0) as u32);
            q[0] << 16 | q[1] << 8 | q[2]
        })
        .collect();
    clut.resize(n, 0);
    clut
}

fn rgb_of(c: u32) -> Rgb {
    [
        f64::from(c >> 16 & 0xff),
        f64::from(c >> 8 & 0xff),
        f64::from(c & 0xff),
    ]
}

fn nearest(clut: &[Rgb], x: Rgb) -> u8 {
    let mut best = (f64::INFINITY, 0);
    for (i, c) in clut.iter().enumerate() {
        let d = sub(*c, x);
        let d = dot(d, d);
        if d < best.0 {
            best = (d, i);
        }
    }
    best.1 as u8
}

/// Encodes an RGB image (see the module documentation).
pub fn encode(img: &Ppm) -> Result<Ccc, String> {
    check_size(img.width, img.height)?;
    let (bw, bh) = (img.width / 4, img.height / 4);
    let px = |x: u32, y: u32| -> Rgb {
        let i = 3 * (y * img.width + x) as usize;
        [0, 1, 2].map(|c| f64::from(img.pixels[i + c]))
    };
    let mut splits = Vec::with_capacity((bw * bh) as usize);
    for by in 0..bh {
        for bx in 0..bw {
            let mut b = [[0.0; 3]; 16];
            for (j, p) in b.iter_mut().enumerate() {
                *p = px(4 * bx + j as u32 % 4, 4 * by + j as u32 / 4);
            }
            splits.push((b, split_block(&b)));
        }
    }
    let points: Vec<(Rgb, f64)> = splits
        .iter()
        .flat_map(|(_, (a, na, b, nb, _))| [(*a, *na), (*b, *nb)])
        .collect();
    let clut = median_cut(&points, 256);
    let cf: Vec<Rgb> = clut.iter().map(|&c| rgb_of(c)).collect();
    let blocks = splits
        .iter()
        .map(|(texels, (a, _, b, _, _))| {
            let (ia, ib) = (nearest(&cf, *a), nearest(&cf, *b));
            let (ca, cb) = (cf[usize::from(ia)], cf[usize::from(ib)]);
            let mut bits = 0u16;
            for (j, t) in texels.iter().enumerate() {
                let (da, db) = (sub(*t, ca), sub(*t, cb));
                if dot(db, db) < dot(da, da) {
                    bits |= 1 << j;
                }
            }
            CccBlock { a: ia, b: ib, bits }
        })
        .collect();
    Ok(Ccc {
        width: img.width,
        height: img.height,
        clut,
        blocks,
    })
}

/// PSNR (dB) and largest absolute error (levels) of `b` against `a`, RGB bytes.
pub fn psnr(a: &[u8], b: &[u8]) -> (f64, u8) {
    let mut se = 0.0;
    let mut worst = 0;
    for (x, y) in a.iter().zip(b) {
        let d = x.abs_diff(*y);
        worst = worst.max(d);
        se += f64::from(d) * f64::from(d);
    }
    let mse = se / a.len().max(1) as f64;
    let p = if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    };
    (p, worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn img(w: u32, h: u32, f: impl Fn(u32, u32) -> [u8; 3]) -> Ppm {
        let mut pixels = Vec::new();
        for y in 0..h {
            for x in 0..w {
                pixels.extend_from_slice(&f(x, y));
            }
        }
        Ppm {
            width: w,
            height: h,
            maxval: 255,
            pixels,
        }
    }

    #[test]
    fn jacobi_finds_the_smallest_eigenvector() {
        // Diagonal in a rotated basis: eigenvalues 5, 2, 1 on axes e1, e2, e3.
        let s = 0.5f64.sqrt();
        let e = [[s, s, 0.0], [-s, s, 0.0], [0.0, 0.0, 1.0]];
        let l = [5.0, 1.0, 2.0];
        let mut a = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] = (0..3).map(|k| l[k] * e[k][i] * e[k][j]).sum();
            }
        }
        let v = smallest_eigenvector(a);
        assert!((dot(v, e[1]).abs() - 1.0).abs() < 1e-9, "{v:?}");
    }

    #[test]
    fn two_colour_blocks_are_lossless() {
        // Each block holds two colours: CCC reproduces it exactly (fewer than 256 colours).
        let p = img(16, 8, |x, y| {
            let (bx, by) = (x / 4, y / 4);
            if (x + 2 * y) % 3 == 0 {
                [(bx * 60) as u8, 200, (by * 90) as u8]
            } else {
                [10, (bx * 40) as u8, 99]
            }
        });
        let c = encode(&p).unwrap();
        assert_eq!(c.decode(), p.pixels);
        let back = Ccc::parse(&c.to_bytes()).unwrap();
        assert_eq!(back, c);
    }

    #[test]
    fn smooth_images_compress_well() {
        let p = img(64, 64, |x, y| {
            [(4 * x) as u8, (4 * y) as u8, ((x * y) / 16) as u8]
        });
        let c = encode(&p).unwrap();
        let (db, _) = psnr(&p.pixels, &c.decode());
        assert!(db > 30.0, "{db} dB");
    }

    #[test]
    fn malformed_files_are_refused() {
        let p = img(8, 4, |x, _| [x as u8, 0, 0]);
        let good = encode(&p).unwrap().to_bytes();
        let mut bad_magic = good.clone();
        bad_magic[0] = b'X';
        let mut bad_size = good.clone();
        bad_size[10] = 6;
        let mut bad_version = good.clone();
        bad_version[8] = 9;
        let mut long = good.clone();
        long.push(0);
        for (b, what) in [
            (&good[..good.len() - 1], "truncated"),
            (&good[..10], "truncated"),
            (&bad_magic[..], "magic"),
            (&bad_size[..], "multiples of 4"),
            (&bad_version[..], "version"),
            (&long[..], "trailing"),
        ] {
            let e = Ccc::parse(b).unwrap_err();
            assert!(e.contains(what), "{e}");
        }
    }
}
