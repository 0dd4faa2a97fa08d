//! An FST tracer: the compact waveform written directly while simulating (no VCD first),
//! with texrtl's own encoder (`fst_file`). Same hierarchy and names as [`crate::VcdTracer`]
//! (`tb.clk`, `tb.rst`, the design under `tb`), the same depth and name filters and trace
//! window; bit-vector variables only (no `real` companions, no probes), no `.gtkw`.
//!
//! The simulation only collects each cycle's changes (value and identifier, no formatting)
//! into batches of [`BATCH`] records; a writer thread encodes them, as Verilator's FST writer
//! compresses in a thread of its own. The batches pass through a channel of eight, and the
//! writer writes a new value-change section whenever the changes it holds pass
//! [`FLUSH_BYTES`], so a run of any length needs bounded memory.

use crate::fst_file::{FstBody, FstHeader};
use crate::output::Staged;
use crate::TraceConfig;
use hdl::kernel::{Dir, Module, Signal, Trace, Visitor};
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, sync_channel, Receiver, Sender, SyncSender};
use std::thread::JoinHandle;

/// Buffered value changes above which a section is written out.
pub const FLUSH_BYTES: usize = 4 << 20;

/// Records per batch handed to the writer thread.
pub const BATCH: usize = 1 << 12;

type Out = BufWriter<File>;

/// What the simulation hands the writer, in order.
#[derive(Clone, Copy)]
enum Rec {
    Time(u64),
    /// A variable's handle and its new bits.
    Change(u32, u64),
}

/// The writer thread's side: the FST body.
struct Writer {
    body: FstBody<Out>,
    /// The output as named (for messages).
    path: PathBuf,
    flush_bytes: usize,
}

impl Writer {
    /// Encodes batches until the simulation hangs up, returning each emptied batch for reuse;
    /// then finishes the file.
    fn run(mut self, batches: Receiver<Vec<Rec>>, recycle: Sender<Vec<Rec>>) -> io::Result<()> {
        for mut batch in batches {
            for &r in &batch {
                match r {
                    Rec::Time(t) => self.time(t)?,
                    Rec::Change(h, bits) => self.body.change(h, bits),
                }
            }
            batch.clear();
            let _ = recycle.send(batch);
        }
        let path = self.path;
        let mut out = self.body.finish().map_err(|e| named(&path, e))?;
        io::Write::flush(&mut out).map_err(|e| named(&path, e))
    }

    /// A new time step, a full section written out first.
    fn time(&mut self, t: u64) -> io::Result<()> {
        if self.body.size() > self.flush_bytes {
            self.body.flush().map_err(|e| named(&self.path, e))?;
        }
        self.body.time(t).map_err(|e| named(&self.path, e))
    }
}

/// The simulation's end of the writer thread.
struct WriterThread {
    batches: SyncSender<Vec<Rec>>,
    recycle: Receiver<Vec<Rec>>,
    handle: JoinHandle<io::Result<()>>,
}

impl WriterThread {
    fn spawn(w: Writer) -> io::Result<WriterThread> {
        let (batches, rx) = sync_channel(8);
        let (back, recycle) = channel();
        let handle = std::thread::Builder::new()
            .name("fst-writer".into())
            .spawn(move || w.run(rx, back))?;
        Ok(WriterThread {
            batches,
            recycle,
            handle,
        })
    }

    /// Hands over `batch`, returning an empty one; a writer that stopped reports its error.
    fn send(self, batch: Vec<Rec>) -> io::Result<(WriterThread, Vec<Rec>)> {
        if self.batches.send(batch).is_err() {
            let e = self.join().err();
            return Err(e.unwrap_or_else(|| io::Error::other("the FST writer stopped")));
        }
        let next = self
            .recycle
            .try_recv()
            .unwrap_or_else(|_| Vec::with_capacity(BATCH));
        Ok((self, next))
    }

    /// Waits for the writer to finish the file.
    fn join(self) -> io::Result<()> {
        drop(self.batches);
        self.handle
            .join()
            .unwrap_or_else(|_| Err(io::Error::other("the FST writer thread panicked")))
    }
}

/// One traced signal: its FST handle and last value (in visit order; `None` = not traced).
struct Var {
    id: Option<u32>,
    last: u64,
}

/// Writes an FST of a simulation; the file appears (renamed from `NAME.partial`) when the run
/// finishes.
pub struct FstTracer {
    path: PathBuf,
    /// The file being written (`None` once committed).
    out: Option<Staged>,
    cfg: TraceConfig,
    header: Option<FstHeader<Out>>,
    writer: Option<WriterThread>,
    vars: Vec<Var>,
    clk: Option<u32>,
    rst: Option<u32>,
    rst_last: Option<bool>,
    started: bool,
    last_time: Option<u64>,
    /// Records not yet handed to the writer.
    batch: Vec<Rec>,
    /// [`FLUSH_BYTES`] and [`BATCH`] unless a test set them ([`FstTracer::with_limits`]).
    flush_bytes: usize,
    batch_len: usize,
    changes: u64,
}

/// `e` with the file's name in front, of the same kind (a full disk stays a full disk).
fn named(path: &Path, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("{}: {e}", path.display()))
}

impl FstTracer {
    /// A tracer that will write `path` (a `.fst`); `cfg.fst` is not read.
    pub fn create(path: impl AsRef<Path>, cfg: TraceConfig) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        cfg.validate().map_err(|e| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{}: {e}", path.display()),
            )
        })?;
        let out = Staged::new(&path);
        let version = concat!("texrtl ", env!("CARGO_PKG_VERSION"));
        let header = File::create(out.write_path())
            .and_then(|f| FstHeader::new(BufWriter::new(f), -12, version))
            .map_err(|e| named(&path, e))?;
        Ok(FstTracer {
            path,
            out: Some(out),
            cfg,
            header: Some(header),
            writer: None,
            vars: Vec::new(),
            clk: None,
            rst: None,
            rst_last: None,
            started: false,
            last_time: None,
            batch: Vec::with_capacity(BATCH),
            flush_bytes: FLUSH_BYTES,
            batch_len: BATCH,
            changes: 0,
        })
    }

    /// The same tracer with other section and batch sizes (at least 1 each): tests use tiny
    /// ones to cross both boundaries many times in a short run.
    pub fn with_limits(mut self, flush_bytes: usize, batch: usize) -> Self {
        self.flush_bytes = flush_bytes.max(1);
        self.batch_len = batch.max(1);
        self
    }

    /// Value changes recorded so far (the clock's rises included, its falls not: as
    /// [`crate::VcdTracer::changes`] counts).
    pub fn changes(&self) -> u64 {
        self.changes
    }

    /// Records not yet handed to the writer thread: fewer than the batch size plus one
    /// cycle's, however long the run (the simulation's memory stays bounded).
    pub fn pending(&self) -> usize {
        self.batch.len()
    }

    fn in_window(&self, cycle: u64) -> bool {
        self.cfg.window.is_none_or(|(a, b)| cycle >= a && cycle < b)
    }

    fn time(&mut self, t: u64) {
        self.batch.push(Rec::Time(t));
        self.last_time = Some(t);
    }

    /// Hands a full batch to the writer.
    fn hand_over(&mut self) -> io::Result<()> {
        // No writer: it stopped on an error already reported (the simulation keeps that
        // first error); the records go nowhere, and memory stays bounded.
        let Some(w) = self.writer.take() else {
            self.batch.clear();
            return Ok(());
        };
        let (w, next) = w.send(std::mem::take(&mut self.batch))?;
        self.writer = Some(w);
        self.batch = next;
        Ok(())
    }
}

/// Declares the design's scopes and the variables the configuration keeps.
struct Declare<'a> {
    h: &'a mut FstHeader<Out>,
    cfg: &'a TraceConfig,
    vars: &'a mut Vec<Var>,
    scope: Vec<String>,
    err: Option<String>,
}

impl Visitor for Declare<'_> {
    fn enter(&mut self, instance: &str, kind: &str) {
        self.scope.push(instance.to_string());
        self.h.scope(instance, kind);
    }
    fn leave(&mut self) {
        self.scope.pop();
        self.h.up_scope();
    }
    fn signal(&mut self, _: Dir, s: &Signal) {
        let depth = self.scope.len();
        let full = format!("{}.{}", self.scope.join("."), s.name());
        let keep = self.cfg.keeps(depth, &full);
        let width = s.fmt().width();
        let id = if keep {
            match self.h.var(s.name(), width) {
                Ok(id) => Some(id),
                Err(e) => {
                    self.err.get_or_insert(e.to_string());
                    None
                }
            }
        } else {
            None
        };
        self.vars.push(Var { id, last: 0 });
    }
}

/// Collects the changed signals of one cycle (every one when `all`).
#[inline]
fn changes<M: Module>(top: &M, vars: &mut [Var], all: bool, out: &mut Vec<Rec>) {
    let mut next = 0;
    top.visit_bits(&mut |bits| {
        let v = &mut vars[next];
        next += 1;
        let Some(id) = v.id else { return };
        if all || bits != v.last {
            v.last = bits;
            out.push(Rec::Change(id, bits));
        }
    });
}

impl Trace for FstTracer {
    fn start(&mut self, top: &dyn Module) -> io::Result<()> {
        let mut h = self.header.take().expect("started once");
        h.scope(crate::ROOT, "");
        self.clk = Some(h.var("clk", 1)?);
        self.rst = Some(h.var("rst", 1)?);
        let mut d = Declare {
            h: &mut h,
            cfg: &self.cfg,
            vars: &mut self.vars,
            scope: vec![crate::ROOT.to_string()],
            err: None,
        };
        top.visit(&mut d);
        if let Some(m) = d.err {
            return Err(io::Error::other(format!("{}: {m}", self.path.display())));
        }
        h.up_scope();
        let body = h.finish().map_err(|e| named(&self.path, e))?;
        self.writer = Some(WriterThread::spawn(Writer {
            body,
            path: self.path.clone(),
            flush_bytes: self.flush_bytes,
        })?);
        Ok(())
    }

    fn sample<M: Module>(&mut self, cycle: u64, reset: bool, top: &M) -> io::Result<()> {
        if !self.in_window(cycle) {
            return Ok(());
        }
        let t = cycle * self.cfg.period_ps;
        self.time(t);
        let before = self.batch.len();
        let all = !self.started;
        self.started = true;
        let (clk, rst) = (self.clk.expect("started"), self.rst.expect("started"));
        self.batch.push(Rec::Change(clk, 1));
        if all || self.rst_last != Some(reset) {
            self.batch.push(Rec::Change(rst, u64::from(reset)));
            self.rst_last = Some(reset);
        }
        changes(top, &mut self.vars, all, &mut self.batch);
        self.time(t + self.cfg.period_ps / 2);
        self.batch.push(Rec::Change(clk, 0));
        // Every record since the cycle's first time step is a change, but the second time
        // step and the clock's fall (counted as the VCD tracer counts).
        self.changes += (self.batch.len() - before - 2) as u64;
        if self.batch.len() >= self.batch_len {
            self.hand_over()?;
        }
        Ok(())
    }

    fn finish(&mut self, cycles: u64) -> io::Result<()> {
        let end = match self.cfg.window {
            Some((a, b)) => cycles.min(b).max(a),
            None => cycles,
        } * self.cfg.period_ps;
        if self.last_time.is_none_or(|l| end > l) {
            self.time(end);
        }
        let Some(w) = self.writer.take() else {
            return Err(io::Error::other(format!(
                "{}: the writer stopped on an earlier error",
                self.path.display()
            )));
        };
        let (w, _) = w.send(std::mem::take(&mut self.batch))?;
        w.join()?;
        self.out.take().expect("tracer already finished").commit()?;
        Ok(())
    }
}

impl Drop for FstTracer {
    /// An unfinished trace leaves no file: the writer is stopped and the partial file removed.
    fn drop(&mut self) {
        if let Some(w) = self.writer.take() {
            drop(w.join());
        }
        // An uncommitted `out` removes its partial file when it is dropped.
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A write error keeps its kind (a full disk stays a full disk for the caller) and is
    /// named after the file.
    #[test]
    fn write_errors_keep_their_kind_and_name_the_file() {
        let full = io::Error::new(io::ErrorKind::StorageFull, "no space left");
        let e = named(Path::new("w.fst"), full);
        assert_eq!(e.kind(), io::ErrorKind::StorageFull);
        assert_eq!(e.to_string(), "w.fst: no space left");
    }
}
