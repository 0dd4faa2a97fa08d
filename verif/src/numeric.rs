//! Numeric coverage: what each named narrowing of a unit met in a run (values narrowed,
//! overflows above and below, rounding ties, values that lost fraction bits, the range before
//! narrowing), merged across configurations and shards, and the paths never exercised.

use crate::coverage::{Coverage, Coverpoint};
use hdl::fx::{Format, Fx, NarrowPath, Narrowing, Overflow};
use hdl::kernel::Module;
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// One narrowing's counts in a testbench's runs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NarrowRow {
    /// Its path: unit instance path and the narrowing's name.
    pub path: String,
    /// The declared destination format (`sQ1.14`).
    pub format: String,
    /// The rounding mode's name.
    pub quant: String,
    /// The overflow mode's name.
    pub overflow: String,
    /// Values narrowed.
    pub narrowed: u64,
    /// Values above the destination's range (saturated, or wrapped).
    pub over_high: u64,
    /// Values below it.
    pub over_low: u64,
    /// Exact half-way values under a mode with a tie rule.
    pub ties: u64,
    /// Values that lost fraction bits.
    pub inexact: u64,
    /// The smallest value before narrowing (`null` when none was narrowed).
    pub min: Option<f64>,
    /// The largest.
    pub max: Option<f64>,
    /// The paths the unit declares unreachable, with the reason (a bound on its values).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unreachable: Vec<Unreachable>,
}

/// A path of a narrowing declared unreachable ([`Narrowing::unreachable`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Unreachable {
    /// `high`, `low` or `tie`.
    pub path: String,
    /// Why no value reaches it.
    pub why: String,
}

/// One path of a narrowing as a coverage bin: its name in reports, the values that took it,
/// the reason it is unreachable if the unit declares it so.
#[derive(Clone, Debug, PartialEq)]
pub struct NumericBin {
    /// `saturation high`, `wrap low`, `tie`, ...
    pub name: String,
    /// Values that took the path.
    pub hits: u64,
    /// The unit's reason it cannot be taken.
    pub unreachable: Option<String>,
}

impl NarrowRow {
    fn of(path: String, n: &Narrowing) -> NarrowRow {
        let s = n.stats();
        let seen = s.narrowed > 0;
        NarrowRow {
            path,
            format: n.dst().to_string(),
            quant: n.quant().name().into(),
            overflow: n.overflow().name().into(),
            narrowed: s.narrowed,
            over_high: s.over_high,
            over_low: s.over_low,
            ties: s.ties,
            inexact: s.inexact,
            min: s.min().filter(|_| seen).map(Fx::to_f64),
            max: s.max().filter(|_| seen).map(Fx::to_f64),
            unreachable: n
                .unreachable_paths()
                .iter()
                .map(|(p, why)| Unreachable {
                    path: p.name().into(),
                    why: (*why).into(),
                })
                .collect(),
        }
    }

    /// What makes two rows the same narrowing: path, declared format and modes.
    fn key(&self) -> (&str, &str, &str, &str) {
        (&self.path, &self.format, &self.quant, &self.overflow)
    }

    fn merge(&mut self, o: &NarrowRow) {
        self.narrowed += o.narrowed;
        self.over_high += o.over_high;
        self.over_low += o.over_low;
        self.ties += o.ties;
        self.inexact += o.inexact;
        let pick = |a: Option<f64>, b: Option<f64>, f: fn(f64, f64) -> f64| match (a, b) {
            (Some(a), Some(b)) => Some(f(a, b)),
            (a, b) => a.or(b),
        };
        self.min = pick(self.min, o.min, f64::min);
        self.max = pick(self.max, o.max, f64::max);
        for u in &o.unreachable {
            if !self.unreachable.iter().any(|x| x.path == u.path) {
                self.unreachable.push(u.clone());
            }
        }
    }

    /// The narrowing's paths as coverage bins: an overflow on each side the destination can
    /// overflow on (below an unsigned one only when a negative value came), a rounding tie
    /// under a mode with a tie rule once a value was rounded at all; and any path the unit
    /// declares unreachable.
    pub fn bins(&self) -> Vec<NumericBin> {
        let wrap = self.overflow == Overflow::Wrap.name();
        let what = if wrap { "wrap" } else { "saturation" };
        let unsigned = Format::parse(&self.format).is_ok_and(|f| !f.is_signed());
        let tie_rule = !self.quant.starts_with("trunc");
        let why = |p: NarrowPath| {
            let u = self.unreachable.iter().find(|u| u.path == p.name());
            u.map(|u| u.why.clone())
        };
        let paths = [
            (
                NarrowPath::High,
                format!("{what} high"),
                self.over_high,
                true,
            ),
            (
                NarrowPath::Low,
                format!("{what} low"),
                self.over_low,
                !(unsigned && self.min.is_some_and(|m| m >= 0.0)),
            ),
            (
                NarrowPath::Tie,
                "tie".into(),
                self.ties,
                tie_rule && self.inexact > 0,
            ),
        ];
        paths
            .into_iter()
            .filter(|(p, _, _, applies)| *applies || why(*p).is_some())
            .map(|(p, name, hits, _)| NumericBin {
                name,
                hits,
                unreachable: why(p),
            })
            .collect()
    }

    /// The paths of this narrowing its runs never took (and the unit does not declare
    /// unreachable): an overflow rule never applied on a side the format can overflow on, a
    /// tie never met by a rounding mode with a tie rule.
    pub fn holes(&self) -> Vec<String> {
        let bins = self.bins().into_iter();
        let holes = bins.filter(|b| b.hits == 0 && b.unreachable.is_none());
        holes
            .map(|b| format!("{}: {} never reached", self.path, b.name))
            .collect()
    }

    /// The paths declared unreachable, with their reasons (`path: saturation high: why`).
    pub fn declared_unreachable(&self) -> Vec<String> {
        let bins = self.bins().into_iter();
        bins.filter_map(|b| Some(format!("{}: {}: {}", self.path, b.name, b.unreachable?)))
            .collect()
    }

    /// The paths declared unreachable that a run took after all: the unit's bound is wrong.
    pub fn contradictions(&self) -> Vec<String> {
        let bins = self.bins().into_iter().filter(|b| b.hits > 0);
        bins.filter_map(|b| {
            let why = b.unreachable?;
            Some(format!(
                "{}: {} declared unreachable ({why}) but taken {} times",
                self.path, b.name, b.hits
            ))
        })
        .collect()
    }
}

/// The narrowings' paths as a coverage model, one coverpoint per narrowing (named by its
/// path) with a bin per path that can be taken (bins declared unreachable are left out): the
/// testbench's numeric coverage, with no line of testbench code.
pub fn coverage(rows: &[NarrowRow]) -> Coverage {
    let mut c = Coverage::new();
    for r in rows {
        let bins = r.bins().into_iter().filter(|b| b.unreachable.is_none());
        let mut p = Coverpoint::new(&r.path);
        for (k, b) in bins.enumerate() {
            p = p.value(&b.name, k as i64);
            if let Some(last) = p.bins.last_mut() {
                last.hits = b.hits;
            }
        }
        if !p.bins.is_empty() {
            c.add(p);
        }
    }
    c
}

/// The narrowest format that would have held every value seen with the same error: the same
/// fraction bits and signedness, integer bits for the observed range, rounded outward (a
/// narrowing that overflowed keeps its format: a narrower one would clip where it did not).
/// With the declared format's integer bits the narrowing never used.
pub fn narrowest(r: &NarrowRow) -> Option<(Format, u32)> {
    let declared = Format::parse(&r.format).ok()?;
    let (lo, hi) = (r.min?, r.max?);
    if r.over_high > 0 || r.over_low > 0 {
        return Some((declared, 0));
    }
    let scale = 2f64.powi(declared.frac());
    let (lo, hi) = ((lo * scale).floor(), (hi * scale).ceil());
    let fits = |w: u32| {
        let f = Format::try_new(w, declared.frac(), declared.is_signed());
        f.is_ok_and(|f| lo >= f.min_raw() as f64 && hi <= f.max_raw() as f64)
    };
    let w = (1..=declared.width()).find(|&w| fits(w))?;
    let f = Format::new(w, declared.frac(), declared.is_signed());
    Some((f, declared.width() - w))
}

/// The headroom to saturation: the least distance from the range seen to either end of the
/// declared format (`-max` for the low end under symmetric saturation), 0 where a value
/// reached or passed an end; `None` before any value.
pub fn headroom(r: &NarrowRow) -> Option<f64> {
    let f = Format::parse(&r.format).ok()?;
    let (lo, hi) = (r.min?, r.max?);
    let scale = 2f64.powi(-f.frac());
    let top = f.max_raw() as f64 * scale;
    let symmetric = r.overflow == Overflow::SaturateSymmetric.name() && f.is_signed();
    let bottom = if symmetric {
        -top
    } else {
        f.min_raw() as f64 * scale
    };
    Some((top - hi).min(lo - bottom).max(0.0))
}

/// Every narrowing of `dut` with its counts (all zero unless tracking was on).
pub fn rows(dut: &dyn Module) -> Vec<NarrowRow> {
    hdl::kernel::narrowings(dut)
        .into_iter()
        .map(|(path, n)| NarrowRow::of(path, &n))
        .collect()
}

/// Adds `more` into `into`, row by row of the same narrowing (the same path, format and
/// modes: configurations that give a narrowing other widths keep a row each), the rows kept
/// in that order: shards and configurations merged in any order give the same rows.
pub fn merge(into: &mut Vec<NarrowRow>, more: &[NarrowRow]) {
    for r in more {
        match into.iter_mut().find(|x| x.key() == r.key()) {
            Some(x) => x.merge(r),
            None => into.push(r.clone()),
        }
    }
    into.sort_by(|a, b| a.key().cmp(&b.key()));
}

/// A row's cells, in the table's and the CSV's column order; `none` for an empty range.
fn cells(r: &NarrowRow, num: fn(f64) -> String, none: &str) -> Vec<String> {
    let opt = |x: Option<f64>| x.map_or_else(|| none.to_string(), num);
    let (narrow, unused) = narrowest(r).map_or((none.to_string(), none.to_string()), |(f, u)| {
        (f.to_string(), u.to_string())
    });
    let counts = [r.narrowed, r.over_high, r.over_low, r.ties, r.inexact];
    let mut c = vec![
        r.path.clone(),
        r.format.clone(),
        r.quant.clone(),
        r.overflow.clone(),
    ];
    c.extend(counts.iter().map(u64::to_string));
    c.extend([opt(r.min), opt(r.max), opt(headroom(r)), unused, narrow]);
    c
}

/// The rows as a Markdown table for `report.md`.
pub fn table(rows: &[NarrowRow]) -> String {
    let mut t = String::from(
        "| narrowing | format | rounding | overflow | narrowed | over high | over low | ties | inexact | min | max | headroom | unused integer bits | narrowest |\n|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            t,
            "| {} |",
            cells(r, |v| format!("{v:.6}"), "-").join(" | ")
        );
    }
    t
}

/// The file name of testbench `name`'s bit chart ([`picture`]) beside `report.md`.
pub fn picture_file(name: &str) -> String {
    format!("{name}_narrowings.svg")
}

/// The rows as bit spans: each narrowing's declared bits, the bits its values used (the
/// narrowest format's, [`narrowest`]), whether any overflowed. Labels drop the path's first
/// scope when every row shares it (the testbench's top unit, named in the title).
pub fn spans(rows: &[NarrowRow]) -> Vec<crate::plot::BitSpan> {
    let top = |p: &str| p.split('.').next().unwrap_or("").to_string();
    let shared = rows.first().map(|r| top(&r.path));
    let shared = shared.filter(|t| rows.iter().all(|r| top(&r.path) == *t));
    let bits = |f: Format| (-f.frac(), f.width() as i32 - f.frac() - 1);
    let dup = |r: &NarrowRow| rows.iter().filter(|x| x.path == r.path).count() > 1;
    rows.iter()
        .filter_map(|r| {
            let declared = Format::parse(&r.format).ok()?;
            let mut label = match &shared {
                Some(t) if r.path.len() > t.len() => r.path[t.len() + 1..].to_string(),
                _ => r.path.clone(),
            };
            if dup(r) {
                label = format!("{label} ({})", r.format);
            }
            Some(crate::plot::BitSpan {
                label,
                declared: bits(declared),
                used: narrowest(r).map(|(f, _)| bits(f)),
                overflowed: r.over_high > 0 || r.over_low > 0,
            })
        })
        .collect()
}

/// Testbench `name`'s bit chart as SVG: per narrowing, the bits declared and the bits used.
pub fn picture(name: &str, rows: &[NarrowRow]) -> Result<String, String> {
    let title = format!("{name}: bits of each narrowing, declared and used");
    crate::plot::bit_spans_svg(&title, &spans(rows))
}

/// A testbench's numeric coverage section of `report.md`: its table, its bit chart
/// ([`picture_file`]), and the paths never taken.
pub fn section(m: &mut String, name: &str, rows: &[NarrowRow]) {
    if rows.is_empty() {
        return;
    }
    let (total, hit) = coverage(rows).totals();
    let _ = writeln!(
        m,
        "\nNumeric coverage (every named narrowing): {hit}/{total} overflow and tie paths taken\n"
    );
    m.push_str(&table(rows));
    let file = picture_file(name);
    let _ = writeln!(
        m,
        "\n![{name}: bits of each narrowing]({file})\n\n*Each narrowing's declared bits (grey) and \
         the bits its values used (blue; red: values overflowed the format)*"
    );
    let holes: Vec<String> = rows.iter().flat_map(NarrowRow::holes).collect();
    if !holes.is_empty() {
        let _ = writeln!(m, "\nNumeric paths never exercised: {}", holes.join("; "));
    }
    let declared: Vec<String> = rows
        .iter()
        .flat_map(NarrowRow::declared_unreachable)
        .collect();
    if !declared.is_empty() {
        let _ = writeln!(m, "\nDeclared unreachable by the unit:\n");
        for d in declared {
            let _ = writeln!(m, "- {d}");
        }
    }
}

/// The rows of every testbench as CSV (`narrowings.csv` beside `report.md`): one line a
/// narrowing, with its testbench.
pub fn csv(results: &[crate::TbResult]) -> String {
    let mut t = String::from("testbench,narrowing,format,rounding,overflow,narrowed,over_high,over_low,ties,inexact,min,max,headroom,unused_integer_bits,narrowest\n");
    for res in results {
        for r in &res.narrowings {
            let _ = writeln!(
                t,
                "{},{}",
                res.name,
                cells(r, |v| v.to_string(), "").join(",")
            );
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use hdl::fx::{set_tracking, Quant};
    use hdl::kernel::{Reg, Signal};

    #[derive(hdl::kernel::Module)]
    #[module(kind = "clip")]
    struct Clip {
        #[input]
        x: Signal,
        #[reg]
        y: Reg,
        #[narrow]
        round: [Narrowing; 2],
    }

    impl Clip {
        fn eval(&mut self) {
            let v = self.round[0].fx(self.x.fx());
            self.y.set_next(self.round[1].fx(v));
        }
    }

    fn clip(xs: &[i64]) -> Vec<NarrowRow> {
        let out = Format::signed(6, 2);
        let mut c = Clip {
            x: Signal::new("x", Format::signed(10, 4)),
            y: Reg::new("y", out),
            round: [
                Narrowing::new("y", out, Quant::RoundHalfEven, Overflow::Saturate),
                Narrowing::new("again", out, Quant::Trunc, Overflow::Wrap),
            ],
        };
        set_tracking(true);
        for &x in xs {
            c.x.set_raw(x);
            c.eval();
        }
        set_tracking(false);
        rows(&c)
    }

    /// The bit chart's rows: the declared bits, the bits the values needed (all of them where
    /// a value overflowed), labels without the shared top scope.
    #[test]
    fn spans_show_declared_and_used_bits() {
        let a = clip(&[511, 2, 6]);
        let s = spans(&a);
        assert_eq!(s.len(), 2);
        // sQ4.2: bits 2^-2 .. 2^3; `y` saturated 31.9375 (above 7.75): all its bits, red.
        assert_eq!((s[0].label.as_str(), s[0].declared), ("y", (-2, 3)));
        assert!(s[0].overflowed && s[0].used == Some((-2, 3)));
        let small = clip(&[2, 6]);
        let s = spans(&small);
        // 0.125 and 0.375 round to 0 and 0.5: raw 0 .. 2 needs 3 signed bits, 2^-2 .. 2^0.
        assert_eq!((s[0].used, s[0].overflowed), (Some((-2, 0)), false));
        let svg = picture("clip_tb", &small).unwrap();
        assert!(svg.contains("clip_tb: bits of each narrowing"));
    }

    /// A narrowing that a configuration gives another format is another row: its counts and
    /// range are not added into the first format's.
    #[test]
    fn a_narrowing_in_another_format_keeps_its_own_row() {
        let a = clip(&[511, 2, 6]);
        let mut wide = a.clone();
        for r in &mut wide {
            r.format = "sQ8.2".into();
        }
        let mut m = Vec::new();
        merge(&mut m, &a);
        merge(&mut m, &wide);
        merge(&mut m, &a);
        let y: Vec<_> = m.iter().filter(|r| r.path == "clip.y").collect();
        assert_eq!(y.len(), 2);
        assert_eq!((y[0].format.as_str(), y[0].narrowed), ("sQ4.2", 6));
        assert_eq!((y[1].format.as_str(), y[1].narrowed), ("sQ8.2", 3));
    }

    /// Rows carry the counts and the declared modes; runs merge path by path, adding counts
    /// and widening the range; the holes are the overflow sides and ties never met.
    #[test]
    fn rows_merge_and_name_their_holes() {
        // 31.9375 saturates high (and drops 0.75 LSB); 0.125 and 0.375 are ties (0.5, 1.5 LSB).
        let a = clip(&[511, 2, 6]);
        assert_eq!(a[0].path, "clip.y");
        assert_eq!((a[0].narrowed, a[0].over_high, a[0].over_low), (3, 1, 0));
        assert_eq!((a[0].ties, a[0].inexact), (2, 3));
        assert_eq!(
            (a[0].format.as_str(), a[0].quant.as_str()),
            ("sQ4.2", "round-half-even")
        );
        assert_eq!(
            a[0].holes(),
            ["clip.y: saturation low never reached"],
            "high and a tie were met"
        );
        let b = clip(&[-512]);
        let mut m = Vec::new();
        merge(&mut m, &a);
        merge(&mut m, &b);
        let mut other_way = Vec::new();
        merge(&mut other_way, &b);
        merge(&mut other_way, &a);
        assert_eq!(m, other_way, "merged in either order");
        let (again, y) = (&m[0], &m[1]);
        assert_eq!(
            (again.path.as_str(), y.path.as_str()),
            ("clip.again", "clip.y")
        );
        let m = vec![y.clone(), again.clone()];
        assert_eq!((m[0].narrowed, m[0].over_high, m[0].over_low), (4, 1, 1));
        assert_eq!((m[0].min, m[0].max), (Some(-32.0), Some(511.0 / 16.0)));
        assert!(m[0].holes().is_empty());
        assert_eq!(
            m[1].holes(),
            [
                "clip.again: wrap high never reached",
                "clip.again: wrap low never reached"
            ]
        );
        let json = serde_json::to_string(&m).unwrap();
        assert_eq!(serde_json::from_str::<Vec<NarrowRow>>(&json).unwrap(), m);
        assert!(table(&m).contains("| clip.y | sQ4.2 | round-half-even | saturate | 4 | 1 | 1 |"));
        let mut res = crate::TbResult::new("clip_tb", "a clip");
        res.narrowings = m.clone();
        let csv = csv(&[res]);
        assert!(csv.starts_with("testbench,narrowing,format,"));
        assert!(
            csv.contains(
                "\nclip_tb,clip.y,sQ4.2,round-half-even,saturate,4,1,1,2,3,-32,31.9375,0,0,sQ4.2\n"
            ),
            "{csv}"
        );
    }

    /// A deliberately over-wide destination (sQ12.2 for values within [-6, 6)): its unused
    /// integer bits are reported, and the narrowest format proposed gives every output of the
    /// run again, bit for bit (the same error against the exact values).
    #[test]
    fn an_over_wide_format_is_narrowed_with_the_same_results() {
        let inputs: Vec<i64> = (-96..96).collect(); // sQ6.4 raws: -6 ..= 5.9375
        let wide = Format::signed(14, 2);
        let run = |fmt: Format| {
            let mut n = Narrowing::new("y", fmt, Quant::RoundHalfEven, Overflow::Saturate);
            set_tracking(true);
            let out: Vec<f64> = inputs
                .iter()
                .map(|&x| {
                    n.fx(hdl::fx::Fx::from_raw(Format::signed(10, 4), x.into()))
                        .to_f64()
                })
                .collect();
            set_tracking(false);
            (out, NarrowRow::of("clip.y".into(), &n))
        };
        let (wide_out, row) = run(wide);
        let (fmt, unused) = narrowest(&row).unwrap();
        assert_eq!(
            fmt,
            Format::signed(6, 2),
            "-6.0 ..= 6.0 after rounding: sQ4.2"
        );
        assert_eq!(unused, 8);
        assert!(table(&[row]).contains("| 8 | sQ4.2 |"));
        let (narrow_out, row) = run(fmt);
        assert_eq!(narrow_out, wide_out, "the same results, so the same error");
        assert_eq!((row.over_high, row.over_low), (0, 0));
        // One bit fewer would clip: 6.0 (5.9375 rounded) needs the sign and three bits.
        let (clipped, _) = run(Format::signed(5, 2));
        assert_ne!(clipped, wide_out);
    }

    /// A path the unit declares unreachable is no hole and no bin of the coverage model but
    /// is listed with its reason; taken after all, it fails the result whether or not numeric
    /// coverage is required; holes fail a result only when it is required.
    #[test]
    fn declared_paths_are_listed_and_taking_one_fails() {
        let run = |xs: &[i64], low_why: Option<&'static str>| {
            let out = Format::signed(6, 2);
            let mut n = Narrowing::new("y", out, Quant::RoundHalfEven, Overflow::Saturate);
            if let Some(why) = low_why {
                n = n.unreachable(NarrowPath::Low, why);
            }
            set_tracking(true);
            for &x in xs {
                n.fx(Fx::from_raw(Format::signed(10, 4), x.into()));
            }
            set_tracking(false);
            NarrowRow::of("clip.y".into(), &n)
        };
        let r = run(&[511, 2], Some("x >= 0 by construction"));
        assert_eq!(
            r.holes(),
            Vec::<String>::new(),
            "high and a tie met, low declared"
        );
        assert_eq!(
            r.declared_unreachable(),
            ["clip.y: saturation low: x >= 0 by construction"]
        );
        assert!(r.contradictions().is_empty());
        let c = coverage(std::slice::from_ref(&r));
        assert_eq!(c.totals(), (2, 2), "high and tie; low left out");
        let mut res = crate::TbResult::new("clip_tb", "a clip");
        res.narrowings = vec![run(&[2], None)];
        res.finish_with(true);
        assert!(res.passed, "holes pass unless required: {:?}", res.failures);
        assert_eq!(res.numeric_percent, Some(100.0 / 3.0));
        assert_eq!(res.numeric_holes.len(), 2, "{:?}", res.numeric_holes);
        res.require_numeric_coverage();
        assert!(!res.passed);
        assert!(res.failures[0].starts_with(
            "numeric coverage holes (2 paths): clip.y: saturation high never reached"
        ));
        res.narrowings = vec![run(&[-512, 511, 2], Some("x >= 0 by construction"))];
        res.finish_with(true);
        assert!(!res.passed, "a declared-unreachable path taken");
        assert_eq!(
            res.failures,
            ["unreachable narrowing path taken: clip.y: saturation low declared unreachable (x >= 0 by construction) but taken 1 times"]
        );
        let json = serde_json::to_string(&res).unwrap();
        let back: crate::TbResult = serde_json::from_str(&json).unwrap();
        assert_eq!(
            back.narrowings, res.narrowings,
            "declarations kept in summary.json"
        );
    }

    /// Off, nothing is counted and the rows are all zeros.
    #[test]
    fn off_counts_nothing() {
        let mut c = Clip {
            x: Signal::new("x", Format::signed(10, 4)),
            y: Reg::new("y", Format::signed(6, 2)),
            round: [
                Narrowing::new("y", Format::signed(6, 2), Quant::Trunc, Overflow::Saturate),
                Narrowing::new("z", Format::signed(6, 2), Quant::Trunc, Overflow::Saturate),
            ],
        };
        c.x.set_raw(511);
        c.eval();
        assert!(rows(&c).iter().all(|r| r.narrowed == 0 && r.min.is_none()));
    }
}
