//! The DRAM 604 and control unit 607 on an address trace (`texrtl dram`), every word read
//! checked against the DRAM's power-up contents.

use hdl::dram::{DramCtrl, DramParams};
use hdl::kernel::{NoTrace, Sim, Trace};
use serde::Serialize;
use std::path::{Path, PathBuf};
use waves::{TraceConfig, VcdTracer};

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
}

/// Reads a CSV with header `addr` of decimal word addresses below `words`.
pub fn read_trace(path: &Path, words: u64) -> Result<Vec<u64>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == "addr" => {}
        _ => return Err(format!("{}:1: header is not 'addr'", path.display())),
    }
    let mut v = Vec::new();
    for (i, l) in lines {
        let l = l.trim();
        if l.is_empty() {
            continue;
        }
        let a: u64 = l
            .parse()
            .map_err(|_| format!("{}:{}: '{l}' is not a word address", path.display(), i + 1))?;
        if a >= words {
            return Err(format!(
                "{}:{}: address {a} beyond the DRAM's {words} words",
                path.display(),
                i + 1
            ));
        }
        v.push(a);
    }
    Ok(v)
}

/// Runs `addrs` through the controller, one request as soon as it is ready.
pub fn run_trace(p: DramParams, addrs: &[u64], vcd: Option<PathBuf>) -> Result<DramStats, String> {
    let ctrl = DramCtrl::new("mem", p)?;
    match vcd {
        Some(path) => {
            let t = VcdTracer::create(
                &path,
                "dram",
                TraceConfig {
                    period_ps: u64::from(p.cycle_ns) * 1000,
                    ..TraceConfig::default()
                },
            )
            .map_err(|e| e.to_string())?;
            let (sim, st) = drive(Sim::traced(ctrl, t).map_err(|e| e.to_string())?, addrs)?;
            sim.finish().map_err(|e| e.to_string())?;
            Ok(st)
        }
        None => drive(Sim::<DramCtrl, NoTrace>::new(ctrl), addrs).map(|x| x.1),
    }
}

fn drive<T: Trace>(
    mut sim: Sim<DramCtrl, T>,
    addrs: &[u64],
) -> Result<(Sim<DramCtrl, T>, DramStats), String> {
    sim.reset(1);
    let start = sim.cycle();
    let p = *sim.dut.params();
    let mut next = 0;
    let mut pending: std::collections::VecDeque<u64> = Default::default();
    let mut data_errors = 0;
    let limit =
        start + 20 * (addrs.len() as u64 + 1) * u64::from(p.t_rp + p.t_rcd + p.t_cas + p.t_cp);
    loop {
        let d = &mut sim.dut;
        let want = next < addrs.len();
        d.req_valid.set_bool(want);
        if want {
            d.req_addr.set_bits(addrs[next]);
        }
        sim.eval();
        if sim.dut.ready.is_high() && want {
            pending.push_back(addrs[next]);
            next += 1;
        }
        if sim.dut.resp_valid.is_high() {
            let a = pending.pop_front().ok_or("response without a request")?;
            data_errors += u64::from(sim.dut.resp_data.bits() as u16 != DramParams::pattern(a));
        }
        let done = next == addrs.len() && pending.is_empty() && sim.dut.ready.is_high();
        if done {
            break;
        }
        sim.tick();
        if sim.cycle() > limit {
            return Err(format!(
                "watchdog: {} of {} reads after {} cycles",
                next,
                addrs.len(),
                sim.cycle() - start
            ));
        }
    }
    let c = &sim.dut;
    // The cycle in which the controller is ready again ends the last access's CAS# precharge.
    let cycles = sim.cycle() - start;
    let ns = cycles * u64::from(p.cycle_ns);
    let st = DramStats {
        reads: c.reads,
        page_hits: c.page_hits,
        page_faults: c.page_faults,
        cycles,
        ns,
        cycle_ns: p.cycle_ns,
        page_words: p.cols,
        reads_per_second: if ns == 0 {
            0.0
        } else {
            c.reads as f64 * 1e9 / ns as f64
        },
        violations: c.dram.violations,
        data_errors,
    };
    Ok((sim, st))
}

/// The DRAM testbench of `texrtl regress`: the document's figures (33 M texels/s peak, about
/// 27 M with 8 texels and 2 page faults per scanline), seeded random traces on both sizes,
/// every word checked, no timing violation, and a waveform of a short trace.
pub fn regress_suite(
    seed: verif::Seed,
    vcd: Option<PathBuf>,
) -> Result<crate::report::TbResult, String> {
    let mut res =
        crate::report::TbResult::new("dram", "DRAM 604 + control unit 607 (Figure 6, section 5)");
    res.seed = Some(seed.to_string());
    res.coverage_percent = 100.0;
    let p = DramParams::default();
    let add = |res: &mut crate::report::TbResult, st: &DramStats| {
        res.transactions += st.reads;
        res.cycles += st.cycles;
        res.mismatches += st.data_errors;
        if st.violations != 0 {
            res.failures
                .push(format!("{} DRAM timing violations", st.violations));
        }
    };
    let peak: Vec<u64> = (0..2000u64).map(|k| k % 512).collect();
    let s = run_trace(p, &peak, None)?;
    add(&mut res, &s);
    let mut lines = Vec::new();
    for line in 0..500u64 {
        let (a, b) = (2 * line % 512, (2 * line + 1) % 512);
        lines.extend((0..4).map(|k| a * 512 + k));
        lines.extend((0..4).map(|k| b * 512 + k));
    }
    let l = run_trace(p, &lines, None)?;
    add(&mut res, &l);
    for (name, got, want) in [
        ("peak", s.reads_per_second, 33.3e6),
        (
            "8 texels + 2 faults per scanline",
            l.reads_per_second,
            26.7e6,
        ),
    ] {
        if (got - want).abs() > 0.05e6 {
            res.failures.push(format!(
                "{name}: {:.2} M reads/s, the document says {:.1} M",
                got / 1e6,
                want / 1e6
            ));
        }
        res.notes.push(format!(
            "{name}: {:.2} M texels/s (document: {:.1} M)",
            got / 1e6,
            want / 1e6
        ));
    }
    let mut stim = verif::Stimulus::new(seed);
    for p in [DramParams::default(), DramParams::one_meg()] {
        let addrs = stim.draw_n(&(0..p.words()), 2000);
        let st = run_trace(p, &addrs, None)?;
        add(&mut res, &st);
    }
    if let Some(path) = vcd {
        let short: Vec<u64> = vec![0, 1, 2, 700, 701, 3, 4];
        let st = run_trace(p, &short, Some(path.clone()))?;
        add(&mut res, &st);
        res.vcd = Some(path);
    }
    res.finish_with(false);
    Ok(res)
}
