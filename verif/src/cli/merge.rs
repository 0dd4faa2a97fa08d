//! `merge`: the summaries of every shard of a run combined into one, concluded by the
//! project's testbenches as an unsharded run is.

use super::args::{all, clap_args, given, path};
use super::{write_out, CmdError};
use crate::project::Project;
use clap::{value_parser, Arg, ArgAction, ArgMatches, Command};
use std::path::PathBuf;

/// Combine the summary.json files of all shards of a run into one.
#[derive(Debug)]
pub struct MergeArgs {
    /// Where to write the merged summary.json.
    pub out: PathBuf,
    /// The shards' summary.json files.
    pub summaries: Vec<PathBuf>,
}

clap_args!(MergeArgs);

impl MergeArgs {
    pub(super) fn augment(c: Command) -> Command {
        c.arg(path("out", "OUT", "Where to write the merged summary.json").required(true))
            .arg(
                Arg::new("summaries")
                    .value_name("SUMMARIES")
                    .value_parser(value_parser!(PathBuf))
                    .action(ArgAction::Append)
                    .num_args(1..)
                    .required(true)
                    .help("The shards' summary.json files"),
            )
    }

    pub(super) fn read(m: &ArgMatches) -> Self {
        MergeArgs {
            out: given(m, "out"),
            summaries: all(m, "summaries"),
        }
    }
}

/// Merges; exit 1 when the merged run failed.
pub fn run(project: &Project, a: &MergeArgs) -> Result<String, CmdError> {
    let ins: Vec<_> = a
        .summaries
        .iter()
        .map(|p| ("a summary", p.as_path()))
        .collect();
    super::check_outputs(&[("--out", a.out.as_path())], &ins)?;
    let m = crate::regress::merge(project, &a.summaries).map_err(CmdError::Input)?;
    let json = serde_json::to_vec_pretty(&m).map_err(|e| CmdError::Failed(e.to_string()))?;
    write_out(&a.out, &json)?;
    let mut s = crate::report::table(&m.testbenches);
    s.push_str(&format!(
        "merged {} shards into {}",
        a.summaries.len(),
        a.out.display()
    ));
    if m.passed {
        Ok(s)
    } else {
        super::say(&format!("{s}\n"));
        Err(CmdError::Failed("merged run failed".into()))
    }
}
