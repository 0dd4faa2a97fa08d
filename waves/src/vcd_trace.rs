//! A VCD tracer for the kernel's [`Sim`](hdl::kernel::Sim), written with the `vcd` crate.

use crate::glob::glob_match;
use crate::gtkw::{Gtkw, Item, Style, View};
use crate::output::Staged;
use crate::vcd_writer::{Batch, Code, Rec, WriterThread, BATCH};
use hdl::fx::Format;
use hdl::kernel::{Dir, Module, Signal, Trace, Visitor};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vcd::{IdCode, ReferenceIndex, TimescaleUnit, VarType};

/// The scope every trace starts with; the DUT's instance is inside it, beside `clk`, `rst` and
/// the testbench's probes.
pub const ROOT: &str = "tb";

/// The scope of the testbench's probes, inside [`ROOT`].
const PROBES: &str = "golden";

/// How many of the design's signals (and their `real` companions) a VCD written by
/// [`VcdTracer`] declares: its variables below [`ROOT`] but for `clk`, `rst` and the
/// testbench's probes. Zero when the trace filters matched nothing. Reads the header only.
pub fn design_variables(path: &Path) -> io::Result<usize> {
    use vcd::ScopeItem;
    fn count(items: &[ScopeItem]) -> usize {
        let one = |i: &ScopeItem| match i {
            ScopeItem::Var(_) => 1,
            ScopeItem::Scope(s) => count(&s.items),
            _ => 0,
        };
        items.iter().map(one).sum()
    }
    let header = vcd::Parser::new(io::BufReader::new(File::open(path)?)).parse_header()?;
    let below = |i: &ScopeItem| match i {
        ScopeItem::Scope(s) if s.identifier != PROBES => count(&s.items),
        _ => 0,
    };
    let root = |i: &ScopeItem| match i {
        ScopeItem::Scope(s) if s.identifier == ROOT => s.items.iter().map(below).sum(),
        _ => 0,
    };
    Ok(header.items.iter().map(root).sum())
}

/// What to trace and how.
#[derive(Clone, Debug)]
pub struct TraceConfig {
    /// Clock period in picoseconds (the VCD timescale is 1 ps). Default 10 000 (100 MHz).
    pub period_ps: u64,
    /// Deepest scope traced: 0 = only `tb` (clock, reset, probes), 1 = the DUT's own ports and
    /// registers, 2 = its children's, ... `None` = everything.
    pub max_depth: Option<usize>,
    /// Glob patterns (`*` any run, `?` one character) on hierarchical names such as
    /// `tb.blend_adjust_153.u0`; a signal is traced if any pattern matches. Empty = every signal.
    pub filters: Vec<String>,
    /// Cycles `[start, end)` to record; `None` = the whole run.
    pub window: Option<(u64, u64)>,
    /// Add a `real` companion (`<name>_real`: the value as a number) for every numeric vector,
    /// fixed-point and integer formats, not flags or FSM states; the `.gtkw` shows the
    /// fixed-point ones as analog steps under their signal.
    pub companions: bool,
    /// Glob patterns (as in `filters`) of the vectors shown in hexadecimal; the others show as
    /// numbers (unsigned or signed decimal, by their format).
    pub hex: Vec<String>,
    /// Also write the FST beside the VCD (same name, `.fst`), directly while simulating
    /// ([`crate::FstTracer`]: the design's variables, no companions, no probes).
    pub fst: bool,
}

impl TraceConfig {
    /// The longest clock period: 1 ms (so that cycle times stay far inside the VCD's 64-bit
    /// time for any run that fits in memory).
    pub const MAX_PERIOD_PS: u64 = 1_000_000_000;

    /// Checks the period (even, 2 ps ..= 1 ms, so the clock can fall half-way) and the window.
    pub fn validate(&self) -> Result<(), String> {
        if self.period_ps < 2
            || !self.period_ps.is_multiple_of(2)
            || self.period_ps > Self::MAX_PERIOD_PS
        {
            return Err(format!(
                "clock period {} ps must be even, in 2..={}",
                self.period_ps,
                Self::MAX_PERIOD_PS
            ));
        }
        if let Some((a, b)) = self.window {
            if a >= b {
                return Err(format!("empty trace window {a}..{b}"));
            }
        }
        Ok(())
    }
}

impl TraceConfig {
    /// Whether a signal at scope depth `depth`, with hierarchical name `full`, is traced.
    pub fn keeps(&self, depth: usize, full: &str) -> bool {
        self.max_depth.is_none_or(|d| depth <= d)
            && (self.filters.is_empty() || self.filters.iter().any(|f| glob_match(f, full)))
    }
}

impl Default for TraceConfig {
    fn default() -> Self {
        TraceConfig {
            period_ps: 10_000,
            max_depth: None,
            filters: Vec::new(),
            window: None,
            companions: true,
            hex: Vec::new(),
            fst: false,
        }
    }
}

/// A value the testbench traces beside the design: the golden model's result, a scoreboard
/// flag, a transaction count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProbeId(usize);

#[derive(Clone, Copy, Debug, PartialEq)]
enum ProbeValue {
    Real(f64),
    Bits(u64),
}

struct Probe {
    name: String,
    id: IdCode,
    code: Box<[u8]>,
    width: u32,
    value: ProbeValue,
    last: Option<ProbeValue>,
    beside: Option<String>,
}

struct Entry {
    id: Option<IdCode>,
    real: Option<IdCode>,
    /// The identifier codes of `id` and `real` as written (empty when not traced).
    code: Box<[u8]>,
    real_code: Box<[u8]>,
    fmt: Format,
}

/// What sampling reads and writes of an entry, kept dense (an entry's codes and format are
/// for the header and the writer thread): the last value, whether traced, and the value
/// changes a change of it makes in the dump (two with a real companion).
#[derive(Clone, Copy)]
struct Hot {
    last: u64,
    changes: u32,
    traced: bool,
}

/// An identifier code as the VCD writes it.
fn code_of(id: IdCode) -> Box<[u8]> {
    id.to_string().into_bytes().into_boxed_slice()
}

/// Writes a VCD (and its `.gtkw`) of a simulation: every port and register of every instance
/// under its hierarchical scope, with its declared width; `$dumpvars` with every initial value;
/// afterwards only changes, at increasing timestamps.
///
/// The file is written as `NAME.vcd.partial` and renamed when the run finishes, so a failed or
/// abandoned run leaves no partial output.
pub struct VcdTracer {
    path: PathBuf,
    /// The file being written (`None` once committed).
    out: Option<Staged>,
    w: Option<vcd::Writer<BufWriter<File>>>,
    cfg: TraceConfig,
    title: String,
    entries: Vec<Entry>,
    /// The entries' sampling state, in the same order.
    hot: Vec<Hot>,
    probes: Vec<Probe>,
    clk: Option<IdCode>,
    rst: Option<IdCode>,
    rst_last: Option<bool>,
    dumped: bool,
    last_time: Option<u64>,
    /// The first time dumped and the first cycle out of reset: where the view opens.
    first_time: u64,
    active: Option<u64>,
    /// The records not yet handed to the writer thread (which formats them; see
    /// [`crate::vcd_writer`]), and the thread, from the end of the declarations until
    /// `finish`; `w` is with the thread meanwhile.
    recs: Batch,
    thread: Option<WriterThread>,
    /// The FST written beside, when the configuration asks for it.
    fst: Option<crate::FstTracer>,
    clk_code: Box<[u8]>,
    rst_code: Box<[u8]>,
    gtkw: Gtkw,
    /// Translate filter files (FSM state names) the `.gtkw` refers to.
    filters: Vec<(PathBuf, &'static [&'static str])>,
    finished: bool,
    changes: u64,
}

fn escape(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn io_err(msg: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, msg)
}

impl VcdTracer {
    /// A tracer that will write `path` (a `.vcd`) and, beside it, the same name with `.gtkw`.
    pub fn create(path: impl AsRef<Path>, title: &str, cfg: TraceConfig) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        cfg.validate()
            .map_err(|e| io_err(format!("{}: {e}", path.display())))?;
        let out = Staged::new(&path);
        let file = out.create()?;
        let fst = match cfg.fst {
            true => Some(crate::FstTracer::create(
                path.with_extension("fst"),
                cfg.clone(),
            )?),
            false => None,
        };
        Ok(VcdTracer {
            gtkw: Gtkw::new(&path),
            path,
            out: Some(out),
            w: Some(vcd::Writer::new(BufWriter::with_capacity(1 << 16, file))),
            cfg,
            title: title.to_string(),
            entries: Vec::new(),
            hot: Vec::new(),
            probes: Vec::new(),
            clk: None,
            rst: None,
            rst_last: None,
            dumped: false,
            last_time: None,
            first_time: 0,
            active: None,
            recs: Batch::new(0),
            thread: None,
            fst,
            clk_code: Box::default(),
            rst_code: Box::default(),
            filters: Vec::new(),
            finished: false,
            changes: 0,
        })
    }

    /// Declares a real-valued probe `tb.golden.NAME` (call before the simulation starts). With
    /// `beside`, the hierarchical name of a DUT signal (e.g. `tb.blend_adjust_153.u0`), the `.gtkw` shows the
    /// probe right under that signal.
    pub fn probe_real(&mut self, name: &str, beside: Option<&str>) -> ProbeId {
        self.add_probe(name, 0, ProbeValue::Real(0.0), beside)
    }

    /// Declares an integer probe `tb.golden.NAME` of `width` bits.
    pub fn probe_bits(&mut self, name: &str, width: u32, beside: Option<&str>) -> ProbeId {
        assert!((1..=64).contains(&width), "probe width {width}");
        self.add_probe(name, width, ProbeValue::Bits(0), beside)
    }

    fn add_probe(
        &mut self,
        name: &str,
        width: u32,
        v: ProbeValue,
        beside: Option<&str>,
    ) -> ProbeId {
        assert!(
            self.clk.is_none(),
            "probes must be declared before the simulation starts"
        );
        self.probes.push(Probe {
            name: escape(name),
            id: IdCode::FIRST,
            code: Box::default(),
            width,
            value: v,
            last: None,
            beside: beside.map(str::to_string),
        });
        ProbeId(self.probes.len() - 1)
    }

    /// Sets a real probe's value for the current cycle.
    pub fn set_real(&mut self, p: ProbeId, v: f64) {
        self.probes[p.0].value = ProbeValue::Real(v);
    }

    /// Sets an integer probe's value for the current cycle (must fit its width).
    pub fn set_bits(&mut self, p: ProbeId, v: u64) {
        let w = self.probes[p.0].width;
        assert!(
            w == 64 || v >> w == 0,
            "probe {} value {v} wider than {w} bits",
            self.probes[p.0].name
        );
        self.probes[p.0].value = ProbeValue::Bits(v);
    }

    /// The final VCD path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The `.gtkw` save file path.
    pub fn gtkw_path(&self) -> &Path {
        self.gtkw.path()
    }

    /// Value changes written so far (including `$dumpvars`).
    pub fn changes(&self) -> u64 {
        self.changes
    }

    /// How the writer thread writes each variable: the design's entries in visit order, then
    /// `clk`, `rst` and the probes (see [`VcdTracer::fixed_codes`]).
    fn codes(&self) -> Arc<[Code]> {
        let vars = self.entries.iter().map(|e| Code {
            code: e.code.clone(),
            width: e.fmt.width(),
            real: e.real.map(|_| (e.real_code.clone(), e.fmt)),
        });
        let bit = |code: &[u8]| Code {
            code: code.into(),
            width: 1,
            real: None,
        };
        let fixed = [bit(&self.clk_code), bit(&self.rst_code)];
        let probes = self.probes.iter().map(|p| Code {
            code: p.code.clone(),
            width: p.width,
            real: None,
        });
        vars.chain(fixed).chain(probes).collect()
    }

    /// The writer's indices of `clk`, `rst` and the first probe.
    fn fixed_codes(&self) -> (u32, u32, u32) {
        let n = self.entries.len() as u32;
        (n, n + 1, n + 2)
    }

    /// Hands the records so far to the writer thread (whose error, if it stopped, is
    /// returned; the file is then given back for `Drop` to remove).
    fn hand_over(&mut self) -> io::Result<()> {
        // No thread: it stopped on an error already reported (the simulation keeps that first
        // error); the records go nowhere, and memory stays bounded.
        let Some(t) = self.thread.take() else {
            self.recs.clear();
            return Ok(());
        };
        match t.send(std::mem::replace(&mut self.recs, Batch::new(0))) {
            Ok((t, next)) => {
                self.thread = Some(t);
                self.recs = next;
                Ok(())
            }
            // The file is closed here, and removed when the tracer is dropped.
            Err((w, e)) => {
                drop(w);
                Err(self.named(e))
            }
        }
    }

    /// `e` with the VCD's path in front (unless it names it already).
    fn named(&self, e: io::Error) -> io::Error {
        let p = self.path.display().to_string();
        if e.to_string().starts_with(&p) {
            e
        } else {
            io::Error::new(e.kind(), format!("{p}: {e}"))
        }
    }

    /// [`Trace::finish`]: the rest of the file, the rename, the view and filter files.
    fn finish_file(&mut self, cycles: u64) -> io::Result<()> {
        if self.thread.is_none() && self.w.is_none() {
            return Err(io_err(format!(
                "{}: the writer stopped on an earlier error",
                self.path.display()
            )));
        }
        if let Some(f) = self.fst.as_mut() {
            f.finish(cycles)?;
        }
        self.hand_over()?;
        if let Some(t) = self.thread.take() {
            let (w, r) = t.join();
            self.w = Some(w);
            r?;
        }
        if !self.dumped {
            // The run ended before the trace window began: every value is unknown in it.
            self.dump_unknown()?;
        }
        let end = match self.cfg.window {
            Some((a, b)) => cycles.min(b).max(a),
            None => cycles,
        };
        let t_end = end * self.cfg.period_ps;
        if self.last_time.is_none_or(|l| t_end > l) {
            self.timestamp(t_end)?;
        }
        let mut w = self.w.take().expect("tracer already finished");
        w.flush()?;
        drop(w);
        let out = self.out.take().expect("tracer already finished");
        let beside = out.is_file();
        out.commit()?;
        self.finished = true;
        if !beside {
            // A device or pipe: no view or filter files beside it.
            return Ok(());
        }
        let (lo, hi) = (self.first_time, self.last_time.unwrap_or(0));
        let active = self.active.map_or(lo, |c| c * self.cfg.period_ps);
        let view = View::whole(lo, hi, self.cfg.period_ps).opening(active);
        // A run that panicked opens on its last cycle: the panic came in the next.
        let view = match std::thread::panicking() {
            true => view.around(
                end.saturating_sub(1) * self.cfg.period_ps,
                "before the panic",
            ),
            false => view,
        };
        self.gtkw.set_view(view);
        for (path, names) in &self.filters {
            write_filter(path, names)?;
        }
        self.gtkw.write(&self.title)?;
        Ok(())
    }

    fn writer(&mut self) -> &mut vcd::Writer<BufWriter<File>> {
        self.w.as_mut().expect("tracer already finished")
    }

    fn in_window(&self, cycle: u64) -> bool {
        self.cfg.window.is_none_or(|(a, b)| cycle >= a && cycle < b)
    }

    fn timestamp(&mut self, t: u64) -> io::Result<()> {
        self.check_time(t)?;
        self.writer().timestamp(t)
    }

    /// Takes `t` as the latest time; timestamps must increase.
    fn check_time(&mut self, t: u64) -> io::Result<()> {
        if let Some(last) = self.last_time {
            if t <= last {
                return Err(io_err(format!(
                    "{}: time {t} after {last}: timestamps must increase",
                    self.path.display()
                )));
            }
        }
        self.last_time = Some(t);
        Ok(())
    }
}

/// Declares the design's scopes and variables.
struct Declare<'a> {
    t: &'a mut VcdTracer,
    scope: Vec<String>,
    /// The kinds of the modules entered.
    kinds: Vec<String>,
    err: Option<io::Error>,
}

impl Declare<'_> {
    /// The translate filter file for enumerated signal `signal` of the current module:
    /// `<dump stem>.<kind>.<signal>.txt` beside the dump (one per kind and signal, since a kind
    /// has one set of state names).
    fn filter(&mut self, signal: &str, names: &'static [&'static str]) -> PathBuf {
        let kind = self.kinds.last().map_or("tb", String::as_str);
        let stem = self
            .t
            .path
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy();
        let path = self
            .t
            .path
            .with_file_name(format!("{stem}.{kind}.{signal}.txt"));
        if !self.t.filters.iter().any(|(p, _)| *p == path) {
            self.t.filters.push((path.clone(), names));
        }
        path
    }
}

impl Visitor for Declare<'_> {
    fn enter(&mut self, instance: &str, kind: &str) {
        let name = escape(instance);
        self.kinds.push(escape(kind));
        self.scope.push(name.clone());
        let depth = self.scope.len();
        let path = self.scope.join(".");
        if self.t.cfg.max_depth.is_none_or(|d| depth <= d) {
            // The instance name, and its kind where it differs (`bilinear_65_red
            // (bilinear_65_68)`); the numbered units are named after their kind.
            let label = if name == kind {
                name.clone()
            } else {
                format!("{name} ({kind})")
            };
            self.t.gtkw.begin_group(&label, &path);
        }
        if let Err(e) = self.t.writer().add_module(&name) {
            self.err.get_or_insert(e);
        }
    }
    fn leave(&mut self) {
        let depth = self.scope.len();
        self.scope.pop();
        self.kinds.pop();
        if self.t.cfg.max_depth.is_none_or(|d| depth <= d) {
            self.t.gtkw.end_group();
        }
        if let Err(e) = self.t.writer().upscope() {
            self.err.get_or_insert(e);
        }
    }
    fn signal(&mut self, _: Dir, s: &Signal) {
        let depth = self.scope.len();
        let name = escape(s.name());
        let full = format!("{}.{}", self.scope.join("."), name);
        let keep = self.t.cfg.keeps(depth, &full);
        let fmt = s.fmt();
        let mut e = Entry {
            id: None,
            real: None,
            code: Box::default(),
            real_code: Box::default(),
            fmt,
        };
        if keep {
            let w = fmt.width();
            let idx = (w > 1).then(|| ReferenceIndex::Range(w as i32 - 1, 0));
            let r = self
                .t
                .writer()
                .add_var(VarType::Wire, w, &name, idx)
                .and_then(|id| {
                    e.id = Some(id);
                    if self.t.cfg.companions && w > 1 && s.states().is_none() {
                        e.real = Some(self.t.writer().add_var(
                            VarType::Real,
                            64,
                            &format!("{name}_real"),
                            None,
                        )?);
                    }
                    Ok(())
                });
            if let Err(err) = r {
                self.err.get_or_insert(err);
            }
            e.code = e.id.map(code_of).unwrap_or_default();
            e.real_code = e.real.map(code_of).unwrap_or_default();
            let style = if w == 1 {
                Style::Bin
            } else if self.t.cfg.hex.iter().any(|g| glob_match(g, &full)) {
                Style::Hex
            } else if fmt.is_signed() {
                Style::SignedDec
            } else {
                Style::Dec
            };
            let vname = if w > 1 {
                format!("{full}[{}:0]", w - 1)
            } else {
                full.clone()
            };
            let filter = s.states().map(|names| self.filter(s.name(), names));
            let style = if filter.is_some() {
                Style::Named
            } else {
                style
            };
            self.t.gtkw.push(Item::Trace {
                name: vname,
                style,
                filter,
            });
            // An integer's companion is in the dump (for an analog view of it, added from the
            // signal tree); the view lists fixed-point ones, whose value the raw row does not
            // show.
            if e.real.is_some() && fmt.frac() != 0 {
                self.t.gtkw.push(Item::Trace {
                    name: format!("{full}_real"),
                    style: Style::Analog,
                    filter: None,
                });
            }
        }
        self.t.entries.push(e);
    }
}

/// Collects the changes of one cycle (every value when `ALL`: a constant, so that the test
/// of every signal after the first cycle is its comparison alone) as records for the writer
/// thread; the count of value changes the dump gets (a real companion's too).
#[inline]
fn sample_changes<M: Module, const ALL: bool>(top: &M, hot: &mut [Hot], recs: &mut Batch) -> u64 {
    let (mut i, mut changes) = (0usize, 0u64);
    // The cursor in a local, written back once.
    let (buf, at) = recs.parts();
    let mut n = *at;
    top.visit_bits(&mut |bits| {
        let h = &mut hot[i];
        i += 1;
        if h.traced && (ALL || bits != h.last) {
            h.last = bits;
            buf[n] = Rec::bits(i as u32 - 1, bits);
            n += 1;
            changes += u64::from(h.changes);
        }
    });
    *at = n;
    changes
}

impl VcdTracer {
    /// `$dumpvars` with every variable unknown (`x`; reals 0) at the window's start, for a
    /// window that no cycle of the run reached: the dump stays valid and says so.
    fn dump_unknown(&mut self) -> io::Result<()> {
        let t = self.cfg.window.map_or(0, |(a, _)| a) * self.cfg.period_ps;
        self.timestamp(t)?;
        let w = self.w.as_mut().expect("tracer already finished");
        w.begin(vcd::SimulationCommand::Dumpvars)?;
        let ids = [self.clk, self.rst].into_iter().flatten().map(|id| (id, 1));
        let vars = self
            .entries
            .iter()
            .filter_map(|e| e.id.map(|id| (id, e.fmt.width())));
        let probes = self
            .probes
            .iter()
            .filter(|p| matches!(p.value, ProbeValue::Bits(_)));
        for (id, width) in ids.chain(vars).chain(probes.map(|p| (p.id, p.width))) {
            writeln!(w.writer(), "b{} {id}", "x".repeat(width as usize))?;
        }
        let reals = self.entries.iter().filter_map(|e| e.real);
        let real_probes = self
            .probes
            .iter()
            .filter(|p| matches!(p.value, ProbeValue::Real(_)));
        for id in reals.chain(real_probes.map(|p| p.id)) {
            w.change_real(id, 0.0)?;
        }
        w.end()?;
        self.dumped = true;
        Ok(())
    }
}

/// A GTKWave translate filter file: one `value name` line per state, values in decimal (the
/// traces that use it are shown in decimal).
pub(crate) fn write_filter(path: &Path, names: &[&str]) -> io::Result<()> {
    let mut text = String::from("# texrtl: state names, value in decimal\n");
    for (v, n) in names.iter().enumerate() {
        text.push_str(&format!("{v} {n}\n"));
    }
    crate::output::write_output(path, text.as_bytes())
}

impl Trace for VcdTracer {
    fn start(&mut self, top: &dyn Module) -> io::Result<()> {
        if let Some(f) = self.fst.as_mut() {
            f.start(top)?;
        }
        let title = self.title.clone();
        let w = self.writer();
        w.comment(&format!("texrtl: {title}"))?;
        w.version(concat!("texrtl ", env!("CARGO_PKG_VERSION")))?;
        w.timescale(1, TimescaleUnit::PS)?;
        w.add_module(ROOT)?;
        let clk = w.add_wire(1, "clk")?;
        let rst = w.add_wire(1, "rst")?;
        self.clk = Some(clk);
        self.rst = Some(rst);
        (self.clk_code, self.rst_code) = (code_of(clk), code_of(rst));
        self.gtkw.treeopen(ROOT);
        self.gtkw.push(Item::Trace {
            name: format!("{ROOT}.clk"),
            style: Style::Bin,
            filter: None,
        });
        self.gtkw.push(Item::Trace {
            name: format!("{ROOT}.rst"),
            style: Style::Bin,
            filter: None,
        });
        let mut d = Declare {
            t: self,
            scope: vec![ROOT.to_string()],
            kinds: Vec::new(),
            err: None,
        };
        top.visit(&mut d);
        if let Some(e) = d.err {
            return Err(e);
        }
        let hot = self.entries.iter().map(|e| Hot {
            last: 0,
            traced: e.id.is_some(),
            changes: 1 + u32::from(e.real.is_some()),
        });
        self.hot = hot.collect();
        // A cycle adds its signals' and probes' changes and at most seven more records (two
        // times, two clock edges, reset, `$dumpvars` and its `$end`).
        let probes = self.probes.len();
        self.recs = Batch::new(BATCH + self.hot.len() + probes + 7);
        if !self.probes.is_empty() {
            self.writer().add_module(PROBES)?;
            for i in 0..self.probes.len() {
                let (name, width, real) = {
                    let p = &self.probes[i];
                    (
                        p.name.clone(),
                        p.width,
                        matches!(p.value, ProbeValue::Real(_)),
                    )
                };
                let id = if real {
                    self.writer().add_var(VarType::Real, 64, &name, None)?
                } else {
                    let idx = (width > 1).then(|| ReferenceIndex::Range(width as i32 - 1, 0));
                    self.writer().add_var(VarType::Wire, width, &name, idx)?
                };
                self.probes[i].id = id;
                self.probes[i].code = code_of(id);
                let full = format!("{ROOT}.{PROBES}.{name}");
                let trace = Item::Trace {
                    name: if !real && width > 1 {
                        format!("{full}[{}:0]", width - 1)
                    } else {
                        full
                    },
                    style: match (real, width) {
                        (true, _) => Style::Analog,
                        (false, 1) => Style::Bin,
                        (false, _) => Style::Dec,
                    },
                    filter: None,
                };
                let beside = self.probes[i].beside.clone();
                self.gtkw.place(trace, beside.as_deref());
            }
            self.writer().upscope()?;
        }
        self.writer().upscope()?;
        self.writer().enddefinitions()?;
        let w = self.w.take().expect("tracer already finished");
        self.thread = Some(WriterThread::spawn(w, self.codes())?);
        Ok(())
    }

    fn sample<M: Module>(&mut self, cycle: u64, reset: bool, top: &M) -> io::Result<()> {
        if let Some(f) = self.fst.as_mut() {
            fst_sample(f, cycle, reset, top)?;
        }
        if !self.in_window(cycle) {
            return Ok(());
        }
        if self.recs.capacity() == 0 {
            return Err(self.named(io_err("a cycle sampled before the trace started".into())));
        }
        let t = cycle * self.cfg.period_ps;
        let half = t + self.cfg.period_ps / 2;
        self.check_time(t)?;
        self.check_time(half)?;
        let all = !self.dumped;
        let (clk, rst, probes) = self.fixed_codes();
        let recs = &mut self.recs;
        recs.push(Rec::time(t));
        if all {
            recs.push(Rec::text(false));
            self.first_time = t;
        }
        recs.push(Rec::bits(clk, 1));
        let mut n = 1;
        if all || self.rst_last != Some(reset) {
            recs.push(Rec::bits(rst, u64::from(reset)));
            self.rst_last = Some(reset);
            if !reset && self.active.is_none() {
                self.active = Some(cycle);
            }
            n += 1;
        }
        n += if all {
            sample_changes::<M, true>(top, &mut self.hot, recs)
        } else {
            sample_changes::<M, false>(top, &mut self.hot, recs)
        };
        for (k, p) in self.probes.iter_mut().enumerate() {
            if all || p.last != Some(p.value) {
                let i = probes + k as u32;
                recs.push(match p.value {
                    ProbeValue::Real(x) => Rec::real(i, x),
                    ProbeValue::Bits(b) => Rec::bits(i, b),
                });
                p.last = Some(p.value);
                n += 1;
            }
        }
        if all {
            recs.push(Rec::text(true));
            self.dumped = true;
        }
        self.changes += n;
        recs.push(Rec::time(half));
        recs.push(Rec::bits(clk, 0));
        if recs.len() >= BATCH {
            self.hand_over()?;
        }
        Ok(())
    }

    fn finish(&mut self, cycles: u64) -> io::Result<()> {
        self.finish_file(cycles).map_err(|e| self.named(e))
    }
}

/// The FST companion's cycle, out of line: inlined, it made the VCD tracer's own cycle slower
/// even without a companion.
#[inline(never)]
fn fst_sample<M: Module>(
    f: &mut crate::FstTracer,
    cycle: u64,
    reset: bool,
    top: &M,
) -> io::Result<()> {
    f.sample(cycle, reset, top)
}

impl Drop for VcdTracer {
    /// An unfinished trace leaves no file, but for a run that panics (a value that does not
    /// fit its signal, a failed assertion): it keeps its waveform as far as it got, with its
    /// view, since the cycles before the panic are what explain it.
    fn drop(&mut self) {
        if !self.finished && std::thread::panicking() && self.out.is_some() {
            let cycles = self.last_time.map_or(0, |t| t / self.cfg.period_ps + 1);
            if self.finish_file(cycles).is_ok() {
                return;
            }
        }
        if let Some(t) = self.thread.take() {
            drop(t.join());
        }
        if !self.finished {
            // Closes the file; dropping `out` then removes the partial file.
            self.w = None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Periods are even, 2 ps to 1 ms; windows hold a cycle.
    #[test]
    fn trace_configurations_are_checked_at_both_ends() {
        let with = |period_ps, window| TraceConfig {
            period_ps,
            window,
            ..TraceConfig::default()
        };
        let max = TraceConfig::MAX_PERIOD_PS;
        for p in [2, 4, max] {
            assert_eq!(with(p, None).validate(), Ok(()), "{p} ps");
        }
        for p in [0, 1, 3, max - 1, max + 1, max + 2] {
            let e = with(p, None).validate().unwrap_err();
            assert!(
                e.starts_with(&format!("clock period {p} ps must be even")),
                "{e}"
            );
        }
        assert_eq!(with(2, Some((3, 4))).validate(), Ok(()));
        assert_eq!(
            with(2, Some((4, 4))).validate(),
            Err("empty trace window 4..4".into())
        );
    }

    /// Probe names become VCD identifiers: letters, digits and `_` kept, the rest `_`.
    #[test]
    fn probe_names_are_escaped() {
        assert_eq!(escape("n_x.gold-1 [ref]"), "n_x_gold_1__ref_");
        assert_eq!(escape("Ab9"), "Ab9");
    }
}
