//! Wavefront OBJ meshes as `texrtl tangents` reads them: parses (every corner's indices in
//! range) or refuses with one short line.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match formats::obj::parse("m.obj", text) {
        Ok(m) => {
            for f in &m.faces {
                assert!(f.corners.len() >= 3);
                for c in &f.corners {
                    assert!(c.p < m.positions.len() && c.t < m.uvs.len());
                    assert!(c.n.is_none_or(|n| n < m.normals.len()));
                }
            }
        }
        Err(e) => assert!(!e.contains('\n') && e.len() < 300, "{e}"),
    }
});
