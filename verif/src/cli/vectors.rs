//! `vectors`: the project's bit-accuracy vectors checked against the kept files, blessed after
//! a deliberate change, or one unit's exported as `$readmemh` files.

use super::args::{clap_args, flag, one, path, value};
use super::CmdError;
use crate::project::Project;
use clap::{value_parser, ArgMatches, Command};
use std::path::{Path, PathBuf};

/// Check, bless or export the bit-accuracy vectors.
#[derive(Debug)]
pub struct VectorsArgs {
    /// Export this unit's vectors (with --out).
    pub unit: Option<String>,
    /// Directory for UNIT_stimulus.hex and UNIT_expected.hex.
    pub out: Option<PathBuf>,
    /// Compare every unit's vectors with the kept files (exit 1 on a difference).
    pub check: bool,
    /// Rewrite the kept files after a deliberate change.
    pub bless: bool,
}

clap_args!(VectorsArgs);

impl VectorsArgs {
    pub(super) fn augment(c: Command) -> Command {
        c.args([
            value("unit", "UNIT", value_parser!(String), "Export this unit's vectors (with --out)")
                .requires("out")
                .conflicts_with_all(["check", "bless"]),
            path("out", "OUT", "Directory for UNIT_stimulus.hex and UNIT_expected.hex").requires("unit"),
            flag("check", "Compare every unit's vectors with the kept files (exit 1 on a difference)").conflicts_with("bless"),
            flag("bless", "Rewrite the kept files after a deliberate change; print how many rows of each unit changed and which"),
        ])
    }

    pub(super) fn read(m: &ArgMatches) -> Self {
        VectorsArgs {
            unit: one(m, "unit"),
            out: one(m, "out"),
            check: m.get_flag("check"),
            bless: m.get_flag("bless"),
        }
    }
}

/// Runs it. A model that panics on its vectors (a value that does not fit its signal's
/// format) is a failure (exit 1), said in one line.
pub fn run(project: &Project, a: &VectorsArgs) -> Result<String, CmdError> {
    crate::testbench::unpanicked(|| vectors(project, a))
        .unwrap_or_else(|e| Err(CmdError::Failed(format!("vectors: a model panicked: {e}"))))
}

fn vectors(project: &Project, a: &VectorsArgs) -> Result<String, CmdError> {
    match (&a.unit, &a.out) {
        (Some(unit), Some(out)) => {
            // Checked before anything is watched or written: what is there stays.
            super::check_folder("--out", out)?;
            let mut guard = super::Outputs::default();
            guard.folder(out);
            guard.settle(export(project, unit, out))
        }
        _ if a.check || a.bless => kept(project, a.bless),
        _ => Err(CmdError::Input(
            "vectors: give --check, --bless, or --unit UNIT --out DIR".into(),
        )),
    }
}

fn kept(project: &Project, bless: bool) -> Result<String, CmdError> {
    let dir = project.kept_vectors().ok_or_else(|| {
        CmdError::Input("vectors: the project keeps no vectors (Project::vectors_dir)".into())
    })?;
    let n = project.vectors().count();
    if bless {
        let changed = crate::vectors::bless(dir, project.vectors()).map_err(CmdError::Input)?;
        if changed.is_empty() {
            return Ok(format!("vectors of {n} units: unchanged"));
        }
        let lines: Vec<String> = changed.iter().map(|c| format!("blessed: {c}")).collect();
        return Ok(lines.join("\n"));
    }
    let diffs = crate::vectors::check(dir, project.vectors()).map_err(CmdError::Input)?;
    if diffs.is_empty() {
        return Ok(format!(
            "vectors of {n} units: every row equal to {}",
            dir.display()
        ));
    }
    for d in &diffs {
        super::say(&format!("{d}\n"));
    }
    Err(CmdError::Failed(format!(
        "vectors: {} of {n} units differ from {}",
        diffs.len(),
        dir.display()
    )))
}

fn export(project: &Project, unit: &str, out: &Path) -> Result<String, CmdError> {
    let v = project
        .vectors_of(unit, "--unit")
        .map_err(CmdError::Input)?;
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
