//! The `normals`, `render` and `sweep normals` commands (issue: FIG. 7 pipeline).

use crate::normals::{quantise, run_normals, NormalsRun, RawNormal, Sample};
use crate::pgm;
use crate::report::write_atomic;
use hdl::bump_params::{BumpParams, Filter, HeightTexel, RsqrtParams};
use hdl::fx::Fx;
use hdl::height_map::HeightMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use verif::Seed;
use waves::TraceConfig;

/// A command's failure: bad input (exit 2) or a run that failed (exit 1).
#[derive(Debug)]
pub enum CmdError {
    Input(String),
    Failed(String),
}

impl From<String> for CmdError {
    fn from(s: String) -> Self {
        CmdError::Input(s)
    }
}

/// Widths and variants an architect can set on the command line.
#[derive(Clone, Debug)]
pub struct Widths {
    pub blend_bits: u32,
    pub texel_bits: u32,
    pub table_bits: u32,
    pub iterations: u32,
    pub out_frac: u32,
    pub tangent_frac: u32,
}

impl Default for Widths {
    fn default() -> Self {
        let p = BumpParams::default();
        Widths {
            blend_bits: p.blend_bits,
            texel_bits: 8,
            table_bits: p.rsqrt.table_bits,
            iterations: p.rsqrt.iterations,
            out_frac: p.out_frac,
            tangent_frac: p.tangent_frac,
        }
    }
}

impl Widths {
    pub fn params(&self) -> Result<BumpParams, String> {
        let height = match self.texel_bits {
            8 => HeightTexel::Bits8,
            4 => HeightTexel::Bits4,
            b => return Err(format!("--texel-bits {b}: 8 or 4")),
        };
        let p = BumpParams {
            blend_bits: self.blend_bits,
            pos_frac: self.blend_bits.max(16),
            height,
            tangent_frac: self.tangent_frac,
            rsqrt: RsqrtParams {
                table_bits: self.table_bits,
                iterations: self.iterations,
                ..RsqrtParams::default()
            },
            out_frac: self.out_frac,
            ..BumpParams::default()
        };
        p.validate()?;
        Ok(p)
    }
}

/// Reads a height map PGM into the texel format of `p`.
pub fn read_height(path: &Path, p: &BumpParams) -> Result<HeightMap, String> {
    let img = pgm::read(path)?;
    HeightMap::new(img.width, img.height, p.texel_fmt(), img.pixels)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads a CSV with header `u,v`; every value must be a finite number.
pub fn read_coords(path: &Path) -> Result<Vec<(f64, f64)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let err = |line: usize, m: String| format!("{}:{line}: {m}", path.display());
    let mut lines = text.lines().enumerate();
    let header = lines.next().map(|(_, l)| l.trim()).unwrap_or("");
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    if cols != ["u", "v"] {
        return Err(err(1, format!("header '{header}' is not 'u,v'")));
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 2 {
            return Err(err(
                i + 1,
                format!("'{line}' has {} fields, expected 2", f.len()),
            ));
        }
        let num = |s: &str| -> Result<f64, String> {
            let x: f64 = s
                .parse()
                .map_err(|_| err(i + 1, format!("'{s}' is not a number")))?;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(err(i + 1, format!("'{s}' is not a finite number")))
            }
        };
        out.push((num(f[0])?, num(f[1])?));
    }
    Ok(out)
}

/// Options of `texrtl normals`.
pub struct NormalsArgs {
    pub height: PathBuf,
    pub coords: PathBuf,
    pub out: PathBuf,
    pub filter: Filter,
    pub scale: f64,
    pub border: hdl::bump_params::Border,
    pub vcd: Option<PathBuf>,
    pub trilinear: bool,
    pub lod: f64,
    pub widths: Widths,
}

/// `texrtl normals`: one CSV row per coordinate, each component the exact decimal value of
/// its fixed-point result. Returns a summary line.
pub fn normals(a: &NormalsArgs) -> Result<String, CmdError> {
    let mut p = a.widths.params()?;
    p.filter = a.filter;
    p.border = a.border;
    p.trilinear = a.trilinear;
    p.validate()?;
    let map = read_height(&a.height, &p)?;
    let coords = read_coords(&a.coords)?;
    let samples: Vec<Sample> = coords
        .iter()
        .map(|&(u, v)| Sample {
            u,
            v,
            scale: a.scale,
            lod: a.lod,
        })
        .collect();
    for (k, s) in samples.iter().enumerate() {
        quantise(&p, s).map_err(|e| format!("{}:{}: {e}", a.coords.display(), k + 2))?;
    }
    for out in [Some(&a.out), a.vcd.as_ref()].into_iter().flatten() {
        if out.is_dir() {
            return Err(CmdError::Input(format!(
                "{}: is a directory",
                out.display()
            )));
        }
    }
    let o = run_normals(&NormalsRun {
        name: "normals".into(),
        params: p,
        map,
        samples: samples.clone(),
        idle_per_mille: 0,
        vcd: a.vcd.clone(),
        trace: TraceConfig::default(),
        check_accuracy: false,
        check_schedule: false,
        seed: Seed(0),
    })
    .map_err(CmdError::Failed)?;
    if !o.result.failures.is_empty() {
        return Err(CmdError::Failed(o.result.failures.join("; ")));
    }
    let nf = p.normal_fmt();
    let pf = p.pos_fmt();
    let mut csv = String::from("u,v,nx,ny,nz\n");
    for (s, n) in samples.iter().zip(&o.outputs) {
        let r = quantise(&p, s).expect("checked above");
        let d = |x: i64, f| Fx::from_raw(f, i128::from(x)).to_string();
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            d(r.u, pf),
            d(r.v, pf),
            d(n.n[0], nf),
            d(n.n[1], nf),
            d(n.n[2], nf)
        );
    }
    write_atomic(&a.out, csv.as_bytes())
        .map_err(|e| CmdError::Input(format!("{}: {e}", a.out.display())))?;
    Ok(format!(
        "{} normals written to {} ({} filter, latency {} cycles; against golden: max component error {:.3e}, max angle {:.3e} deg)",
        o.outputs.len(),
        a.out.display(),
        a.filter,
        o.latency,
        o.max_component_err,
        o.max_angle_deg
    ))
}

/// Options of `texrtl render`.
pub struct RenderArgs {
    pub height: PathBuf,
    pub out: PathBuf,
    pub light: [f64; 3],
    pub scale: f64,
    pub zoom: u32,
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

fn dot3(n: [f64; 3], l: [f64; 3]) -> f64 {
    (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0)
}

/// `texrtl render`: Dot3-lit pictures of the height map, side by side: Blinn (bit-exact) |
/// B-spline (bit-exact) | golden B-spline | heat map of |B-spline - golden| in intensity
/// (log scale, black = below 2^-24, white = 2^-8 or more). Returns a summary.
pub fn render(a: &RenderArgs) -> Result<String, CmdError> {
    if !a.zoom.is_power_of_two() || a.zoom > 64 {
        return Err(CmdError::Input(format!(
            "--zoom {}: a power of two up to 64",
            a.zoom
        )));
    }
    let p = a.widths.params()?;
    let map = read_height(&a.height, &p)?;
    let (w, h) = (map.width() * a.zoom, map.height() * a.zoom);
    if u64::from(w) * u64::from(h) > 4 << 20 {
        return Err(CmdError::Input(format!(
            "{}: {w}x{h} pixels per panel is too large (4 Mpixel at most)",
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
    write_atomic(&a.out, &png).map_err(|e| CmdError::Input(format!("{}: {e}", a.out.display())))?;
    Ok(format!(
        "{}: {w}x{h} per panel: Blinn | B-spline (bit-exact) | golden | heat map of |B-spline - golden| (log scale 2^-24..2^-8); worst intensity error {worst:.3e}",
        a.out.display()
    ))
}

/// The four-panel Dot3 picture as PNG bytes, and the worst intensity error of the B-spline
/// panel against golden.
pub fn render_png(
    map: &HeightMap,
    p: &BumpParams,
    light: [f64; 3],
    scale: f64,
    zoom: u32,
) -> Result<(Vec<u8>, f64), String> {
    let (w, h) = (map.width() * zoom, map.height() * zoom);
    let l = {
        let n = (light[0] * light[0] + light[1] * light[1] + light[2] * light[2]).sqrt();
        light.map(|x| x / n)
    };
    let z = f64::from(zoom);
    let samples: Vec<Sample> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| Sample {
            u: (f64::from(x) + 0.5) / z,
            v: (f64::from(y) + 0.5) / z,
            scale,
            lod: 0.0,
        })
        .collect();
    let run = |filter: Filter| {
        run_normals(&NormalsRun {
            name: format!("render {filter}"),
            params: BumpParams { filter, ..*p },
            map: map.clone(),
            samples: samples.clone(),
            idle_per_mille: 0,
            vcd: None,
            trace: TraceConfig::default(),
            check_accuracy: false,
            check_schedule: false,
            seed: Seed(0),
        })
    };
    let blinn = run(Filter::Blinn)?;
    let bspline = run(Filter::BSpline)?;
    let nf = p.normal_fmt();
    let intensity = |n: &RawNormal| dot3(n.n.map(|x| crate::normals::real(x, nf)), l);
    let mut img = image::RgbImage::new(4 * w + 3 * 4, h);
    let mut worst = 0.0f64;
    for k in 0..samples.len() {
        let (x, y) = (k as u32 % w, k as u32 / w);
        let ib = intensity(&blinn.outputs[k]);
        let is = intensity(&bspline.outputs[k]);
        let ig = dot3(bspline.golden[k], l);
        let grey = |i: f64| {
            let g = (i * 255.0).round().clamp(0.0, 255.0) as u8;
            image::Rgb([g, g, g])
        };
        img.put_pixel(x, y, grey(ib));
        img.put_pixel(w + 4 + x, y, grey(is));
        img.put_pixel(2 * (w + 4) + x, y, grey(ig));
        let e = (is - ig).abs();
        worst = worst.max(e);
        img.put_pixel(3 * (w + 4) + x, y, heat(e));
    }
    Ok((encode_png(&img)?, worst))
}

/// PNG bytes of an RGB image.
pub fn encode_png(img: &image::RgbImage) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(png)
}

/// Log-scale heat colour: black below 2^-24, through blue, red and yellow to white at 2^-8.
fn heat(e: f64) -> image::Rgb<u8> {
    let t = if e <= 0.0 {
        0.0
    } else {
        ((e.log2() + 24.0) / 16.0).clamp(0.0, 1.0)
    };
    let stops = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 1.0],
    ];
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let c =
        [0, 1, 2].map(|k| ((stops[i][k] * (1.0 - f) + stops[i + 1][k] * f) * 255.0).round() as u8);
    image::Rgb(c)
}

/// `texrtl sweep normals`: max and mean error of the B-spline normals against golden for
/// blend-factor bits x rsqrt table bits, on the built-in noise map at random positions with 16
/// fraction bits (so the address unit's truncation to F bits is part of the error).
pub fn sweep_normals(map_name: &str, samples: usize, seed: Seed) -> Result<String, CmdError> {
    crate::maps::builtin(map_name, 16, 16, BumpParams::default().texel_fmt())?;
    let blends = [4u32, 6, 8, 10, 12, 14, 16];
    let tables = [4u32, 6, 8, 10, 12];
    let mut stim = verif::Stimulus::new(seed);
    let pts: Vec<Sample> = (0..samples)
        .map(|_| {
            let (u, v) = stim.draw(&(0u64..(16 << 16), 0u64..(16 << 16)));
            Sample {
                u: u as f64 / 65536.0,
                v: v as f64 / 65536.0,
                scale: 1.0,
                lod: 0.0,
            }
        })
        .collect();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "B-spline normals vs golden, {map_name} map 16x16, {samples} positions with 16 fraction bits, seed {seed}\n\
         each cell: max component error / mean component error, in units of 2^-16 (default output LSB); max angle in degrees\n"
    );
    let _ = write!(s, "{:>11}", "blend\\table");
    for t in tables {
        let _ = write!(s, " | {:>26}", format!("{t} bits"));
    }
    s.push('\n');
    for b in blends {
        let _ = write!(s, "{b:>11}");
        for t in tables {
            let w = Widths {
                blend_bits: b,
                table_bits: t,
                ..Widths::default()
            };
            let mut p = w.params()?;
            p.pos_frac = 16;
            let map = crate::maps::builtin(map_name, 16, 16, p.texel_fmt())?;
            let o = run_normals(&NormalsRun {
                name: format!("sweep F={b} T={t}"),
                params: p,
                map,
                samples: pts.clone(),
                idle_per_mille: 0,
                vcd: None,
                trace: TraceConfig::default(),
                check_accuracy: false,
                check_schedule: false,
                seed,
            })
            .map_err(CmdError::Failed)?;
            let lsb = 1.0 / 65536.0;
            let mean = o.result.stats.sum_abs_lsb / o.result.stats.count.max(1) as f64
                * (-(p.out_frac as f64)).exp2()
                / lsb;
            let _ = write!(
                s,
                " | {:>26}",
                format!(
                    "{:.1} / {:.2}, {:.4} deg",
                    o.max_component_err / lsb,
                    mean,
                    o.max_angle_deg
                )
            );
        }
        s.push('\n');
    }
    Ok(s)
}

/// Options of `texrtl mipmap`.
pub struct MipmapArgs {
    pub inputs: Vec<PathBuf>,
    pub out: PathBuf,
    pub scan: hdl::mipmap::Scan,
    pub rounding: hdl::mipmap::Rounding,
    pub vcd: Option<PathBuf>,
}

/// `texrtl mipmap`: every frame through the cycle-accurate generator; `DIR/levelK.pgm` (or
/// `DIR/frameF/levelK.pgm` for several frames) and `DIR/stats.json`. Every input is checked
/// before anything is written.
pub fn mipmap(a: &MipmapArgs) -> Result<String, CmdError> {
    if a.inputs.is_empty() {
        return Err(CmdError::Input("mipmap: no --in frame".into()));
    }
    let mut frames = Vec::new();
    let mut size = None;
    for path in &a.inputs {
        let img = pgm::read(path)?;
        let p = hdl::mipmap::MipmapParams {
            width: img.width,
            height: img.height,
            scan: a.scan,
            rounding: a.rounding,
        };
        p.validate()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        match size {
            None => size = Some((img.width, img.height)),
            Some(s) if s != (img.width, img.height) => {
                return Err(CmdError::Input(format!(
                    "{}: {}x{} differs from the first frame's {}x{}",
                    path.display(),
                    img.width,
                    img.height,
                    s.0,
                    s.1
                )))
            }
            _ => {}
        }
        frames.push(img.pixels);
    }
    if a.out.exists() && !a.out.is_dir() {
        return Err(CmdError::Input(format!(
            "{}: exists and is not a directory",
            a.out.display()
        )));
    }
    if let Some(v) = &a.vcd {
        if v.is_dir() {
            return Err(CmdError::Input(format!("{}: is a directory", v.display())));
        }
    }
    let (w, h) = size.expect("at least one frame");
    let p = hdl::mipmap::MipmapParams {
        width: w,
        height: h,
        scan: a.scan,
        rounding: a.rounding,
    };
    let o = crate::mipmap::run_mipmap(
        p,
        &frames,
        a.vcd.clone().map(|v| (v, TraceConfig::default())),
    )
    .map_err(CmdError::Failed)?;
    if o.error != 0 {
        return Err(CmdError::Failed(format!(
            "mipmap generator reported error code {}",
            o.error
        )));
    }
    std::fs::create_dir_all(&a.out)
        .map_err(|e| CmdError::Input(format!("{}: {e}", a.out.display())))?;
    let dims = p.levels();
    for (f, levels) in o.frames.iter().enumerate() {
        let dir = if frames.len() == 1 {
            a.out.clone()
        } else {
            a.out.join(format!("frame{f}"))
        };
        std::fs::create_dir_all(&dir)
            .map_err(|e| CmdError::Input(format!("{}: {e}", dir.display())))?;
        for (k, texels) in levels.iter().enumerate() {
            let path = dir.join(format!("level{k}.pgm"));
            write_atomic(&path, &pgm::encode(dims[k].0, dims[k].1, texels))
                .map_err(|e| CmdError::Input(format!("{}: {e}", path.display())))?;
        }
    }
    let json = serde_json::to_vec_pretty(&o.stats).map_err(|e| CmdError::Failed(e.to_string()))?;
    let stats = a.out.join("stats.json");
    write_atomic(&stats, &json)
        .map_err(|e| CmdError::Input(format!("{}: {e}", stats.display())))?;
    Ok(format!(
        "{} frame(s) of {w}x{h}: {} levels written to {}; {} cycles, mipmap complete {} cycles after the last texel",
        frames.len(),
        dims.len(),
        a.out.display(),
        o.stats.cycles,
        o.stats.latency_after_last_texel
    ))
}
