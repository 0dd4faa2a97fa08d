//! `texrtl normals`: normals of a height map at given positions through the FIG. 7 pipeline.

use super::widths::Widths;
use super::{parse_finite, write_out, CmdError};
use clap::Args;
use formats::netpbm;
use hdl::fx::Fx;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::runs::normals::{quantise, run_normals, NormalsRun, Sample};
use units::bump::derivative_0086::{DerivFilter, Derivative, DerivativeUnit};
use units::bump::height_map::HeightMap;
use units::bump::params::{Border, BumpParams, Filter};
use verif::Seed;
use waves::TraceConfig;

/// Normals of a height map at given positions through the FIG. 7 pipeline.
#[derive(Args, Debug)]
pub struct NormalsArgs {
    /// Height map: 8-bit PGM, binary (P5) or ASCII (P2); texel values are raw heights.
    #[arg(long)]
    pub height: PathBuf,
    /// CSV with header u,v: positions in texel units.
    #[arg(long)]
    pub coords: PathBuf,
    /// Output CSV u,v,nx,ny,nz (exact decimal values of the fixed-point results).
    #[arg(long)]
    pub out: PathBuf,
    /// The FIG. 7 pipeline's bspline, bezier or blinn; or para. 0086's derivative filters
    /// central, sobel, prewitt, table (the 5-point taps) or table:c1,..,cK (antisymmetric
    /// taps in units of 2^-12, K <= 4), whose normals are sQ1.14.
    #[arg(long, default_value = "bspline", value_parser = parse_filter)]
    pub filter: NormalsFilter,
    /// Height scale factor (quantised to uQ8.8).
    #[arg(long, default_value_t = 1.0, value_parser = parse_finite)]
    pub scale: f64,
    /// wrap, clamp, mirror, constant (0) or constant:N.
    #[arg(long, default_value = "wrap", value_parser = parse_border)]
    pub border: Border,
    /// Waveform of the run (with its .gtkw beside it).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
    /// Trilinear normals from this map and its next MIP level (2x2 box filter).
    #[arg(long)]
    pub trilinear: bool,
    /// Weight of the coarser level with --trilinear, in [0, 1).
    #[arg(long, default_value_t = 0.0, value_parser = parse_finite)]
    pub lod: f64,
    #[command(flatten)]
    pub widths: Widths,
}

/// A pipeline surface or a derivative filter.
#[derive(Clone, Debug)]
pub enum NormalsFilter {
    Pipeline(Filter),
    Derivative(DerivFilter),
}

fn parse_filter(s: &str) -> Result<NormalsFilter, String> {
    if let Some(d) = DerivFilter::parse(s) {
        return Ok(NormalsFilter::Derivative(d));
    }
    s.parse().map(NormalsFilter::Pipeline).map_err(|_| {
        format!(
            "unknown filter '{}' (one of bspline, bezier, blinn, central, sobel, prewitt, table, table:c1,..,cK)",
            formats::shorten(s)
        )
    })
}
fn parse_border(s: &str) -> Result<Border, String> {
    s.parse()
}

/// Reads a height map PGM into the texel format of `p`.
pub fn read_height(path: &Path, p: &BumpParams) -> Result<HeightMap, String> {
    let img = netpbm::read(path)?;
    HeightMap::new(img.width, img.height, p.texel_fmt(), img.pixels)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads a CSV with header `u,v`; every value must be a finite number.
pub fn read_coords(path: &Path) -> Result<Vec<(f64, f64)>, String> {
    let t = formats::csv::read(path, &["u,v"])?;
    t.rows
        .iter()
        .map(|r| Ok((t.finite(r, 0)?, t.finite(r, 1)?)))
        .collect()
}

/// `texrtl normals`: one CSV row per coordinate, each component the exact decimal value of
/// its fixed-point result. Returns a summary line.
pub fn run(a: &NormalsArgs) -> Result<String, CmdError> {
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.vcd.as_deref().map(|p| ("--vcd", p)));
    let ins = [
        ("--height", a.height.as_path()),
        ("--coords", a.coords.as_path()),
    ];
    let guard = super::Outputs::check(&outs, &ins)?;
    guard.settle(normals(a))
}

/// The command once its outputs are checked.
fn normals(a: &NormalsArgs) -> Result<String, CmdError> {
    if a.lod != 0.0 && !a.trilinear {
        return Err(CmdError::Input(
            "--lod: the weight of the coarser MIP level needs --trilinear".into(),
        ));
    }
    let mut p = a.widths.params()?;
    let filter = match &a.filter {
        NormalsFilter::Pipeline(f) => *f,
        NormalsFilter::Derivative(d) => return derivative_normals(a, d, &p),
    };
    p.filter = filter;
    p.border = a.border;
    p.trilinear = a.trilinear;
    p.validate()?;
    // The options that every sample shares, checked before the files are read and named as
    // options (not as the coordinates file's first row).
    let at_origin = Sample {
        u: 0.0,
        v: 0.0,
        scale: a.scale,
        lod: a.lod,
    };
    tb::runs::normals::quantise(&p, &at_origin).map_err(|e| CmdError::Input(format!("--{e}")))?;
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
    .map_err(CmdError::Input)?;
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
    write_out(&a.out, csv.as_bytes())?;
    Ok(format!(
        "{} normals written to {} ({} filter, latency {} cycles; against golden: max component error {:.3e}, max angle {:.3e} deg)",
        o.outputs.len(),
        a.out.display(),
        filter,
        o.latency,
        o.max_component_err,
        o.max_angle_deg
    ))
}

/// `texrtl normals --filter central|sobel|prewitt|table..`: para. 0086's unit, one sample a
/// cycle, normals sQ1.14.
fn derivative_normals(
    a: &NormalsArgs,
    f: &DerivFilter,
    p: &BumpParams,
) -> Result<String, CmdError> {
    if a.trilinear {
        return Err(CmdError::Input(format!(
            "--trilinear: the derivative filter {} reads one level",
            f.name()
        )));
    }
    if !(0.0..256.0).contains(&a.scale) {
        return Err(CmdError::Input(format!(
            "--scale {}: 0 ..< 256 (uQ8.8)",
            formats::shorten(&a.scale.to_string())
        )));
    }
    let map = read_height(&a.height, p)?;
    let coords = read_coords(&a.coords)?;
    let pos = |x: f64, k: usize| -> Result<i64, String> {
        let r = (x * 65536.0).round_ties_even();
        if r.abs() < 2f64.powi(31) {
            Ok(r as i64)
        } else {
            Err(format!(
                "{}:{}: position {} outside +-32768",
                a.coords.display(),
                k + 2,
                formats::shorten(&x.to_string())
            ))
        }
    };
    let q: Vec<(i64, i64)> = coords
        .iter()
        .enumerate()
        .map(|(k, &(u, v))| Ok((pos(u, k)?, pos(v, k)?)))
        .collect::<Result<_, String>>()?;
    let scale = (a.scale * 256.0).round() as i64;
    let d = Derivative::new(f.clone(), map, a.border, tb::derivative::POS_FRAC);
    let work = verif::Workload::vcd(a.vcd.as_deref());
    let own_period_ps = TraceConfig::default().period_ps;
    let (mut sim, _) = work.sim(
        DerivativeUnit::new(d),
        "derivative_0086",
        own_period_ps,
        |_| (),
    )?;
    sim.reset(1);
    let mut csv = String::from("u,v,nx,ny,nz\n");
    for &(u, v) in &q {
        sim.dut.valid_in.set_bool(true);
        sim.dut.u.set_raw(u);
        sim.dut.v.set_raw(v);
        sim.dut.scale.set_raw(scale);
        sim.step();
        let n = sim.dut.n.each_ref().map(|r| r.q().raw());
        let d = |x: i64, f: i32| {
            Fx::from_raw(hdl::fx::Format::signed(48, f), i128::from(x)).to_string()
        };
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            d(u, 16),
            d(v, 16),
            d(n[0], 14),
            d(n[1], 14),
            d(n[2], 14)
        );
    }
    work.finish(sim)?;
    write_out(&a.out, csv.as_bytes())?;
    Ok(format!(
        "{} normals written to {} (derivative filter {} of para. 0086, {} texels a sample)",
        q.len(),
        a.out.display(),
        f.name(),
        f.texels_per_sample()
    ))
}
