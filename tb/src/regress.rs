//! `texrtl regress`: every testbench on built-in stimulus, with waveforms and a summary.

use crate::blend_adjust::{self, BaConfig};
use crate::report::{table, write_atomic, Summary, TbResult};
use std::path::PathBuf;
use verif::Seed;
use waves::check::{check_gtkw, read_vcd};
use waves::TraceConfig;

/// What `texrtl regress` runs with.
#[derive(Clone, Debug)]
pub struct RegressConfig {
    pub out: PathBuf,
    pub seed: Seed,
    /// Write a VCD and `.gtkw` per testbench.
    pub vcd: bool,
    pub trace: TraceConfig,
}

/// Runs every testbench, checks every waveform it wrote (read back with wellen, `.gtkw`
/// checked against it), writes `summary.json`. `Err` is for I/O failures only; mismatches are
/// in the results.
pub fn regress(cfg: &RegressConfig) -> Result<Vec<TbResult>, String> {
    std::fs::create_dir_all(&cfg.out).map_err(|e| format!("{}: {e}", cfg.out.display()))?;
    let mut results = Vec::new();

    let ba = BaConfig {
        seed: cfg.seed.derive(153),
        vcd: cfg.vcd.then(|| cfg.out.join("blend_adjust.vcd")),
        trace: cfg.trace.clone(),
        ..BaConfig::default()
    };
    results.push(blend_adjust::run_tb(&ba)?);
    results.push(crate::normals::regress_suite(
        cfg.seed.derive(7),
        cfg.vcd.then(|| cfg.out.join("normals.vcd")),
        cfg.trace.clone(),
    )?);

    results.push(crate::mipmap::regress_suite(
        cfg.seed.derive(816),
        cfg.vcd.then(|| cfg.out.join("mipmap.vcd")),
        cfg.trace.clone(),
    )?);

    // Bit-accuracy vectors of this source tree, when it is there (not for an installed binary).
    let dir = crate::vectors::vectors_dir();
    if dir.is_dir() {
        let mut r = TbResult::new(
            "vectors",
            "bit-accuracy regression vectors (golden/vectors/)",
        );
        r.coverage_percent = 100.0;
        match crate::vectors::check(&dir) {
            Ok(d) => {
                r.transactions = crate::vectors::UNITS.len() as u64;
                r.mismatches = d.len() as u64;
                r.mismatch_log = d;
            }
            Err(e) => r.failures.push(e),
        }
        r.finish_with(false);
        results.push(r);
    }

    for r in &mut results {
        if let Some(vcd) = &r.vcd {
            match read_vcd(vcd).and_then(|rb| check_gtkw(vcd, &rb)) {
                Ok(_) => {}
                Err(e) => {
                    r.failures.push(format!("waveform: {e}"));
                    r.passed = false;
                }
            }
        }
    }
    let passed = results.iter().all(|r| r.passed);
    let summary = Summary {
        texrtl: env!("CARGO_PKG_VERSION"),
        seed: cfg.seed.to_string(),
        passed,
        testbenches: &results,
    };
    let json = serde_json::to_vec_pretty(&summary).map_err(|e| e.to_string())?;
    let path = cfg.out.join("summary.json");
    write_atomic(&path, &json).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(results)
}

/// The table and a closing line, as `texrtl regress` prints them.
pub fn render(results: &[TbResult], cfg: &RegressConfig) -> String {
    let mut s = table(results);
    let failed = results.iter().filter(|r| !r.passed).count();
    s.push_str(&format!(
        "{} testbenches: {} passed, {} failed (seed {}; outputs in {})\n",
        results.len(),
        results.len() - failed,
        failed,
        cfg.seed,
        cfg.out.display()
    ));
    s
}
