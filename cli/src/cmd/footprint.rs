//! `texrtl footprint`: anisotropic filtering by footprint assembly (Schilling & Knittel
//! section 10) through the cycle-accurate setup unit, sample generator and accumulator in
//! front of the TEXRAM chip.

use super::{input, write_out, CmdError};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::footprint::Pixel;
use tb::runs::footprint::{run_footprint, run_footprint_texture, FootprintRun};
use units::footprint::setup_fig12::{NRounding, SetupParams, MAX_LOG2_N};
use units::texram::{Border, Drf};

/// Anisotropic filtering by footprint assembly (section 10) through the TEXRAM chip.
#[derive(Clone, Debug, clap::Args)]
pub struct FootprintArgs {
    /// The texture. --unit texram: an 8-bit PGM (P5 or P2), sides powers of two up to 1024,
    /// its mipmap built as the generator 816 rounds, (a+b+c+d+2)>>2. --unit texture: a .ccc
    /// file or a PPM (encoded to CCC), sides multiples of 4 up to 4096.
    #[arg(long)]
    pub texture: PathBuf,
    /// CSV with header u,v,dudx,dvdx,dudy,dvdy: the pixel centre (level-0 texel units,
    /// -4096..4096, 8 fraction bits) and its screen derivatives (-2048..2048, 8 fraction
    /// bits), rounded ties to even.
    #[arg(long)]
    pub requests: PathBuf,
    /// CSV: u,v,dudx,dvdx,dudy,dvdy (as quantised), n, lambda, then value (texram) or
    /// r,g,b (texture) per pixel in order.
    #[arg(long)]
    pub out: PathBuf,
    /// The most squares a pixel: a power of two, 1..=64.
    #[arg(long, default_value_t = 16)]
    pub max_n: u32,
    /// N rounded to a power of two in the log domain (log) or the linear one (linear).
    #[arg(long, default_value = "log")]
    pub rounding: String,
    /// texram (the TEXRAM chip of Figure 8: trilinear on a mipmap) or texture (the Figure 6
    /// texture unit 602: bilinear on a CCC texture, 4 fraction bits, cache and lookahead; the
    /// document's low-cost system).
    #[arg(long, default_value = "texram")]
    pub unit: String,
    /// wrap, clamp, mirror or border:N (N 0..=255, the border colour); texram only (the
    /// texture unit clamps to the edge).
    #[arg(long, default_value = "wrap")]
    pub border: String,
    /// JSON: pixels, accesses, mean_n, slots (texram), page_faults (texram: slots they added;
    /// texture: DRAM reads that opened another row), bank_misses (texram), cycles, ns,
    /// pixels_per_second.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Waveform: setup unit, generator, accumulator and the chip's units.
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// Pixels from the CSV, quantised and range-checked.
fn read_pixels(path: &Path) -> Result<Vec<Pixel>, String> {
    let t = formats::csv::read(path, &["u,v,dudx,dvdx,dudy,dvdy"])?;
    let mut v = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let mut raw = [0i32; 6];
        for (k, x) in raw.iter_mut().enumerate() {
            let lim = if k < 2 { 4096.0 } else { 2048.0 };
            let f = t.finite(r, k)?;
            let q = (f * 256.0).round_ties_even() / 256.0;
            if !(-lim..lim).contains(&q) {
                let name = &t.columns[k];
                let s = formats::shorten(&r.fields[k]);
                return Err(t.error(r, format!("{name} {s} outside -{lim}..{lim}")));
            }
            *x = (q * 256.0) as i32;
        }
        v.push(Pixel {
            u: raw[0],
            v: raw[1],
            r1: (raw[2], raw[3]),
            r2: (raw[4], raw[5]),
        });
    }
    Ok(v)
}

/// `texrtl footprint`.
pub fn run(a: &FootprintArgs) -> Result<String, CmdError> {
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.stats.as_deref().map(|p| ("--stats", p)));
    outs.extend(a.vcd.as_deref().map(|p| ("--vcd", p)));
    let ins = [
        ("--texture", a.texture.as_path()),
        ("--requests", a.requests.as_path()),
    ];
    let guard = super::Outputs::check(&outs, &ins)?;
    guard.settle(footprint(a))
}

/// The options into setup parameters, a border and the unit (true: texram).
fn options(a: &FootprintArgs) -> Result<(SetupParams, Border, bool), CmdError> {
    if !a.max_n.is_power_of_two() || a.max_n > 1 << MAX_LOG2_N {
        return Err(input(format!(
            "--max-n {}: a power of two, 1..=64",
            a.max_n
        )));
    }
    let rounding = match a.rounding.as_str() {
        "log" => NRounding::Log,
        "linear" => NRounding::Linear,
        r => {
            let r = formats::shorten(r);
            return Err(input(format!("--rounding {r}: log or linear")));
        }
    };
    let texram = match a.unit.as_str() {
        "texram" => true,
        "texture" => false,
        u => {
            let u = formats::shorten(u);
            return Err(input(format!("--unit {u}: texram or texture")));
        }
    };
    let border = super::texture_border(&a.border)?;
    let p = SetupParams {
        max_log2_n: a.max_n.trailing_zeros(),
        rounding,
    };
    Ok((p, border, texram))
}

/// The command once its outputs are checked.
fn footprint(a: &FootprintArgs) -> Result<String, CmdError> {
    let (p, border, texram) = options(a)?;
    let pixels = if texram {
        let (drf, level0) = read_pgm(&a.texture, border)?;
        let pixels = read_pixels(&a.requests).map_err(input)?;
        let run =
            run_footprint(drf, &level0, p, &pixels, a.vcd.as_deref()).map_err(super::run_error)?;
        (pixels, run)
    } else {
        let tex = super::texread::read_texture(&a.texture).map_err(input)?;
        let tp = units::texmem::texture_unit_602::TexParams::new(tex.width, tex.height);
        tp.validate()
            .map_err(|e| input(format!("{}: {e}", a.texture.display())))?;
        let pixels = read_pixels(&a.requests).map_err(input)?;
        let run = run_footprint_texture(&tex, tp, p, &pixels, a.vcd.as_deref())
            .map_err(super::run_error)?;
        (pixels, run)
    };
    write_results(a, &pixels.0, &pixels.1, texram)
}

/// A PGM as the TEXRAM map of DRF 0.
fn read_pgm(path: &Path, border: Border) -> Result<(Drf, Vec<u8>), CmdError> {
    let img = formats::netpbm::read(path).map_err(input)?;
    let side = |n: u32, what: &str| {
        if n.is_power_of_two() && n <= 1024 {
            Ok(n.trailing_zeros())
        } else {
            Err(input(format!(
                "{}: {what} {n} is not a power of two up to 1024",
                path.display()
            )))
        }
    };
    let (wl, hl) = (side(img.width, "width")?, side(img.height, "height")?);
    if img.maxval != 255 {
        return Err(input(format!(
            "{}: maxval {}, 8-bit texels need 255",
            path.display(),
            img.maxval
        )));
    }
    Ok((Drf::new(wl, hl, border), img.pixels))
}

/// The CSV, the stats, the closing line.
fn write_results(
    a: &FootprintArgs,
    pixels: &[Pixel],
    run: &FootprintRun,
    texram: bool,
) -> Result<String, CmdError> {
    let head = if texram { "value" } else { "r,g,b" };
    let mut csv = format!("u,v,dudx,dvdx,dudy,dvdy,n,lambda,{head}\n");
    let f = |r: i32| f64::from(r) / 256.0;
    for (q, (r, lambda)) in pixels.iter().zip(&run.results) {
        let colour = if texram {
            r.value.to_string()
        } else {
            format!("{},{},{}", r.rgb >> 16, r.rgb >> 8 & 0xff, r.rgb & 0xff)
        };
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{colour}",
            f(q.u),
            f(q.v),
            f(q.r1.0),
            f(q.r1.1),
            f(q.r2.0),
            f(q.r2.1),
            r.n,
            f(*lambda),
        );
    }
    write_out(&a.out, csv.as_bytes())?;
    if let Some(s) = &a.stats {
        let json = serde_json::to_vec_pretty(&run.stats).map_err(|e| input(e.to_string()))?;
        write_out(s, &json)?;
    }
    let st = &run.stats;
    Ok(format!(
        "{} pixels written to {}: {} accesses ({:.2} a pixel), {} page faults, {:.2} M pixels/s",
        st.pixels,
        a.out.display(),
        st.accesses,
        st.mean_n,
        st.page_faults,
        st.pixels_per_second / 1e6
    ))
}
