//! The RTL's own coverage in a co-simulation: [`RtlCoverage`], read from Verilator's
//! `coverage.dat`.

use std::path::{Path, PathBuf};
use std::process::Command;

/// How much of the RTL a co-simulation's stimulus reached, as Verilator measures it in a
/// build with `--coverage-line --coverage-toggle`: its blocks of statements (lines and
/// branches) and the bits of its signals that toggled, counted over every instance under the
/// testbench's `dut` (the testbench's own are left out). What it says of the model's
/// stimulus: an RTL line it never reached is a line the comparison never checked.
#[derive(Clone, Debug, PartialEq)]
pub struct RtlCoverage {
    /// Blocks of statements (a process, an `if`'s branch, ...) reached, of all.
    pub blocks: (usize, usize),
    /// Signal bits that toggled, of all.
    pub toggles: (usize, usize),
    /// The lines of the blocks never reached in any instance, by file name and line
    /// (`file:line`), in the order of the files' paths, each once (the blocks count each
    /// instance's).
    pub unreached: Vec<String>,
    /// Verilator's coverage data of the run (`coverage.dat`: `verilator_coverage` reads it,
    /// and merges several).
    pub data: PathBuf,
    /// The same as an lcov tracefile (`genhtml coverage.info` draws it as HTML).
    pub info: PathBuf,
    /// The RTL's sources annotated by `verilator_coverage`: each counted line marked with its
    /// count, `%000000` where it was never reached.
    pub annotated: PathBuf,
}

/// One coverage point: its file, line, column, what it is (`block`, `if`, `else`, a signal's
/// bit), page (`v_line/MODULE`, `v_branch/MODULE`, `v_toggle/MODULE`), hierarchy and count.
#[derive(Debug, PartialEq)]
struct Point {
    file: String,
    line: u32,
    column: String,
    what: String,
    page: String,
    hier: String,
    count: u64,
}

impl RtlCoverage {
    /// Blocks never reached named in the summary line.
    pub const SHOWN: usize = 8;

    /// Reads `dat` (written by the run in `dir`), leaves in it only the points under the
    /// testbench's `dut`, and has `verilator_coverage` write its lcov file and annotated
    /// sources into `dir` (made when it is not there). (The testbench's points name the
    /// testbench generated in the folder the build was made in, which a cached build's run
    /// need not have.)
    pub fn read(dat: &Path, dir: &Path) -> Result<RtlCoverage, String> {
        let (text, kept, points) = dut_points(dat)?;
        if kept != text {
            std::fs::write(dat, kept).map_err(|e| format!("{}: {e}", dat.display()))?;
        }
        let mut c = summary(&points);
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        c.data = dat.to_path_buf();
        (c.info, c.annotated) = (dir.join("coverage.info"), dir.join("coverage_annotated"));
        tool(
            Command::new("verilator_coverage")
                .arg("--write-info")
                .arg(&c.info)
                .arg("--annotate")
                .arg(&c.annotated)
                .args(["--annotate-all", "--annotate-min", "1"])
                .arg(dat),
        )?;
        Ok(c)
    }

    /// The coverage of several runs together: their data merged by `verilator_coverage` into
    /// `dir/coverage.dat` (a point reached in any run is reached), then read as [`read`]
    /// reads one.
    ///
    /// [`read`]: RtlCoverage::read
    pub fn merge(runs: &[&RtlCoverage], dir: &Path) -> Result<RtlCoverage, String> {
        let data: Vec<PathBuf> = runs.iter().map(|r| r.data.clone()).collect();
        RtlCoverage::merge_files(&data, dir)
    }

    /// [`merge`] of runs' `coverage.dat` files, into `dir` (made when it is not there).
    ///
    /// [`merge`]: RtlCoverage::merge
    pub fn merge_files(data: &[PathBuf], dir: &Path) -> Result<RtlCoverage, String> {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let dat = dir.join("coverage.dat");
        tool(
            Command::new("verilator_coverage")
                .arg("--write")
                .arg(&dat)
                .args(data),
        )?;
        RtlCoverage::read(&dat, dir)
    }

    /// `(reached, all)` as a percentage (100 when there is nothing to reach).
    pub fn percent((reached, all): (usize, usize)) -> f64 {
        if all == 0 {
            100.0
        } else {
            100.0 * reached as f64 / all as f64
        }
    }
}

impl RtlCoverage {
    /// The figures of the line it prints, without where its files are: blocks, toggles, the
    /// first lines never reached.
    pub fn figures(&self) -> String {
        let (l, t) = (self.blocks, self.toggles);
        let mut s = format!(
            "the RTL's coverage (Verilator): blocks {} of {} ({:.1} %), toggles {} of {} ({:.1} %)",
            l.0,
            l.1,
            Self::percent(l),
            t.0,
            t.1,
            Self::percent(t)
        );
        if !self.unreached.is_empty() {
            let shown = &self.unreached[..self.unreached.len().min(Self::SHOWN)];
            let more = match self.unreached.len() - shown.len() {
                0 => String::new(),
                n => format!(" and {n} more"),
            };
            s.push_str(&format!("; never reached: {}{more}", shown.join(", ")));
        }
        s
    }
}

impl std::fmt::Display for RtlCoverage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}; annotated sources in {}",
            self.figures(),
            self.annotated.display()
        )
    }
}

/// Runs `verilator_coverage` as `c`; a failure is its first message.
fn tool(c: &mut Command) -> Result<(), String> {
    let o = c.output().map_err(|e| format!("verilator_coverage: {e}"))?;
    if o.status.success() {
        return Ok(());
    }
    let err = String::from_utf8_lossy(&o.stderr);
    let first = err.lines().next().unwrap_or("failed");
    Err(format!("verilator_coverage: {first}"))
}

/// The counts of `points` under the testbench's `dut`.
fn summary(points: &[Point]) -> RtlCoverage {
    let dut: Vec<&Point> = points.iter().filter(|p| p.in_dut()).collect();
    let count = |toggle: bool| {
        let of: Vec<&&Point> = dut
            .iter()
            .filter(|p| p.page.starts_with("v_toggle/") == toggle)
            .collect();
        (of.iter().filter(|p| p.count > 0).count(), of.len())
    };
    // A block is never reached when it was in no instance; its line is named once.
    let mut blocks: Vec<(&str, u32, &str, &str, bool)> = dut
        .iter()
        .filter(|p| !p.page.starts_with("v_toggle/"))
        .map(|p| (&*p.file, p.line, &*p.column, &*p.what, p.count > 0))
        .collect();
    blocks.sort();
    let mut unreached: Vec<(&str, u32)> = Vec::new();
    for same in blocks.chunk_by(|a, b| (a.0, a.1, a.2, a.3) == (b.0, b.1, b.2, b.3)) {
        if same.iter().all(|b| !b.4) && unreached.last() != Some(&(same[0].0, same[0].1)) {
            unreached.push((same[0].0, same[0].1));
        }
    }
    let named = |(f, l): &(&str, u32)| {
        let name = Path::new(f).file_name().and_then(|n| n.to_str());
        format!("{}:{l}", name.unwrap_or(f))
    };
    RtlCoverage {
        blocks: count(false),
        toggles: count(true),
        unreached: unreached.iter().map(named).collect(),
        data: PathBuf::new(),
        info: PathBuf::new(),
        annotated: PathBuf::new(),
    }
}

impl Point {
    /// Whether it is the RTL's: under the testbench's `dut`.
    fn in_dut(&self) -> bool {
        self.hier == "TOP.tb.dut" || self.hier.starts_with("TOP.tb.dut.")
    }
}

/// A line `C '<keys>' COUNT` of `coverage.dat`: keys `\x01NAME\x02VALUE` (`f` file, `l` line,
/// `page`, `h` hierarchy, and others).
fn point(line: &str) -> Result<Point, String> {
    let bad = || format!("not a coverage point: {}", waves::output::shorten(line));
    let rest = line.strip_prefix("C '").ok_or_else(bad)?;
    let end = rest.rfind('\'').ok_or_else(bad)?;
    let count = rest[end + 1..].trim().parse().map_err(|_| bad())?;
    let mut p = Point {
        file: String::new(),
        line: 0,
        column: String::new(),
        what: String::new(),
        page: String::new(),
        hier: String::new(),
        count,
    };
    for kv in rest[..end].split('\x01').filter(|kv| !kv.is_empty()) {
        let (k, v) = kv.split_once('\x02').ok_or_else(bad)?;
        match k {
            "f" => p.file = v.to_string(),
            "l" => p.line = v.parse().map_err(|_| bad())?,
            "n" => p.column = v.to_string(),
            "o" => p.what = v.to_string(),
            "page" => p.page = v.to_string(),
            "h" => p.hier = v.to_string(),
            _ => {}
        }
    }
    Ok(p)
}

/// What runs reached of one RTL source file, over every instance of every run.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FileCoverage {
    /// The file, as the runs' builds named it.
    pub file: String,
    /// Its blocks of statements reached in some instance of some run, of all.
    pub blocks: (usize, usize),
    /// Its signal bits toggled in some instance of some run, of all.
    pub toggles: (usize, usize),
    /// The lines of its blocks no run reached, in order, each once.
    pub unreached: Vec<u32>,
}

/// A `coverage.dat`'s text, the same without the points outside the testbench's `dut`, and
/// the points under it.
fn dut_points(dat: &Path) -> Result<(String, String, Vec<Point>), String> {
    let text = std::fs::read_to_string(dat).map_err(|e| format!("{}: {e}", dat.display()))?;
    let (mut kept, mut points) = (String::with_capacity(text.len()), Vec::new());
    for l in text.lines() {
        if l.starts_with("C '") {
            let p = point(l).map_err(|e| format!("{}: {e}", dat.display()))?;
            if !p.in_dut() {
                continue;
            }
            points.push(p);
        }
        kept.push_str(l);
        kept.push('\n');
    }
    Ok((text, kept, points))
}

/// Point keys of one file: a block or a signal bit (line, column, what), reached or not.
type Keys = std::collections::BTreeMap<(u32, String, String), bool>;

/// The coverage of every RTL file under the testbenches' `dut` in the runs' `coverage.dat`
/// files, by source file: a block or a signal bit is counted once, wherever it is
/// instantiated, and is reached when any instance of any run reached it (runs of different
/// units that share a file add up). In the order of the files' paths.
pub fn by_file(data: &[PathBuf]) -> Result<Vec<FileCoverage>, String> {
    let mut files: std::collections::BTreeMap<String, (Keys, Keys)> = Default::default();
    for dat in data {
        for p in dut_points(dat)?.2 {
            let (blocks, toggles) = files.entry(lexically_clean(&p.file)).or_default();
            let keys = if p.page.starts_with("v_toggle/") {
                toggles
            } else {
                blocks
            };
            *keys.entry((p.line, p.column, p.what)).or_default() |= p.count > 0;
        }
    }
    let count = |k: &Keys| (k.values().filter(|r| **r).count(), k.len());
    Ok(files
        .into_iter()
        .map(|(file, (blocks, toggles))| {
            let mut unreached: Vec<u32> = (blocks.iter())
                .filter(|(_, r)| !**r)
                .map(|((line, ..), _)| *line)
                .collect();
            unreached.dedup();
            FileCoverage {
                file,
                blocks: count(&blocks),
                toggles: count(&toggles),
                unreached,
            }
        })
        .collect())
}

/// `path` without its `.` and with each `dir/..` taken out, as written (no link followed): a
/// file a library search found as `hw/../cells/x.sv` is the `cells/x.sv` another build
/// named.
fn lexically_clean(path: &str) -> String {
    use std::path::Component;
    let mut kept: Vec<Component> = Vec::new();
    for c in Path::new(path).components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir if matches!(kept.last(), Some(Component::Normal(_))) => {
                kept.pop();
            }
            // Above the root is the root.
            Component::ParentDir if matches!(kept.last(), Some(Component::RootDir)) => {}
            _ => kept.push(c),
        }
    }
    let clean: PathBuf = kept.iter().collect();
    clean.to_string_lossy().into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(file: &str, l: u32, page: &str, hier: &str, count: u64) -> String {
        format!("C '\x01f\x02{file}\x01l\x02{l}\x01n\x025\x01page\x02{page}\x01o\x02block\x01h\x02{hier}' {count}")
    }

    /// Two runs of different units that share a file: a block of it is reached when either
    /// run reached it in any instance; each file counted once, the testbench left out.
    #[test]
    fn by_file_adds_up_the_runs_that_share_a_file() {
        let dir = std::env::temp_dir().join(format!("texrtl-by-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let a = [
            line("/a/tb.sv", 3, "v_line/tb", "TOP.tb", 0),
            line("/r/u.v", 9, "v_line/u", "TOP.tb.dut", 4),
            line("/r/u.v", 12, "v_line/u", "TOP.tb.dut", 0),
            line("/r/sub.v", 5, "v_line/sub", "TOP.tb.dut.s0", 1),
            line("/r/sub.v", 6, "v_line/sub", "TOP.tb.dut.s0", 0),
            line("/r/sub.v", 7, "v_line/sub", "TOP.tb.dut.s0", 0),
            line("/r/sub.v", 2, "v_toggle/sub", "TOP.tb.dut.s0", 0),
        ];
        // The other build found the file through a library folder: the same file.
        let b = [
            line("/r/lib/../sub.v", 5, "v_line/sub", "TOP.tb.dut", 0),
            line("/r/./lib/../sub.v", 6, "v_line/sub", "TOP.tb.dut", 3),
            line("/r/lib/../sub.v", 7, "v_line/sub", "TOP.tb.dut", 0),
            line("/r/lib/../sub.v", 2, "v_toggle/sub", "TOP.tb.dut", 1),
        ];
        let write = |name: &str, lines: &[String]| {
            let p = dir.join(name);
            std::fs::write(&p, format!("# SystemC::Coverage-3\n{}\n", lines.join("\n"))).unwrap();
            p
        };
        let files = by_file(&[write("a.dat", &a), write("b.dat", &b)]).unwrap();
        let sub = FileCoverage {
            file: "/r/sub.v".into(),
            blocks: (2, 3),
            toggles: (1, 1),
            unreached: vec![7],
        };
        let u = FileCoverage {
            file: "/r/u.v".into(),
            blocks: (1, 2),
            toggles: (0, 0),
            unreached: vec![12],
        };
        assert_eq!(files, [sub, u]);
        assert!(by_file(&[dir.join("none.dat")]).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_path_is_cleaned_as_written() {
        assert_eq!(lexically_clean("/p/hw/../cells/x.sv"), "/p/cells/x.sv");
        assert_eq!(lexically_clean("./a/./b.v"), "a/b.v");
        assert_eq!(lexically_clean("../up/x.v"), "../up/x.v");
        assert_eq!(lexically_clean("a/../../x.v"), "../x.v");
        assert_eq!(lexically_clean("/../x.v"), "/x.v");
    }

    /// Points under the dut counted by kind, the testbench's own left out, the blocks never
    /// reached named by file and line in order.
    #[test]
    fn the_dut_s_points_are_counted_by_kind() {
        let text = [
            line("/a/tb.sv", 3, "v_line/tb", "TOP.tb", 0),
            line("/r/u.v", 9, "v_line/u", "TOP.tb.dut", 4),
            line("/r/u.v", 12, "v_line/u", "TOP.tb.dut", 0),
            line("/r/sub.v", 5, "v_line/sub", "TOP.tb.dut.s0", 0),
            line("/r/sub.v", 5, "v_line/sub", "TOP.tb.dut.s1", 0),
            line("/r/sub.v", 6, "v_line/sub", "TOP.tb.dut.s0", 0),
            line("/r/sub.v", 6, "v_line/sub", "TOP.tb.dut.s1", 2),
            line("/r/sub.v", 7, "v_branch/sub", "TOP.tb.dut.s0", 4)
                .replace("\x01o\x02block", "\x01o\x02else"),
            line("/r/sub.v", 7, "v_branch/sub", "TOP.tb.dut.s0", 0)
                .replace("\x01o\x02block", "\x01o\x02if"),
            line("/r/u.v", 2, "v_toggle/u", "TOP.tb.dut", 7),
            line("/r/u.v", 2, "v_toggle/u", "TOP.tb.dut", 0),
            line("/r/u.v", 2, "v_toggle/u", "TOP.tb.dutx", 0),
        ];
        let points: Vec<Point> = text.iter().map(|l| point(l).unwrap()).collect();
        assert_eq!(points[1].line, 9);
        let c = summary(&points);
        assert_eq!(c.blocks, (3, 8), "each instance's blocks");
        assert_eq!(c.toggles, (1, 2));
        assert_eq!(
            c.unreached,
            ["sub.v:5", "sub.v:7", "u.v:12"],
            "each line once; a block reached in another instance is reached; an if beside its else"
        );
        let many = RtlCoverage {
            unreached: (1..=10).map(|l| format!("u.v:{l}")).collect(),
            ..c
        };
        assert!(
            many.to_string().contains("u.v:8 and 2 more; annotated"),
            "{many}"
        );
        assert!(point("C 'x").is_err());
        assert!(
            point(&line("/r/u.v", 1, "v_line/u", "TOP.tb.dut", 1).replace("' 1", "' x")).is_err()
        );
    }

    /// Two runs' data merged by `verilator_coverage`: a point reached in either is reached
    /// (skipped without Verilator).
    #[test]
    fn runs_merged_reach_what_either_reached() {
        if Command::new("verilator_coverage")
            .arg("--version")
            .output()
            .is_err()
        {
            return;
        }
        let t = tempfile::tempdir().unwrap();
        let u = t.path().join("u.v");
        std::fs::write(
            &u,
            "module u;\n  reg r;\n  always @* r = 0;\n  always @* r = 1;\nendmodule\n",
        )
        .unwrap();
        let u = u.to_str().unwrap();
        let run = |name: &str, counts: [u64; 2]| {
            let dir = t.path().join(name);
            std::fs::create_dir_all(&dir).unwrap();
            let text = format!(
                "# SystemC::Coverage-3\n{}\n{}\n",
                line(u, 3, "v_line/u", "TOP.tb.dut", counts[0]),
                line(u, 4, "v_line/u", "TOP.tb.dut", counts[1])
            );
            std::fs::write(dir.join("coverage.dat"), text).unwrap();
            RtlCoverage::read(&dir.join("coverage.dat"), &dir).unwrap()
        };
        let (a, b) = (run("a", [1, 0]), run("b", [0, 0]));
        assert_eq!((a.blocks, b.blocks), ((1, 2), (0, 2)));
        let both = RtlCoverage::merge(&[&a, &b], t.path()).unwrap();
        assert_eq!(both.blocks, (1, 2));
        assert_eq!(both.unreached, ["u.v:4"]);
        assert!(t.path().join("coverage.info").is_file());
    }
}
