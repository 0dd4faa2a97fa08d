//! One driver and one monitor for every ready/valid port ([`hdl::kernel::Stream`]), over its
//! payload bundle: a transaction type says once how it goes onto the bundle's signals and
//! comes off them ([`hdl::kernel::Payload`]), and a testbench names the port ([`crate::stream!`]) instead
//! of writing a driver or a monitor for the unit (SpinalHDL's `StreamDriver` and
//! `StreamMonitor` are the model).

use crate::run::{Driver, Monitor};
use hdl::kernel::{Payload, Stream};
use std::marker::PhantomData;

/// Where a module's stream is: its field, to drive and to read ([`crate::stream!`] makes one).
pub type StreamAt<M, P> = (fn(&mut M) -> &mut Stream<P>, fn(&M) -> &Stream<P>);

/// The accessors of the stream in field `$field` of the module type `$m`, for
/// [`StreamDriver::new`] and [`StreamMonitor::new`]: `stream!(RayCaster, ray)`.
#[macro_export]
macro_rules! stream {
    ($m:ty, $($field:tt).+) => {{
        let at: $crate::StreamAt<$m, _> = (|d| &mut d.$($field).+, |d| &d.$($field).+);
        at
    }};
}

/// Drives a module's input stream with transactions `T`: each stays presented (valid high,
/// payload held) until a cycle in which the module's `ready` takes it; idle, valid is low.
pub struct StreamDriver<M, P, T> {
    at: StreamAt<M, P>,
    txn: PhantomData<fn(&T)>,
}

impl<M, P, T> StreamDriver<M, P, T> {
    /// The driver of the stream `at`.
    pub fn new(at: StreamAt<M, P>) -> Self {
        StreamDriver {
            at,
            txn: PhantomData,
        }
    }
}

impl<M, P, T: Payload<P>> Driver<M> for StreamDriver<M, P, T> {
    type Txn = T;
    fn drive(&mut self, dut: &mut M, txn: Option<&T>) {
        let s = (self.at.0)(dut);
        s.valid.set_bool(txn.is_some());
        if let Some(t) = txn {
            t.put(&mut s.payload);
        }
    }
    fn accepted(&self, dut: &M) -> bool {
        (self.at.1)(dut).ready.is_high()
    }
}

/// Watches a module's output stream: drives its `ready` as the run's sink pacing says, and
/// reports the payload of each transfer (valid and ready) as a `T`.
pub struct StreamMonitor<M, P, T> {
    at: StreamAt<M, P>,
    txn: PhantomData<fn() -> T>,
}

impl<M, P, T> StreamMonitor<M, P, T> {
    /// The monitor of the stream `at`.
    pub fn new(at: StreamAt<M, P>) -> Self {
        StreamMonitor {
            at,
            txn: PhantomData,
        }
    }
}

impl<M, P, T: Payload<P>> Monitor<M> for StreamMonitor<M, P, T> {
    type Txn = T;
    fn ready(&mut self, dut: &mut M, ready: bool) {
        (self.at.0)(dut).ready.set_bool(ready);
    }
    fn sample(&mut self, dut: &M) -> Option<T> {
        let s = (self.at.1)(dut);
        s.fire().then(|| T::take(&s.payload))
    }
}
