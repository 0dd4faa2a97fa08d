//! The `texrtl` command: the framework's command line (`regress`, the default, `merge`,
//! `cosim`, `vectors`, `bench`, `list`) run on the texture project, and the texture units' own
//! commands, one module per subcommand in [`cmd`], each owning its clap arguments.

mod cmd;

use clap::Subcommand;
use std::process::ExitCode;

/// What `texrtl --help` says it is.
const ABOUT: &str = "Bit-exact, cycle-accurate models of texture-mapping hardware: testbenches, waveforms, golden models";

/// The texture units' own commands.
#[derive(Subcommand)]
enum Cmd {
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
    /// Write a user crate of your own: a unit, its golden model, testbench, Verilog twin,
    /// descriptor and vectors, depending on this texrtl by path.
    New(cmd::new::NewArgs),
    /// Error tables over bit widths, for choosing widths.
    #[command(subcommand)]
    Sweep(cmd::sweep::SweepCmd),
}

fn main() -> ExitCode {
    let project = tb::project::project();
    verif::cli::main_with(&project, ABOUT, run)
}

fn run(c: Cmd) -> ExitCode {
    let r = match c {
        Cmd::Normals(a) => cmd::normals::run(&a),
        Cmd::Render(a) => cmd::render::run(&a),
        Cmd::Mipmap(a) => cmd::mipmap::run(&a),
        Cmd::Dram(a) => cmd::dram::run(&a),
        Cmd::Ccc(c) => cmd::ccc::run(&c),
        Cmd::Texread(a) => cmd::texread::run(&a),
        Cmd::Texram(a) => cmd::texram::run(&a),
        Cmd::Footprint(a) => cmd::footprint::run(&a),
        Cmd::Volume(a) => cmd::volume::run(&a),
        Cmd::Mapchain(a) => cmd::mapchain::run(&a),
        Cmd::Ptm(c) => cmd::ptm::run(&c),
        Cmd::Tangents(a) => cmd::tangents::run(&a),
        Cmd::Sweep(c) => cmd::sweep::run(&c),
        Cmd::New(a) => cmd::new::run(&a),
    };
    verif::cli::finish("texrtl", r)
}
