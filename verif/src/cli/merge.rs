//! `merge`: the summaries of every shard of a run combined into one, concluded by the
//! project's testbenches as an unsharded run is.

use super::args::{all, clap_args, given, one, path};
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
    /// A folder for the merged run's report.md and pictures.
    pub report: Option<PathBuf>,
    /// A file for the merged run's JUnit XML.
    pub junit: Option<PathBuf>,
    /// Fail a testbench whose merged narrowings left a path untaken.
    pub require_numeric: bool,
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
            .arg(path(
                "report",
                "DIR",
                "Also write the merged run's report.md (with each failing job and the command that reproduces it) and its pictures into this folder",
            ))
            .arg(path(
                "junit",
                "FILE",
                "Also write the merged run's JUnit XML (one test case per job, as the unsharded run's but for the times)",
            ))
            .arg(
                Arg::new("require-numeric-coverage")
                    .long("require-numeric-coverage")
                    .action(ArgAction::SetTrue)
                    .help("Fail a testbench whose named narrowings, over all the shards, left a saturation, wrap or rounding tie never reached (unless the unit declares it unreachable)"),
            )
    }

    pub(super) fn read(m: &ArgMatches) -> Self {
        MergeArgs {
            out: given(m, "out"),
            summaries: all(m, "summaries"),
            report: one(m, "report"),
            junit: one(m, "junit"),
            require_numeric: m.get_flag("require-numeric-coverage"),
        }
    }
}

/// Merges; exit 1 when the merged run failed.
pub fn run(project: &Project, a: &MergeArgs) -> Result<String, CmdError> {
    let ins: Vec<_> = a
        .summaries
        .iter()
        .map(|p| ("summary", p.as_path()))
        .collect();
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.junit.as_deref().map(|j| ("--junit", j)));
    // Every output watched from here: bad input or an I/O error later (a report that cannot
    // be written) leaves none of them behind.
    let mut made = super::Outputs::check(&outs, &ins)?;
    if let Some(d) = &a.report {
        super::check_folder("--report", d)?;
        made.folder(d);
    }
    made.settle(merged(project, a))
}

/// The merge once its outputs are checked: the summary, the JUnit file, the report.
fn merged(project: &Project, a: &MergeArgs) -> Result<String, CmdError> {
    let shards = crate::regress::read_summaries(&a.summaries).map_err(CmdError::Input)?;
    let mut m = crate::regress::merge_shards(project, &shards).map_err(CmdError::Input)?;
    if a.require_numeric {
        m.testbenches
            .iter_mut()
            .for_each(crate::TbResult::require_numeric_coverage);
        m.passed = m.testbenches.iter().all(|r| r.passed);
    }
    let json = serde_json::to_vec_pretty(&m).map_err(|e| CmdError::Failed(e.to_string()))?;
    write_out(&a.out, &json)?;
    if let Some(j) = &a.junit {
        let jobs: Vec<_> = shards
            .iter()
            .flat_map(|(_, s)| s.jobs.iter().cloned())
            .collect();
        let cosim_jobs: Vec<_> = shards
            .iter()
            .flat_map(|(_, s)| s.cosim_jobs.iter().cloned())
            .collect();
        let xml = crate::junit::junit(project, &m, &jobs, &cosim_jobs).map_err(CmdError::Failed)?;
        write_out(j, xml.as_bytes())?;
    }
    if let Some(dir) = &a.report {
        report(project, dir, &m)?;
    }
    let mut s = crate::report::failing_lines(&m, 10);
    s.push_str(&crate::report::table(&m.testbenches));
    s.push_str(&crate::report::rtl_coverage_lines(&m, 10));
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

/// The merged run's report.md and pictures in `dir`.
fn report(
    project: &Project,
    dir: &std::path::Path,
    m: &crate::regress::Summary,
) -> Result<(), CmdError> {
    super::make_folder("--report", dir)?;
    crate::report::write_report(project, dir, m).map_err(CmdError::Input)
}
