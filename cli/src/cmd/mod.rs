//! One file per subcommand, each owning its clap arguments and its `run`.

pub mod ccc;
pub mod cosim;
pub mod dram;
pub mod footprint;
pub mod mapchain;
pub mod merge;
pub mod mipmap;
pub mod normals;
pub mod outputs;
pub mod ptm;
pub mod regress;
pub mod render;
pub mod sweep;
pub mod tangents;
pub mod texram;
pub mod texread;
pub mod vectors;
pub mod volume;
pub mod widths;

use std::path::Path;

pub use outputs::Outputs;

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

/// Whether two paths name one file: the same absolute path, or (when both exist) the same
/// file after links are resolved.
pub(crate) fn same_file(a: &Path, b: &Path) -> bool {
    let abs = |p: &Path| std::path::absolute(p).ok();
    if abs(a).is_some() && abs(a) == abs(b) {
        return true;
    }
    matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}

/// Every output of a command, checked before any work: each one's folder exists and it is
/// not a folder, no two are the same file, and none is one of the inputs (which it would
/// overwrite). `outs` and `ins` pair each path with its option's name, which the one-line
/// message names.
pub fn check_outputs(outs: &[(&str, &Path)], ins: &[(&str, &Path)]) -> Result<(), CmdError> {
    for (k, (opt, path)) in outs.iter().enumerate() {
        check_out(path).map_err(|e| match e {
            CmdError::Input(m) => input(format!("{opt} {m}")),
            other => other,
        })?;
        let earlier = outs[..k].iter().chain(ins);
        if let Some((other, _)) = earlier.clone().find(|(_, q)| same_file(path, q)) {
            let what = if ins.iter().any(|(o, _)| o == other) {
                "the input"
            } else {
                "the output"
            };
            return Err(input(format!(
                "{opt} {}: the same file as {what} {other}: choose another",
                path.display()
            )));
        }
    }
    Ok(())
}

/// Writes an output file atomically; an I/O error is bad input naming the file.
pub fn write_out(path: &Path, bytes: &[u8]) -> Result<(), CmdError> {
    check_out(path)?;
    formats::output::write_output(path, bytes).map_err(|e| input(e.to_string()))
}

/// A finite number (a clap value parser).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{}' is not a finite number", formats::shorten(s))),
    }
}
