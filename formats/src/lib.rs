//! texrtl's file formats, apart from the testbenches and the command line that use them:
//!
//! * [`netpbm`]: 8-bit PGM (P5, P2) and PPM (P6, P3) images, read strictly;
//! * [`csv`]: the request and trace tables the commands read (a header naming the columns,
//!   one row per line), with errors that name the file, the line and the column;
//! * [`ccc`]: the `.ccc` colour-cell-compressed texture format and its offline encoder;
//! * [`obj`]: Wavefront OBJ meshes for the tangent frames;
//! * [`maps_json`]: the map chain's description (its DRFs and the map files they name);
//! * [`ptm`]: the `.ptm` occlusion PTM as the hardware stores it;
//! * [`output`]: writing a file so that no partial file is ever left behind.

pub mod ccc;
pub mod csv;
pub mod maps_json;
pub mod netpbm;
pub mod obj;
pub mod ptm;

pub use waves::output::{self, shorten};
