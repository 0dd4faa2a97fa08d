//! The command line as a library: `regress` (the default), `merge`, `cosim`, `vectors`,
//! `bench` and `list`, for any [`Project`]. A program's `main` is one call:
//!
//! ```no_run
//! use verif::project::{Project, Unit};
//! fn main() -> std::process::ExitCode {
//!     let project = Project::new("mychip", env!("CARGO_PKG_VERSION"))
//!         .unit(Unit::new("alu_7", "the ALU of figure 7"));
//!     verif::cli::main(&project)
//! }
//! ```
//!
//! and [`main_with`] adds the program's own subcommands beside them. Exit status: 0 passed,
//! 1 a check failed (a testbench, a co-simulation, a vectors check), 2 bad input (one line on
//! stderr naming the option or file). The output files and their names are the same for every
//! project.

mod args;
mod bench;
mod cosim;
mod merge;
mod outputs;
mod regress;
mod vectors;

pub use bench::{run as bench, BenchArgs};
pub use cosim::CosimArgs;
pub use merge::MergeArgs;
pub use outputs::Outputs;
pub use regress::RegressArgs;
pub use vectors::VectorsArgs;

use crate::project::Project;
use clap::{Command, FromArgMatches, Subcommand};
use std::process::ExitCode;

/// The framework's subcommands and their one-line help.
const COMMANDS: [(&str, &str); 6] = [
    ("regress", "Run every testbench on built-in stimulus, check the vectors, co-simulate every twin (the default command)"),
    ("merge", "Combine the summary.json files of all shards of a run into one"),
    ("cosim", "Co-simulate a unit's model and Verilog (its twin, or --rtl FILE.v of yours): every output port compared on every cycle"),
    ("vectors", "Check, bless or export the bit-accuracy vectors"),
    ("bench", "Every twin against Verilator on the same stimulus: cycles per second, untraced and traced"),
    ("list", "The project's units: testbenches, twin, vectors"),
];

/// The command line: the framework's subcommands, the program's own (`E`) after them, and
/// `regress`'s options at the top for the default command.
fn command<E: Subcommand>(project: &Project, about: &'static str) -> Command {
    let name = project.name();
    let augment: [fn(Command) -> Command; 6] = [
        RegressArgs::augment,
        MergeArgs::augment,
        CosimArgs::augment,
        VectorsArgs::augment,
        BenchArgs::augment,
        |c| c,
    ];
    let mut cmd = Command::new(name)
        .bin_name(name)
        .args_conflicts_with_subcommands(true);
    for ((sub, help), add) in COMMANDS.into_iter().zip(augment) {
        cmd = cmd.subcommand(add(Command::new(sub).about(help)));
    }
    // After the program's subcommands, whose derive may set an about of its own; a program
    // that gives none is described by what it runs.
    let about = match about {
        "" => format!("{name}'s units: their testbenches, bit-accuracy vectors and co-simulations"),
        about => about.to_string(),
    };
    let cmd = E::augment_subcommands(RegressArgs::augment(cmd))
        .version(project.version())
        .about(about);
    negatives(cmd)
}

/// An option's value may be a negative number (`--lod -1.5`, `--seed -1`): it is read as the
/// value, so the option's own check refuses it naming the option, rather than as an unknown
/// option `-1`. (Any other value beginning with `-` is written `--dims=-inf`: taking every
/// such word as a value would take a forgotten value's next option, `--out --vcd w.vcd`.)
fn negatives(cmd: Command) -> Command {
    cmd.mut_args(|a| {
        if a.get_action().takes_values() {
            a.allow_negative_numbers(true)
        } else {
            a
        }
    })
    .mut_subcommands(negatives)
}

/// A program with no subcommands of its own.
#[derive(Debug)]
pub enum NoCommands {}

impl FromArgMatches for NoCommands {
    fn from_arg_matches(_: &clap::ArgMatches) -> Result<Self, clap::Error> {
        Err(clap::Error::new(clap::error::ErrorKind::InvalidSubcommand))
    }
    fn update_from_arg_matches(&mut self, _: &clap::ArgMatches) -> Result<(), clap::Error> {
        match *self {}
    }
}

impl Subcommand for NoCommands {
    fn augment_subcommands(c: Command) -> Command {
        c
    }
    fn augment_subcommands_for_update(c: Command) -> Command {
        c
    }
    fn has_subcommand(_: &str) -> bool {
        false
    }
}

/// Runs the command line of `project`: `regress`, `merge`, `cosim`, `vectors`, `bench`, `list`.
pub fn main(project: &Project) -> ExitCode {
    main_with(project, "", |c: NoCommands| match c {})
}

/// [`main`] with the program's own subcommands `E` beside the framework's, run by `own`;
/// `about` is the program's one-line description in `--help`.
pub fn main_with<E: Subcommand>(
    project: &Project,
    about: &'static str,
    own: impl FnOnce(E) -> ExitCode,
) -> ExitCode {
    let name = project.name();
    let m = match command::<E>(project, about).try_get_matches() {
        Ok(m) => m,
        Err(e) => return clap_error(name, e),
    };
    match m.subcommand() {
        None => regress::run(project, RegressArgs::read(&m)),
        Some(("regress", s)) => regress::run(project, RegressArgs::read(s)),
        Some(("merge", s)) => finish(name, merge::run(project, &MergeArgs::read(s))),
        Some(("cosim", s)) => finish(name, cosim::run(project, &CosimArgs::read(s))),
        Some(("vectors", s)) => finish(name, vectors::run(project, &VectorsArgs::read(s))),
        Some(("bench", s)) => finish(name, bench::run(project, &BenchArgs::read(s))),
        Some(("list", _)) => {
            say(&list(project));
            ExitCode::SUCCESS
        }
        Some(_) => match E::from_arg_matches(&m) {
            Ok(e) => own(e),
            Err(e) => clap_error(name, e),
        },
    }
}

/// Help and version exit 0; any other parse error is one line, exit 2.
fn clap_error(name: &str, e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        let _ = e.print();
        return ExitCode::SUCCESS;
    }
    fail(name, clap_message(name, &e))
}

/// A parse error as one line, naming the option.
fn clap_message(name: &str, e: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue};
    let mut text = e.to_string();
    // The value or argument refused, with a newline or other control character in it, shown
    // escaped (before the lines are split: the message is its first line).
    let kinds = [
        ContextKind::InvalidValue,
        ContextKind::InvalidArg,
        ContextKind::InvalidSubcommand,
    ];
    for kind in kinds {
        if let Some(ContextValue::String(v)) = e.get(kind) {
            let shown = waves::output::escape_controls(v);
            if shown != *v {
                text = text.replace(&format!("'{v}'"), &format!("'{shown}'"));
            }
        }
    }
    let mut lines = text.lines();
    let first = lines.next().unwrap_or("bad arguments");
    let first = first.strip_prefix("error: ").unwrap_or(first);
    // A list after a colon (the required options not given) joins the line.
    let listed: Vec<&str> = lines
        .take_while(|l| l.starts_with("  "))
        .map(str::trim)
        .collect();
    let first = match first.strip_suffix(':') {
        Some(head) if !listed.is_empty() => format!("{head}: {}", listed.join(", ")),
        _ => first.to_string(),
    };
    // clap quotes the argument it refuses: a long one is shortened, as every message's values.
    let first = waves::output::shorten_quoted(&first, '\'');
    let first = waves::output::shorten_message(&first, 200);
    // `--dims -inf` is read as the short options -i -n -f, `--dims "-- x"` as an unknown
    // option; `--dimz` is a misspelt option, with no hint.
    let long_option = |a: &str| {
        a.strip_prefix("--").is_some_and(|n| {
            !n.is_empty() && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '-')
        })
    };
    let value_like = matches!(e.get(ContextKind::InvalidArg),
        Some(ContextValue::String(a)) if a.starts_with('-') && !long_option(a));
    let hint = if e.kind() == clap::error::ErrorKind::UnknownArgument && value_like {
        "; a value beginning with '-' is written --OPTION=VALUE"
    } else {
        ""
    };
    format!("{first}{hint} (see {name} --help)")
}

/// A command's result as its exit status: its message on stdout (0), or one line on stderr
/// (2 for bad input, 1 for a failed check).
pub fn finish(name: &str, r: Result<String, CmdError>) -> ExitCode {
    match r {
        Ok(msg) => {
            say(&format!("{msg}\n"));
            ExitCode::SUCCESS
        }
        Err(CmdError::Input(e)) => fail(name, e),
        Err(CmdError::Failed(e)) => {
            eprintln!("{name}: {}", one_line(&e));
            ExitCode::from(1)
        }
    }
}

/// Writes to stdout; a closed pipe (`prog | head`) is not an error worth a panic.
pub fn say(s: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(s.as_bytes());
}

/// Bad input: one line on stderr, exit status 2.
pub fn fail(name: &str, msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("{name}: {}", one_line(&msg.to_string()));
    ExitCode::from(2)
}

/// A message kept on one short line: a newline or other control character in it (a file name
/// can hold one) is shown escaped, and a word (a value, a path) longer than 80 characters is
/// cut to its first 40 and last 30 (a path keeps its file name). A path that exists is kept
/// whole, to be copied: the waveform a failed run names, the folder a refusal is about.
pub fn one_line(s: &str) -> String {
    let escaped = waves::output::escape_controls(s);
    let punctuation: &[char] = &['(', ')', ',', ';', ':', '\'', '`'];
    escaped
        .split(' ')
        .map(|w| {
            let n = w.chars().count();
            if n <= 80 || std::path::Path::new(w.trim_matches(punctuation)).exists() {
                return w.to_string();
            }
            let head: String = w.chars().take(40).collect();
            let tail: String = w.chars().skip(n - 30).collect();
            format!("{head}...{tail}")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::one_line;

    #[test]
    fn messages_stay_one_short_line() {
        assert_eq!(one_line("a\nb\tc"), "a\\nb\\tc");
        let long = format!("/tmp/{}/file.csv: no such file", "d".repeat(200));
        let m = one_line(&long);
        assert!(
            m.len() < 100 && m.ends_with("/file.csv: no such file"),
            "{m}"
        );
        assert_eq!(one_line("short words stay"), "short words stay");
        // A path that exists is whole, however long: it is there to be opened.
        let dir = std::env::temp_dir().join(format!("{}-{}", "d".repeat(90), std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let said = format!("waveform: gtkwave {}/, the first", dir.display());
        let kept = one_line(&said);
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(kept, said);
    }

    fn parse_error(args: &[&str]) -> String {
        let p = crate::project::Project::new("chip", "1");
        let e = super::command::<super::NoCommands>(&p, "")
            .try_get_matches_from(args)
            .unwrap_err();
        super::clap_message("chip", &e)
    }

    #[test]
    fn a_parse_error_names_the_option_on_one_line() {
        assert_eq!(
            parse_error(&["chip", "cosim"]),
            "the following required arguments were not provided: --unit <UNIT> (see chip --help)"
        );
        let m = parse_error(&["chip", "vectors", "--unit", "u", "--check"]);
        assert!(m.contains("'--check'") && !m.contains('\n'), "{m}");
        let m = parse_error(&["chip", "--seed", &"9".repeat(500)]);
        assert!(m.starts_with("invalid value '") && m.len() < 200, "{m}");
        // A control character in the value is shown escaped, and the line is not cut there.
        let m = parse_error(&["chip", "--trace-window", "1\n..5"]);
        assert!(
            m.contains("'1\\n..5' for '--trace-window") && !m.contains('\n'),
            "{m}"
        );
        // A negative number is the option's value, refused by the option's own check.
        let m = parse_error(&["chip", "--count", "-5"]);
        assert!(m.starts_with("invalid value '-5' for '--count"), "{m}");
        let m = parse_error(&["chip", "--count", "-inf"]);
        assert!(
            m.contains("'-i'") && m.contains("written --OPTION=VALUE"),
            "{m}"
        );
        let m = parse_error(&["chip", "--count", "-- x"]);
        assert!(m.contains("written --OPTION=VALUE"), "{m}");
        let m = parse_error(&["chip", "--cuont", "5"]);
        assert!(!m.contains("written --OPTION=VALUE"), "{m}");
        let m = parse_error(&["chip", "--count=-inf"]);
        assert!(m.starts_with("invalid value '-inf' for '--count"), "{m}");
    }

    #[test]
    fn the_default_command_takes_regress_options_and_a_subcommand_its_own() {
        let p = crate::project::Project::new("chip", "1");
        let m = super::command::<super::NoCommands>(&p, "")
            .try_get_matches_from(["chip", "--count", "5", "-j", "2"])
            .unwrap();
        let a = super::RegressArgs::read(&m);
        assert_eq!((a.count, a.jobs), (Some(5), Some(2)));
        let m = super::command::<super::NoCommands>(&p, "")
            .try_get_matches_from(["chip", "bench", "--unit", "a", "--unit", "b"])
            .unwrap();
        let (sub, s) = m.subcommand().unwrap();
        assert_eq!(sub, "bench");
        assert_eq!(super::BenchArgs::read(s).unit, ["a", "b"]);
        assert!(super::command::<super::NoCommands>(&p, "")
            .try_get_matches_from(["chip", "--count", "5", "list"])
            .is_err());
    }

    #[test]
    fn a_folder_output_under_a_file_is_refused_naming_the_file() {
        let d = tempfile::Builder::new()
            .prefix("texrtl-cli-folder-")
            .tempdir()
            .unwrap();
        let file = d.path().join("notes.txt");
        std::fs::write(&file, "x").unwrap();
        let msg = |r: Result<(), super::CmdError>| match r {
            Err(super::CmdError::Input(m)) => m,
            other => panic!("{other:?}"),
        };
        let m = msg(super::check_folder("--out", &file.join("a/b")));
        assert_eq!(
            m,
            format!(
                "--out {}/a/b: {} is not a directory",
                file.display(),
                file.display()
            )
        );
        let m = msg(super::make_folder("--report", &file));
        assert!(
            m.ends_with("notes.txt: exists and is not a directory"),
            "{m}"
        );
        super::make_folder("--out", &d.path().join("x/y")).unwrap();
        assert!(d.path().join("x/y").is_dir());
        super::check_folder("--out", std::path::Path::new("")).unwrap();
    }
}

/// `list`: every unit with its testbenches, twin and vectors.
pub fn list(project: &Project) -> String {
    let mut s = String::new();
    for u in project.units() {
        let tbs = project.testbenches_of(u.name());
        let mut has = Vec::new();
        if !tbs.is_empty() {
            has.push(format!("testbench {}", tbs.join(", ")));
        }
        if let Some(t) = u.twin_unit() {
            let count =
                |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
            let (sources, lists) = (t.rtl().len(), t.file_lists().len());
            let files = match (sources, lists) {
                (n, 0) => count(n, "Verilog source"),
                (0, l) => count(l, "file list"),
                (n, l) => format!("{}, {}", count(n, "Verilog source"), count(l, "file list")),
            };
            has.push(format!("twin {} ({files})", t.top()));
        }
        match (u.vectors_fn(), u.no_vectors_reason()) {
            (Some(_), _) => has.push("vectors".to_string()),
            (None, Some(why)) => has.push(format!("no vectors ({why})")),
            (None, None) => {}
        }
        if u.pictures_fn().is_some() {
            has.push("pictures".to_string());
        }
        s.push_str(&format!(
            "{}: {}\n  {}\n",
            u.name(),
            u.about(),
            has.join("; ")
        ));
    }
    s
}

use std::path::Path;

/// A command's failure: bad input (exit 2) or a run that failed (exit 1).
#[derive(Debug)]
pub enum CmdError {
    /// Bad input: exit 2, the message names the option or file.
    Input(String),
    /// A check failed: exit 1.
    Failed(String),
}

impl std::fmt::Display for CmdError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CmdError::Input(m) | CmdError::Failed(m) => f.write_str(m),
        }
    }
}

impl From<String> for CmdError {
    fn from(s: String) -> Self {
        CmdError::Input(s)
    }
}

/// Bad input: a [`CmdError::Input`].
pub fn input(e: String) -> CmdError {
    CmdError::Input(e)
}

/// An output path must not be a directory and its directory must exist.
pub fn check_out(path: &Path) -> Result<(), CmdError> {
    if path.is_dir() {
        return Err(input(format!("{}: is a directory", path.display())));
    }
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() && !d.is_dir() => {
            let what = if d.symlink_metadata().is_ok() {
                "is not a directory"
            } else {
                "does not exist"
            };
            Err(input(format!(
                "{}: directory {} {what}",
                path.display(),
                d.display()
            )))
        }
        _ => Ok(()),
    }
}

/// A folder output of option `opt` (`--out DIR`), checked before any work: it is a folder or
/// is not there, and the nearest of its parents that is there is a folder (the ones that are
/// not there are made with it).
pub fn check_folder(opt: &str, path: &Path) -> Result<(), CmdError> {
    let there = |p: &Path| !p.as_os_str().is_empty() && p.symlink_metadata().is_ok();
    let Some(found) = path.ancestors().find(|p| there(p)) else {
        return Ok(());
    };
    match (found.is_dir(), found == path) {
        (true, _) => Ok(()),
        (false, true) => Err(input(format!(
            "{opt} {}: exists and is not a directory",
            path.display()
        ))),
        (false, false) => Err(input(format!(
            "{opt} {}: {} is not a directory",
            path.display(),
            found.display()
        ))),
    }
}

/// Makes folder output `path` of option `opt`, and its missing parents; a failure (no
/// permission, a read-only file system) is bad input naming both.
pub fn make_folder(opt: &str, path: &Path) -> Result<(), CmdError> {
    check_folder(opt, path)?;
    std::fs::create_dir_all(path).map_err(|e| {
        input(format!(
            "{opt} {}: cannot make the folder: {}",
            path.display(),
            waves::output::io_reason(&e)
        ))
    })
}

/// Whether two paths name one file: the same absolute path, or (when both exist) the same
/// file after links are resolved.
pub fn same_file(a: &Path, b: &Path) -> bool {
    let abs = |p: &Path| std::path::absolute(p).ok();
    if abs(a).is_some() && abs(a) == abs(b) {
        return true;
    }
    matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}

/// Every output of a command, checked before any work: each one's folder exists and it is
/// not a folder, no two are the same file, and none is one of the inputs (which it would
/// overwrite). `outs` and `ins` pair each path with its option's name, which the one-line
/// message names.
pub fn check_outputs(outs: &[(&str, &Path)], ins: &[(&str, &Path)]) -> Result<(), CmdError> {
    for (k, (opt, path)) in outs.iter().enumerate() {
        check_out(path).map_err(|e| match e {
            CmdError::Input(m) => input(format!("{opt} {m}")),
            other => other,
        })?;
        let earlier = outs[..k].iter().chain(ins);
        if let Some((other, _)) = earlier.clone().find(|(_, q)| same_file(path, q)) {
            let what = if ins.iter().any(|(o, _)| o == other) {
                "the input"
            } else {
                "the output"
            };
            return Err(input(format!(
                "{opt} {}: the same file as {what} {other}: choose another",
                path.display()
            )));
        }
    }
    Ok(())
}

/// Writes an output file atomically; an I/O error is bad input naming the file.
pub fn write_out(path: &Path, bytes: &[u8]) -> Result<(), CmdError> {
    check_out(path)?;
    waves::output::write_output(path, bytes).map_err(|e| input(e.to_string()))
}

/// A finite number (a clap value parser).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!(
            "'{}' is not a finite number",
            waves::output::shorten(s)
        )),
    }
}
