//! One file per subcommand, each owning its clap arguments and its `run`.

pub mod ccc;
pub mod dram;
pub mod footprint;
pub mod mapchain;
pub mod mipmap;
pub mod new;
pub mod normals;
pub mod ptm;
pub mod render;
pub mod sweep;
pub mod tangents;
pub mod texram;
pub mod texread;
pub mod volume;
pub mod widths;

pub use verif::cli::{check_outputs, input, parse_finite, same_file, write_out, CmdError, Outputs};
