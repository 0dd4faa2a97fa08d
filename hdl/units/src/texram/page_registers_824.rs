//! Page registers 824: one open row per bank. Reads never modify a row, so no precharge is
//! waited for; an access whose banks all hit their open rows takes one 30 ns slot, and "a page
//! fault causes a delay of another 30 ns" (section 5): two slots if any bank it reads misses,
//! whatever the number of banks that miss. Every missed bank then holds its new row.

use super::banks_810::{BANKS, ROW_WORDS};

/// The open row of every bank.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PageRegisters {
    open: [Option<u32>; BANKS],
}

/// What one access cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cost {
    /// 1, or 2 after a page fault.
    pub slots: u32,
    /// Banks that missed their open row.
    pub faults: u32,
}

impl PageRegisters {
    /// All rows closed (the first access to a bank faults).
    pub fn new() -> PageRegisters {
        PageRegisters::default()
    }

    /// The row bank `bank` has open.
    pub fn open_row(&self, bank: usize) -> Option<u32> {
        self.open[bank]
    }

    /// One access reading `word[bank]` from the banks where it is `Some`.
    pub fn access(&mut self, word: &[Option<u32>; BANKS]) -> Cost {
        let mut faults = 0;
        for (open, w) in self.open.iter_mut().zip(word) {
            if let Some(w) = w {
                let row = w / ROW_WORDS;
                if *open != Some(row) {
                    faults += 1;
                    *open = Some(row);
                }
            }
        }
        Cost {
            slots: if faults > 0 { 2 } else { 1 },
            faults,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_take_one_slot_and_any_miss_two() {
        let mut p = PageRegisters::new();
        let mut w = [None; BANKS];
        w[0] = Some(5);
        w[3] = Some(700);
        assert_eq!(
            p.access(&w),
            Cost {
                slots: 2,
                faults: 2
            }
        );
        assert_eq!(p.open_row(3), Some(1));
        assert_eq!(
            p.access(&w),
            Cost {
                slots: 1,
                faults: 0
            }
        );
        w[0] = Some(ROW_WORDS - 1);
        assert_eq!(
            p.access(&w),
            Cost {
                slots: 1,
                faults: 0
            }
        );
        w[0] = Some(ROW_WORDS);
        assert_eq!(
            p.access(&w),
            Cost {
                slots: 2,
                faults: 1
            }
        );
        // A bank not read keeps its row.
        assert_eq!(
            p.access(&[None; BANKS]),
            Cost {
                slots: 1,
                faults: 0
            }
        );
        assert_eq!(p.open_row(0), Some(1));
        assert_eq!(p.open_row(5), None);
    }
}
