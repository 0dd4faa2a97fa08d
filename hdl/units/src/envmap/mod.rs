//! Environment mapping (Schilling & Knittel section 7): the local frame of eqs 2-3, the
//! reflection vector of eq. 4 and the cube-face selection. The chain walker of 812
//! ([`crate::mapchain`]) reads the face's mipmap at the coordinates they give.

pub mod cube_face;
pub mod frame_eq2;
pub mod reflect_eq4;
