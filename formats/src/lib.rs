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

pub use waves::output::{self, read_bounded, shorten};

/// The largest file an image, table or mesh input may be (an ASCII PPM of 4096 x 4096 pixels
/// fits): an endless device such as `/dev/zero` is refused at this size, not read forever.
pub const MAX_INPUT_BYTES: u64 = 256 << 20;

/// [`read_bounded`] as UTF-8 text.
pub fn read_text_bounded(path: &std::path::Path, max: u64) -> Result<String, String> {
    String::from_utf8(read_bounded(path, max)?)
        .map_err(|_| format!("{}: stream did not contain valid UTF-8", path.display()))
}
