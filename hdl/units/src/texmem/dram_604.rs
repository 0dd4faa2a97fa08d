//! Page-mode DRAM 604 (Schilling & Knittel, Figure 6, section 5), at pin level. Its control
//! unit is [`super::control_607`]; the rest of the memory path (CCC decode, cache 614, colour
//! extract and bilinear) is in [`super::texture_unit_602`].
//!
//! # The DRAM (like a vendor's behavioural model)
//! `rows x cols` words of 16 bits behind RAS#, CAS#, WE#, OE# and an 11-pin multiplexed
//! address. The falling edge of RAS# latches the row into the page register (the open row);
//! each falling edge of CAS# latches a column; `t_cas` cycles after it the word is driven on
//! DQ (with OE# low) until CAS# rises. The model checks the timing it is driven with and counts
//! every violation (with the first ones described): RAS# precharge `t_rp`, RAS#-to-CAS# delay
//! `t_rcd`, CAS# low `t_cas`, CAS# precharge `t_cp`, an address beyond the array, CAS# without
//! an open row, a write (WE# low: this model is read-only).
//!
//! # Timing
//! All times in controller cycles of `cycle_ns` (default 5 ns). Defaults reproduce the
//! document's figures: a page-mode access `t_cas + t_cp` = 3 + 3 cycles = 30 ns, a page fault
//! `t_rp + t_rcd` = 3 + 3 cycles = another 30 ns.

use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::signals;

/// Geometry and timing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DramParams {
    pub rows: u32,
    /// Words per row (the page).
    pub cols: u32,
    pub cycle_ns: u32,
    pub t_rp: u32,
    pub t_rcd: u32,
    pub t_cas: u32,
    pub t_cp: u32,
}

impl Default for DramParams {
    /// 256K x 16 with 512-word pages.
    fn default() -> Self {
        DramParams {
            rows: 512,
            cols: 512,
            cycle_ns: 5,
            t_rp: 3,
            t_rcd: 3,
            t_cas: 3,
            t_cp: 3,
        }
    }
}

impl DramParams {
    /// 1M x 16 with 1024-word pages.
    pub fn one_meg() -> DramParams {
        DramParams {
            rows: 1024,
            cols: 1024,
            ..DramParams::default()
        }
    }

    /// Words in the array.
    pub fn words(&self) -> u64 {
        u64::from(self.rows) * u64::from(self.cols)
    }

    pub fn validate(&self) -> Result<(), String> {
        for (n, v) in [("rows", self.rows), ("page words", self.cols)] {
            if !v.is_power_of_two() || !(2..=2048).contains(&v) {
                return Err(format!(
                    "{n} {v}: a power of two in 2..=2048 (11 address pins)"
                ));
            }
        }
        for (n, v) in [
            ("t_rp", self.t_rp),
            ("t_rcd", self.t_rcd),
            ("t_cp", self.t_cp),
            ("cycle_ns", self.cycle_ns),
        ] {
            if v == 0 || v > 1000 {
                return Err(format!("{n} {v}: 1..=1000"));
            }
        }
        if !(2..=1000).contains(&self.t_cas) {
            return Err(format!(
                "t_cas {}: 2..=1000 (the column is latched at CAS# falling)",
                self.t_cas
            ));
        }
        Ok(())
    }

    /// The contents the model powers up with: a fixed function of the address (so reads can
    /// be checked without loading anything).
    pub fn pattern(addr: u64) -> u16 {
        let x = addr.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 48;
        x as u16
    }
}

/// A timing or protocol violation seen by the DRAM model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Violation {
    pub cycle: u64,
    pub what: String,
}

/// DRAM 604.
#[derive(Clone, Debug)]
pub struct Dram {
    name: String,
    p: DramParams,
    mem: Vec<u16>,
    pub ras_n: Signal,
    pub cas_n: Signal,
    pub we_n: Signal,
    pub oe_n: Signal,
    pub addr: Signal,
    pub dq: Signal,
    pub dq_valid: Signal,
    /// The page register: the open row (valid while RAS# is low).
    pub page_row: Reg,
    col: Reg,
    /// Cycles RAS#/CAS# have held their level, and cycles since RAS# fell.
    ras_level_for: u32,
    cas_level_for: u32,
    since_ras_fall: u32,
    last: (bool, bool),
    cycle: u64,
    /// Violations counted, and the first ones described.
    pub violations: u64,
    pub log: Vec<Violation>,
}

impl Dram {
    pub fn new(name: &str, p: DramParams) -> Result<Dram, String> {
        p.validate()?;
        let rb = 32 - (p.rows - 1).leading_zeros().min(31);
        let cb = 32 - (p.cols - 1).leading_zeros().min(31);
        let mut ras_n = Signal::bit("ras_n");
        ras_n.set_bool(true);
        let mut cas_n = Signal::bit("cas_n");
        cas_n.set_bool(true);
        let mut we_n = Signal::bit("we_n");
        we_n.set_bool(true);
        let mut oe_n = Signal::bit("oe_n");
        oe_n.set_bool(true);
        Ok(Dram {
            name: name.into(),
            mem: (0..p.words()).map(DramParams::pattern).collect(),
            p,
            ras_n,
            cas_n,
            we_n,
            oe_n,
            addr: Signal::new("addr", Format::uint(11)),
            dq: Signal::new("dq", Format::uint(16)),
            dq_valid: Signal::bit("dq_valid"),
            page_row: Reg::new("page_row", Format::uint(rb.max(1))),
            col: Reg::new("col", Format::uint(cb.max(1))),
            ras_level_for: 1000,
            cas_level_for: 1000,
            since_ras_fall: 0,
            last: (true, true),
            cycle: 0,
            violations: 0,
            log: Vec::new(),
        })
    }

    /// Writes `words` into the array from word `base` (a back-door load, as a testbench
    /// preloads a vendor model; not a pin-level write).
    pub fn load(&mut self, base: u64, words: &[u16]) -> Result<(), String> {
        let end = base + words.len() as u64;
        if end > self.p.words() {
            return Err(format!(
                "{} words from {base} do not fit the DRAM's {} words",
                words.len(),
                self.p.words()
            ));
        }
        self.mem[base as usize..end as usize].copy_from_slice(words);
        Ok(())
    }

    fn violate(&mut self, what: String) {
        self.violations += 1;
        if self.log.len() < 20 {
            self.log.push(Violation {
                cycle: self.cycle,
                what,
            });
        }
    }
}

impl Module for Dram {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "dram_604"
    }
    fn eval(&mut self) {
        // Data out: CAS# low for at least t_cas cycles, OE# low.
        let (ras_n, cas_n) = (self.ras_n.is_high(), self.cas_n.is_high());
        // Low for `cas_level_for` earlier cycles plus this one; the column was latched at the
        // falling edge, so data can come from the second low cycle on (t_cas >= 2).
        let valid = !ras_n
            && !cas_n
            && !self.oe_n.is_high()
            && !self.last.1
            && self.cas_level_for + 1 >= self.p.t_cas;
        self.dq_valid.set_bool(valid);
        if valid {
            let a = u64::from(self.page_row.q().bits() as u32) * u64::from(self.p.cols)
                + self.col.q().bits();
            self.dq.set_bits(u64::from(self.mem[a as usize]));
        }
    }
    fn tick(&mut self, reset: bool) {
        self.cycle += 1;
        if reset {
            self.last = (true, true);
            self.ras_level_for = 1000;
            self.cas_level_for = 1000;
            return;
        }
        let (ras_n, cas_n) = (self.ras_n.is_high(), self.cas_n.is_high());
        let a = self.addr.bits() as u32;
        if !self.we_n.is_high() {
            self.violate("WE# low: the texture DRAM is read here, never written".into());
        }
        // RAS# edges.
        if self.last.0 && !ras_n {
            if self.ras_level_for < self.p.t_rp {
                self.violate(format!(
                    "RAS# precharge {} cycles < t_rp {}",
                    self.ras_level_for, self.p.t_rp
                ));
            }
            if a >= self.p.rows {
                self.violate(format!("row {a} beyond {} rows", self.p.rows));
            }
            self.page_row.set_next_bits(u64::from(a % self.p.rows));
            self.page_row.tick(false);
            self.since_ras_fall = 0;
        }
        // CAS# edges.
        if self.last.1 && !cas_n {
            if ras_n {
                self.violate("CAS# fell with no open row (RAS# high)".into());
            }
            if self.since_ras_fall < self.p.t_rcd {
                self.violate(format!(
                    "RAS#-to-CAS# {} cycles < t_rcd {}",
                    self.since_ras_fall, self.p.t_rcd
                ));
            }
            if self.cas_level_for < self.p.t_cp {
                self.violate(format!(
                    "CAS# precharge {} cycles < t_cp {}",
                    self.cas_level_for, self.p.t_cp
                ));
            }
            if a >= self.p.cols {
                self.violate(format!("column {a} beyond {} words per page", self.p.cols));
            }
            self.col.set_next_bits(u64::from(a % self.p.cols));
            self.col.tick(false);
        }
        if !self.last.1 && cas_n && self.cas_level_for < self.p.t_cas {
            self.violate(format!(
                "CAS# low {} cycles < t_cas {}",
                self.cas_level_for, self.p.t_cas
            ));
        }
        self.ras_level_for = if self.last.0 == ras_n {
            self.ras_level_for.saturating_add(1)
        } else {
            1
        };
        self.cas_level_for = if self.last.1 == cas_n {
            self.cas_level_for.saturating_add(1)
        } else {
            1
        };
        self.since_ras_fall = self.since_ras_fall.saturating_add(1);
        self.last = (ras_n, cas_n);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        signals!(v;
            Input: self.ras_n, self.cas_n, self.we_n, self.oe_n, self.addr;
            Output: self.dq, self.dq_valid;
            Reg: self.page_row, self.col);
        v.leave();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(set: impl Fn(&mut DramParams)) -> Result<(), String> {
        let mut p = DramParams::default();
        set(&mut p);
        p.validate()
    }

    /// The power-up contents: the top 16 bits of the address times 2^64 / golden ratio
    /// (values worked out apart), so neighbouring words differ.
    #[test]
    fn power_up_words_are_the_top_bits_of_a_fibonacci_hash() {
        let p = DramParams::pattern;
        assert_eq!((p(0), p(1), p(2), p(1 << 20)), (0, 0x9e37, 0x3c6e, 0x9b97));
        let words: std::collections::HashSet<u16> = (0..256).map(p).collect();
        assert_eq!(words.len(), 256);
    }

    /// One cycle at the pins (`true` = asserted, i.e. the pin low): the word on DQ if
    /// `dq_valid`.
    fn pins(d: &mut Dram, ras: bool, cas: bool, oe: bool, a: u64) -> Option<u16> {
        d.ras_n.set_bool(!ras);
        d.cas_n.set_bool(!cas);
        d.oe_n.set_bool(!oe);
        d.addr.set_bits(a);
        d.eval();
        let out = d.dq_valid.is_high().then(|| d.dq.bits() as u16);
        d.tick(false);
        out
    }

    /// DQ is driven only from the t_cas-th cycle of CAS# low on, with RAS# low (a row open)
    /// and OE# low; never when idle, when CAS# rises, with OE# high, or with no row open.
    #[test]
    fn dq_is_valid_only_in_a_whole_cas_cycle_with_a_row_open_and_oe_low() {
        let p = DramParams::default();
        let mut d = Dram::new("dram_604", p).unwrap();
        let word = DramParams::pattern(7 * u64::from(p.cols) + 5);
        let mut seen = Vec::new();
        for _ in 0..3 {
            seen.push(pins(&mut d, false, false, true, 0)); // idle
        }
        for _ in 0..3 {
            seen.push(pins(&mut d, true, false, true, 7)); // RAS# low with row 7
        }
        for _ in 0..4 {
            seen.push(pins(&mut d, true, true, true, 5)); // CAS# low with column 5
        }
        seen.push(pins(&mut d, true, false, true, 5)); // CAS# rises
        let mut want = vec![None; 8];
        want.extend([Some(word), Some(word), None]);
        assert_eq!(seen, want);
        // The same column again with OE# high: no data.
        for _ in 0..2 {
            assert_eq!(pins(&mut d, true, false, false, 5), None);
        }
        for _ in 0..4 {
            assert_eq!(pins(&mut d, true, true, false, 5), None, "OE# high");
        }
        assert_eq!(d.violations, 0, "{:?}", d.log);
        // RAS# high (no row open), CAS# low for long: a violation and no data.
        for _ in 0..4 {
            assert_eq!(pins(&mut d, false, false, true, 0), None);
        }
        for _ in 0..5 {
            assert_eq!(pins(&mut d, false, true, true, 5), None, "no row open");
        }
        assert_eq!(d.violations, 1, "{:?}", d.log);
    }

    /// Every violation is counted; the first 20 are described, with their edges.
    #[test]
    fn violations_are_counted_and_the_first_twenty_logged() {
        let mut d = Dram::new("dram_604", DramParams::default()).unwrap();
        for c in 0..30 {
            d.we_n.set_bool(!(3..28).contains(&c));
            pins(&mut d, false, false, false, 0);
        }
        assert_eq!(d.violations, 25);
        assert_eq!(d.log.len(), 20);
        let cycles: Vec<u64> = d.log.iter().map(|v| v.cycle).collect();
        // Numbered by the edge that saw them: the edge after cycle c is the model's c + 1.
        assert_eq!(cycles, (4..24).collect::<Vec<_>>());
        assert!(d.log[0].what.starts_with("WE# low"), "{:?}", d.log[0]);
    }

    /// Each range at both ends, and one beyond, naming the parameter.
    #[test]
    fn validate_takes_each_range_at_both_ends() {
        assert_eq!(DramParams::default().validate(), Ok(()));
        assert_eq!(DramParams::one_meg().words(), 1 << 20);
        for v in [2, 2048] {
            assert_eq!(check(|p| p.rows = v), Ok(()), "rows {v}");
            assert_eq!(check(|p| p.cols = v), Ok(()), "cols {v}");
        }
        for v in [0, 1, 3, 1536, 4096] {
            assert!(
                check(|p| p.rows = v).unwrap_err().starts_with("rows"),
                "{v}"
            );
            assert!(check(|p| p.cols = v).unwrap_err().starts_with("page words"));
        }
        type Set = fn(&mut DramParams, u32);
        let timings: [(&str, Set, u32); 5] = [
            ("t_rp", |p, v| p.t_rp = v, 1),
            ("t_rcd", |p, v| p.t_rcd = v, 1),
            ("t_cp", |p, v| p.t_cp = v, 1),
            ("cycle_ns", |p, v| p.cycle_ns = v, 1),
            ("t_cas", |p, v| p.t_cas = v, 2),
        ];
        for (name, set, lo) in timings {
            assert_eq!(check(|p| set(p, lo)), Ok(()), "{name} {lo}");
            assert_eq!(check(|p| set(p, 1000)), Ok(()), "{name} 1000");
            for bad in [lo - 1, 1001] {
                let e = check(|p| set(p, bad)).unwrap_err();
                assert!(e.starts_with(&format!("{name} {bad}: ")), "{e}");
            }
        }
    }
}
