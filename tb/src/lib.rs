//! texrtl's testbenches: one module per testbench, named after the unit it verifies, each a
//! [`verif::Testbench`] with its driver, monitor, golden comparison, integer reference and
//! coverage model; [`regress`] holds the registry and runs them all; [`vectors`] keeps the
//! bit-accuracy vectors.

pub mod biquadratic;
pub mod blend_adjust;
pub mod cosim;
pub mod derivative;
pub mod dram;
pub mod footprint;
pub mod footprint_normals;
pub mod frames;
pub mod mapchain;
pub mod maps;
pub mod mipmap;
pub mod normals;
pub mod ptm;
pub mod regress;
pub mod tangents;
pub mod texram;
pub mod texram_video;
pub mod texture;
pub mod vectors;
pub mod volume;
