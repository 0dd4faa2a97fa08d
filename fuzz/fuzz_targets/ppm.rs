//! PPM (P3 and P6): parses or refuses; what parses holds width x height x 3 samples.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(img) = formats::netpbm::parse_ppm(data) {
        assert_eq!(img.pixels.len(), 3 * img.width as usize * img.height as usize);
    }
});
