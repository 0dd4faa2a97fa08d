//! The DRAM 604 and control unit 607 on an address trace (`texrtl dram`), every word read
//! checked against the DRAM's power-up contents.

use crate::RunError;
use hdl::kernel::{Sim, Trace};
use serde::Serialize;
use std::path::PathBuf;
use units::texmem::control_607::DramCtrl;
use units::texmem::dram_604::DramParams;
use verif::{
    run, About, Coverage, Coverpoint, Ctx, Event, Pacing, PinDriver, PinMonitor, RunSpec, TbResult,
    Testbench, Workload,
};
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

/// The coverage model of DRAM 604 + 607: each read's page outcome (hit or fault) and what it
/// followed (hit after hit, fault after hit, ...), where in the array it falls (row and
/// column regions), and whether it came back to back with the previous request or after idle
/// cycles, crossed with the outcome.
pub fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let page = c.add(Coverpoint::new("page").value("hit", 1).value("fault", 2));
    c.add(Coverpoint::new("after").values(&[
        "first_read",
        "hit_after_hit",
        "fault_after_hit",
        "hit_after_fault",
        "fault_after_fault",
    ]));
    let rows = c.add(
        Coverpoint::new("row")
            .value("first", 0)
            .ranges("inner", 1, 14, 2)
            .value("last", 15),
    );
    let cols = c.add(
        Coverpoint::new("column")
            .value("first", 0)
            .ranges("inner", 1, 14, 2)
            .value("last", 15),
    );
    let spacing = c.add(Coverpoint::new("spacing").values(&["back_to_back", "after_idle"]));
    c.cross("page_x_spacing", page, spacing);
    c.cross("row_x_column", rows, cols);
    c
}

/// A position in 16ths of a range of `n`: 0 first, 15 last, 1..=14 inside.
fn region(x: u64, n: u64) -> i64 {
    match x {
        0 => 0,
        _ if x + 1 == n => 15,
        _ => (1 + x * 14 / n) as i64,
    }
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

/// The configurations of the dram testbench: directed traces for the document's figures and
/// the waveform, random traces with page locality on both sizes, with and without idle gaps.
const CONFIGS: [&str; 6] = [
    "directed: hits, faults, a return to an old row (traced)",
    "peak: one page (document: 33.3 M texels/s)",
    "8 texels + 2 page faults per scanline (document: 26.7 M texels/s)",
    "random, 256K x 16, back to back",
    "random, 1M x 16, back to back",
    "random, 256K x 16, idle gaps",
];

/// The testbench's name: the top it drives, control unit 607 with its DRAM 604.
pub const NAME: &str = "control_607";

/// The DRAM testbench of `texrtl regress`.
pub struct DramTb;

/// `n` random addresses: half stay in the previous row (a random column), half anywhere, so
/// that every page outcome follows every other; then 32 directed ones covering the row and
/// column regions.
fn random_trace(p: &DramParams, n: usize, seed: verif::Seed) -> Vec<u64> {
    let mut stim = verif::Stimulus::new(seed);
    let words = p.words();
    let cols = u64::from(p.cols);
    let mut v: Vec<u64> = Vec::with_capacity(n);
    for _ in 0..n {
        let (same_row, a) = stim.draw(&(proptest::bool::ANY, 0..words));
        let a = match v.last() {
            Some(prev) if same_row => prev / cols * cols + a % cols,
            _ => a,
        };
        v.push(a);
    }
    // Every row region with every column region (first, inner, last), whatever the count:
    // row by row (hits after hits), then column by column (faults after faults).
    let rows = u64::from(p.rows);
    let rs = [0, rows / 4, 3 * rows / 4, rows - 1];
    let cs = [0, cols / 4, 3 * cols / 4, cols - 1];
    for r in rs {
        v.extend(cs.map(|c| r * cols + c));
    }
    for c in cs {
        v.extend(rs.map(|r| r * cols + c));
    }
    v
}

impl Testbench for DramTb {
    fn about(&self) -> About {
        About::new(NAME, "DRAM 604 + control unit 607 (Figure 6, section 5)")
            .count(2000, "random reads per random configuration")
    }
    fn configurations(&self) -> Vec<String> {
        CONFIGS.iter().map(|s| s.to_string()).collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let p = if ctx.index == 4 {
            DramParams::one_meg()
        } else {
            DramParams::default()
        };
        let addrs: Vec<u64> = match ctx.index {
            0 => vec![0, 1, 2, 700, 701, 3, 4, 511, 512],
            1 => (0..2000u64).map(|k| k % 512).collect(),
            2 => (0..500u64)
                .flat_map(|line| {
                    let (a, b) = (2 * line % 512, (2 * line + 1) % 512);
                    (0..4)
                        .map(move |k| a * 512 + k)
                        .chain((0..4).map(move |k| b * 512 + k))
                })
                .collect(),
            _ => random_trace(&p, ctx.count, ctx.seed),
        };
        let pacing = if ctx.index == 5 {
            // Longer than a page fault's access: 607 waits idle before every request.
            Pacing::every(16)
        } else {
            Pacing::full()
        };
        let wave = ctx
            .waves
            .as_ref()
            .map(|w| (w.vcd.clone(), w.config(u64::from(p.cycle_ns) * 1000)));
        let setup = DramRun {
            pacing,
            wave,
            coverage: true,
            check_schedule: ctx.check_schedule,
        };
        let (st, cov) = run_paced(p, &addrs, setup)?;
        let mut res = TbResult::new(self.name(), self.unit());
        res.transactions = st.reads;
        res.cycles = st.cycles;
        res.mismatches = st.data_errors;
        res.coverage = cov;
        res.vcd = ctx.waves.as_ref().map(|w| w.vcd.clone());
        if let Some(h) = st.hung {
            // Its counts stop where it hung: that is the finding.
            res.failures.push(h);
            return Ok(res);
        }
        if st.violations != 0 {
            res.failures
                .push(format!("{} DRAM timing violations", st.violations));
        }
        check_counts(&mut res, &p, &addrs, &st);
        let figure = [(1, 33.3e6), (2, 26.7e6)]
            .into_iter()
            .find(|f| f.0 == ctx.index);
        if let Some((_, want)) = figure {
            let got = st.reads_per_second;
            if (got - want).abs() > 0.05e6 {
                res.failures.push(format!(
                    "{:.2} M reads/s, the document says {:.1} M",
                    got / 1e6,
                    want / 1e6
                ));
            }
            res.notes
                .push(format!("{}: {:.2} M texels/s", ctx.label, got / 1e6));
        }
        Ok(res)
    }
}

/// The controller's page counts against the trace's own (a page hit is a read in the row the
/// previous read opened), and its time against the timing parameters.
fn check_counts(res: &mut TbResult, p: &DramParams, addrs: &[u64], st: &DramStats) {
    let cols = u64::from(p.cols);
    let faults = addrs
        .iter()
        .enumerate()
        .filter(|&(i, a)| i == 0 || addrs[i - 1] / cols != a / cols)
        .count() as u64;
    if (st.page_faults, st.page_hits) != (faults, addrs.len() as u64 - faults) {
        res.failures.push(format!(
            "page faults / hits {} / {}, the trace has {faults} / {}",
            st.page_faults,
            st.page_hits,
            addrs.len() as u64 - faults
        ));
    }
    let (per, fault) = (u64::from(p.t_cas + p.t_cp), u64::from(p.t_rp + p.t_rcd));
    if st.cycles < st.reads * per + st.page_faults * fault {
        res.failures.push(format!(
            "{} cycles for {} reads and {} faults: faster than the DRAM's timing allows",
            st.cycles, st.reads, st.page_faults
        ));
    }
}
