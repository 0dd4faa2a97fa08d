//! One file per subcommand, each owning its clap arguments and its `run`.

pub mod ccc;
pub mod dram;
pub mod footprint;
pub mod mapchain;
pub mod mipmap;
pub mod new;
pub mod normals;
pub mod ptm;
pub mod render;
pub mod sweep;
pub mod tangents;
pub mod texram;
pub mod texread;
pub mod volume;
pub mod widths;

pub use verif::cli::{check_outputs, input, parse_finite, same_file, write_out, CmdError, Outputs};

/// A texture's `--border`: wrap, clamp, mirror or border:N. A tile border (`tile:T`) is for
/// the detail maps of a map chain (section 9), which these commands do not read: refused.
pub fn texture_border(s: &str) -> Result<units::texram::Border, CmdError> {
    let bad = || {
        let b = waves::output::shorten(s);
        input(format!(
            "--border {b}: wrap, clamp, mirror or border:N (N 0..=255)"
        ))
    };
    match units::texram::Border::parse(s) {
        Some(units::texram::Border::Tile(_)) | None => Err(bad()),
        Some(b) => Ok(b),
    }
}

/// A unit's run on a command's input: input the unit refuses is bad input, a waveform that
/// cannot be written bad output naming `--vcd` (exit 2), anything else a failed run (exit 1).
pub fn run_error(e: tb::RunError) -> CmdError {
    match e {
        tb::RunError::Input(m) => input(m),
        tb::RunError::Waveform(m) => input(format!("--vcd {m}")),
        tb::RunError::Failed(m) => CmdError::Failed(m),
    }
}

#[cfg(test)]
mod tests {
    use super::{run_error, CmdError};
    use tb::RunError;

    /// A unit's run that fails is exit 1 with its message; input the unit refuses is exit 2
    /// as it is, a waveform that cannot be written exit 2 naming `--vcd`.
    #[test]
    fn a_failed_run_is_exit_1_and_refused_input_exit_2() {
        let failed = run_error(RunError::Failed("watchdog: not idle by cycle 90".into()));
        assert!(matches!(failed, CmdError::Failed(m) if m == "watchdog: not idle by cycle 90"));
        let input = run_error(RunError::Input("frame 0 has 3 texels".into()));
        assert!(matches!(input, CmdError::Input(m) if m == "frame 0 has 3 texels"));
        let wave = run_error(RunError::Waveform("w.vcd: No space left on device".into()));
        assert!(matches!(wave, CmdError::Input(m) if m == "--vcd w.vcd: No space left on device"));
    }
}
