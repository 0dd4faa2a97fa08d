//! Packed heights of para. 0055 (Fenney; GB2297886's interleave): four 8-bit heights of a
//! 2 x 2 block in one 32-bit colour word, so that the 3 x 3 window of the B-spline surface
//! around any sample spans exactly 2 x 2 words: four fetches (units 60-63), one a word.
//!
//! Word `(x >> 1, y >> 1)` holds texel `(x, y)` in byte `2 (y & 1) + (x & 1)`.

/// The words of a `w x h` height map (even sides), row-major by word.
pub fn pack(w: u32, h: u32, heights: &[u8]) -> Result<Vec<u32>, String> {
    if !w.is_multiple_of(2) || !h.is_multiple_of(2) || heights.len() != (w * h) as usize {
        return Err(format!(
            "{w}x{h}: even sides and w h heights ({} given)",
            heights.len()
        ));
    }
    let (ww, wh) = (w / 2, h / 2);
    Ok((0..ww * wh)
        .map(|k| {
            let (bx, by) = (k % ww, k / ww);
            (0..4).fold(0u32, |acc, b| {
                let (x, y) = (2 * bx + (b & 1), 2 * by + (b >> 1));
                acc | u32::from(heights[(y * w + x) as usize]) << (8 * b)
            })
        })
        .collect())
}

/// The word holding texel `(x, y)` and its byte.
pub fn locate(x: u32, y: u32) -> ((u32, u32), u32) {
    ((x >> 1, y >> 1), 2 * (y & 1) + (x & 1))
}

/// The 3 x 3 window whose top-left texel is `(x, y)` (inside a `w x h` map, wrapped), read
/// from the words: the four words it needs (in fetch-unit order 60, 61, 62, 63) and the nine
/// heights row by row.
pub fn window(words: &[u32], w: u32, h: u32, x: u32, y: u32) -> ([(u32, u32); 4], [u8; 9]) {
    let ww = w / 2;
    let (bx, by) = (x >> 1, y >> 1);
    let wrap = |a: u32, n: u32| a % n;
    let fetch = [(bx, by), (bx + 1, by), (bx, by + 1), (bx + 1, by + 1)]
        .map(|(a, b)| (wrap(a, w / 2), wrap(b, h / 2)));
    let mut out = [0u8; 9];
    for (k, o) in out.iter_mut().enumerate() {
        let (tx, ty) = (wrap(x + (k % 3) as u32, w), wrap(y + (k / 3) as u32, h));
        let ((wx, wy), byte) = locate(tx, ty);
        debug_assert!(fetch.contains(&(wx, wy)));
        *o = (words[(wy * ww + wx) as usize] >> (8 * byte)) as u8;
    }
    (fetch, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exhaustively on a 16 x 12 map: every 3 x 3 window touches exactly its four words, each
    /// of them, and reads the heights the map holds.
    #[test]
    fn any_3x3_window_spans_exactly_2x2_words() {
        let (w, h) = (16u32, 12u32);
        let heights: Vec<u8> = (0..w * h).map(|k| (k * 37 % 251) as u8).collect();
        let words = pack(w, h, &heights).unwrap();
        for y in 0..h {
            for x in 0..w {
                let (fetch, got) = window(&words, w, h, x, y);
                let mut used = std::collections::BTreeSet::new();
                for k in 0..9u32 {
                    let (tx, ty) = ((x + k % 3) % w, (y + k / 3) % h);
                    used.insert(locate(tx, ty).0);
                    assert_eq!(got[k as usize], heights[(ty * w + tx) as usize]);
                }
                let want: std::collections::BTreeSet<_> = fetch.into_iter().collect();
                assert_eq!(used, want, "({x}, {y})");
                assert_eq!(used.len(), 4);
            }
        }
        // Even sides and every height given, each checked alone.
        assert!(pack(3, 2, &[0; 6]).is_err());
        assert!(pack(2, 3, &[0; 6]).is_err());
        assert!(pack(2, 2, &[0; 3]).is_err());
        assert!(pack(2, 2, &[0; 4]).is_ok());
    }
}
