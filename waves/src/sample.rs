//! A simulator's VCD read back once a cycle: the signals under one scope (an RTL's
//! internals, dumped by Verilator or Icarus), as a co-simulation's waveform shows them beside
//! the model's ports.

use std::io::BufReader;
use std::ops::Range;
use std::path::Path;
use vcd::{Command, IdCode, ReferenceIndex, ScopeItem, Value};

/// The signals under one scope of a VCD, sampled once a cycle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sampled {
    /// Each signal's path below the scope (`acc`, `u_stage.acc`, `mem[3]`) and width, in the
    /// VCD's order (a scope's signals together).
    pub signals: Vec<(String, u32)>,
    /// `values[i][k]`: signal `k` in cycle `cycles.start + i` (`None`: x or z).
    pub values: Vec<Vec<Option<u64>>>,
    /// The cycles sampled.
    pub cycles: Range<usize>,
    /// Signals left out: wider than 64 bits, real or string, or beyond [`MAX_SIGNALS`].
    pub skipped: usize,
}

/// The most signals kept (a big design's dump keeps its first ones).
pub const MAX_SIGNALS: usize = 4096;

/// Reads the VCD at `path` and samples the signals under the first scope whose path ends
/// with `scope` (`["tb", "dut"]`: `tb.dut`, or `TOP.tb.dut` as Verilator names it) in
/// `cycles`: cycle `c` has the values of the last changes before time `before(c)`, in
/// picoseconds. A cycle before the dump's first time has no values (`None`).
pub fn sample(
    path: &Path,
    scope: &[&str],
    cycles: Range<usize>,
    before: impl Fn(usize) -> u64,
) -> Result<Sampled, String> {
    let shown = path.display();
    let err = |e: std::io::Error| format!("{shown}: {e}");
    let f = std::fs::File::open(path).map_err(err)?;
    let mut p = vcd::Parser::new(BufReader::new(f));
    let header = p.parse_header().map_err(err)?;
    let ps = header
        .timescale
        .map_or(Some(1), |(n, unit)| picoseconds(n, unit))
        .ok_or_else(|| format!("{shown}: a timescale finer than 1 ps"))?;
    let items = find(&header.items, scope)
        .ok_or_else(|| format!("{shown}: no scope {}", scope.join(".")))?;
    let mut out = Sampled {
        cycles: cycles.clone(),
        ..Sampled::default()
    };
    // The signals each id code stands for (a net seen in several scopes has one code).
    let mut of_code: std::collections::HashMap<IdCode, Vec<usize>> = Default::default();
    collect(items, "", &mut out, &mut of_code);
    let mut now: Vec<Option<u64>> = vec![None; out.signals.len()];
    let mut next = cycles.start;
    let mut take = |upto: Option<u64>, now: &[Option<u64>], out: &mut Sampled| {
        while next < cycles.end && upto.is_none_or(|t| before(next) <= t * ps) {
            out.values.push(now.to_vec());
            next += 1;
        }
    };
    let mut started = false;
    for c in p {
        match c.map_err(err)? {
            Command::Timestamp(t) => {
                // Cycles before the first time dumped have no values.
                let known = if started {
                    now.clone()
                } else {
                    vec![None; now.len()]
                };
                take(Some(t), &known, &mut out);
                started = true;
            }
            Command::ChangeScalar(id, v) => set(&of_code, &mut now, id, scalar(v)),
            Command::ChangeVector(id, v) => set(&of_code, &mut now, id, bits(v.iter())),
            _ => {}
        }
    }
    take(None, &now, &mut out);
    Ok(out)
}

/// Picoseconds in `n` of `unit` (`None` below one).
fn picoseconds(n: u32, unit: vcd::TimescaleUnit) -> Option<u64> {
    use vcd::TimescaleUnit::*;
    let per = match unit {
        S => 1_000_000_000_000,
        MS => 1_000_000_000,
        US => 1_000_000,
        NS => 1_000,
        PS => 1,
        FS => return (n.is_multiple_of(1000) && n > 0).then(|| u64::from(n / 1000)),
    };
    Some(u64::from(n) * per)
}

/// The items of the first scope whose path ends with `path`.
fn find<'a>(items: &'a [ScopeItem], path: &[&str]) -> Option<&'a [ScopeItem]> {
    for it in items {
        if let ScopeItem::Scope(s) = it {
            if s.identifier == path[0] {
                let inner = if path.len() == 1 {
                    Some(&s.items[..])
                } else {
                    direct(&s.items, &path[1..])
                };
                if inner.is_some() {
                    return inner;
                }
            }
            if let Some(found) = find(&s.items, path) {
                return Some(found);
            }
        }
    }
    None
}

/// The items of the scope `path` directly under `items`.
fn direct<'a>(items: &'a [ScopeItem], path: &[&str]) -> Option<&'a [ScopeItem]> {
    items.iter().find_map(|it| match it {
        ScopeItem::Scope(s) if s.identifier == path[0] => match path {
            [_] => Some(&s.items[..]),
            [_, rest @ ..] => direct(&s.items, rest),
            [] => None,
        },
        _ => None,
    })
}

/// Every variable under `items` (names prefixed with `prefix`), in order.
fn collect(
    items: &[ScopeItem],
    prefix: &str,
    out: &mut Sampled,
    of_code: &mut std::collections::HashMap<IdCode, Vec<usize>>,
) {
    for it in items {
        match it {
            ScopeItem::Scope(s) => collect(
                &s.items,
                &format!("{prefix}{}.", s.identifier),
                out,
                of_code,
            ),
            ScopeItem::Var(v) => {
                let kept = v.size <= 64
                    && !matches!(v.var_type, vcd::VarType::Real | vcd::VarType::String)
                    && out.signals.len() < MAX_SIGNALS;
                if !kept {
                    out.skipped += 1;
                    continue;
                }
                let name = match v.index {
                    Some(ReferenceIndex::BitSelect(i)) => format!("{}[{i}]", v.reference),
                    _ => v.reference.clone(),
                };
                of_code.entry(v.code).or_default().push(out.signals.len());
                out.signals.push((format!("{prefix}{name}"), v.size));
            }
            _ => {}
        }
    }
}

fn set(
    of_code: &std::collections::HashMap<IdCode, Vec<usize>>,
    now: &mut [Option<u64>],
    id: IdCode,
    v: Option<u64>,
) {
    for &k in of_code.get(&id).into_iter().flatten() {
        now[k] = v;
    }
}

fn scalar(v: Value) -> Option<u64> {
    match v {
        Value::V0 => Some(0),
        Value::V1 => Some(1),
        Value::X | Value::Z => None,
    }
}

/// A vector's bits, MSB first, as a number (`None` if any is x or z).
fn bits(v: impl Iterator<Item = Value>) -> Option<u64> {
    v.map(scalar)
        .try_fold(0u64, |acc, b| b.map(|b| (acc << 1) | b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Verilator's layout (`TOP.tb.dut`, a net under two scopes with one code, a timescale
    /// of 1 ns): each cycle takes the last values before its time; a cycle before the dump's
    /// first time has none; x is `None`; a bit of an array is named with its index; a
    /// 65-bit signal and a real are left out, counted.
    #[test]
    fn a_scope_is_sampled_once_a_cycle_before_each_time() {
        let vcd = "$timescale 1ns $end\n$scope module TOP $end\n$scope module tb $end\n\
            $var wire 4 ! a [3:0] $end\n$scope module dut $end\n$var wire 4 ! a [3:0] $end\n\
            $var wire 1 \" q $end\n$scope module u $end\n$var wire 1 # m [2] $end\n\
            $var wire 65 $ wide [64:0] $end\n$var real 64 % r $end\n$upscope $end\n\
            $upscope $end\n$upscope $end\n$upscope $end\n$enddefinitions $end\n\
            #4\nb0101 !\n0\"\nx#\n#6\n1\"\n#8\nb1 !\n1#\n#10\nbx1 !\n";
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("d.vcd");
        std::fs::write(&p, vcd).unwrap();
        // Cycle c before (2c + 1) ns: cycle 1 before 3 ns (nothing dumped yet), cycle 2
        // before 5 ns, 3 before 7, 4 before 9, 5 before 11.
        let s = sample(&p, &["tb", "dut"], 1..6, |c| (2 * c as u64 + 1) * 1000).unwrap();
        let names: Vec<&str> = s.signals.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["a", "q", "u.m[2]"]);
        assert_eq!(s.skipped, 2);
        assert_eq!(
            s.values,
            [
                vec![None, None, None],
                vec![Some(5), Some(0), None],
                vec![Some(5), Some(1), None],
                vec![Some(1), Some(1), Some(1)],
                vec![None, Some(1), Some(1)],
            ]
        );
        assert!(sample(&p, &["tb", "nope"], 0..1, |_| 0).is_err());
    }
}
