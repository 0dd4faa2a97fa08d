//! Mipmap levels as real numbers: level k is the plain average of each `2^k x 2^k` block of
//! level 0 (once a side has reached one texel, blocks stop growing along it).
//!
//! Error bound of a chain of rounded box filters against these averages: level k averages
//! four (or two) level-(k-1) texels, so it inherits at most the largest error of its inputs,
//! and adds its own rounding. Round half up adds at most +1/2 LSB (`(s+2)>>2 - s/4` is one of
//! 0, -1/4, +1/2, +1/4; `(s+1)>>1 - s/2` one of 0, +1/2); truncation at most 3/4 LSB for
//! sums of four, 1/2 for pairs. Hence `|level k - average| <= sum of the per-level maxima`.

/// The block averages of level `k` of a `w x h` frame, row-major.
pub fn box_average(frame: &[u8], w: usize, h: usize, k: u32) -> Vec<f64> {
    let bw = (1usize << k).min(w);
    let bh = (1usize << k).min(h);
    let (lw, lh) = (w / bw, h / bh);
    let mut out = Vec::with_capacity(lw * lh);
    for by in 0..lh {
        for bx in 0..lw {
            let mut s = 0u64;
            for y in 0..bh {
                for x in 0..bw {
                    s += u64::from(frame[(by * bh + y) * w + bx * bw + x]);
                }
            }
            out.push(s as f64 / (bw * bh) as f64);
        }
    }
    out
}

/// The bound above for level `k` of a `w x h` frame, in LSBs; `round`: round half up, else
/// truncation.
pub fn error_bound(w: usize, h: usize, k: u32, round: bool) -> f64 {
    let (mut lw, mut lh) = (w, h);
    let mut b = 0.0;
    for _ in 0..k {
        let four = lw > 1 && lh > 1;
        b += match (round, four) {
            (true, _) => 0.5,
            (false, true) => 0.75,
            (false, false) => 0.5,
        };
        lw = (lw / 2).max(1);
        lh = (lh / 2).max(1);
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averages_and_bounds() {
        let f: Vec<u8> = (0..32).collect(); // 8 x 4
        let l1 = box_average(&f, 8, 4, 1);
        assert_eq!(l1.len(), 8);
        assert_eq!(l1[0], (0.0 + 1.0 + 8.0 + 9.0) / 4.0);
        let l3 = box_average(&f, 8, 4, 3); // blocks 8 x 4: one texel
        assert_eq!(l3, vec![15.5]);
        assert_eq!(error_bound(8, 4, 3, true), 1.5);
        assert_eq!(error_bound(8, 4, 3, false), 0.75 + 0.75 + 0.5);
    }
}
