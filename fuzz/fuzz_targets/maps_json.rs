//! The map chain's description (M.json) as `texrtl mapchain` reads it: every DRF it accepts
//! is in range and described once, or it refuses with one short line. The bytes are written
//! to a file of this process first (the reader resolves the maps it names beside it).
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

static FILE: OnceLock<std::path::PathBuf> = OnceLock::new();

fuzz_target!(|data: &[u8]| {
    let path = FILE.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("texrtl-fuzz-maps-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d.join("M.json")
    });
    std::fs::write(path, data).unwrap();
    match formats::maps_json::read(path) {
        Ok(specs) => {
            let mut seen = std::collections::BTreeSet::new();
            for s in &specs {
                assert!(seen.insert(s.index), "a DRF described twice was accepted");
            }
        }
        Err(e) => assert!(!e.contains('\n') && e.len() < 400, "{e}"),
    }
});
