//! `texrtl dram`: DRAM 604 and control unit 607 alone on a trace of word reads.

use super::CmdError;
use clap::Args;
use std::path::{Path, PathBuf};

/// The DRAM 604 and its control unit 607 alone on a trace of word reads; JSON on stdout.
#[derive(Args, Debug)]
pub struct DramArgs {
    /// CSV with header addr: 16-bit word addresses in decimal, read in order.
    #[arg(long)]
    pub trace: PathBuf,
    /// Words per page (DRAM row).
    #[arg(long, default_value_t = 512)]
    pub page_words: u32,
    /// Extra time of a page fault in ns (RAS# precharge plus RAS#-to-CAS#), a multiple of
    /// the 5 ns controller cycle, at least 10.
    #[arg(long, default_value_t = 30)]
    pub t_fault_ns: u32,
    /// 256k (256K x 16) or 1m (1M x 16).
    #[arg(long, default_value = "256k")]
    pub size: String,
    /// Waveform of the pins, page register and controller state.
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// Reads a CSV with header `addr` of decimal word addresses below `words`.
pub fn read_trace(path: &Path, words: u64) -> Result<Vec<u64>, String> {
    let t = formats::csv::read(path, &["addr"])?;
    let mut v = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let a: u64 = t.parse(r, 0, "a word address")?;
        if a >= words {
            return Err(t.error(r, format!("address {a} beyond the DRAM's {words} words")));
        }
        v.push(a);
    }
    Ok(v)
}

/// Runs the trace; prints the statistics as JSON.
pub fn run(a: &DramArgs) -> Result<String, CmdError> {
    let outs: Vec<_> = a.vcd.as_deref().map(|v| ("--vcd", v)).into_iter().collect();
    let guard = super::Outputs::check(&outs, &[("--trace", a.trace.as_path())])?;
    guard.settle(dram_cmd(
        &a.trace,
        a.page_words,
        a.t_fault_ns,
        &a.size,
        a.vcd.clone(),
    ))
}

fn dram_cmd(
    trace: &std::path::Path,
    page_words: u32,
    t_fault_ns: u32,
    size: &str,
    vcd: Option<PathBuf>,
) -> Result<String, CmdError> {
    let words: u64 = match size {
        "256k" => 256 * 1024,
        "1m" => 1024 * 1024,
        _ => return Err(CmdError::Input(format!("--size {size}: 256k or 1m"))),
    };
    let base = units::texmem::dram_604::DramParams::default();
    if !t_fault_ns.is_multiple_of(base.cycle_ns) || t_fault_ns < 2 * base.cycle_ns {
        return Err(CmdError::Input(format!(
            "--t-fault-ns {t_fault_ns}: a multiple of the {} ns cycle, at least {}",
            base.cycle_ns,
            2 * base.cycle_ns
        )));
    }
    if page_words == 0 || !words.is_multiple_of(u64::from(page_words)) {
        return Err(CmdError::Input(format!(
            "--page-words {page_words}: must divide {words}"
        )));
    }
    let fault = t_fault_ns / base.cycle_ns;
    let p = units::texmem::dram_604::DramParams {
        cols: page_words,
        rows: (words / u64::from(page_words)) as u32,
        t_rp: fault / 2,
        t_rcd: fault - fault / 2,
        ..base
    };
    p.validate().map_err(|e| {
        // The fault time sets t_rp and t_rcd; the page size sets the rest.
        if e.starts_with("t_rp") || e.starts_with("t_rcd") {
            CmdError::Input(format!("--t-fault-ns {t_fault_ns}: {e}"))
        } else {
            CmdError::Input(format!("--page-words {page_words}: {e}"))
        }
    })?;
    let addrs = read_trace(trace, p.words()).map_err(CmdError::Input)?;
    let st = tb::runs::dram::run_trace(p, &addrs, vcd).map_err(super::run_error)?;
    if st.violations != 0 || st.data_errors != 0 {
        return Err(CmdError::Failed(format!(
            "{} timing violations, {} data errors",
            st.violations, st.data_errors
        )));
    }
    serde_json::to_string_pretty(&st).map_err(|e| CmdError::Failed(e.to_string()))
}
