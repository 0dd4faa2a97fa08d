//! `merge`: the summaries of every shard of a run combined into one, concluded by the
//! project's testbenches as an unsharded run is.

use super::{write_out, CmdError};
use crate::project::Project;
use clap::Args;
use std::path::PathBuf;

/// Combine the summary.json files of all shards of a run into one.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// Where to write the merged summary.json.
    #[arg(long)]
    pub out: PathBuf,
    /// The shards' summary.json files.
    #[arg(required = true)]
    pub summaries: Vec<PathBuf>,
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
