//! The derivative filters of Fenney's para. 0086 in f64, from their kernels: the height's
//! slope at the four texel centres around a point, interpolated bilinearly (the weights
//! truncated to 8 bits, as the hardware's address arithmetic declares), and the normal
//! `normalize(-Dx s, -Dy s, 1)`.

/// A kernel: central differences, Sobel, Prewitt, or antisymmetric taps along each axis.
#[derive(Clone, Debug, PartialEq)]
pub enum Kernel {
    Central,
    Sobel,
    Prewitt,
    Taps(Vec<f64>),
}

/// The slope `(dh/dx, dh/dy)` at texel `(x, y)` of the heights `h`.
pub fn slope_at(k: &Kernel, h: &dyn Fn(i64, i64) -> f64, x: i64, y: i64) -> (f64, f64) {
    let diff_x = |dy: i64, r: i64| h(x + r, y + dy) - h(x - r, y + dy);
    let diff_y = |dx: i64, r: i64| h(x + dx, y + r) - h(x + dx, y - r);
    match k {
        Kernel::Central => (diff_x(0, 1) / 2.0, diff_y(0, 1) / 2.0),
        Kernel::Sobel => (
            (diff_x(-1, 1) + 2.0 * diff_x(0, 1) + diff_x(1, 1)) / 8.0,
            (diff_y(-1, 1) + 2.0 * diff_y(0, 1) + diff_y(1, 1)) / 8.0,
        ),
        Kernel::Prewitt => (
            (diff_x(-1, 1) + diff_x(0, 1) + diff_x(1, 1)) / 6.0,
            (diff_y(-1, 1) + diff_y(0, 1) + diff_y(1, 1)) / 6.0,
        ),
        Kernel::Taps(c) => {
            let sx = c
                .iter()
                .enumerate()
                .map(|(i, ci)| ci * diff_x(0, i as i64 + 1))
                .sum();
            let sy = c
                .iter()
                .enumerate()
                .map(|(i, ci)| ci * diff_y(0, i as i64 + 1))
                .sum();
            (sx, sy)
        }
    }
}

/// The unit normal at `(u, v)` (texel units, centres at k + 1/2) with height scale `s`.
pub fn normal(k: &Kernel, h: &dyn Fn(i64, i64) -> f64, u: f64, v: f64, s: f64) -> [f64; 3] {
    let (x, y) = (u - 0.5, v - 0.5);
    let (i, j) = (x.floor(), y.floor());
    let t = |f: f64| (f * 256.0).floor() / 256.0;
    let (a, b) = (t(x - i), t(y - j));
    let (mut dx, mut dy) = (0.0, 0.0);
    for (oy, wy) in [(0, 1.0 - b), (1, b)] {
        for (ox, wx) in [(0, 1.0 - a), (1, a)] {
            let (gx, gy) = slope_at(k, h, i as i64 + ox, j as i64 + oy);
            dx += wx * wy * gx;
            dy += wx * wy * gy;
        }
    }
    let v = [-dx * s, -dy * s, 1.0];
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}
