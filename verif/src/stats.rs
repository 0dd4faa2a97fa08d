//! Error statistics of a DUT against its golden model, in LSBs of the DUT's output format.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Error of fixed-point results against real-valued golden results, in output LSBs.
///
/// Each sample's error is `(dut - golden) / lsb`. Reported: count, max and mean absolute
/// error, counts of exact results (error 0) and of results within +-1 LSB, a histogram of
/// the error rounded to the nearest whole LSB, and the SQNR in dB (golden power over error
/// power).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Results measured.
    pub count: u64,
    /// The largest absolute error, in LSBs.
    pub max_abs_lsb: f64,
    /// The sum of the absolute errors, in LSBs (for the mean).
    pub sum_abs_lsb: f64,
    /// Results with no error.
    pub exact: u64,
    /// Results within one LSB.
    pub within_1_lsb: u64,
    /// Error rounded to whole LSBs (ties away from zero) -> count.
    pub histogram: BTreeMap<i64, u64>,
    sum_sq_signal: f64,
    sum_sq_error: f64,
    /// Sample index and values of the worst error: (index, dut, golden).
    pub worst: Option<(u64, f64, f64)>,
}

impl ErrorStats {
    /// No result yet.
    pub fn new() -> ErrorStats {
        ErrorStats::default()
    }

    /// Records one result: the DUT's value, the golden value, the DUT's LSB weight (`2^-F`).
    /// A NaN golden value is a testbench bug and panics.
    pub fn record(&mut self, dut: f64, golden: f64, lsb: f64) {
        assert!(
            golden.is_finite() && dut.is_finite(),
            "non-finite value: dut {dut}, golden {golden}"
        );
        let e = (dut - golden) / lsb;
        let a = e.abs();
        if a > self.max_abs_lsb || self.worst.is_none() {
            self.max_abs_lsb = a;
            self.worst = Some((self.count, dut, golden));
        }
        self.count += 1;
        self.sum_abs_lsb += a;
        self.exact += u64::from(e == 0.0);
        self.within_1_lsb += u64::from(a <= 1.0);
        *self.histogram.entry(e.round() as i64).or_insert(0) += 1;
        self.sum_sq_signal += golden * golden;
        self.sum_sq_error += (dut - golden) * (dut - golden);
    }

    /// Mean absolute error in LSBs (0 when empty).
    pub fn mean_abs_lsb(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            self.sum_abs_lsb / self.count as f64
        }
    }

    /// Signal-to-quantisation-noise ratio in dB; `None` when the error is zero.
    pub fn sqnr_db(&self) -> Option<f64> {
        (self.sum_sq_error > 0.0).then(|| 10.0 * (self.sum_sq_signal / self.sum_sq_error).log10())
    }

    /// Combines statistics of two runs (shards).
    pub fn merge(&mut self, o: &ErrorStats) -> Result<(), String> {
        // Into a copy: an overflow leaves `self` as it was.
        let mut m = self.clone();
        let add = |a: u64, b: u64| {
            a.checked_add(b)
                .ok_or_else(|| "error statistics: a count overflows u64".to_string())
        };
        let sum = |a: f64, b: f64| {
            let x = a + b;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(format!(
                    "error statistics: {a:e} + {b:e} is not a finite sum"
                ))
            }
        };
        if !o.max_abs_lsb.is_finite() {
            return Err(format!(
                "error statistics: maximum {} is not finite",
                o.max_abs_lsb
            ));
        }
        if o.max_abs_lsb > m.max_abs_lsb {
            m.max_abs_lsb = o.max_abs_lsb;
            m.worst = o.worst.map(|(i, d, g)| (i.saturating_add(m.count), d, g));
        }
        m.count = add(m.count, o.count)?;
        m.sum_abs_lsb = sum(m.sum_abs_lsb, o.sum_abs_lsb)?;
        m.exact = add(m.exact, o.exact)?;
        m.within_1_lsb = add(m.within_1_lsb, o.within_1_lsb)?;
        for (k, v) in &o.histogram {
            let e = m.histogram.entry(*k).or_insert(0);
            *e = add(*e, *v)?;
        }
        m.sum_sq_signal = sum(m.sum_sq_signal, o.sum_sq_signal)?;
        m.sum_sq_error = sum(m.sum_sq_error, o.sum_sq_error)?;
        *self = m;
        Ok(())
    }

    /// One line: `n=…, max=… LSB, mean=… LSB, exact=…, ±1=…`.
    pub fn summary(&self) -> String {
        format!(
            "n={} max={:.3} LSB mean={:.4} LSB exact={} within±1={}{}",
            self.count,
            self.max_abs_lsb,
            self.mean_abs_lsb(),
            self.exact,
            self.within_1_lsb,
            self.sqnr_db()
                .map(|s| format!(" SQNR={s:.1} dB"))
                .unwrap_or_default()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_in_lsbs() {
        let mut s = ErrorStats::new();
        let lsb = 1.0 / 256.0;
        s.record(0.5, 0.5, lsb);
        s.record(0.5 + lsb, 0.5, lsb);
        s.record(0.5 - 3.0 * lsb, 0.5, lsb);
        assert_eq!(s.count, 3);
        assert_eq!(s.exact, 1);
        assert_eq!(s.within_1_lsb, 2);
        assert_eq!(s.max_abs_lsb, 3.0);
        assert!((s.mean_abs_lsb() - 4.0 / 3.0).abs() < 1e-12);
        assert_eq!(s.histogram.get(&-3), Some(&1));
        assert_eq!(s.worst.unwrap().0, 2);
        let mut t = ErrorStats::new();
        t.record(1.0, 1.0, lsb);
        t.merge(&s).unwrap();
        assert_eq!(t.count, 4);
        assert_eq!(t.worst.unwrap().0, 3);
        assert!(t.sqnr_db().unwrap() > 40.0);
    }

    /// Merged shard summaries once wrapped u64 counters and wrote 1e308 + 1e308 as
    /// `null`. Both are refused, and the refused merge changes nothing.
    #[test]
    fn merging_refuses_overflow_and_leaves_the_stats_unchanged() {
        let mut a = ErrorStats::new();
        a.record(1.0, 1.0, 1.0);
        let before = a.clone();
        let mut b = a.clone();
        b.count = u64::MAX;
        assert!(a.merge(&b).unwrap_err().contains("overflows u64"));
        let mut c = a.clone();
        c.sum_sq_signal = 1e308;
        a.sum_sq_signal = 1e308;
        assert!(a.merge(&c).unwrap_err().contains("not a finite sum"));
        a.sum_sq_signal = before.sum_sq_signal;
        assert_eq!(a.count, before.count);
        assert_eq!(a.sum_abs_lsb, before.sum_abs_lsb);
    }

    #[test]
    fn the_summary_line_names_every_figure() {
        let mut s = ErrorStats::new();
        assert_eq!(
            s.summary(),
            "n=0 max=0.000 LSB mean=0.0000 LSB exact=0 within±1=0"
        );
        let lsb = 1.0 / 256.0;
        for (d, g) in [(0.5, 0.5), (0.5 + lsb, 0.5), (0.5 - 3.0 * lsb, 0.5)] {
            s.record(d, g, lsb);
        }
        // SQNR: 0.75 / (10 / 65536) = 4915.2, 36.9 dB.
        assert_eq!(
            s.summary(),
            "n=3 max=3.000 LSB mean=1.3333 LSB exact=1 within±1=2 SQNR=36.9 dB"
        );
    }

    /// The worst result is the first with the largest error, in one run and across a merge.
    #[test]
    fn the_worst_is_the_first_of_equals() {
        let mut a = ErrorStats::new();
        a.record(2.0, 0.0, 1.0);
        a.record(-2.0, 0.0, 1.0);
        assert_eq!(a.worst, Some((0, 2.0, 0.0)));
        let mut b = ErrorStats::new();
        b.record(5.0, 3.0, 1.0);
        a.merge(&b).unwrap();
        assert_eq!(
            a.worst,
            Some((0, 2.0, 0.0)),
            "the merged-in equal comes later"
        );
    }

    #[test]
    #[should_panic(expected = "non-finite")]
    fn nan_is_refused() {
        ErrorStats::new().record(0.0, f64::NAN, 1.0);
    }
}
