//! The testbench tests that judge a mutant (`.cargo/mutants.toml`), gathered into one test
//! binary so that each mutant costs one link instead of one per file. Built only with the
//! `mutants` feature: a plain `cargo test` runs each file as its own binary, once.

#[path = "biquadratic.rs"]
mod biquadratic;
#[path = "blend_adjust.rs"]
mod blend_adjust;
#[path = "derivative.rs"]
mod derivative;
#[path = "dram.rs"]
mod dram;
#[path = "envmap.rs"]
mod envmap;
#[path = "footprint.rs"]
mod footprint;
#[path = "frames.rs"]
mod frames;
#[path = "hierarchy.rs"]
mod hierarchy;
#[path = "mapchain.rs"]
mod mapchain;
#[path = "mipmap.rs"]
mod mipmap;
#[path = "normals.rs"]
mod normals;
#[path = "project.rs"]
mod project;
#[path = "ptm.rs"]
mod ptm;
#[path = "tangents.rs"]
mod tangents;
#[path = "test_files.rs"]
mod test_files;
#[path = "texram.rs"]
mod texram;
#[path = "texram_video.rs"]
mod texram_video;
#[path = "texture.rs"]
mod texture;
#[path = "unit_address.rs"]
mod unit_address;
#[path = "unit_bilinear.rs"]
mod unit_bilinear;
#[path = "unit_replicate.rs"]
mod unit_replicate;
#[path = "unit_rsqrt.rs"]
mod unit_rsqrt;
#[path = "unit_tangent_normal.rs"]
mod unit_tangent_normal;
#[path = "unit_texel_fetch.rs"]
mod unit_texel_fetch;
#[path = "vectors.rs"]
mod vectors;
#[path = "volume.rs"]
mod volume;
