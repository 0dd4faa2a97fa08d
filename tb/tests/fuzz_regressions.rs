//! Every input the fuzz campaign (`fuzz/campaign`) found a crash with, kept in
//! `fuzz/regressions/summary/`, read and merged as `texrtl merge` does: a clean error or a
//! merged summary, never a panic.

use std::path::{Path, PathBuf};

#[test]
fn summaries_that_once_crashed_merge_now_give_a_clean_answer() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/regressions/summary");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        let bytes = std::fs::read(&p).unwrap();
        let r = verif::regress::parse_summary(&p, &bytes).and_then(|s| {
            verif::regress::merge_shards(&tb::project::project(), &[(PathBuf::from(&p), s)])
        });
        if let Err(e) = r {
            assert!(!e.contains('\n'), "{}: {e}", p.display());
        }
        n += 1;
    }
    assert!(n > 0, "no regression inputs in {}", dir.display());
}

/// Every M.json the campaign crashed the reader with, kept in `fuzz/regressions/maps_json/`:
/// read as `texrtl mapchain` reads it, a description or one line.
#[test]
fn map_descriptions_that_once_crashed_give_one_line() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/regressions/maps_json");
    let tmp = std::env::temp_dir().join(format!("texrtl-maps-regress-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = tmp.join("M.json");
        std::fs::write(&p, std::fs::read(e.unwrap().path()).unwrap()).unwrap();
        if let Err(e) = formats::maps_json::read(&p) {
            assert!(!e.contains('\n') && e.len() < 400, "{e}");
        }
        n += 1;
    }
    let _ = std::fs::remove_dir_all(&tmp);
    assert!(n > 0, "no regression inputs in {}", dir.display());
}
