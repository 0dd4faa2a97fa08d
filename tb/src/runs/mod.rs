//! The units' runs that are not testbenches, one module a unit, over the same models, drivers
//! and references as the unit's testbench: what the `texrtl` commands do with a user's input,
//! what the regression vectors replay, and the measurements behind the report's tables (the
//! document's timings and rates, the footprint's quality, the video port's cost), which the
//! testbenches' conclusions hold against the document.

pub mod dram;
pub mod footprint;
pub mod mapchain;
pub mod mipmap;
pub mod normals;
pub mod ptm;
pub mod tangents;
pub mod texram;
pub mod texram_video;
pub mod texture;
pub mod volume;
