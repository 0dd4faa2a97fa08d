//! `texrtl new NAME`: a user crate outside texrtl's workspace, depending on texrtl by path: a
//! small unit in the documented style (a saturating accumulator), its golden model, a
//! testbench with coverage, its Verilog twin, its descriptor and kept vectors, and a README
//! with the two commands. It is `examples/sat_acc` with `sat_acc` renamed NAME.

use super::{input, CmdError, Outputs};
use clap::Args;
use std::path::{Path, PathBuf};

/// Write a user crate: a unit, its golden model, testbench, Verilog twin, descriptor, vectors.
#[derive(Args, Debug)]
pub struct NewArgs {
    /// The crate's name, also its unit's, its Verilog module's and its vectors' (a lower-case
    /// letter, then letters, digits or '_'; at most 40).
    pub name: String,
    /// Folder to create the crate in (default: ./NAME).
    #[arg(long)]
    pub dir: Option<PathBuf>,
    /// The texrtl checkout the crate depends on by path (default: the one this texrtl was
    /// built from).
    #[arg(long)]
    pub texrtl: Option<PathBuf>,
}

/// The template's files, by their path in the crate (`sat_acc` renamed on writing).
const FILES: [(&str, &str); 12] = [
    (
        "Cargo.toml",
        include_str!("../../../examples/sat_acc/Cargo.toml"),
    ),
    (
        "README.md",
        include_str!("../../../examples/sat_acc/README.md"),
    ),
    (
        ".gitignore",
        include_str!("../../../examples/sat_acc/.gitignore"),
    ),
    (
        "rustfmt.toml",
        include_str!("../../../examples/sat_acc/rustfmt.toml"),
    ),
    (
        "src/lib.rs",
        include_str!("../../../examples/sat_acc/src/lib.rs"),
    ),
    (
        "src/main.rs",
        include_str!("../../../examples/sat_acc/src/main.rs"),
    ),
    (
        "src/unit.rs",
        include_str!("../../../examples/sat_acc/src/unit.rs"),
    ),
    (
        "src/tb.rs",
        include_str!("../../../examples/sat_acc/src/tb.rs"),
    ),
    (
        "rtl/sat_acc.v",
        include_str!("../../../examples/sat_acc/rtl/sat_acc.v"),
    ),
    (
        "tests/cosim.rs",
        include_str!("../../../examples/sat_acc/tests/cosim.rs"),
    ),
    (
        "vectors/sat_acc.json",
        include_str!("../../../examples/sat_acc/vectors/sat_acc.json"),
    ),
    (
        "vectors/sat_acc.rows",
        include_str!("../../../examples/sat_acc/vectors/sat_acc.rows"),
    ),
];

/// Names a crate, a Rust module and a Verilog module cannot take, or that clash with the
/// crate's dependencies.
const RESERVED: [&str; 24] = [
    "hdl", "verif", "waves", "proptest", "std", "core", "alloc", "test", "self", "super", "crate",
    "type", "fn", "mod", "use", "impl", "module", "input", "output", "wire", "reg", "begin", "end",
    "assign",
];

fn check_name(name: &str) -> Result<(), CmdError> {
    let shown = waves::output::shorten(name);
    let ok = name.len() <= 40
        && name.starts_with(|c: char| c.is_ascii_lowercase())
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !ok {
        return Err(input(format!(
            "NAME {shown}: a lower-case letter, then lower-case letters, digits or '_', at most 40"
        )));
    }
    if RESERVED.contains(&name) {
        return Err(input(format!(
            "NAME {shown}: reserved in Rust, Verilog or by a dependency"
        )));
    }
    Ok(())
}

/// Writes the crate.
pub fn run(a: &NewArgs) -> Result<String, CmdError> {
    check_name(&a.name)?;
    let dir = a.dir.clone().unwrap_or_else(|| PathBuf::from(&a.name));
    if dir.symlink_metadata().is_ok() {
        return Err(input(format!(
            "--dir {}: exists; choose a new folder",
            dir.display()
        )));
    }
    verif::cli::check_folder("--dir", &dir)?;
    let built_from = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let texrtl = a.texrtl.clone().unwrap_or(built_from);
    let texrtl = texrtl
        .canonicalize()
        .ok()
        .filter(|t| t.join("verif/Cargo.toml").is_file());
    let texrtl = texrtl.ok_or_else(|| {
        input("--texrtl: not a texrtl checkout (no verif/Cargo.toml); give the folder".into())
    })?;
    let mut made = Outputs::default();
    made.folder(&dir);
    made.settle(write_crate(&a.name, &dir, &texrtl))
}

fn write_crate(name: &str, dir: &Path, texrtl: &Path) -> Result<String, CmdError> {
    let root = texrtl.to_string_lossy().replace('\\', "/");
    for (file, text) in FILES {
        let path = dir.join(file.replace("sat_acc", name));
        let mut text = text.replace("sat_acc", name);
        if file == "Cargo.toml" {
            text = text.replace("path = \"../..", &format!("path = \"{root}"));
        }
        let parent = path.parent().unwrap_or(dir);
        verif::cli::make_folder("--dir", parent)?;
        waves::output::write_output(&path, text.as_bytes())
            .map_err(|e| input(format!("{}: {e}", path.display())))?;
    }
    Ok(format!(
        "{name}: a unit with its golden model, testbench, Verilog twin and vectors in {}; cd there, then `cargo test` and `cargo run`",
        dir.display()
    ))
}
