//! An FST tracer: the compact waveform written directly while simulating (no VCD first),
//! through `fst-writer`. Same hierarchy and names as [`crate::VcdTracer`] (`tb.clk`, `tb.rst`,
//! the design under `tb`), the same depth and name filters and trace window; bit-vector
//! variables only (no `real` companions, no probes), no `.gtkw`. Value changes are buffered in
//! memory and flushed into a new value-change section whenever the buffer passes
//! [`FLUSH_BYTES`], so a long run needs bounded memory.

use crate::TraceConfig;
use fst_writer::{
    FstBodyWriter, FstFileType, FstHeaderWriter, FstInfo, FstScopeType, FstSignalId, FstSignalType,
    FstVarDirection, FstVarType,
};
use hdl::kernel::{Dir, Module, Signal, Trace, Visitor};
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};

/// Buffered value changes above which a section is written out.
pub const FLUSH_BYTES: usize = 64 << 20;

type Out = BufWriter<File>;

/// One traced signal: its FST id, width and last value (in visit order; `None` = not traced).
struct Var {
    id: Option<FstSignalId>,
    width: u32,
    last: u64,
}

/// Writes an FST of a simulation; the file appears (renamed from `NAME.partial`) when the run
/// finishes.
pub struct FstTracer {
    path: PathBuf,
    tmp: PathBuf,
    cfg: TraceConfig,
    header: Option<FstHeaderWriter<Out>>,
    body: Option<FstBodyWriter<Out>>,
    vars: Vec<Var>,
    clk: Option<FstSignalId>,
    rst: Option<FstSignalId>,
    rst_last: Option<bool>,
    started: bool,
    last_time: Option<u64>,
    bits: Vec<u8>,
    /// The cycle's changes (kept between cycles: no allocation per cycle).
    pending: Vec<(FstSignalId, u32, u64)>,
}

fn fst_err(path: &Path, e: impl std::fmt::Debug) -> io::Error {
    io::Error::other(format!("{}: {e:?}", path.display()))
}

impl FstTracer {
    /// A tracer that will write `path` (a `.fst`).
    pub fn create(path: impl AsRef<Path>, cfg: TraceConfig) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        cfg.validate().map_err(|e| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{}: {e}", path.display()),
            )
        })?;
        let tmp = crate::partial_path(&path);
        let info = FstInfo {
            start_time: cfg.window.map_or(0, |(a, _)| a * cfg.period_ps),
            timescale_exponent: -12,
            version: concat!("texrtl ", env!("CARGO_PKG_VERSION")).into(),
            date: String::new(),
            file_type: FstFileType::Verilog,
        };
        let header = fst_writer::open_fst(&tmp, &info).map_err(|e| fst_err(&tmp, e))?;
        Ok(FstTracer {
            path,
            tmp,
            cfg,
            header: Some(header),
            body: None,
            vars: Vec::new(),
            clk: None,
            rst: None,
            rst_last: None,
            started: false,
            last_time: None,
            bits: Vec::with_capacity(64),
            pending: Vec::new(),
        })
    }

    fn in_window(&self, cycle: u64) -> bool {
        self.cfg.window.is_none_or(|(a, b)| cycle >= a && cycle < b)
    }

    /// A new time step (flushing a full buffer first, which fst-writer allows only here).
    fn time(&mut self, t: u64) -> io::Result<()> {
        let body = self.body.as_mut().expect("started");
        if body.size() > FLUSH_BYTES {
            body.flush().map_err(|e| fst_err(&self.tmp, e))?;
        }
        body.time_change(t).map_err(|e| fst_err(&self.tmp, e))?;
        self.last_time = Some(t);
        Ok(())
    }

    fn change(&mut self, id: FstSignalId, width: u32, bits: u64) -> io::Result<()> {
        self.bits.clear();
        crate::vcd_trace::push_binary(&mut self.bits, width, bits);
        let body = self.body.as_mut().expect("started");
        body.signal_change(id, &self.bits)
            .map_err(|e| fst_err(&self.tmp, e))
    }
}

/// Declares the design's scopes and the variables the configuration keeps.
struct Declare<'a> {
    h: &'a mut FstHeaderWriter<Out>,
    cfg: &'a TraceConfig,
    vars: &'a mut Vec<Var>,
    scope: Vec<String>,
    err: Option<String>,
}

impl Visitor for Declare<'_> {
    fn enter(&mut self, instance: &str, kind: &str) {
        self.scope.push(instance.to_string());
        if let Err(e) = self.h.scope(instance, kind, FstScopeType::Module) {
            self.err.get_or_insert(format!("{e:?}"));
        }
    }
    fn leave(&mut self) {
        self.scope.pop();
        if let Err(e) = self.h.up_scope() {
            self.err.get_or_insert(format!("{e:?}"));
        }
    }
    fn signal(&mut self, _: Dir, s: &Signal) {
        let depth = self.scope.len();
        let full = format!("{}.{}", self.scope.join("."), s.name());
        let keep = self.cfg.keeps(depth, &full);
        let width = s.fmt().width();
        let id = if keep {
            let t = FstSignalType::bit_vec(width);
            match self.h.var(
                s.name(),
                t,
                FstVarType::Wire,
                FstVarDirection::Implicit,
                None,
            ) {
                Ok(id) => Some(id),
                Err(e) => {
                    self.err.get_or_insert(format!("{e:?}"));
                    None
                }
            }
        } else {
            None
        };
        self.vars.push(Var { id, width, last: 0 });
    }
}

/// Collects the changed signals of one cycle.
struct Changes<'a> {
    vars: &'a mut [Var],
    next: usize,
    all: bool,
    out: &'a mut Vec<(FstSignalId, u32, u64)>,
}

impl Visitor for Changes<'_> {
    fn enter(&mut self, _: &str, _: &str) {}
    fn leave(&mut self) {}
    #[inline]
    fn signal(&mut self, _: Dir, s: &Signal) {
        let v = &mut self.vars[self.next];
        self.next += 1;
        let Some(id) = v.id else { return };
        let bits = s.bits();
        if self.all || bits != v.last {
            v.last = bits;
            self.out.push((id, v.width, bits));
        }
    }
}

impl Trace for FstTracer {
    fn start(&mut self, top: &dyn Module) -> io::Result<()> {
        let mut h = self.header.take().expect("started once");
        let e = |e| fst_err(&self.tmp, e);
        h.scope(crate::ROOT, "", FstScopeType::Module).map_err(e)?;
        let bit = FstSignalType::bit_vec(1);
        self.clk = Some(
            h.var(
                "clk",
                bit,
                FstVarType::Wire,
                FstVarDirection::Implicit,
                None,
            )
            .map_err(e)?,
        );
        self.rst = Some(
            h.var(
                "rst",
                bit,
                FstVarType::Wire,
                FstVarDirection::Implicit,
                None,
            )
            .map_err(e)?,
        );
        let mut d = Declare {
            h: &mut h,
            cfg: &self.cfg,
            vars: &mut self.vars,
            scope: vec![crate::ROOT.to_string()],
            err: None,
        };
        top.visit(&mut d);
        if let Some(m) = d.err {
            return Err(fst_err(&self.tmp, m));
        }
        h.up_scope().map_err(e)?;
        let mut body = h.finish().map_err(e)?;
        body.set_deduplicate(false);
        self.body = Some(body);
        Ok(())
    }

    fn sample(&mut self, cycle: u64, reset: bool, top: &dyn Module) -> io::Result<()> {
        if !self.in_window(cycle) {
            return Ok(());
        }
        let t = cycle * self.cfg.period_ps;
        self.time(t)?;
        let all = !self.started;
        self.started = true;
        let (clk, rst) = (self.clk.expect("started"), self.rst.expect("started"));
        self.change(clk, 1, 1)?;
        if all || self.rst_last != Some(reset) {
            self.change(rst, 1, u64::from(reset))?;
            self.rst_last = Some(reset);
        }
        let mut out = std::mem::take(&mut self.pending);
        out.clear();
        top.visit(&mut Changes {
            vars: &mut self.vars,
            next: 0,
            all,
            out: &mut out,
        });
        for &(id, width, bits) in &out {
            self.change(id, width, bits)?;
        }
        self.pending = out;
        self.time(t + self.cfg.period_ps / 2)?;
        self.change(clk, 1, 0)
    }

    fn finish(&mut self, cycles: u64) -> io::Result<()> {
        let end = match self.cfg.window {
            Some((a, b)) => cycles.min(b).max(a),
            None => cycles,
        } * self.cfg.period_ps;
        if self.body.is_some() && self.last_time.is_none_or(|l| end > l) {
            self.time(end)?;
        }
        if let Some(body) = self.body.take() {
            body.finish().map_err(|e| fst_err(&self.tmp, e))?;
        }
        std::fs::rename(&self.tmp, &self.path)
    }
}
