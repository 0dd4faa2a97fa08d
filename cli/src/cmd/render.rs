//! `texrtl render`: Dot3-lit pictures of a height map (FIG. 8a against 8b).

use super::normals::read_height;
use super::widths::Widths;
use super::{parse_finite, write_out, CmdError};
use clap::Args;
use std::path::PathBuf;
use tb::pictures::lighting::render_png;

/// Pixels of one panel at most (1024 x 1024: about 2.5 s and 190 MB on 2 cores; past it the
/// four panels' normals runs grow beyond a few seconds and hundreds of megabytes).
const MAX_PANEL_PIXELS: u64 = 1 << 20;

/// Dot3-lit pictures: Blinn | B-spline (bit-exact) | golden | error heat map.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Height map: 8-bit PGM.
    #[arg(long)]
    pub height: PathBuf,
    /// Output PNG.
    #[arg(long)]
    pub out: PathBuf,
    /// Light direction X,Y,Z (normalised).
    #[arg(long, default_value = "1,1,2", value_parser = parse_light, allow_hyphen_values = true)]
    pub light: [f64; 3],
    /// Height scale factor.
    #[arg(long, default_value_t = 1.0, value_parser = parse_finite)]
    pub scale: f64,
    /// Pixels per texel (a power of two up to 64; a panel is at most 1024x1024 pixels).
    #[arg(long, default_value_t = 4)]
    pub zoom: u32,
    #[command(flatten)]
    pub widths: Widths,
}

/// Parses `X,Y,Z` (a non-zero, finite light direction).
pub fn parse_light(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("light '{s}' is not X,Y,Z"))?;
    if v.len() != 3 || v.iter().any(|x| !x.is_finite()) || v.iter().all(|x| *x == 0.0) {
        return Err(format!(
            "light '{s}' must be three finite numbers, not all zero"
        ));
    }
    Ok([v[0], v[1], v[2]])
}

/// `texrtl render`: Dot3-lit pictures of the height map, side by side: Blinn (bit-exact) |
/// B-spline (bit-exact) | golden B-spline | heat map of |B-spline - golden| in intensity
/// (log scale, black = below 2^-24, white = 2^-8 or more). Returns a summary.
pub fn run(a: &RenderArgs) -> Result<String, CmdError> {
    super::check_outputs(
        &[("--out", a.out.as_path())],
        &[("--height", a.height.as_path())],
    )?;
    if !a.zoom.is_power_of_two() || a.zoom > 64 {
        return Err(CmdError::Input(format!(
            "--zoom {}: a power of two up to 64",
            a.zoom
        )));
    }
    let p = a.widths.params()?;
    // The scale every pixel shares, checked before the height map is read, named as the option.
    let at_origin = tb::runs::normals::Sample {
        u: 0.0,
        v: 0.0,
        scale: a.scale,
        lod: 0.0,
    };
    tb::runs::normals::quantise(&p, &at_origin).map_err(|e| CmdError::Input(format!("--{e}")))?;
    let map = read_height(&a.height, &p)?;
    let (w, h) = (map.width() * a.zoom, map.height() * a.zoom);
    if u64::from(w) * u64::from(h) > MAX_PANEL_PIXELS {
        return Err(CmdError::Input(format!(
            "{}: {w}x{h} pixels per panel is too large (1024x1024 at most: lower --zoom)",
            a.height.display()
        )));
    }
    if a.out.is_dir() {
        return Err(CmdError::Input(format!(
            "{}: is a directory",
            a.out.display()
        )));
    }
    let (png, worst) = render_png(&map, &p, a.light, a.scale, a.zoom).map_err(CmdError::Input)?;
    write_out(&a.out, &png)?;
    Ok(format!(
        "{}: {w}x{h} per panel: Blinn | B-spline (bit-exact) | golden | heat map of |B-spline - golden| (log scale 2^-24..2^-8); worst intensity error {worst:.3e}",
        a.out.display()
    ))
}
