//! Simulator builds reused across runs: a Verilator `simv` or an Icarus `sim.vvp` is kept,
//! keyed by everything it is built from, and a later run with the same key runs the kept one
//! instead of building again.
//!
//! The key is a hash of the simulator and its version line (and the C++ compiler's, for
//! Verilator), the build options (include folders and defines among them), the generated
//! testbench (ports, parameters, reset), every Verilog source's name and contents, and those
//! of every file the sources `` `include `` (found beside the including file and in the include
//! folders; a name given by a macro is not followed). The stimulus, the cycle count and the memory
//! images are read at run time from the run's folder, so they are not part of it: the
//! testbench names them by relative path and takes the cycle count as a plusarg.
//!
//! The cache is a folder (`TEXRTL_SIM_CACHE`, default `texrtl-sim-cache` in the system's
//! temporary folder; `TEXRTL_SIM_CACHE=off` builds every time). An entry is built in its run's
//! folder, copied into a temporary folder of the cache and renamed into place whole, so a
//! concurrent run sees an entry complete or not at all, and two runs that build the same key
//! keep one. A run reuses an entry through its own hard link or copy ([`take`]), so another
//! run pruning it cannot take it away mid-use. At most [`MAX_ENTRIES`] entries and
//! [`MAX_BYTES`] are kept, the least recently used removed first. Deleting the folder clears
//! it.
//!
//! A run is kept the same way: its outputs under a key of the build's key, the cycle count
//! and the run-time inputs' names and contents. A simulator is deterministic, so the same
//! build on the same inputs writes the same outputs; a kept run's are copied into the run's
//! folder instead of simulating again.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::OnceLock;

/// Entries kept at most (a Verilator `simv` of texrtl's twins is 1-10 MB, a run's outputs up
/// to a few MB) ...
pub const MAX_ENTRIES: usize = 256;
/// ... and bytes.
pub const MAX_BYTES: u64 = 1 << 30;

/// The environment variable naming the cache's folder, or `off`.
pub const CACHE_ENV: &str = "TEXRTL_SIM_CACHE";

/// The name of the marker file every complete entry holds (its mtime: the last use).
const DONE: &str = "done";

/// The cache's folder, `None` when switched off.
pub fn root() -> Option<PathBuf> {
    match std::env::var_os(CACHE_ENV) {
        Some(v) if v == "off" => None,
        Some(v) if !v.is_empty() => Some(PathBuf::from(v)),
        _ => Some(std::env::temp_dir().join("texrtl-sim-cache")),
    }
}

/// The first line a tool prints for `arg` (its version), or an empty string.
fn version_line(exe: &str, arg: &str) -> String {
    let Ok(o) = Command::new(exe).arg(arg).output() else {
        return String::new();
    };
    let out = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    out.lines().next().unwrap_or("").to_string()
}

/// The tools' version lines, asked once a process.
fn tool_versions() -> &'static String {
    static V: OnceLock<String> = OnceLock::new();
    V.get_or_init(|| {
        [
            version_line("verilator", "--version"),
            version_line("c++", "--version"),
            version_line("iverilog", "-V"),
        ]
        .join("\n")
    })
}

/// The key of a build: `what` names the simulator and its options; `tb` is the generated
/// testbench; `sources` the Verilog files (read here: an unreadable one has no key, and the
/// build that follows names it).
pub fn key(what: &str, tb: &str, sources: &[PathBuf]) -> Option<String> {
    let mut h = DefaultHasher::new();
    (what, tool_versions(), tb).hash(&mut h);
    let mut h2 = DefaultHasher::new();
    (tb, what).hash(&mut h2);
    for s in sources {
        let text = std::fs::read(s).ok()?;
        s.file_name().hash(&mut h);
        text.hash(&mut h);
        text.len().hash(&mut h2);
        text.hash(&mut h2);
    }
    tool_versions().hash(&mut h2);
    let name = what.split_whitespace().next().unwrap_or("sim");
    Some(format!("{name}-{:016x}{:016x}", h.finish(), h2.finish()))
}

/// The kept artifact of `key` (`file` in its entry), marked as just used; `None` on a miss.
pub fn lookup(root: &Path, key: &str, file: &str) -> Option<PathBuf> {
    let entry = root.join(key);
    let done = entry.join(DONE);
    if !done.is_file() {
        return None;
    }
    // The marker's mtime is the entry's last use (for the size bound).
    let _ = std::fs::write(&done, key);
    let f = entry.join(file);
    f.is_file().then_some(f)
}

/// The kept artifact of `key` (`file` in its entry) made the run's own at `dest`, so that
/// another run pruning the entry afterwards cannot take it away mid-use: a hard link when
/// `link` (a build, which nothing writes again; a copy across file systems), else a copy (an
/// output the run's folder may be rewritten with). `false` on a miss, or when the entry went
/// between the lookup and the link.
pub fn take(root: &Path, key: &str, file: &str, dest: &Path, link: bool) -> bool {
    let Some(kept) = lookup(root, key, file) else {
        return false;
    };
    let _ = std::fs::remove_file(dest);
    (link && std::fs::hard_link(&kept, dest).is_ok()) || std::fs::copy(&kept, dest).is_ok()
}

/// Keeps `artifact` as `key`'s entry: copied into a fresh temporary folder of the cache, then
/// renamed into place whole (a concurrent run that kept the same key first wins; the copy is
/// dropped). Then the oldest entries past the bounds go. Failures only cost a rebuild.
pub fn store(root: &Path, key: &str, artifact: &Path) {
    static N: AtomicU64 = AtomicU64::new(0);
    let Some(name) = artifact.file_name() else {
        return;
    };
    if std::fs::create_dir_all(root).is_err() {
        return;
    }
    let n = N.fetch_add(1, Ordering::Relaxed);
    let tmp = root.join(format!(".tmp-{}-{n}", std::process::id()));
    let made = std::fs::create_dir_all(&tmp)
        .and_then(|_| std::fs::copy(artifact, tmp.join(name)))
        .and_then(|_| std::fs::write(tmp.join(DONE), key))
        .and_then(|_| std::fs::rename(&tmp, root.join(key)));
    if made.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    prune(root, MAX_ENTRIES, MAX_BYTES);
}

/// The bytes of the files in `dir`.
fn size(dir: &Path) -> u64 {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return 0;
    };
    rd.flatten()
        .filter_map(|e| e.metadata().ok())
        .map(|m| m.len())
        .sum()
}

/// Removes the least recently used entries until at most `keep` remain, holding at most
/// `bytes`.
pub fn prune(root: &Path, keep: usize, bytes: u64) {
    let Ok(rd) = std::fs::read_dir(root) else {
        return;
    };
    let mut entries: Vec<(std::time::SystemTime, PathBuf, u64)> = rd
        .flatten()
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .filter_map(|e| {
            let used = e
                .path()
                .join(DONE)
                .metadata()
                .and_then(|m| m.modified())
                .ok()?;
            Some((used, e.path(), size(&e.path())))
        })
        .collect();
    entries.sort();
    let mut total: u64 = entries.iter().map(|e| e.2).sum();
    let mut left = entries.len();
    for (_, p, n) in &entries {
        if left <= keep && total <= bytes {
            break;
        }
        let _ = std::fs::remove_dir_all(p);
        left -= 1;
        total -= n;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(tag: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("texrtl-cache-test-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// The key changes with the testbench, a source's contents, its name and the tool; it
    /// does not change with the folder the sources are in.
    #[test]
    fn the_key_is_what_the_build_is_made_of() {
        let d = folder("key");
        let (a, b) = (d.join("a.v"), d.join("sub/a.v"));
        std::fs::create_dir_all(b.parent().unwrap()).unwrap();
        std::fs::write(&a, "module a; endmodule\n").unwrap();
        std::fs::write(&b, "module a; endmodule\n").unwrap();
        let k = |what: &str, tb: &str, s: &PathBuf| key(what, tb, std::slice::from_ref(s)).unwrap();
        let base = k("verilator -O3", "tb", &a);
        assert_eq!(base, k("verilator -O3", "tb", &b), "same name and contents");
        assert_ne!(base, k("verilator -O3", "tb2", &a));
        assert_ne!(base, k("iverilog -g2012", "tb", &a));
        std::fs::write(&b, "module a; wire w; endmodule\n").unwrap();
        assert_ne!(base, k("verilator -O3", "tb", &b));
        let c = d.join("c.v");
        std::fs::copy(&a, &c).unwrap();
        assert_ne!(base, k("verilator -O3", "tb", &c), "another file name");
        assert_eq!(key("x", "tb", &[d.join("missing.v")]), None);
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A taken artifact is the run's own: pruning its entry afterwards (another run keeping
    /// its own) leaves it whole; an entry that is gone is a miss.
    #[test]
    fn a_taken_artifact_outlives_its_entry() {
        let d = folder("take");
        let root = d.join("cache");
        let art = d.join("simv");
        std::fs::write(&art, b"binary").unwrap();
        store(&root, "k1", &art);
        for link in [true, false] {
            let mine = d.join(format!("mine-{link}"));
            assert!(take(&root, "k1", "simv", &mine, link));
            assert_eq!(std::fs::read(&mine).unwrap(), b"binary");
        }
        prune(&root, 0, MAX_BYTES);
        assert_eq!(std::fs::read(d.join("mine-true")).unwrap(), b"binary");
        assert!(!take(&root, "k1", "simv", &d.join("again"), true));
        std::fs::remove_dir_all(&d).unwrap();
    }

    /// A stored artifact is found under its key with the same bytes; a second store of the
    /// key keeps one entry; past the bound the least recently used go, and nothing but
    /// entries.
    #[test]
    fn entries_are_kept_whole_and_bounded() {
        let d = folder("store");
        let root = d.join("cache");
        let art = d.join("simv");
        std::fs::write(&art, b"binary").unwrap();
        assert_eq!(lookup(&root, "k1", "simv"), None);
        store(&root, "k1", &art);
        store(&root, "k1", &art);
        let got = lookup(&root, "k1", "simv").unwrap();
        assert_eq!(std::fs::read(got).unwrap(), b"binary");
        let names = |r: &Path| {
            let mut v: Vec<String> = std::fs::read_dir(r)
                .unwrap()
                .flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect();
            v.sort();
            v
        };
        assert_eq!(names(&root), ["k1"], "one entry, no temporary left");
        for k in ["k2", "k3"] {
            std::thread::sleep(std::time::Duration::from_millis(20));
            store(&root, k, &art);
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
        lookup(&root, "k1", "simv").unwrap(); // k1 used last: k2 is the oldest
        prune(&root, 2, MAX_BYTES);
        assert_eq!(names(&root), ["k1", "k3"]);
        prune(&root, 2, 2 * (6 + 2) - 1); // each entry: "binary" and a 2-byte marker
        assert_eq!(names(&root), ["k1"], "the oldest goes for size too");
        // A dot-named folder (Verilator's runtime objects) is not an entry: never pruned.
        let runtime = root.join(".verilator-runtime-0");
        std::fs::create_dir_all(&runtime).unwrap();
        std::fs::write(runtime.join("verilated.o"), b"object").unwrap();
        prune(&root, 0, 0);
        assert_eq!(names(&root), [".verilator-runtime-0"]);
        std::fs::remove_dir_all(&d).unwrap();
    }
}
