//! Footprint assembly (Schilling & Knittel section 10, Figures 12 and 13): anisotropic
//! filtering by N trilinear accesses along the longer edge of the pixel's footprint.
//!
//! * [`setup_fig12`](crate::footprint::setup_fig12): the rasterizer-side setup unit (eqs 19-21): N, the step and the level
//!   of detail from the screen derivatives, with no square root or division;
//! * [`assembly_fig12`](crate::footprint::assembly_fig12): the chip-side sample generator (eq. 22) and accumulator in front of
//!   the TEXRAM chip 802: N accesses a pixel, the exact sum of their trilinear sums, one
//!   rounding of the mean, and the same at transaction level over any `TexramAccess`;
//! * [`footprint_fig12`](crate::footprint::footprint_fig12): the two together in front of the chip;
//! * [`normals_0081`](crate::footprint::normals_0081): the generator in front of the FIG. 7 height-map pipeline, whose
//!   tangents are averaged over the samples and normalised once (Fenney para. 0081).

pub mod assembly_fig12;
pub mod footprint_fig12;
pub mod normals_0081;
pub mod setup_fig12;
