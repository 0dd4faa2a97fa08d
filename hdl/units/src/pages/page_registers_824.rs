//! Page registers 824: one open row per bank. Reads never modify a row, so no precharge is
//! waited for; an access whose banks all hit their open rows takes one 30 ns slot, and "a page
//! fault causes a delay of another 30 ns" (section 5): two slots if any bank it reads misses,
//! whatever the number of banks that miss. Every missed bank then holds its new row.
//!
//! One clocked unit for every user of the banks: the chip 802 (its rasterizer accesses and the
//! video port's row transfers), the ray caster of Figure 15, the mipmap generator 816 on its
//! own frame store, and the behavioural chip. Its owner calls [`PageRegisters824::eval`] at
//! the start of its own `eval`, then [`PageRegisters824::round`] (or
//! [`PageRegisters824::open`]) for each access of the cycle in the order the banks make them;
//! the rows they leave open are the registers' next values.
//!
//! | register | format |
//! |---|---|
//! | `open0` .. `open{banks-1}` | `u<row_bits>`: the open row plus one, 0 while closed |

use crate::fx::Format;
use crate::kernel::{Module, Reg};

/// The most banks one set of page registers serves (the chip's eight).
pub const MAX_BANKS: usize = 8;
const OPEN_NAMES: [&str; MAX_BANKS] = [
    "open0", "open1", "open2", "open3", "open4", "open5", "open6", "open7",
];

/// The access slot in clock cycles: 30 ns at the 5 ns clock is 6; every user of the banks
/// takes `1..=15` (a four-bit slot counter).
pub fn check_slot_cycles(slot_cycles: u32) -> Result<(), String> {
    if !(1..=15).contains(&slot_cycles) {
        return Err(format!("slot_cycles {slot_cycles}: 1..=15"));
    }
    Ok(())
}

/// What one access round cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cost {
    /// 1, or 2 after a page fault.
    pub slots: u32,
    /// Banks that missed their open row.
    pub faults: u32,
}

/// The open row of every bank, as registers.
#[derive(Clone, Debug, Module)]
#[module(kind = "page_registers_824")]
pub struct PageRegisters824 {
    /// Per bank the open row plus one (0: closed).
    #[reg]
    open: Vec<Reg>,
    /// The rows as this cycle's accesses so far leave them (plus one), from `eval` on.
    rows: [u64; MAX_BANKS],
}

impl PageRegisters824 {
    /// `banks` (1..=8) page registers of `row_bits` bits (a row plus one), every row closed.
    pub fn new(banks: usize, row_bits: u32) -> PageRegisters824 {
        assert!((1..=MAX_BANKS).contains(&banks), "{banks} banks: 1..=8");
        PageRegisters824 {
            open: OPEN_NAMES[..banks]
                .iter()
                .map(|n| Reg::new(n, Format::uint(row_bits)))
                .collect(),
            rows: [0; MAX_BANKS],
        }
    }

    /// The start of a cycle: every row as the registers hold it.
    #[inline]
    pub fn eval(&mut self) {
        for (r, o) in self.rows.iter_mut().zip(&self.open) {
            *r = o.q().bits();
        }
    }

    /// The row `bank` has open (at the last edge).
    pub fn open_row(&self, bank: usize) -> Option<u64> {
        self.open[bank].q().bits().checked_sub(1)
    }

    /// An access to `row` of `bank`, after this cycle's earlier ones: whether it missed (the
    /// bank then holds `row`).
    #[inline]
    pub fn open(&mut self, bank: usize, row: u64) -> bool {
        let next = row + 1;
        if self.rows[bank] == next {
            return false;
        }
        self.rows[bank] = next;
        self.open[bank].set_next_bits(next);
        true
    }

    /// One round of an access, reading `(bank, row)` for each bank it reads (each bank at
    /// most once): one slot, two if any bank missed.
    #[inline]
    pub fn round(&mut self, rows: impl IntoIterator<Item = (usize, u64)>) -> Cost {
        let faults = rows.into_iter().filter(|&(b, r)| self.open(b, r)).count() as u32;
        Cost {
            slots: 1 + u32::from(faults > 0),
            faults,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Sim;

    /// One clocked round.
    fn round(sim: &mut Sim<PageRegisters824>, rows: &[(usize, u64)]) -> Cost {
        sim.dut.eval();
        let c = sim.dut.round(rows.iter().copied());
        sim.tick();
        c
    }

    #[test]
    fn hits_take_one_slot_and_any_miss_two() {
        let mut sim = Sim::new(PageRegisters824::new(8, 11)).check_schedule(true);
        let c = |slots, faults| Cost { slots, faults };
        assert_eq!(round(&mut sim, &[(0, 0), (3, 1)]), c(2, 2));
        assert_eq!(sim.dut.open_row(3), Some(1));
        assert_eq!(round(&mut sim, &[(0, 0), (3, 1)]), c(1, 0));
        assert_eq!(round(&mut sim, &[(0, 1), (3, 1)]), c(2, 1));
        // A bank not read keeps its row; an empty round is one slot.
        assert_eq!(round(&mut sim, &[]), c(1, 0));
        assert_eq!(sim.dut.open_row(0), Some(1));
        assert_eq!(sim.dut.open_row(5), None);
    }

    #[test]
    fn a_second_round_sees_the_rows_the_first_opened() {
        let mut p = PageRegisters824::new(2, 4);
        p.eval();
        assert_eq!(p.round([(0, 3)]).faults, 1);
        assert_eq!(p.round([(0, 3)]).faults, 0, "opened earlier this cycle");
        // Evaluated again (as the schedule check does): the same decisions.
        p.eval();
        assert_eq!(p.round([(0, 3)]).faults, 1);
        assert_eq!(p.open_row(0), None, "until the edge");
    }

    #[test]
    fn slot_cycles_are_one_to_fifteen() {
        assert!(check_slot_cycles(6).is_ok());
        assert_eq!(check_slot_cycles(0).unwrap_err(), "slot_cycles 0: 1..=15");
        assert!(check_slot_cycles(16).is_err());
    }
}
