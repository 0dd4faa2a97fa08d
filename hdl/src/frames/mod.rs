//! Tangent frames (003): the per-triangle tangent setup unit in fixed point.

pub mod tangent_setup;
