//! texrtl's hardware side: the RTL kernel, bit-accurate fixed point and the datapath models.
//!
//! No floating point is used inside a model: values are integers with a declared
//! [`fx::Format`]; conversions to `f64` exist only at the edges (tracing, golden comparison).

pub mod fx;
pub mod kernel;

pub mod blend_adjust;

// The FIG. 7 normal pipeline of US 2004/0207631, one module per unit.
pub mod address;
pub mod bilinear;
pub mod bump_params;
pub mod height_map;
pub mod normal;
pub mod normal_pipeline;
pub mod replicate;
pub mod rsqrt;
pub mod tangent;
pub mod texel_fetch;

// Real-time mipmap generation for interlaced video (Schilling & Knittel, section 12, FIG. 14).
pub mod fifo;
pub mod mipmap;

// The texture memory path (Schilling & Knittel, Figure 6): DRAM 604 and control unit 607,
// CCC decode 608/610/612, cache 614, colour extract 618, bilinear 622, and the unit 602.
pub mod ccc_decode;
pub mod color_bilinear;
pub mod color_extract;
pub mod dram;
pub mod texture_cache;
pub mod texture_layout;
pub mod texture_unit;
