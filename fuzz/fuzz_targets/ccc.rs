//! `.ccc` textures: parses or refuses; what parses writes back to the same bytes and decodes
//! to width x height texels.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(c) = formats::ccc::Ccc::parse(data) {
        assert_eq!(c.to_bytes(), data);
        assert_eq!(c.decode().len(), 3 * c.width as usize * c.height as usize);
    }
});
