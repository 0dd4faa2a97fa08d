//! `summary.json` as `texrtl merge` reads it: parsed, then merged as a one-shard run (which
//! checks the shard, the version, the coverage models and the counters).
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

static PROJECT: OnceLock<verif::project::Project> = OnceLock::new();

fuzz_target!(|data: &[u8]| {
    let project = PROJECT.get_or_init(tb::project::project);
    let p = Path::new("s.json");
    let Ok(s) = verif::regress::parse_summary(p, data) else {
        return;
    };
    if let Err(e) = verif::regress::merge_shards(project, &[(PathBuf::from(p), s)]) {
        assert!(!e.contains('\n'), "{e}");
    }
});
