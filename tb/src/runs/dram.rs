//! `texrtl dram` (and the DRAM testbench): an address trace through control unit 607 and its
//! DRAM 604, perhaps paced and traced, every word read checked against the DRAM's power-up
//! contents; the statistics the command prints and the testbench holds against the document.

use crate::dram::{coverage_model, region, NAME};
use crate::RunError;
use hdl::kernel::{Sim, Trace};
use serde::Serialize;
use std::path::PathBuf;
use units::texmem::control_607::DramCtrl;
use units::texmem::dram_604::DramParams;
use verif::{run, Coverage, Event, Pacing, PinDriver, PinMonitor, RunSpec, Workload};
use waves::TraceConfig;

/// What a trace run measured.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct DramStats {
    pub reads: u64,
    pub page_hits: u64,
    pub page_faults: u64,
    /// Controller cycles from the first request until the last read has completed
    /// (CAS# precharge included).
    pub cycles: u64,
    /// `cycles * cycle_ns`.
    pub ns: u64,
    pub cycle_ns: u32,
    pub page_words: u32,
    /// Reads per second at this timing (`reads / ns`).
    pub reads_per_second: f64,
    /// Timing or protocol violations the DRAM model saw (0 for a correct controller).
    pub violations: u64,
    /// Reads whose data differed from the DRAM's contents.
    pub data_errors: u64,
    /// How the run hung, if it did (the reads stopped, or 607 never became ready again):
    /// the figures above are then up to where it stopped.
    #[serde(skip)]
    pub hung: Option<String>,
}

/// One read request: a word address, and whether the requester leaves the bus idle for a
/// while before it (`gap` cycles of the driver's pacing are set by the configuration).
pub type Addr = u64;

/// Presents word-read requests to control unit 607 (`req_valid`, `req_addr`); a request is
/// taken in a cycle with `ready` high.
pub fn drive_dram(dut: &mut DramCtrl, a: Option<&Addr>) {
    dut.req_valid.set_bool(a.is_some());
    if let Some(&a) = a {
        dut.req_addr.set_bits(a);
    }
}

/// Control unit 607 takes a request in a cycle with `ready` high.
pub fn dram_ready(dut: &DramCtrl) -> bool {
    dut.ready.is_high()
}

/// Collects each read's data word when `resp_valid` is high.
pub fn sample_dram(dut: &DramCtrl) -> Option<u16> {
    dut.resp_valid
        .is_high()
        .then(|| dut.resp_data.bits() as u16)
}

/// Runs `addrs` through the controller, one request as soon as it is ready; a hang fails the
/// run.
pub fn run_trace(
    p: DramParams,
    addrs: &[u64],
    vcd: Option<PathBuf>,
) -> Result<DramStats, RunError> {
    let period_ps = u64::from(p.cycle_ns) * 1000;
    let trace = TraceConfig {
        period_ps,
        ..TraceConfig::default()
    };
    let setup = DramRun {
        wave: vcd.map(|path| (path, trace)),
        ..DramRun::default()
    };
    let (st, _) = run_paced(p, addrs, setup)?;
    match &st.hung {
        Some(h) => Err(RunError::Failed(h.clone())),
        None => Ok(st),
    }
}

/// How a trace is run.
pub struct DramRun {
    /// When the requester offers its next read.
    pub pacing: Pacing,
    pub wave: Option<(PathBuf, TraceConfig)>,
    /// Sample the coverage model with every read.
    pub coverage: bool,
    pub check_schedule: bool,
}

impl Default for DramRun {
    fn default() -> Self {
        DramRun {
            pacing: Pacing::full(),
            wave: None,
            coverage: false,
            check_schedule: false,
        }
    }
}

/// Runs `addrs` through the controller as `setup` says; returns the statistics and (with
/// `setup.coverage`) the coverage model sampled with every read.
pub fn run_paced(
    p: DramParams,
    addrs: &[u64],
    setup: DramRun,
) -> Result<(DramStats, Option<Coverage>), RunError> {
    let ctrl = DramCtrl::new("control_607", p).map_err(RunError::Input)?;
    let cov = setup.coverage.then(coverage_model);
    let check = setup.check_schedule;
    let work = Workload::traced(setup.wave);
    let (sim, _) = work
        .sim(ctrl, NAME, 0, |_| ())
        .map_err(RunError::Waveform)?;
    let (sim, st, cov) = drive(sim.check_schedule(check), addrs, setup.pacing, cov)?;
    work.finish(sim).map_err(RunError::Waveform)?;
    Ok((st, cov))
}

/// A finished run: the simulation (to close its trace), the statistics, the coverage.
type Driven<T> = (Sim<DramCtrl, T>, DramStats, Option<Coverage>);

fn drive<T: Trace>(
    mut sim: Sim<DramCtrl, T>,
    addrs: &[u64],
    pacing: Pacing,
    mut cov: Option<Coverage>,
) -> Result<Driven<T>, String> {
    sim.reset(1);
    let start = sim.cycle();
    let p = *sim.dut.params();
    let mut sent: std::collections::VecDeque<u64> = Default::default();
    let (mut data_errors, mut received) = (0, 0usize);
    let (mut open_row, mut previous, mut idle) = (None::<u64>, 0i64, false);
    let mut done_at = None;
    let worst = u64::from(p.t_rp + p.t_rcd + p.t_cas + p.t_cp);
    let mut spec = RunSpec::new(
        addrs.len() as u64,
        100 + 20 * (addrs.len() as u64 + 1) * worst,
    )
    .pacing(pacing);
    let n = addrs.len();
    let r = run(
        &mut sim,
        &mut PinDriver::new(drive_dram).ready(dram_ready),
        &mut PinMonitor::new(sample_dram),
        addrs.iter().copied(),
        &mut spec,
        |sim, ev| match ev {
            Event::Sent { txn, .. } => {
                let (row, col) = (txn / u64::from(p.cols), txn % u64::from(p.cols));
                // 1 hit, 2 fault (the first read opens a row: a fault).
                let page = if open_row == Some(row) { 1 } else { 2 };
                let after = if previous == 0 {
                    0
                } else {
                    1 + 2 * (previous - 1) + (page - 1)
                };
                if let Some(c) = cov.as_mut() {
                    let (r, k) = (
                        region(row, u64::from(p.rows)),
                        region(col, u64::from(p.cols)),
                    );
                    c.sample(&[page, after, r, k, i64::from(idle)]);
                }
                (open_row, previous, idle) = (Some(row), page, false);
                sent.push_back(*txn);
            }
            Event::Received { txn, .. } => {
                let a = sent.pop_front().expect("a response follows a request");
                data_errors += u64::from(txn != DramParams::pattern(a));
                received += 1;
            }
            // The cycle in which the controller is ready again ends the last access's CAS#
            // precharge: the run's time ends there.
            Event::Settled { cycle } => {
                // A cycle in which 607 was ready and nothing was asked of it.
                idle |= sim.dut.ready.is_high() && !sim.dut.req_valid.is_high();
                if received == n && sim.dut.ready.is_high() && done_at.is_none() {
                    done_at = Some(cycle);
                }
            }
        },
    )
    .map_err(|t| t.to_string());
    let hung = match r {
        Ok(r) => settle(&mut sim, &mut done_at, start + r.cycles + worst).err(),
        Err(t) => Some(t),
    };
    let c = &sim.dut;
    let cycles = done_at.unwrap_or(sim.cycle()) - start;
    let ns = cycles * u64::from(p.cycle_ns);
    let st = DramStats {
        reads: c.reads.q().bits(),
        page_hits: c.page_hits.q().bits(),
        page_faults: c.page_faults.q().bits(),
        cycles,
        ns,
        cycle_ns: p.cycle_ns,
        page_words: p.cols,
        reads_per_second: if ns == 0 {
            0.0
        } else {
            c.reads.q().bits() as f64 * 1e9 / ns as f64
        },
        violations: c.dram.violations(),
        data_errors,
        hung,
    };
    Ok((sim, st, cov))
}

/// Runs on until control unit 607 is ready again (the last access's precharge done), by cycle
/// `limit` at the latest.
pub fn settle<T: Trace>(
    sim: &mut Sim<DramCtrl, T>,
    done_at: &mut Option<u64>,
    limit: u64,
) -> Result<(), String> {
    while done_at.is_none() {
        sim.eval();
        if sim.dut.ready.is_high() {
            *done_at = Some(sim.cycle());
        } else if sim.cycle() > limit {
            return Err(format!(
                "watchdog: control unit 607 not ready again by cycle {limit}"
            ));
        } else {
            sim.tick();
        }
    }
    Ok(())
}
