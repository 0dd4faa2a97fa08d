//! In-order scoreboard: golden transactions in, DUT transactions in, every mismatch recorded.

use crate::run::{run_scored, Driver, Monitor, RunSpec, RunStats, Scored, Timeout};
use hdl::kernel::{Module, Sim, Trace};
use serde::Serialize;
use std::collections::VecDeque;
use std::fmt::Debug;

/// One disagreement between the DUT and the golden model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mismatch {
    /// Index of the transaction (0 = first compared).
    pub index: u64,
    /// Cycle in which the DUT's transaction was seen (`None` for a missing one).
    pub cycle: Option<u64>,
    /// The golden transaction, as text.
    pub expected: String,
    /// The DUT's, as text.
    pub actual: String,
    /// What differs.
    pub detail: String,
}

/// Says what differs between a golden and a DUT transaction, or `Ok` when they agree.
pub type Comparator<E, A> = Box<dyn Fn(&E, &A) -> Result<(), String>>;

/// A comparator's verdict on values that may differ from their golden ones by a derived
/// bound: `Ok` when every `actual[k]` is within `bound` of `expected[k]`, else what the
/// largest difference was. Both in the same unit (scale raw integers by their LSB first).
///
/// ```
/// assert!(verif::within(&[1.0, 2.25], &[1.2, 2.0], 0.25).is_ok());
/// let e = verif::within(&[1.0, 2.5], &[1.0, 2.0], 0.25).unwrap_err();
/// assert_eq!(e, "[1.0, 2.5] is 5.000e-1 from [1.0, 2.0] (bound 2.500e-1)");
/// assert!(verif::within(&[f64::NAN], &[0.0], 1.0).is_err());
/// ```
pub fn within(actual: &[f64], expected: &[f64], bound: f64) -> Result<(), String> {
    assert_eq!(
        actual.len(),
        expected.len(),
        "within: values against golden values"
    );
    let worst = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| (a - e).abs())
        // A NaN difference is the worst (`f64::max` would drop it).
        .fold(0.0, |w, d| if d > w || d.is_nan() { d } else { w });
    if worst <= bound {
        Ok(())
    } else {
        Err(format!(
            "{actual:?} is {worst:.3e} from {expected:?} (bound {bound:.3e})"
        ))
    }
}

/// The result of comparing one DUT transaction.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome<E> {
    /// Whether it agreed with the golden one.
    pub ok: bool,
    /// The golden transaction it was compared with (`None`: the DUT produced one too many).
    pub expected: Option<E>,
}

/// Compares DUT transactions `A` against golden transactions `E` in order, with a comparator
/// that says what differs (or `Ok` when they agree).
pub struct Scoreboard<E, A> {
    expected: VecDeque<E>,
    compare: Comparator<E, A>,
    mismatches: Vec<Mismatch>,
    compared: u64,
    /// Keep at most this many mismatches in detail (all are counted).
    pub keep: usize,
    count: u64,
}

impl<E: Debug, A: Debug> Scoreboard<E, A> {
    /// A scoreboard comparing with `compare`.
    pub fn new(compare: impl Fn(&E, &A) -> Result<(), String> + 'static) -> Self {
        Scoreboard {
            expected: VecDeque::new(),
            compare: Box::new(compare),
            mismatches: Vec::new(),
            compared: 0,
            keep: 100,
            count: 0,
        }
    }

    /// Queues a golden transaction.
    pub fn expect(&mut self, e: E) {
        self.expected.push_back(e);
    }

    /// Compares a DUT transaction seen in `cycle` with the oldest golden one. Returns whether
    /// they agree, and the golden transaction it was compared with (for error statistics).
    pub fn observe(&mut self, cycle: u64, a: A) -> Outcome<E> {
        let index = self.compared;
        self.compared += 1;
        match self.expected.pop_front() {
            Some(e) => match (self.compare)(&e, &a) {
                Ok(()) => Outcome {
                    ok: true,
                    expected: Some(e),
                },
                Err(detail) => {
                    self.record(Mismatch {
                        index,
                        cycle: Some(cycle),
                        expected: format!("{e:?}"),
                        actual: format!("{a:?}"),
                        detail,
                    });
                    Outcome {
                        ok: false,
                        expected: Some(e),
                    }
                }
            },
            None => {
                self.record(Mismatch {
                    index,
                    cycle: Some(cycle),
                    expected: "nothing".into(),
                    actual: format!("{a:?}"),
                    detail: "unexpected transaction from the DUT".into(),
                });
                Outcome {
                    ok: false,
                    expected: None,
                }
            }
        }
    }

    /// Runs `stimulus` through the DUT ([`run_scored`]) and scores it. Each item pairs a
    /// transaction with its expectation: when the DUT accepts the transaction, the
    /// expectation is queued; each transaction the monitor receives is compared with the
    /// oldest one queued, and `compared` hears it with that expectation (error statistics,
    /// coverage, probes); one the DUT produced with nothing queued is only a mismatch.
    pub fn run<M, T, D, Mo>(
        &mut self,
        sim: &mut Sim<M, T>,
        driver: &mut D,
        monitor: &mut Mo,
        stimulus: impl IntoIterator<Item = (D::Txn, E)>,
        spec: &mut RunSpec,
        mut compared: impl FnMut(&mut Sim<M, T>, E, A),
    ) -> Result<RunStats, Timeout>
    where
        M: Module,
        T: Trace,
        D: Driver<M>,
        Mo: Monitor<M, Txn = A>,
        A: Clone,
    {
        let (txns, expected): (Vec<D::Txn>, VecDeque<E>) = stimulus.into_iter().unzip();
        let mut expected = expected.into_iter();
        run_scored(sim, driver, monitor, txns, spec, |sim, ev| match ev {
            Scored::Sent { .. } => self.expect(expected.next().expect("one a transaction")),
            Scored::Received { cycle, txn } => {
                if let Some(e) = self.observe(cycle, txn.clone()).expected {
                    compared(sim, e, txn);
                }
            }
        })
    }

    /// At the end of a run: every golden transaction still waiting is a mismatch.
    pub fn drain(&mut self) {
        while let Some(e) = self.expected.pop_front() {
            let index = self.compared;
            self.compared += 1;
            self.record(Mismatch {
                index,
                cycle: None,
                expected: format!("{e:?}"),
                actual: "nothing".into(),
                detail: "the DUT never produced it".into(),
            });
        }
    }

    fn record(&mut self, m: Mismatch) {
        self.count += 1;
        if self.mismatches.len() < self.keep {
            self.mismatches.push(m);
        }
    }

    /// Transactions compared (including missing and unexpected ones).
    pub fn compared(&self) -> u64 {
        self.compared
    }
    /// Mismatches counted.
    pub fn mismatch_count(&self) -> u64 {
        self.count
    }
    /// The first `keep` mismatches in detail.
    pub fn mismatches(&self) -> &[Mismatch] {
        &self.mismatches
    }
    /// Golden transactions still waiting for the DUT's.
    pub fn pending(&self) -> usize {
        self.expected.len()
    }
    /// No mismatch and nothing pending.
    pub fn passed(&self) -> bool {
        self.count == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_mismatch_missing_and_unexpected() {
        let mut sb = Scoreboard::new(|e: &u32, a: &u32| {
            if e == a {
                Ok(())
            } else {
                Err(format!("{a} != {e}"))
            }
        });
        sb.expect(1);
        sb.expect(2);
        sb.expect(3);
        assert!(sb.observe(10, 1).ok);
        assert!(!sb.observe(11, 5).ok);
        sb.drain();
        assert!(!sb.observe(12, 7).ok);
        assert_eq!(sb.mismatch_count(), 3);
        let m = sb.mismatches();
        assert_eq!((m[0].index, m[0].cycle), (1, Some(11)));
        assert_eq!(m[0].detail, "5 != 2");
        assert_eq!(m[1].cycle, None);
        assert_eq!(m[2].expected, "nothing");
        assert!(!sb.passed());
        assert_eq!(
            sb.compared(),
            4,
            "matched, differing, never produced, unexpected"
        );
    }

    /// Every mismatch is counted; the first hundred are kept in detail.
    #[test]
    fn a_hundred_mismatches_are_kept() {
        let mut sb = Scoreboard::new(|_: &u32, _: &u32| Err("no".into()));
        for k in 0..150 {
            sb.expect(k);
        }
        sb.drain();
        assert_eq!((sb.compared(), sb.mismatch_count()), (150, 150));
        assert_eq!(sb.mismatches().len(), 100);
        assert_eq!(sb.mismatches()[99].index, 99);
    }
}
