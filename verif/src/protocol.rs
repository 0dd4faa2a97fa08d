//! A checker for the rules of a valid/ready handshake, sampled once a cycle after the design
//! settled. Once the sender raises `valid` it must keep `valid` high and its payload unchanged
//! until the cycle in which `ready` is high (the transfer); the receiver may raise or lower
//! `ready` at any time. A sender that withdraws a request, or changes it while waiting, breaks a
//! receiver that takes it a cycle later; results may still match, so only a check at the pins
//! sees it.

use std::fmt;

/// A broken rule, with the cycle it was seen in.
// Each variant's line names its fields.
#[allow(missing_docs)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Violation<T> {
    /// `valid` fell in `cycle` while the payload `data` was still waiting for `ready`.
    Withdrawn { cycle: u64, data: T },
    /// The payload changed from `from` to `to` in `cycle` while waiting for `ready`.
    Changed { cycle: u64, from: T, to: T },
}

impl<T: fmt::Debug> fmt::Display for Violation<T> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Violation::Withdrawn { cycle, data } => {
                write!(
                    f,
                    "cycle {cycle}: valid withdrawn before ready (payload {data:?})"
                )
            }
            Violation::Changed { cycle, from, to } => write!(
                f,
                "cycle {cycle}: payload changed from {from:?} to {to:?} before ready"
            ),
        }
    }
}

/// Watches one handshake (see the module doc). The payload is whatever identifies the
/// transaction: an address, or a tuple of the fields that travel with `valid`.
#[derive(Clone, Debug)]
pub struct Handshake<T = u64> {
    name: &'static str,
    /// The payload presented and not yet taken.
    waiting: Option<T>,
    transfers: u64,
    violations: Vec<Violation<T>>,
    /// Violations beyond those kept (the first [`KEPT`] are kept).
    dropped: u64,
}

/// Violations kept for the report; later ones are only counted.
pub const KEPT: usize = 16;

impl<T: Copy + PartialEq + fmt::Debug> Handshake<T> {
    /// A checker for the handshake `name` (the valid signal's scope and name, for the message).
    pub fn new(name: &'static str) -> Handshake<T> {
        Handshake {
            name,
            waiting: None,
            transfers: 0,
            violations: Vec::new(),
            dropped: 0,
        }
    }

    /// The settled pins of `cycle`; returns whether a transfer happened in it.
    pub fn sample(&mut self, cycle: u64, valid: bool, ready: bool, data: T) -> bool {
        if let Some(from) = self.waiting {
            if !valid {
                self.record(Violation::Withdrawn { cycle, data: from });
            } else if data != from {
                self.record(Violation::Changed {
                    cycle,
                    from,
                    to: data,
                });
            }
        }
        let transfer = valid && ready;
        self.transfers += u64::from(transfer);
        self.waiting = (valid && !ready).then_some(data);
        transfer
    }

    fn record(&mut self, v: Violation<T>) {
        if self.violations.len() < KEPT {
            self.violations.push(v);
        } else {
            self.dropped += 1;
        }
    }

    /// Transfers seen (valid and ready in the same cycle).
    pub fn transfers(&self) -> u64 {
        self.transfers
    }

    /// The violations kept, in order.
    pub fn violations(&self) -> &[Violation<T>] {
        &self.violations
    }

    /// All violations seen, kept or not.
    pub fn violation_count(&self) -> u64 {
        self.violations.len() as u64 + self.dropped
    }

    /// `Err` with one line naming the handshake, the first violation and how many there were.
    pub fn check(&self) -> Result<(), String> {
        match self.violations.first() {
            None => Ok(()),
            Some(v) => Err(format!(
                "protocol {}: {v} ({} violation(s))",
                self.name,
                self.violation_count()
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds `(valid, ready, data)` per cycle from cycle 0; returns the checker.
    fn feed(pins: &[(bool, bool, u64)]) -> Handshake {
        let mut h = Handshake::new("u.req_valid");
        for (c, &(v, r, d)) in pins.iter().enumerate() {
            h.sample(c as u64, v, r, d);
        }
        h
    }

    #[test]
    fn a_request_held_until_ready_is_one_transfer() {
        let h = feed(&[
            (true, false, 7),
            (true, false, 7),
            (true, true, 7),
            (false, false, 0),
        ]);
        assert_eq!((h.transfers(), h.violations()), (1, &[][..]));
        assert_eq!(h.check(), Ok(()));
    }

    #[test]
    fn back_to_back_transfers_may_change_the_payload_each_cycle() {
        let h = feed(&[(true, true, 1), (true, true, 2), (true, true, 3)]);
        assert_eq!((h.transfers(), h.violation_count()), (3, 0));
    }

    #[test]
    fn ready_without_valid_and_idle_payload_changes_are_allowed() {
        let h = feed(&[
            (false, true, 5),
            (false, false, 9),
            (false, true, 1),
            (true, true, 4),
        ]);
        assert_eq!((h.transfers(), h.violation_count()), (1, 0));
    }

    #[test]
    fn a_withdrawn_request_is_reported_with_its_cycle_and_payload() {
        let h = feed(&[(true, false, 0x12), (false, true, 0x12)]);
        assert_eq!(
            h.violations(),
            [Violation::Withdrawn {
                cycle: 1,
                data: 0x12
            }]
        );
        assert_eq!(h.transfers(), 0);
        assert_eq!(
            h.check(),
            Err(
                "protocol u.req_valid: cycle 1: valid withdrawn before ready (payload 18) \
                 (1 violation(s))"
                    .into()
            )
        );
    }

    #[test]
    fn a_changed_payload_is_reported_and_the_new_one_waits() {
        // The change is one violation; the new payload is then held and taken.
        let h = feed(&[
            (true, false, 3),
            (true, false, 4),
            (true, false, 4),
            (true, true, 4),
        ]);
        let want = Violation::Changed {
            cycle: 1,
            from: 3,
            to: 4,
        };
        assert_eq!(h.violations(), [want]);
        assert_eq!(h.transfers(), 1);
        assert!(h.check().unwrap_err().contains("from 3 to 4"));
    }

    #[test]
    fn a_change_in_the_transfer_cycle_is_still_a_violation() {
        let h = feed(&[(true, false, 3), (true, true, 4)]);
        assert_eq!(h.violation_count(), 1);
        assert_eq!(h.transfers(), 1);
    }

    #[test]
    fn only_the_first_violations_are_kept_and_all_are_counted() {
        let mut pins = Vec::new();
        for k in 0..40u64 {
            pins.push((true, false, k));
        }
        let h = feed(&pins);
        assert_eq!(h.violations().len(), KEPT);
        assert_eq!(h.violation_count(), 39);
        assert!(h.check().unwrap_err().ends_with("(39 violation(s))"));
    }
}
