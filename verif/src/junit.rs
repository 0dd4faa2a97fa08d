//! JUnit XML of a regression (`regress --junit FILE`, `merge --junit FILE`), the results file
//! Jenkins, GitLab and GitHub read: one test suite per testbench, one test case per job (a
//! configuration under one seed) with its time, its seed and the command that runs it again
//! alone, and a failure carrying its first mismatch; a case per testbench for the verdict on
//! the merged result (coverage holes and the testbench's own conclusions); and a suite of the
//! checks that are not jobs (the vectors, each co-simulation). Written through `quick-junit`.

use crate::jobs::{job_label, job_seed, JobResult};
use crate::project::Project;
use crate::regress::{reproduce, Summary};
use crate::{Seed, TbResult};
use quick_junit::{NonSuccessKind, Property, Report, TestCase, TestCaseStatus, TestSuite};
use std::time::Duration;

/// A result's status: success, or a failure with its first message and the others below.
fn status(failed: bool, r: &TbResult) -> TestCaseStatus {
    if !failed {
        return TestCaseStatus::success();
    }
    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
    let lines: Vec<&String> = r.mismatch_log.iter().chain(&r.failures).collect();
    s.set_message(lines.first().map_or("failed", |l| l.as_str()));
    s.set_description(
        lines
            .iter()
            .map(|l| l.as_str())
            .collect::<Vec<_>>()
            .join("\n"),
    );
    s
}

/// The suite of one testbench: its jobs, then its merged verdict.
fn suite(
    project: &Project,
    run: (Seed, u32, Option<usize>),
    row: &TbResult,
    jobs: &[&JobResult],
) -> TestSuite {
    let mut suite = TestSuite::new(row.name.as_str());
    suite.add_property(Property::new("unit", row.unit.as_str()));
    let labels = project
        .registry()
        .get(&row.name)
        .map(|t| t.configurations())
        .unwrap_or_default();
    for j in jobs {
        let label = labels.get(j.configuration).map_or("?", String::as_str);
        let mut case = TestCase::new(
            job_label(label, j.repeat),
            status(j.result.failed_itself(), &j.result),
        );
        case.set_classname(row.name.as_str())
            .set_time(Duration::from_secs_f64(j.seconds.max(0.0)));
        let seed = job_seed(run.0, &row.name, j.configuration, j.repeat);
        case.add_property(Property::new("job", j.index.to_string()))
            .add_property(Property::new("seed", seed.to_string()))
            .add_property(Property::new("reproduce", reproduce(project, run, j)));
        suite.add_test_case(case);
    }
    let mut verdict = TestCase::new("merged result", status(!row.passed, row));
    verdict.set_classname(row.name.as_str());
    suite.add_test_case(verdict);
    suite
}

/// The JUnit XML of summary `s`, whose testbenches ran `jobs` (any order; each testbench's
/// are taken in job order).
pub fn junit(project: &Project, s: &Summary, jobs: &[JobResult]) -> Result<String, String> {
    let seed = Seed::parse(&s.seed)?;
    let run = (seed, s.seeds, s.count);
    let reg = project.registry();
    let mut report = Report::new(project.name());
    let mut checks = TestSuite::new("checks");
    for row in &s.testbenches {
        let Some(tb) = reg.get(&row.name) else {
            let mut case = TestCase::new(row.name.as_str(), status(!row.passed, row));
            case.set_classname("checks");
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
    if !checks.test_cases.is_empty() {
        report.add_test_suite(checks);
    }
    report.to_string().map_err(|e| e.to_string())
}
