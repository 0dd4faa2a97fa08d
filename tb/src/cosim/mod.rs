//! The texture units' co-simulation adapters: each unit with a Verilog twin in `rtl/` as a
//! [`verif::cosim::CosimUnit`] (its model, its sources, its parameters, its stimulus), named
//! after the unit, and the regression vectors' transactions as directed runs ([`vectors`]).
//! The descriptors of [`crate::project`] register them; the harness is the framework's.

pub mod bump;
pub mod mapchain;
pub mod mipmap;
pub mod texmem;
pub mod texram;
pub mod vectors;

pub use bump::*;
pub use mapchain::*;
pub use mipmap::*;
pub use texmem::*;
pub use texram::*;

use std::path::{Path, PathBuf};

/// The repository's `rtl/` folder (the twins).
pub fn rtl_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rtl")
}

/// Twin sources named relative to [`rtl_dir`].
pub fn twin(files: Vec<&str>) -> Vec<PathBuf> {
    files.into_iter().map(|f| rtl_dir().join(f)).collect()
}
