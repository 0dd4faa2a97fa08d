//! The units' runs that are not testbenches: what the `texrtl` commands do with a user's input
//! (and the regression vectors replay), one module a unit, over the same models, drivers and
//! references as the unit's testbench.

pub mod footprint;
pub mod mapchain;
pub mod texram;
pub mod volume;
