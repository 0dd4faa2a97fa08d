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
//! In the waveform a violation is the `violation` wire's bit for its rule ([`rule`]) in the
//! cycle before the edge that breaks it, and the `violations` register counts them.
//!
//! # Timing
//! All times in controller cycles of `cycle_ns` (default 5 ns). Defaults reproduce the
//! document's figures: a page-mode access `t_cas + t_cp` = 3 + 3 cycles = 30 ns, a page fault
//! `t_rp + t_rcd` = 3 + 3 cycles = another 30 ns.

use crate::fx::{Bit, Format, Fx};
use crate::kernel::declared::Regs;
use crate::kernel::{Dir, Module, Reg, RegOf, Signal, SignalOf, Visitor};

hdl::formats! {
    /// The address pins: a row, then a column.
    pub Addr = Format::uint(11);
    /// A data word.
    pub Word = Format::uint(16);
    /// One bit a rule ([`rule`]).
    pub Rules = Format::uint(8);
    /// Cycles a pin has held its level, saturating at 1023.
    pub HeldCycles = Format::uint(10);
}

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

    /// A word address as `(row, column)`. `cols` is a power of two (see
    /// [`DramParams::validate`]), so this is a shift and a mask, not a division.
    #[inline]
    pub fn row_col(&self, addr: u64) -> (u64, u64) {
        debug_assert!(self.cols.is_power_of_two());
        (
            addr >> self.cols.trailing_zeros(),
            addr & u64::from(self.cols - 1),
        )
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

/// The rules the model checks, one bit each of its `violation` wire (the cycle before the
/// edge that breaks them).
pub mod rule {
    /// WE# low: the texture DRAM is read here, never written.
    pub const WRITE: u64 = 1 << 0;
    /// RAS# fell after less than `t_rp` cycles high.
    pub const T_RP: u64 = 1 << 1;
    /// A row beyond the array.
    pub const ROW: u64 = 1 << 2;
    /// CAS# fell with RAS# high.
    pub const NO_ROW: u64 = 1 << 3;
    /// CAS# fell less than `t_rcd` cycles after RAS#.
    pub const T_RCD: u64 = 1 << 4;
    /// CAS# fell after less than `t_cp` cycles high.
    pub const T_CP: u64 = 1 << 5;
    /// A column beyond the page.
    pub const COL: u64 = 1 << 6;
    /// CAS# rose after less than `t_cas` cycles low.
    pub const T_CAS: u64 = 1 << 7;
}

/// The violations seen so far: counted (traced as the register `violations`), the first 20
/// described. Each cycle's are decided by `eval` and committed at the edge, as a register's
/// next value is; under reset none is.
#[derive(Clone, Debug)]
pub struct ViolationLog {
    count: Signal,
    cycle: u64,
    log: Vec<Violation>,
    next: Vec<String>,
}

impl ViolationLog {
    fn new() -> ViolationLog {
        ViolationLog {
            count: Signal::new("violations", Format::uint(40)),
            cycle: 0,
            log: Vec::new(),
            next: Vec::new(),
        }
    }
}

impl Regs for ViolationLog {
    #[inline]
    fn tick_regs(&mut self, reset: bool) {
        self.cycle += 1;
        if reset {
            self.next.clear();
            return;
        }
        if self.next.is_empty() {
            // The count holds (the common cycle: no violation).
            return;
        }
        let n = self.count.bits() + self.next.len() as u64;
        self.count.set_bits(n & ((1 << 40) - 1));
        for what in self.next.drain(..) {
            if self.log.len() < 20 {
                self.log.push(Violation {
                    cycle: self.cycle,
                    what,
                });
            }
        }
    }
    fn visit_regs(&self, v: &mut dyn Visitor) {
        v.signal(Dir::Reg, &self.count);
    }
}

/// A timing counter's register: cycles a pin has held its level, saturating at 1023 (every
/// timing is at most 1000 cycles, so a comparison with one is exact).
const LEVEL_MAX: u64 = 1023;

/// DRAM 604.
#[derive(Clone, Debug, Module)]
#[module(kind = "dram_604")]
pub struct Dram {
    #[instance]
    name: &'static str,
    p: DramParams,
    mem: Vec<u16>,
    #[input]
    pub ras_n: SignalOf<Bit>,
    #[input]
    pub cas_n: SignalOf<Bit>,
    #[input]
    pub we_n: SignalOf<Bit>,
    #[input]
    pub oe_n: SignalOf<Bit>,
    #[input]
    pub addr: SignalOf<Addr>,
    #[output]
    pub dq: SignalOf<Word>,
    #[output]
    pub dq_valid: SignalOf<Bit>,
    /// The rules ([`rule`]) the pins break at the coming edge.
    #[wire]
    pub violation: SignalOf<Rules>,
    /// The page register: the open row (valid while RAS# is low).
    #[reg]
    pub page_row: Reg,
    #[reg]
    col: Reg,
    /// RAS# and CAS# at the last edge.
    #[reg]
    ras_n_was: RegOf<Bit>,
    #[reg]
    cas_n_was: RegOf<Bit>,
    /// Cycles RAS#/CAS# have held their level, and cycles since RAS# fell.
    #[reg]
    ras_level_for: RegOf<HeldCycles>,
    #[reg]
    cas_level_for: RegOf<HeldCycles>,
    #[reg]
    since_ras_fall: RegOf<HeldCycles>,
    #[reg]
    log: ViolationLog,
}

impl Dram {
    pub fn new(name: &'static str, p: DramParams) -> Result<Dram, String> {
        p.validate()?;
        let rb = 32 - (p.rows - 1).leading_zeros().min(31);
        let cb = 32 - (p.cols - 1).leading_zeros().min(31);
        let high = |n| {
            let mut s = SignalOf::new(n);
            s.set_bool(true);
            s
        };
        let was_high = |n| RegOf::new(n).reset_to(Fx::from_int(Bit::FMT, 1));
        // After reset both pins have been high "long ago".
        let level = |n| RegOf::new(n).reset_to(Fx::from_int(HeldCycles::FMT, 1000));
        Ok(Dram {
            name,
            mem: (0..p.words()).map(DramParams::pattern).collect(),
            p,
            ras_n: high("ras_n"),
            cas_n: high("cas_n"),
            we_n: high("we_n"),
            oe_n: high("oe_n"),
            addr: SignalOf::new("addr"),
            dq: SignalOf::new("dq"),
            dq_valid: SignalOf::new("dq_valid"),
            violation: SignalOf::new("violation"),
            page_row: Reg::new("page_row", Format::uint(rb.max(1))),
            col: Reg::new("col", Format::uint(cb.max(1))),
            ras_n_was: was_high("ras_n_was"),
            cas_n_was: was_high("cas_n_was"),
            ras_level_for: level("ras_level_for"),
            cas_level_for: level("cas_level_for"),
            since_ras_fall: RegOf::new("since_ras_fall"),
            log: ViolationLog::new(),
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

    /// Violations counted since power-up.
    pub fn violations(&self) -> u64 {
        self.log.count.bits()
    }

    /// The first 20 violations, described.
    pub fn log(&self) -> &[Violation] {
        &self.log.log
    }

    /// Rule `bit` broken at the coming edge, if `broken`: flagged on the wire, described.
    fn check(&mut self, bit: u64, broken: bool, what: impl FnOnce() -> String) {
        if broken {
            self.violation.set_bits(self.violation.bits() | bit);
            self.log.next.push(what());
        }
    }

    /// Data out: CAS# low for at least `t_cas` cycles, OE# low. The column was latched at
    /// the falling edge, so data can come from the second low cycle on (`t_cas >= 2`).
    fn data_out(&mut self) {
        let valid = !self.ras_n.is_high()
            && !self.cas_n.is_high()
            && !self.oe_n.is_high()
            && !self.cas_n_was.q().is_high()
            && self.cas_level_for.q().bits() + 1 >= u64::from(self.p.t_cas);
        self.dq_valid.set_bool(valid);
        if valid {
            let a = self.page_row.q().bits() * u64::from(self.p.cols) + self.col.q().bits();
            self.dq.set_bits(u64::from(self.mem[a as usize]));
        }
    }

    /// The pins, one cycle: data out, and the rules and latches of the coming edge.
    pub fn eval(&mut self) {
        self.data_out();
        self.violation.set_bits(0);
        self.log.next.clear();
        let (ras_n, cas_n) = (self.ras_n.is_high(), self.cas_n.is_high());
        let (ras_was, cas_was) = (self.ras_n_was.q().is_high(), self.cas_n_was.q().is_high());
        let (ras_for, cas_for) = (self.ras_level_for.q().bits(), self.cas_level_for.q().bits());
        let since = self.since_ras_fall.q().bits();
        let a = self.addr.bits() as u32;
        let p = self.p;
        self.check(rule::WRITE, !self.we_n.is_high(), || {
            "WE# low: the texture DRAM is read here, never written".into()
        });
        let ras_falls = ras_was && !ras_n;
        if ras_falls {
            self.check(rule::T_RP, ras_for < u64::from(p.t_rp), || {
                format!("RAS# precharge {ras_for} cycles < t_rp {}", p.t_rp)
            });
            self.check(rule::ROW, a >= p.rows, || {
                format!("row {a} beyond {} rows", p.rows)
            });
            // Powers of two: the modulo is a mask.
            self.page_row.set_next_bits(u64::from(a & (p.rows - 1)));
        }
        if cas_was && !cas_n {
            self.check(rule::NO_ROW, ras_n, || {
                "CAS# fell with no open row (RAS# high)".into()
            });
            self.check(rule::T_RCD, since < u64::from(p.t_rcd), || {
                format!("RAS#-to-CAS# {since} cycles < t_rcd {}", p.t_rcd)
            });
            self.check(rule::T_CP, cas_for < u64::from(p.t_cp), || {
                format!("CAS# precharge {cas_for} cycles < t_cp {}", p.t_cp)
            });
            self.check(rule::COL, a >= p.cols, || {
                format!("column {a} beyond {} words per page", p.cols)
            });
            self.col.set_next_bits(u64::from(a & (p.cols - 1)));
        }
        let short = !cas_was && cas_n && cas_for < u64::from(p.t_cas);
        self.check(rule::T_CAS, short, || {
            format!("CAS# low {cas_for} cycles < t_cas {}", p.t_cas)
        });
        let held = |was: bool, now: bool, n: u64| {
            if was == now {
                (n + 1).min(LEVEL_MAX)
            } else {
                1
            }
        };
        self.ras_level_for
            .set_next_bits(held(ras_was, ras_n, ras_for));
        self.cas_level_for
            .set_next_bits(held(cas_was, cas_n, cas_for));
        let since = if ras_falls {
            1
        } else {
            (since + 1).min(LEVEL_MAX)
        };
        self.since_ras_fall.set_next_bits(since);
        self.ras_n_was.set_next_bool(ras_n);
        self.cas_n_was.set_next_bool(cas_n);
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
        assert_eq!(d.violations(), 0, "{:?}", d.log());
        // RAS# high (no row open), CAS# low for long: a violation and no data.
        for _ in 0..4 {
            assert_eq!(pins(&mut d, false, false, true, 0), None);
        }
        for _ in 0..5 {
            assert_eq!(pins(&mut d, false, true, true, 5), None, "no row open");
        }
        assert_eq!(d.violations(), 1, "{:?}", d.log());
    }

    /// Every violation is counted; the first 20 are described, with their edges.
    #[test]
    fn violations_are_counted_and_the_first_twenty_logged() {
        let mut d = Dram::new("dram_604", DramParams::default()).unwrap();
        for c in 0..30 {
            d.we_n.set_bool(!(3..28).contains(&c));
            pins(&mut d, false, false, false, 0);
        }
        assert_eq!(d.violations(), 25);
        assert_eq!(d.log().len(), 20);
        let cycles: Vec<u64> = d.log().iter().map(|v| v.cycle).collect();
        // Numbered by the edge that saw them: the edge after cycle c is the model's c + 1.
        assert_eq!(cycles, (4..24).collect::<Vec<_>>());
        assert!(d.log()[0].what.starts_with("WE# low"), "{:?}", d.log()[0]);
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
