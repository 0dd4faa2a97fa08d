//! `texrtl texram`: trilinear texture accesses through the cycle-accurate TEXRAM chip of
//! Figure 8 (the luminance configuration; the others are not modelled yet).

use super::{input, write_out, CmdError};
use hdl::texram::Border;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::texram::{run_texram, TexReq};

/// Trilinear accesses through the cycle-accurate TEXRAM chip (Figure 8).
#[derive(Clone, Debug, clap::Args)]
pub struct TexramArgs {
    /// The texture: an 8-bit PGM (P5 or P2), sides powers of two up to 1024; its mipmap is
    /// built as the generator 816 rounds, (a+b+c+d+2)>>2.
    #[arg(long)]
    pub texture: PathBuf,
    /// CSV with header u,v,lambda: level-0 texel units (texel centres at k + 0.5), the level of
    /// detail -4..=10; rounded to 8 fraction bits, ties to even.
    #[arg(long)]
    pub requests: PathBuf,
    /// CSV: u,v,lambda,r,g,b,a per request in order (as quantised; luminance in all four).
    #[arg(long)]
    pub out: PathBuf,
    /// luminance (the others of section 6, index, truecolor and planar, are not modelled yet).
    #[arg(long, default_value = "luminance")]
    pub config: String,
    /// wrap, clamp, mirror or border:N (N 0..=255, the border colour).
    #[arg(long, default_value = "wrap")]
    pub border: String,
    /// JSON: accesses, slots, page_faults (accesses that took a second slot), bank_misses,
    /// bank_conflicts, video_slots, cycles, ns, pixels_per_second.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Waveform of the chip (one scope per unit: 812, 824, 810, 818).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// The texture as `2^wl x 2^hl` luminance texels.
fn read_texture(path: &Path) -> Result<(Vec<u8>, u32, u32), String> {
    let img = formats::netpbm::read(path)?;
    let log2 = |n: u32, what: &str| {
        if n.is_power_of_two() && n <= 1024 {
            Ok(n.trailing_zeros())
        } else {
            Err(format!(
                "{}: {what} {n} is not a power of two up to 1024",
                path.display()
            ))
        }
    };
    let (wl, hl) = (log2(img.width, "width")?, log2(img.height, "height")?);
    if img.maxval != 255 {
        return Err(format!(
            "{}: maxval {}, 8-bit texels need 255",
            path.display(),
            img.maxval
        ));
    }
    Ok((img.pixels, wl, hl))
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
    match a.config.as_str() {
        "luminance" => {}
        "index" | "truecolor" | "planar" => {
            return Err(input(format!(
                "--config {}: not modelled yet (luminance is)",
                a.config
            )))
        }
        c => {
            let c = formats::shorten(c);
            return Err(input(format!(
                "--config {c}: luminance, index, truecolor or planar"
            )));
        }
    }
    let border = Border::parse(&a.border).ok_or_else(|| {
        let b = formats::shorten(&a.border);
        input(format!(
            "--border {b}: wrap, clamp, mirror or border:N (N 0..=255)"
        ))
    })?;
    let (level0, wl, hl) = read_texture(&a.texture).map_err(input)?;
    let reqs = read_requests(&a.requests).map_err(input)?;
    let run = run_texram(&level0, (wl, hl), border, &reqs, a.vcd.as_deref()).map_err(input)?;
    let mut csv = String::from("u,v,lambda,r,g,b,a\n");
    for (q, x) in reqs.iter().zip(&run.values) {
        let f = |r: i32| f64::from(r) / 256.0;
        let _ = writeln!(csv, "{},{},{},{x},{x},{x},{x}", f(q.u), f(q.v), f(q.lambda));
    }
    write_out(&a.out, csv.as_bytes())?;
    if let Some(s) = &a.stats {
        let json = serde_json::to_vec_pretty(&run.stats).map_err(|e| input(e.to_string()))?;
        write_out(s, &json)?;
    }
    let st = &run.stats;
    Ok(format!(
        "{} accesses written to {}: {} slots, {} page faults, {:.2} M pixels/s",
        st.accesses,
        a.out.display(),
        st.slots,
        st.page_faults,
        st.pixels_per_second / 1e6
    ))
}
