//! The arithmetic of one resample point (the trilinear interpolator 818 in volume mode).
//!
//! * Weights: the point's fractions (12 bits each) truncated to 8 bits, `a`, `b`, `c` along
//!   x, y, z [C, as the texture path's]; the eight corner weights `(256 - a | a)(256 - b | b)
//!   (256 - c | c)` sum to `2^24`.
//! * Value: the exact weighted sum of the eight voxels, rounded once half up to u8:
//!   `(S + 2^23) >> 24`.
//! * Gradient \[C\]: central differences at the eight corners without the 1/2,
//!   `g_x = f(x+1) - f(x-1)` (s9, exact), the same weights, rounded once half up to sQ9.4:
//!   `(S + 2^19) >> 20`. A linear field `ax + by + cz + d` gives `(2a, 2b, 2c)` exactly at
//!   every point whose neighbours are inside the volume.
//!
//! Voxel buffer (32 bytes), as the eight accesses of gradient mode bring them, 4 voxels an
//! access in the order of [`super::layout::access_voxels`]: `buf[4a + t]`.

/// Fraction bits of the gradient output.
pub const GRAD_FRAC: u32 = 4;

/// The eight corner weights of fractions `a`, `b`, `c` (8 bits), corner `(dx, dy, dz)` at
/// index `dx + 2 dy + 4 dz`.
pub fn weights(a: u8, b: u8, c: u8) -> [u64; 8] {
    let w = |f: u8, one: bool| {
        if one {
            u64::from(f)
        } else {
            256 - u64::from(f)
        }
    };
    std::array::from_fn(|n| w(a, n & 1 == 1) * w(b, n & 2 == 2) * w(c, n & 4 == 4))
}

/// Voxel of corner `(dx, dy, dz)` offset by `(ox, oy, oz)` (each -1..=1 with at most one
/// nonzero) from the buffer of gradient (or value) mode.
fn voxel(
    buf: &[u8; 32],
    (dx, dy, dz): (usize, usize, usize),
    (ox, oy, oz): (i32, i32, i32),
) -> i64 {
    let t = |x: usize, y: usize| x + 2 * y;
    let at = match (ox, oy, oz) {
        // Columns i-1 (slot 0) and i+2 (slot 1) of accesses 3-4: x = -1 or 2.
        (-1, 0, 0) | (1, 0, 0) => {
            let x = dx as i32 + ox;
            if (0..=1).contains(&x) {
                4 * dz + t(x as usize, dy)
            } else {
                8 + 4 * dz + t(usize::from(x == 2), dy)
            }
        }
        (0, -1, 0) | (0, 1, 0) => {
            let y = dy as i32 + oy;
            if (0..=1).contains(&y) {
                4 * dz + t(dx, y as usize)
            } else {
                16 + 4 * dz + t(dx, usize::from(y == 2))
            }
        }
        // Along z (and no offset, z = dz): slices k-1 and k+2 beyond the 2x2x2.
        _ => {
            let z = dz as i32 + oz;
            if (0..=1).contains(&z) {
                4 * z as usize + t(dx, dy)
            } else {
                24 + 4 * usize::from(z == 2) + t(dx, dy)
            }
        }
    };
    i64::from(buf[at])
}

/// The value at the point: the 2x2 of slices k (`buf[0..4]`) and k+1 (`buf[4..8]`).
pub fn value(buf: &[u8; 32], w: &[u64; 8]) -> u8 {
    let s: u64 = (0..8)
        .map(|n| u64::from(buf[4 * (n >> 2) + (n & 3)]) * w[n])
        .sum();
    ((s + (1 << 23)) >> 24) as u8
}

/// The gradient at the point (raw sQ9.4 each): central differences at the corners, weighed.
pub fn gradient(buf: &[u8; 32], w: &[u64; 8]) -> [i64; 3] {
    let axes = [(1, 0, 0), (0, 1, 0), (0, 0, 1)];
    axes.map(|(ax, ay, az)| {
        let s: i64 = (0..8)
            .map(|n| {
                let c = (n & 1, (n >> 1) & 1, n >> 2);
                let g = voxel(buf, c, (ax, ay, az)) - voxel(buf, c, (-ax, -ay, -az));
                g * w[n] as i64
            })
            .sum();
        (s + (1 << 19)) >> 20
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_2_24() {
        for (a, b, c) in [(0, 0, 0), (255, 255, 255), (1, 128, 77)] {
            assert_eq!(weights(a, b, c).iter().sum::<u64>(), 1 << 24);
        }
        assert_eq!(weights(0, 0, 0)[0], 1 << 24);
    }

    /// A linear field in the buffer (as the accesses bring it): the value at a corner is the
    /// voxel, the gradient (2a, 2b, 2c) at any weights.
    #[test]
    fn a_linear_field_has_its_exact_gradient() {
        let f = |x: i64, y: i64, z: i64| (3 * x + 5 * y + 7 * z + 40) as u8;
        let mut buf = [0u8; 32];
        // Voxels of the access table: (i, j, k) = (1, 1, 1).
        let acc: [([i64; 2], [i64; 2], i64); 8] = [
            ([0, 1], [0, 1], 0),
            ([0, 1], [0, 1], 1),
            ([-1, 2], [0, 1], 0),
            ([-1, 2], [0, 1], 1),
            ([0, 1], [-1, 2], 0),
            ([0, 1], [-1, 2], 1),
            ([0, 1], [0, 1], -1),
            ([0, 1], [0, 1], 2),
        ];
        for (a, (xs, ys, z)) in acc.iter().enumerate() {
            for t in 0..4 {
                buf[4 * a + t] = f(1 + xs[t & 1], 1 + ys[t >> 1], 1 + z);
            }
        }
        for (a, b, c) in [(0, 0, 0), (200, 13, 255), (128, 128, 128)] {
            let w = weights(a, b, c);
            assert_eq!(gradient(&buf, &w), [6 << 4, 10 << 4, 14 << 4]);
        }
        assert_eq!(value(&buf, &weights(0, 0, 0)), f(1, 1, 1));
        assert_eq!(
            value(&buf, &weights(0, 0, 255)),
            f(1, 1, 2),
            "c 255/256 of 7: 6.97 -> 7"
        );
    }
}
