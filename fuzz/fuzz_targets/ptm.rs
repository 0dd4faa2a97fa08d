//! `.ptm` occlusion PTMs as `texrtl ptm eval` reads them: parses (what it writes back parses
//! to the same PTM, of the size its header declares) or refuses with one short line.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match formats::ptm::Ptm::parse(data) {
        Ok(p) => {
            assert_eq!(p.q.len(), 6 * p.width as usize * p.height as usize);
            assert_eq!(formats::ptm::Ptm::parse(&p.to_bytes()).as_ref(), Ok(&p));
        }
        Err(e) => assert!(!e.contains('\n') && e.len() < 300, "{e}"),
    }
});
