//! GTKWave save files (`.gtkw`) that open a trace with the signals grouped per unit.
//!
//! Trace flags (hex, from GTKWave's save-file format): binary 0x8, hex 0x2, decimal 0x4,
//! signed 0x400, right-justify 0x20, translate filter file 0x2000, analog step 0x8000, real
//! 0x40000, blank/comment 0x200, group begin 0x800000, group end 0x1000000. A trace shown
//! through a translate filter file (the names of an FSM's states) is preceded by a line
//! `^N /path/to/filter`, which loads that file into GTKWave's filter slot N.

use std::io;
use std::path::{Path, PathBuf};

/// How a trace is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// One-bit signals: binary.
    Bin,
    /// Unsigned vectors: hexadecimal.
    Hex,
    /// Signed vectors: signed decimal (the raw two's complement integer).
    SignedDec,
    /// Real values (fixed-point companions, golden values): analog step waveform.
    Analog,
    /// Enumerated values (FSM states): decimal, translated to names by a filter file.
    Named,
}

impl Style {
    /// The `@` flags line.
    pub fn flags(self) -> u32 {
        const RJUSTIFY: u32 = 0x20;
        match self {
            Style::Bin => 0x8 | RJUSTIFY,
            Style::Hex => 0x2 | RJUSTIFY,
            Style::SignedDec => 0x4 | 0x400 | RJUSTIFY,
            Style::Analog => 0x8000 | 0x40000 | RJUSTIFY,
            Style::Named => 0x2000 | 0x4 | RJUSTIFY,
        }
    }
}

/// One line group of a save file.
// Each variant's line names its fields.
#[allow(missing_docs)]
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A signal; `filter` is the translate filter file of a [`Style::Named`] one.
    Trace {
        name: String,
        style: Style,
        filter: Option<PathBuf>,
    },
    /// The start of a named group.
    GroupBegin(String),
    /// Its end.
    GroupEnd(String),
}

/// A save file being assembled.
#[derive(Clone, Debug)]
pub struct Gtkw {
    path: PathBuf,
    dumpfile: String,
    items: Vec<Item>,
    open: Vec<String>,
    tree: Vec<String>,
    end_time: u64,
}

/// The trace name without a `[msb:lsb]` suffix.
fn base(name: &str) -> &str {
    name.split_once('[').map_or(name, |(b, _)| b)
}

impl Gtkw {
    /// The save file for the dump at `vcd` (same name, `.gtkw`).
    ///
    /// GTKWave 3.3 resolves a relative `[dumpfile]` against its working directory, not the save
    /// file's, so both paths are written absolute; when the pair is moved together, GTKWave
    /// finds the dump through the `[savefile]` line, and `gtkwave X.vcd X.gtkw` always works.
    pub fn new(vcd: &Path) -> Gtkw {
        let abs = std::path::absolute(vcd).unwrap_or_else(|_| vcd.to_path_buf());
        Gtkw {
            path: vcd.with_extension("gtkw"),
            dumpfile: abs.to_string_lossy().into_owned(),
            items: Vec::new(),
            open: Vec::new(),
            tree: Vec::new(),
            end_time: 0,
        }
    }

    /// Where the save file goes.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The dump's last timestamp: the view opens zoomed to show all of it.
    pub fn set_end_time(&mut self, t: u64) {
        self.end_time = t;
    }

    /// Expands scope `path` in the signal tree.
    pub fn treeopen(&mut self, path: &str) {
        self.tree.push(path.to_string());
    }

    /// Opens a group (and expands its scope in the tree).
    pub fn begin_group(&mut self, label: &str, scope: &str) {
        self.items.push(Item::GroupBegin(label.to_string()));
        self.open.push(label.to_string());
        self.treeopen(scope);
    }

    /// Closes the innermost group.
    pub fn end_group(&mut self) {
        let label = self.open.pop().expect("no open group");
        self.items.push(Item::GroupEnd(label));
    }

    /// Adds a trace, blank or group line.
    pub fn push(&mut self, item: Item) {
        self.items.push(item);
    }

    /// Adds `trace` right after the trace named `beside` (and its `_real` companion), or at the
    /// end in a group "golden" when there is no such trace.
    pub fn place(&mut self, trace: Item, beside: Option<&str>) {
        let pos = beside.and_then(|b| {
            let i = self.items.iter().position(|it| matches!(it, Item::Trace { name, .. } if base(name) == b))?;
            let companion = format!("{b}_real");
            let next_is_companion = matches!(self.items.get(i + 1), Some(Item::Trace { name, .. }) if *name == companion);
            Some(i + 1 + usize::from(next_is_companion))
        });
        match pos {
            Some(p) => self.items.insert(p, trace),
            None => {
                let g = "golden".to_string();
                let end = Item::GroupEnd(g.clone());
                if self.items.last() == Some(&end) {
                    let n = self.items.len();
                    self.items.insert(n - 1, trace);
                } else {
                    self.items.push(Item::GroupBegin(g));
                    self.items.push(trace);
                    self.items.push(end);
                }
            }
        }
    }

    /// The save file's text.
    pub fn render(&self, title: &str) -> String {
        let mut s = String::new();
        s.push_str(&format!("[*] texrtl: {title}\n"));
        s.push_str(&format!("[dumpfile] \"{}\"\n", self.dumpfile));
        let save = std::path::absolute(&self.path).unwrap_or_else(|_| self.path.clone());
        s.push_str(&format!("[savefile] \"{}\"\n", save.display()));
        s.push_str("[timestart] 0\n[size] 1600 900\n[pos] -1 -1\n");
        // At zoom 0 GTKWave 3.3 shows about 5 time units across the wave pane and each unit of
        // zoom halves or doubles that (measured under Xvfb): fit the whole run, with a margin.
        let zoom = -((self.end_time.max(10) as f64) * 1.05 / 5.0).log2();
        s.push_str(&format!("*{zoom:.6} 0\n"));
        s.push_str(
            "[sst_width] 260\n[signals_width] 300\n[sst_expanded] 1\n[sst_vpaned_height] 260\n",
        );
        for t in &self.tree {
            s.push_str(&format!("[treeopen] {t}.\n"));
        }
        let mut flags = None;
        let mut filters: Vec<&PathBuf> = Vec::new();
        for it in self.without_empty_groups() {
            match it {
                Item::Trace {
                    name,
                    style,
                    filter,
                } => {
                    if flags != Some(style.flags()) {
                        s.push_str(&format!("@{:x}\n", style.flags()));
                        flags = Some(style.flags());
                    }
                    if let Some(f) = filter {
                        // Slots 1.. in order of first use; the same file keeps its slot.
                        let slot = match filters.iter().position(|g| *g == f) {
                            Some(i) => i + 1,
                            None => {
                                filters.push(f);
                                filters.len()
                            }
                        };
                        let abs = std::path::absolute(f).unwrap_or_else(|_| f.clone());
                        s.push_str(&format!("^{slot} {}\n", abs.display()));
                    }
                    s.push_str(name);
                    s.push('\n');
                }
                Item::GroupBegin(l) => {
                    s.push_str(&format!("@800200\n-{l}\n"));
                    flags = None;
                }
                Item::GroupEnd(l) => {
                    s.push_str(&format!("@1000200\n-{l}\n"));
                    flags = None;
                }
            }
        }
        s.push_str("[pattern_trace] 1\n[pattern_trace] 0\n");
        s
    }

    /// Writes the save file (via a temporary name, so it is never left half written).
    pub fn write(&self, title: &str) -> io::Result<()> {
        crate::output::write_output(&self.path, self.render(title).as_bytes())
    }

    /// The items without the groups that hold no trace (a filtered trace leaves them): a
    /// group is kept when a trace follows its begin before its end.
    fn without_empty_groups(&self) -> Vec<&Item> {
        let mut out: Vec<&Item> = Vec::new();
        // Per open group: its index in `out` and whether a trace was seen inside it.
        let mut open: Vec<(usize, bool)> = Vec::new();
        for it in &self.items {
            match it {
                Item::GroupBegin(_) => {
                    open.push((out.len(), false));
                    out.push(it);
                }
                Item::GroupEnd(_) => match open.pop() {
                    Some((i, false)) => out.truncate(i),
                    _ => out.push(it),
                },
                Item::Trace { .. } => {
                    for g in &mut open {
                        g.1 = true;
                    }
                    out.push(it);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(name: &str, style: Style) -> Item {
        Item::Trace {
            name: name.into(),
            style,
            filter: None,
        }
    }

    fn named(name: &str, filter: &str) -> Item {
        Item::Trace {
            name: name.into(),
            style: Style::Named,
            filter: Some(filter.into()),
        }
    }

    /// The flag words of GTKWave's save-file format (module comment), each right-justified.
    #[test]
    fn styles_are_gtkwave_flag_words() {
        assert_eq!(Style::Bin.flags(), 0x28);
        assert_eq!(Style::Hex.flags(), 0x22);
        assert_eq!(Style::SignedDec.flags(), 0x424);
        assert_eq!(Style::Analog.flags(), 0x48020);
        assert_eq!(Style::Named.flags(), 0x2024);
    }

    /// A probe goes under its signal and that signal's `_real` companion; one with no such
    /// signal goes into one "golden" group at the end.
    #[test]
    fn probes_are_placed_beside_their_signal_or_in_the_golden_group() {
        let mut g = Gtkw::new(Path::new("/w/x.vcd"));
        g.begin_group("u", "tb.u");
        g.push(trace("tb.u.a[3:0]", Style::Hex));
        g.push(trace("tb.u.a_real", Style::Analog));
        g.push(trace("tb.u.b[3:0]", Style::Hex));
        g.end_group();
        g.place(trace("tb.golden.a", Style::Analog), Some("tb.u.a"));
        g.place(trace("tb.golden.b", Style::Analog), Some("tb.u.b"));
        g.place(trace("tb.golden.p", Style::Analog), None);
        g.place(trace("tb.golden.q", Style::Analog), Some("tb.u.nothing"));
        let order: Vec<String> = g
            .items
            .iter()
            .map(|it| match it {
                Item::Trace { name, .. } => name.clone(),
                Item::GroupBegin(l) => format!("+{l}"),
                Item::GroupEnd(l) => format!("-{l}"),
            })
            .collect();
        let want = "+u tb.u.a[3:0] tb.u.a_real tb.golden.a tb.u.b[3:0] tb.golden.b -u \
                    +golden tb.golden.p tb.golden.q -golden";
        assert_eq!(order.join(" "), want);
    }

    /// The whole text: header with the zoom that fits the run, the open scopes, a flags line
    /// only where the style changes, filter slots by first use, empty groups left out.
    #[test]
    fn a_save_file_renders_line_for_line() {
        let mut g = Gtkw::new(Path::new("/w/x.vcd"));
        g.set_end_time(1000);
        g.treeopen("tb");
        g.begin_group("u", "tb.u");
        g.push(trace("tb.u.a", Style::Bin));
        g.push(trace("tb.u.b", Style::Bin));
        g.push(trace("tb.u.c[7:0]", Style::Hex));
        g.push(named("tb.u.s[1:0]", "/w/s.txt"));
        g.push(named("tb.u.t[1:0]", "/w/t.txt"));
        g.push(named("tb.u.s2[1:0]", "/w/s.txt"));
        g.end_group();
        g.begin_group("empty", "tb.e");
        g.end_group();
        let want = "[*] texrtl: T\n[dumpfile] \"/w/x.vcd\"\n[savefile] \"/w/x.gtkw\"\n\
            [timestart] 0\n[size] 1600 900\n[pos] -1 -1\n*-7.714246 0\n\
            [sst_width] 260\n[signals_width] 300\n[sst_expanded] 1\n[sst_vpaned_height] 260\n\
            [treeopen] tb.\n[treeopen] tb.u.\n[treeopen] tb.e.\n\
            @800200\n-u\n@28\ntb.u.a\ntb.u.b\n@22\ntb.u.c[7:0]\n\
            @2024\n^1 /w/s.txt\ntb.u.s[1:0]\n^2 /w/t.txt\ntb.u.t[1:0]\n^1 /w/s.txt\ntb.u.s2[1:0]\n\
            @1000200\n-u\n[pattern_trace] 1\n[pattern_trace] 0\n";
        assert_eq!(g.render("T"), want);
        g.set_end_time(0);
        assert!(
            g.render("T").contains("\n*-1.070389 0\n"),
            "at least 10 units shown"
        );
    }
}
