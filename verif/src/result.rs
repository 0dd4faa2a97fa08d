//! What a testbench found: counts, error statistics, coverage, failures, notes and
//! machine-readable records, in the form `summary.json` keeps and `texrtl merge` adds up.

use crate::coverage::Coverage;
use crate::stats::ErrorStats;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// Coverage-hole failures start with this text (so merged shards can drop their own).
const HOLES: &str = "coverage holes";
/// The failure of a run asked to reach every numeric path (`--require-numeric-coverage`).
const NUMERIC_HOLES: &str = "numeric coverage holes";
/// The failure of a narrowing path taken that its unit declares unreachable.
const TAKEN: &str = "unreachable narrowing path taken";
/// The failure of a whole run's testbench that compared no transaction ([`TbResult::vacuous`]).
const NOTHING: &str = "compared nothing";

/// What one testbench (or one of its configurations) found.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TbResult {
    /// The testbench's name (a row of the table).
    pub name: String,
    /// The hardware unit and where the source document describes it.
    pub unit: String,
    /// Configurations run (of this shard).
    #[serde(default)]
    pub configurations: u64,
    /// Transactions compared.
    pub transactions: u64,
    /// Cycles simulated.
    pub cycles: u64,
    /// Transactions that differed from the golden model beyond the tolerance.
    pub mismatches: u64,
    /// The first mismatches in detail.
    pub mismatch_log: Vec<String>,
    /// The cycle of the first mismatch a scoreboard saw with its cycle (of the first
    /// configuration that had one): where a reproduction's trace window goes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_mismatch_cycle: Option<u64>,
    /// Anything else that failed: latency, throughput, watchdog, coverage holes, waveforms.
    pub failures: Vec<String>,
    /// Share of the coverage bins hit, in percent.
    pub coverage_percent: f64,
    /// The bins never hit.
    pub unhit: Vec<String>,
    #[serde(skip, default)]
    /// The coverage model's report (not kept in `summary.json`).
    pub coverage_report: String,
    /// Error against the golden model, in output LSBs.
    pub stats: ErrorStats,
    /// Cycles from a transaction's input to its output, where the unit has one.
    pub latency: Option<u64>,
    /// Measured figures worth a line in the report.
    pub notes: Vec<String>,
    /// Markdown tables for `report.md` only (not the console).
    #[serde(default)]
    pub tables: Vec<String>,
    /// Per-configuration measurements in the testbench's own row type (as JSON), concatenated
    /// when shards merge; the testbench's [`conclude`](crate::Testbench::conclude) turns them
    /// into notes, tables and plots.
    #[serde(default)]
    pub records: Vec<serde_json::Value>,
    /// What each named narrowing of the unit met (numeric coverage), merged over the runs.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub narrowings: Vec<crate::numeric::NarrowRow>,
    /// Numeric coverage: the percentage of the narrowings' overflow and tie paths taken
    /// (`None` without narrowings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub numeric_percent: Option<f64>,
    /// The narrowings' paths never taken (numeric coverage holes), merged over the shards.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub numeric_holes: Vec<String>,
    /// The seed that replays the run.
    pub seed: Option<String>,
    /// The waveform written, if any.
    pub vcd: Option<PathBuf>,
    /// The coverage model with its hits, so shards can be merged.
    pub coverage: Option<Coverage>,
    /// How many notes and tables the configurations wrote before the testbench's conclusions
    /// were added (so merged shards can conclude again from the records).
    #[serde(default)]
    pub own: Option<(usize, usize)>,
    /// The verdict: no mismatch, no failure and (for a whole run) no coverage hole.
    pub passed: bool,
}

impl TbResult {
    /// An empty result of testbench `name` for `unit`.
    pub fn new(name: &str, unit: &str) -> TbResult {
        TbResult {
            name: name.into(),
            unit: unit.into(),
            configurations: 0,
            transactions: 0,
            cycles: 0,
            mismatches: 0,
            mismatch_log: Vec::new(),
            first_mismatch_cycle: None,
            failures: Vec::new(),
            coverage_percent: 0.0,
            unhit: Vec::new(),
            coverage_report: String::new(),
            stats: ErrorStats::new(),
            latency: None,
            notes: Vec::new(),
            tables: Vec::new(),
            records: Vec::new(),
            narrowings: Vec::new(),
            numeric_percent: None,
            numeric_holes: Vec::new(),
            seed: None,
            vcd: None,
            coverage: None,
            own: None,
            passed: false,
        }
    }

    /// Decides pass/fail: no mismatch, no other failure, every coverage bin hit.
    pub fn finish(&mut self) {
        self.finish_with(true)
    }

    /// Decides pass/fail; coverage holes fail it only when `require_coverage` (a shard cannot
    /// know whether another shard hits its holes: `texrtl merge` decides for the whole run).
    pub fn finish_with(&mut self, require_coverage: bool) {
        self.failures.retain(|f| {
            ![HOLES, NUMERIC_HOLES, TAKEN, NOTHING]
                .iter()
                .any(|p| f.starts_with(p))
        });
        self.finish_numeric();
        if require_coverage && !self.unhit.is_empty() {
            let first: Vec<&str> = self.unhit.iter().take(8).map(String::as_str).collect();
            self.failures.push(format!(
                "{HOLES} ({} bins): {}",
                self.unhit.len(),
                first.join(", ")
            ));
        }
        self.passed = self.mismatches == 0 && self.failures.is_empty();
    }

    /// Fails a whole run's testbench that compared no transaction in any job: a pass that
    /// checked nothing (a driver that never sends, a monitor that never samples, a scoreboard
    /// never scored) is not a pass. A result that fails already (a job that panicked before
    /// it scored) is left to say why.
    pub fn vacuous(&mut self) {
        if self.passed && self.transactions == 0 {
            self.failures.push(format!(
                "{NOTHING}: no transaction was scored in any configuration"
            ));
            self.passed = false;
        }
    }

    /// Numeric coverage from the narrowings: the percentage and the holes; a path taken that
    /// the unit declares unreachable is a failure.
    fn finish_numeric(&mut self) {
        use crate::numeric::{coverage, NarrowRow};
        let rows = &self.narrowings;
        self.numeric_percent = (!rows.is_empty()).then(|| coverage(rows).percent());
        self.numeric_holes = rows.iter().flat_map(NarrowRow::holes).collect();
        let taken: Vec<String> = rows.iter().flat_map(NarrowRow::contradictions).collect();
        self.failures
            .extend(taken.into_iter().map(|t| format!("{TAKEN}: {t}")));
    }

    /// Fails the result if a narrowing path was never taken (`--require-numeric-coverage`:
    /// for a whole run, or a merged one, as a shard cannot know what the others reached).
    pub fn require_numeric_coverage(&mut self) {
        self.failures.retain(|f| !f.starts_with(NUMERIC_HOLES));
        if !self.numeric_holes.is_empty() {
            let first: Vec<&str> = self
                .numeric_holes
                .iter()
                .take(8)
                .map(String::as_str)
                .collect();
            self.failures.push(format!(
                "{NUMERIC_HOLES} ({} paths): {}",
                self.numeric_holes.len(),
                first.join("; ")
            ));
        }
        self.passed = self.mismatches == 0 && self.failures.is_empty();
    }

    /// Whether this result failed on its own account: a mismatch, or a failure other than
    /// coverage holes (which only a whole run's merged coverage decides).
    pub fn failed_itself(&self) -> bool {
        let holes = |f: &String| f.starts_with(HOLES) || f.starts_with(NUMERIC_HOLES);
        self.mismatches > 0 || self.failures.iter().any(|f| !holes(f))
    }

    /// Sets coverage figures from a model (kept for merging shards).
    pub fn set_coverage(&mut self, cov: Coverage) {
        self.coverage_percent = cov.percent();
        self.unhit = cov.unhit();
        self.coverage_report = cov.report();
        self.coverage = Some(cov);
    }

    /// Adds another configuration's or shard's result of the same testbench. Messages of a
    /// configuration are prefixed with `label` when one is given. Coverage of another model
    /// is an error, and then nothing is added.
    pub fn absorb(&mut self, o: &TbResult, label: Option<&str>) -> Result<(), String> {
        // Everything that can fail first, into copies: a refused result changes nothing.
        let coverage = match (&self.coverage, &o.coverage) {
            (Some(a), Some(b)) => {
                let mut m = a.clone();
                m.merge(b)?;
                Some(m)
            }
            (a, b) => a.clone().or_else(|| b.clone()),
        };
        let mut stats = self.stats.clone();
        stats.merge(&o.stats)?;
        let add = |a: u64, b: u64, what: &str| {
            a.checked_add(b)
                .ok_or_else(|| format!("the {what} count overflows u64"))
        };
        let configurations = add(
            self.configurations,
            o.configurations.max(u64::from(label.is_some())),
            "configuration",
        )?;
        let transactions = add(self.transactions, o.transactions, "transaction")?;
        let cycles = add(self.cycles, o.cycles, "cycle")?;
        let mismatches = add(self.mismatches, o.mismatches, "mismatch")?;
        let tag = |m: &String| match label {
            Some(l) => format!("[{l}] {m}"),
            None => m.clone(),
        };
        self.coverage = coverage;
        self.stats = stats;
        self.configurations = configurations;
        self.transactions = transactions;
        self.cycles = cycles;
        self.mismatches = mismatches;
        self.mismatch_log.extend(o.mismatch_log.iter().map(tag));
        self.first_mismatch_cycle = self.first_mismatch_cycle.or(o.first_mismatch_cycle);
        self.mismatch_log.truncate(20);
        // The verdicts a merged result decides again from its merged figures.
        let again = |f: &&String| {
            [HOLES, NUMERIC_HOLES, TAKEN]
                .iter()
                .any(|p| f.starts_with(p))
        };
        let failures = o.failures.iter().filter(|f| !again(f));
        self.failures.extend(failures.map(tag));
        self.latency = match (self.latency, o.latency) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        self.notes.extend(o.notes.iter().cloned());
        self.tables.extend(o.tables.iter().cloned());
        self.records.extend(o.records.iter().cloned());
        crate::numeric::merge(&mut self.narrowings, &o.narrowings);
        self.vcd = self.vcd.take().or_else(|| o.vcd.clone());
        Ok(())
    }

    /// Drops the testbench's conclusions (notes and tables added after the configurations
    /// ran), to conclude again over merged records.
    pub fn strip_conclusions(&mut self) {
        if let Some((n, t)) = self.own.take() {
            self.notes.truncate(n);
            self.tables.truncate(t);
        }
    }

    /// Adds a scoreboard's comparisons: transactions, mismatches and the first of them in
    /// detail (with the cycle each was seen in).
    pub fn score<E: std::fmt::Debug, A: std::fmt::Debug>(&mut self, sb: &crate::Scoreboard<E, A>) {
        self.transactions += sb.compared();
        self.mismatches += sb.mismatch_count();
        let first = sb.mismatches().iter().filter_map(|m| m.cycle).min();
        self.first_mismatch_cycle = self.first_mismatch_cycle.or(first);
        for m in sb.mismatches().iter().take(10) {
            self.mismatch_log.push(format!(
                "transaction {} (cycle {:?}): {}",
                m.index, m.cycle, m.detail
            ));
        }
    }

    /// Adds a run's outcome: its cycles, or the timeout as a failure.
    pub fn ran(&mut self, r: &Result<crate::RunStats, crate::Timeout>) {
        match r {
            Ok(st) => self.cycles += st.cycles,
            Err(t) => self.failures.push(t.to_string()),
        }
    }

    /// The records of one row type (those that do not parse as `T` are skipped).
    pub fn records_of<T: serde::de::DeserializeOwned>(&self) -> Vec<T> {
        self.records
            .iter()
            .filter_map(|v| serde_json::from_value(v.clone()).ok())
            .collect()
    }

    /// Adds a record (any serialisable row).
    pub fn record<T: Serialize>(&mut self, row: &T) {
        if let Ok(v) = serde_json::to_value(row) {
            self.records.push(v);
        }
    }

    /// One line: name, transactions, mismatches, coverage, worst error, verdict.
    pub fn summary(&self) -> String {
        format!(
            "{}: {} transactions, {} mismatches, coverage {:.1} %, max error {} LSB: {}",
            self.name,
            self.transactions,
            self.mismatches,
            self.coverage_percent,
            self.stats.max_abs_lsb,
            self.verdict()
        )
    }

    /// The latency column: cycles, or `-`.
    pub fn latency_text(&self) -> String {
        self.latency
            .map(|l| l.to_string())
            .unwrap_or_else(|| "-".into())
    }

    /// `PASS` or `FAIL`.
    pub fn verdict(&self) -> &'static str {
        if self.passed {
            "PASS"
        } else {
            "FAIL"
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Merged counters once wrapped. An overflowing result is refused and the merged
    /// result keeps what it had.
    #[test]
    fn absorb_refuses_overflowing_counters_and_changes_nothing() {
        let mut a = TbResult::new("t", "u");
        a.transactions = 5;
        a.cycles = 7;
        let mut b = TbResult::new("t", "u");
        b.transactions = 1;
        b.cycles = u64::MAX;
        let e = a.absorb(&b, None).unwrap_err();
        assert!(e.contains("cycle count overflows"), "{e}");
        assert_eq!((a.transactions, a.cycles), (5, 7));
        b.cycles = 1;
        a.absorb(&b, None).unwrap();
        assert_eq!((a.transactions, a.cycles), (6, 8));
    }

    /// The verdict: a mismatch or a failure fails; coverage holes fail a whole run only, and
    /// deciding again replaces the holes line rather than adding another.
    #[test]
    fn finishing_decides_from_mismatches_failures_and_holes() {
        let mut r = TbResult::new("t", "u");
        r.finish();
        assert!(r.passed, "nothing wrong");
        r.unhit = vec!["p.b".into()];
        r.finish_with(false);
        assert!(r.passed, "a shard's holes");
        r.finish();
        r.finish();
        assert!(!r.passed);
        assert_eq!(r.failures, ["coverage holes (1 bins): p.b"]);
        r.unhit.clear();
        r.failures.push("timed out".into());
        r.finish();
        assert!(!r.passed);
        assert_eq!(
            r.failures,
            ["timed out"],
            "the holes line goes, the failure stays"
        );
        r.failures.clear();
        r.mismatches = 1;
        r.finish();
        assert!(!r.passed);
    }

    /// A configuration's failures are carried labelled, its holes line is not (the merged
    /// result decides its own holes); its scoreboard, runs and conclusions add up.
    #[test]
    fn absorbing_carries_failures_and_adds_scores_and_runs() {
        let mut c = TbResult::new("t", "u");
        c.failures = vec!["coverage holes (1 bins): p.b".into(), "timed out".into()];
        let mut sb = crate::Scoreboard::new(|e: &u8, a: &u8| {
            if e == a {
                Ok(())
            } else {
                Err("differs".into())
            }
        });
        for (e, a) in [(1, 1), (2, 3), (4, 5)] {
            sb.expect(e);
            sb.observe(9, a);
        }
        c.score(&sb);
        c.score(&sb);
        assert_eq!((c.transactions, c.mismatches), (6, 4));
        let stats = crate::RunStats {
            cycles: 40,
            ..Default::default()
        };
        c.ran(&Ok(stats.clone()));
        c.ran(&Ok(stats));
        assert_eq!(c.cycles, 80);
        let mut m = TbResult::new("t", "u");
        m.absorb(&c, Some("w8")).unwrap();
        assert_eq!(m.failures, ["[w8] timed out"]);
        assert_eq!((m.transactions, m.mismatches, m.cycles), (6, 4, 80));
        // Records come back by row type, from every configuration absorbed.
        #[derive(Serialize, serde::Deserialize, Debug, PartialEq)]
        struct Row {
            width: u32,
        }
        c.record(&Row { width: 8 });
        c.record(&"not a row");
        m.absorb(&c, Some("w9")).unwrap();
        assert_eq!(m.records_of::<Row>(), [Row { width: 8 }]);
        assert_eq!(m.records_of::<String>(), ["not a row"]);
        m.notes = vec!["ran".into(), "concluded".into()];
        m.own = Some((1, 0));
        m.strip_conclusions();
        assert_eq!(m.notes, ["ran"]);
    }

    #[test]
    fn summary_line_latency_column_and_verdict() {
        let mut r = TbResult::new("rsqrt", "156");
        assert_eq!((r.latency_text(), r.verdict()), ("-".to_string(), "FAIL"));
        r.transactions = 12;
        r.mismatches = 1;
        r.coverage_percent = 87.54;
        r.stats.record(1.0, 0.75, 0.125);
        r.latency = Some(3);
        assert_eq!(
            r.summary(),
            "rsqrt: 12 transactions, 1 mismatches, coverage 87.5 %, max error 2 LSB: FAIL"
        );
        r.passed = true;
        assert_eq!((r.latency_text(), r.verdict()), ("3".to_string(), "PASS"));
    }
}
