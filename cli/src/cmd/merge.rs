//! `texrtl merge`: the summaries of every shard of a run combined into one.

use super::{write_out, CmdError};
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
pub fn run(a: &MergeArgs) -> Result<String, CmdError> {
    let ins: Vec<_> = a
        .summaries
        .iter()
        .map(|p| ("a summary", p.as_path()))
        .collect();
    super::check_outputs(&[("--out", a.out.as_path())], &ins)?;
    merge_cmd(&a.out, &a.summaries)
}

fn merge_cmd(out: &std::path::Path, paths: &[PathBuf]) -> Result<String, CmdError> {
    let m = tb::regress::merge(paths).map_err(CmdError::Input)?;
    let json = serde_json::to_vec_pretty(&m).map_err(|e| CmdError::Failed(e.to_string()))?;
    write_out(out, &json)?;
    let mut s = crate::report::table(&m.testbenches);
    s.push_str(&format!(
        "merged {} shards into {}",
        paths.len(),
        out.display()
    ));
    if m.passed {
        Ok(s)
    } else {
        crate::say(&format!("{s}\n"));
        Err(CmdError::Failed("merged run failed".into()))
    }
}
