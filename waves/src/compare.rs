//! A waveform of two implementations side by side (the Rust model and the RTL of a
//! co-simulation): scopes `tb.model` and `tb.rtl` with the same ports, `tb.mismatch` with a
//! flag per port, and a `.gtkw` that puts each RTL port and its flag right under the model's.
//! Beside them, [`Shown`] scopes: the inputs, signals inside the model, and the RTL's
//! internals around a difference ([`crate::sample`]), each a scope under `tb`.

use crate::gtkw::{self, Gtkw, Item, Style};
use std::io::{BufWriter, Write};
use std::path::Path;
use vcd::{IdCode, TimescaleUnit};

/// A port: name, width and whether its format is signed (shown as signed decimal).
pub type PortDef<'a> = (&'a str, u32, bool);

/// Values shown beside the comparison, not compared: the inputs of every cycle, signals
/// inside the model, the RTL's internals around a difference.
pub struct Shown<'a> {
    /// The scope under `tb` (`inputs`, `probes`).
    pub scope: &'a str,
    /// The signals' names and widths. A name with dots (`u_stage.acc`) is in scopes of
    /// its own below this one, in the waveform's tree but not in the save file's view.
    pub signals: &'a [PortDef<'a>],
    /// Their values.
    pub values: Values<'a>,
    /// The signals with named values (an FSM's states): each one's index in `signals` and
    /// its names, value by value. Shown by name where the view shows it (a translate
    /// filter file beside the dump).
    pub states: &'a [(usize, &'a [&'a str])],
}

/// The values of a [`Shown`] scope's signals.
#[derive(Clone, Copy, Debug)]
pub enum Values<'a> {
    /// `v[c][k]`: signal `k` in cycle `c`.
    Every(&'a [Vec<u64>]),
    /// `v[i][k]`: signal `k` in cycle `first + i` (`None`: unknown, written as `x`); in
    /// every other cycle the signal was not recorded, written as `z`.
    From(usize, &'a [Vec<Option<u64>>]),
}

impl Values<'_> {
    /// Whether a value may change in cycle `c`: a window's only at its start and up to the
    /// cycle after it (and cycle 0, where everything starts), so a long run does not look
    /// at thousands of unrecorded signals every cycle.
    fn may_change(&self, c: usize) -> bool {
        match *self {
            Values::Every(_) => true,
            Values::From(first, v) => c == 0 || (first..=first + v.len()).contains(&c),
        }
    }

    /// What signal `k` (`width` bits) shows in cycle `c`.
    fn level(&self, c: usize, k: usize, width: u32) -> Level {
        match *self {
            Values::Every(v) => Level::of(v.get(c).and_then(|v| v.get(k)).copied(), width),
            Values::From(first, v) => match c.checked_sub(first).and_then(|i| v.get(i)) {
                Some(row) => Level::of(row.get(k).copied().flatten(), width),
                None => Level::Unrecorded,
            },
        }
    }
}

/// A value as the waveform shows it: its bits (a one-bit signal's lowest only), unknown
/// (`x`), or not recorded (`z`). Equal levels are equal texts, so a change is found without
/// formatting the value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Level {
    Bits(u64),
    Unknown,
    Unrecorded,
}

impl Level {
    fn of(v: Option<u64>, width: u32) -> Level {
        match v {
            Some(b) if width == 1 => Level::Bits(b & 1),
            Some(b) => Level::Bits(b),
            None => Level::Unknown,
        }
    }

    /// Writes the value change of a `width`-bit signal `id` to this level: `1!`, `b0101 !`,
    /// `x!`, `bz !` (binary digits down to the width, more where the bits reach higher).
    fn write(self, w: &mut impl Write, width: u32, id: &IdCode) -> std::io::Result<()> {
        match (self, width) {
            (Level::Bits(b), 1) => w.write_all(&[b'0' + b as u8])?,
            (Level::Unknown, 1) => w.write_all(b"x")?,
            (Level::Unrecorded, 1) => w.write_all(b"z")?,
            (Level::Bits(b), _) => {
                // `b`, the zeros above a 64-bit value's bits (a wider signal), the bits, ` `.
                let digits = width.max(64 - b.leading_zeros()).max(1) as usize;
                let low = digits.min(64);
                let mut text = [0u8; 64];
                crate::vcd_text::binary_digits(&mut text[..low], b);
                w.write_all(b"b")?;
                for _ in low..digits {
                    w.write_all(b"0")?;
                }
                w.write_all(&text[..low])?;
                w.write_all(b" ")?;
            }
            (Level::Unknown, _) => w.write_all(b"bx ")?,
            (Level::Unrecorded, _) => w.write_all(b"bz ")?,
        }
        writeln!(w, "{id}")
    }
}

/// Writes `path` (and its `.gtkw`): `model[c][k]` and `rtl[c][k]` are port `k`'s values in
/// cycle `c` (`None`: unknown, written as `x`); one cycle per 10 ns. `differs(c, k)` raises
/// port `k`'s mismatch flag in cycle `c` (the comparison's own rule: a port compared only when
/// valid, or under a mask, is flagged only where it counts).
pub fn write(
    path: &Path,
    title: &str,
    ports: &[PortDef],
    model: &[Vec<u64>],
    rtl: &[Vec<Option<u64>>],
    differs: &dyn Fn(usize, usize) -> bool,
    shown: &[Shown],
) -> Result<(), String> {
    let err = |e: std::io::Error| format!("{}: {e}", path.display());
    let out = crate::output::Staged::new(path);
    let f = out.create().map_err(|e| e.to_string())?;
    let mut w = vcd::Writer::new(BufWriter::new(f));
    let (ids, shown_ids) = header(&mut w, title, ports, shown).map_err(err)?;
    let mut last: Vec<Option<Level>> = vec![None; ids.len()];
    let mut first = None;
    let mut differed = vec![false; ports.len()];
    let mut last_shown: Vec<Vec<Option<Level>>> =
        shown.iter().map(|s| vec![None; s.signals.len()]).collect();
    for (c, (m, r)) in model.iter().zip(rtl).enumerate() {
        w.timestamp(c as u64 * PERIOD).map_err(err)?;
        if c == 0 {
            w.begin(vcd::SimulationCommand::Dumpvars).map_err(err)?;
        }
        for (k, &(_, width, _)) in ports.iter().enumerate() {
            let flag = differs(c, k);
            first = first.or(flag.then_some(c as u64));
            differed[k] |= flag;
            let vals = [Some(m[k]), r[k], Some(u64::from(flag))];
            for (j, v) in vals.into_iter().enumerate() {
                let wd = if j == 2 { 1 } else { width };
                let (level, slot) = (Level::of(v, wd), 3 * k + j);
                if last[slot] != Some(level) {
                    level.write(w.writer(), wd, &ids[slot]).map_err(err)?;
                    last[slot] = Some(level);
                }
            }
        }
        for (i, sh) in shown
            .iter()
            .enumerate()
            .filter(|(_, sh)| sh.values.may_change(c))
        {
            for (k, &(_, width, _)) in sh.signals.iter().enumerate() {
                let level = sh.values.level(c, k, width);
                if last_shown[i][k] != Some(level) {
                    level
                        .write(w.writer(), width, &shown_ids[i][k])
                        .map_err(err)?;
                    last_shown[i][k] = Some(level);
                }
            }
        }
        if c == 0 {
            w.end().map_err(err)?;
        }
    }
    w.timestamp(model.len() as u64 * PERIOD).map_err(err)?;
    w.flush().map_err(err)?;
    drop(w);
    let beside = out.is_file();
    out.commit().map_err(|e| e.to_string())?;
    if !beside {
        return Ok(());
    }
    let end = model.len() as u64 * PERIOD;
    let active = match shown.first() {
        Some(s) if s.signals.first().map(|p| p.0) == Some("rst") => match s.values {
            Values::Every(v) => out_of_reset(v),
            Values::From(..) => 0,
        },
        _ => 0,
    };
    let view = gtkw::View::whole(0, end, PERIOD).opening(active * PERIOD);
    let view = match first {
        Some(c) => view.around(c * PERIOD, "first mismatch"),
        None => view,
    };
    // At a difference, the ports that never differ are closed: the view opens on those that
    // do, and what is below them.
    let closed: Vec<&str> = match first {
        Some(_) => (ports.iter().zip(&differed))
            .filter(|(_, d)| !**d)
            .map(|(p, _)| p.0)
            .collect(),
        None => Vec::new(),
    };
    gtkw(path, title, (ports, &closed), shown, view)
}

/// The clock period of a comparison's waveform (10 ns).
const PERIOD: u64 = 10_000;

/// The first cycle whose first shown value (a shown `rst`) is 0: where activity starts.
fn out_of_reset(values: &[Vec<u64>]) -> u64 {
    values
        .iter()
        .position(|v| v.first() == Some(&0))
        .unwrap_or(0) as u64
}

/// The ids of the compared ports (model, RTL, mismatch of each) and of each shown scope's.
type Ids = (Vec<IdCode>, Vec<Vec<IdCode>>);

fn var<W: Write>(w: &mut vcd::Writer<W>, name: &str, width: u32) -> std::io::Result<IdCode> {
    let idx = (width > 1).then(|| vcd::ReferenceIndex::Range(width as i32 - 1, 0));
    w.add_var(vcd::VarType::Wire, width, name, idx)
}

fn header<W: Write>(
    w: &mut vcd::Writer<W>,
    title: &str,
    ports: &[PortDef],
    shown: &[Shown],
) -> std::io::Result<Ids> {
    w.comment(&format!("texrtl cosim: {title}"))?;
    w.timescale(1, TimescaleUnit::PS)?;
    w.add_module("tb")?;
    let mut ids = vec![IdCode::FIRST; 3 * ports.len()];
    for (j, scope) in ["model", "rtl", "mismatch"].into_iter().enumerate() {
        w.add_module(scope)?;
        for (k, &(name, width, _)) in ports.iter().enumerate() {
            ids[3 * k + j] = var(w, name, if j == 2 { 1 } else { width })?;
        }
        w.upscope()?;
    }
    let mut shown_ids = Vec::new();
    for sh in shown {
        w.add_module(sh.scope)?;
        shown_ids.push(nested_vars(w, sh.signals)?);
        w.upscope()?;
    }
    w.upscope()?;
    w.enddefinitions()?;
    Ok((ids, shown_ids))
}

/// A `width`-bit trace of the save file: `path` with its range (vectors in decimal, signed
/// ones in signed decimal, bits in binary), under `alias` when one is given (`+{u0 model} `).
fn trace(alias: &str, path: &str, (width, signed): (u32, bool)) -> Item {
    let (range, style) = match (width, signed) {
        (1, _) => (String::new(), Style::Bin),
        (w, false) => (format!("[{}:0]", w - 1), Style::Dec),
        (w, true) => (format!("[{}:0]", w - 1), Style::SignedDec),
    };
    Item::Trace {
        name: format!("{alias}{path}{range}"),
        style,
        filter: None,
    }
}

/// The variables of `signals` in the current scope, each dotted name (`u_stage.acc`) in
/// scopes of its own (`u_stage`); a scope's signals are together, as a simulator lists them.
fn nested_vars<W: Write>(
    w: &mut vcd::Writer<W>,
    signals: &[PortDef],
) -> std::io::Result<Vec<IdCode>> {
    let mut open: Vec<&str> = Vec::new();
    let mut ids = Vec::with_capacity(signals.len());
    for &(name, width, _) in signals {
        let mut path: Vec<&str> = name.split('.').collect();
        let leaf = path.pop().unwrap_or(name);
        let same = open.iter().zip(&path).take_while(|(a, b)| a == b).count();
        for _ in same..open.len() {
            w.upscope()?;
        }
        open.truncate(same);
        for s in &path[same..] {
            w.add_module(s)?;
            open.push(s);
        }
        ids.push(var(w, leaf, width)?);
    }
    for _ in &open {
        w.upscope()?;
    }
    Ok(ids)
}

/// A shown scope's group in the view: its own signals (those of its nested scopes are in
/// the tree), each with named values by name through a filter file written beside `vcd`.
fn shown_group(g: &mut Gtkw, vcd: &Path, sh: &Shown) -> Result<(), String> {
    g.begin_group(sh.scope, "tb");
    for (k, &(name, width, signed)) in sh.signals.iter().enumerate() {
        if name.contains('.') {
            continue;
        }
        let mut item = trace("", &format!("tb.{}.{name}", sh.scope), (width, signed));
        if let (Some((_, names)), Item::Trace { style, filter, .. }) =
            (sh.states.iter().find(|(i, _)| *i == k), &mut item)
        {
            let stem = vcd.file_stem().unwrap_or_default().to_string_lossy();
            let file = vcd.with_file_name(format!("{stem}.{}.{name}.txt", sh.scope));
            crate::vcd_trace::write_filter(&file, names)
                .map_err(|e| format!("{}: {e}", file.display()))?;
            (*style, *filter) = (Style::Named, Some(file));
        }
        g.push(item);
    }
    g.end_group();
    Ok(())
}

fn gtkw(
    vcd: &Path,
    title: &str,
    (ports, closed): (&[PortDef], &[&str]),
    shown: &[Shown],
    view: gtkw::View,
) -> Result<(), String> {
    let mut g = Gtkw::new(vcd);
    g.set_view(view);
    g.treeopen("tb");
    // Scopes of every cycle (inputs, probes) above the ports; a window (around a
    // difference) below them.
    let window = |sh: &&Shown| matches!(sh.values, Values::From(..));
    for sh in shown.iter().filter(|sh| !window(sh)) {
        shown_group(&mut g, vcd, sh)?;
    }
    for &(name, width, signed) in ports {
        g.begin_group(name, "tb");
        if closed.contains(&name) {
            g.close_group(name);
        }
        // Each trace under an alias (`+{u0 model}`): GTKWave shows leaf names, the same in
        // both scopes.
        for (scope, label) in [("model", "model"), ("rtl", "RTL")] {
            let alias = format!("+{{{name} {label}}} ");
            g.push(trace(
                &alias,
                &format!("tb.{scope}.{name}"),
                (width, signed),
            ));
        }
        g.push(Item::Trace {
            name: format!("+{{{name} mismatch}} tb.mismatch.{name}"),
            style: Style::Bin,
            filter: None,
        });
        g.end_group();
    }
    for sh in shown.iter().filter(window) {
        shown_group(&mut g, vcd, sh)?;
    }
    g.write(&format!("cosim {title}"))
        .map_err(|e| format!("{}: {e}", g.path().display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value change's text as VCD writes it, from `format!`: what [`Level::write`] must write
    /// byte for byte without formatting.
    fn expected(l: Level, width: u32) -> String {
        match (l, width) {
            (Level::Bits(b), 1) => format!("{}", b & 1),
            (Level::Unknown, 1) => "x".into(),
            (Level::Unrecorded, 1) => "z".into(),
            (Level::Bits(b), w) => format!("b{b:0w$b} ", w = w as usize),
            (Level::Unknown, _) => "bx ".into(),
            (Level::Unrecorded, _) => "bz ".into(),
        }
    }

    /// Every width from 1 to 80 bits (wider than a value's 64) with values at the edges of
    /// the width and beyond it, unknown and unrecorded: the same text, then the id.
    #[test]
    fn a_value_change_is_written_as_format_writes_it() {
        let id = IdCode::from(7u32);
        for width in 1..=80u32 {
            let top = if width >= 64 {
                u64::MAX
            } else {
                (1 << width) - 1
            };
            let values = [
                0,
                1,
                2,
                top,
                top >> 1,
                top.wrapping_add(1),
                u64::MAX,
                0x5a5a,
            ];
            let levels = values
                .iter()
                .map(|&v| Level::of(Some(v), width))
                .chain([Level::Unknown, Level::Unrecorded]);
            for l in levels {
                let mut got = Vec::new();
                l.write(&mut got, width, &id).unwrap();
                let want = format!("{}{id}\n", expected(l, width));
                assert_eq!(String::from_utf8(got).unwrap(), want, "{l:?}, {width} bits");
            }
        }
    }
}
