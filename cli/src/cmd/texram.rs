//! `texrtl texram`: trilinear texture accesses through the cycle-accurate TEXRAM chip of
//! Figure 8, in the luminance, planar and literal ("truecolor") configurations.

use super::{input, write_out, CmdError};
use hdl::texram::{Border, Config, Drf};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::texram::{run_texram, TexReq};

/// Trilinear accesses through the cycle-accurate TEXRAM chip (Figure 8).
#[derive(Clone, Debug, clap::Args)]
pub struct TexramArgs {
    /// The texture: an 8-bit PGM (P5 or P2, luminance) or PPM (P6 or P3, planar and
    /// truecolor: square, up to 512, the four components fill a space twice as wide and high),
    /// sides powers of two up to 1024; its mipmap is built as the generator 816 rounds,
    /// (a+b+c+d+2)>>2.
    #[arg(long)]
    pub texture: PathBuf,
    /// CSV with header u,v,lambda: level-0 texel units (texel centres at k + 0.5), the level of
    /// detail -4..=10; rounded to 8 fraction bits, ties to even.
    #[arg(long)]
    pub requests: PathBuf,
    /// CSV: u,v,lambda,r,g,b,a per request in order (as quantised; luminance in all four).
    #[arg(long)]
    pub out: PathBuf,
    /// luminance (PGM), planar (PPM, components in four planes: conflict-free, four accesses a
    /// pixel) or truecolor (PPM, the document's literal 2x2 cells: bank conflicts, counted);
    /// index is not in the command yet.
    #[arg(long, default_value = "luminance")]
    pub config: String,
    /// wrap, clamp, mirror or border:N (N 0..=255, the border colour).
    #[arg(long, default_value = "wrap")]
    pub border: String,
    /// JSON: requests, accesses (four a pixel in the colour layouts), slots, page_faults (slots
    /// they added), bank_misses, bank_conflicts, video_slots, cycles, ns, pixels_per_second.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Waveform of the chip (one scope per unit: 812, 824, 810, 818).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// `n` as log2 if a power of two up to `max`.
fn log2(path: &Path, what: &str, n: u32, max: u32) -> Result<u32, String> {
    if n.is_power_of_two() && n <= max {
        Ok(n.trailing_zeros())
    } else {
        Err(format!(
            "{}: {what} {n} is not a power of two up to {max}",
            path.display()
        ))
    }
}

/// The texture as the chip stores it for `config`: the DRF and its space's level 0.
/// Luminance: a PGM as it is. Planar: a PPM's R, G, B planes and an opaque alpha in the
/// quadrants of a space twice as wide and high; truecolor: the same components in 2x2 cells.
fn read_texture(path: &Path, config: Config, border: Border) -> Result<(Drf, Vec<u8>), String> {
    if config == Config::Luminance {
        let img = formats::netpbm::read(path)?;
        let wl = log2(path, "width", img.width, 1024)?;
        let hl = log2(path, "height", img.height, 1024)?;
        if img.maxval != 255 {
            return Err(format!(
                "{}: maxval {}, 8-bit texels need 255",
                path.display(),
                img.maxval
            ));
        }
        return Ok((Drf::new(wl, hl, border), img.pixels));
    }
    let img = formats::netpbm::read_ppm(path)?;
    let wl = log2(path, "width", img.width, 512)?;
    let hl = log2(path, "height", img.height, 512)?;
    let mut drf = Drf::new(wl + 1, hl + 1, border);
    drf.config = config;
    let plane = drf.component_map();
    let (w, h) = (img.width as usize, img.height as usize);
    let mut space = vec![0u8; 4 * w * h];
    for y in 0..h {
        for x in 0..w {
            for c in 0..4u32 {
                let t = if c == 3 {
                    255
                } else {
                    img.pixels[3 * (y * w + x) + c as usize]
                };
                let (gx, gy) = config.place(&plane, c, 0, x as u32, y as u32);
                space[gy as usize * 2 * w + gx as usize] = t;
            }
        }
    }
    Ok((drf, space))
}

/// Requests from the CSV, quantised and range-checked (u, v: sQ12.8; lambda: -4..=10).
fn read_requests(path: &Path) -> Result<Vec<TexReq>, String> {
    let t = formats::csv::read(path, &["u,v,lambda"])?;
    let mut v = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let mut raw = [0i32; 3];
        for (k, (lo, hi)) in [(-4096.0, 4096.0), (-4096.0, 4096.0), (-4.0, 10.0)]
            .into_iter()
            .enumerate()
        {
            let x = t.finite(r, k)?;
            let q = (x * 256.0).round_ties_even() / 256.0;
            let inside = if k == 2 {
                q >= lo && q <= hi
            } else {
                q >= lo && q < hi
            };
            if !inside {
                let name = &t.columns[k];
                let f = formats::shorten(&r.fields[k]);
                return Err(t.error(r, format!("{name} {f} outside {lo}..{hi}")));
            }
            raw[k] = (q * 256.0) as i32;
        }
        v.push(TexReq {
            u: raw[0],
            v: raw[1],
            lambda: raw[2],
        });
    }
    Ok(v)
}

/// `texrtl texram`.
pub fn run(a: &TexramArgs) -> Result<String, CmdError> {
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.stats.as_deref().map(|p| ("--stats", p)));
    outs.extend(a.vcd.as_deref().map(|p| ("--vcd", p)));
    let ins = [
        ("--texture", a.texture.as_path()),
        ("--requests", a.requests.as_path()),
    ];
    let guard = super::Outputs::check(&outs, &ins)?;
    guard.settle(texram(a))
}

/// The command once its outputs are checked.
fn texram(a: &TexramArgs) -> Result<String, CmdError> {
    let config =
        match a.config.as_str() {
            "luminance" => Config::Luminance,
            "planar" => Config::Planar,
            "truecolor" => Config::Literal,
            "index" => return Err(input(
                "--config index: not in the command yet (its upper levels need host-made palettes)"
                    .into(),
            )),
            c => {
                let c = formats::shorten(c);
                return Err(input(format!(
                    "--config {c}: luminance, index, truecolor or planar"
                )));
            }
        };
    let border = Border::parse(&a.border).ok_or_else(|| {
        let b = formats::shorten(&a.border);
        input(format!(
            "--border {b}: wrap, clamp, mirror or border:N (N 0..=255)"
        ))
    })?;
    let (drf, level0) = read_texture(&a.texture, config, border).map_err(input)?;
    let reqs = read_requests(&a.requests).map_err(input)?;
    let run = run_texram(&level0, drf, &reqs, a.vcd.as_deref()).map_err(input)?;
    let mut csv = String::from("u,v,lambda,r,g,b,a\n");
    for (q, [r, g, b, al]) in reqs.iter().zip(&run.values) {
        let f = |r: i32| f64::from(r) / 256.0;
        let _ = writeln!(
            csv,
            "{},{},{},{r},{g},{b},{al}",
            f(q.u),
            f(q.v),
            f(q.lambda)
        );
    }
    write_out(&a.out, csv.as_bytes())?;
    if let Some(s) = &a.stats {
        let json = serde_json::to_vec_pretty(&run.stats).map_err(|e| input(e.to_string()))?;
        write_out(s, &json)?;
    }
    let st = &run.stats;
    Ok(format!(
        "{} pixels written to {}: {} accesses in {} slots, {} page faults, {:.2} M pixels/s",
        st.requests,
        a.out.display(),
        st.accesses,
        st.slots,
        st.page_faults,
        st.pixels_per_second / 1e6
    ))
}
