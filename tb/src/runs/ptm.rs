//! `texrtl ptm`: a swatch's samples fitted by the clocked fitter 604, and how well the stored
//! PTM reproduces them (through the shader's integer reference) and what it costs to store.

use crate::ptm::{host_pinv, ref_k, run_fitter, Swatch};
use hdl::kernel::Sim;
use units::ptm::fitter_604::Fitter604;
use units::ptm::texture_612::PtmFormat;

/// How well a PTM fits its samples, and what it costs to store.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PtmQuality {
    pub texels: usize,
    pub lights: usize,
    pub bits: u32,
    /// Per texel: the RMS over the lights of the stored PTM's occlusion (the shader's, exact)
    /// against the marched samples, in [0, 1]; its mean and largest over the texels.
    pub rmse_mean: f64,
    pub rmse_max: f64,
    /// Bytes: the PTM (six coefficients a texel, no header), the binary sample images (one
    /// bit a texel a light), a 4096 x 4096 shadow map of 32-bit depths (\[0006\]) per light.
    pub ptm_bytes: u64,
    pub images_bytes: u64,
    pub shadow_map_bytes: u64,
}

/// The quality of the fits `q` (one a texel) of `sw` stored as `fmt`.
pub fn quality(sw: &Swatch, q: &[[u64; 6]], fmt: &PtmFormat) -> PtmQuality {
    let uv: Vec<(i64, i64)> = sw
        .lights
        .iter()
        .map(|l| {
            let (u, v) = l.uv();
            let r = |x: f64| (x * 16384.0).round() as i64;
            (r(u), r(v))
        })
        .collect();
    let mut rmse = Vec::with_capacity(q.len());
    for (t, c) in q.iter().enumerate() {
        let s = sw.texel_samples(t);
        let se: f64 = uv
            .iter()
            .zip(s)
            .map(|(&(u, v), &x)| {
                let k = f64::from(ref_k(fmt, c, u, v)) / 256.0;
                (k - (1.0 - f64::from(x) / 255.0)).powi(2)
            })
            .sum();
        rmse.push((se / s.len() as f64).sqrt());
    }
    let texels = q.len();
    let lights = sw.lights.len();
    PtmQuality {
        texels,
        lights,
        bits: fmt.bits,
        rmse_mean: rmse.iter().sum::<f64>() / texels.max(1) as f64,
        rmse_max: rmse.iter().copied().fold(0.0, f64::max),
        ptm_bytes: (6 * texels as u64 * u64::from(fmt.bits)).div_ceil(8),
        images_bytes: (texels as u64 * lights as u64).div_ceil(8),
        shadow_map_bytes: 4096 * 4096 * 4 * lights as u64,
    }
}

/// The fits of every texel of `sw` through the clocked fitter.
pub fn fit_swatch(sw: &Swatch, bits: u32) -> Result<(Vec<[u64; 6]>, PtmFormat), String> {
    let p = host_pinv(&sw.lights)?;
    let fmt = PtmFormat::for_pinv(&p, bits)?;
    let (q, _) = run_fitter(Sim::new(Fitter604::new(p, fmt)?), &sw.samples);
    Ok((q, fmt))
}
