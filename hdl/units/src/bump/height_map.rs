//! A height map held in texture memory: `width x height` raw texels of a declared format.

use crate::fx::Format;

/// Height texels, row-major (`texels[y * width + x]`), each a raw value of `fmt`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HeightMap {
    width: u32,
    height: u32,
    fmt: Format,
    texels: Vec<u8>,
}

impl HeightMap {
    /// Largest side accepted.
    pub const MAX_SIDE: u32 = 1 << 15;

    /// A map; errors for a side below 2 or above `MAX_SIDE`, a texel count that does not
    /// match, or a texel that does not fit `fmt`.
    pub fn new(width: u32, height: u32, fmt: Format, texels: Vec<u8>) -> Result<HeightMap, String> {
        if width < 2 || height < 2 || width > Self::MAX_SIDE || height > Self::MAX_SIDE {
            return Err(format!(
                "height map {width}x{height}: each side must be 2..={}",
                Self::MAX_SIDE
            ));
        }
        if texels.len() != (width as usize) * (height as usize) {
            return Err(format!(
                "height map {width}x{height} needs {} texels, got {}",
                width as u64 * height as u64,
                texels.len()
            ));
        }
        if let Some(t) = texels.iter().find(|&&t| !fmt.contains_raw(i128::from(t))) {
            return Err(format!("texel {t} does not fit {fmt}"));
        }
        Ok(HeightMap {
            width,
            height,
            fmt,
            texels,
        })
    }

    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    pub fn fmt(&self) -> Format {
        self.fmt
    }
    pub fn texels(&self) -> &[u8] {
        &self.texels
    }

    /// The raw texel at `(x, y)` (in range).
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> u8 {
        self.texels[y as usize * self.width as usize + x as usize]
    }

    /// The next MIP level: each texel the average of a 2x2 block, round half up; odd sides
    /// repeat their last row/column, and a side of 2 stays 2 (the pipeline needs 2x2).
    pub fn downsample(&self) -> HeightMap {
        let (w, h) = ((self.width / 2).max(2), (self.height / 2).max(2));
        let mut t = Vec::with_capacity((w * h) as usize);
        for y in 0..h {
            for x in 0..w {
                let xs = [(2 * x).min(self.width - 1), (2 * x + 1).min(self.width - 1)];
                let ys = [
                    (2 * y).min(self.height - 1),
                    (2 * y + 1).min(self.height - 1),
                ];
                let s: u32 = ys
                    .iter()
                    .flat_map(|&yy| xs.iter().map(move |&xx| u32::from(self.get(xx, yy))))
                    .sum();
                t.push(((s + 2) >> 2) as u8);
            }
        }
        HeightMap::new(w, h, self.fmt, t).expect("a downsampled map is valid")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The next level against the definition written out: sides halved (at least 2), each texel
    /// the 2x2 block's mean rounded half up, an odd side's last row or column repeated.
    #[test]
    fn downsample_averages_each_block_and_repeats_odd_edges() {
        for (w, h) in [(8, 4), (5, 3), (2, 7), (9, 2), (4, 4)] {
            let texels: Vec<u8> = (0..w * h)
                .map(|i| ((i * 37 + i / w * 11) % 256) as u8)
                .collect();
            let map = HeightMap::new(w, h, Format::uint(8), texels.clone()).unwrap();
            let next = map.downsample();
            let (nw, nh) = (std::cmp::max(w / 2, 2), std::cmp::max(h / 2, 2));
            assert_eq!((next.width(), next.height()), (nw, nh), "{w}x{h}");
            let at = |x: u32, y: u32| u32::from(texels[(y.min(h - 1) * w + x.min(w - 1)) as usize]);
            for y in 0..nh {
                for x in 0..nw {
                    let block = [(0, 0), (1, 0), (0, 1), (1, 1)];
                    let sum: u32 = block
                        .iter()
                        .map(|&(dx, dy)| at(2 * x + dx, 2 * y + dy))
                        .sum();
                    let want = (sum + 2) / 4;
                    assert_eq!(u32::from(next.get(x, y)), want, "{w}x{h} at ({x}, {y})");
                }
            }
        }
        // A tie rounds up: 1, 2, 1, 2 averages 1.5.
        let map = HeightMap::new(2, 2, Format::uint(8), vec![1, 2, 1, 2]).unwrap();
        assert_eq!(map.downsample().get(0, 0), 2);
    }
}
