//! The DRAM testbench: control unit 607 and its DRAM 604 on directed traces (the document's
//! figures) and random ones with page locality, over the run of `texrtl dram`
//! ([`crate::runs::dram`]); the page counts and time held against the trace and the timing.

use crate::runs::dram::{run_paced, DramRun, DramStats};
use units::texmem::dram_604::DramParams;
use verif::{About, Coverage, Coverpoint, Ctx, Pacing, TbResult, Testbench};

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
pub(crate) fn region(x: u64, n: u64) -> i64 {
    match x {
        0 => 0,
        _ if x + 1 == n => 15,
        _ => (1 + x * 14 / n) as i64,
    }
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
