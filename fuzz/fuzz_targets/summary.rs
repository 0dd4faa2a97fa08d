//! `summary.json` as `texrtl merge` reads it: parsed, then merged as a one-shard run (which
//! checks the shard, the version, the coverage models and the counters).
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::{Path, PathBuf};

thread_local! {
    // A project holds testbenches that are not Send: one per thread (libFuzzer runs one).
    static PROJECT: &'static verif::project::Project = Box::leak(Box::new(tb::project::project()));
}

fuzz_target!(|data: &[u8]| {
    let project = PROJECT.with(|p| *p);
    let p = Path::new("s.json");
    let Ok(s) = verif::regress::parse_summary(p, data) else {
        return;
    };
    if let Err(e) = verif::regress::merge_shards(project, &[(PathBuf::from(p), s)]) {
        assert!(!e.contains('\n'), "{e}");
    }
});
