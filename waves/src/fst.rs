//! FST output: the compact format GTKWave and Surfer load fastest, for long runs. The FST is
//! made from the finished VCD (read with `wellen`, written with `fst-writer`), so both hold the
//! same hierarchy, widths and values; `gtkwave X.fst X.gtkw` opens it with the VCD's view.

use fst_writer::{FstFileType, FstInfo, FstScopeType, FstSignalType, FstVarDirection, FstVarType};
use std::path::Path;
use wellen::{simple, SignalValue, SignalValueRef};

/// An fst-writer error as one line (its I/O variant with the operating system's words).
fn fst_message(e: &fst_writer::FstWriteError) -> String {
    match e {
        fst_writer::FstWriteError::Io(io) => io.to_string(),
        e => e.to_string(),
    }
}

/// Writes `fst` with everything `vcd` holds (through `fst.partial`, renamed when complete).
pub fn vcd_to_fst(vcd: &Path, fst: &Path) -> Result<(), String> {
    let err = |m: String| format!("{}: {m}", fst.display());
    let mut w = simple::read(vcd).map_err(|e| format!("{}: {e}", vcd.display()))?;
    let h = w.hierarchy();
    let exp = crate::check::timescale_exp(h).unwrap_or(-12);
    let info = FstInfo {
        // fst-writer writes this into the header's time zero, an offset GTKWave adds to every
        // time it shows; the VCD's times are absolute (a trace window's too).
        start_time: 0,
        timescale_exponent: exp,
        version: concat!("texrtl ", env!("CARGO_PKG_VERSION")).into(),
        date: String::new(),
        file_type: FstFileType::Verilog,
    };
    let out = crate::output::Staged::new(fst);
    let mut hw = fst_writer::open_fst(out.write_path(), &info).map_err(|e| err(fst_message(&e)))?;
    // Hierarchy: walk scopes depth first, declaring each scope's variables.
    let mut ids = Vec::new(); // (signal ref, fst id, is real, width)
    fn walk(
        h: &wellen::Hierarchy,
        s: wellen::ScopeRef,
        hw: &mut fst_writer::FstHeaderWriter<std::io::BufWriter<std::fs::File>>,
        ids: &mut Vec<(wellen::SignalRef, fst_writer::FstSignalId, bool, u32)>,
    ) -> Result<(), String> {
        let scope = &h[s];
        hw.scope(scope.name(h), "", FstScopeType::Module)
            .map_err(|e| fst_message(&e))?;
        for v in scope.vars(h) {
            let var = &h[v];
            let real = var.is_real(h);
            let width = var.length(h).unwrap_or(64);
            let (st, vt) = if real {
                (FstSignalType::real(), FstVarType::Real)
            } else {
                (FstSignalType::bit_vec(width), FstVarType::Wire)
            };
            let id = hw
                .var(var.name(h), st, vt, FstVarDirection::Implicit, None)
                .map_err(|e| fst_message(&e))?;
            ids.push((var.signal_ref(), id, real, width));
        }
        for c in scope.scopes(h) {
            walk(h, c, hw, ids)?;
        }
        hw.up_scope().map_err(|e| fst_message(&e))
    }
    for s in h.scopes() {
        walk(h, s, &mut hw, &mut ids).map_err(err)?;
    }
    let refs: Vec<_> = ids.iter().map(|i| i.0).collect();
    w.load_signals(&refs);
    let times = w.time_table().to_vec();
    // Every change as (time index, variable index, value bytes), in time order.
    let mut changes: Vec<(u32, usize, Vec<u8>)> = Vec::new();
    for (k, (r, _, _, _)) in ids.iter().enumerate() {
        let sig = w
            .get_signal(*r)
            .ok_or_else(|| err("signal not loaded".into()))?;
        for (ti, v) in sig.iter_changes() {
            let v: SignalValue = v.into();
            let bytes = match SignalValueRef::from(&v) {
                // Only a real variable has real values.
                SignalValueRef::Real(x) => x.to_le_bytes().to_vec(),
                other => other.to_bit_string().unwrap_or_default().into_bytes(),
            };
            changes.push((ti, k, bytes));
        }
    }
    changes.sort_by_key(|c| (c.0, c.1));
    let mut bw = hw.finish().map_err(|e| err(fst_message(&e)))?;
    let mut current = None;
    for (ti, k, bytes) in &changes {
        if current != Some(*ti) {
            bw.time_change(times[*ti as usize])
                .map_err(|e| err(fst_message(&e)))?;
            current = Some(*ti);
        }
        bw.signal_change(ids[*k].1, bytes)
            .map_err(|e| err(fst_message(&e)))?;
    }
    // The VCD's closing timestamp, so the trace does not look as if it ended early.
    if let Some(&end) = times.last() {
        bw.time_change(end).map_err(|e| err(fst_message(&e)))?;
    }
    bw.finish().map_err(|e| err(fst_message(&e)))?;
    out.commit().map_err(|e| e.to_string())
}

/// Whether a FST read back holds the VCD's variables, widths and, at every VCD timestamp, the
/// VCD's values, and ends when the VCD ends (a FST may carry one extra leading timestamp:
/// fst-writer starts time at 0).
pub fn same_values(
    vcd: &crate::check::Readback,
    fst: &crate::check::Readback,
) -> Result<(), String> {
    if vcd.vars.keys().ne(fst.vars.keys()) {
        return Err("different variables".into());
    }
    if vcd.times.last() != fst.times.last() {
        return Err(format!(
            "the VCD ends at {:?}, the FST at {:?}",
            vcd.times.last(),
            fst.times.last()
        ));
    }
    for (name, v) in &vcd.vars {
        let f = &fst.vars[name];
        if v.width != f.width {
            return Err(format!("{name}: width {:?} vs {:?}", v.width, f.width));
        }
        for &t in &vcd.times {
            if vcd.value_at(name, t) != fst.value_at(name, t) {
                return Err(format!("{name} differs at time {t}"));
            }
        }
    }
    Ok(())
}
