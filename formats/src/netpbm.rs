//! 8-bit PGM images (binary P5 and ASCII P2) and PPM images (binary P6 and ASCII P3), read
//! strictly.

use std::path::Path;

/// A greyscale image of 8-bit samples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Pgm {
    pub width: u32,
    pub height: u32,
    pub maxval: u32,
    pub pixels: Vec<u8>,
}

/// Reads `path`; the error names the file and the problem.
pub fn read(path: &Path) -> Result<Pgm, String> {
    let bytes = crate::read_bounded(path, crate::MAX_INPUT_BYTES)?;
    parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses a P5 or P2 PGM with `maxval <= 255`.
pub fn parse(b: &[u8]) -> Result<Pgm, String> {
    netpbm(b, 1)
}

/// An RGB image of 8-bit samples (`pixels` holds r, g, b per pixel, rows top to bottom).
pub type Ppm = Pgm;

/// Reads a PPM; the error names the file and the problem.
pub fn read_ppm(path: &Path) -> Result<Ppm, String> {
    let bytes = crate::read_bounded(path, crate::MAX_INPUT_BYTES)?;
    parse_ppm(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses a P6 or P3 PPM with `maxval <= 255` (samples are not rescaled).
pub fn parse_ppm(b: &[u8]) -> Result<Ppm, String> {
    netpbm(b, 3)
}

/// The P6 encoding of an RGB image.
pub fn encode_ppm(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
    let mut v = format!("P6\n{width} {height}\n255\n").into_bytes();
    v.extend_from_slice(rgb);
    v
}

fn netpbm(b: &[u8], channels: usize) -> Result<Pgm, String> {
    let (kind, bin, asc) = if channels == 1 {
        ("PGM", b"P5", b"P2")
    } else {
        ("PPM", b"P6", b"P3")
    };
    let ascii = match b.get(..2) {
        Some(m) if m == bin => false,
        Some(m) if m == asc => true,
        _ => {
            return Err(format!(
                "not a {kind} (expected magic {} or {})",
                String::from_utf8_lossy(bin),
                String::from_utf8_lossy(asc)
            ))
        }
    };
    let mut pos = 2;
    let mut header = [0u32; 3];
    for (k, name) in ["width", "height", "maxval"].iter().enumerate() {
        header[k] =
            token(b, &mut pos)?.ok_or_else(|| format!("{kind} header ends before {name}"))?;
    }
    let [w, h, maxval] = header;
    if w == 0 || h == 0 {
        return Err(format!("{kind} size {w}x{h} is empty"));
    }
    if w > 65535 || h > 65535 {
        return Err(format!(
            "{kind} size {w}x{h} is too large (at most 65535 a side)"
        ));
    }
    if maxval == 0 || maxval > 255 {
        return Err(format!("maxval {maxval}: not an 8-bit {kind} (1..=255)"));
    }
    let n = w as usize * h as usize * channels;
    let pixels: Vec<u8> = if ascii {
        // Each sample takes a digit and a separator, so the bytes left bound what the file can
        // hold: a header declaring more is refused before anything is allocated for it.
        let room = (b.len() - pos).div_ceil(2);
        if n > room {
            return Err(format!(
                "{kind} declares {w}x{h} ({n} samples) but its {} bytes of samples hold at \
                 most {room}",
                b.len() - pos
            ));
        }
        let mut v = Vec::with_capacity(n);
        for k in 0..n {
            let x = token(b, &mut pos)?.ok_or_else(|| format!("{kind} has {k} of {n} samples"))?;
            if x > maxval {
                return Err(format!("sample {k} is {x}, above maxval {maxval}"));
            }
            v.push(x as u8);
        }
        if token(b, &mut pos)?.is_some() {
            return Err(format!("{kind} has more than {n} samples"));
        }
        v
    } else {
        // Exactly one whitespace byte after maxval, then the raster.
        if !b.get(pos).is_some_and(u8::is_ascii_whitespace) {
            return Err("no whitespace after maxval".into());
        }
        let data = &b[pos + 1..];
        if data.len() != n {
            return Err(format!(
                "raster has {} bytes, {w}x{h} needs {n}",
                data.len()
            ));
        }
        if let Some(k) = data.iter().position(|&x| u32::from(x) > maxval) {
            return Err(format!("sample {k} is {}, above maxval {maxval}", data[k]));
        }
        data.to_vec()
    };
    Ok(Pgm {
        width: w,
        height: h,
        maxval,
        pixels,
    })
}

/// The next decimal token, skipping whitespace and `#` comments.
fn token(b: &[u8], pos: &mut usize) -> Result<Option<u32>, String> {
    loop {
        match b.get(*pos) {
            None => return Ok(None),
            Some(c) if c.is_ascii_whitespace() => *pos += 1,
            Some(b'#') => {
                while b.get(*pos).is_some_and(|&c| c != b'\n') {
                    *pos += 1;
                }
            }
            Some(c) if c.is_ascii_digit() => break,
            Some(c) => {
                return Err(format!(
                    "unexpected byte {:?} in the header or samples",
                    *c as char
                ))
            }
        }
    }
    let start = *pos;
    while b.get(*pos).is_some_and(u8::is_ascii_digit) {
        *pos += 1;
    }
    let s = std::str::from_utf8(&b[start..*pos]).unwrap_or("");
    s.parse()
        .map(Some)
        .map_err(|_| format!("number {s} too large"))
}

/// The P5 encoding of an 8-bit image.
pub fn encode(width: u32, height: u32, pixels: &[u8]) -> Vec<u8> {
    let mut v = format!("P5\n{width} {height}\n255\n").into_bytes();
    v.extend_from_slice(pixels);
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_encodings_and_errors() {
        let p = parse(b"P2\n# c\n3 2\n255\n0 1 2\n3 4 255\n").unwrap();
        assert_eq!(
            (p.width, p.height, p.pixels.clone()),
            (3, 2, vec![0, 1, 2, 3, 4, 255])
        );
        let q = parse(&encode(3, 2, &p.pixels)).unwrap();
        assert_eq!(p.pixels, q.pixels);
        for bad in [
            &b"P6\n1 1\n255\n\0"[..],
            b"P5\n2 2\n255\n\0\0\0",
            b"P5\n2 2\n65535\n",
            b"P2\n2 1\n255\n1",
            b"P2\n2 1\n15\n1 16",
            b"P2\n0 1\n255\n",
            b"P2\n1 1\n255\n1 2",
            b"",
        ] {
            assert!(parse(bad).is_err(), "{:?}", String::from_utf8_lossy(bad));
        }
    }

    /// A plain (ASCII) header may declare any size up to 65535 a side; the parser refuses one
    /// its bytes cannot hold before allocating for it (65535x65535x3 would be 12 GB).
    #[test]
    fn ascii_sizes_are_checked_against_the_file_before_allocating() {
        for (b, ppm) in [
            (&b"P2\n65535 65535\n255\n1 2 3\n"[..], false),
            (&b"P3\n46341 46341\n255\n1 2 3\n"[..], true),
            (&b"P2\n2 2\n255\n1 2 3\n"[..], false),
        ] {
            let e = if ppm {
                parse_ppm(b).map(|_| ()).unwrap_err()
            } else {
                parse(b).map(|_| ()).unwrap_err()
            };
            assert!(e.contains("at most") || e.contains("has 3 of 4"), "{e}");
        }
        // Exactly enough bytes, the last sample without a separator, still parses.
        assert_eq!(parse(b"P2\n2 1\n9\n1 2").unwrap().pixels, vec![1, 2]);
    }

    #[test]
    fn ppm_both_encodings_and_errors() {
        let p = parse_ppm(b"P3\n2 1\n255\n1 2 3 4 5 6\n").unwrap();
        assert_eq!(p.pixels, vec![1, 2, 3, 4, 5, 6]);
        assert_eq!(parse_ppm(&encode_ppm(2, 1, &p.pixels)).unwrap(), p);
        for bad in [
            &b"P5\n1 1\n255\n\0"[..],
            b"P6\n1 1\n255\n\0\0",
            b"P3\n1 1\n255\n1 2",
            b"P6\n70000 1\n255\n",
        ] {
            assert!(
                parse_ppm(bad).is_err(),
                "{:?}",
                String::from_utf8_lossy(bad)
            );
        }
    }
}
