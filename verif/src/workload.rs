//! A command's run of a unit outside a testbench (a user's file of requests through it, with
//! its statistics and an optional waveform): [`Workload::sim`] and [`Workload::finish`] are
//! to a command what [`crate::Ctx::sim`] and [`crate::Ctx::finish`] are to a testbench, so a
//! traced simulation is built one way everywhere.

use crate::WaveOut;
use hdl::kernel::{Module, Sim};
use std::path::{Path, PathBuf};
use waves::{TraceConfig, VcdTracer};

/// Where a command's run writes its waveform, if anywhere.
#[derive(Clone, Debug, Default)]
pub struct Workload {
    /// The waveform, when asked for.
    pub wave: Option<WaveOut>,
}

impl Workload {
    /// Traced into `vcd` when given: every signal, at the design's own clock.
    pub fn vcd(vcd: Option<&Path>) -> Workload {
        Workload {
            wave: vcd.map(|p| WaveOut {
                vcd: p.to_path_buf(),
                trace: TraceConfig::default(),
                period_ps: None,
            }),
        }
    }

    /// Traced into the VCD given, with its trace configuration and clock period.
    pub fn traced(wave: Option<(PathBuf, TraceConfig)>) -> Workload {
        Workload {
            wave: wave.map(|(vcd, trace)| WaveOut {
                period_ps: Some(trace.period_ps),
                vcd,
                trace,
            }),
        }
    }

    /// The waveform's path, when there is one.
    pub fn path(&self) -> Option<&Path> {
        self.wave.as_ref().map(|w| w.vcd.as_path())
    }

    /// A simulation of `dut`, traced when there is a waveform (titled `title`, clocked at
    /// `own_period_ps` unless the configuration set a period); `probes` declares the golden
    /// values shown beside the design (called only when traced). Errors name the file.
    pub fn sim<M: Module, P>(
        &self,
        dut: M,
        title: &str,
        own_period_ps: u64,
        probes: impl FnOnce(&mut VcdTracer) -> P,
    ) -> Result<(Sim<M, VcdTracer>, Option<P>), String> {
        let Some(w) = &self.wave else {
            return Ok((
                Sim::maybe_traced(dut, None).map_err(|e| e.to_string())?,
                None,
            ));
        };
        let named = |e: std::io::Error| named(&w.vcd, e);
        let mut t = VcdTracer::create(&w.vcd, title, w.config(own_period_ps)).map_err(named)?;
        let p = probes(&mut t);
        Ok((Sim::traced(dut, t).map_err(named)?, Some(p)))
    }

    /// Ends a simulation made by [`Workload::sim`]: the waveform is closed and its `.gtkw`
    /// written. Errors name the file.
    pub fn finish<M: Module>(&self, sim: Sim<M, VcdTracer>) -> Result<M, String> {
        sim.finish()
            .map_err(|e| named(self.path().unwrap_or(Path::new("")), e))
    }
}

/// `e` as one line naming `path` (once: an error that names it already is kept as it is).
fn named(path: &Path, e: std::io::Error) -> String {
    let (e, shown) = (e.to_string(), path.display().to_string());
    if e.starts_with(&shown) {
        e
    } else {
        format!("{shown}: {e}")
    }
}
