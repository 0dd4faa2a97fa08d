//! The project, the one list of the units: its shards, what each testbench counts, and the
//! tables and files that must agree with it.

use std::collections::BTreeSet;
use std::path::Path;
use tb::project::project;
use verif::Shard;

/// The shards of every split deal out each configuration once: their counts add up to the
/// whole run's, testbench by testbench and over all.
#[test]
fn shards_own_every_configuration_once() {
    let project = project();
    let reg = project.registry();
    let whole: u64 = reg.iter().map(|t| t.configurations().len() as u64).sum();
    assert!(
        whole > reg.names().len() as u64,
        "some testbench has several"
    );
    assert_eq!(reg.owned_configurations(Shard::default(), &[]), whole);
    for count in [2, 3, 7] {
        let shards = (1..=count).map(|index| Shard { index, count });
        let parts: Vec<u64> = shards.map(|s| reg.owned_configurations(s, &[])).collect();
        assert_eq!(parts.iter().sum::<u64>(), whole, "{count} shards");
    }
    for (i, t) in reg.iter().enumerate() {
        let only = [t.name().to_string()];
        let n = reg.owned_configurations(Shard::default(), &only);
        assert_eq!(n, t.configurations().len() as u64, "{}", t.name());
        assert_eq!(reg.position(t.name()), Some(i));
    }
}

/// The progress line's unit: the default for a testbench of random transactions, its own
/// for one that counts something else.
#[test]
fn each_testbench_says_what_its_count_counts() {
    let project = project();
    let reg = project.registry();
    let unit = |n: &str| reg.get(n).unwrap().count_unit();
    assert_eq!(unit(tb::blend_adjust::NAME), "random transactions");
    assert_ne!(unit(tb::texture::NAME), "random transactions");
    assert!(reg.iter().all(|t| !t.count_unit().is_empty()));
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
}

/// The backticked names of a column of a markdown table (rows starting with `|` or `//! |`).
fn column(text: &str, col: usize) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    for line in text.lines() {
        let line = line.trim_start_matches("//!").trim();
        if !line.starts_with('|') || line.starts_with("|---") {
            continue;
        }
        if let Some(cell) = line.split('|').nth(col + 1) {
            for part in cell.split('`').skip(1).step_by(2) {
                names.insert(part.to_string());
            }
        }
    }
    names
}

/// The unit table of the units crate names every unit of the project as a kind (or an
/// instance), every testbench it names is one of the project's, and it names every twin's
/// sources and every unit's kept vectors, which exist.
#[test]
fn the_unit_table_agrees_with_the_project() {
    let p = project();
    let table = read("../hdl/units/src/lib.rs");
    let kinds = column(&table, 2);
    for u in p.units() {
        assert!(
            kinds.contains(u.name()),
            "{} is not in the unit table",
            u.name()
        );
    }
    let tbs = column(&table, 3);
    for t in tbs
        .iter()
        .filter(|t| !t.contains('/') && !t.ends_with(".rs"))
    {
        assert!(
            p.registry().get(t).is_some(),
            "the unit table names testbench {t}"
        );
    }
    for t in p.registry().names() {
        assert!(tbs.contains(t), "testbench {t} is not in the unit table");
    }
    let twins = column(&table, 5);
    for f in &twins {
        let path = tb::cosim::rtl_dir().join(f);
        assert!(path.exists(), "the unit table names twin {f}, not in rtl/");
    }
    for u in p.twins() {
        for f in u.rtl() {
            let f = f.to_string_lossy();
            let name = &f[f.rfind("rtl/").map_or(0, |k| k + 4)..];
            assert!(twins.contains(name), "{} is not in the unit table", name);
        }
    }
    let vectors = column(&table, 6);
    for f in &vectors {
        let path = tb::vectors::vectors_dir().join(f);
        assert!(path.exists(), "the unit table names vectors {f}, not kept");
    }
    for u in p.units().filter(|u| u.vectors_fn().is_some()) {
        let f = format!("{}.json", u.name());
        assert!(vectors.contains(&f), "{f} is not in the unit table");
    }
}

/// Every unit with a testbench keeps bit-accuracy vectors, or says in its descriptor why not.
#[test]
fn every_testbench_unit_has_vectors_or_a_reason() {
    let p = project();
    for u in p.units().filter(|u| !p.testbenches_of(u.name()).is_empty()) {
        assert!(
            u.vectors_fn().is_some() || u.no_vectors_reason().is_some(),
            "{} has a testbench but no vectors and no reason",
            u.name()
        );
    }
}

/// No list of unit names is kept by hand beside the project: no `UNITS` constant, no
/// `registry()` and no `match` on unit names in the crates that serve the command line.
#[test]
fn no_other_list_of_units() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in ["tb/src", "cli/src", "bench/src", "verif/src"] {
        collect(&root.join(dir), &mut files);
    }
    let names: Vec<String> = project()
        .names()
        .iter()
        .map(|n| format!("\"{n}\" =>"))
        .collect();
    for f in files.iter().filter(|f| !f.ends_with("tb/src/project.rs")) {
        let text = std::fs::read_to_string(f).unwrap();
        for bad in ["const UNITS", "fn registry()", "fn unit_vectors("] {
            assert!(!text.contains(bad), "{}: {bad}", f.display());
        }
        for n in &names {
            assert!(
                !text.contains(n.as_str()),
                "{}: a match on {n}",
                f.display()
            );
        }
    }
}

fn collect(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            collect(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}
