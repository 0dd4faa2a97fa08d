//! Co-simulation: a unit's Rust model and a Verilog implementation with the same ports (its
//! twin in `rtl/`, or the user's own) driven with the same inputs on every cycle, every output
//! port compared on every cycle, the first difference reported with its cycle, port, both
//! values and the inputs that led to it, and one waveform holding both.
//!
//! The RTL runs in a generated SystemVerilog testbench that replays the stimulus with
//! `$readmemh` and writes every output port every cycle with `$fwrite` (Verilator with
//! `--timing`, its runtime reused between builds, see `verilator.rs`, or Icarus `iverilog
//! -g2012`); the Rust side then compares. This costs a file per
//! run but needs no C++ glue or FFI, runs unchanged in both simulators, and leaves the
//! testbench, stimulus and outputs in the run's folder for the RTL engineer to rerun by hand.

use hdl::fx::{Format, Fx};
use hdl::kernel::{Dir, Module, Signal, Sim, Visitor};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

pub mod bump;
pub mod mipmap;
pub mod texmem;
pub mod vectors;
mod verilator;

pub use bump::*;
pub use mipmap::*;
pub use texmem::*;

/// A port of the unit's top: its name and format.
#[derive(Clone, Debug, PartialEq)]
pub struct Port {
    pub name: String,
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
    /// A benchmark run of the design as built (not as [`CosimModel::cycle`] left it): `stim`
    /// driven cycle by cycle ([`RESET_CYCLES`] in reset), no schedule check, no output read;
    /// untraced, or traced (every signal, no `real` companions). Returns the time of the cycle
    /// loop with the trace's final flush.
    fn bench(&self, stim: &[Vec<u64>], trace: BenchTrace) -> Result<std::time::Duration, String>;
}

/// What a benchmark run writes.
#[derive(Clone, Copy, Debug)]
pub enum BenchTrace<'a> {
    None,
    Vcd(&'a Path),
    /// FST written while simulating ([`waves::FstTracer`]).
    Fst(&'a Path),
}

/// The cycle loop of a benchmark run; its time, the trace finished.
fn bench_loop<M: Module, T: hdl::kernel::Trace>(
    mut sim: Sim<M, T>,
    stim: &[Vec<u64>],
    drive: fn(&mut M, &[u64]),
) -> std::io::Result<std::time::Duration> {
    // One contiguous array, as the Verilator side replays it: no pointer per cycle.
    let n = stim.first().map_or(0, Vec::len);
    let flat: Vec<u64> = stim.iter().flatten().copied().collect();
    assert_eq!(flat.len(), n * stim.len(), "every cycle drives every input");
    let t0 = std::time::Instant::now();
    for c in 0..stim.len() {
        sim.set_reset(c < RESET_CYCLES);
        drive(&mut sim.dut, &flat[c * n..(c + 1) * n]);
        sim.eval();
        sim.tick();
    }
    sim.finish()?;
    Ok(t0.elapsed())
}

/// A co-simulation model of a [`Module`] whose inputs `drive` sets from raw bits.
pub struct ModelSim<M: Module> {
    sim: Sim<M>,
    /// The design as built, for benchmark runs.
    pristine: M,
    drive: fn(&mut M, &[u64]),
    /// Values inside the model compared as further output ports (see [`ModelSim::probes`]).
    probes: Vec<Port>,
    probe: fn(&M) -> Vec<u64>,
}

impl<M: Module + Clone> ModelSim<M> {
    pub fn new(dut: M, drive: fn(&mut M, &[u64])) -> Self {
        ModelSim {
            pristine: dut.clone(),
            sim: Sim::new(dut).check_schedule(true),
            drive,
            probes: Vec::new(),
            probe: |_| Vec::new(),
        }
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

impl<M: Module + Clone> CosimModel for ModelSim<M> {
    fn ports(&self) -> (Vec<Port>, Vec<Port>) {
        let t = top_ports(&self.sim.dut);
        let mut outs = t.outputs;
        outs.extend(self.probes.iter().cloned());
        (t.inputs, outs)
    }
    fn cycle(&mut self, rst: bool, inputs: &[u64]) -> Vec<u64> {
        self.sim.set_reset(rst);
        (self.drive)(&mut self.sim.dut, inputs);
        self.sim.eval();
        let mut out = top_ports(&self.sim.dut).out_bits;
        out.extend((self.probe)(&self.sim.dut));
        self.sim.tick();
        out
    }
    fn bench(&self, stim: &[Vec<u64>], trace: BenchTrace) -> Result<std::time::Duration, String> {
        let dut = self.pristine.clone();
        let cfg = waves::TraceConfig {
            companions: false,
            ..Default::default()
        };
        let r = match trace {
            BenchTrace::None => bench_loop(Sim::new(dut), stim, self.drive),
            BenchTrace::Vcd(p) => {
                let title = format!("{} benchmark", self.pristine.kind());
                waves::VcdTracer::create(p, &title, cfg)
                    .and_then(|t| Sim::traced(dut, t))
                    .and_then(|s| bench_loop(s, stim, self.drive))
            }
            BenchTrace::Fst(p) => waves::FstTracer::create(p, cfg)
                .and_then(|t| Sim::traced(dut, t))
                .and_then(|s| bench_loop(s, stim, self.drive)),
        };
        r.map_err(|e| e.to_string())
    }
}

/// A unit that has a Verilog twin.
pub trait CosimUnit {
    /// The unit's name: its module in Verilog, its kind in the model.
    fn name(&self) -> &'static str;
    /// The Verilog module the testbench instantiates: the unit itself, or the unit with the
    /// behavioural parts the model holds beside it (control 607 with its DRAM 604).
    fn top(&self) -> &'static str {
        self.name()
    }
    /// The twin's sources, relative to the repository's `rtl/` (what `--rtl` replaces).
    fn rtl(&self) -> Vec<&'static str>;
    /// Testbench-side sources, relative to `rtl/`, always compiled (with the twin or the
    /// user's `--rtl`): the top wrapping the unit and the behavioural models it drives.
    fn bench_rtl(&self) -> Vec<&'static str> {
        Vec::new()
    }
    /// The Verilog parameters of this configuration (the model's parameters).
    fn parameters(&self) -> Vec<(&'static str, i64)>;
    fn model(&self) -> Result<Box<dyn CosimModel>, String>;
    /// Inputs of `cycles` cycles (raw bits in input-port order), seeded.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>>;
    /// Whether the twin has `clk` and `rst` ports (a combinational unit has none).
    fn clocked(&self) -> bool {
        true
    }
    /// Memory images the twin loads with `$readmemh` (file name, text): written into the
    /// run's folder, where the simulator runs, before it starts.
    fn memories(&self) -> Vec<(String, String)> {
        Vec::new()
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
    Verilator,
    Icarus,
}

impl Simulator {
    pub fn parse(s: &str) -> Option<Simulator> {
        match s {
            "verilator" => Some(Simulator::Verilator),
            "icarus" => Some(Simulator::Icarus),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Simulator::Verilator => "verilator",
            Simulator::Icarus => "icarus",
        }
    }
    /// `Err` names what to install when the simulator is not on the PATH.
    pub fn check_installed(self) -> Result<(), String> {
        let (exe, pkg) = match self {
            Simulator::Verilator => ("verilator", "verilator"),
            Simulator::Icarus => ("iverilog", "iverilog"),
        };
        match Command::new(exe).arg("-V").output() {
            Ok(_) => Ok(()),
            Err(_) => Err(format!(
                "{exe} not found: install it (Debian: apt-get install {pkg})"
            )),
        }
    }
}

/// The repository's `rtl/` folder (the twins).
pub fn rtl_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rtl")
}

/// What a co-simulation found.
#[derive(Clone, Debug)]
pub struct CosimResult {
    pub cycles: usize,
    /// The first difference, if any.
    pub mismatch: Option<Difference>,
    /// Differences counted over all cycles and ports.
    pub differences: u64,
    pub vcd: PathBuf,
}

/// The first cycle and port where the RTL and the model part.
#[derive(Clone, Debug)]
pub struct Difference {
    pub cycle: usize,
    pub port: String,
    pub fmt: Format,
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

/// Values of a `width`-bit field: its corners (0, 1, the largest, the sign boundary 2^(w-1)
/// and one below it) a quarter of the time, otherwise uniform. `width` is 1..=64, as every
/// unit's `validate` guarantees.
pub(crate) fn field(width: u32) -> impl proptest::strategy::Strategy<Value = u64> {
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

/// The units with a Verilog twin, by name, in their default configuration.
pub fn unit(name: &str) -> Result<Box<dyn CosimUnit>, String> {
    match name {
        "blend_adjust_153" => Ok(Box::new(BlendAdjustCosim(Default::default()))),
        "address_150" => Ok(Box::new(AddressCosim::default())),
        "replicate_152" => Ok(Box::new(ReplicateCosim {
            texel_bits: 8,
            bezier: false,
        })),
        "bilinear_65_68" => Ok(Box::new(BilinearCosim {
            texel_bits: 8,
            blend_bits: 8,
            bilinear_frac: None,
        })),
        "tangent_155" => Ok(Box::new(TangentCosim(Default::default()))),
        "rsqrt_156" => Ok(Box::new(RsqrtCosim(Default::default()))),
        "normal_156" => Ok(Box::new(NormalCosim(Default::default()))),
        "texel_fetch_151" => Ok(Box::new(TexelFetchCosim::new(
            Default::default(),
            16,
            16,
            1,
        ))),
        "normal_pipeline_fig7" => Ok(Box::new(PipelineCosim::new(Default::default(), 16, 16, 1))),
        "control_607" => Ok(Box::new(ControlCosim(Default::default()))),
        "cache_614" => Ok(Box::new(CacheCosim { tag_bits: 9 })),
        "mipmap_gen_816" => Ok(Box::new(MipmapCosim::new(
            units::mipmap::mipmap_gen_816::MipmapParams {
                width: 16,
                height: 16,
                scan: units::mipmap::mipmap_gen_816::Scan::Progressive,
                rounding: units::mipmap::mipmap_gen_816::Rounding::Round,
            },
        ))),
        "fill_engine_607" => Ok(Box::new(FillCosim {
            layout: units::texmem::layout::Layout::RowMajor,
            blocks: (16, 16),
            base: 0,
            dram: Default::default(),
        })),
        "lookahead_queue_607" => Ok(Box::new(LookaheadCosim {
            mode: Default::default(),
            blocks: (16, 16),
            frac_bits: 4,
        })),
        _ => Err(format!(
            "--unit {}: no Verilog twin (there are: {})",
            formats::shorten(name),
            UNITS.join(", ")
        )),
    }
}

/// The units with a Verilog twin.
pub const UNITS: [&str; 14] = [
    "address_150",
    "texel_fetch_151",
    "replicate_152",
    "blend_adjust_153",
    "bilinear_65_68",
    "tangent_155",
    "rsqrt_156",
    "normal_156",
    "normal_pipeline_fig7",
    "control_607",
    "lookahead_queue_607",
    "cache_614",
    "fill_engine_607",
    "mipmap_gen_816",
];

/// Runs `unit` in `sim` against `rtl` (its twin when empty) for `cycles` cycles in `dir`.
/// `Err` is for what stops the run (a simulator missing or failing, bad sources); a difference
/// is in the result.
pub fn run(
    unit: &dyn CosimUnit,
    sim: Simulator,
    rtl: &[PathBuf],
    cycles: usize,
    seed: verif::Seed,
    dir: &Path,
) -> Result<CosimResult, String> {
    run_with(unit, sim, rtl, &unit.stimulus(seed, cycles), dir)
}

/// Runs `unit` as [`run`] does on the given inputs of every cycle (`stim`, the first
/// [`RESET_CYCLES`] of them in reset): directed stimulus, such as the regression vectors.
pub fn run_with(
    unit: &dyn CosimUnit,
    sim: Simulator,
    rtl: &[PathBuf],
    stim: &[Vec<u64>],
    dir: &Path,
) -> Result<CosimResult, String> {
    let cycles = stim.len();
    if cycles == 0 {
        return Err(format!("{}: no cycles to simulate", unit.name()));
    }
    sim.check_installed()?;
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
    let mut model = unit.model()?;
    let (ins, outs) = model.ports();
    let rst = |c: usize| c < RESET_CYCLES;
    let expected: Vec<Vec<u64>> = (0..cycles).map(|c| model.cycle(rst(c), &stim[c])).collect();
    let mut sources: Vec<PathBuf> = if rtl.is_empty() {
        unit.rtl().iter().map(|f| rtl_dir().join(f)).collect()
    } else {
        rtl.to_vec()
    };
    sources.extend(unit.bench_rtl().iter().map(|f| rtl_dir().join(f)));
    let sources: Vec<PathBuf> = sources
        .iter()
        .map(|s| std::path::absolute(s).unwrap_or_else(|_| s.clone()))
        .collect();
    for s in &sources {
        if !s.is_file() {
            return Err(format!("{}: no such Verilog file", s.display()));
        }
    }
    write_stimulus(&dir.join("stim.hex"), &ins, stim)?;
    for (file, text) in unit.memories() {
        let path = dir.join(file);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let tb = testbench(unit, &ins, &outs, cycles, dir);
    std::fs::write(dir.join("tb.sv"), tb).map_err(|e| format!("{}: {e}", dir.display()))?;
    let got = simulate(sim, dir, &sources, &outs)?;
    if got.len() != cycles {
        return Err(format!(
            "{}: the RTL wrote {} cycles of outputs, {cycles} expected",
            sim.name(),
            got.len()
        ));
    }
    let (mismatch, differences) = compare(&ins, &outs, stim, &expected, &got);
    let vcd = dir.join(format!("{}_cosim.vcd", unit.name()));
    let defs: Vec<(&str, u32)> = outs
        .iter()
        .map(|p| (p.name.as_str(), p.fmt.width()))
        .collect();
    waves::compare::write(&vcd, unit.name(), &defs, &expected, &got)?;
    Ok(CosimResult {
        cycles,
        mismatch,
        differences,
        vcd,
    })
}

/// Every output port on every cycle from [`FIRST_COMPARED`]; the first difference with the
/// inputs of the cycles before it (up to four).
fn compare(
    ins: &[Port],
    outs: &[Port],
    stim: &[Vec<u64>],
    expected: &[Vec<u64>],
    got: &[Vec<Option<u64>>],
) -> (Option<Difference>, u64) {
    let mut first = None;
    let mut n = 0;
    for (c, (e, g)) in expected.iter().zip(got).enumerate().skip(FIRST_COMPARED) {
        for (k, p) in outs.iter().enumerate() {
            if g[k] == Some(e[k]) {
                continue;
            }
            n += 1;
            if first.is_none() {
                let inputs = (c.saturating_sub(3)..=c)
                    .map(|i| (i, describe_inputs(ins, &stim[i], i < RESET_CYCLES)))
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
    let mut s = format!("rst={}", u8::from(rst));
    for (p, x) in ins.iter().zip(v) {
        let _ = write!(s, " {}={}", p.name, show(*x, p.fmt));
    }
    s
}

/// One line per cycle: `{rst, inputs...}` packed MSB first, in hex.
fn write_stimulus(path: &Path, ins: &[Port], stim: &[Vec<u64>]) -> Result<(), String> {
    let width: u32 = 1 + ins.iter().map(|p| p.fmt.width()).sum::<u32>();
    let digits = width.div_ceil(4) as usize;
    let mut text = String::with_capacity(stim.len() * (digits + 1));
    // Bits MSB first, left-padded to whole hex digits (a line may be wider than any integer).
    let mut bits = Vec::with_capacity(digits * 4);
    for (c, v) in stim.iter().enumerate() {
        bits.clear();
        bits.resize(digits * 4 - width as usize, false);
        bits.push(c < RESET_CYCLES);
        for (p, x) in ins.iter().zip(v) {
            bits.extend((0..p.fmt.width()).rev().map(|k| (x >> k) & 1 == 1));
        }
        for nibble in bits.chunks(4) {
            let d = nibble.iter().fold(0u32, |d, b| (d << 1) | u32::from(*b));
            text.push(char::from_digit(d, 16).unwrap_or('0'));
        }
        text.push('\n');
    }
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// `[msb:0] ` for a port.
fn range(p: &Port) -> String {
    match p.fmt.width() {
        1 => String::new(),
        w => format!("[{}:0] ", w - 1),
    }
}

/// The generated SystemVerilog testbench: replays the stimulus, writes every output port every
/// cycle (after the inputs settle, before the clock edge, as the model is sampled).
fn testbench(
    unit: &dyn CosimUnit,
    ins: &[Port],
    outs: &[Port],
    cycles: usize,
    dir: &Path,
) -> String {
    let abs = |f: &str| std::path::absolute(dir.join(f)).unwrap_or_else(|_| dir.join(f));
    let width: u32 = 1 + ins.iter().map(|p| p.fmt.width()).sum::<u32>();
    let mut s = String::from("`timescale 1ns/1ps\n// Generated by texrtl cosim.\nmodule tb;\n");
    let _ = writeln!(s, "    reg clk = 1'b0;\n    reg rst;");
    for p in ins {
        let _ = writeln!(s, "    reg {}{};", range(p), p.name);
    }
    for p in outs {
        let _ = writeln!(s, "    wire {}{};", range(p), p.name);
    }
    // The testbench's own names carry a prefix, so no port of the unit can collide with them.
    let _ = writeln!(
        s,
        "    reg [{}:0] texrtl_stim [0:{}];",
        width - 1,
        cycles - 1
    );
    let params: Vec<String> = unit
        .parameters()
        .iter()
        .map(|(n, v)| format!(".{n}({v})"))
        .collect();
    let clock: &[&str] = if unit.clocked() { &["clk", "rst"] } else { &[] };
    let conns: Vec<String> = clock
        .iter()
        .map(|n| n.to_string())
        .chain(ins.iter().chain(outs).map(|p| p.name.clone()))
        .map(|n| format!(".{n}({n})"))
        .collect();
    let _ = writeln!(
        s,
        "    {} #({}) dut ({});",
        unit.top(),
        params.join(", "),
        conns.join(", ")
    );
    let names: Vec<&str> = ins.iter().map(|p| p.name.as_str()).collect();
    let fmt: Vec<&str> = outs.iter().map(|_| "%h").collect();
    let onames: Vec<&str> = outs.iter().map(|p| p.name.as_str()).collect();
    let _ = write!(
        s,
        "    integer texrtl_cycle, texrtl_fd;\n    initial begin\n        $readmemh(\"{}\", texrtl_stim);\n        texrtl_fd = $fopen(\"{}\", \"w\");\n        for (texrtl_cycle = 0; texrtl_cycle < {cycles}; texrtl_cycle = texrtl_cycle + 1) begin\n            {{rst, {}}} = texrtl_stim[texrtl_cycle];\n            #1;\n            $fwrite(texrtl_fd, \"{}\\n\", {});\n            clk = 1'b1;\n            #1;\n            clk = 1'b0;\n            #1;\n        end\n        $fclose(texrtl_fd);\n        $finish;\n    end\nendmodule\n",
        abs("stim.hex").display(),
        abs("rtl_out.hex").display(),
        names.join(", "),
        fmt.join(" "),
        onames.join(", ")
    );
    s
}

/// Builds and runs the testbench; reads the outputs back (`None` where the RTL drove x/z).
fn simulate(
    sim: Simulator,
    dir: &Path,
    sources: &[PathBuf],
    outs: &[Port],
) -> Result<Vec<Vec<Option<u64>>>, String> {
    let tb = dir.join("tb.sv");
    let run = |cmd: &mut Command, what: &str| -> Result<(), String> {
        let o = cmd.output().map_err(|e| format!("{what}: {e}"))?;
        if o.status.success() {
            return Ok(());
        }
        let err = String::from_utf8_lossy(&o.stderr);
        let first = err
            .lines()
            .find(|l| !l.trim().is_empty())
            .unwrap_or("failed");
        // The simulator's first message, cut at 200 characters (it names the file and line).
        let first: String = first.chars().take(200).collect();
        Err(format!("{what}: {first}"))
    };
    match sim {
        Simulator::Verilator => {
            let simv = verilator::build(&tb, sources, &dir.join("obj_dir"), &run)?;
            run(Command::new(simv).current_dir(dir), "simv")?;
        }
        Simulator::Icarus => {
            let vvp = dir.join("sim.vvp");
            let mut c = Command::new("iverilog");
            c.args(["-g2012", "-s", "tb", "-o"])
                .arg(&vvp)
                .arg(&tb)
                .args(sources);
            run(&mut c, "iverilog")?;
            run(
                Command::new("vvp").arg("-n").arg(&vvp).current_dir(dir),
                "vvp",
            )?;
        }
    }
    let path = dir.join("rtl_out.hex");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            if f.len() != outs.len() {
                return Err(format!(
                    "{}: '{}' has not {} ports",
                    path.display(),
                    formats::shorten(l),
                    outs.len()
                ));
            }
            Ok(f.iter().map(|x| u64::from_str_radix(x, 16).ok()).collect())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

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
        write_stimulus(&f, &ins, &stim).unwrap();
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
