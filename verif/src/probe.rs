//! Values a testbench shows beside the design in its waveform (golden results, mismatch
//! flags), set the same way whether the run is traced or not.

use hdl::kernel::NoTrace;
use waves::{ProbeId, VcdTracer};

/// A tracer the testbench can set probes on; untraced runs take [`NoTrace`], which ignores
/// them, so one testbench body serves both.
pub trait ProbeSink {
    /// A real-valued probe (a golden value).
    fn real(&mut self, p: ProbeId, v: f64);
    /// A bit-vector probe (a reference word, a flag).
    fn bits(&mut self, p: ProbeId, v: u64);
    /// A one-bit flag.
    fn flag(&mut self, p: ProbeId, v: bool) {
        self.bits(p, u64::from(v));
    }
}

impl ProbeSink for VcdTracer {
    fn real(&mut self, p: ProbeId, v: f64) {
        self.set_real(p, v);
    }
    fn bits(&mut self, p: ProbeId, v: u64) {
        self.set_bits(p, v);
    }
}

impl ProbeSink for NoTrace {
    fn real(&mut self, _: ProbeId, _: f64) {}
    fn bits(&mut self, _: ProbeId, _: u64) {}
}
