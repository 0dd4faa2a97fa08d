//! The FIG. 7 normal pipeline of US 2004/0207631 (Fenney, bump mapping), one file per unit,
//! named after the unit and its number: address unit 150, texel fetch 151, replicate 152,
//! blend-factor adjust 153, bilinear units 65-68, tangent unit 155, normal unit 156 with its
//! inverse square root; the pipeline top that wires them as the figure does; its parameters
//! and the height map it reads; and para. 0081's tangent average for footprint assembly.

pub mod address_150;
pub mod bilinear_65_68;
pub mod biquadratic_0087;
pub mod blend_adjust_153;
pub mod derivative_0086;
pub mod height_map;
pub mod normal_156;
pub mod normal_pipeline_fig7;
pub mod packed_0055;
pub mod params;
pub mod replicate_152;
pub mod rsqrt_156;
pub mod tangent_155;
pub mod tangent_average_0081;
pub mod texel_fetch_151;
