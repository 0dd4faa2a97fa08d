//! Golden model of bilinear texture filtering (Schilling & Knittel, Figure 6, unit 622),
//! in `f64`, written from the definition and sharing nothing with `hdl`.
//!
//! A texture is a function from integer texel positions to RGB values (0..=255 as reals).
//! The filtered colour at real position `(u, v)`, with `x0 = floor(u)`, `a = u - x0`,
//! `y0 = floor(v)`, `b = v - y0`, clamping positions to the texture (clamp to edge), is
//! `(1-a)(1-b) T(x0,y0) + a(1-b) T(x0+1,y0) + (1-a) b T(x0,y0+1) + a b T(x0+1,y0+1)`.

/// Bilinear filtering of `texel` (a `width x height` texture) at `(u, v)` in texel units,
/// `0 <= u < width`, `0 <= v < height`.
pub fn bilinear(
    texel: impl Fn(u32, u32) -> [f64; 3],
    width: u32,
    height: u32,
    u: f64,
    v: f64,
) -> [f64; 3] {
    let (xf, yf) = (u.floor(), v.floor());
    let (a, b) = (u - xf, v - yf);
    let clamp = |t: f64, n: u32| t.clamp(0.0, f64::from(n - 1)) as u32;
    let (x0, x1) = (clamp(xf, width), clamp(xf + 1.0, width));
    let (y0, y1) = (clamp(yf, height), clamp(yf + 1.0, height));
    let t = [texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1)];
    let w = [(1.0 - a) * (1.0 - b), a * (1.0 - b), (1.0 - a) * b, a * b];
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        *o = (0..4).map(|k| w[k] * t[k][c]).sum();
    }
    out
}

/// The hardware's error bound against [`bilinear`] of the same texels at the same (exactly
/// representable) position: the weights and products are exact, one round to nearest to an
/// integer follows, so at most half an LSB (plus `f64` rounding of the reference itself, far
/// below 1e-9 for 8-bit values).
pub const ERROR_BOUND_LSB: f64 = 0.5 + 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_and_midpoints() {
        let t = |x: u32, y: u32| [f64::from(x * 10 + y), 0.0, 255.0];
        assert_eq!(bilinear(t, 4, 4, 1.0, 2.0), [12.0, 0.0, 255.0]);
        assert_eq!(bilinear(t, 4, 4, 1.5, 2.5), [17.5, 0.0, 255.0]);
        // Clamped at the right edge: x0 = x1 = 3.
        assert_eq!(bilinear(t, 4, 4, 3.5, 0.0), [30.0, 0.0, 255.0]);
    }
}
