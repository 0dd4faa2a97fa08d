//! The PTM swatch in the report: marched truth over the stored PTM's visibility.

use crate::ptm::{ref_k, Swatch};
use crate::runs::ptm::{fit_swatch, quality, PtmQuality};
use golden::ptm::Light;

/// The report's swatch: a 32 x 32 woven cloth fitted under a 4 x 12 dome, then lit from four
/// directions at 30 degrees that are not in the dome: the marched truth (top row) and the
/// shader's visibility from the 8-bit PTM (bottom row), each `side` texels. Returns the
/// pixels (row-major, 4 side x 2 side) and the fit's quality.
pub fn swatch_picture() -> Result<(Vec<u8>, usize, PtmQuality), String> {
    let side = 32;
    let sw = Swatch::new(
        side,
        golden::ptm::woven(side, 2.5),
        golden::ptm::dome(4, 12),
    );
    let (q, fmt) = fit_swatch(&sw, 8)?;
    let qual = quality(&sw, &q, &fmt);
    let w = 4 * side;
    let mut px = vec![0u8; w * 2 * side];
    for k in 0..4 {
        let l = Light {
            elevation: 30.0,
            azimuth: 20.0 + 90.0 * k as f64,
        };
        let (u, v) = l.uv();
        let (u, v) = ((u * 16384.0).round() as i64, (v * 16384.0).round() as i64);
        for (t, qt) in q.iter().enumerate() {
            let (x, y) = (t % side, t / side);
            let truth = if golden::ptm::lit(&sw.heights, side, x, y, l) {
                255
            } else {
                0
            };
            px[y * w + k * side + x] = truth;
            px[(side + y) * w + k * side + x] = 255 - ref_k(&fmt, qt, u, v);
        }
    }
    Ok((px, side, qual))
}
