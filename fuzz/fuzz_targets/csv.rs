//! CSV tables as the commands read them (each header they accept), every field as a finite
//! number: parses or refuses with one line.
#![no_main]
use libfuzzer_sys::fuzz_target;

const HEADERS: &[&str] = &["u,v", "addr", "u,v,dudx,dvdx,dudy,dvdy", "u,v,lambda"];

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match formats::csv::parse("f.csv", text, HEADERS) {
        Ok(t) => {
            for r in &t.rows {
                assert_eq!(r.fields.len(), t.columns.len());
                for c in 0..t.columns.len() {
                    if let Err(e) = t.finite(r, c) {
                        assert!(!e.contains('\n') && e.len() < 300, "{e}");
                    }
                }
            }
        }
        Err(e) => assert!(!e.contains('\n') && e.len() < 300, "{e}"),
    }
});
