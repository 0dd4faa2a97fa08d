//! Environment mapping (Schilling & Knittel section 7, issue 15): so far the cube-face
//! selection unit; the reflection vector of eq. 4, the face's mipmap through DRF 7 and the
//! chain walker are the rest of the issue.

pub mod cube_face;
