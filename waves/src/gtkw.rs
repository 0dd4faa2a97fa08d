//! GTKWave save files (`.gtkw`) that open a trace with the signals grouped per unit.
//!
//! A save file opens on a window a person can read: the first cycles of activity after reset,
//! or the cycles around a failing run's first mismatch with GTKWave's marker A on it (named,
//! and also the primary marker, so the signal pane lists every value of that cycle). Each
//! trace's radix follows its format: binary for one bit, decimal for unsigned numbers, signed
//! decimal for signed ones, state names for an FSM, hex only where the trace configuration
//! asks for it.
//!
//! Trace flags (hex, from GTKWave's save-file format): binary 0x8, hex 0x2, decimal 0x4,
//! signed 0x400, right-justify 0x20, translate filter file 0x2000, analog step 0x8000, real
//! 0x40000, blank/comment 0x200, group begin 0x800000, group end 0x1000000. A trace shown
//! through a translate filter file (the names of an FSM's states) is preceded by a line
//! `^N filter`, which loads that file into GTKWave's filter slot N. A filter beside the save
//! file is named by its file name alone: GTKWave resolves it against the save file's folder,
//! so a copied output folder keeps its state names.

use std::io;
use std::path::{Path, PathBuf};

/// How a trace is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// One-bit signals: binary.
    Bin,
    /// Unsigned vectors: decimal.
    Dec,
    /// Unsigned vectors where asked: hexadecimal.
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
            Style::Dec => 0x4 | RJUSTIFY,
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

/// Cycles shown when a view opens on the start of activity: with the default 1600-pixel
/// window about 14 pixels a cycle, enough for a decimal value that holds for three cycles.
pub const OPENING_CYCLES: u64 = 64;
/// Cycles shown before a failing run's first mismatch (where its causes are) ...
pub const CYCLES_BEFORE: u64 = 40;
/// ... and after it.
pub const CYCLES_AFTER: u64 = 24;

/// What a save file opens on: the dump's time range, its clock, the window shown and a named
/// marker. Times are the dump's (picoseconds).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct View {
    /// First and last time in the dump.
    pub dump: (u64, u64),
    /// The clock period.
    pub period: u64,
    /// First and last time shown.
    pub window: (u64, u64),
    /// Marker A: time and name.
    pub marker: Option<(u64, String)>,
}

impl View {
    /// The whole dump `[start, end]`, clocked at `period`.
    pub fn whole(start: u64, end: u64, period: u64) -> View {
        View {
            dump: (start, end.max(start)),
            period: period.max(1),
            window: (start, end.max(start)),
            marker: None,
        }
    }

    /// Opens on [`OPENING_CYCLES`] from a couple of cycles before `active` (the first cycle
    /// out of reset), inside the dump.
    pub fn opening(mut self, active: u64) -> View {
        let (lo, hi) = self.dump;
        let start = active.saturating_sub(2 * self.period).clamp(lo, hi);
        self.window = (
            start,
            start.saturating_add(OPENING_CYCLES * self.period).min(hi),
        );
        self
    }

    /// Opens around the cycle starting at time `t`, with marker A named `name` half-way into
    /// it; a time outside the dump leaves the view as it is.
    pub fn around(mut self, t: u64, name: &str) -> View {
        let (lo, hi) = self.dump;
        if t < lo || t > hi {
            return self;
        }
        let start = t.saturating_sub(CYCLES_BEFORE * self.period).max(lo);
        let end = t.saturating_add(CYCLES_AFTER * self.period).min(hi);
        self.window = (start, end);
        self.marker = Some(((t + self.period / 2).min(hi), name.to_string()));
        self
    }

    /// The header lines: the dump's range and clock as a comment (what [`focus`] reads back),
    /// the first time shown, the zoom that fits the window and the markers.
    fn render(&self) -> String {
        let (a, b) = self.window;
        // At zoom 0 GTKWave 3.3 shows about 5 time units across the wave pane and each unit of
        // zoom halves or doubles that (measured under Xvfb): fit the window, with a margin.
        let shown = ((b - a).max(10) as f64) * 1.05;
        let zoom = -(shown / 5.0).log2();
        // GTKWave opens at time 0 instead when what it shows from `[timestart]` would pass the
        // dump's end (measured): a window at the end starts early enough to fit (1 % spare).
        let last_start = self.dump.1.saturating_sub((shown * 1.01).ceil() as u64);
        let a = a.min(last_start).max(self.dump.0);
        let mut s = format!(
            "[*] dump {} {} ps, clock period {} ps\n[timestart] {a}\n[size] 1600 900\n[pos] -1 -1\n",
            self.dump.0, self.dump.1, self.period
        );
        match &self.marker {
            Some((t, name)) => {
                s.push_str(&format!("*{zoom:.6} {t} {t}\n[markername] A{name}\n"));
            }
            None => s.push_str(&format!("*{zoom:.6} -1\n")),
        }
        s
    }

    /// Reads the view back from a save file's text (written by [`Gtkw::render`]).
    pub fn parse(text: &str) -> Option<View> {
        let mut words = text
            .lines()
            .find_map(|l| l.strip_prefix("[*] dump "))?
            .split([' ', ',']);
        let mut num = || words.find_map(|w| w.parse::<u64>().ok());
        let (lo, hi, period) = (num()?, num()?, num()?);
        let start = text.lines().find_map(|l| l.strip_prefix("[timestart] "))?;
        let start: u64 = start.trim().parse().ok()?;
        let zoom_line = text.lines().find(|l| l.starts_with('*'))?;
        let zoom: f64 = zoom_line[1..].split(' ').next()?.parse().ok()?;
        let span = (5.0 * (-zoom).exp2() / 1.05).round() as u64;
        let marker = zoom_line.split(' ').nth(2).and_then(|t| t.parse().ok());
        let name = text.lines().find_map(|l| l.strip_prefix("[markername] A"));
        Some(View {
            dump: (lo, hi),
            period,
            window: (start, start + span),
            marker: marker.map(|t| (t, name.unwrap_or("").to_string())),
        })
    }
}

/// Rewrites the view of the save file at `gtkw` (one texrtl wrote) to open around clock cycle
/// `cycle` with marker A named `name` on it: what a failing run's waveform opens on once the
/// run knows where its first mismatch is. A cycle outside the dump leaves the file alone.
pub fn focus(gtkw: &Path, cycle: u64, name: &str) -> io::Result<()> {
    let text = std::fs::read_to_string(gtkw)?;
    let bad = || {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("{}: not a texrtl save file", gtkw.display()),
        )
    };
    let view = View::parse(&text).ok_or_else(bad)?;
    let t = cycle.saturating_mul(view.period);
    if t < view.dump.0 || t > view.dump.1 {
        return Ok(());
    }
    let head = View {
        marker: None,
        ..view
    }
    .around(t, name)
    .render();
    let mut out = String::new();
    let mut placed = false;
    for line in text.lines() {
        let header = [
            "[*] dump ",
            "[timestart] ",
            "[size] ",
            "[pos] ",
            "*",
            "[markername] ",
        ];
        if header.iter().any(|h| line.starts_with(h)) {
            if !placed {
                out.push_str(&head);
                placed = true;
            }
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    crate::output::write_output(gtkw, out.as_bytes())
}

/// A save file being assembled.
#[derive(Clone, Debug)]
pub struct Gtkw {
    path: PathBuf,
    dumpfile: String,
    items: Vec<Item>,
    open: Vec<String>,
    /// Groups shown closed (their label once begun).
    closed: Vec<String>,
    tree: Vec<String>,
    view: View,
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
            closed: Vec::new(),
            tree: Vec::new(),
            view: View::whole(0, 0, 1),
        }
    }

    /// Where the save file goes.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The dump's last timestamp: the view opens zoomed to show all of it.
    pub fn set_end_time(&mut self, t: u64) {
        self.view = View::whole(0, t, 1);
    }

    /// What the save file opens on.
    pub fn set_view(&mut self, view: View) {
        self.view = view;
    }

    /// Expands scope `path` in the signal tree.
    pub fn treeopen(&mut self, path: &str) {
        // Once each: every group of a scope opens it.
        if !self.tree.iter().any(|t| t == path) {
            self.tree.push(path.to_string());
        }
    }

    /// Opens a group (and expands its scope in the tree).
    pub fn begin_group(&mut self, label: &str, scope: &str) {
        self.items.push(Item::GroupBegin(label.to_string()));
        self.open.push(label.to_string());
        self.treeopen(scope);
    }

    /// Shows the group `label` closed, its traces a click away (a group of matching ports
    /// beside one that differs).
    pub fn close_group(&mut self, label: &str) {
        self.closed.push(label.to_string());
    }

    /// Ends the innermost group.
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
        s.push_str(&self.view.render());
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
                        s.push_str(&format!("^{slot} {}\n", self.filter_name(f)));
                    }
                    s.push_str(name);
                    s.push('\n');
                }
                // GTKWave's flags: a group's begin, its end, blank; 0x400000 closed (and
                // 0x1000 collapsed on the end, as GTKWave itself writes a closed group).
                Item::GroupBegin(l) => {
                    let closed = if self.closed.contains(l) {
                        0x40_0000
                    } else {
                        0
                    };
                    s.push_str(&format!("@{:x}\n-{l}\n", 0x80_0200 | closed));
                    flags = None;
                }
                Item::GroupEnd(l) => {
                    let closed = if self.closed.contains(l) {
                        0x40_1000
                    } else {
                        0
                    };
                    s.push_str(&format!("@{:x}\n-{l}\n", 0x100_0200 | closed));
                    flags = None;
                }
            }
        }
        s.push_str("[pattern_trace] 1\n[pattern_trace] 0\n");
        s
    }

    /// How the save file names filter file `f`: its file name when it lies beside the save
    /// file, else its absolute path.
    fn filter_name(&self, f: &Path) -> String {
        let dir = |p: &Path| {
            std::path::absolute(p)
                .ok()
                .and_then(|a| a.parent().map(Path::to_path_buf))
        };
        match (dir(f), dir(&self.path), f.file_name()) {
            (Some(a), Some(b), Some(n)) if a == b => n.to_string_lossy().into_owned(),
            _ => std::path::absolute(f)
                .unwrap_or_else(|_| f.to_path_buf())
                .display()
                .to_string(),
        }
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

    /// The whole text: header with the view, the open scopes, a flags line only where the
    /// style changes, filter slots by first use (beside the save file: by file name), empty
    /// groups left out.
    #[test]
    fn a_save_file_renders_line_for_line() {
        let mut g = Gtkw::new(Path::new("/w/x.vcd"));
        g.set_view(View::whole(0, 1000, 10));
        g.treeopen("tb");
        g.begin_group("u", "tb.u");
        g.push(trace("tb.u.a", Style::Bin));
        g.push(trace("tb.u.b", Style::Bin));
        g.push(trace("tb.u.c[7:0]", Style::Dec));
        g.push(named("tb.u.s[1:0]", "/w/s.txt"));
        g.push(named("tb.u.t[1:0]", "/v/t.txt"));
        g.push(named("tb.u.s2[1:0]", "/w/s.txt"));
        g.end_group();
        g.begin_group("empty", "tb.e");
        g.end_group();
        let want = "[*] texrtl: T\n[dumpfile] \"/w/x.vcd\"\n[savefile] \"/w/x.gtkw\"\n\
            [*] dump 0 1000 ps, clock period 10 ps\n\
            [timestart] 0\n[size] 1600 900\n[pos] -1 -1\n*-7.714246 -1\n\
            [sst_width] 260\n[signals_width] 300\n[sst_expanded] 1\n[sst_vpaned_height] 260\n\
            [treeopen] tb.\n[treeopen] tb.u.\n[treeopen] tb.e.\n\
            @800200\n-u\n@28\ntb.u.a\ntb.u.b\n@24\ntb.u.c[7:0]\n\
            @2024\n^1 s.txt\ntb.u.s[1:0]\n^2 /v/t.txt\ntb.u.t[1:0]\n^1 s.txt\ntb.u.s2[1:0]\n\
            @1000200\n-u\n[pattern_trace] 1\n[pattern_trace] 0\n";
        assert_eq!(g.render("T"), want);
        g.set_end_time(0);
        assert!(
            g.render("T").contains("\n*-1.070389 -1\n"),
            "at least 10 units shown"
        );
    }

    /// A view opens on the first cycles of activity, or around a time with marker A half-way
    /// into its cycle, always inside the dump; what is rendered parses back.
    #[test]
    fn views_open_on_activity_or_around_a_mismatch_inside_the_dump() {
        let p = 100;
        let whole = View::whole(0, 100_000, p);
        let open = whole.clone().opening(500);
        assert_eq!(open.window, (300, 300 + OPENING_CYCLES * p));
        assert_eq!(whole.clone().opening(99_950).window, (99_750, 100_000));
        let at = whole.clone().around(50_000, "first mismatch");
        assert_eq!(
            at.window,
            (50_000 - CYCLES_BEFORE * p, 50_000 + CYCLES_AFTER * p)
        );
        assert_eq!(at.marker, Some((50_050, "first mismatch".to_string())));
        // Rendered, a window at the dump's end starts where what GTKWave shows of it fits
        // before the end: GTKWave opens at 0 when it would not.
        let end = whole.clone().around(99_900, "panic").render();
        let start = |r: &str| -> u64 {
            let l = r
                .lines()
                .find_map(|l| l.strip_prefix("[timestart] "))
                .unwrap();
            l.parse().unwrap()
        };
        // The window: 40 cycles before the marker's, to the end.
        let span = (100_000 - (99_900 - CYCLES_BEFORE * p)) as f64 * 1.05 * 1.01;
        assert_eq!(start(&end), 100_000 - span.ceil() as u64);
        assert!(end.contains("*-9.749869 99950 99950\n"), "{end}");
        assert_eq!(
            start(&at.render()),
            50_000 - CYCLES_BEFORE * p,
            "inside: as asked"
        );
        assert_eq!(
            whole.clone().around(1_000, "m").window.0,
            0,
            "clamped at the start"
        );
        assert_eq!(
            whole.clone().around(200_000, "m"),
            whole,
            "outside: unchanged"
        );
        for v in [open, at] {
            let back = View::parse(&v.render()).unwrap();
            assert_eq!(
                (back.dump, back.period, back.marker.clone()),
                (v.dump, v.period, v.marker.clone())
            );
            assert_eq!(back.window.0, v.window.0);
            assert!(back.window.1.abs_diff(v.window.1) <= 1, "{back:?} {v:?}");
        }
    }

    /// `focus` moves a written save file's view to a mismatch, marker and all, and keeps the
    /// rest of the file line for line; a time outside the dump leaves it alone.
    #[test]
    fn focus_rewrites_only_the_view() {
        let dir = std::env::temp_dir().join(format!("texrtl-gtkw-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut g = Gtkw::new(&dir.join("x.vcd"));
        g.set_view(View::whole(0, 1_000_000, 1000).opening(0));
        g.push(trace("tb.u.a", Style::Bin));
        g.write("T").unwrap();
        let before = std::fs::read_to_string(g.path()).unwrap();
        focus(g.path(), 2_000, "m").unwrap();
        assert_eq!(std::fs::read_to_string(g.path()).unwrap(), before);
        focus(g.path(), 500, "first mismatch").unwrap();
        let after = std::fs::read_to_string(g.path()).unwrap();
        let mut g2 = g.clone();
        g2.set_view(View::whole(0, 1_000_000, 1000).around(500_000, "first mismatch"));
        assert_eq!(after, g2.render("T"));
        assert!(
            after.contains("\n*-13.714246 500500 500500\n[markername] Afirst mismatch\n"),
            "{after}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
