//! Results of testbenches, the summary table and `summary.json`.

use serde::{Deserialize, Serialize};
use std::fmt::Write;
use std::path::{Path, PathBuf};
pub use verif::TbResult;

/// The summary table printed by `texrtl regress`.
pub fn table(results: &[TbResult]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<14} {:>9} {:>9} {:>6} {:>7} {:>9} {:>10} {:>7}  result",
        "testbench", "txns", "cycles", "mism", "cover", "max LSB", "mean LSB", "latency"
    );
    for r in results {
        let _ = writeln!(
            s,
            "{:<14} {:>9} {:>9} {:>6} {:>6.1}% {:>9.3} {:>10.4} {:>7}  {}",
            r.name,
            r.transactions,
            r.cycles,
            r.mismatches,
            r.coverage_percent,
            r.stats.max_abs_lsb,
            r.stats.mean_abs_lsb(),
            r.latency_text(),
            r.verdict()
        );
    }
    for r in results {
        for n in &r.notes {
            let _ = writeln!(s, "  {}: {n}", r.name);
        }
    }
    for r in results.iter().filter(|r| !r.passed) {
        for m in r.mismatch_log.iter().chain(&r.failures) {
            let _ = writeln!(s, "  {}: {m}", r.name);
        }
    }
    s
}

/// `summary.json`: every result, the seed, the shard and the tool version.
#[derive(Serialize, Deserialize)]
pub struct Summary {
    pub texrtl: String,
    pub seed: String,
    /// `I/N` when the run was one shard of N.
    pub shard: Option<String>,
    pub passed: bool,
    pub testbenches: Vec<TbResult>,
}

/// Writes `contents` to `path` through a temporary file, so no partial file is ever left.
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, contents)?;
    std::fs::rename(&tmp, path)
}

/// `report.md`: the summary, each testbench's figures, error histogram and coverage, and
/// links to its waveform and pictures.
pub fn markdown(s: &Summary, pictures: &[(&str, &str)]) -> String {
    let mut m = String::new();
    let _ = writeln!(m, "# texrtl regression report\n");
    let _ = writeln!(
        m,
        "texrtl {}, seed `{}`{}: **{}**.\n",
        s.texrtl,
        s.seed,
        s.shard
            .as_ref()
            .map(|x| format!(", shard {x}"))
            .unwrap_or_default(),
        if s.passed { "all passed" } else { "FAILED" }
    );
    let _ = writeln!(m, "| testbench | unit | transactions | cycles | mismatches | coverage | max error (LSB) | mean error (LSB) | latency | result |");
    let _ = writeln!(m, "|---|---|---:|---:|---:|---:|---:|---:|---:|---|");
    for r in &s.testbenches {
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {} | {:.1} % | {:.3} | {:.4} | {} | {} |",
            r.name,
            r.unit,
            r.transactions,
            r.cycles,
            r.mismatches,
            r.coverage_percent,
            r.stats.max_abs_lsb,
            r.stats.mean_abs_lsb(),
            r.latency_text(),
            r.verdict()
        );
    }
    let _ = writeln!(
        m,
        "\nHow to read it: *mismatches* are transactions whose bits differ from the golden model \
         beyond the testbench's stated tolerance (zero for exact units); *coverage* is the share of \
         functional-coverage bins hit (a hole fails the testbench); errors are in LSBs of each \
         unit's output format against the f64 golden model. Each waveform opens with \
         `gtkwave <name>.gtkw`.\n"
    );
    if !pictures.is_empty() {
        let _ = writeln!(m, "## Pictures\n");
        for (file, caption) in pictures {
            let _ = writeln!(m, "![{caption}]({file})\n\n*{caption}*\n");
        }
    }
    for r in &s.testbenches {
        let _ = writeln!(m, "## {}\n\n{}\n", r.name, r.unit);
        let st = &r.stats;
        if st.count > 0 {
            let _ = writeln!(
                m,
                "Error against golden: {} results, max {:.3} LSB, mean {:.4} LSB, {} exact, {} within ±1 LSB{}.\n",
                st.count,
                st.max_abs_lsb,
                st.mean_abs_lsb(),
                st.exact,
                st.within_1_lsb,
                st.sqnr_db().map(|x| format!(", SQNR {x:.1} dB")).unwrap_or_default()
            );
            let _ = writeln!(m, "| error (LSB, rounded) | count |\n|---:|---:|");
            for (k, v) in &st.histogram {
                let _ = writeln!(m, "| {k} | {v} |");
            }
            m.push('\n');
        }
        for n in &r.notes {
            let _ = writeln!(m, "- {n}");
        }
        for t in &r.tables {
            let _ = writeln!(m, "\n{t}");
        }
        if let Some(v) = &r.vcd {
            let name = v
                .file_name()
                .map(|x| x.to_string_lossy().into_owned())
                .unwrap_or_default();
            let g = v.with_extension("gtkw");
            let gname = g
                .file_name()
                .map(|x| x.to_string_lossy().into_owned())
                .unwrap_or_default();
            let _ = writeln!(m, "\nWaveform: [{name}]({name}), view: [{gname}]({gname})");
        }
        if !r.unhit.is_empty() {
            let _ = writeln!(m, "\nCoverage holes: {}", r.unhit.join(", "));
        }
        for f in r.mismatch_log.iter().chain(&r.failures) {
            let _ = writeln!(m, "- **{f}**");
        }
        m.push('\n');
    }
    m
}
