//! The TEXRAM's slots in the report: what each configuration's layout costs a scanline.

use units::texram::{Border, Config, Drf};

/// Slots per pixel, and slots lost per scanline to page faults and bank conflicts (beyond one
/// slot per component access), of each configuration, for the report's picture: a
/// 256x256-texel view rendered scanline by scanline (64 lines of 64 pixels, each pixel 4
/// texels along u, lambda 2.5) on a 512x512 map (colour layouts: 256x256 components). From the
/// stub, which the tests hold equal to the chip slot for slot.
pub fn layout_rows() -> Vec<(String, f64, f64)> {
    use units::texram::{TexramAccess, TexramRequest};
    let configs = [
        ("luminance", Config::Luminance, 9),
        ("index", Config::Index, 9),
        ("planar colour", Config::Planar, 9),
        ("literal colour", Config::Literal, 9),
    ];
    let mut rows = Vec::new();
    for (name, config, log2) in configs {
        let mut stub = units::texram::stub::TexramStub::new();
        let mut d = Drf::new(log2, log2, Border::Wrap);
        d.config = config;
        stub.set_drf(0, d).expect("fits");
        let (lines, px) = (64u64, 64u64);
        for y in 0..lines as i32 {
            for x in 0..px as i32 {
                let q = TexramRequest {
                    drf: 0,
                    u: (4 * x) << 8,
                    v: (4 * y) << 8,
                    lambda: 640,
                };
                stub.access(q).expect("in range");
            }
        }
        let parts = if matches!(config, Config::Planar | Config::Literal) {
            4
        } else {
            1
        };
        let slots = stub.slots();
        let lost = slots.saturating_sub(parts * lines * px);
        rows.push((
            name.to_string(),
            slots as f64 / (lines * px) as f64,
            lost as f64 / lines as f64,
        ));
    }
    rows
}
