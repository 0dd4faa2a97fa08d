//! Functional coverage: coverpoints with bins, crosses of two coverpoints, and a report that
//! lists every bin never hit.

use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// A bin: an inclusive range of sampled values, with a name and a hit count.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Bin {
    /// The bin's name in reports.
    pub name: String,
    /// The lowest value it holds.
    pub lo: i64,
    /// The highest value it holds.
    pub hi: i64,
    /// Samples that fell in it.
    pub hits: u64,
}

/// A coverpoint: named bins over one sampled value.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Coverpoint {
    /// The coverpoint's name (what it samples).
    pub name: String,
    /// Its bins, in the order declared.
    pub bins: Vec<Bin>,
    /// Samples that fell in no bin.
    pub unbinned: u64,
}

impl Coverpoint {
    /// A coverpoint with no bin yet.
    pub fn new(name: &str) -> Coverpoint {
        Coverpoint {
            name: name.to_string(),
            bins: Vec::new(),
            unbinned: 0,
        }
    }

    /// Adds a bin for `lo..=hi`.
    pub fn bin(mut self, name: &str, lo: i64, hi: i64) -> Coverpoint {
        assert!(lo <= hi, "bin {name}: {lo} > {hi}");
        self.bins.push(Bin {
            name: name.to_string(),
            lo,
            hi,
            hits: 0,
        });
        self
    }

    /// Adds a bin for one value.
    pub fn value(self, name: &str, v: i64) -> Coverpoint {
        self.bin(name, v, v)
    }

    /// Adds a bin for each of the values 0, 1, 2 ..., named by `names` in order (an
    /// enumeration's coverpoint: modes, states, borders).
    pub fn values(mut self, names: &[&str]) -> Coverpoint {
        for (v, name) in names.iter().enumerate() {
            self = self.value(name, v as i64);
        }
        self
    }

    /// Splits `lo..=hi` into `n` bins of (nearly) equal size, named `name[k]`.
    pub fn ranges(mut self, name: &str, lo: i64, hi: i64, n: usize) -> Coverpoint {
        let span = (hi - lo + 1) as i128;
        let n = (n as i128).min(span).max(1);
        for k in 0..n {
            let a = lo as i128 + span * k / n;
            let b = lo as i128 + span * (k + 1) / n - 1;
            self = self.bin(&format!("{name}[{k}]"), a as i64, b as i64);
        }
        self
    }

    /// Samples `v`: every bin holding it is hit.
    pub fn sample(&mut self, v: i64) {
        let mut any = false;
        for b in &mut self.bins {
            if b.lo <= v && v <= b.hi {
                b.hits += 1;
                any = true;
            }
        }
        self.unbinned += u64::from(!any);
    }

    /// Bins hit at least once.
    pub fn hit_bins(&self) -> usize {
        self.bins.iter().filter(|b| b.hits > 0).count()
    }
}

/// The cross of two coverpoints: one bin per pair of their bins.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Cross {
    /// The cross's name.
    pub name: String,
    /// The first coverpoint, by index in the model.
    pub a: usize,
    /// The second coverpoint, by index in the model.
    pub b: usize,
    /// `hits[i][j]`: bin i of `a` with bin j of `b`.
    pub hits: Vec<Vec<u64>>,
}

/// A coverage model: coverpoints and crosses, sampled together.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Coverage {
    /// The coverpoints, each sampled with one value.
    pub points: Vec<Coverpoint>,
    /// The crosses of pairs of them.
    pub crosses: Vec<Cross>,
}

impl Coverage {
    /// An empty model.
    pub fn new() -> Coverage {
        Coverage::default()
    }

    /// Adds a coverpoint; returns its index.
    pub fn add(&mut self, p: Coverpoint) -> usize {
        self.points.push(p);
        self.points.len() - 1
    }

    /// Crosses coverpoints `a` and `b` (indices from [`Coverage::add`]).
    pub fn cross(&mut self, name: &str, a: usize, b: usize) {
        let (na, nb) = (self.points[a].bins.len(), self.points[b].bins.len());
        self.crosses.push(Cross {
            name: name.to_string(),
            a,
            b,
            hits: vec![vec![0; nb]; na],
        });
    }

    /// Samples one value per coverpoint (in the order they were added) and every cross.
    pub fn sample(&mut self, values: &[i64]) {
        assert_eq!(values.len(), self.points.len(), "one value per coverpoint");
        for (p, v) in self.points.iter_mut().zip(values) {
            p.sample(*v);
        }
        for c in &mut self.crosses {
            let (pa, pb) = (&self.points[c.a], &self.points[c.b]);
            for (i, ba) in pa.bins.iter().enumerate() {
                if !(ba.lo <= values[c.a] && values[c.a] <= ba.hi) {
                    continue;
                }
                for (j, bb) in pb.bins.iter().enumerate() {
                    if bb.lo <= values[c.b] && values[c.b] <= bb.hi {
                        c.hits[i][j] += 1;
                    }
                }
            }
        }
    }

    /// Whether the model is whole (one read from a file may not be): every bin's `lo <= hi`,
    /// every cross names two coverpoints and has one count per pair of their bins. `Err` says
    /// the first problem.
    pub fn validate(&self) -> Result<(), String> {
        for p in &self.points {
            if let Some(b) = p.bins.iter().find(|b| b.lo > b.hi) {
                return Err(format!(
                    "coverpoint '{}': bin '{}' is empty",
                    p.name, b.name
                ));
            }
        }
        for c in &self.crosses {
            let bins = |k: usize| self.points.get(k).map(|p| p.bins.len());
            let (Some(na), Some(nb)) = (bins(c.a), bins(c.b)) else {
                return Err(format!("cross '{}': no such coverpoint", c.name));
            };
            if c.hits.len() != na || c.hits.iter().any(|r| r.len() != nb) {
                return Err(format!(
                    "cross '{}': not {na} x {nb} counts like its coverpoints",
                    c.name
                ));
            }
        }
        Ok(())
    }

    /// Whether `o` is a model of the same shape: the same coverpoints with the same bins, the
    /// same crosses. `Err` says the first difference.
    pub fn same_model(&self, o: &Coverage) -> Result<(), String> {
        self.validate()?;
        o.validate()?;
        if self.points.len() != o.points.len() || self.crosses.len() != o.crosses.len() {
            return Err("coverage models differ in their coverpoints or crosses".into());
        }
        for (a, b) in self.points.iter().zip(&o.points) {
            let same = a.name == b.name
                && a.bins.len() == b.bins.len()
                && a.bins
                    .iter()
                    .zip(&b.bins)
                    .all(|(x, y)| (x.name.as_str(), x.lo, x.hi) == (y.name.as_str(), y.lo, y.hi));
            if !same {
                return Err(format!(
                    "coverpoint '{}' differs between the models",
                    a.name
                ));
            }
        }
        // Both models are whole and their coverpoints alike, so crosses of the same two
        // coverpoints have the same counts.
        for (a, b) in self.crosses.iter().zip(&o.crosses) {
            if a.name != b.name || (a.a, a.b) != (b.a, b.b) {
                return Err(format!("cross '{}' differs between the models", a.name));
            }
        }
        Ok(())
    }

    /// Adds the hits of `o`, a model of the same shape (a run of the same testbench). A model
    /// of another shape, or a count that would overflow, is an error and changes nothing.
    pub fn merge(&mut self, o: &Coverage) -> Result<(), String> {
        self.same_model(o)?;
        let mut m = self.clone();
        let add = |x: &mut u64, y: u64| -> Result<(), String> {
            *x = x.checked_add(y).ok_or("coverage hit count overflows u64")?;
            Ok(())
        };
        for (a, b) in m.points.iter_mut().zip(&o.points) {
            for (x, y) in a.bins.iter_mut().zip(&b.bins) {
                add(&mut x.hits, y.hits)?;
            }
            add(&mut a.unbinned, b.unbinned)?;
        }
        for (a, b) in m.crosses.iter_mut().zip(&o.crosses) {
            for (ra, rb) in a.hits.iter_mut().zip(&b.hits) {
                for (x, y) in ra.iter_mut().zip(rb) {
                    add(x, *y)?;
                }
            }
        }
        *self = m;
        Ok(())
    }

    /// Bins (coverpoint bins and cross bins) in all, and how many were hit.
    pub fn totals(&self) -> (usize, usize) {
        let mut total = 0;
        let mut hit = 0;
        for p in &self.points {
            total += p.bins.len();
            hit += p.hit_bins();
        }
        for c in &self.crosses {
            for row in &c.hits {
                total += row.len();
                hit += row.iter().filter(|h| **h > 0).count();
            }
        }
        (total, hit)
    }

    /// Percentage of bins hit (100 for an empty model).
    pub fn percent(&self) -> f64 {
        let (t, h) = self.totals();
        if t == 0 {
            100.0
        } else {
            100.0 * h as f64 / t as f64
        }
    }

    /// Names of every bin never hit: `point.bin` and `cross.(binA, binB)`.
    pub fn unhit(&self) -> Vec<String> {
        let mut v = Vec::new();
        for p in &self.points {
            for b in p.bins.iter().filter(|b| b.hits == 0) {
                v.push(format!("{}.{}", p.name, b.name));
            }
        }
        for c in &self.crosses {
            for (i, row) in c.hits.iter().enumerate() {
                for (j, h) in row.iter().enumerate() {
                    if *h == 0 {
                        v.push(format!(
                            "{}.({}, {})",
                            c.name, self.points[c.a].bins[i].name, self.points[c.b].bins[j].name
                        ));
                    }
                }
            }
        }
        v
    }

    /// A readable report: per coverpoint and cross, bins hit of total, then the unhit bins.
    pub fn report(&self) -> String {
        let mut s = String::new();
        let (t, h) = self.totals();
        let _ = writeln!(s, "coverage: {h}/{t} bins ({:.1} %)", self.percent());
        for p in &self.points {
            let _ = writeln!(
                s,
                "  {:<24} {}/{} bins{}",
                p.name,
                p.hit_bins(),
                p.bins.len(),
                if p.unbinned > 0 {
                    format!(", {} samples in no bin", p.unbinned)
                } else {
                    String::new()
                }
            );
        }
        for c in &self.crosses {
            let n: usize = c.hits.iter().map(Vec::len).sum();
            let hit: usize = c.hits.iter().flatten().filter(|x| **x > 0).count();
            let _ = writeln!(s, "  {:<24} {hit}/{n} bins (cross)", c.name);
        }
        let u = self.unhit();
        if !u.is_empty() {
            let _ = writeln!(s, "  unhit: {}", u.join(", "));
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_read_from_a_file_is_checked_whole() {
        let mut c = Coverage::new();
        let a = c.add(Coverpoint::new("a").value("x", 0).value("y", 1));
        let b = c.add(Coverpoint::new("b").value("p", 0));
        c.cross("ab", a, b);
        assert!(c.validate().is_ok());
        // An enumeration's bins are its values in order.
        let e = Coverpoint::new("a").values(&["x", "y"]);
        let bins: Vec<_> = e
            .bins
            .iter()
            .map(|b| (b.name.as_str(), b.lo, b.hi))
            .collect();
        assert_eq!(bins, [("x", 0, 0), ("y", 1, 1)]);
        let mut short = c.clone();
        short.crosses[0].hits.pop();
        assert!(short.validate().unwrap_err().contains("not 2 x 1"));
        assert!(c.same_model(&short).is_err());
        let mut dangling = c.clone();
        dangling.crosses[0].b = 7;
        assert!(dangling
            .validate()
            .unwrap_err()
            .contains("no such coverpoint"));
        let mut empty = c.clone();
        empty.points[0].bins[0].lo = 5;
        assert!(empty.validate().unwrap_err().contains("bin 'x' is empty"));
    }

    #[test]
    fn bins_crosses_and_unhit_report() {
        let mut c = Coverage::new();
        let a = c.add(
            Coverpoint::new("mode")
                .value("normal", 0)
                .value("bypass", 1),
        );
        let b = c.add(
            Coverpoint::new("u")
                .value("zero", 0)
                .value("max", 255)
                .ranges("mid", 1, 254, 4),
        );
        c.cross("mode_x_u", a, b);
        c.sample(&[0, 0]);
        c.sample(&[1, 255]);
        c.sample(&[0, 100]);
        c.sample(&[7, 100]);
        assert_eq!(c.points[1].bins.len(), 6);
        assert_eq!(c.points[1].bins[2].lo, 1);
        assert_eq!(c.points[1].bins[5].hi, 254);
        assert_eq!(c.points[0].unbinned, 1);
        let row = |m: usize| c.crosses[0].hits[m].clone();
        assert_eq!(
            row(0),
            [1, 0, 0, 1, 0, 0],
            "normal with zero, then with mid[1]"
        );
        assert_eq!(
            row(1),
            [0, 1, 0, 0, 0, 0],
            "bypass with max; mode 7 in no bin"
        );
        let (t, h) = c.totals();
        assert_eq!(t, 2 + 6 + 12);
        assert_eq!(h, 2 + 3 + 3);
        let u = c.unhit();
        assert!(u.contains(&"u.mid[0]".to_string()));
        assert!(u.contains(&"mode_x_u.(bypass, zero)".to_string()));
        assert_eq!(c.percent(), 40.0);
        assert_eq!(Coverage::new().percent(), 100.0);
        let r = c.report();
        assert!(r.starts_with("coverage: 8/20 bins (40.0 %)\n"), "{r}");
        assert!(r.contains("\n  mode                     2/2 bins, 1 samples in no bin\n"));
        assert!(r.contains("\n  u                        3/6 bins\n"), "{r}");
        assert!(
            r.contains("\n  mode_x_u                 3/12 bins (cross)\n"),
            "{r}"
        );
        assert_eq!(r.matches("in no bin").count(), 1, "{r}");
        assert!(r.contains("\n  unhit: u.mid[0], "), "{r}");
    }

    /// Two coverpoints crossed and a third, each change below alone makes another model.
    #[test]
    fn models_differing_anywhere_in_shape_are_not_the_same() {
        let model = || {
            let mut c = Coverage::new();
            let a = c.add(Coverpoint::new("a").value("x", 0).value("y", 1));
            let b = c.add(Coverpoint::new("b").value("p", 0));
            c.add(Coverpoint::new("c").value("r", 0));
            c.cross("ab", a, b);
            c
        };
        let mut hit = model();
        hit.sample(&[1, 0, 0]);
        assert_eq!(model().same_model(&hit), Ok(()), "hits are not shape");
        type Change = (&'static str, fn(&mut Coverage));
        let changes: [Change; 8] = [
            ("a coverpoint more", |m| {
                m.add(Coverpoint::new("d"));
            }),
            ("a cross more", |m| m.cross("ba", 1, 0)),
            ("a coverpoint renamed", |m| m.points[2].name = "q".into()),
            ("a bin more", |m| {
                m.points[2] = m.points[2].clone().value("s", 1)
            }),
            ("a bin renamed", |m| m.points[2].bins[0].name = "s".into()),
            ("a bin moved", |m| m.points[2].bins[0].hi = 1),
            ("a cross renamed", |m| m.crosses[0].name = "ba".into()),
            ("a cross of another coverpoint", |m| m.crosses[0].b = 2),
        ];
        for (what, change) in changes {
            let mut other = model();
            change(&mut other);
            assert_eq!(other.validate(), Ok(()), "{what}: still a whole model");
            assert!(model().same_model(&other).is_err(), "{what}");
            assert!(other.same_model(&model()).is_err(), "{what}");
            assert!(model().merge(&other).is_err(), "{what}");
        }
    }
}
