//! [`Twin`]: a [`CosimUnit`] made from a module and its Verilog, for the common case: the
//! unit's name is the module's kind, its ports are the module's top ports, and its stimulus
//! is corner-weighted random on every input ([`super::field`]) unless given.

use super::{
    field, top_ports, Clocking, Compare, CosimModel, CosimUnit, ModelSim, PathsFrom, Port,
    Unmodelled,
};
use crate::Seed;
use hdl::kernel::Module;
use std::path::PathBuf;

type Stimulus = dyn Fn(Seed, usize) -> Vec<Vec<u64>> + Send + Sync;

/// A module and its Verilog twin. The builder's methods are named apart from
/// [`CosimUnit`]'s (`sources` sets what `rtl()` returns), so both read unambiguously.
///
/// ```no_run
/// # use hdl::kernel::Module;
/// # fn demo<M: Module + Clone + Send + Sync + 'static>(make: fn() -> M, drive: fn(&mut M, &[u64])) {
/// let twin = verif::cosim::Twin::new(make, drive)
///     .sources([std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/unit.v")]);
/// # }
/// ```
///
/// `Twin::new` keeps the drive function as a function pointer, so the type is always
/// `Twin<M>` (a closure bound with `let` fits too). [`Twin::with_drive`] keeps the function's
/// own type instead, so the benchmark's cycle loop inlines it: faster, but the type can only
/// be returned as `impl CosimUnit`.
pub struct Twin<M, D = fn(&mut M, &[u64])> {
    make: fn() -> M,
    drive: D,
    name: &'static str,
    top: Option<&'static str>,
    rtl: Vec<PathBuf>,
    bench_rtl: Vec<PathBuf>,
    parameters: Vec<(&'static str, i64)>,
    clocking: Option<Clocking>,
    compare: Vec<Compare>,
    history: usize,
    stimulus: Option<Box<Stimulus>>,
    watch: Vec<Port>,
    watch_fn: fn(&M) -> Vec<u64>,
    unmodelled: Vec<Unmodelled>,
    include_dirs: Vec<PathBuf>,
    defines: Vec<String>,
    file_lists: Vec<(PathBuf, PathsFrom)>,
}

impl<M: Module + Clone + Send + Sync + 'static> Twin<M> {
    /// The module `make` builds, its inputs set from raw bits (input-port order) by `drive`;
    /// clocked by `clk` with `rst` active high (see [`Twin::clocked_by`]).
    pub fn new(make: fn() -> M, drive: fn(&mut M, &[u64])) -> Twin<M> {
        Twin::with_drive(make, drive)
    }
}

impl<M, D> Twin<M, D>
where
    M: Module + Clone + Send + Sync + 'static,
    D: Fn(&mut M, &[u64]) + Clone + Send + Sync + 'static,
{
    /// As [`Twin::new`], with `drive` kept as its own type (a function item or a closure), so
    /// that a benchmark run inlines it into the cycle loop.
    ///
    /// ```no_run
    /// # use hdl::kernel::{Module, Signal};
    /// # use verif::cosim::{CosimUnit, Twin};
    /// # fn demo<M: Module + Clone + Send + Sync + 'static>(make: fn() -> M, x: fn(&mut M) -> &mut Signal) {
    /// let twin = Twin::with_drive(make, move |m: &mut M, v: &[u64]| x(m).set_bits(v[0]));
    /// # let _: &dyn CosimUnit = &twin;
    /// # }
    /// ```
    pub fn with_drive(make: fn() -> M, drive: D) -> Twin<M, D> {
        Twin {
            name: make().kind(),
            top: None,
            make,
            drive,
            rtl: Vec::new(),
            bench_rtl: Vec::new(),
            parameters: Vec::new(),
            clocking: Some(Clocking::default()),
            compare: Vec::new(),
            history: 4,
            stimulus: None,
            watch: Vec::new(),
            watch_fn: |_| Vec::new(),
            unmodelled: Vec::new(),
            include_dirs: Vec::new(),
            defines: Vec::new(),
            file_lists: Vec::new(),
        }
    }

    /// Signals inside the model shown in the co-simulation's waveform, not compared
    /// ([`ModelSim::watch`]).
    pub fn watch(mut self, ports: Vec<Port>, f: fn(&M) -> Vec<u64>) -> Self {
        self.watch = ports;
        self.watch_fn = f;
        self
    }
    /// The Verilog module to instantiate when it is not named as the module's kind (a second
    /// model of the same design).
    pub fn top(mut self, module: &'static str) -> Self {
        self.top = Some(module);
        self
    }
    /// The twin's Verilog sources.
    pub fn sources(mut self, files: impl IntoIterator<Item = PathBuf>) -> Self {
        self.rtl = files.into_iter().collect();
        self
    }
    /// Testbench-side Verilog compiled with the twin or a user's `--rtl` (a wrapper, a
    /// behavioural memory).
    pub fn bench_sources(mut self, files: impl IntoIterator<Item = PathBuf>) -> Self {
        self.bench_rtl = files.into_iter().collect();
        self
    }
    /// A Verilog parameter of the configuration.
    pub fn parameter(mut self, name: &'static str, value: i64) -> Self {
        self.parameters.push((name, value));
        self
    }
    /// The clock and reset ports (`None`: combinational).
    pub fn clocked_by(mut self, c: Option<Clocking>) -> Self {
        self.clocking = c;
        self
    }
    /// A comparison rule for an output.
    pub fn compare_rule(mut self, c: Compare) -> Self {
        self.compare.push(c);
        self
    }
    /// Cycles of inputs shown with the first difference.
    pub fn show_history(mut self, cycles: usize) -> Self {
        self.history = cycles;
        self
    }
    /// An input of the Verilog top that the model lacks, driven with `bits` on every cycle
    /// (a debug or test input; see [`CosimUnit::unmodelled`]).
    pub fn tie(mut self, port: &str, bits: u64) -> Self {
        self.unmodelled
            .push(Unmodelled::Tied(port.to_string(), bits));
        self
    }
    /// An output of the Verilog top that the model lacks, left open and not compared.
    pub fn open(mut self, port: &str) -> Self {
        self.unmodelled.push(Unmodelled::Open(port.to_string()));
        self
    }
    /// A folder searched for `` `include `` files (each source's own folder always is).
    pub fn include_dir(mut self, dir: PathBuf) -> Self {
        self.include_dirs.push(dir);
        self
    }
    /// A preprocessor macro defined for the build: `NAME` or `NAME=VALUE`.
    pub fn define(mut self, macro_: &str) -> Self {
        self.defines.push(macro_.to_string());
        self
    }
    /// A file list of the twin's Verilog ([`super::FileList`]), read at each run, relative
    /// paths taken as `from` says: its sources after [`Twin::sources`]'.
    pub fn file_list(mut self, list: PathBuf, from: PathsFrom) -> Self {
        self.file_lists.push((list, from));
        self
    }
    /// The stimulus of `cycles` cycles from a seed (raw bits in input-port order), in place of
    /// corner-weighted random inputs.
    pub fn stimulus_from(
        mut self,
        f: impl Fn(Seed, usize) -> Vec<Vec<u64>> + Send + Sync + 'static,
    ) -> Self {
        self.stimulus = Some(Box::new(f));
        self
    }
}

/// Corner-weighted random values on every input port, cycle by cycle.
pub fn random_inputs(inputs: &[Port], seed: Seed, cycles: usize) -> Vec<Vec<u64>> {
    let mut st = crate::Stimulus::new(seed);
    let per_port: Vec<Vec<u64>> = inputs
        .iter()
        .map(|p| st.draw_n(&field(p.fmt.width()), cycles))
        .collect();
    (0..cycles)
        .map(|c| per_port.iter().map(|v| v[c]).collect())
        .collect()
}

impl<M, D> CosimUnit for Twin<M, D>
where
    M: Module + Clone + Send + Sync + 'static,
    D: Fn(&mut M, &[u64]) + Clone + Send + Sync + 'static,
{
    fn name(&self) -> &str {
        self.name
    }
    fn top(&self) -> &str {
        self.top.unwrap_or(self.name)
    }
    fn rtl(&self) -> Vec<PathBuf> {
        self.rtl.clone()
    }
    fn bench_rtl(&self) -> Vec<PathBuf> {
        self.bench_rtl.clone()
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        self.parameters.clone()
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        let m = ModelSim::new((self.make)(), self.drive.clone());
        Ok(Box::new(m.watch(self.watch.clone(), self.watch_fn)))
    }
    fn stimulus(&self, seed: Seed, cycles: usize) -> Vec<Vec<u64>> {
        match &self.stimulus {
            Some(f) => f(seed, cycles),
            None => random_inputs(&top_ports(&(self.make)()).inputs, seed, cycles),
        }
    }
    fn clocking(&self) -> Option<Clocking> {
        self.clocking.clone()
    }
    fn compare(&self) -> Vec<Compare> {
        self.compare.clone()
    }
    fn history(&self) -> usize {
        self.history
    }
    fn unmodelled(&self) -> Vec<Unmodelled> {
        self.unmodelled.clone()
    }
    fn include_dirs(&self) -> Vec<PathBuf> {
        self.include_dirs.clone()
    }
    fn defines(&self) -> Vec<String> {
        self.defines.clone()
    }
    fn file_lists(&self) -> Vec<(PathBuf, PathsFrom)> {
        self.file_lists.clone()
    }
}
