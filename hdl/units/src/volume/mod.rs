//! Volume rendering on the TEXRAM chip (Schilling & Knittel section 13, Figure 15): "only
//! the four larger memory arrays in the TEXRAM holding level 0" (banks 810, 0-3) as a voxel
//! store, a 3-D sample stepper (the footprint generator of section 10 in three dimensions)
//! and the trilinear interpolator, reading the eight voxels round a resample point in two
//! accesses ("value mode"), or the 32 voxels its central-difference gradient needs in eight
//! ("gradient mode"). Compositing is off-chip (the golden model has one).
//!
//! * [`layout`](crate::volume::layout): voxel `(x, y, z)` to bank and word, the border operation, the accesses of a
//!   resample point in each mode (each reads four voxels from four different banks: proved
//!   exhaustively in its tests);
//! * [`interp`](crate::volume::interp): the value and gradient arithmetic of one resample point;
//! * [`ray_caster_fig15`](crate::volume::ray_caster_fig15): the cycle-accurate ray caster: ray port, stepper, accesses through
//!   the page registers, interpolation, sample port;
//! * [`lockstep`](crate::volume::lockstep): pre-classified RGBA on four chips in lock-step.
//!
//! The document gives the data path and two timings; the rest is \[C\] (see
//! `../shared/notes/seed-systems.md` section 3 and the README).

pub mod interp;
pub mod layout;
pub mod lockstep;
pub mod ray_caster_fig15;
