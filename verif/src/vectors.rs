//! Bit-accuracy regression vectors: the bit-exact outputs of a unit for a fixed set of
//! stimuli, kept in a folder of the project (`<unit>.json`: the fields, a hash of every output
//! bit and the first rows, readable; `<unit>.rows`: every row, one line each), and their export
//! as `$readmemh` files for Verilog testbenches.
//!
//! The stimuli depend on no seed: a change of a single output bit changes the hash, and the
//! rows file names the first row that changed, by index and field. `bless` rewrites the files
//! after a deliberate change and says how many rows changed and which.

use serde::{Deserialize, Serialize};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use waves::output::write_output;

/// A named field of a vector and its width in bits (1..=64).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Field {
    /// The field's name (a port's, usually).
    pub name: String,
    /// Its width in bits, 1..=64.
    pub width: u32,
}

impl Field {
    /// A field `name` of `width` bits.
    pub fn new(name: impl Into<String>, width: u32) -> Field {
        Field {
            name: name.into(),
            width,
        }
    }
}

/// Stimulus and expected outputs of one unit, one row per transaction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnitVectors {
    /// The unit's name (the kept files').
    pub unit: String,
    /// How the stimuli are made, in a sentence (the unit's configuration, the inputs' pattern).
    pub description: String,
    /// The fields of a row's inputs.
    pub inputs: Vec<Field>,
    /// The fields of a row's outputs.
    pub outputs: Vec<Field>,
    /// Raw bit patterns (two's complement within each field's width).
    pub rows: Vec<(Vec<u64>, Vec<u64>)>,
}

/// What `<unit>.json` holds.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct VectorFile {
    /// The unit's name.
    pub unit: String,
    /// How the stimuli are made.
    pub description: String,
    /// The inputs' fields.
    pub inputs: Vec<Field>,
    /// The outputs' fields.
    pub outputs: Vec<Field>,
    /// The number of rows.
    pub count: usize,
    /// FNV-1a 64 over every field of every row, as hex.
    pub hash: String,
    /// The first rows, readable: `"inputs -> outputs"` in hex.
    pub first: Vec<String>,
}

/// How many rows the `.json` shows.
const READABLE: usize = 8;

/// A raw value of `width` bits from a signed one (two's complement, cut to the width).
pub fn mask(v: i64, width: u32) -> u64 {
    if width >= 64 {
        v as u64
    } else {
        (v as u64) & ((1u64 << width) - 1)
    }
}

/// FNV-1a 64 over every field value (little-endian bytes).
pub fn hash(v: &UnitVectors) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for (i, o) in &v.rows {
        for x in i.iter().chain(o) {
            for b in x.to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    format!("{h:016x}")
}

fn hex_row(fields: &[Field], vals: &[u64]) -> String {
    fields
        .iter()
        .zip(vals)
        .map(|(f, v)| format!("{v:0w$x}", w = (f.width as usize).div_ceil(4)))
        .collect::<Vec<_>>()
        .join("_")
}

impl UnitVectors {
    /// Row `k` as `inputs -> outputs`, each field in hex, fields joined by `_`.
    pub fn row_text(&self, k: usize) -> String {
        let (i, o) = &self.rows[k];
        format!(
            "{} -> {}",
            hex_row(&self.inputs, i),
            hex_row(&self.outputs, o)
        )
    }

    /// The `.json` file.
    pub fn file(&self) -> VectorFile {
        VectorFile {
            unit: self.unit.clone(),
            description: self.description.clone(),
            inputs: self.inputs.clone(),
            outputs: self.outputs.clone(),
            count: self.rows.len(),
            hash: hash(self),
            first: (0..self.rows.len().min(READABLE))
                .map(|k| self.row_text(k))
                .collect(),
        }
    }

    /// The `.rows` file: every row as [`UnitVectors::row_text`], one a line.
    pub fn rows_text(&self) -> String {
        let mut s = String::with_capacity(self.rows.len() * 32);
        for k in 0..self.rows.len() {
            s.push_str(&self.row_text(k));
            s.push('\n');
        }
        s
    }

    /// Row `k`'s fields that differ from the kept row text `kept`, as `name a -> b`.
    fn changed_fields(&self, k: usize, kept: &str) -> String {
        let now = self.row_text(k);
        let split = |t: &str| -> Vec<String> {
            t.split(" -> ")
                .flat_map(|h| h.split('_'))
                .map(str::to_string)
                .collect()
        };
        let (a, b) = (split(kept), split(&now));
        let names = self.inputs.iter().chain(&self.outputs).map(|f| &f.name);
        let diffs: Vec<String> = names
            .zip(a.iter().zip(&b))
            .filter(|(_, (x, y))| x != y)
            .map(|(n, (x, y))| format!("{n} {x} -> {y}"))
            .collect();
        if diffs.is_empty() || a.len() != b.len() {
            format!("{kept} => {now}")
        } else {
            diffs.join(", ")
        }
    }

    /// `$readmemh` files: `<unit>_stimulus.hex` and `<unit>_expected.hex`, each line one
    /// vector with its fields concatenated MSB first (the header names fields and widths).
    pub fn write_readmemh(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        std::fs::create_dir_all(dir)?;
        let mut out = Vec::new();
        for (kind, fields, pick) in [
            ("stimulus", &self.inputs, 0usize),
            ("expected", &self.outputs, 1),
        ] {
            let path = dir.join(format!("{}_{kind}.hex", self.unit));
            write_output(&path, self.readmemh(kind, fields, pick).as_bytes())?;
            out.push(path);
        }
        Ok(out)
    }

    fn readmemh(&self, kind: &str, fields: &[Field], pick: usize) -> String {
        let total: u32 = fields.iter().map(|f| f.width).sum();
        let mut s = String::new();
        let _ = writeln!(s, "// texrtl {} {kind}: {}", self.unit, self.description);
        let layout: Vec<String> = fields
            .iter()
            .map(|f| format!("{}[{}:0]", f.name, f.width - 1))
            .collect();
        let _ = writeln!(
            s,
            "// {} vectors of {total} bits, fields MSB first: {}",
            self.rows.len(),
            layout.join(" ")
        );
        for row in &self.rows {
            let vals = if pick == 0 { &row.0 } else { &row.1 };
            let mut word: u128 = 0;
            for (f, v) in fields.iter().zip(vals) {
                word = (word << f.width) | u128::from(*v);
            }
            let _ = writeln!(s, "{word:0w$x}", w = (total as usize).div_ceil(4));
        }
        s
    }
}

/// A unit's vectors: its name and the function that makes them.
pub type VectorsFn = dyn Fn() -> Result<UnitVectors, String> + Send + Sync;

/// The kept files of `unit` in `dir`: the `.json` (`None` when missing or unreadable) and
/// the rows (`None` when there is no `.rows` file).
fn kept(dir: &Path, unit: &str) -> Result<(Option<VectorFile>, Option<String>), String> {
    let path = dir.join(format!("{unit}.json"));
    let file = match std::fs::read(&path) {
        Ok(b) => Some(serde_json::from_slice(&b).map_err(|e| {
            let e = waves::output::escape_controls(&e.to_string());
            let e = waves::output::shorten_message(&waves::output::shorten_quoted(&e, '`'), 200);
            format!("{}: {e}", path.display())
        })?),
        Err(_) => None,
    };
    let rows = std::fs::read_to_string(dir.join(format!("{unit}.rows"))).ok();
    Ok((file, rows))
}

/// Compares every unit's vectors with the kept files; returns one line per unit that differs
/// (a missing file is a difference).
pub fn check<'a>(
    dir: &Path,
    units: impl IntoIterator<Item = (&'a str, &'a VectorsFn)>,
) -> Result<Vec<String>, String> {
    let mut diffs = Vec::new();
    for (u, make) in units {
        let now = make()?;
        let (file, rows) = kept(dir, u)?;
        let Some(file) = file else {
            diffs.push(format!(
                "{}: missing (bless to make it)",
                dir.join(format!("{u}.json")).display()
            ));
            continue;
        };
        if file != now.file() || rows.as_deref().is_some_and(|r| r != now.rows_text()) {
            diffs.push(describe(&file, rows.as_deref(), &now));
        }
    }
    Ok(diffs)
}

/// What changed between the kept files and `now`: the hash and count, how many rows changed
/// and the first of them by index and field.
fn describe(kept: &VectorFile, rows: Option<&str>, now: &UnitVectors) -> String {
    let file = now.file();
    let mut s = format!(
        "{}: hash {} -> {} ({} -> {} vectors)",
        now.unit, kept.hash, file.hash, kept.count, file.count
    );
    let kept_rows: Vec<&str> = match rows {
        Some(r) => r.lines().collect(),
        None => kept.first.iter().map(String::as_str).collect(),
    };
    let changed: Vec<usize> = (0..now.rows.len().min(kept_rows.len()))
        .filter(|&k| now.row_text(k) != kept_rows[k])
        .collect();
    if let Some(&k) = changed.first() {
        let _ = write!(
            s,
            "; {} rows changed{}, the first row {k}: {}",
            changed.len(),
            if rows.is_some() {
                ""
            } else {
                " of the first kept"
            },
            now.changed_fields(k, kept_rows[k])
        );
        let more: Vec<String> = changed
            .iter()
            .skip(1)
            .take(7)
            .map(|k| k.to_string())
            .collect();
        if !more.is_empty() {
            let _ = write!(
                s,
                "; then rows {}{}",
                more.join(", "),
                if changed.len() > 8 { ", ..." } else { "" }
            );
        }
    } else if rows.is_none() && kept.hash != file.hash {
        s.push_str("; the first readable vectors are unchanged and no .rows file is kept: bless to keep every row");
    }
    if kept.inputs != file.inputs || kept.outputs != file.outputs {
        s.push_str("; the fields changed");
    }
    s
}

/// Rewrites the kept files of every unit whose vectors changed (and the `.rows` file where it
/// is missing); returns a line per unit that changed.
pub fn bless<'a>(
    dir: &Path,
    units: impl IntoIterator<Item = (&'a str, &'a VectorsFn)>,
) -> Result<Vec<String>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut changed = Vec::new();
    for (u, make) in units {
        let now = make()?;
        let file = now.file();
        let (kept, rows) = kept(dir, u).unwrap_or((None, None));
        let rows_now = now.rows_text();
        let same_rows = rows.as_deref() == Some(rows_now.as_str());
        match &kept {
            Some(k) if *k == file && same_rows => continue,
            Some(k) if *k == file && rows.is_none() => {
                changed.push(format!(
                    "{u}: unchanged, its {} rows now kept one a line",
                    k.count
                ));
            }
            Some(k) => changed.push(describe(k, rows.as_deref(), &now)),
            None => changed.push(format!(
                "{u}: new, {} vectors, hash {}",
                file.count, file.hash
            )),
        }
        let mut json = serde_json::to_vec_pretty(&file).map_err(|e| e.to_string())?;
        json.push(b'\n');
        let err = |e: std::io::Error| e.to_string();
        write_output(&dir.join(format!("{u}.json")), &json).map_err(err)?;
        write_output(&dir.join(format!("{u}.rows")), rows_now.as_bytes()).map_err(err)?;
    }
    Ok(changed)
}
