//! Reads a VCD back with an independent reader (the `wellen` crate, which the Surfer viewer
//! uses) and checks what GTKWave needs: a timescale, hierarchical scopes, every variable with
//! a value at the first timestamp (`$dumpvars`), strictly increasing timestamps, and a `.gtkw`
//! beside it that names only variables that exist, with their real widths.

use std::collections::BTreeMap;
use std::path::Path;
use wellen::{simple, SignalValue, SignalValueRef};

/// A variable as the independent reader saw it.
#[derive(Clone, Debug, PartialEq)]
pub struct VarInfo {
    /// Bits, or `None` for a real.
    pub width: Option<u32>,
    /// Every change: time and value (`b0101`-style bit string, or the real printed).
    pub changes: Vec<(u64, Value)>,
}

/// A value read back.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A vector or bit, as its binary digits (`x`/`z` kept).
    Bits(String),
    /// A `real` variable.
    Real(f64),
}

impl Value {
    /// The value as an unsigned integer (bit vectors of up to 64 bits).
    pub fn as_u64(&self) -> Option<u64> {
        match self {
            Value::Bits(b) => u64::from_str_radix(b, 2).ok(),
            Value::Real(_) => None,
        }
    }
    /// A real's value, or a vector's as an unsigned number (`None` with `x`/`z`).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Real(r) => Some(*r),
            Value::Bits(_) => None,
        }
    }
}

/// What a VCD holds, by full hierarchical name (`tb.blend_adjust_153.u0`).
#[derive(Clone, Debug)]
pub struct Readback {
    /// Timescale exponent (-12 for 1 ps).
    pub timescale_exp: Option<i8>,
    /// Every scope, by its full name.
    pub scopes: Vec<String>,
    /// Every variable by its full name, with its changes.
    pub vars: BTreeMap<String, VarInfo>,
    /// Every timestamp, in order.
    pub times: Vec<u64>,
}

impl Readback {
    /// The value of `var` at time `t` (the last change at or before it).
    pub fn value_at(&self, var: &str, t: u64) -> Option<&Value> {
        let v = self.vars.get(var)?;
        v.changes
            .iter()
            .rev()
            .find(|(ct, _)| *ct <= t)
            .map(|(_, v)| v)
    }

    /// Total value changes (including the initial values).
    pub fn total_changes(&self) -> usize {
        self.vars.values().map(|v| v.changes.len()).sum()
    }
}

/// Reads an FST with wellen and applies the same checks as [`read_vcd`] but the textual ones
/// (strictly increasing time is checked on wellen's time table).
pub fn read_fst(path: &Path) -> Result<Readback, String> {
    let rb = read_waves(path)?;
    if rb.times.windows(2).any(|w| w[1] <= w[0]) {
        return Err(format!("{}: time does not increase", path.display()));
    }
    Ok(rb)
}

/// Reads `path` with wellen and checks it (see the module docs). The error names the file.
pub fn read_vcd(path: &Path) -> Result<Readback, String> {
    let err = |m: String| format!("{}: {m}", path.display());
    // Timestamps must increase strictly: checked on the text, since readers may merge.
    let text = std::fs::read_to_string(path).map_err(|e| err(e.to_string()))?;
    let mut last: Option<u64> = None;
    let mut saw_dumpvars = false;
    for line in text.lines() {
        if let Some(t) = line.strip_prefix('#') {
            let t: u64 = t
                .trim()
                .parse()
                .map_err(|_| err(format!("bad timestamp '{line}'")))?;
            if last.is_some_and(|l| t <= l) {
                return Err(err(format!("timestamp {t} does not increase")));
            }
            last = Some(t);
        } else if line.starts_with("$dumpvars") {
            saw_dumpvars = true;
        }
    }
    if !saw_dumpvars {
        return Err(err("no $dumpvars block".into()));
    }
    read_waves(path)
}

/// The dump's time step as a power of ten of seconds (`10 ps`: -11), if it states one.
pub(crate) fn timescale_exp(h: &wellen::Hierarchy) -> Option<i8> {
    h.timescale().and_then(|t| {
        t.unit
            .to_exponent()
            .map(|e| e + (t.factor as f64).log10() as i8)
    })
}

/// The format-independent part: hierarchy, widths, initial values, every change.
fn read_waves(path: &Path) -> Result<Readback, String> {
    let err = |m: String| format!("{}: {m}", path.display());
    let mut w = simple::read(path).map_err(|e| err(format!("wellen: {e}")))?;
    let h = w.hierarchy();
    let timescale_exp = timescale_exp(h);
    if timescale_exp.is_none() {
        return Err(err("no $timescale".into()));
    }
    let scopes: Vec<String> = h.all_scopes().map(|s| h[s].full_name(h)).collect();
    let vars: Vec<(String, Option<u32>, wellen::SignalRef)> = h
        .all_vars()
        .map(|v| {
            let var = &h[v];
            (var.full_name(h), var.length(h), var.signal_ref())
        })
        .collect();
    let refs: Vec<_> = vars.iter().map(|v| v.2).collect();
    w.load_signals(&refs);
    let times = w.time_table().to_vec();
    let first = *times.first().ok_or_else(|| err("no timestamps".into()))?;
    let mut out = BTreeMap::new();
    for (name, width, r) in vars {
        let sig = w
            .get_signal(r)
            .ok_or_else(|| err(format!("{name} not loaded")))?;
        let mut changes = Vec::new();
        for (ti, v) in sig.iter_changes() {
            let t = times[ti as usize];
            let v: SignalValue = v.into();
            let v = match SignalValueRef::from(&v) {
                SignalValueRef::Real(r) => Value::Real(r),
                other => Value::Bits(
                    other
                        .to_bit_string()
                        .ok_or_else(|| err(format!("{name}: unsupported value")))?,
                ),
            };
            if let (Value::Bits(b), Some(wd)) = (&v, width) {
                if b.len() as u32 != wd {
                    return Err(err(format!("{name}: value {b} is not {wd} bits")));
                }
            }
            changes.push((t, v));
        }
        if changes.first().is_none_or(|c| c.0 != first) {
            return Err(err(format!("{name} has no initial value at time {first}")));
        }
        let real = changes.iter().any(|c| matches!(c.1, Value::Real(_)));
        out.insert(
            name,
            VarInfo {
                width: if real { None } else { width },
                changes,
            },
        );
    }
    Ok(Readback {
        timescale_exp,
        scopes,
        vars: out,
        times,
    })
}

/// Checks a `^N /path` translate-filter line: a slot number and a readable file of
/// `value name` lines (comments `#`).
fn check_filter(line: &str, dir: &Path) -> Result<(), String> {
    let (slot, path) = line
        .split_once(' ')
        .ok_or_else(|| format!("bad filter line ^{line}"))?;
    slot.parse::<u32>()
        .map_err(|_| format!("bad filter slot in ^{line}"))?;
    // A relative name is GTKWave's: against the save file's folder.
    let text =
        std::fs::read_to_string(dir.join(path)).map_err(|e| format!("filter file {path}: {e}"))?;
    for l in text
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
    {
        // Trimmed, a line with a space has a name after it.
        let (v, _) = l
            .trim()
            .split_once(' ')
            .ok_or_else(|| format!("filter file {path}: '{l}' is not 'value name'"))?;
        v.parse::<u64>()
            .map_err(|_| format!("filter file {path}: '{v}' is not a decimal value"))?;
    }
    Ok(())
}

/// The view a save file opens on starts inside its dump and is no wider than the dump (or
/// the ten time units GTKWave shows at least); its marker is inside the dump.
fn check_view(text: &str) -> Result<(), String> {
    let v = crate::gtkw::View::parse(text).ok_or("no view (dump range, [timestart], zoom)")?;
    let (lo, hi) = v.dump;
    let (a, b) = v.window;
    // The zoom's six decimals round the window's width by a few parts in a million.
    let widest = (hi - lo).max(10) + (hi - lo) / 1000 + 1;
    if a < lo || a > hi || b - a > widest {
        return Err(format!("the view {a}..{b} leaves the dump {lo}..{hi}"));
    }
    match v.marker {
        Some((t, _)) if t < lo || t > hi => Err(format!("marker at {t} outside the dump")),
        _ => Ok(()),
    }
}

/// Checks the `.gtkw` beside `vcd`: it exists, names this dump, its view and marker lie in
/// the dump, every trace it lists exists
/// in `rb` with the width in its `[msb:lsb]` suffix, and every translate filter file it
/// names is there and well formed. Returns the number of traces.
pub fn check_gtkw(vcd: &Path, rb: &Readback) -> Result<usize, String> {
    let g = vcd.with_extension("gtkw");
    let err = |m: String| format!("{}: {m}", g.display());
    let text = std::fs::read_to_string(&g).map_err(|e| err(e.to_string()))?;
    let name = vcd.file_name().unwrap_or_default().to_string_lossy();
    let opens = text.lines().any(|l| {
        l.strip_prefix("[dumpfile] \"")
            .and_then(|r| r.strip_suffix('"'))
            .is_some_and(|p| Path::new(p).file_name() == vcd.file_name())
    });
    if !opens {
        return Err(err(format!("does not open {name}")));
    }
    check_view(&text).map_err(err)?;
    let mut n = 0;
    let mut depth = 0i32;
    let mut last_flags = "";
    for line in text.lines() {
        if let Some(f) = line.strip_prefix('@') {
            last_flags = f;
            continue;
        }
        if let Some(f) = line.strip_prefix('^') {
            check_filter(f, g.parent().unwrap_or(Path::new("."))).map_err(err)?;
            continue;
        }
        if line.starts_with('-') {
            // GTKWave's flags: a group's begin 0x800000, its end 0x1000000 (0x400000 closed).
            let flags = u32::from_str_radix(last_flags, 16).unwrap_or(0);
            if flags & 0x80_0000 != 0 {
                depth += 1;
            } else if flags & 0x100_0000 != 0 {
                depth -= 1;
            }
            if depth < 0 {
                return Err(err("group closed twice".into()));
            }
            continue;
        }
        if line.is_empty() || line.starts_with('[') || line.starts_with('*') {
            continue;
        }
        // A trace shown under an alias: `+{alias} name`.
        let line = match line.strip_prefix("+{").and_then(|r| r.split_once("} ")) {
            Some((_, name)) => name,
            None => line,
        };
        let (base, width) = match line.split_once('[') {
            Some((b, r)) => {
                let r = r.trim_end_matches(']');
                let (msb, lsb) = r
                    .split_once(':')
                    .ok_or_else(|| err(format!("bad range in {line}")))?;
                let msb: u32 = msb
                    .parse()
                    .map_err(|_| err(format!("bad range in {line}")))?;
                let lsb: u32 = lsb
                    .parse()
                    .map_err(|_| err(format!("bad range in {line}")))?;
                let bits = msb.checked_sub(lsb).and_then(|d| d.checked_add(1));
                (
                    b,
                    Some(bits.ok_or_else(|| err(format!("bad range in {line}")))?),
                )
            }
            None => (line, None),
        };
        let v = rb
            .vars
            .get(base)
            .ok_or_else(|| err(format!("trace {base} is not in the dump")))?;
        if let Some(wd) = width {
            if v.width != Some(wd) {
                return Err(err(format!(
                    "trace {line}: the dump says {:?} bits",
                    v.width
                )));
            }
        }
        n += 1;
    }
    if depth != 0 {
        return Err(err("unbalanced groups".into()));
    }
    Ok(n)
}
