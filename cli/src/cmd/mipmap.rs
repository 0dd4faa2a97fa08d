//! `texrtl mipmap`: mipmaps of video frames through the cycle-accurate generator of FIG. 14.

use super::{write_out, CmdError};
use clap::Args;
use formats::netpbm;
use std::path::{Path, PathBuf};
use units::mipmap::{Rounding, Scan};
use waves::TraceConfig;

/// Mipmaps of video frames through the cycle-accurate generator of FIG. 14.
#[derive(Args, Debug)]
pub struct MipmapArgs {
    /// A frame: 8-bit PGM with power-of-two sides up to 1024; repeat for a sequence.
    #[arg(long = "in", required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output directory: levelK.pgm (frameF/levelK.pgm for several frames) and stats.json.
    #[arg(long)]
    pub out: PathBuf,
    /// progressive, interlaced-top (even lines first) or interlaced-bottom.
    #[arg(long, default_value = "progressive", value_parser = parse_scan)]
    pub scan: Scan,
    /// round ((a+b+c+d+2)>>2) or truncate (>>2).
    #[arg(long, default_value = "round", value_parser = parse_rounding)]
    pub rounding: Rounding,
    /// Waveform of the run (with its .gtkw beside it).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

fn parse_scan(s: &str) -> Result<Scan, String> {
    s.parse()
}
fn parse_rounding(s: &str) -> Result<Rounding, String> {
    s.parse()
}

/// `texrtl mipmap`: every frame through the cycle-accurate generator; `DIR/levelK.pgm` (or
/// `DIR/frameF/levelK.pgm` for several frames) and `DIR/stats.json`. Every input is checked
/// before anything is written.
pub fn run(a: &MipmapArgs) -> Result<String, CmdError> {
    if a.inputs.is_empty() {
        return Err(CmdError::Input("mipmap: no --in frame".into()));
    }
    let ins: Vec<_> = a.inputs.iter().map(|p| ("--in", p.as_path())).collect();
    let vcd: Vec<_> = a.vcd.iter().map(|p| ("--vcd", p.as_path())).collect();
    let mut guard = super::Outputs::check(&vcd, &ins)?;
    check_folder(a, &ins)?;
    guard.folder(&a.out);
    guard.settle(mipmap(a))
}

/// The most levels a frame has (1024 x 1024 down to 1 x 1).
const MAX_LEVELS: usize = 11;

/// The output folder: not a file, not the VCD, and no file it may receive (levels, stats)
/// one of the inputs.
fn check_folder(a: &MipmapArgs, ins: &[(&str, &Path)]) -> Result<(), CmdError> {
    verif::cli::check_folder("--out", &a.out)?;
    let dirs: Vec<PathBuf> = match a.inputs.len() {
        1 => vec![a.out.clone()],
        n => (0..n).map(|f| a.out.join(format!("frame{f}"))).collect(),
    };
    let mut planned = vec![a.out.join("stats.json")];
    for d in &dirs {
        planned.extend((0..MAX_LEVELS).map(|k| d.join(format!("level{k}.pgm"))));
    }
    let vcd = a.vcd.iter().map(|v| ("--vcd", v.as_path()));
    let others: Vec<(&str, &Path)> = ins.iter().copied().chain(vcd).collect();
    for p in &planned {
        if p.is_dir() {
            return Err(CmdError::Input(format!(
                "--out {}: {} is a directory",
                a.out.display(),
                p.display()
            )));
        }
        if let Some((opt, q)) = others.iter().find(|(_, q)| super::same_file(p, q)) {
            return Err(CmdError::Input(format!(
                "--out {}: would overwrite {opt} {}: choose another folder",
                a.out.display(),
                q.display()
            )));
        }
    }
    Ok(())
}

/// The command once its outputs are checked.
fn mipmap(a: &MipmapArgs) -> Result<String, CmdError> {
    let mut frames = Vec::new();
    let mut size = None;
    for path in &a.inputs {
        let img = netpbm::read(path)?;
        let p = units::mipmap::MipmapParams {
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
    let (w, h) = size.expect("at least one frame");
    let p = units::mipmap::MipmapParams {
        width: w,
        height: h,
        scan: a.scan,
        rounding: a.rounding,
    };
    let o = tb::runs::mipmap::run_mipmap(
        p,
        &frames,
        a.vcd.clone().map(|v| (v, TraceConfig::default())),
    )
    .map_err(super::run_error)?;
    if o.error != 0 {
        return Err(CmdError::Failed(format!(
            "mipmap generator reported error code {}",
            o.error
        )));
    }
    verif::cli::make_folder("--out", &a.out)?;
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
            write_out(&path, &netpbm::encode(dims[k].0, dims[k].1, texels))?;
        }
    }
    let json = serde_json::to_vec_pretty(&o.stats).map_err(|e| CmdError::Failed(e.to_string()))?;
    let stats = a.out.join("stats.json");
    write_out(&stats, &json)?;
    Ok(format!(
        "{} frame(s) of {w}x{h}: {} levels written to {}; {} cycles, mipmap complete {} cycles after the last texel",
        frames.len(),
        dims.len(),
        a.out.display(),
        o.stats.cycles,
        o.stats.latency_after_last_texel
    ))
}
