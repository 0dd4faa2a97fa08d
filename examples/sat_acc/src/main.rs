//! The command line: texrtl's (`regress`, `merge`, `cosim`, `vectors`, `bench`, `list`) on this
//! project.
fn main() -> std::process::ExitCode {
    verif::cli::main(&sat_acc::project())
}
