//! Inverse square root of normal unit 156 (US 2004/0207631, para. 0080: "computing the inverse
//! of the square root"): a table of first approximations plus Newton-Raphson iterations.
//!
//! The input is a mantissa `m` in [1, 4) (`uQ2.M`); the output `y ~ 1/sqrt(m)` in (1/2, 1]
//! (`uQ1.Y`). The table is indexed by one bit that tells [1,2) from [2,4) and the next
//! `table_bits - 1` bits below the leading one; each entry is `1/sqrt` of its interval's
//! midpoint, correctly rounded to Y fraction bits (computed with integer square roots at
//! construction). Each iteration is
//!
//! ```text
//! t  = round(m * y^2)            to Y+2 fraction bits
//! y' = round(y * (3 - t) / 2)    to Y fraction bits
//! ```
//!
//! (nearest, ties to even; all products exact before rounding). Error: a table entry is off by
//! at most `e0 = 2^-(table_bits+1) + 2^-(Y+1)` relative; an iteration turns a relative error
//! `e` into at most `1.5 e^2 + 0.5 e^3` plus its rounding (`2^-Y` and `2^-(Y+2)` scaled):
//! `golden::rsqrt::error_bound_ulps` gives the bound in ULPs, which the exhaustive test checks against the
//! exact integer reference over every input.
//!
//! Pipeline: the table lookup is one register stage, each iteration one more: latency
//! `1 + iterations`.

use crate::bump::params::{RsqrtParams, ROUND, SAT};
use crate::fx::{Format, NarrowPath, Narrowing};
use crate::kernel::declared::Narrowings;
use crate::kernel::{Module, Reg, Signal, Visitor};

/// The first-approximation table.
#[derive(Clone, Debug)]
pub struct RsqrtTable {
    p: RsqrtParams,
    entries: Vec<u64>,
}

impl RsqrtTable {
    pub fn new(p: RsqrtParams) -> Result<RsqrtTable, String> {
        if !(1..=p.mant_frac).contains(&p.table_bits) {
            return Err(format!(
                "rsqrt: table_bits {} outside 1..=mant_frac ({})",
                p.table_bits, p.mant_frac
            ));
        }
        let lo_bits = p.table_bits - 1;
        let mut entries = Vec::with_capacity(1 << p.table_bits);
        for hi in 0..2u32 {
            for lo in 0..(1u64 << lo_bits) {
                let shift = p.mant_frac + hi - lo_bits;
                let start = ((1u128 << lo_bits) | u128::from(lo)) << shift;
                // Midpoint with one more fraction bit: 2*start + 2^shift, over 2^(M+1).
                let mid2 = 2 * start + (1u128 << shift);
                // y = sqrt(2^(2Y+M+1) / mid2); z = floor(2y); round = (z+1)/2.
                let z = ((1u128 << (2 * p.y_frac + p.mant_frac + 1 + 2)) / mid2).isqrt();
                entries.push(((z + 1) >> 1) as u64);
            }
        }
        Ok(RsqrtTable { p, entries })
    }

    /// The table index of mantissa `m` (raw `uQ2.M`, in [2^M, 2^(M+2))).
    #[inline]
    pub fn index(&self, m: u64) -> usize {
        let (mf, lo_bits) = (self.p.mant_frac, self.p.table_bits - 1);
        let hi = (m >> (mf + 1)) & 1;
        let shift = mf + hi as u32 - lo_bits;
        let lo = (m >> shift) & ((1 << lo_bits) - 1);
        ((hi << lo_bits) | lo) as usize
    }

    #[inline]
    pub fn lookup(&self, m: u64) -> u64 {
        self.entries[self.index(m)]
    }

    pub fn entries(&self) -> &[u64] {
        &self.entries
    }
}

/// One Newton-Raphson iteration on raw values: `m` (`uQ2.M`), `y` (`uQ1.Y`).
#[inline]
pub fn nr_step(p: &RsqrtParams, m: u64, y: u64) -> u64 {
    nr_step_in(p, m, y, &mut NrNarrowings::new(p, 1))
}

/// An iteration's two narrowings: `t = m y^2` into `uQ2.(Y+2)` and the new `y` into `uQ1.Y`.
#[derive(Clone, Debug)]
pub struct NrNarrowings {
    t: Narrowing,
    y: Narrowing,
}

const T_NAMES: [&str; 3] = ["t1", "t2", "t3"];
const NEXT_NAMES: [&str; 3] = ["y1", "y2", "y3"];

impl NrNarrowings {
    /// Iteration `i` (1-based)'s, named `t<i>` and `y<i>`.
    pub fn new(p: &RsqrtParams, i: usize) -> NrNarrowings {
        let yf = p.y_frac;
        // t = m y^2 in uQ2.(Y+2): y^2 m is close to 1; 4 integer bits leave room for any input.
        let t_fmt = Format::new(yf + 4, yf as i32 + 2, false);
        // y stays near rsqrt(m) in (0.5, 1] from the table on (each step moves it closer), so
        // t = m y^2 stays near 1 and the next y near rsqrt(m): neither comes near 4 or 2.
        const NEAR_ONE: &str = "t = m y^2 is 1 within the table's error, far below 4";
        const NEAR_RSQRT: &str =
            "y (3 - t) / 2 from y <= 1 and t >= 1/4 (m >= 1, y >= 1/2) is at most 1.375, below 2";
        NrNarrowings {
            t: Narrowing::new(T_NAMES[i - 1], t_fmt, ROUND, SAT)
                .unreachable(NarrowPath::High, NEAR_ONE),
            y: Narrowing::new(NEXT_NAMES[i - 1], y_fmt(p), ROUND, SAT)
                .unreachable(NarrowPath::High, NEAR_RSQRT),
        }
    }
}

impl Narrowings for NrNarrowings {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        v.narrowing(&self.t);
        v.narrowing(&self.y);
    }
}

/// [`nr_step`] through named narrowings (counted when numeric tracking is on).
#[inline]
pub fn nr_step_in(p: &RsqrtParams, m: u64, y: u64, n: &mut NrNarrowings) -> u64 {
    let (mf, yf) = (p.mant_frac, p.y_frac);
    let (m, y) = (i128::from(m), i128::from(y));
    let t = n.t.raw(m * y * y, (mf + 2 * yf) as i32);
    let e = (3i128 << (yf + 2)) - t;
    n.y.raw(y * e, (2 * yf + 3) as i32) as u64
}

/// Output format `uQ1.Y`.
pub fn y_fmt(p: &RsqrtParams) -> Format {
    Format::unsigned(p.y_frac + 1, p.y_frac as i32)
}

/// Mantissa format `uQ2.M`.
pub fn m_fmt(p: &RsqrtParams) -> Format {
    Format::unsigned(p.mant_frac + 2, p.mant_frac as i32)
}

/// The whole unit as a function (what the pipeline computes, stage by stage).
pub fn rsqrt(table: &RsqrtTable, m: u64) -> u64 {
    let mut y = table.lookup(m);
    for _ in 0..table.p.iterations {
        y = nr_step(&table.p, m, y);
    }
    y
}

const M_NAMES: [&str; 4] = ["m0_r", "m1_r", "m2_r", "m3_r"];
const Y_NAMES: [&str; 4] = ["y0_r", "y1_r", "y2_r", "y3_r"];

/// The rsqrt unit as pipeline stages: table (1 stage) then one stage per iteration.
#[derive(Clone, Debug, Module)]
#[module(kind = "rsqrt_156")]
pub struct Rsqrt {
    #[instance]
    name: String,
    table: RsqrtTable,
    #[input]
    pub m: Signal,
    #[output]
    pub y: Signal,
    /// Per stage: the mantissa carried along and the current approximation.
    #[reg]
    m_r: Vec<Reg>,
    #[reg]
    y_r: Vec<Reg>,
    /// Each iteration's narrowings.
    #[narrow]
    steps: Vec<NrNarrowings>,
}

impl Rsqrt {
    pub fn new(name: &str, p: RsqrtParams) -> Result<Rsqrt, String> {
        let n = 1 + p.iterations as usize;
        Ok(Rsqrt {
            name: name.into(),
            table: RsqrtTable::new(p)?,
            m: Signal::new("m", m_fmt(&p)),
            y: Signal::new("y", y_fmt(&p)),
            m_r: M_NAMES[..n]
                .iter()
                .map(|nm| Reg::new(nm, m_fmt(&p)))
                .collect(),
            y_r: Y_NAMES[..n]
                .iter()
                .map(|nm| Reg::new(nm, y_fmt(&p)))
                .collect(),
            steps: (1..n).map(|i| NrNarrowings::new(&p, i)).collect(),
        })
    }

    pub fn latency(&self) -> usize {
        self.y_r.len()
    }

    pub fn table(&self) -> &RsqrtTable {
        &self.table
    }
}

impl Rsqrt {
    #[inline]
    /// The table stage and the Newton-Raphson stages, one register stage each.
    pub fn eval(&mut self) {
        let m = self.m.bits();
        // Stage 0: table lookup. An input below 1 (zero, when idle; never from unit 156, whose
        // sum of squares is at least 1) gives 0 at every stage, as the Verilog twin's
        // `below_one`.
        let y0 = if m >> self.table.p.mant_frac == 0 {
            0
        } else {
            self.table.lookup(m)
        };
        self.m_r[0].set_next_bits(m);
        self.y_r[0].set_next_bits(y0);
        for s in 1..self.y_r.len() {
            let (mq, yq) = (self.m_r[s - 1].q().bits(), self.y_r[s - 1].q().bits());
            let y = if mq >> self.table.p.mant_frac == 0 {
                0
            } else {
                nr_step_in(&self.table.p, mq, yq, &mut self.steps[s - 1])
            };
            self.m_r[s].set_next_bits(mq);
            self.y_r[s].set_next_bits(y);
        }
        let last = self.y_r.len() - 1;
        self.y.follow(self.y_r[last].q());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entry `e` of the interval whose midpoint is `mid2 / 2^(M+1)` is `1/sqrt(mid)` rounded to
    /// nearest at Y fraction bits: `(e - 1/2)^2 <= 2^2Y / mid < (e + 1/2)^2`, checked in integers.
    fn is_nearest(e: u64, mid2: u128, p: &RsqrtParams) -> bool {
        let target = 1u128 << (2 * p.y_frac + 2 + p.mant_frac + 1);
        let (lo, hi) = (2 * u128::from(e) - 1, 2 * u128::from(e) + 1);
        lo * lo * mid2 <= target && target < hi * hi * mid2
    }

    #[test]
    fn every_entry_is_the_nearest_to_its_interval_midpoint() {
        for (table_bits, mant_frac, y_frac) in [(1, 8, 8), (3, 10, 12), (8, 22, 24), (10, 12, 30)] {
            let p = RsqrtParams {
                table_bits,
                iterations: 0,
                mant_frac,
                y_frac,
            };
            let t = RsqrtTable::new(p).unwrap();
            assert_eq!(t.entries().len(), 1 << table_bits, "{p:?}");
            // Walk the mantissas [1, 4) interval by interval: [1,2) has 2^(table_bits-1)
            // intervals of 2^-(table_bits-1), [2,4) as many of twice that.
            let lo_bits = table_bits - 1;
            for (i, &e) in t.entries().iter().enumerate() {
                let hi = (i >> lo_bits) as u32;
                let width = 1u64 << (mant_frac + hi - lo_bits);
                let start = (1u64 << (mant_frac + hi)) + (i as u64 & ((1 << lo_bits) - 1)) * width;
                let mid2 = u128::from(2 * start + width);
                assert!(is_nearest(e, mid2, &p), "{p:?} entry {i} = {e}");
                for m in [start, start + width / 2, start + width - 1] {
                    assert_eq!(t.index(m), i, "{p:?} m {m:#x}");
                    assert_eq!(t.lookup(m), e, "{p:?} m {m:#x}");
                }
            }
        }
    }

    #[test]
    fn the_one_bit_table_holds_one_over_root_1_5_and_root_3() {
        let p = RsqrtParams {
            table_bits: 1,
            iterations: 0,
            mant_frac: 8,
            y_frac: 8,
        };
        // 256/sqrt(1.5) = 209.02, 256/sqrt(3) = 147.80.
        assert_eq!(RsqrtTable::new(p).unwrap().entries(), &[209, 148]);
    }

    /// Below 1 (outside the mantissa's range) every stage gives 0; from 1 up the table and
    /// the iterations.
    #[test]
    fn inputs_below_one_give_zero_at_every_stage() {
        use crate::kernel::Sim;
        // Without iterations the table stage's check alone decides; with them, each stage's.
        for iterations in [0, 2] {
            let p = RsqrtParams {
                iterations,
                ..RsqrtParams::default()
            };
            let mut sim = Sim::new(Rsqrt::new("rsqrt_156", p).unwrap()).check_schedule(true);
            let one = 1u64 << p.mant_frac;
            let inputs = [0, 1, one - 1, one, one >> 1, 3 * one, one - 1, 4 * one - 1];
            let lat = sim.dut.latency();
            let table = RsqrtTable::new(p).unwrap();
            for c in 0..inputs.len() + lat {
                sim.dut.m.set_bits(*inputs.get(c).unwrap_or(&0));
                sim.eval();
                if let Some(&m) = c.checked_sub(lat).and_then(|k| inputs.get(k)) {
                    let want = if m < one { 0 } else { rsqrt(&table, m) };
                    assert_eq!(sim.dut.y.bits(), want, "{iterations}: m {m:#x}");
                }
                sim.tick();
            }
        }
    }
}
