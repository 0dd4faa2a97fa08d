//! The units' systems import one another in one direction only: no cycle among the top-level
//! modules (`bump`, `envmap`, `texram`, ...) of the units crate, read from their `use` lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Each top-level module and the other top-level modules its files `use`.
fn imports(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut g = BTreeMap::new();
    for dir in std::fs::read_dir(src).unwrap().flatten() {
        if !dir.path().is_dir() {
            continue;
        }
        let name = dir.file_name().to_string_lossy().into_owned();
        let mut uses = BTreeSet::new();
        for f in std::fs::read_dir(dir.path()).unwrap().flatten() {
            let text = std::fs::read_to_string(f.path()).unwrap_or_default();
            for line in text
                .lines()
                .map(str::trim)
                .filter(|l| l.starts_with("use crate::"))
            {
                let m = line["use crate::".len()..]
                    .split([':', ';'])
                    .next()
                    .unwrap();
                if m != name && src.join(m).is_dir() {
                    uses.insert(m.to_string());
                }
            }
        }
        g.insert(name, uses);
    }
    g
}

/// Whether a cycle runs through `at` from the modules on `path` (depth first).
fn cycle(g: &BTreeMap<String, BTreeSet<String>>, at: &str, path: &mut Vec<String>) -> bool {
    let seen = path.iter().any(|p| p == at);
    path.push(at.into());
    if seen {
        return true;
    }
    for next in g.get(at).into_iter().flatten() {
        if cycle(g, next, path) {
            return true;
        }
    }
    path.pop();
    false
}

#[test]
fn the_systems_import_one_another_without_a_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let g = imports(&src);
    assert!(g.len() > 5, "the systems were found: {g:?}");
    assert!(
        g["envmap"].contains("bump"),
        "the reader sees imports: {g:?}"
    );
    for m in g.keys() {
        let mut path = Vec::new();
        assert!(
            !cycle(&g, m, &mut path),
            "import cycle: {}",
            path.join(" -> ")
        );
    }
    // The reader finds a cycle where there is one.
    let mut two = BTreeMap::new();
    two.insert("a".to_string(), BTreeSet::from(["b".to_string()]));
    two.insert("b".to_string(), BTreeSet::from(["a".to_string()]));
    assert!(cycle(&two, "a", &mut Vec::new()));
}
