//! Built-in height maps, made procedurally, so no input file is needed.

use hdl::fx::Format;
use units::bump::height_map::HeightMap;

/// Names of the built-in maps.
pub const NAMES: [&str; 7] = [
    "flat", "steep", "steps", "noise", "smooth", "extremes", "bumps",
];

/// A built-in map of `w x h` texels in format `fmt` (raw texels 0..=max).
///
/// * `flat`: every texel at mid height;
/// * `steep`: columns alternating 0 and max: the steepest slope the format allows;
/// * `steps`: terraces four texels wide climbing by a quarter of the range, diagonally;
/// * `noise`: independent uniform texels from a fixed-seed generator;
/// * `smooth`: a sum of two sine waves;
/// * `extremes`: a checkerboard of 0 and max (steepest in both directions at once);
/// * `bumps`: round bumps on a grid (for pictures).
pub fn builtin(name: &str, w: u32, h: u32, fmt: Format) -> Result<HeightMap, String> {
    let max = fmt.max_raw() as u32;
    let mut t = Vec::with_capacity((w * h) as usize);
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    for y in 0..h {
        for x in 0..w {
            let v = match name {
                "flat" => max / 2,
                "steep" => (x % 2) * max,
                "steps" => (((x + y) / 4) % 4) * max / 3,
                "noise" => {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    (state % u64::from(max + 1)) as u32
                }
                "smooth" => {
                    let fx = f64::from(x) * std::f64::consts::TAU / 16.0;
                    let fy = f64::from(y) * std::f64::consts::TAU / 23.0;
                    let s = 0.5 + 0.3 * fx.sin() + 0.2 * (fy + 0.5 * fx).cos();
                    (s * f64::from(max)).round().clamp(0.0, f64::from(max)) as u32
                }
                "extremes" => ((x + y) % 2) * max,
                "bumps" => {
                    let (cx, cy) = ((x % 16) as f64 - 7.5, (y % 16) as f64 - 7.5);
                    let r2 = (cx * cx + cy * cy) / 36.0;
                    let s = if r2 < 1.0 { (1.0 - r2).sqrt() } else { 0.0 };
                    (s * f64::from(max)).round() as u32
                }
                _ => {
                    return Err(format!(
                        "unknown built-in map '{name}' (one of {})",
                        NAMES.join(", ")
                    ))
                }
            };
            t.push(v as u8);
        }
    }
    HeightMap::new(w, h, fmt, t)
}
