//! One file per subcommand, each owning its clap arguments and its `run`.

pub mod ccc;
pub mod cosim;
pub mod dram;
pub mod merge;
pub mod mipmap;
pub mod normals;
pub mod regress;
pub mod render;
pub mod sweep;
pub mod texread;
pub mod vectors;
pub mod widths;

use std::path::Path;

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

/// Bad input: a [`CmdError::Input`].
pub fn input(e: String) -> CmdError {
    CmdError::Input(e)
}

/// An output path must not be a directory and its directory must exist.
pub fn check_out(path: &Path) -> Result<(), CmdError> {
    if path.is_dir() {
        return Err(input(format!("{}: is a directory", path.display())));
    }
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() && !d.is_dir() => Err(input(format!(
            "{}: directory {} does not exist",
            path.display(),
            d.display()
        ))),
        _ => Ok(()),
    }
}

/// Writes an output file atomically; an I/O error is bad input naming the file.
pub fn write_out(path: &Path, bytes: &[u8]) -> Result<(), CmdError> {
    check_out(path)?;
    formats::output::write_atomic(path, bytes)
        .map_err(|e| input(format!("{}: {e}", path.display())))
}

/// A finite number (a clap value parser).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{}' is not a finite number", formats::shorten(s))),
    }
}
