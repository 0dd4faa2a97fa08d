//! The `texrtl` command line: one module per subcommand in [`cmd`], each owning its clap
//! arguments; the report and its plots. With no arguments it runs `texrtl regress`.

mod cmd;
mod plots;
mod report;

use clap::{Parser, Subcommand};
use cmd::CmdError;
use std::process::ExitCode;

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
    regress: cmd::regress::RegressArgs,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run every testbench on built-in stimulus (the default command).
    Regress(cmd::regress::RegressArgs),
    /// Normals of a height map at given positions through the FIG. 7 pipeline.
    Normals(cmd::normals::NormalsArgs),
    /// Dot3-lit pictures: Blinn | B-spline (bit-exact) | golden | error heat map.
    Render(cmd::render::RenderArgs),
    /// Mipmaps of video frames through the cycle-accurate generator of FIG. 14.
    Mipmap(cmd::mipmap::MipmapArgs),
    /// The DRAM 604 and its control unit 607 alone on a trace of word reads; JSON on stdout.
    Dram(cmd::dram::DramArgs),
    /// CCC texture compression (Schilling & Knittel, section 3): encode a PPM, decode a .ccc.
    #[command(subcommand)]
    Ccc(cmd::ccc::CccCmd),
    /// Texture requests through the cycle-accurate memory path of Figure 6 (DRAM 604,
    /// control 607, CCC decode, cache 614 with lookahead, bilinear 622).
    #[command(after_help = cmd::texread::STATS_HELP)]
    Texread(cmd::texread::TexreadArgs),
    Texram(cmd::texram::TexramArgs),
    Footprint(cmd::footprint::FootprintArgs),
    Volume(cmd::volume::VolumeArgs),
    /// Pixels through the map chain walker of 812 (section 14): linked texture, offset,
    /// detail, reflectance and environment maps, eqs 5-7.
    Mapchain(cmd::mapchain::MapchainArgs),
    /// PTM micro-occlusion (001): fit a height map's occlusion under a dome of lights through
    /// the fitter 604; evaluate a PTM through the light shader 608.
    #[command(subcommand)]
    Ptm(cmd::ptm::PtmCmd),
    /// Tangent frames of an OBJ mesh per face corner in the 3ds Max, Maya or DirectX way (003).
    Tangents(cmd::tangents::TangentsArgs),
    /// Co-simulate a unit's model and Verilog (its twin in rtl/, or --rtl FILE.v of yours):
    /// every output port compared on every cycle.
    Cosim(cmd::cosim::CosimArgs),
    /// Combine the summary.json files of all shards of a run into one.
    Merge(cmd::merge::MergeArgs),
    /// Export a unit's bit-accuracy vectors as $readmemh files for a Verilog testbench.
    Vectors(cmd::vectors::VectorsArgs),
    /// Error tables over bit widths, for choosing widths.
    #[command(subcommand)]
    Sweep(cmd::sweep::SweepCmd),
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
        Some(Cmd::Regress(a)) => return cmd::regress::run(a),
        None => return cmd::regress::run(cli.regress),
        Some(Cmd::Normals(a)) => cmd::normals::run(&a),
        Some(Cmd::Render(a)) => cmd::render::run(&a),
        Some(Cmd::Mipmap(a)) => cmd::mipmap::run(&a),
        Some(Cmd::Dram(a)) => cmd::dram::run(&a),
        Some(Cmd::Ccc(c)) => cmd::ccc::run(&c),
        Some(Cmd::Texread(a)) => cmd::texread::run(&a),
        Some(Cmd::Texram(a)) => cmd::texram::run(&a),
        Some(Cmd::Footprint(a)) => cmd::footprint::run(&a),
        Some(Cmd::Volume(a)) => cmd::volume::run(&a),
        Some(Cmd::Mapchain(a)) => cmd::mapchain::run(&a),
        Some(Cmd::Ptm(c)) => cmd::ptm::run(&c),
        Some(Cmd::Tangents(a)) => cmd::tangents::run(&a),
        Some(Cmd::Cosim(a)) => cmd::cosim::run(&a),
        Some(Cmd::Merge(a)) => cmd::merge::run(&a),
        Some(Cmd::Vectors(a)) => cmd::vectors::run(&a),
        Some(Cmd::Sweep(c)) => cmd::sweep::run(&c),
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
