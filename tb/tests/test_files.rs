//! The tests folder itself: what the mutation run's one test binary gathers, and that every
//! test of the crate is here, none in its library.

/// tests/mutants.rs, the mutation run's one test binary, gathers every test file of tests/
/// but those left out for time (co-simulation, the fuzz regressions): a new test
/// file that is not added there would judge no mutant.
#[test]
fn the_mutation_binary_gathers_every_testbench_test_file() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let gathered = std::fs::read_to_string(dir.join("mutants.rs")).unwrap();
    let left_out = ["cosim", "fuzz_regressions", "mutants"];
    let mut files = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let Some(stem) = name.strip_suffix(".rs") else {
            continue;
        };
        let line = format!("#[path = \"{name}\"]\nmod {stem};");
        assert_eq!(
            gathered.contains(&line),
            !left_out.contains(&stem),
            "{name}"
        );
        files += 1;
    }
    assert!(files > 20, "{files} test files");
}

/// The library's own tests would never run: its manifest says `test = false` (it is not
/// compiled a second time for them), so every test of the crate is in tests/.
#[test]
fn the_library_holds_no_tests() {
    fn walk(dir: &std::path::Path, found: &mut Vec<String>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, found);
            } else if std::fs::read_to_string(&p).unwrap().contains("#[test]") {
                found.push(p.display().to_string());
            }
        }
    }
    let mut found = Vec::new();
    walk(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &mut found,
    );
    assert!(
        found.is_empty(),
        "tests in the library, never run: {found:?}"
    );
}
