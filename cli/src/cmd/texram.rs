//! `texrtl texram`: trilinear texture accesses through the cycle-accurate TEXRAM chip of
//! Figure 8, in the luminance, index, planar and literal ("truecolor") configurations.

use super::{input, write_out, CmdError};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::runs::texram::{run_texram, TexramTexture};
use tb::texram::TexReq;
use units::texram::clut_814::Clut;
use units::texram::{Border, Config, Drf};

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
    /// luminance (PGM), index (PPM of at most 256 colours: the CLUT, host-made upper levels),
    /// planar (PPM, components in four planes: conflict-free, four accesses a pixel) or
    /// truecolor (PPM, the document's literal 2x2 cells: bank conflicts, counted).
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

/// The texture as the chip stores it for `config`. Luminance: a PGM as it is. Planar: a
/// PPM's R, G, B planes and an opaque alpha in the quadrants of a space twice as wide and
/// high; truecolor: the same components in 2x2 cells. Index: a PPM of at most 256 colours,
/// its palette in the CLUT; its upper levels made by the host (see [`index_levels`]).
fn read_texture(path: &Path, config: Config, border: Border) -> Result<TexramTexture, String> {
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
        return Ok(TexramTexture::generated(
            Drf::new(wl, hl, border),
            &img.pixels,
        ));
    }
    let img = formats::netpbm::read_ppm(path)?;
    if config == Config::Index {
        let wl = log2(path, "width", img.width, 1024)?;
        let hl = log2(path, "height", img.height, 1024)?;
        let mut drf = Drf::new(wl, hl, border);
        drf.config = config;
        return index_levels(&img, drf).map_err(|e| format!("{}: {e}", path.display()));
    }
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
    Ok(TexramTexture::generated(drf, &space))
}

/// An index map \[C\]: the palette is the image's colours in order of first appearance (at
/// most 256, alpha 255); each upper level's texel is the palette entry nearest (squared RGB
/// distance, the lowest index on a tie) to the rounded mean colour of the 2x2 (or pair) below
/// it. The generator 816 cannot make these: it averages values, which means nothing for
/// indices.
fn index_levels(img: &formats::netpbm::Ppm, drf: Drf) -> Result<TexramTexture, String> {
    let mut palette: Vec<[u8; 3]> = Vec::new();
    let mut level0 = Vec::with_capacity(img.pixels.len() / 3);
    for px in img.pixels.chunks_exact(3) {
        let c = [px[0], px[1], px[2]];
        let i = match palette.iter().position(|p| *p == c) {
            Some(i) => i,
            None if palette.len() < 256 => {
                palette.push(c);
                palette.len() - 1
            }
            None => return Err("more than 256 colours: index mode holds 256".into()),
        };
        level0.push(i as u8);
    }
    let nearest = |c: [u32; 3]| -> u8 {
        let d = |p: &[u8; 3]| {
            (0..3)
                .map(|k| (i64::from(p[k]) - i64::from(c[k])).pow(2))
                .sum::<i64>()
        };
        (0..palette.len())
            .min_by_key(|&i| (d(&palette[i]), i))
            .unwrap_or(0) as u8
    };
    let mut levels = vec![level0];
    for k in 0..drf.max_level() {
        let (w, h) = drf.level_size(k);
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let prev = &levels[k as usize];
        let mut next = Vec::with_capacity((nw * nh) as usize);
        for y in 0..nh {
            for x in 0..nw {
                let (sx, sy) = (if w > 1 { 2 } else { 1 }, if h > 1 { 2 } else { 1 });
                let mut sum = [0u32; 3];
                for dy in 0..sy {
                    for dx in 0..sx {
                        let p =
                            palette[usize::from(prev[((y * sy + dy) * w + x * sx + dx) as usize])];
                        for c in 0..3 {
                            sum[c] += u32::from(p[c]);
                        }
                    }
                }
                let n = sx * sy;
                next.push(nearest(sum.map(|s| (s + n / 2) / n)));
            }
        }
        levels.push(next);
    }
    let mut entries = [0u32; 256];
    for (e, p) in entries.iter_mut().zip(&palette) {
        *e = u32::from_be_bytes([p[0], p[1], p[2], 255]);
    }
    Ok(TexramTexture {
        drf,
        levels,
        clut: Clut { entries },
    })
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
    let config = match a.config.as_str() {
        "luminance" => Config::Luminance,
        "planar" => Config::Planar,
        "truecolor" => Config::Literal,
        "index" => Config::Index,
        c => {
            let c = formats::shorten(c);
            return Err(input(format!(
                "--config {c}: luminance, index, truecolor or planar"
            )));
        }
    };
    let border = super::texture_border(&a.border)?;
    let tex = read_texture(&a.texture, config, border).map_err(input)?;
    let reqs = read_requests(&a.requests).map_err(input)?;
    let run = run_texram(&tex, &reqs, a.vcd.as_deref()).map_err(super::run_error)?;
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
