//! Regressions on a scheduler: `contrib/slurm/farm` on a single-node Slurm started here
//! (`contrib/slurm/local-cluster`, Debian's slurm-wlm and munge). The merged summary of a job
//! array equals one machine's run byte for byte; a task cancelled mid-run is named by the
//! merge and its resubmission completes it; in a 2,000-job farm of a user crate with a rare
//! injected bug, the one command the merged report prints for a failing job reproduces it
//! with its waveform.
//!
//! Without slurmctld, slurmd and munged these tests pass with a note, unless
//! `TEXRTL_REQUIRE_SLURM=1` (as `.ci/run` sets), which makes a missing scheduler a failure.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn script(name: &str) -> PathBuf {
    root().join("contrib/slurm").join(name)
}

fn text(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

/// A single-node cluster in a folder, stopped when dropped.
struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
}

impl Cluster {
    /// `None` (with a note) when Slurm is not installed and not required.
    fn start(dir: &Path) -> Option<Cluster> {
        let installed = ["slurmctld", "slurmd", "munged", "sbatch"].iter().all(|t| {
            ["/usr/sbin", "/usr/bin", "/sbin", "/bin"]
                .iter()
                .any(|d| Path::new(d).join(t).is_file())
        });
        if !installed {
            assert!(
                std::env::var("TEXRTL_REQUIRE_SLURM").as_deref() != Ok("1"),
                "TEXRTL_REQUIRE_SLURM=1 but Slurm is not installed (apt-get install slurm-wlm munge)"
            );
            eprintln!("note: Slurm is not installed; the farm test did not run");
            return None;
        }
        let o = Command::new(script("local-cluster"))
            .arg("start")
            .arg(dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "local-cluster start: {}", text(&o));
        let conf = PathBuf::from(String::from_utf8_lossy(&o.stdout).trim());
        Some(Cluster {
            dir: dir.to_path_buf(),
            conf,
        })
    }

    fn cmd(&self, program: impl AsRef<std::ffi::OsStr>) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", &self.conf);
        c
    }

    /// Waits until job `id` has left the queue.
    fn wait_gone(&self, id: &str, limit: Duration) {
        let t = Instant::now();
        loop {
            let o = self.cmd("squeue").args(["-h", "-j", id]).output().unwrap();
            if String::from_utf8_lossy(&o.stdout).trim().is_empty() {
                return;
            }
            assert!(t.elapsed() < limit, "job {id} still queued after {limit:?}");
            std::thread::sleep(Duration::from_millis(200));
        }
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = Command::new(script("local-cluster"))
            .arg("stop")
            .arg(&self.dir)
            .output();
    }
}

fn fresh(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("texrtl-farm-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The ids `farm` prints: `array ID: ...`, `merge ID: ...`.
fn ids(out: &str) -> (String, String) {
    let id = |what: &str| {
        out.lines()
            .find_map(|l| l.strip_prefix(what))
            .and_then(|l| l.split(':').next())
            .unwrap_or_else(|| panic!("no '{what}' line in {out}"))
            .trim()
            .to_string()
    };
    (id("array "), id("merge "))
}

/// The first task of `array` seen running (polled every 20 ms for a minute).
/// A task of `array` to cancel: the last one still pending when there is one (queued behind
/// the others, it cannot finish before the cancel lands; a running task near its end could,
/// and then nothing would be missing), else one that runs.
fn a_task_to_cancel(c: &Cluster, array: &str) -> String {
    let t = Instant::now();
    let tasks = |state: &str| {
        let o = c
            .cmd("squeue")
            .args(["-h", "-r", "-t", state, "-j", array, "-o", "%i"])
            .output()
            .unwrap();
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        out.lines()
            .map(|l| l.trim().to_string())
            .collect::<Vec<_>>()
    };
    while t.elapsed() < Duration::from_secs(60) {
        if let Some(task) = tasks("PD").into_iter().rfind(|t| !t.contains('[')) {
            return task;
        }
        if let Some(task) = tasks("R").into_iter().next() {
            return task;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    panic!("no task of {array} was queued or ran within a minute");
}

const OPTIONS: [&str; 5] = ["--seeds", "2", "--count", "20", "--no-cosim"];

#[test]
#[ignore = "slow (a Slurm cluster started and stopped): cargo test -- --ignored, as .ci/run does"]
fn a_slurm_array_merges_to_the_single_machine_run_and_names_a_cancelled_task() {
    let d = fresh("texrtl");
    let Some(c) = Cluster::start(&d.join("cluster")) else {
        return;
    };
    let texrtl = env!("CARGO_BIN_EXE_texrtl");
    let whole = d.join("whole");
    let o = Command::new(texrtl)
        .args(["regress", "--no-vcd", "-j", "1"])
        .args(OPTIONS)
        .arg("--out")
        .arg(&whole)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let farm_dir = d.join("farm");
    let farm = |before: &[&str]| {
        c.cmd(script("farm"))
            .args(before)
            .arg(texrtl)
            .arg(&farm_dir)
            .arg("6")
            .args(OPTIONS)
            .output()
            .unwrap()
    };
    let o = farm(&[]);
    assert!(o.status.success(), "farm: {}", text(&o));
    let (array, merge) = ids(&text(&o));
    // One task cancelled before it ends: the merge names its shard.
    let task = a_task_to_cancel(&c, &array);
    let k = task.rsplit('_').next().unwrap().to_string();
    let o = c.cmd("scancel").arg(&task).output().unwrap();
    assert!(o.status.success(), "scancel {task}: {}", text(&o));
    c.wait_gone(&merge, Duration::from_secs(600));
    let log = std::fs::read_to_string(farm_dir.join("logs/merge.out")).unwrap();
    assert!(
        log.contains(&format!("shard {k}/6 is missing")),
        "the merge after cancelling task {task}: {log}"
    );
    assert!(!farm_dir.join("merged/summary.json").exists());
    // Resubmitted alone, the task completes the merge: the single machine's summary.
    let o = farm(&["--wait", "--resubmit", &k]);
    assert!(o.status.success(), "farm --resubmit {k}: {}", text(&o));
    let merged = std::fs::read(farm_dir.join("merged/summary.json")).unwrap();
    assert!(
        merged == std::fs::read(whole.join("summary.json")).unwrap(),
        "the farm's merged summary differs from the single machine's"
    );
    assert!(farm_dir.join("merged/report.md").is_file());
    drop(c);
    let _ = std::fs::remove_dir_all(&d);
}

/// `texrtl new` with a rare bug in the model: one sum in one state comes out one LSB high.
fn crate_with_a_rare_bug(d: &Path) -> PathBuf {
    let dir = d.join("farm_acc");
    let o = Command::new(env!("CARGO_BIN_EXE_texrtl"))
        .args(["new", "farm_acc", "--dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    std::fs::copy(root().join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
    let unit = dir.join("src/unit.rs");
    let src = std::fs::read_to_string(&unit).unwrap();
    let line = "            self.acc_r.set_next(self.to_acc.fx(sum));";
    assert!(src.contains(line), "the template's accumulator line moved");
    let bug = "            let q = self.to_acc.fx(sum);\n            \
               if self.x.raw() == 37 && (100..102).contains(&self.acc_r.q().raw()) {\n                \
               self.acc_r.set_next_raw(q.raw() as i64 + 1);\n            } else {\n                \
               self.acc_r.set_next(q);\n            }";
    std::fs::write(&unit, src.replace(line, bug)).unwrap();
    let target = root().join("target/template");
    let o = Command::new(env!("CARGO"))
        .args(["build", "--quiet"])
        .current_dir(&dir)
        .env("CARGO_TARGET_DIR", &target)
        .env_remove("RUSTFLAGS")
        .output()
        .unwrap();
    assert!(o.status.success(), "cargo build: {}", text(&o));
    target.join("debug/farm_acc")
}

#[test]
#[ignore = "slow (a user crate built, 2,000 jobs on Slurm): cargo test -- --ignored, as .ci/run does"]
fn a_failing_seed_of_a_2000_job_farm_is_reproduced_by_its_line_in_the_report() {
    let d = fresh("jobs");
    let Some(c) = Cluster::start(&d.join("cluster")) else {
        return;
    };
    let program = crate_with_a_rare_bug(&d);
    // 1,000 seeds x 2 configurations = 2,000 jobs, over TEXRTL_FARM_TASKS array tasks.
    let tasks = std::env::var("TEXRTL_FARM_TASKS").unwrap_or_else(|_| "40".into());
    let options = ["--seeds", "1000", "--count", "50", "--no-cosim"];
    let t = Instant::now();
    let o = Command::new(&program)
        .args(["regress", "--no-vcd", "-j", "1"])
        .args(options)
        .arg("--out")
        .arg(d.join("one"))
        .current_dir(&d)
        .output()
        .unwrap();
    let one_process = t.elapsed();
    assert_eq!(
        o.status.code(),
        Some(1),
        "the bug fails some jobs: {}",
        text(&o)
    );
    let farm_dir = d.join("farm");
    let t = Instant::now();
    let o = c
        .cmd(script("farm"))
        .arg("--wait")
        .arg(&program)
        .arg(&farm_dir)
        .arg(&tasks)
        .args(options)
        .output()
        .unwrap();
    let farm = t.elapsed();
    eprintln!(
        "2000 jobs: one process {:.1} s, a {tasks}-task Slurm array and its merge {:.1} s",
        one_process.as_secs_f64(),
        farm.as_secs_f64()
    );
    // The merge exits 1: the run failed. Every job is accounted for: the single run's bytes.
    assert_eq!(o.status.code(), Some(1), "farm: {}", text(&o));
    let merged = farm_dir.join("merged/summary.json");
    assert!(std::fs::read(&merged).unwrap() == std::fs::read(d.join("one/summary.json")).unwrap());
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(&merged).unwrap()).unwrap();
    let failing = s["failing"].as_array().unwrap();
    assert!(
        !failing.is_empty() && failing.len() < 200,
        "{} failing jobs",
        failing.len()
    );
    let report = std::fs::read_to_string(farm_dir.join("merged/report.md")).unwrap();
    let line = failing[0]["reproduce"].as_str().unwrap();
    assert!(report.contains("## Failing jobs") && report.contains(line));
    // The JUnit file: a case per job (and a verdict per testbench), the failing ones failed.
    let junit = std::fs::read_to_string(farm_dir.join("merged/junit.xml")).unwrap();
    let rows = s["testbenches"].as_array().unwrap();
    let failed_rows = rows.iter().filter(|r| r["passed"] != true).count();
    let head = format!(
        r#"<testsuites name="farm_acc" tests="{}" failures="{}""#,
        2000 + rows.len(),
        failing.len() + failed_rows
    );
    assert!(junit.contains(&head), "{head}: {}", &junit[..300]);
    reproduce(&program, &d, line, failing[0]["first"].as_str().unwrap());
    co_simulations_in_a_farm(&c, &program, &d);
    drop(c);
    let _ = std::fs::remove_dir_all(&d);
}

/// The twin co-simulated under three seeds in each simulator installed, as one process and
/// as a three-task array: the same rows (but for the folders of their waveforms).
fn co_simulations_in_a_farm(c: &Cluster, program: &Path, d: &Path) {
    let sims: Vec<&str> = [("verilator", "verilator"), ("icarus", "iverilog")]
        .into_iter()
        .filter(|(_, exe)| Command::new(exe).arg("-V").output().is_ok())
        .map(|(s, _)| s)
        .collect();
    if sims.is_empty() {
        return;
    }
    let mut options = vec!["--only", "cosim", "--seeds", "3"];
    options.extend(sims.iter().flat_map(|s| ["--sim", s]));
    let o = Command::new(program)
        .args(["regress", "--no-vcd", "-j", "1"])
        .args(&options)
        .arg("--out")
        .arg(d.join("cosim-one"))
        .current_dir(d)
        .output()
        .unwrap();
    let one = o.status.code();
    let farm_dir = d.join("cosim-farm");
    let o = c
        .cmd(script("farm"))
        .arg("--wait")
        .arg(program)
        .arg(&farm_dir)
        .arg("3")
        .args(&options)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), one, "farm: {}", text(&o));
    let rows = |p: PathBuf| {
        let s: serde_json::Value = serde_json::from_slice(&std::fs::read(p).unwrap()).unwrap();
        let mut rows = s["testbenches"].as_array().unwrap().clone();
        for r in &mut rows {
            let r = r.as_object_mut().unwrap();
            r.remove("vcd");
            r.remove("seconds");
        }
        rows
    };
    let merged = rows(farm_dir.join("merged/summary.json"));
    assert_eq!(merged.len(), sims.len(), "a row per simulator");
    assert_eq!(merged, rows(d.join("cosim-one/summary.json")));
}

/// Runs the report's command (its first word is the program) and checks that it fails the
/// same way, with a waveform whose mismatch flag rises inside the trace window.
fn reproduce(program: &Path, dir: &Path, line: &str, first: &str) {
    let mut words = line.split_whitespace();
    assert_eq!(words.next(), Some("farm_acc"));
    let args: Vec<&str> = words.collect();
    let o = Command::new(program)
        .args(&args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{line}: {}", text(&o));
    assert!(
        text(&o).contains(first),
        "{line} did not fail with {first}: {}",
        text(&o)
    );
    let out = args
        .iter()
        .skip_while(|a| **a != "--out")
        .nth(1)
        .expect("the command names its folder");
    let vcd = dir.join(out).join("farm_acc.vcd");
    let back = waves::check::read_vcd(&vcd).unwrap();
    let flag = back
        .vars
        .iter()
        .find(|(name, _)| name.ends_with("mismatch"))
        .map(|(_, v)| v)
        .expect("the mismatch flag is traced");
    assert!(
        flag.changes.iter().any(|(_, v)| v.as_u64() == Some(1)),
        "the waveform of {line} shows no mismatch"
    );
    // Its view opens on the first mismatch: marker A there, the flag up under it.
    let g = std::fs::read_to_string(vcd.with_extension("gtkw")).unwrap();
    let view = waves::gtkw::View::parse(&g).unwrap();
    let (t, name) = view.marker.clone().expect("a marker on the mismatch");
    assert_eq!(name, "first mismatch");
    assert!(view.window.0 <= t && t <= view.window.1, "{view:?}");
    let at = |t: u64| {
        flag.changes
            .iter()
            .take_while(|(c, _)| *c <= t)
            .last()
            .and_then(|(_, v)| v.as_u64())
    };
    assert_eq!(
        at(t),
        Some(1),
        "the mismatch flag at the marker ({t} ps): {view:?}"
    );
}
