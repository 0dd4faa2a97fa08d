//! `texrtl ptm fit|eval`: PTM micro-occlusion (001): a height map's occlusion under a dome
//! of lights fitted into an occlusion PTM by the fitter 604, and the PTM evaluated by the
//! light shader 608.

use super::{input, write_out, CmdError};
use clap::Subcommand;
use formats::ptm::Ptm;
use golden::ptm::Light;
use hdl::kernel::Sim;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use units::ptm::shader_608::Shader608;

/// PTM micro-occlusion: fit a height map's occlusion, evaluate a PTM.
#[derive(Subcommand, Debug)]
pub enum PtmCmd {
    /// Height map (PGM) and lights (CSV) to an occlusion PTM (.ptm) through the fitter 604.
    Fit {
        /// 8-bit PGM of heights, sides 2..=1024, tiled (its borders meet their opposites);
        /// a height is value x --height-scale texels.
        #[arg(long)]
        height: PathBuf,
        /// CSV with header elevation,azimuth: degrees, elevation in (0, 90], at least two
        /// elevations and 6..=1024 lights.
        #[arg(long)]
        lights: PathBuf,
        /// The PTM (`.ptm`, see `units::ptm`).
        #[arg(long)]
        out: PathBuf,
        /// Bits a stored coefficient: 8 or 16.
        #[arg(long, default_value_t = 8)]
        bits: u32,
        /// Texels a height level: 1/256 ..= 1.
        #[arg(long, default_value_t = 0.0625, value_parser = super::parse_finite)]
        height_scale: f64,
        /// JSON: texels, lights, bits, rmse_mean, rmse_max, ptm_bytes, images_bytes,
        /// shadow_map_bytes.
        #[arg(long)]
        stats: Option<PathBuf>,
    },
    /// A PTM's occlusion at given texels and lights through the shader 608.
    Eval {
        #[arg(long)]
        ptm: PathBuf,
        /// CSV with header x,y,lu,lv: a texel and the light in its tangent plane (lu^2 + lv^2
        /// <= 1, 14 fraction bits, rounded ties to even).
        #[arg(long)]
        queries: PathBuf,
        /// CSV: x,y,lu,lv,k,visibility, k and visibility uQ0.8 (0..=255) per query.
        #[arg(long)]
        out: PathBuf,
    },
}

/// Runs `fit` or `eval`.
pub fn run(c: &PtmCmd) -> Result<String, CmdError> {
    match c {
        PtmCmd::Fit {
            height,
            lights,
            out,
            bits,
            height_scale,
            stats,
        } => {
            let mut outs = vec![("--out", out.as_path())];
            outs.extend(stats.as_deref().map(|p| ("--stats", p)));
            let ins = [
                ("--height", height.as_path()),
                ("--lights", lights.as_path()),
            ];
            let guard = super::Outputs::check(&outs, &ins)?;
            guard.settle(fit(
                height,
                lights,
                out,
                *bits,
                *height_scale,
                stats.as_deref(),
            ))
        }
        PtmCmd::Eval { ptm, queries, out } => {
            let ins = [("--ptm", ptm.as_path()), ("--queries", queries.as_path())];
            let guard = super::Outputs::check(&[("--out", out.as_path())], &ins)?;
            guard.settle(eval(ptm, queries, out))
        }
    }
}

/// The lights of `path`.
fn read_lights(path: &Path) -> Result<Vec<Light>, String> {
    let t = formats::csv::read(path, &["elevation,azimuth"])?;
    let mut v = Vec::with_capacity(t.rows.len().min(1025));
    for r in &t.rows {
        let (e, a) = (t.finite(r, 0)?, t.finite(r, 1)?);
        if !(e > 0.0 && e <= 90.0) {
            let f = formats::shorten(&r.fields[0]);
            return Err(t.error(r, format!("elevation {f}: not in (0, 90]")));
        }
        if a.abs() > 360.0 {
            let f = formats::shorten(&r.fields[1]);
            return Err(t.error(r, format!("azimuth {f}: not in [-360, 360]")));
        }
        if v.len() == 1024 {
            return Err(format!("{}: more than 1024 lights", path.display()));
        }
        v.push(Light {
            elevation: e,
            azimuth: a,
        });
    }
    Ok(v)
}

fn fit(
    height: &Path,
    lights: &Path,
    out: &Path,
    bits: u32,
    scale: f64,
    stats: Option<&Path>,
) -> Result<String, CmdError> {
    if bits != 8 && bits != 16 {
        return Err(input(format!("--bits {bits}: 8 or 16")));
    }
    if !(1.0 / 256.0..=1.0).contains(&scale) {
        let s = formats::shorten(&scale.to_string());
        return Err(input(format!("--height-scale {s}: 1/256 ..= 1")));
    }
    let img = formats::netpbm::read(height).map_err(input)?;
    if img.width != img.height || !(2..=1024).contains(&img.width) {
        return Err(input(format!(
            "{}: {}x{}: a square of side 2..=1024",
            height.display(),
            img.width,
            img.height
        )));
    }
    let ls = read_lights(lights).map_err(input)?;
    tb::ptm::host_pinv(&ls).map_err(|e| input(format!("{}: {e}", lights.display())))?;
    let n = img.width as usize;
    let heights = img.pixels.iter().map(|&h| f64::from(h) * scale).collect();
    let sw = tb::ptm::Swatch::new(n, heights, ls);
    let (q, fmt) = tb::runs::ptm::fit_swatch(&sw, bits).map_err(input)?;
    let qual = tb::runs::ptm::quality(&sw, &q, &fmt);
    let ptm = Ptm {
        width: img.width,
        height: img.height,
        format: fmt,
        q: q.iter().flatten().copied().collect(),
    };
    write_out(out, &ptm.to_bytes())?;
    if let Some(s) = stats {
        let json = serde_json::to_vec_pretty(&qual).map_err(|e| input(e.to_string()))?;
        write_out(s, &json)?;
    }
    Ok(format!(
        "{}: {n}x{n} texels of {} lights, {bits}-bit coefficients; fit RMSE a texel {:.3} mean, {:.3} worst; {} bytes (binary images {}, shadow maps {})",
        out.display(),
        qual.lights,
        qual.rmse_mean,
        qual.rmse_max,
        qual.ptm_bytes,
        qual.images_bytes,
        qual.shadow_map_bytes
    ))
}

/// The queries of `path` inside `ptm`: texel and raw (u, v).
fn read_queries(path: &Path, ptm: &Ptm) -> Result<Vec<(u32, u32, i64, i64)>, String> {
    let t = formats::csv::read(path, &["x,y,lu,lv"])?;
    let mut v = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let bad = |c: usize, what: String| {
            t.error(
                r,
                format!(
                    "{} {}: {what}",
                    t.columns[c],
                    formats::shorten(&r.fields[c])
                ),
            )
        };
        let x: u32 = t.parse(r, 0, "a texel column")?;
        let y: u32 = t.parse(r, 1, "a texel row")?;
        if x >= ptm.width {
            return Err(bad(0, format!("outside 0..{}", ptm.width)));
        }
        if y >= ptm.height {
            return Err(bad(1, format!("outside 0..{}", ptm.height)));
        }
        let q = |c: usize| -> Result<i64, String> {
            let f = t.finite(r, c)?;
            Ok((f * 16384.0).round_ties_even().clamp(-32768.0, 32767.0) as i64)
        };
        let (u, w) = (q(2)?, q(3)?);
        if u * u + w * w > 1 << 28 {
            return Err(t.error(r, "the light (lu, lv) is outside the unit disc"));
        }
        v.push((x, y, u, w));
    }
    Ok(v)
}

fn eval(ptm_path: &Path, queries: &Path, out: &Path) -> Result<String, CmdError> {
    let ptm = Ptm::read(ptm_path).map_err(input)?;
    let qs = read_queries(queries, &ptm).map_err(input)?;
    let mut sim = Sim::new(Shader608::new(ptm.format).map_err(input)?);
    sim.reset(1);
    let mut csv = String::from("x,y,lu,lv,k,visibility\n");
    for &(x, y, u, v) in &qs {
        let d = &mut sim.dut;
        d.in_valid.set_bool(true);
        for (s, c) in d.q.iter_mut().zip(ptm.texel(x, y)) {
            s.set_bits(c);
        }
        d.u.set_raw(u);
        d.v.set_raw(v);
        sim.step();
        let (k, vis) = (sim.dut.k.q().bits(), sim.dut.visibility.q().bits());
        let f = |r: i64| r as f64 / 16384.0;
        let _ = writeln!(csv, "{x},{y},{},{},{k},{vis}", f(u), f(v));
    }
    write_out(out, csv.as_bytes())?;
    Ok(format!("{} queries written to {}", qs.len(), out.display()))
}
