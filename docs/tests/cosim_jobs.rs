//! A regression's co-simulations as jobs, on the guide's blend with a rare bug planted in its
//! Verilog: each seed co-simulates its own stimulus, the row fails exactly for the seeds whose
//! stimulus reaches the bug (predicted from the stimulus, not from the run), each failing
//! seed is a failing job with the command that reproduces it, and the run dealt to shards
//! merges to the one machine's rows and failing jobs; a shard left out is named. A twin whose
//! Verilog does not build fails its row, and the run goes on.

use guide::blend::Blend;
use hdl::kernel::Signal;
use std::path::{Path, PathBuf};
use verif::cosim::{CosimUnit, Simulator, Twin};
use verif::project::{Project, Unit};
use verif::regress::{cosim_seed, merge_shards, regress, RegressConfig, Summary, COSIM_CYCLES};
use verif::{Seed, Shard};

/// The blend's Verilog with one product wrong: a = alpha = 200 (a valid input) gives an
/// output one LSB high, two cycles later.
fn broken_rtl(dir: &Path) -> PathBuf {
    let good =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/blend.v")).unwrap();
    let wrong = "wire signed [17:0] product = (a == 8'd200 && alpha == 8'd200) ? full[17:0] + 18'sd256 : full[17:0];";
    let bad = good.replace("wire signed [17:0] product = full[17:0];", wrong);
    assert_ne!(bad, good, "the blend's product line moved");
    let path = dir.join("blend_rare_bug.v");
    std::fs::write(&path, bad).unwrap();
    path
}

fn twin(rtl: PathBuf) -> impl CosimUnit {
    let drive = |d: &mut Blend, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.a, &mut d.b, &mut d.alpha], v);
    };
    Twin::with_drive(Blend::default, drive).sources([rtl])
}

fn broken_project(rtl: PathBuf) -> Project {
    let unit = Unit::new("blend", "a two-stage alpha blend, a rare bug planted").twin(twin(rtl));
    Project::new("blend", env!("CARGO_PKG_VERSION")).unit(unit)
}

/// Whether a stimulus reaches the bug where the comparison sees it: a valid input with
/// a = alpha = 200 after reset, at least two cycles before the end.
fn reaches_the_bug(unit: &dyn CosimUnit, seed: Seed) -> bool {
    let n = COSIM_CYCLES[0];
    let stim = unit.stimulus(seed, n);
    let resets = verif::cosim::reset_cycles(unit);
    (resets..n - 2).any(|c| stim[c][0] == 1 && stim[c][1] == 200 && stim[c][3] == 200)
}

fn config(out: PathBuf, seed: Seed, seeds: u32) -> RegressConfig {
    let mut cfg = RegressConfig::new(out);
    cfg.seed = seed;
    cfg.seeds = seeds;
    cfg.vcd = false;
    cfg.only = vec!["cosim".into()];
    cfg.simulators = vec![Simulator::Verilator];
    cfg.jobs = 2;
    cfg
}

fn run(p: &Project, cfg: &RegressConfig) -> Summary {
    std::fs::create_dir_all(&cfg.out).unwrap();
    regress(p, cfg, &mut |_, _| {}).unwrap()
}

/// The rows as JSON, without their waveforms' paths (each run writes into its own folder).
fn rows(s: &Summary) -> String {
    let mut rows = s.testbenches.clone();
    rows.iter_mut().for_each(|r| r.vcd = None);
    serde_json::to_string(&rows).unwrap()
}

const SEEDS: u32 = 6;

#[test]
fn each_seed_co_simulates_its_own_stimulus_and_a_farm_merges_to_the_one_machine() {
    if Simulator::Verilator.check_installed().is_err() {
        eprintln!("note: Verilator is not installed; the co-simulation jobs were not run");
        return;
    }
    let out = std::env::temp_dir().join(format!("guide-cosim-jobs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let p = broken_project(broken_rtl(&out));
    let unit = p.twins().next().unwrap();
    // A run seed whose seeds split: some reach the bug, some do not.
    let hits = |seed: Seed| -> Vec<u32> {
        (0..SEEDS)
            .filter(|&r| reaches_the_bug(unit, cosim_seed(seed, r)))
            .collect()
    };
    let seed = (1..200u64)
        .map(Seed)
        .find(|&s| !hits(s).is_empty() && hits(s).len() < SEEDS as usize && !hits(s).contains(&0))
        .expect("a run seed whose later seeds alone reach the bug");
    let expected = hits(seed);

    let mut cfg = config(out.join("whole"), seed, SEEDS);
    cfg.junit = Some(out.join("whole.xml"));
    let whole = run(&p, &cfg);
    let row = &whole.testbenches[0];
    assert_eq!(row.name, "cosim/blend/verilator");
    assert_eq!(row.cycles, u64::from(SEEDS) * COSIM_CYCLES[0] as u64);
    assert!(!row.passed, "seeds {expected:?} reach the bug");
    for r in 1..SEEDS {
        let tag = format!("[seed #{r}] ");
        let said = row.mismatch_log.iter().any(|l| l.starts_with(&tag));
        assert_eq!(
            said,
            expected.contains(&r),
            "seed #{r}: {:#?}",
            row.mismatch_log
        );
    }
    // The first failing seed's command reproduces it: its seed is that seed's stimulus.
    let first = expected[0];
    let again = format!(
        "blend cosim --unit blend --sim verilator --count {} --seed {}",
        COSIM_CYCLES[0],
        cosim_seed(seed, first)
    );
    assert!(
        row.mismatch_log.iter().any(|l| l.ends_with(&again)),
        "{:#?}",
        row.mismatch_log
    );
    // The failing seeds are the run's failing jobs, each with its command.
    let failing: Vec<u32> = whole.failing.iter().map(|f| f.repeat).collect();
    assert_eq!(failing, expected);
    assert_eq!(whole.failing[0].reproduce, again);
    let folder = |r: u32| out.join(format!("whole/cosim/blend-verilator-seed{r}"));
    assert!(
        folder(first).join("blend_cosim.vcd").is_file(),
        "a failing seed keeps its waveform"
    );
    let passing = (1..SEEDS).find(|r| !expected.contains(r)).unwrap();
    assert!(
        !folder(passing).exists(),
        "a later seed that agrees leaves no folder"
    );

    // JUnit: the row a suite, a case per seed's job, failed exactly where the seed reaches
    // the bug, with its own command.
    let xml = std::fs::read_to_string(out.join("whole.xml")).unwrap();
    junit_cases_per_seed(&xml, seed, &expected);
    farm_merges_to_the_whole(&p, &out, seed, &whole, &xml);
    std::fs::remove_dir_all(&out).unwrap();
}

/// The run of `whole` dealt to three shards, as a farm runs it: the same rows, failing jobs
/// and JUnit file (but for the times); a shard left out is named.
fn farm_merges_to_the_whole(p: &Project, out: &Path, seed: Seed, whole: &Summary, xml: &str) {
    let mut shards = Vec::new();
    for i in 1..=3 {
        let mut c = config(out.join(format!("shard{i}")), seed, SEEDS);
        c.shard = Shard::parse(&format!("{i}/3")).unwrap();
        let s = run(p, &c);
        assert_eq!(
            s.cosim_jobs.len(),
            2,
            "shard {i}: six jobs dealt over three shards"
        );
        shards.push((c.out.join("summary.json"), s));
    }
    let merged = merge_shards(p, &shards).unwrap();
    assert_eq!(rows(&merged), rows(whole));
    assert_eq!(merged.passed, whole.passed);
    let json = |s: &Summary| serde_json::to_string(&s.failing).unwrap();
    assert_eq!(json(&merged), json(whole));
    let cosim_jobs: Vec<_> = shards
        .iter()
        .flat_map(|(_, s)| s.cosim_jobs.clone())
        .collect();
    let from_merge = verif::junit::junit(p, &merged, &[], &cosim_jobs).unwrap();
    assert_eq!(
        verif::junit::timeless(&from_merge),
        verif::junit::timeless(xml)
    );
    shards.remove(1);
    let e = merge_shards(p, &shards).err().unwrap();
    assert!(e.contains("shard 2/3 is missing"), "{e}");
}

/// The co-simulation row's JUnit suite in `xml`: one case per seed, each naming its job,
/// seed and command, failed exactly for the seeds in `failing`, then the row's verdict.
fn junit_cases_per_seed(xml: &str, seed: Seed, failing: &[u32]) {
    let suite = r#"<testsuite name="cosim/blend/verilator" tests="7" "#;
    assert!(xml.contains(suite), "{xml}");
    for r in 0..SEEDS {
        let name = match r {
            0 => format!("{} cycles", COSIM_CYCLES[0]),
            _ => format!("{} cycles, seed #{r}", COSIM_CYCLES[0]),
        };
        let start = xml
            .find(&format!(r#"<testcase name="{name}""#))
            .expect(&name);
        let case = &xml[start..start + xml[start..].find("</testcase>").unwrap()];
        let command = format!(
            "blend cosim --unit blend --sim verilator --count {} --seed {}",
            COSIM_CYCLES[0],
            cosim_seed(seed, r)
        );
        assert!(case.contains(&format!("job {}\n", r)), "{case}");
        assert!(case.contains(&format!("reproduce: {command}")), "{case}");
        assert_eq!(case.contains("<failure"), failing.contains(&r), "{case}");
    }
}

/// `--rtl-coverage` under several seeds: one note a row, the seeds' coverage merged (at least
/// each seed's own), each later seed's data kept and nothing else of it; a farm's merge says
/// the same, its shards' runs built where the whole run's folder was, since removed.
#[test]
fn the_rtl_coverage_of_every_seed_is_merged_into_the_row() {
    if Simulator::Verilator.check_installed().is_err() {
        return;
    }
    // A relative folder, as a user gives `--out` (the test runs in the crate's folder).
    let out = PathBuf::from("target").join(format!("guide-cosim-coverage-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let p = guide::project::project();
    let covered = |out: PathBuf| {
        let mut c = config(out, Seed(0x7e47), 3);
        c.rtl_coverage = true;
        c
    };
    let whole = run(&p, &covered(out.join("whole")));
    let notes = &whole.testbenches[0].notes;
    assert_eq!(notes.len(), 1, "{notes:#?}");
    assert!(notes[0].starts_with("3 seeds together: the RTL's coverage (Verilator): blocks "));
    let all = verif::cosim::RtlCoverage::read(
        &out.join("whole/cosim/blend-verilator-all-seeds/coverage.dat"),
        &out.join("read"),
    )
    .unwrap();
    assert_eq!(notes[0], format!("3 seeds together: {}", all.figures()));
    // By source file: the blend's one file, one instance, so the same figures.
    let files = &whole.rtl_coverage;
    assert_eq!(files.len(), 1, "{files:#?}");
    assert!(files[0].file.ends_with("rtl/blend.v"), "{}", files[0].file);
    assert_eq!(
        (files[0].blocks, files[0].toggles),
        (all.blocks, all.toggles)
    );
    let report = verif::report::markdown(&p, &whole, &[]);
    assert!(
        report.contains("## The RTL's coverage by source file"),
        "{report}"
    );
    // Printed under the table, and a property of the JUnit checks suite.
    let f = &files[0];
    let complete = f.blocks.0 == f.blocks.1 && f.toggles.0 == f.toggles.1;
    let printed = verif::report::rtl_coverage_lines(&whole, 10);
    let head = format!(
        "the RTL's coverage by source file: {} of 1 files complete",
        usize::from(complete)
    );
    assert!(printed.starts_with(&head), "{printed}");
    assert_eq!(
        printed.contains("  blend.v: blocks "),
        !complete,
        "{printed}"
    );
    let xml = verif::junit::junit(&p, &whole, &[], &[]).unwrap();
    let property = format!(
        "<property name=\"rtl_coverage {}\" value=\"blocks {} of {}, toggles {} of {}, ",
        f.file, f.blocks.0, f.blocks.1, f.toggles.0, f.toggles.1
    );
    assert!(xml.contains(&property), "{xml}");
    for r in 0..3 {
        let folder = match r {
            0 => out.join("whole/cosim/blend-verilator"),
            _ => out.join(format!("whole/cosim/blend-verilator-seed{r}")),
        };
        let dat = folder.join("coverage.dat");
        let one = verif::cosim::RtlCoverage::read(&dat, &out.join("read")).unwrap();
        assert!(all.blocks.0 >= one.blocks.0 && all.toggles.0 >= one.toggles.0);
        assert_eq!((all.blocks.1, all.toggles.1), (one.blocks.1, one.toggles.1));
        if r > 0 {
            let kept: Vec<_> = std::fs::read_dir(&folder).unwrap().flatten().collect();
            assert_eq!(kept.len(), 1, "seed #{r} keeps its coverage data only");
        }
    }
    // The shards' runs take the covered build from the cache, made in a folder now gone.
    std::fs::remove_dir_all(out.join("whole")).unwrap();
    let mut shards = Vec::new();
    for i in 1..=2 {
        let mut c = covered(out.join(format!("shard{i}")));
        c.shard = Shard::parse(&format!("{i}/2")).unwrap();
        let s = run(&p, &c);
        shards.push((c.out.join("summary.json"), s));
    }
    let merged = merge_shards(&p, &shards).unwrap();
    assert_eq!(merged.testbenches[0].notes, *notes);
    assert_eq!(merged.rtl_coverage, whole.rtl_coverage);
    std::fs::remove_dir_all(&out).unwrap();
    let _ = std::fs::remove_dir("target");
}

/// A twin whose Verilog does not build fails its row with the simulator's message, as a job
/// of the run with the command that runs it again; the regression goes on (exit 1, not 2), so
/// one broken file does not take a night's results with it.
#[test]
fn rtl_that_does_not_build_fails_its_row_and_the_run_goes_on() {
    if Simulator::Verilator.check_installed().is_err() {
        return;
    }
    let out = std::env::temp_dir().join(format!("guide-cosim-unbuilt-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let good =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/blend.v")).unwrap();
    let rtl = out.join("blend_typo.v");
    std::fs::write(&rtl, good.replace("endmodule", "endmodul")).unwrap();
    let p = broken_project(rtl.clone());
    let s = run(&p, &config(out.join("run"), Seed(5), 2));
    let row = &s.testbenches[0];
    assert!(!row.passed);
    assert_eq!(
        row.failures.len(),
        2,
        "each seed's job: {:#?}",
        row.failures
    );
    let said = format!("{}:", rtl.display());
    assert!(
        row.failures.iter().all(|f| f.contains(&said)),
        "{:#?}",
        row.failures
    );
    let seeds: Vec<u32> = s.failing.iter().map(|f| f.repeat).collect();
    assert_eq!(seeds, [0, 1]);
    let f = &s.failing[0];
    assert_eq!(
        f.configuration,
        format!("{} cycles of random stimulus", COSIM_CYCLES[0])
    );
    assert_eq!(
        f.reproduce,
        format!(
            "blend cosim --unit blend --sim verilator --count {} --seed {}",
            COSIM_CYCLES[0],
            Seed(5)
        )
    );
    std::fs::remove_dir_all(&out).unwrap();
}
