//! Co-simulation: a unit's Rust model and a Verilog implementation with the same ports (a twin
//! kept beside the model, or anyone's own) driven with the same inputs on every cycle, every
//! output port compared on every cycle (or only when its qualifier says the value is valid,
//! under its mask), the first difference reported with its cycle, port, both values and the
//! inputs that led to it, and one waveform holding both.
//!
//! The RTL runs in a generated SystemVerilog testbench that replays the stimulus with
//! `$readmemh` and writes every output port every cycle with `$fwrite` (Verilator with
//! `--timing`, its runtime reused between builds, see `verilator.rs`, or Icarus `iverilog
//! -g2012`); the Rust side then compares. This costs a file per run but needs no C++ glue or
//! FFI, runs unchanged in both simulators, and leaves the testbench, stimulus and outputs in
//! the run's folder for the RTL engineer to rerun by hand.
//!
//! A unit reaches co-simulation through [`CosimUnit`]: its model (usually a [`ModelSim`] of
//! its [`Module`]), its Verilog sources and top module, its parameters, its stimulus, and the
//! [`Clocking`] and [`Compare`] rules of its ports.

use hdl::fx::{Format, Fx};
use hdl::kernel::{Dir, Module, Signal, Sim, Visitor};
use std::path::{Path, PathBuf};
use std::process::Command;

pub mod cache;
mod coverage;
mod filelist;
mod internals;
mod library;
mod rtl;
pub(crate) use rtl::made_of;
mod twin;
mod verilator;

pub use coverage::{by_file, FileCoverage, RtlCoverage};
pub use filelist::{FileList, PathsFrom};
pub use internals::ModelInternals;
use internals::{internals, Internals};
pub use library::Library;
pub use rtl::verilog_range;
pub use twin::{random_inputs, Twin};

/// A port of the unit's top: its name and format.
#[derive(Clone, Debug, PartialEq)]
pub struct Port {
    /// The port's name in the model and in Verilog.
    pub name: String,
    /// Its width and format (the waveform and the mismatch report show values in it).
    pub fmt: Format,
}

impl Port {
    /// An unsigned integer port of `width` bits.
    pub fn uint(name: impl Into<String>, width: u32) -> Port {
        Port {
            name: name.into(),
            fmt: Format::uint(width),
        }
    }
}

/// The model's side of a co-simulation: the top's ports and one cycle at a time.
pub trait CosimModel {
    /// Input and output ports of the top, in declaration (visit) order.
    fn ports(&self) -> (Vec<Port>, Vec<Port>);
    /// One cycle: reset, inputs (raw bits in input-port order), settle, the outputs' bits in
    /// output-port order, then the clock edge.
    fn cycle(&mut self, rst: bool, inputs: &[u64]) -> Vec<u64>;
    /// Signals inside the model shown in the co-simulation's waveform beside the comparison,
    /// not compared (none by default).
    fn watched(&self) -> Vec<Port> {
        Vec::new()
    }
    /// [`CosimModel::cycle`], also returning the [`CosimModel::watched`] signals' values, read
    /// when the outputs are.
    fn cycle_watched(&mut self, rst: bool, inputs: &[u64]) -> (Vec<u64>, Vec<u64>) {
        (self.cycle(rst, inputs), Vec::new())
    }
    /// Every signal of the model's hierarchy in `cycles` of a run of the design as built on
    /// `stim` (the first `resets` in reset): what an explained run shows beside the RTL's
    /// internals around a difference (nothing by default).
    fn internals(
        &self,
        _stim: &[Vec<u64>],
        _resets: usize,
        _cycles: std::ops::Range<usize>,
    ) -> Option<ModelInternals> {
        None
    }
    /// A benchmark run of the design as built (not as [`CosimModel::cycle`] left it):
    /// `cycles` cycles of `stim`'s rows replayed as a ring (cycle `c` drives row
    /// `c % stim.len()`; the first `resets` cycles in reset), no schedule check, no output
    /// read; untraced, or traced (every signal, no `real` companions). Returns the time of the
    /// cycle loop with the trace's final flush.
    fn bench(
        &self,
        stim: &[Vec<u64>],
        cycles: usize,
        resets: usize,
        trace: BenchTrace,
    ) -> Result<std::time::Duration, String>;
}

/// What a benchmark run writes.
#[derive(Clone, Copy, Debug)]
pub enum BenchTrace<'a> {
    /// Untraced.
    None,
    /// A VCD written while simulating.
    Vcd(&'a Path),
    /// FST written while simulating ([`waves::FstTracer`]).
    Fst(&'a Path),
}

/// The cycle loop of a benchmark run; its time, the trace finished.
fn bench_loop<M: Module, T: hdl::kernel::Trace, D: Fn(&mut M, &[u64])>(
    mut sim: Sim<M, T>,
    stim: &[Vec<u64>],
    cycles: usize,
    resets: usize,
    drive: &D,
) -> std::io::Result<std::time::Duration> {
    assert!(
        !stim.is_empty() || cycles == 0,
        "cycles to run and no stimulus"
    );
    let n = stim.first().map_or(0, Vec::len);
    let flat: Vec<u64> = stim.iter().flatten().copied().collect();
    assert_eq!(flat.len(), n * stim.len(), "every cycle drives every input");
    let t0 = std::time::Instant::now();
    cycle_loop(&mut sim, (&flat, n), cycles, resets, drive);
    sim.finish()?;
    Ok(t0.elapsed())
}

/// The timed cycles of a benchmark run: the rows of `n` inputs in `flat` (one contiguous
/// array, as the Verilator side reads them) replayed in a ring. A function of its own, never
/// inlined, so that callgrind counts the cycles alone (`--toggle-collect='*cosim::cycle_loop*'`),
/// not the stimulus copy before them.
#[inline(never)]
fn cycle_loop<M: Module, T: hdl::kernel::Trace, D: Fn(&mut M, &[u64])>(
    sim: &mut Sim<M, T>,
    (flat, n): (&[u64], usize),
    cycles: usize,
    resets: usize,
    drive: &D,
) {
    if n == 0 {
        // No inputs: every row is the empty one.
        for c in 0..cycles {
            step(sim, c < resets, &[], drive);
        }
        return;
    }
    // Passes over the rows (the last over as many as the cycles left need): a row is a chunk
    // of the array, with no index to check.
    let mut c = 0;
    while c < cycles {
        for row in flat.chunks_exact(n).take(cycles - c) {
            step(sim, c < resets, row, drive);
            c += 1;
        }
    }
}

/// One cycle of a benchmark run: `row` driven, the design evaluated, its clock edge.
#[inline(always)]
fn step<M: Module, T: hdl::kernel::Trace, D: Fn(&mut M, &[u64])>(
    sim: &mut Sim<M, T>,
    reset: bool,
    row: &[u64],
    drive: &D,
) {
    sim.set_reset(reset);
    drive(&mut sim.dut, row);
    sim.eval();
    sim.tick();
}

/// A co-simulation model of a [`Module`] whose inputs `drive` sets from raw bits (a
/// function or a closure, each its own type, so that the benchmark's cycle loop inlines it).
pub struct ModelSim<M: Module, D = fn(&mut M, &[u64])> {
    sim: Sim<M>,
    /// The design as built, for benchmark runs.
    pristine: M,
    drive: D,
    /// Values inside the model compared as further output ports (see [`ModelSim::probes`]).
    probes: Vec<Port>,
    probe: fn(&M) -> Vec<u64>,
    /// Values inside the model shown in the waveform, not compared ([`ModelSim::watch`]).
    watch: Vec<Port>,
    watch_fn: fn(&M) -> Vec<u64>,
}

impl<M: Module + Clone, D: Fn(&mut M, &[u64])> ModelSim<M, D> {
    /// The model `dut` (kept as built for benchmark runs), its inputs set from raw bits in
    /// input-port order by `drive`.
    pub fn new(dut: M, drive: D) -> Self {
        ModelSim {
            pristine: dut.clone(),
            sim: Sim::new(dut).check_schedule(true),
            drive,
            probes: Vec::new(),
            probe: |_| Vec::new(),
            watch: Vec::new(),
            watch_fn: |_| Vec::new(),
        }
    }

    /// Shows `ports` in the co-simulation's waveform (scope `tb.watched`) beside the
    /// comparison, not compared: `f` reads them from the settled model each cycle (a state
    /// register, a pipeline's valid bits, the culprit's path).
    pub fn watch(mut self, ports: Vec<Port>, f: fn(&M) -> Vec<u64>) -> Self {
        self.watch = ports;
        self.watch_fn = f;
        self
    }

    /// Compares `ports` too, after the top's outputs: `probe` reads them from the settled
    /// model (signals of a child, such as the pins a controller drives, or counters the RTL
    /// brings out as ports).
    pub fn probes(mut self, ports: Vec<Port>, probe: fn(&M) -> Vec<u64>) -> Self {
        self.probes = ports;
        self.probe = probe;
        self
    }
}

/// The top's own ports (depth 1 of the hierarchy), by direction.
struct TopPorts {
    depth: usize,
    inputs: Vec<Port>,
    outputs: Vec<Port>,
    out_bits: Vec<u64>,
}

impl Visitor for TopPorts {
    fn enter(&mut self, _: &str, _: &str) {
        self.depth += 1;
    }
    fn leave(&mut self) {
        self.depth -= 1;
    }
    fn signal(&mut self, d: Dir, s: &Signal) {
        if self.depth != 1 {
            return;
        }
        let p = Port {
            name: s.name().to_string(),
            fmt: s.fmt(),
        };
        match d {
            Dir::Input => self.inputs.push(p),
            Dir::Output => {
                self.outputs.push(p);
                self.out_bits.push(s.bits());
            }
            _ => {}
        }
    }
}

fn top_ports(m: &dyn Module) -> TopPorts {
    let mut t = TopPorts {
        depth: 0,
        inputs: Vec::new(),
        outputs: Vec::new(),
        out_bits: Vec::new(),
    };
    m.visit(&mut t);
    t
}

impl<M: Module + Clone, D: Fn(&mut M, &[u64])> CosimModel for ModelSim<M, D> {
    fn ports(&self) -> (Vec<Port>, Vec<Port>) {
        let t = top_ports(&self.sim.dut);
        let mut outs = t.outputs;
        outs.extend(self.probes.iter().cloned());
        (t.inputs, outs)
    }
    fn cycle(&mut self, rst: bool, inputs: &[u64]) -> Vec<u64> {
        self.cycle_watched(rst, inputs).0
    }
    fn watched(&self) -> Vec<Port> {
        self.watch.clone()
    }
    fn cycle_watched(&mut self, rst: bool, inputs: &[u64]) -> (Vec<u64>, Vec<u64>) {
        self.sim.set_reset(rst);
        (self.drive)(&mut self.sim.dut, inputs);
        self.sim.eval();
        let mut out = top_ports(&self.sim.dut).out_bits;
        out.extend((self.probe)(&self.sim.dut));
        let watched = (self.watch_fn)(&self.sim.dut);
        self.sim.tick();
        (out, watched)
    }
    fn internals(
        &self,
        stim: &[Vec<u64>],
        resets: usize,
        cycles: std::ops::Range<usize>,
    ) -> Option<ModelInternals> {
        let dut = self.pristine.clone();
        Some(ModelInternals::of(dut, &self.drive, stim, resets, cycles))
    }
    fn bench(
        &self,
        stim: &[Vec<u64>],
        cycles: usize,
        resets: usize,
        trace: BenchTrace,
    ) -> Result<std::time::Duration, String> {
        let dut = self.pristine.clone();
        let cfg = waves::TraceConfig {
            companions: false,
            ..Default::default()
        };
        let r = match trace {
            BenchTrace::None => bench_loop(Sim::new(dut), stim, cycles, resets, &self.drive),
            BenchTrace::Vcd(p) => {
                let title = format!("{} benchmark", self.pristine.kind());
                waves::VcdTracer::create(p, &title, cfg)
                    .and_then(|t| Sim::traced(dut, t))
                    .and_then(|s| bench_loop(s, stim, cycles, resets, &self.drive))
            }
            BenchTrace::Fst(p) => waves::FstTracer::create(p, cfg)
                .and_then(|t| Sim::traced(dut, t))
                .and_then(|s| bench_loop(s, stim, cycles, resets, &self.drive)),
        };
        r.map_err(|e| e.to_string())
    }
}

/// A unit that has a Verilog implementation to co-simulate against: everything the
/// generated testbench and the comparison need to know, said by the unit.
pub trait CosimUnit: Send + Sync {
    /// The unit's name: its module in Verilog, its kind in the model, its folder's name.
    fn name(&self) -> &str;
    /// The Verilog module the testbench instantiates: the unit itself, or the unit with the
    /// behavioural parts the model holds beside it (a memory controller with its DRAM).
    fn top(&self) -> &str {
        self.name()
    }
    /// The unit's own Verilog sources (what `cosim --rtl` replaces). A relative path is taken
    /// from the current folder: give them from your crate's root with
    /// `Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/unit.v")`.
    fn rtl(&self) -> Vec<PathBuf>;
    /// Testbench-side sources, always compiled (with the unit's own or the user's `--rtl`):
    /// the top wrapping the unit and the behavioural models it drives.
    fn bench_rtl(&self) -> Vec<PathBuf> {
        Vec::new()
    }
    /// The Verilog parameters of this configuration (the model's parameters).
    fn parameters(&self) -> Vec<(&'static str, i64)>;
    /// The model in this configuration, from reset.
    fn model(&self) -> Result<Box<dyn CosimModel>, String>;
    /// Inputs of `cycles` cycles (raw bits in input-port order), seeded; the first
    /// [`Clocking::reset_cycles`] are driven in reset.
    fn stimulus(&self, seed: crate::Seed, cycles: usize) -> Vec<Vec<u64>>;
    /// The clock and reset ports of the Verilog top and how reset is driven; `None` for a
    /// combinational unit (no clock, no reset port).
    fn clocking(&self) -> Option<Clocking> {
        Some(Clocking::default())
    }
    /// Which outputs are compared when, and under which mask; an output with no rule is
    /// compared whole on every cycle.
    fn compare(&self) -> Vec<Compare> {
        Vec::new()
    }
    /// Cycles of inputs shown with the first difference, the cycle itself included: enough to
    /// show the transaction in flight through the unit's deepest pipeline.
    fn history(&self) -> usize {
        4
    }
    /// Memory images the RTL loads with `$readmemh` (file name, text): written into the run's
    /// folder, where the simulator runs, before it starts.
    fn memories(&self) -> Vec<(String, String)> {
        Vec::new()
    }
    /// Ports of the Verilog top that the model lacks in this configuration (a second MIP
    /// level's inputs a parameter leaves unused, levels beyond the frame's size): each input
    /// tied to a constant, each output left open. The testbench connects the top's ports by
    /// name, and a port neither the model's nor listed here refuses the build, naming it.
    fn unmodelled(&self) -> Vec<Unmodelled> {
        Vec::new()
    }
    /// Folders searched for `` `include `` files, after the folder of each source (which is
    /// always searched).
    fn include_dirs(&self) -> Vec<PathBuf> {
        Vec::new()
    }
    /// Preprocessor macros defined for the build: `NAME` or `NAME=VALUE`.
    fn defines(&self) -> Vec<String> {
        Vec::new()
    }
    /// File lists of the unit's own Verilog ([`FileList`]), read at each run: their sources
    /// compiled after [`CosimUnit::rtl`]'s, their folders and macros before the unit's own,
    /// their module libraries ([`Library`]) searched after the include folders.
    /// Like `rtl`, what `cosim --rtl` and `cosim -f` replace.
    fn file_lists(&self) -> Vec<(PathBuf, PathsFrom)> {
        Vec::new()
    }
}

/// Whether `m` is a preprocessor macro as a build takes it: a Verilog identifier, then
/// optionally `=` and its value (on one line).
pub fn is_define(m: &str) -> bool {
    !m.contains(char::is_control) && is_identifier(m.split('=').next().unwrap_or(""))
}

/// Whether `name` is a simple Verilog identifier (a module's, a macro's).
pub fn is_identifier(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$')
}

/// What the preprocessor of a build is given, in both simulators alike.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Preprocessor {
    /// Folders searched for `` `include `` files, absolute: each source's, then those of the
    /// unit's file lists, then the unit's own.
    pub include_dirs: Vec<PathBuf>,
    /// Macros defined: the file lists', then the unit's (`NAME` or `NAME=VALUE`).
    pub defines: Vec<String>,
}

impl Preprocessor {
    /// As the simulators' command lines take it: `-IDIR` and `-DNAME[=VALUE]`.
    pub fn flags(&self) -> Vec<String> {
        let dirs = self
            .include_dirs
            .iter()
            .map(|d| format!("-I{}", d.display()));
        dirs.chain(self.defines.iter().map(|m| format!("-D{m}")))
            .collect()
    }
}

/// What a build of a unit compiles, resolved: its sources, its preprocessor and its module
/// library.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Build {
    /// Every source, absolute and an existing file: the unit's own ([`CosimUnit::rtl`], then
    /// its file lists' sources) or the user's in their place, then
    /// [`CosimUnit::bench_rtl`].
    pub sources: Vec<PathBuf>,
    /// Its include folders and macros.
    pub pre: Preprocessor,
    /// Where the modules the sources do not define are found: its file lists' libraries.
    pub library: Library,
}

impl Build {
    /// The build of `unit` against `rtl` (the unit's own sources and file lists when empty).
    /// Each include folder must be a folder, each macro a Verilog identifier with an optional
    /// `=VALUE`, and the folders searched for modules may hold no more module files than
    /// [`Library::listing`] lists.
    pub fn of(unit: &dyn CosimUnit, rtl: &[PathBuf]) -> Result<Build, String> {
        let mut listed = FileList::default();
        let own = if rtl.is_empty() {
            for (list, from) in unit.file_lists() {
                let l = FileList::read(&list, from)?;
                listed.sources.extend(l.sources);
                listed.include_dirs.extend(l.include_dirs);
                listed.defines.extend(l.defines);
                listed.library.extend(l.library);
            }
            [unit.rtl(), std::mem::take(&mut listed.sources)].concat()
        } else {
            rtl.to_vec()
        };
        let sources: Vec<PathBuf> = own
            .into_iter()
            .chain(unit.bench_rtl())
            .map(|s| std::path::absolute(&s).unwrap_or(s))
            .collect();
        if let Some(s) = sources.iter().find(|s| !s.is_file()) {
            return Err(format!("{}: no such Verilog file", s.display()));
        }
        let mut include_dirs: Vec<PathBuf> = Vec::new();
        let own = sources
            .iter()
            .filter_map(|s| s.parent().map(Path::to_path_buf));
        for d in own.chain(listed.include_dirs).chain(unit.include_dirs()) {
            let d = std::path::absolute(&d).unwrap_or(d);
            if !d.is_dir() {
                return Err(format!("include folder {}: no such folder", d.display()));
            }
            if !include_dirs.contains(&d) {
                include_dirs.push(d);
            }
        }
        let defines = [listed.defines, unit.defines()].concat();
        if let Some(m) = defines.iter().find(|m| !is_define(m)) {
            let shown = waves::output::shorten(m);
            return Err(format!("define '{shown}': not NAME or NAME=VALUE"));
        }
        let pre = Preprocessor {
            include_dirs,
            defines,
        };
        listed.library.listing(&pre.include_dirs)?;
        Ok(Build {
            sources,
            pre,
            library: listed.library,
        })
    }
}

/// A port of the Verilog top that the model lacks ([`CosimUnit::unmodelled`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Unmodelled {
    /// An input, driven with these bits on every cycle.
    Tied(String, u64),
    /// An output, left unconnected and not compared.
    Open(String),
}

impl Unmodelled {
    /// The port's name.
    pub fn name(&self) -> &str {
        match self {
            Unmodelled::Tied(n, _) | Unmodelled::Open(n) => n,
        }
    }

    /// A tied input's name and bits.
    pub fn tied(&self) -> Option<(&str, u64)> {
        match self {
            Unmodelled::Tied(n, bits) => Some((n, *bits)),
            Unmodelled::Open(_) => None,
        }
    }
}

/// The clock and reset of a clocked Verilog top. The model sees reset as the `rst` of
/// [`CosimModel::cycle`] on the same cycles; only the Verilog side has names and a polarity.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Clocking {
    /// The clock port, rising edge active.
    pub clock: String,
    /// The reset port; `None`: the top has none (the model is still reset on the first
    /// cycles, which the Verilog must then match from its own initial values).
    pub reset: Option<String>,
    /// Reset asserted high (`true`) or low.
    pub reset_active_high: bool,
    /// Cycles in reset at the start of every run (at least 1).
    pub reset_cycles: usize,
}

impl Default for Clocking {
    /// `clk`, synchronous `rst` active high for [`RESET_CYCLES`] cycles.
    fn default() -> Self {
        Clocking {
            clock: "clk".into(),
            reset: Some("rst".into()),
            reset_active_high: true,
            reset_cycles: RESET_CYCLES,
        }
    }
}

/// A comparison rule for one output port.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Compare {
    /// The output port the rule is for.
    pub port: String,
    /// Compare it only on cycles where this output (1 bit, itself compared) is 1 in the model:
    /// data that is valid only with its valid flag.
    pub when: Option<String>,
    /// Compare only these bits (all ones: the whole port).
    pub mask: u64,
}

impl Compare {
    /// `port` compared only when the output `valid` is 1.
    pub fn when(port: impl Into<String>, valid: impl Into<String>) -> Compare {
        Compare {
            port: port.into(),
            when: Some(valid.into()),
            mask: u64::MAX,
        }
    }
    /// `port` compared on the bits of `mask` only.
    pub fn masked(port: impl Into<String>, mask: u64) -> Compare {
        Compare {
            port: port.into(),
            when: None,
            mask,
        }
    }
    /// This rule, also masked.
    pub fn mask(mut self, mask: u64) -> Compare {
        self.mask = mask;
        self
    }
}

/// The rules of every output port, by index, checked against the ports.
#[derive(Clone, Debug)]
struct Rules {
    /// Per output: the index of its qualifier and its mask.
    per_port: Vec<(Option<usize>, u64)>,
}

impl Rules {
    fn new(unit: &dyn CosimUnit, outs: &[Port]) -> Result<Rules, String> {
        let mut per_port: Vec<(Option<usize>, u64)> = outs
            .iter()
            .map(|p| (None, width_mask(p.fmt.width())))
            .collect();
        let find = |name: &str, what: &str| {
            outs.iter().position(|p| p.name == name).ok_or_else(|| {
                format!(
                    "{}: the compare rule's {what} '{name}' is no output port",
                    unit.name()
                )
            })
        };
        for c in unit.compare() {
            let k = find(&c.port, "port")?;
            let q = match &c.when {
                Some(w) => {
                    let q = find(w, "qualifier")?;
                    if outs[q].fmt.width() != 1 || q == k {
                        return Err(format!(
                            "{}: the qualifier '{w}' of '{}' must be another 1-bit output",
                            unit.name(),
                            c.port
                        ));
                    }
                    Some(q)
                }
                None => None,
            };
            per_port[k] = (q, per_port[k].1 & c.mask);
        }
        Ok(Rules { per_port })
    }

    /// Whether output `k` differs on a cycle whose model outputs are `e` and RTL outputs `g`.
    fn differs(&self, k: usize, e: &[u64], g: &[Option<u64>]) -> bool {
        let (q, mask) = self.per_port[k];
        if q.is_some_and(|q| e[q] == 0) || mask == 0 {
            return false;
        }
        g[k].is_none_or(|g| (g ^ e[k]) & mask != 0)
    }

    /// The bits of a cycle's outputs `o` that the comparison looks at, summed (wrapping): an
    /// output under its mask, on a cycle its qualifier is 1.
    fn compared_sum(&self, o: &[u64]) -> u64 {
        let mut sum = 0u64;
        for (&(q, mask), v) in self.per_port.iter().zip(o) {
            if q.is_none_or(|q| o[q] != 0) {
                sum = sum.wrapping_add(v & mask);
            }
        }
        sum
    }

    /// [`Rules::compared_sum`] in C++, over the outputs `outs` of a Verilator model `top`,
    /// added into `sum`: one statement an output.
    fn compared_sum_cpp(&self, outs: &[Port]) -> String {
        let mut s = String::new();
        for (p, &(q, mask)) in outs.iter().zip(&self.per_port) {
            let add = format!("sum += (uint64_t)top.{} & {mask}ULL;", p.name);
            match q {
                Some(q) => s += &format!("if (top.{}) {add} ", outs[q].name),
                None => s += &format!("{add} "),
            }
        }
        s
    }
}

/// The co-simulation's comparison of `unit` as one number, for a harness that runs the twin
/// but does not compare it cycle by cycle (the bench's): its `model`, as built, run on
/// `cycles` cycles of `stim`'s rows replayed in a ring (the first [`reset_cycles`] in reset),
/// and on every cycle from [`FIRST_COMPARED`] the bits of every output its rule compares,
/// sampled where the co-simulation samples them (inputs settled, before the clock edge),
/// summed (wrapping).
pub(crate) fn compared_checksum(
    unit: &dyn CosimUnit,
    model: &mut dyn CosimModel,
    stim: &[Vec<u64>],
    cycles: usize,
) -> Result<u64, String> {
    let rules = Rules::new(unit, &model.ports().1)?;
    let resets = reset_cycles(unit);
    let mut sum = 0u64;
    for (c, inputs) in stim.iter().cycle().take(cycles).enumerate() {
        let o = crate::testbench::unpanicked(|| model.cycle(c < resets, inputs))
            .map_err(|said| format!("{MODEL_PANICKED}{c}: {said}"))?;
        if c >= FIRST_COMPARED {
            sum = sum.wrapping_add(rules.compared_sum(&o));
        }
    }
    Ok(sum)
}

/// The C++ statements that add a cycle's [`compared_checksum`] terms into `sum`, over the
/// outputs `outs` of `unit`'s Verilator model `top`.
pub(crate) fn compared_checksum_cpp(unit: &dyn CosimUnit, outs: &[Port]) -> Result<String, String> {
    Ok(Rules::new(unit, outs)?.compared_sum_cpp(outs))
}

fn width_mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// Cycles of reset at the start of every run.
pub const RESET_CYCLES: usize = 2;

/// The first cycle compared: cycle 0 shows the registers' power-up values, which Verilog
/// leaves unknown (`x`) and the model sets to their reset values; from cycle 1 on, the first
/// reset edge has defined them.
pub const FIRST_COMPARED: usize = 1;

/// The simulators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simulator {
    /// Verilator (`--binary --timing`), its runtime reused between builds.
    Verilator,
    /// Icarus Verilog (`iverilog -g2012`, `vvp`).
    Icarus,
}

impl Simulator {
    /// `verilator` or `icarus`.
    pub fn parse(s: &str) -> Option<Simulator> {
        match s {
            "verilator" => Some(Simulator::Verilator),
            "icarus" => Some(Simulator::Icarus),
            _ => None,
        }
    }
    /// The name `parse` reads.
    pub fn name(self) -> &'static str {
        match self {
            Simulator::Verilator => "verilator",
            Simulator::Icarus => "icarus",
        }
    }
    /// `Err` names what to install when the simulator is not on the PATH. Once found, it is
    /// not looked for again in the process (`verilator -V` takes about 40 ms, a regression
    /// asks before every run).
    pub fn check_installed(self) -> Result<(), String> {
        use std::sync::atomic::{AtomicBool, Ordering};
        static FOUND: [AtomicBool; 2] = [AtomicBool::new(false), AtomicBool::new(false)];
        let (exe, pkg) = match self {
            Simulator::Verilator => ("verilator", "verilator"),
            Simulator::Icarus => ("iverilog", "iverilog"),
        };
        let found = &FOUND[self as usize];
        if found.load(Ordering::Relaxed) {
            return Ok(());
        }
        match Command::new(exe).arg("-V").output() {
            Ok(_) => {
                found.store(true, Ordering::Relaxed);
                Ok(())
            }
            Err(_) => Err(format!(
                "{exe} not found: install it (Debian: apt-get install {pkg})"
            )),
        }
    }
}

/// What a co-simulation found.
#[derive(Clone, Debug)]
pub struct CosimResult {
    /// Cycles simulated, reset included.
    pub cycles: usize,
    /// The first difference, if any.
    pub mismatch: Option<Difference>,
    /// Differences counted over all cycles and ports.
    pub differences: u64,
    /// The waveform holding the model, the RTL, a mismatch flag per port and the inputs
    /// (`None` when [`RunOptions::waveform_on_difference_only`] left it out).
    pub vcd: Option<PathBuf>,
    /// After a difference in [`run_explained`]: which of the RTL's internals the waveform
    /// shows, or why it shows none.
    pub internals: Option<String>,
    /// The RTL's coverage, when [`RunOptions::rtl_coverage`] asked for it.
    pub rtl_coverage: Option<RtlCoverage>,
}

/// What a run does besides comparing ([`run_with_options`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RunOptions {
    /// At a difference, show the RTL's internals around it ([`run_explained`]).
    pub internals: bool,
    /// Measure the RTL's line and toggle coverage ([`RtlCoverage`]; Verilator only): the
    /// build is another (`--coverage-line --coverage-toggle`, its runtime compiled anew), and
    /// the run is always simulated, never taken from the cache.
    pub rtl_coverage: bool,
    /// Write the waveform only when the RTL and the model differ: a regression's further
    /// seeds, whose agreeing runs leave nothing to look at (their stimulus is the seed's).
    pub waveform_on_difference_only: bool,
}

/// The first cycle and port where the RTL and the model part.
#[derive(Clone, Debug)]
pub struct Difference {
    /// The cycle (from 0, reset included).
    pub cycle: usize,
    /// The output port.
    pub port: String,
    /// The port's format.
    pub fmt: Format,
    /// The model's bits.
    pub model: u64,
    /// `None`: the RTL drove `x` or `z`.
    pub rtl: Option<u64>,
    /// The inputs of the cycles up to this one (the transaction in flight), oldest first.
    pub inputs: Vec<(usize, String)>,
}

fn show(bits: u64, fmt: Format) -> String {
    let w = (fmt.width() as usize).div_ceil(4);
    format!("0x{bits:0w$x} ({})", Fx::from_bits(fmt, u128::from(bits)))
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let rtl = self
            .rtl
            .map_or("x (unknown)".to_string(), |r| show(r, self.fmt));
        write!(
            f,
            "cycle {}: port {} ({}): model {}, RTL {rtl}",
            self.cycle,
            self.port,
            self.fmt,
            show(self.model, self.fmt)
        )?;
        for (c, i) in &self.inputs {
            write!(f, "\n  inputs at cycle {c}: {i}")?;
        }
        Ok(())
    }
}

/// One directed run: a name for its folder, the unit in the configuration the stimulus was made
/// for, and the inputs of every cycle (reset first): the regression vectors' transactions as
/// co-simulation stimulus, for example.
pub struct Directed {
    /// The run's name, its folder's.
    pub label: String,
    /// The unit in the configuration the stimulus was made for.
    pub unit: Box<dyn CosimUnit>,
    /// The inputs of every cycle, raw bits in input-port order, reset cycles first.
    pub stimulus: Vec<Vec<u64>>,
}

/// Values of a `width`-bit field: its corners (0, 1, the largest, the sign boundary 2^(w-1)
/// and one below it) a quarter of the time, otherwise uniform. `width` is 1..=64, as every
/// unit's `validate` guarantees.
pub fn field(width: u32) -> impl proptest::strategy::Strategy<Value = u64> {
    use proptest::strategy::Just;
    let max = if width == 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    let top = 1u64 << (width - 1);
    proptest::prop_oneof![
        1 => proptest::prop_oneof![Just(0u64), Just(1 & max), Just(max), Just(top), Just(top - 1)],
        3 => 0..=max,
    ]
}

/// Runs `unit` in `sim` against `rtl` (its twin when empty) for `cycles` cycles in `dir`.
/// `Err` is for what stops the run (a simulator missing or failing, bad sources); a difference
/// is in the result.
pub fn run(
    unit: &dyn CosimUnit,
    sim: Simulator,
    rtl: &[PathBuf],
    cycles: usize,
    seed: crate::Seed,
    dir: &Path,
) -> Result<CosimResult, String> {
    run_with(unit, sim, rtl, &unit.stimulus(seed, cycles), dir)
}

/// Cycles in reset at the start of `unit`'s runs.
pub fn reset_cycles(unit: &dyn CosimUnit) -> usize {
    unit.clocking().map_or(RESET_CYCLES, |c| c.reset_cycles)
}

/// Runs `unit` as [`run`] does on the given inputs of every cycle (`stim`, the first
/// [`reset_cycles`] of them in reset): directed stimulus, such as the regression vectors.
pub fn run_with(
    unit: &dyn CosimUnit,
    sim: Simulator,
    rtl: &[PathBuf],
    stim: &[Vec<u64>],
    dir: &Path,
) -> Result<CosimResult, String> {
    run_with_options(unit, sim, rtl, stim, dir, RunOptions::default())
}

/// Cycles of the RTL's internals dumped before the first difference ([`run_explained`]).
pub const INTERNALS_BEFORE: usize = 100;
/// Cycles of the RTL's internals dumped after the first difference.
pub const INTERNALS_AFTER: usize = 20;

/// As [`run_with`], and at a difference the RTL is simulated again, dumping every signal
/// under its top from [`INTERNALS_BEFORE`] cycles before the first difference to
/// [`INTERNALS_AFTER`] after it: the waveform shows them, sampled as the ports are, under
/// `tb.rtl_internals` (its top's own signals in the view, below the ports; its sub-modules
/// in the tree). The run is built with the dump compiled in (Verilator's with `--trace`, a
/// build slower by about a half), so that the second run repeats the first exactly; it is
/// what `cosim` runs. [`CosimResult::internals`] says what was shown, or why not.
pub fn run_explained(
    unit: &dyn CosimUnit,
    sim: Simulator,
    rtl: &[PathBuf],
    stim: &[Vec<u64>],
    dir: &Path,
) -> Result<CosimResult, String> {
    let internals = RunOptions {
        internals: true,
        ..RunOptions::default()
    };
    run_with_options(unit, sim, rtl, stim, dir, internals)
}

/// Runs `unit` as [`run_with`] does, doing what `options` asks besides.
pub fn run_with_options(
    unit: &dyn CosimUnit,
    sim: Simulator,
    rtl: &[PathBuf],
    stim: &[Vec<u64>],
    dir: &Path,
    options: RunOptions,
) -> Result<CosimResult, String> {
    let (cycles, explain) = (stim.len(), options.internals);
    refused(unit, sim, &options, cycles)?;
    let mut model = unit.model()?;
    let (ins, outs) = model.ports();
    let rules = Rules::new(unit, &outs)?;
    let build = Build::of(unit, rtl)?;
    // The model first: a model that panics leaves no folder.
    let resets = reset_cycles(unit);
    let (expected, watched) = expect(unit, model.as_mut(), stim, resets)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    // The simulator runs inside `dir`: every path it is given is absolute.
    let dir = &std::path::absolute(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let plain = |c: char| c.is_ascii_alphanumeric() || "._-/".contains(c);
    if sim == Simulator::Verilator && !dir.to_string_lossy().chars().all(plain) {
        return Err(format!(
            "{}: Verilator's build (make) needs a folder path of letters, digits, '.', '_', '-' and '/'",
            dir.display()
        ));
    }
    let mut run = rtl_run(unit, dir, &build, (&ins, &outs), stim, explain)?;
    run.coverage = options.rtl_coverage;
    if run.coverage {
        // Not an earlier run's, if this one writes none.
        let _ = std::fs::remove_file(dir.join("coverage.dat"));
    }
    let got = rtl::simulate(sim, &run)?;
    let rtl_coverage = options
        .rtl_coverage
        .then(|| RtlCoverage::read(&dir.join("coverage.dat"), dir))
        .transpose()?;
    if got.len() != cycles {
        return Err(format!(
            "{}: the RTL wrote {} cycles of outputs, {cycles} expected",
            sim.name(),
            got.len()
        ));
    }
    let history = unit.history().max(1);
    let found = compare(
        &ins,
        &outs,
        &rules,
        stim,
        &expected,
        &got,
        (resets, history),
    );
    let first = found.0.as_ref().filter(|_| explain).map(|d| d.cycle);
    let internals = first.map(|c| internals(sim, &run, &got, c));
    let model_internals =
        first.and_then(|c| model.internals(stim, resets, internals::window(c, cycles)));
    let shown = Compared {
        unit,
        rules: &rules,
        expected: &expected,
        got: &got,
        watched: (&model.watched(), &watched),
        stim,
        internals: internals.as_ref().and_then(|r| r.as_ref().ok()),
        model_internals: model_internals.as_ref(),
    };
    let wanted = found.0.is_some() || !options.waveform_on_difference_only;
    let vcd = wanted.then(|| shown.write(dir, &ins, &outs)).transpose()?;
    Ok(CosimResult {
        cycles,
        mismatch: found.0,
        differences: found.1,
        vcd,
        internals: internals.map(|r| {
            let rtl = r.map_or_else(|e| e, |s| s.said());
            match &model_internals {
                Some(m) => format!("{rtl}; {}", m.said()),
                None => rtl,
            }
        }),
        rtl_coverage,
    })
}

/// What an error of [`run_with_options`] says when the model panicked (a value that does not
/// fit its signal's format): `UNIT: the model panicked in cycle C: MESSAGE`. A finding about
/// the model, not bad input.
pub const MODEL_PANICKED: &str = "the model panicked in cycle ";

/// Each cycle's outputs and watched signals of a model.
type Expected = (Vec<Vec<u64>>, Vec<Vec<u64>>);

/// The model's outputs and watched signals on every cycle of `stim`, or the cycle it panicked
/// in and why.
fn expect(
    unit: &dyn CosimUnit,
    model: &mut dyn CosimModel,
    stim: &[Vec<u64>],
    resets: usize,
) -> Result<Expected, String> {
    let (mut expected, mut watched) = (Vec::with_capacity(stim.len()), Vec::new());
    for (c, inputs) in stim.iter().enumerate() {
        let (e, w) = crate::testbench::unpanicked(|| model.cycle_watched(c < resets, inputs))
            .map_err(|said| format!("{}: {MODEL_PANICKED}{c}: {said}", unit.name()))?;
        expected.push(e);
        watched.push(w);
    }
    Ok((expected, watched))
}

/// Why a run cannot be made, before anything is written: no cycles, the RTL's coverage asked
/// of a simulator that has none, no reset cycle, the simulator not installed.
fn refused(
    unit: &dyn CosimUnit,
    sim: Simulator,
    options: &RunOptions,
    cycles: usize,
) -> Result<(), String> {
    if cycles == 0 {
        return Err(format!("{}: no cycles to simulate", unit.name()));
    }
    if options.rtl_coverage && sim != Simulator::Verilator {
        return Err(format!("{}: the RTL's coverage is Verilator's", sim.name()));
    }
    if unit.clocking().is_some_and(|c| c.reset_cycles == 0) {
        return Err(format!("{}: reset_cycles must be at least 1", unit.name()));
    }
    sim.check_installed()
}

/// What a run's waveform shows: the comparison, the inputs, the model's watched signals and
/// the RTL's and the model's internals when dumped.
struct Compared<'a> {
    unit: &'a dyn CosimUnit,
    rules: &'a Rules,
    expected: &'a [Vec<u64>],
    got: &'a [Vec<Option<u64>>],
    watched: (&'a [Port], &'a [Vec<u64>]),
    stim: &'a [Vec<u64>],
    internals: Option<&'a Internals>,
    model_internals: Option<&'a ModelInternals>,
}

impl Compared<'_> {
    /// Writes the waveform (and its `.gtkw`) into `dir`; returns its path.
    fn write(&self, dir: &Path, ins: &[Port], outs: &[Port]) -> Result<PathBuf, String> {
        use waves::compare::{Shown, Values};
        let resets = reset_cycles(self.unit);
        let vcd = dir.join(format!("{}_cosim.vcd", self.unit.name()));
        let defs: Vec<(&str, u32, bool)> = outs
            .iter()
            .map(|p| (p.name.as_str(), p.fmt.width(), p.fmt.is_signed()))
            .collect();
        // Flagged where the comparison counts a difference: not before its first compared cycle.
        let (expected, got) = (self.expected, self.got);
        let differs = |c: usize, k: usize| {
            c >= FIRST_COMPARED && self.rules.differs(k, &expected[c], &got[c])
        };
        let (inputs, watch) = (shown_ports(ins, true), shown_ports(self.watched.0, false));
        let stim_rst: Vec<Vec<u64>> = (self.stim.iter().enumerate())
            .map(|(c, v)| {
                std::iter::once(u64::from(c < resets))
                    .chain(v.iter().copied())
                    .collect()
            })
            .collect();
        let mut shown = vec![Shown {
            scope: "inputs",
            signals: &inputs,
            values: Values::Every(&stim_rst),
            states: &[],
        }];
        if !watch.is_empty() {
            shown.push(Shown {
                scope: "watched",
                signals: &watch,
                values: Values::Every(self.watched.1),
                states: &[],
            });
        }
        let inner: Vec<(&str, u32, bool)> = self.internals.map_or(Vec::new(), |i| {
            let s = &i.sampled.signals;
            s.iter().map(|(n, w)| (n.as_str(), *w, false)).collect()
        });
        if let Some(i) = self.internals {
            let s = &i.sampled;
            shown.push(Shown {
                scope: "rtl_internals",
                signals: &inner,
                values: Values::From(s.cycles.start, &s.values),
                states: &[],
            });
        }
        let (mine, mine_values) = match self.model_internals {
            Some(m) => (
                (m.signals.iter())
                    .map(|(n, w, sg)| (n.as_str(), *w, *sg))
                    .collect(),
                (m.values.iter())
                    .map(|row| row.iter().copied().map(Some).collect())
                    .collect(),
            ),
            None => (Vec::new(), Vec::new()),
        };
        if let Some(m) = self.model_internals {
            shown.push(Shown {
                scope: "model_internals",
                signals: &mine,
                values: Values::From(m.cycles.start, &mine_values),
                states: &m.states,
            });
        }
        let title = self.unit.name();
        waves::compare::write(&vcd, title, &defs, expected, got, &differs, &shown)?;
        Ok(vcd)
    }
}

/// Writes a run's files into `dir` (the stimulus, the memory images, the testbench): the run
/// of the RTL, to simulate (or take a kept run of).
fn rtl_run<'a>(
    unit: &'a dyn CosimUnit,
    dir: &'a Path,
    build: &'a Build,
    (ins, outs): (&'a [Port], &'a [Port]),
    stim: &[Vec<u64>],
    dumps: bool,
) -> Result<rtl::RtlRun<'a>, String> {
    rtl::write_stimulus(&dir.join("stim.hex"), ins, stim, reset_cycles(unit))?;
    let mut inputs = vec![dir.join("stim.hex")];
    for (file, text) in unit.memories() {
        let path = dir.join(file);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        inputs.push(path);
    }
    let tb = rtl::testbench(unit, ins, outs);
    std::fs::write(dir.join("tb.sv"), tb).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut pre = build.pre.clone();
    if dumps {
        pre.defines.push(rtl::DUMP_MACRO.to_string());
    }
    Ok(rtl::RtlRun {
        dir,
        sources: &build.sources,
        library: &build.library,
        top: unit.top(),
        clocking: unit.clocking(),
        unmodelled: unit.unmodelled(),
        parameters: unit.parameters().iter().map(|p| p.0).collect(),
        pre,
        ins,
        outs,
        cycles: stim.len(),
        inputs,
        dumps,
        coverage: false,
        dump_from: None,
        init_seed: None,
    })
}

/// Names and widths of `ports` for the waveform, after a 1-bit `rst` when `with_reset`.
fn shown_ports(ports: &[Port], with_reset: bool) -> Vec<(&str, u32, bool)> {
    let rst = with_reset.then_some(("rst", 1, false));
    rst.into_iter()
        .chain(
            ports
                .iter()
                .map(|p| (p.name.as_str(), p.fmt.width(), p.fmt.is_signed())),
        )
        .collect()
}

/// Every output port on every cycle from [`FIRST_COMPARED`], under its rule; the first
/// difference with the inputs of the `history` cycles up to it. `resets`: cycles in reset.
fn compare(
    ins: &[Port],
    outs: &[Port],
    rules: &Rules,
    stim: &[Vec<u64>],
    expected: &[Vec<u64>],
    got: &[Vec<Option<u64>>],
    (resets, history): (usize, usize),
) -> (Option<Difference>, u64) {
    let mut first = None;
    let mut n = 0;
    for (c, (e, g)) in expected.iter().zip(got).enumerate().skip(FIRST_COMPARED) {
        for (k, p) in outs.iter().enumerate() {
            if !rules.differs(k, e, g) {
                continue;
            }
            n += 1;
            if first.is_none() {
                let inputs = (c.saturating_sub(history - 1)..=c)
                    .map(|i| (i, describe_inputs(ins, &stim[i], i < resets)))
                    .collect();
                first = Some(Difference {
                    cycle: c,
                    port: p.name.clone(),
                    fmt: p.fmt,
                    model: e[k],
                    rtl: g[k],
                    inputs,
                });
            }
        }
    }
    (first, n)
}

fn describe_inputs(ins: &[Port], v: &[u64], rst: bool) -> String {
    use std::fmt::Write as _;
    let mut s = format!("rst={}", u8::from(rst));
    for (p, x) in ins.iter().zip(v) {
        let _ = write!(s, " {}={}", p.name, show(*x, p.fmt));
    }
    s
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Its output is its input: an input of 8 does not fit the 3-bit output.
    #[derive(Clone)]
    pub(crate) struct Echo {
        pub(crate) x: Signal,
        pub(crate) y: Signal,
    }

    impl Module for Echo {
        fn kind(&self) -> &'static str {
            "echo"
        }
        fn eval(&mut self) {
            self.y.set_bits(self.x.bits());
        }
        fn tick(&mut self, _: bool) {}
        fn visit(&self, v: &mut dyn Visitor) {
            v.enter("echo", "echo");
            v.signal(Dir::Input, &self.x);
            v.signal(Dir::Output, &self.y);
            v.leave();
        }
    }

    /// The bench's checksum adds what the comparison looks at: an output under its mask, a
    /// qualified one only on a cycle its qualifier is 1; and its C++ says the same.
    #[test]
    fn the_compared_sum_takes_what_the_comparison_compares() {
        let rules = Rules {
            per_port: vec![(None, 0b111), (Some(2), u64::MAX), (None, 1)],
        };
        assert_eq!(rules.compared_sum(&[0xff, 5, 0]), 7);
        assert_eq!(rules.compared_sum(&[0xff, 5, 1]), 7 + 5 + 1);
        assert_eq!(rules.compared_sum(&[u64::MAX, u64::MAX, 1]), 7);
        let outs = [Port::uint("a", 8), Port::uint("b", 64), Port::uint("ok", 1)];
        assert_eq!(
            rules.compared_sum_cpp(&outs),
            "sum += (uint64_t)top.a & 7ULL; if (top.ok) sum += (uint64_t)top.b & 18446744073709551615ULL; sum += (uint64_t)top.ok & 1ULL; "
        );
    }

    /// A model that panics is named with the cycle it panicked in and why; the cycles before
    /// it ran.
    #[test]
    fn a_model_that_panics_says_in_which_cycle() {
        let make = || Echo {
            x: Signal::new("x", Format::uint(4)),
            y: Signal::new("y", Format::uint(3)),
        };
        let twin = Twin::new(make, |d, v| d.x.set_bits(v[0]));
        let mut model = twin.model().unwrap();
        let stim: Vec<Vec<u64>> = [1, 2, 7, 8, 3].iter().map(|&x| vec![x]).collect();
        let e = expect(&twin, model.as_mut(), &stim, 1).unwrap_err();
        let want =
            "echo: the model panicked in cycle 3: signal 'y' (u3, 3 bits): bits 0x8 does not fit";
        assert_eq!(e, want);
        assert!(e.contains(MODEL_PANICKED));
        let (expected, _) = expect(&twin, twin.model().unwrap().as_mut(), &stim[..3], 1).unwrap();
        assert_eq!(expected, [[1], [2], [7]]);
    }

    /// A stimulus line wider than any machine integer keeps every field in place: reset
    /// first, then each port MSB first, left-padded to whole hex digits.
    #[test]
    fn stimulus_lines_wider_than_128_bits_are_packed_whole() {
        let port = Port::uint;
        let ins = [port("a", 60), port("b", 60), port("c", 60), port("d", 3)];
        let x = (1u64 << 59) | 1;
        let stim = vec![vec![x, 0, x, 5]; RESET_CYCLES + 1];
        let dir = std::env::temp_dir().join(format!("texrtl-stim-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("stim.hex");
        rtl::write_stimulus(&f, &ins, &stim, RESET_CYCLES).unwrap();
        let text = std::fs::read_to_string(&f).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        // 1 + 183 = 184 bits = 46 digits; the last line is out of reset.
        let bits = |rst: bool| {
            let mut s = String::from(if rst { "1" } else { "0" });
            let f = |v: u64, w: usize| format!("{v:0w$b}");
            s += &(f(x, 60) + &f(0, 60) + &f(x, 60) + &f(5, 3));
            s
        };
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), RESET_CYCLES + 1);
        for (c, line) in lines.iter().enumerate() {
            assert_eq!(line.len(), 46, "{line}");
            let got: String = line
                .chars()
                .map(|d| format!("{:04b}", d.to_digit(16).unwrap()))
                .collect();
            assert_eq!(got, bits(c < RESET_CYCLES), "cycle {c}");
        }
    }
}
