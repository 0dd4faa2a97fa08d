//! Tangent frames (003) and the per-pixel frame unit (003, 002): the per-triangle tangent
//! setup unit, and the unit that perturbs a pixel's normal in its frame (bump maps, normal
//! maps), and parallax mapping (002).

pub mod frame_unit;
pub mod parallax;
pub mod tangent_setup;
