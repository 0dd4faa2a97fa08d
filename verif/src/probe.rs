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

#[cfg(test)]
mod tests {
    use super::*;
    use hdl::kernel::Sim;
    use units::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
    use waves::check::read_vcd;
    use waves::TraceConfig;

    /// What a testbench body does: one value of each kind a cycle, through the trait.
    fn show<S: ProbeSink>(s: &mut S, p: [ProbeId; 3], c: u64) {
        s.real(p[0], c as f64 / 4.0);
        s.bits(p[1], 3 * c);
        s.flag(p[2], c % 2 == 1);
    }

    #[test]
    fn probes_set_through_the_trait_reach_the_waveform() {
        let dir = std::env::temp_dir().join(format!("texrtl-probe-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("probe.vcd");
        let mut t = VcdTracer::create(&path, "probes", TraceConfig::default()).unwrap();
        let p = [
            t.probe_real("r", None),
            t.probe_bits("b", 8, None),
            t.probe_bits("f", 1, None),
        ];
        let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
        let mut sim = Sim::traced(dut, t).unwrap();
        let mut untraced = NoTrace;
        for c in 0..6 {
            sim.eval();
            show(sim.trace_mut().unwrap(), p, c);
            show(&mut untraced, p, c);
            sim.tick();
        }
        sim.finish().unwrap();
        let rb = read_vcd(&path).unwrap();
        let at = |v: &str, c: u64| rb.value_at(v, c * 10_000).cloned();
        for c in 0..6 {
            let r = at("tb.golden.r", c).and_then(|v| v.as_f64());
            assert_eq!(r, Some(c as f64 / 4.0), "cycle {c}");
            assert_eq!(at("tb.golden.b", c).and_then(|v| v.as_u64()), Some(3 * c));
            assert_eq!(at("tb.golden.f", c).and_then(|v| v.as_u64()), Some(c % 2));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
