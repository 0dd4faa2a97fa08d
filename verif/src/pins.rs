//! A driver and a monitor written as functions, for a unit whose ports are plain signals
//! rather than a [`hdl::kernel::Stream`]: the function says how a transaction goes onto the
//! pins (or comes off them), and the adapter is the [`Driver`] or [`Monitor`].
//!
//! ```
//! use hdl::fx::Format;
//! use hdl::kernel::Signal;
//! use verif::{Driver, Monitor, PinDriver, PinMonitor};
//!
//! struct Unit { valid_in: Signal, a: Signal, valid: Signal, out: Signal }
//!
//! // Presents `a` with `valid_in`; an idle cycle drives `valid_in` low.
//! fn drive(d: &mut Unit, t: Option<&u64>) {
//!     d.valid_in.set_bool(t.is_some());
//!     d.a.set_bits(t.copied().unwrap_or(0));
//! }
//! // Takes `out` in a cycle with `valid` high.
//! fn sample(d: &Unit) -> Option<u64> {
//!     d.valid.is_high().then(|| d.out.bits())
//! }
//!
//! let (bit, byte) = (Format::uint(1), Format::uint(8));
//! let mut u = Unit {
//!     valid_in: Signal::new("valid_in", bit),
//!     a: Signal::new("a", byte),
//!     valid: Signal::new("valid", bit),
//!     out: Signal::new("out", byte),
//! };
//! let (mut drv, mut mon) = (PinDriver::new(drive), PinMonitor::new(sample));
//! drv.drive(&mut u, Some(&7));
//! assert_eq!(u.a.bits(), 7);
//! assert!(drv.accepted(&u)); // no `ready` given: every cycle takes the transaction
//! assert_eq!(mon.sample(&u), None);
//! ```

use crate::run::{Driver, Monitor};
use std::marker::PhantomData;

/// A [`Driver`] made of a function that sets the pins for a transaction (or for an idle
/// cycle, `None`), and one that reads the unit's `ready` (by default: always ready).
pub struct PinDriver<M, T, D, A = fn(&M) -> bool> {
    drive: D,
    accepted: A,
    txn: PhantomData<fn(&mut M, &T)>,
}

impl<M, T, D: FnMut(&mut M, Option<&T>)> PinDriver<M, T, D> {
    /// The driver that sets the pins with `drive`, on a unit without backpressure.
    pub fn new(drive: D) -> Self {
        PinDriver {
            drive,
            accepted: |_| true,
            txn: PhantomData,
        }
    }

    /// The same driver on a unit that takes a transaction in a cycle where `ready` says so.
    pub fn ready<A: Fn(&M) -> bool>(self, ready: A) -> PinDriver<M, T, D, A> {
        PinDriver {
            drive: self.drive,
            accepted: ready,
            txn: PhantomData,
        }
    }
}

impl<M, T, D, A> Driver<M> for PinDriver<M, T, D, A>
where
    D: FnMut(&mut M, Option<&T>),
    A: Fn(&M) -> bool,
{
    type Txn = T;
    fn drive(&mut self, dut: &mut M, txn: Option<&T>) {
        (self.drive)(dut, txn)
    }
    fn accepted(&self, dut: &M) -> bool {
        (self.accepted)(dut)
    }
}

/// A [`Monitor`] made of a function that reads a transaction off the settled pins (`None` in
/// a cycle without one), and one that drives the unit's output `ready` (by default: none).
pub struct PinMonitor<M, T, S, R = fn(&mut M, bool)> {
    sample: S,
    ready: R,
    txn: PhantomData<fn(&M) -> T>,
}

impl<M, T, S: FnMut(&M) -> Option<T>> PinMonitor<M, T, S> {
    /// The monitor that reads transactions with `sample`, on a unit without an output
    /// handshake.
    pub fn new(sample: S) -> Self {
        PinMonitor {
            sample,
            ready: |_, _| {},
            txn: PhantomData,
        }
    }

    /// The same monitor on a unit whose output waits for `ready`: `ready` drives it as the
    /// run's sink pacing says.
    pub fn ready<R: FnMut(&mut M, bool)>(self, ready: R) -> PinMonitor<M, T, S, R> {
        PinMonitor {
            sample: self.sample,
            ready,
            txn: PhantomData,
        }
    }
}

impl<M, T, S, R> Monitor<M> for PinMonitor<M, T, S, R>
where
    S: FnMut(&M) -> Option<T>,
    R: FnMut(&mut M, bool),
{
    type Txn = T;
    fn ready(&mut self, dut: &mut M, ready: bool) {
        (self.ready)(dut, ready)
    }
    fn sample(&mut self, dut: &M) -> Option<T> {
        (self.sample)(dut)
    }
}
