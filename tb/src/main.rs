//! The `texrtl` command line. With no arguments it runs `texrtl regress`.

use clap::{Args, Parser, Subcommand};
use hdl::bump_params::{Border, Filter};
use hdl::mipmap::{Rounding, Scan};
use std::path::PathBuf;
use std::process::ExitCode;
use tb::commands::{self, parse_light, CmdError, MipmapArgs, NormalsArgs, RenderArgs, Widths};
use tb::regress::{regress, render, RegressConfig};
use verif::{Seed, Shard};
use waves::TraceConfig;

#[derive(Parser)]
#[command(
    name = "texrtl",
    version,
    about = "Bit-exact, cycle-accurate models of texture-mapping hardware: testbenches, waveforms, golden models",
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    cmd: Option<Cmd>,
    #[command(flatten)]
    regress: RegressArgs,
}

#[derive(Subcommand)]
enum CccCmd {
    /// PPM (P6/P3, sides multiples of 4) to .ccc.
    Encode {
        #[arg(long = "in")]
        input: PathBuf,
        #[arg(long)]
        out: PathBuf,
    },
    /// .ccc to a binary PPM.
    Decode {
        #[arg(long = "in")]
        input: PathBuf,
        #[arg(long)]
        out: PathBuf,
    },
}

#[derive(Subcommand)]
enum Cmd {
    /// Run every testbench on built-in stimulus (the default command).
    Regress(RegressArgs),
    /// Normals of a height map at given positions through the FIG. 7 pipeline.
    Normals(NormalsCli),
    /// Dot3-lit pictures: Blinn | B-spline (bit-exact) | golden | error heat map.
    Render(RenderCli),
    /// Mipmaps of video frames through the cycle-accurate generator of FIG. 14.
    Mipmap(MipmapCli),
    /// The DRAM 604 and its control unit 607 alone on a trace of word reads; JSON on stdout.
    Dram {
        /// CSV with header addr: 16-bit word addresses in decimal, read in order.
        #[arg(long)]
        trace: PathBuf,
        /// Words per page (DRAM row).
        #[arg(long, default_value_t = 512)]
        page_words: u32,
        /// Extra time of a page fault in ns (RAS# precharge plus RAS#-to-CAS#), a multiple of
        /// the 5 ns controller cycle, at least 10.
        #[arg(long, default_value_t = 30)]
        t_fault_ns: u32,
        /// 256k (256K x 16) or 1m (1M x 16).
        #[arg(long, default_value = "256k")]
        size: String,
        /// Waveform of the pins, page register and controller state.
        #[arg(long)]
        vcd: Option<PathBuf>,
    },
    /// CCC texture compression (Schilling & Knittel, section 3): encode a PPM, decode a .ccc.
    #[command(subcommand)]
    Ccc(CccCmd),
    /// Texture requests through the cycle-accurate memory path of Figure 6 (DRAM 604,
    /// control 607, CCC decode, cache 614 with lookahead, bilinear 622).
    Texread(tb::texcmd::TexreadArgs),
    /// Combine the summary.json files of all shards of a run into one.
    Merge {
        /// Where to write the merged summary.json.
        #[arg(long)]
        out: PathBuf,
        /// The shards' summary.json files.
        #[arg(required = true)]
        summaries: Vec<PathBuf>,
    },
    /// Export a unit's bit-accuracy vectors as $readmemh files for a Verilog testbench.
    Vectors {
        /// blend_adjust, normals or mipmap.
        #[arg(long)]
        unit: String,
        /// Directory for <unit>_stimulus.hex and <unit>_expected.hex.
        #[arg(long)]
        out: PathBuf,
    },
    /// Error tables over bit widths, for choosing widths.
    #[command(subcommand)]
    Sweep(SweepCmd),
}

#[derive(Subcommand)]
enum SweepCmd {
    /// Max and mean normal error against blend-factor bits and rsqrt table bits.
    Normals {
        /// Built-in height map: flat, steep, steps, noise, smooth, extremes, bumps.
        #[arg(long, default_value = "smooth")]
        map: String,
        /// Positions per configuration.
        #[arg(long, default_value_t = 2000)]
        samples: usize,
        #[arg(long, value_parser = Seed::parse, default_value = "0x5eed")]
        seed: Seed,
    },
}

/// Bit widths of the FIG. 7 pipeline.
#[derive(Args, Clone)]
struct WidthArgs {
    /// Blend-factor fraction bits F (4..=16).
    #[arg(long, default_value_t = 8)]
    blend_bits: u32,
    /// Height texel bits: 8 (uQ6.2) or 4 (uQ3.1).
    #[arg(long, default_value_t = 8)]
    texel_bits: u32,
    /// Inverse-square-root table index bits (3..=14).
    #[arg(long, default_value_t = 8)]
    rsqrt_table_bits: u32,
    /// Newton-Raphson iterations after the table (0..=3).
    #[arg(long, default_value_t = 1)]
    rsqrt_iterations: u32,
    /// Fraction bits of the normal components (8..=24).
    #[arg(long, default_value_t = 16)]
    out_frac: u32,
    /// Fraction bits of the tangents (8..=24).
    #[arg(long, default_value_t = 16)]
    tangent_frac: u32,
}

impl WidthArgs {
    fn widths(&self) -> Widths {
        Widths {
            blend_bits: self.blend_bits,
            texel_bits: self.texel_bits,
            table_bits: self.rsqrt_table_bits,
            iterations: self.rsqrt_iterations,
            out_frac: self.out_frac,
            tangent_frac: self.tangent_frac,
        }
    }
}

#[derive(Args)]
struct NormalsCli {
    /// Height map: 8-bit PGM, binary (P5) or ASCII (P2); texel values are raw heights.
    #[arg(long)]
    height: PathBuf,
    /// CSV with header u,v: positions in texel units.
    #[arg(long)]
    coords: PathBuf,
    /// Output CSV u,v,nx,ny,nz (exact decimal values of the fixed-point results).
    #[arg(long)]
    out: PathBuf,
    #[arg(long, default_value = "bspline", value_parser = parse_filter)]
    filter: Filter,
    /// Height scale factor (quantised to uQ8.8).
    #[arg(long, default_value_t = 1.0, value_parser = parse_finite)]
    scale: f64,
    /// wrap, clamp, mirror or constant[:N].
    #[arg(long, default_value = "wrap", value_parser = parse_border)]
    border: Border,
    /// Waveform of the run (with its .gtkw beside it).
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// Trilinear normals from this map and its next MIP level (2x2 box filter).
    #[arg(long)]
    trilinear: bool,
    /// Weight of the coarser level with --trilinear, in [0, 1).
    #[arg(long, default_value_t = 0.0, value_parser = parse_finite)]
    lod: f64,
    #[command(flatten)]
    widths: WidthArgs,
}

#[derive(Args)]
struct MipmapCli {
    /// A frame: 8-bit PGM with power-of-two sides up to 1024; repeat for a sequence.
    #[arg(long = "in", required = true)]
    inputs: Vec<PathBuf>,
    /// Output directory: levelK.pgm (frameF/levelK.pgm for several frames) and stats.json.
    #[arg(long)]
    out: PathBuf,
    /// progressive, interlaced-top (even lines first) or interlaced-bottom.
    #[arg(long, default_value = "progressive", value_parser = parse_scan)]
    scan: Scan,
    /// round ((a+b+c+d+2)>>2) or truncate (>>2).
    #[arg(long, default_value = "round", value_parser = parse_rounding)]
    rounding: Rounding,
    /// Waveform of the run (with its .gtkw beside it).
    #[arg(long)]
    vcd: Option<PathBuf>,
}

fn parse_scan(s: &str) -> Result<Scan, String> {
    s.parse()
}
fn parse_rounding(s: &str) -> Result<Rounding, String> {
    s.parse()
}

#[derive(Args)]
struct RenderCli {
    /// Height map: 8-bit PGM.
    #[arg(long)]
    height: PathBuf,
    /// Output PNG.
    #[arg(long)]
    out: PathBuf,
    /// Light direction X,Y,Z (normalised).
    #[arg(long, default_value = "1,1,2", value_parser = parse_light)]
    light: [f64; 3],
    /// Height scale factor.
    #[arg(long, default_value_t = 1.0, value_parser = parse_finite)]
    scale: f64,
    /// Pixels per texel (a power of two up to 64).
    #[arg(long, default_value_t = 4)]
    zoom: u32,
    #[command(flatten)]
    widths: WidthArgs,
}

fn parse_filter(s: &str) -> Result<Filter, String> {
    s.parse()
}
fn parse_border(s: &str) -> Result<Border, String> {
    s.parse()
}
fn parse_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{s}' is not a finite number")),
    }
}

#[derive(Args, Clone)]
struct RegressArgs {
    /// Directory for VCDs, .gtkw files and summary.json.
    #[arg(long, default_value = "target/texrtl")]
    out: PathBuf,
    /// Stimulus seed (hex 0x... or decimal); the run prints it, and the same seed replays it.
    #[arg(long, value_parser = Seed::parse, default_value = "0x7e47")]
    seed: Seed,
    /// Write no waveforms.
    #[arg(long)]
    no_vcd: bool,
    /// Trace scopes down to this depth (0 = clock, reset and golden probes only; 1 = each
    /// testbench's top unit; ...).
    #[arg(long)]
    trace_depth: Option<usize>,
    /// Trace only signals whose hierarchical name (e.g. tb.ba.u0) matches this glob; repeatable.
    #[arg(long = "trace-filter")]
    trace_filter: Vec<String>,
    /// Trace only cycles START..END.
    #[arg(long, value_parser = parse_window)]
    trace_window: Option<(u64, u64)>,
    /// Clock period in picoseconds shown in every waveform (even, >= 2; default: each
    /// testbench's own clock, 10 ns for the FIG. 7 and FIG. 14 units, 5 ns for the memory path).
    #[arg(long)]
    period_ps: Option<u64>,
    /// Rewrite the bit-accuracy vectors under golden/vectors/ after a deliberate change, and
    /// print what changed.
    #[arg(long)]
    bless: bool,
    /// Run only shard I of N (configurations dealt round-robin; merge the summaries with
    /// `texrtl merge`).
    #[arg(long, value_parser = Shard::parse, default_value = "1/1")]
    shard: Shard,
    /// Random transactions per configuration (default: each testbench's own).
    #[arg(long)]
    count: Option<usize>,
    /// Also write every waveform as FST (compact; open with `gtkwave X.fst X.gtkw`).
    #[arg(long)]
    fst: bool,
    /// Run only this testbench (repeatable; `vectors` is the bit-accuracy check).
    #[arg(long)]
    only: Vec<String>,
    /// List the testbenches with their configurations and what --count counts, and exit.
    #[arg(long)]
    list: bool,
    /// Run the kernel's schedule check (every cycle evaluated twice) in every testbench.
    #[arg(long)]
    check_schedule: bool,
}

/// `texrtl regress --list`.
fn list_testbenches() -> String {
    let mut s = String::new();
    for tb in tb::regress::registry().iter() {
        let c = tb.configurations();
        s.push_str(&format!(
            "{}: {}
  --count: {} (default {})
  {} configurations; traced: {}
",
            tb.name(),
            tb.unit(),
            tb.count_unit(),
            tb.default_count(),
            c.len(),
            c.get(tb.traced()).map_or("none", String::as_str)
        ));
        for (i, l) in c.iter().enumerate() {
            s.push_str(&format!(
                "    {i:>3}  {l}
"
            ));
        }
    }
    s.push_str(&format!(
        "{}: the bit-accuracy vectors under golden/vectors/ (fixed stimuli)
",
        tb::regress::VECTORS
    ));
    s
}

fn parse_window(s: &str) -> Result<(u64, u64), String> {
    let bad = || format!("'{s}' is not a window START..END of cycles");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let (a, b): (u64, u64) = (a.parse().map_err(|_| bad())?, b.parse().map_err(|_| bad())?);
    if a >= b {
        return Err(format!("window {a}..{b} is empty"));
    }
    Ok((a, b))
}

/// Writes to stdout; a closed pipe (`texrtl | head`) is not an error worth a panic.
fn say(s: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(s.as_bytes());
}

/// Bad input: one line, exit status 2.
fn fail(msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("texrtl: {msg}");
    ExitCode::from(2)
}

fn run_regress(a: RegressArgs) -> ExitCode {
    if a.list {
        say(&list_testbenches());
        return ExitCode::SUCCESS;
    }
    if a.out.exists() && !a.out.is_dir() {
        return fail(format!(
            "--out {}: exists and is not a directory",
            a.out.display()
        ));
    }
    let bless = a.bless;
    let cfg = RegressConfig {
        out: a.out,
        seed: a.seed,
        vcd: !a.no_vcd,
        trace: TraceConfig {
            period_ps: a.period_ps.unwrap_or(10_000),
            max_depth: a.trace_depth,
            filters: a.trace_filter,
            window: a.trace_window,
            companions: true,
        },
        period_ps: a.period_ps,
        shard: a.shard,
        count: a.count,
        fst: a.fst,
        only: a.only,
        check_schedule: a.check_schedule,
    };
    if let Err(e) = cfg.trace.validate() {
        return fail(format!("--period-ps/--trace-window: {e}"));
    }
    if let Err(e) = cfg.validate(&tb::regress::registry()) {
        return fail(e);
    }
    eprintln!(
        "texrtl regress: seed {} (replay with --seed {})",
        cfg.seed, cfg.seed
    );
    match regress(&cfg) {
        Ok(results) => {
            say(&render(&results, &cfg));
            if bless {
                match tb::vectors::bless(&tb::vectors::vectors_dir()) {
                    Ok(changed) if changed.is_empty() => say("vectors: unchanged\n"),
                    Ok(changed) => {
                        for c in changed {
                            say(&format!("vectors blessed: {c}\n"));
                        }
                    }
                    Err(e) => return fail(e),
                }
            }
            if results.iter().all(|r| r.passed) {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Err(e) => fail(e),
    }
}

fn dram_cmd(
    trace: &std::path::Path,
    page_words: u32,
    t_fault_ns: u32,
    size: &str,
    vcd: Option<PathBuf>,
) -> Result<String, CmdError> {
    let words: u64 = match size {
        "256k" => 256 * 1024,
        "1m" => 1024 * 1024,
        _ => return Err(CmdError::Input(format!("--size {size}: 256k or 1m"))),
    };
    let base = hdl::dram::DramParams::default();
    if !t_fault_ns.is_multiple_of(base.cycle_ns) || t_fault_ns < 2 * base.cycle_ns {
        return Err(CmdError::Input(format!(
            "--t-fault-ns {t_fault_ns}: a multiple of the {} ns cycle, at least {}",
            base.cycle_ns,
            2 * base.cycle_ns
        )));
    }
    if page_words == 0 || !words.is_multiple_of(u64::from(page_words)) {
        return Err(CmdError::Input(format!(
            "--page-words {page_words}: must divide {words}"
        )));
    }
    let fault = t_fault_ns / base.cycle_ns;
    let p = hdl::dram::DramParams {
        cols: page_words,
        rows: (words / u64::from(page_words)) as u32,
        t_rp: fault / 2,
        t_rcd: fault - fault / 2,
        ..base
    };
    p.validate()
        .map_err(|e| CmdError::Input(format!("--page-words {page_words}: {e}")))?;
    let addrs = tb::dram::read_trace(trace, p.words()).map_err(CmdError::Input)?;
    if let Some(v) = &vcd {
        if v.is_dir() {
            return Err(CmdError::Input(format!("{}: is a directory", v.display())));
        }
    }
    let st = tb::dram::run_trace(p, &addrs, vcd).map_err(CmdError::Failed)?;
    if st.violations != 0 || st.data_errors != 0 {
        return Err(CmdError::Failed(format!(
            "{} timing violations, {} data errors",
            st.violations, st.data_errors
        )));
    }
    serde_json::to_string_pretty(&st).map_err(|e| CmdError::Failed(e.to_string()))
}

fn merge_cmd(out: &std::path::Path, paths: &[PathBuf]) -> Result<String, CmdError> {
    let m = tb::regress::merge(paths).map_err(CmdError::Input)?;
    if out.is_dir() {
        return Err(CmdError::Input(format!(
            "{}: is a directory",
            out.display()
        )));
    }
    let json = serde_json::to_vec_pretty(&m).map_err(|e| CmdError::Failed(e.to_string()))?;
    tb::report::write_atomic(out, &json)
        .map_err(|e| CmdError::Input(format!("{}: {e}", out.display())))?;
    let mut s = tb::report::table(&m.testbenches);
    s.push_str(&format!(
        "merged {} shards into {}",
        paths.len(),
        out.display()
    ));
    if m.passed {
        Ok(s)
    } else {
        say(&format!("{s}\n"));
        Err(CmdError::Failed("merged run failed".into()))
    }
}

fn vectors_cmd(unit: &str, out: &std::path::Path) -> Result<String, CmdError> {
    let v = tb::vectors::unit_vectors(unit).map_err(CmdError::Input)?;
    if out.exists() && !out.is_dir() {
        return Err(CmdError::Input(format!(
            "{}: exists and is not a directory",
            out.display()
        )));
    }
    let files = v
        .write_readmemh(out)
        .map_err(|e| CmdError::Input(format!("{}: {e}", out.display())))?;
    let names: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
    Ok(format!(
        "{} vectors of {}: {}",
        v.rows.len(),
        unit,
        names.join(", ")
    ))
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("bad arguments");
            let first = first.strip_prefix("error: ").unwrap_or(first);
            return fail(format!("{first} (see texrtl --help)"));
        }
    };
    let r = match cli.cmd {
        Some(Cmd::Regress(a)) => return run_regress(a),
        None => return run_regress(cli.regress),
        Some(Cmd::Normals(a)) => commands::normals(&NormalsArgs {
            height: a.height,
            coords: a.coords,
            out: a.out,
            filter: a.filter,
            scale: a.scale,
            border: a.border,
            vcd: a.vcd,
            trilinear: a.trilinear,
            lod: a.lod,
            widths: a.widths.widths(),
        }),
        Some(Cmd::Render(a)) => commands::render(&RenderArgs {
            height: a.height,
            out: a.out,
            light: a.light,
            scale: a.scale,
            zoom: a.zoom,
            widths: a.widths.widths(),
        }),
        Some(Cmd::Vectors { unit, out }) => vectors_cmd(&unit, &out),
        Some(Cmd::Merge { out, summaries }) => merge_cmd(&out, &summaries),
        Some(Cmd::Dram {
            trace,
            page_words,
            t_fault_ns,
            size,
            vcd,
        }) => dram_cmd(&trace, page_words, t_fault_ns, &size, vcd),
        Some(Cmd::Ccc(CccCmd::Encode { input, out })) => tb::texcmd::ccc_encode(&input, &out),
        Some(Cmd::Ccc(CccCmd::Decode { input, out })) => tb::texcmd::ccc_decode(&input, &out),
        Some(Cmd::Texread(a)) => tb::texcmd::texread(&a),
        Some(Cmd::Mipmap(a)) => commands::mipmap(&MipmapArgs {
            inputs: a.inputs,
            out: a.out,
            scan: a.scan,
            rounding: a.rounding,
            vcd: a.vcd,
        }),
        Some(Cmd::Sweep(SweepCmd::Normals { map, samples, seed })) => {
            commands::sweep_normals(&map, samples, seed)
        }
    };
    match r {
        Ok(msg) => {
            say(&format!("{msg}\n"));
            ExitCode::SUCCESS
        }
        Err(CmdError::Input(e)) => fail(e),
        Err(CmdError::Failed(e)) => {
            eprintln!("texrtl: {e}");
            ExitCode::from(1)
        }
    }
}
