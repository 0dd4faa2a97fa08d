//! JUnit XML of a regression (`regress --junit FILE`, `merge --junit FILE`), the results file
//! Jenkins, GitLab and GitHub read: one test suite per testbench and per co-simulation row,
//! one test case per job (a configuration, or a twin's co-simulation, under one seed) with
//! its time, its seed and the command that runs it again alone, and a failure carrying its
//! first mismatch; a case per suite for the verdict on the merged result (coverage holes and
//! the testbench's own conclusions); and a suite of the checks that are not jobs (the
//! vectors), whose properties give the RTL's coverage by source file. Written through `quick-junit`,
//! within the element and attribute set of Jenkins' xUnit plugin, the strictest reader
//! (`verif/schema/junit.xsd`, checked in the tests): a case has no properties, so its job,
//! seed and command are the lines of its `system-out`.

use crate::cosim::Simulator;
use crate::jobs::{job_label, job_seed, JobResult};
use crate::project::Project;
use crate::regress::{cosim_seed, reproduce, CosimJob, Summary};
use crate::{Seed, TbResult};
use quick_junit::{NonSuccessKind, Property, Report, TestCase, TestCaseStatus, TestSuite};
use std::time::Duration;

/// A result's status: success, or a failure with its first message and the others below,
/// then the command that reproduces it (when there is one; a line of the result's that
/// already ends with it is left out, as a co-simulation row's is).
fn status(failed: bool, r: &TbResult, reproduce: Option<&str>) -> TestCaseStatus {
    if !failed {
        return TestCaseStatus::success();
    }
    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
    let said = |l: &&String| reproduce.is_none_or(|c| !l.ends_with(c));
    let lines: Vec<&String> = (r.mismatch_log.iter().chain(&r.failures))
        .filter(said)
        .collect();
    s.set_message(lines.first().map_or("failed", |l| l.as_str()));
    let mut text: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    text.extend(reproduce.map(|c| format!("reproduce: {c}")));
    s.set_description(text.join("\n"));
    s
}

/// A job case's `system-out`: the lines `job N`, `seed S` and `reproduce: COMMAND`.
pub fn case_output(job: u64, seed: Seed, reproduce: &str) -> String {
    format!("job {job}\nseed {seed}\nreproduce: {reproduce}")
}

/// The command that runs a check again alone: a co-simulation row `cosim/UNIT/SIM` as
/// `cosim` with its cycles and seed (its first failing seed's, as its line says, else the
/// run's), the vectors as `regress --only vectors`.
pub(crate) fn check_command(program: &str, seed: Seed, row: &TbResult) -> String {
    let mut parts = row.name.split('/');
    let cosim = match (parts.next(), parts.next(), parts.next()) {
        (Some(crate::regress::COSIM), Some(unit), Some(sim)) => {
            Simulator::parse(sim).map(|sim| (unit, sim))
        }
        _ => None,
    };
    let Some((unit, sim)) = cosim else {
        return format!("{program} regress --only {} --seed {seed}", row.name);
    };
    let said = row.mismatch_log.iter().find_map(|l| {
        let (_, c) = l.split_once(crate::regress::AGAIN)?;
        Some(c.to_string())
    });
    said.unwrap_or_else(|| crate::regress::cosim_command(program, unit, sim, seed))
}

/// quick-junit writes a `skipped` count on `testsuites`, which the xUnit plugin's schema does
/// not allow; texrtl skips no case, and each suite keeps its own count.
fn without_total_skipped(mut xml: String) -> String {
    let start = xml.find("<testsuites").unwrap_or(0);
    let end = xml[start..].find('>').map_or(start, |e| start + e);
    if let Some(k) = xml[start..end].find(" skipped=\"0\"") {
        xml.replace_range(start + k..start + k + " skipped=\"0\"".len(), "");
    }
    xml
}

/// `xml` without its `time="..."` attributes: what two runs of the same jobs agree on (a
/// merge's file and the unsharded run's, a run and its rerun).
pub fn timeless(xml: &str) -> String {
    let mut out = String::with_capacity(xml.len());
    let mut rest = xml;
    while let Some(k) = rest.find(" time=\"") {
        out.push_str(&rest[..k]);
        let after = &rest[k + " time=\"".len()..];
        rest = &after[after.find('"').map_or(after.len(), |e| e + 1)..];
    }
    out.push_str(rest);
    out
}

/// A row's suite: its `cases` (one per job), then its verdict on the merged result.
fn row_suite(row: &TbResult, cases: Vec<TestCase>) -> TestSuite {
    let mut suite = TestSuite::new(row.name.as_str());
    suite.add_property(Property::new("unit", row.unit.as_str()));
    suite.add_test_cases(cases);
    let mut verdict = TestCase::new("merged result", status(!row.passed, row, None));
    verdict.set_classname(row.name.as_str());
    suite.add_test_case(verdict);
    suite
}

/// The case of one job of `row`: its name, its result (failed or not), the command that runs
/// it again, its index, seed and time.
fn job_case(
    row: &str,
    name: String,
    failed: bool,
    r: &TbResult,
    job: (u64, Seed, f64),
    command: &str,
) -> TestCase {
    let (index, seed, seconds) = job;
    let mut case = TestCase::new(name, status(failed, r, Some(command)));
    case.set_classname(row)
        .set_time(Duration::from_secs_f64(seconds.max(0.0)))
        .set_system_out(case_output(index, seed, command));
    case
}

/// The suite of one testbench: its jobs, then its merged verdict.
fn suite(
    project: &Project,
    run: (Seed, u32, Option<usize>),
    row: &TbResult,
    jobs: &[&JobResult],
) -> TestSuite {
    let labels = project
        .registry()
        .get(&row.name)
        .map(|t| t.configurations())
        .unwrap_or_default();
    let cases = jobs.iter().map(|j| {
        let label = labels.get(j.configuration).map_or("?", String::as_str);
        let seed = job_seed(run.0, &row.name, j.configuration, j.repeat);
        let command = reproduce(project, run, j);
        let name = job_label(label, j.repeat);
        let failed = j.result.failed_itself();
        job_case(
            &row.name,
            name,
            failed,
            &j.result,
            (j.index, seed, j.seconds),
            &command,
        )
    });
    row_suite(row, cases.collect())
}

/// The suite of one co-simulation row: a case per seed's job, then the row's verdict.
fn cosim_suite(program: &str, seed: Seed, row: &TbResult, jobs: &[&CosimJob]) -> TestSuite {
    let cases = jobs.iter().map(|j| {
        let seed = cosim_seed(seed, j.repeat);
        let command = check_command(program, seed, &j.result);
        let name = job_label(&format!("{} cycles", j.cycles()), j.repeat);
        let failed = !j.result.passed;
        job_case(
            &row.name,
            name,
            failed,
            &j.result,
            (j.job, seed, j.seconds),
            &command,
        )
    });
    row_suite(row, cases.collect())
}

/// The JUnit XML of summary `s`, whose testbenches ran `jobs` and whose co-simulation rows
/// ran `cosim_jobs` (any order; each row's are taken in job order). A row none of whose jobs
/// is given (the vectors, a co-simulation row of a summary without its jobs) is one case of
/// the `checks` suite.
pub fn junit(
    project: &Project,
    s: &Summary,
    jobs: &[JobResult],
    cosim_jobs: &[CosimJob],
) -> Result<String, String> {
    let seed = Seed::parse(&s.seed)?;
    let run = (seed, s.seeds, s.count);
    let reg = project.registry();
    let mut report = Report::new(project.name());
    let mut checks = TestSuite::new("checks");
    for row in &s.testbenches {
        let mut its: Vec<&CosimJob> = cosim_jobs.iter().filter(|j| j.row == row.name).collect();
        if !its.is_empty() {
            its.sort_by_key(|j| j.job);
            report.add_test_suite(cosim_suite(project.name(), seed, row, &its));
            continue;
        }
        let Some(tb) = reg.get(&row.name) else {
            let command = check_command(project.name(), seed, row);
            let mut case =
                TestCase::new(row.name.as_str(), status(!row.passed, row, Some(&command)));
            case.set_classname("checks")
                .set_system_out(format!("seed {seed}\nreproduce: {command}"));
            checks.add_test_case(case);
            continue;
        };
        let position = reg.position(tb.name()).unwrap_or(0);
        let own = crate::jobs::testbench_jobs(tb, position, reg, s.seeds);
        let (lo, hi) = (
            own.first().map_or(0, |j| j.index),
            own.last().map_or(0, |j| j.index),
        );
        let mut mine: Vec<&JobResult> = jobs
            .iter()
            .filter(|j| (lo..=hi).contains(&j.index))
            .collect();
        mine.sort_by_key(|j| j.index);
        report.add_test_suite(suite(project, run, row, &mine));
    }
    // The RTL's coverage by source file (`--rtl-coverage`), one property a file: facts
    // about the run, not tests that pass or fail.
    for f in &s.rtl_coverage {
        let unreached: Vec<String> = f.unreached.iter().map(u32::to_string).collect();
        checks.add_property(Property::new(
            format!("rtl_coverage {}", f.file),
            format!(
                "blocks {} of {}, toggles {} of {}, lines never reached: {}",
                f.blocks.0,
                f.blocks.1,
                f.toggles.0,
                f.toggles.1,
                if unreached.is_empty() {
                    "none".into()
                } else {
                    unreached.join(", ")
                }
            ),
        ));
    }
    if !checks.test_cases.is_empty() || !checks.properties.is_empty() {
        report.add_test_suite(checks);
    }
    let xml = report.to_string().map_err(|e| e.to_string())?;
    Ok(without_total_skipped(xml))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A co-simulation row names its command in its own log; the failure says it once, as its
    /// `reproduce:` line, after the difference.
    #[test]
    fn a_failure_names_its_command_once() {
        let mut r = TbResult::new("cosim/u/icarus", "");
        let again = "p cosim --unit u --sim icarus --count 9 --seed 0x7";
        r.mismatch_log.push("cycle 4: port y differs".into());
        r.mismatch_log
            .push(format!("again alone, the RTL's internals: {again}"));
        let TestCaseStatus::NonSuccess {
            message,
            description,
            ..
        } = status(true, &r, Some(again))
        else {
            panic!("a failure");
        };
        let text = description.map(|d| d.to_string()).unwrap_or_default();
        assert_eq!(
            message.map(|m| m.to_string()).as_deref(),
            Some("cycle 4: port y differs")
        );
        assert_eq!(text, format!("cycle 4: port y differs\nreproduce: {again}"));
    }

    /// A row of several seeds that fails at a later one reproduces with that seed's command,
    /// not the run's; a row that passes names the run's, with one seed's cycles.
    #[test]
    fn a_co_simulation_row_reproduces_with_its_failing_seed() {
        let mut r = TbResult::new("cosim/u/icarus", "");
        r.cycles = 60_000;
        let run = "p cosim --unit u --sim icarus --count 20000 --seed 0x0000000000000007";
        assert_eq!(check_command("p", Seed(7), &r), run);
        let again = "p cosim --unit u --sim icarus --count 20000 --seed 0x1234";
        r.mismatch_log
            .push("[seed #2] cycle 4: port y differs".into());
        let said = format!("[seed #2] {}{again}", crate::regress::AGAIN);
        r.mismatch_log.push(said);
        assert_eq!(check_command("p", Seed(7), &r), again);
    }
}
