//! Real-time mipmap generation for interlaced video (Schilling & Knittel, section 12,
//! FIG. 14): the generation unit 816 with its levels (adders 1402 and 1410, register 1404,
//! FIFOs 1408 and 1412) and frame store.

pub mod fifo;
pub mod level_fig14;
pub mod mipmap_gen_816;

pub use mipmap_gen_816::{FrameBuffer, MipmapGen, MipmapParams, Rounding, Scan};
