//! texrtl's testbenches of the texture units: one module per testbench, named after the unit it
//! verifies, each a [`verif::Testbench`] with its driver, monitor, golden comparison, integer
//! reference and coverage model; [`cosim`] the units' Verilog twins as co-simulation adapters;
//! [`vectors`] their bit-accuracy vectors; [`runs`] what the `texrtl` commands run on a user's
//! input; [`pictures`] their report pictures; and
//! [`project`] the one list that describes every unit to the framework.

pub mod biquadratic;
pub mod blend_adjust;
pub mod cosim;
pub mod derivative;
pub mod dram;
pub mod footprint;
pub mod footprint_normals;
pub mod frames;
pub mod mapchain;
pub mod maps;
pub mod mipmap;
pub mod normals;
pub mod pictures;
pub mod project;
pub mod ptm;
pub mod runs;
pub mod tangents;
pub mod texram;
pub mod texram_video;
pub mod texture;
pub mod vectors;
pub mod volume;

/// What stops a run of a unit on a command's input: the input does not fit the unit, or its
/// waveform could not be written (bad input or output: the command exits 2), or the run
/// itself failed (a wrong result, a hang, a protocol broken: exit 1).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RunError {
    /// The input or the parameters do not fit the unit (a texture or a map its memory
    /// refuses, a request outside the texture, a parameter out of range).
    Input(String),
    /// The waveform's file could not be created or written; the message names the file.
    Waveform(String),
    /// Anything else.
    Failed(String),
}

impl From<String> for RunError {
    fn from(s: String) -> Self {
        RunError::Failed(s)
    }
}

impl From<RunError> for String {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Input(m) | RunError::Waveform(m) | RunError::Failed(m) => m,
        }
    }
}
