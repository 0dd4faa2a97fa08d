//! Environment mapping (Schilling & Knittel section 7, issue 15): so far the local frame of
//! eqs 2-3, the reflection vector of eq. 4 and the cube-face selection; the face's mipmap
//! through DRF 7 and the chain walker are the rest of the issue.

pub mod cube_face;
pub mod frame_eq2;
pub mod reflect_eq4;
