//! The `.ptm` file of `texrtl ptm`: an occlusion PTM (001) as the hardware stores it.
//!
//! ```text
//! texrtl-ptm 1\n
//! W H BITS\n                      sides 1..=4096, BITS 8 or 16
//! e1 b1 e2 b2 ... e6 b6\n         per coefficient: exponent 0..=40, bias (units of 2^-20)
//! W*H*6 coefficients              texels row by row, A1..A6 each; u8, or u16 little-endian
//! ```
//!
//! Coefficient j of stored q stands for `q 2^e_j + b_j` units of 2^-20
//! (`units::ptm::texture_612::PtmFormat`). Reading checks the header and the length before it
//! allocates anything of the declared size.

use units::ptm::texture_612::PtmFormat;

/// A PTM: its size, format and coefficients (`6 W H`, texel-major).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ptm {
    pub width: u32,
    pub height: u32,
    pub format: PtmFormat,
    pub q: Vec<u64>,
}

const MAGIC: &str = "texrtl-ptm 1";

impl Ptm {
    /// The six stored coefficients of texel `(x, y)`.
    pub fn texel(&self, x: u32, y: u32) -> [u64; 6] {
        let at = 6 * (y as usize * self.width as usize + x as usize);
        std::array::from_fn(|j| self.q[at + j])
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let f = &self.format;
        let mut head = format!("{MAGIC}\n{} {} {}\n", self.width, self.height, f.bits);
        let pairs: Vec<String> = (0..6)
            .map(|j| format!("{} {}", f.exp[j], f.bias[j]))
            .collect();
        head.push_str(&pairs.join(" "));
        head.push('\n');
        let mut b = head.into_bytes();
        for &q in &self.q {
            if f.bits == 8 {
                b.push(q as u8);
            } else {
                b.extend_from_slice(&(q as u16).to_le_bytes());
            }
        }
        b
    }

    pub fn parse(bytes: &[u8]) -> Result<Ptm, String> {
        let mut lines = Vec::new();
        let mut at = 0;
        for _ in 0..3 {
            let end = bytes[at..]
                .iter()
                .take(400)
                .position(|&c| c == b'\n')
                .ok_or("header: a line missing or over 400 bytes")?;
            let line = std::str::from_utf8(&bytes[at..at + end]).map_err(|_| "header: not text")?;
            lines.push(line);
            at += end + 1;
        }
        if lines[0] != MAGIC {
            return Err(format!(
                "not a texrtl PTM (first line '{}')",
                crate::shorten(lines[0])
            ));
        }
        let nums = |l: &str, n: usize, what: &str| -> Result<Vec<i64>, String> {
            let v: Vec<i64> = l
                .split_whitespace()
                .map(|t| t.parse::<i64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("{what}: '{}' is not {n} integers", crate::shorten(l)))?;
            if v.len() == n {
                Ok(v)
            } else {
                Err(format!(
                    "{what}: '{}' is not {n} integers",
                    crate::shorten(l)
                ))
            }
        };
        let size = nums(lines[1], 3, "size line")?;
        let (w, h, bits) = (size[0], size[1], size[2]);
        if !(1..=4096).contains(&w) || !(1..=4096).contains(&h) {
            return Err(format!("size {w}x{h}: sides 1..=4096"));
        }
        let ph = nums(lines[2], 12, "scale line")?;
        let fmt = PtmFormat {
            bits: u32::try_from(bits).map_err(|_| format!("bits {bits}: 8 or 16"))?,
            exp: std::array::from_fn(|j| ph[2 * j].clamp(0, 1 << 20) as u32),
            bias: std::array::from_fn(|j| ph[2 * j + 1]),
        };
        if ph.iter().step_by(2).any(|e| !(0..=40).contains(e)) {
            return Err("scale line: exponents 0..=40".into());
        }
        fmt.validate()?;
        let n = (w * h * 6) as usize;
        let need = n * (fmt.bits / 8) as usize;
        let body = &bytes[at..];
        if body.len() != need {
            return Err(format!(
                "{} bytes of coefficients, {w}x{h}x6 of {} bits need {need}",
                body.len(),
                fmt.bits
            ));
        }
        let q = if fmt.bits == 8 {
            body.iter().map(|&b| u64::from(b)).collect()
        } else {
            body.chunks_exact(2)
                .map(|c| u64::from(u16::from_le_bytes([c[0], c[1]])))
                .collect()
        };
        Ok(Ptm {
            width: w as u32,
            height: h as u32,
            format: fmt,
            q,
        })
    }

    pub fn read(path: &std::path::Path) -> Result<Ptm, String> {
        let b = crate::read_bounded(path, crate::MAX_INPUT_BYTES)?;
        Ptm::parse(&b).map_err(|e| format!("{}: {e}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_refusals() {
        for bits in [8, 16] {
            let p = Ptm {
                width: 3,
                height: 2,
                format: PtmFormat {
                    bits,
                    exp: [0, 1, 2, 3, 4, 40],
                    bias: [-5, 6, -7, 8, 0, -(1 << 39)],
                },
                q: (0..36).map(|k| k * 7 % 256).collect(),
            };
            let b = p.to_bytes();
            assert_eq!(Ptm::parse(&b).unwrap(), p);
            assert!(Ptm::parse(&b[..b.len() - 1])
                .unwrap_err()
                .contains("bytes of coefficients"));
        }
        let huge = b"texrtl-ptm 1\n4096 4096 16\n0 0 0 0 0 0 0 0 0 0 0 0\n";
        assert!(Ptm::parse(huge).unwrap_err().contains("need"));
        assert!(Ptm::parse(b"texrtl-ptm 1\n5000 1 8\n").is_err());
        assert!(Ptm::parse(b"P5\n").is_err());
        assert!(
            Ptm::parse(b"texrtl-ptm 1\n1 1 12\n0 0 0 0 0 0 0 0 0 0 0 0\n")
                .unwrap_err()
                .contains("bits")
        );
    }
}
