//! Map linking (Schilling & Knittel section 14, Fig. 16) with the maps it links: detail maps
//! (section 9, Figs 9a/9b), reflectance maps (section 8, eq. 7) and environment maps
//! (section 7; the reflection vector and the cube face are in [`crate::envmap`]).
//!
//! * [`drf_812`](crate::mapchain::drf_812): the seven description register files of unit 812 and where maps go;
//! * [`detail_fig9`](crate::mapchain::detail_fig9): the detail path's arithmetic, units 902-914;
//! * [`program`](crate::mapchain::program): the walker's micro-program, one step per access;
//! * [`walker_812`](crate::mapchain::walker_812): the walker cycle by cycle over the banks ([`crate::texram::TexramAccess`]:
//!   the stub or the chip), with the output stage 820's eqs 5-7 at the chain's end.

pub mod detail_fig9;
pub mod drf_812;
pub mod program;
pub mod walker_812;
