//! The derivative filters' panels of the report (para. 0086): a height map lit through each
//! filter's normals.

use crate::derivative::POS_FRAC;
use units::bump::derivative_0086::{DerivFilter, Derivative};
use units::bump::height_map::HeightMap;
use units::bump::params::Border;

/// Dot3 intensities (0..=255) of `map` at `zoom` samples a texel under light `l` with the
/// unit and `filter`, row by row.
pub fn render(map: &HeightMap, filter: DerivFilter, scale: f64, zoom: u32, l: [f64; 3]) -> Vec<u8> {
    let d = Derivative::new(filter, map.clone(), Border::Wrap, POS_FRAC);
    let (w, h) = (map.width() * zoom, map.height() * zoom);
    let s = (scale * 256.0).round() as i64;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let c = |k: u32| ((2 * i64::from(k) + 1) << POS_FRAC) / (2 * i64::from(zoom));
            let n = d.normal(c(x), c(y), s);
            let i: f64 = (0..3).map(|k| n[k] as f64 / 16384.0 * l[k]).sum();
            out.push((i.max(0.0) * 255.0).round().min(255.0) as u8);
        }
    }
    out
}
