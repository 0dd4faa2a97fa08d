//! A ready/valid port (SpinalHDL's `Stream`): `valid` and a payload bundle flow one way,
//! `ready` the other. A module declares it once, by the direction of its data
//! (`#[input] pub req: Stream<Req>`: inputs `valid` and the payload, output `ready`), and a
//! testbench drives or watches it with a generic driver or monitor (`verif::StreamDriver`,
//! `verif::StreamMonitor`) instead of one written for the unit.

use super::declared::Signals;
use super::module::{Dir, Visitor};
use super::signal::Signal;

/// A transaction that the payload bundle `P` of a stream carries: how it goes onto the
/// bundle's signals and comes off them, written once for every driver and monitor.
pub trait Payload<P>: Sized {
    /// Sets the bundle's signals to this transaction.
    fn put(&self, port: &mut P);
    /// The transaction the bundle's signals hold.
    fn take(port: &P) -> Self;
}

/// A ready/valid port carrying the payload bundle `P`. A transfer happens in a cycle where
/// both `valid` and `ready` are high ([`Stream::fire`]).
#[derive(Clone, Debug)]
pub struct Stream<P> {
    /// The source offers a payload.
    pub valid: Signal,
    /// The sink takes it this cycle.
    pub ready: Signal,
    /// What is offered: a struct of signals, each with its format.
    pub payload: P,
}

impl<P> Stream<P> {
    /// The port with its `valid` and `ready` named as given, carrying `payload`.
    pub fn new(valid: &'static str, ready: &'static str, payload: P) -> Stream<P> {
        Stream {
            valid: Signal::bit(valid),
            ready: Signal::bit(ready),
            payload,
        }
    }

    /// Whether the payload is transferred this cycle: valid and ready.
    #[inline]
    pub fn fire(&self) -> bool {
        self.valid.is_high() && self.ready.is_high()
    }
}

/// Visited in the direction of its data: `valid` and the payload as declared, `ready` the
/// other way (an input stream's `ready` is an output of the module, and the reverse).
impl<P: Signals> Signals for Stream<P> {
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        v.signal(dir, &self.valid);
        self.payload.visit_signals(dir, v);
        let back = match dir {
            Dir::Input => Dir::Output,
            Dir::Output => Dir::Input,
            d => d,
        };
        v.signal(back, &self.ready);
    }
    #[inline]
    fn bits_signals<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.valid.bits());
        self.payload.bits_signals(f);
        f(self.ready.bits());
    }
}
