//! PGM (P2 and P5): parses or refuses; what parses holds width x height pixels.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(img) = formats::netpbm::parse(data) {
        assert_eq!(img.pixels.len(), img.width as usize * img.height as usize);
    }
});
