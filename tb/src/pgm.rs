//! 8-bit PGM images (binary P5 and ASCII P2), read strictly, written atomically.

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
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses a P5 or P2 PGM with `maxval <= 255`.
pub fn parse(b: &[u8]) -> Result<Pgm, String> {
    let ascii = match b.get(..2) {
        Some(b"P5") => false,
        Some(b"P2") => true,
        _ => return Err("not a PGM (expected magic P5 or P2)".into()),
    };
    let mut pos = 2;
    let mut header = [0u32; 3];
    for (k, name) in ["width", "height", "maxval"].iter().enumerate() {
        header[k] = token(b, &mut pos)?.ok_or_else(|| format!("PGM header ends before {name}"))?;
    }
    let [w, h, maxval] = header;
    if w == 0 || h == 0 {
        return Err(format!("PGM size {w}x{h} is empty"));
    }
    if maxval == 0 || maxval > 255 {
        return Err(format!("maxval {maxval}: not an 8-bit PGM (1..=255)"));
    }
    let n = w as usize * h as usize;
    let pixels: Vec<u8> = if ascii {
        let mut v = Vec::with_capacity(n);
        for k in 0..n {
            let x = token(b, &mut pos)?.ok_or_else(|| format!("PGM has {k} of {n} samples"))?;
            if x > maxval {
                return Err(format!("sample {k} is {x}, above maxval {maxval}"));
            }
            v.push(x as u8);
        }
        if token(b, &mut pos)?.is_some() {
            return Err(format!("PGM has more than {n} samples"));
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
                    "unexpected byte {:?} in PGM header or samples",
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
}
