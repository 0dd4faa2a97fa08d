//! `texrtl ccc encode|decode`: CCC texture compression (Schilling & Knittel, section 3).

use super::{input, write_out, CmdError};
use clap::Subcommand;
use formats::ccc::{self, Ccc};
use std::path::{Path, PathBuf};

/// CCC texture compression: encode a PPM, decode a .ccc.
#[derive(Subcommand, Debug)]
pub enum CccCmd {
    /// PPM (P6/P3, sides multiples of 4) to .ccc.
    Encode {
        #[arg(long = "in")]
        input: PathBuf,
        #[arg(long)]
        out: PathBuf,
    },
    /// .ccc to a binary PPM.
    Decode {
        #[arg(long = "in")]
        input: PathBuf,
        #[arg(long)]
        out: PathBuf,
    },
}

/// Runs `encode` or `decode`.
pub fn run(c: &CccCmd) -> Result<String, CmdError> {
    match c {
        CccCmd::Encode { input, out } => encode(input, out),
        CccCmd::Decode { input, out } => decode(input, out),
    }
}

/// `texrtl ccc encode`: PPM to `.ccc`; reports the PSNR of the decoded texture.
fn encode(inp: &Path, out: &Path) -> Result<String, CmdError> {
    super::check_outputs(&[("--out", out)], &[("--in", inp)])?;
    let img = formats::netpbm::read_ppm(inp).map_err(input)?;
    let c = ccc::encode(&img).map_err(|e| input(format!("{}: {e}", inp.display())))?;
    write_out(out, &c.to_bytes())?;
    let (db, worst) = ccc::psnr(&img.pixels, &c.decode());
    Ok(format!(
        "{}: {}x{} texels, {} blocks, {} bytes; decoded PSNR {db:.2} dB, worst texel error {worst} levels",
        out.display(),
        c.width,
        c.height,
        c.blocks.len(),
        c.to_bytes().len()
    ))
}

/// `texrtl ccc decode`: `.ccc` to a binary PPM (the reference decoder).
fn decode(inp: &Path, out: &Path) -> Result<String, CmdError> {
    super::check_outputs(&[("--out", out)], &[("--in", inp)])?;
    let c = Ccc::read(inp).map_err(input)?;
    write_out(
        out,
        &formats::netpbm::encode_ppm(c.width, c.height, &c.decode()),
    )?;
    Ok(format!("{}: {}x{}", out.display(), c.width, c.height))
}
