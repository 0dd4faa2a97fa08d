//! texrtl's testbenches and the machinery of the `texrtl` program.
//!
//! One module per testbench, named after the unit it verifies; `regress` runs them all.

pub mod blend_adjust;
pub mod ccc;
pub mod commands;
pub mod dram;
pub mod maps;
pub mod mipmap;
pub mod normals;
pub mod pgm;
pub mod plots;
pub mod regress;
pub mod report;
pub mod texcmd;
pub mod texture;
pub mod vectors;
