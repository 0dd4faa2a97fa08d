//! `texrtl vectors`: a unit's bit-accuracy vectors as `$readmemh` files.

use super::CmdError;
use clap::Args;
use std::path::PathBuf;

/// Export a unit's bit-accuracy vectors as $readmemh files for a Verilog testbench.
#[derive(Args, Debug)]
pub struct VectorsArgs {
    /// The unit (see golden/vectors/).
    #[arg(long)]
    pub unit: String,
    /// Directory for UNIT_stimulus.hex and UNIT_expected.hex.
    #[arg(long)]
    pub out: PathBuf,
}

/// Writes the files.
pub fn run(a: &VectorsArgs) -> Result<String, CmdError> {
    let mut guard = super::Outputs::default();
    guard.folder(&a.out);
    guard.settle(vectors_cmd(&a.unit, &a.out))
}

fn vectors_cmd(unit: &str, out: &std::path::Path) -> Result<String, CmdError> {
    let v = tb::vectors::unit_vectors(unit).map_err(CmdError::Input)?;
    if out.exists() && !out.is_dir() {
        return Err(CmdError::Input(format!(
            "--out {}: exists and is not a directory",
            out.display()
        )));
    }
    let files = v
        .write_readmemh(out)
        .map_err(|e| CmdError::Input(format!("--out {}: {e}", out.display())))?;
    let names: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
    Ok(format!(
        "{} vectors of {}: {}",
        v.rows.len(),
        unit,
        names.join(", ")
    ))
}
