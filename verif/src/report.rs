//! A regression's report: the table `regress` prints, and `report.md` with each testbench's
//! figures, error histogram, coverage holes, waveform links and the units' pictures.

use crate::cosim::FileCoverage;
use crate::project::{Picture, Project};
use crate::regress::{RegressConfig, Summary};
use crate::TbResult;
use std::fmt::Write;
use std::path::Path;
use waves::output::write_output;

/// The summary table printed by `texrtl regress`.
pub fn table(results: &[TbResult]) -> String {
    let mut s = String::new();
    // The name column fits the longest name (co-simulation rows are long).
    let w = results
        .iter()
        .map(|r| r.name.len())
        .max()
        .unwrap_or(0)
        .max(32);
    let _ = writeln!(
        s,
        "{:<w$} {:>9} {:>9} {:>6} {:>7} {:>9} {:>10} {:>7}  result",
        "testbench", "txns", "cycles", "mism", "cover", "max LSB", "mean LSB", "latency"
    );
    for r in results {
        let _ = writeln!(
            s,
            "{:<w$} {:>9} {:>9} {:>6} {:>6.1}% {:>9.3} {:>10.4} {:>7}  {}",
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

/// `report.md`: the summary, each testbench's figures, error histogram and coverage, and
/// links to its waveform and pictures.
pub fn markdown(project: &Project, s: &Summary, pictures: &[Picture]) -> String {
    let mut m = String::new();
    let _ = writeln!(m, "# {} regression report\n", project.name());
    let _ = writeln!(
        m,
        "{} {}, seed `{}`{}: **{}**.\n",
        project.name(),
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
    failing_section(&mut m, s);
    rtl_coverage_section(&mut m, s);
    if !pictures.is_empty() {
        let _ = writeln!(m, "## Pictures\n");
        for Picture { file, caption } in pictures {
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
        crate::numeric::section(&mut m, &r.name, &r.narrowings);
        for f in r.mismatch_log.iter().chain(&r.failures) {
            let _ = writeln!(m, "- **{f}**");
        }
        m.push('\n');
    }
    m
}

/// The pictures and `report.md` of a regression's summary: each unit's own pictures (when one
/// of its testbenches ran) and an error histogram per testbench that measured errors.
pub fn write_report(project: &Project, out: &Path, summary: &Summary) -> Result<(), String> {
    let write = |f: &str, b: &[u8]| write_output(&out.join(f), b).map_err(|e| e.to_string());
    let results = &summary.testbenches;
    let mut pictures = Vec::new();
    for u in project.units() {
        let ran = project
            .testbenches_of(u.name())
            .iter()
            .any(|t| results.iter().any(|r| r.name == *t));
        if let Some(f) = u.pictures_fn().filter(|_| ran) {
            pictures.extend(f(out, results)?);
        }
    }
    for r in results.iter().filter(|r| r.stats.count > 0) {
        let file = format!("{}_error_histogram.svg", r.name);
        let title = format!("{}: error against golden", r.name);
        let svg = crate::plot::histogram_svg(&title, &r.stats.histogram)?;
        write(&file, svg.as_bytes())?;
        pictures.push(Picture {
            file,
            caption: format!(
                "{}: histogram of the error against the golden model, in output LSBs (log scale)",
                r.name
            ),
        });
    }
    if results.iter().any(|r| !r.narrowings.is_empty()) {
        write("narrowings.csv", crate::numeric::csv(results).as_bytes())?;
    }
    for r in results.iter().filter(|r| !r.narrowings.is_empty()) {
        let svg = crate::numeric::picture(&r.name, &r.narrowings)?;
        write(&crate::numeric::picture_file(&r.name), svg.as_bytes())?;
    }
    write(
        "report.md",
        markdown(project, summary, &pictures).as_bytes(),
    )
}

/// Each failing job with its testbench, configuration, seed and the command that runs it
/// again alone, with its waveform.
fn failing_section(m: &mut String, s: &Summary) {
    if s.failing.is_empty() {
        return;
    }
    let _ = writeln!(m, "## Failing jobs\n");
    let _ = writeln!(
        m,
        "{} jobs failed; each command runs its job again, alone, with its waveform (traced \
         around the first mismatch where its cycle is known).\n",
        s.failing.len()
    );
    let _ = writeln!(
        m,
        "| job | testbench | configuration | seed | first | reproduce |"
    );
    let _ = writeln!(m, "|---:|---|---|---|---|---|");
    for f in &s.failing {
        let first = f.first.replace('|', "\\|");
        let seed = if f.repeat == 0 {
            f.seed.clone()
        } else {
            format!("{} (#{})", f.seed, f.repeat)
        };
        let _ = writeln!(
            m,
            "| {} | {} | {} | `{seed}` | {first} | `{}` |",
            f.job, f.testbench, f.configuration, f.reproduce
        );
    }
    let _ = writeln!(m);
}

/// What the run's co-simulations reached of each RTL source file (`--rtl-coverage`), over
/// every row, instance and seed.
fn rtl_coverage_section(m: &mut String, s: &Summary) {
    if s.rtl_coverage.is_empty() {
        return;
    }
    let _ = writeln!(m, "## The RTL's coverage by source file\n");
    let _ = writeln!(
        m,
        "What every co-simulation of the run reached of each file (Verilator's line and toggle \
         coverage): a block or a signal bit counts once however often the file is instantiated, \
         and is reached when any row, instance or seed reached it.\n"
    );
    let _ = writeln!(m, "| file | blocks | toggles | lines never reached |");
    let _ = writeln!(m, "|---|---:|---:|---|");
    let pc = crate::cosim::RtlCoverage::percent;
    for f in &s.rtl_coverage {
        let lines: Vec<String> = f.unreached.iter().map(u32::to_string).collect();
        let _ = writeln!(
            m,
            "| `{}` | {} of {} ({:.1} %) | {} of {} ({:.1} %) | {} |",
            f.file,
            f.blocks.0,
            f.blocks.1,
            pc(f.blocks),
            f.toggles.0,
            f.toggles.1,
            pc(f.toggles),
            if lines.is_empty() {
                "-".into()
            } else {
                lines.join(", ")
            }
        );
    }
    let _ = writeln!(m);
}

/// The RTL's coverage by source file in a few lines, as `regress` and `merge` print it under
/// their table (`--rtl-coverage`): how many files every run reached in full, then each file
/// short of full, at most `max` of them, fewest blocks reached first. `report.md` has every
/// file with the lines never reached.
pub fn rtl_coverage_lines(s: &Summary, max: usize) -> String {
    let files = &s.rtl_coverage;
    if files.is_empty() {
        return String::new();
    }
    let full = |f: &&FileCoverage| f.blocks.0 == f.blocks.1 && f.toggles.0 == f.toggles.1;
    let mut short: Vec<&FileCoverage> = files.iter().filter(|f| !full(f)).collect();
    short.sort_by(|a, b| {
        let pc = crate::cosim::RtlCoverage::percent;
        pc(a.blocks)
            .total_cmp(&pc(b.blocks))
            .then(a.file.cmp(&b.file))
    });
    let mut out = format!(
        "the RTL's coverage by source file: {} of {} files complete",
        files.len() - short.len(),
        files.len()
    );
    out.push_str(if short.is_empty() { "\n" } else { "; short:\n" });
    for f in short.iter().take(max) {
        let name = std::path::Path::new(&f.file)
            .file_name()
            .map_or(f.file.clone(), |n| n.to_string_lossy().into_owned());
        let _ = writeln!(
            out,
            "  {name}: blocks {} of {}, toggles {} of {}, {} never reached",
            f.blocks.0,
            f.blocks.1,
            f.toggles.0,
            f.toggles.1,
            match f.unreached.len() {
                1 => "1 line".to_string(),
                n => format!("{n} lines"),
            }
        );
    }
    if short.len() > max {
        let _ = writeln!(out, "  ... and {} more", short.len() - max);
    }
    if !short.is_empty() {
        let _ = writeln!(
            out,
            "  (the lines never reached: summary.json's rtl_coverage, report.md)"
        );
    }
    out
}

/// The failing jobs' commands, at most `max` of them, as `regress` and `merge` print them.
pub fn failing_lines(s: &Summary, max: usize) -> String {
    let mut out = String::new();
    for f in s.failing.iter().take(max) {
        let _ = writeln!(
            out,
            "failing job {} ({} [{}]): {}",
            f.job, f.testbench, f.configuration, f.reproduce
        );
    }
    if s.failing.len() > max {
        let _ = writeln!(out, "... and {} more in report.md", s.failing.len() - max);
    }
    out
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
