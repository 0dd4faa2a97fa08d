//! DRAM control unit 607 (Schilling & Knittel, Figure 6, section 5): the word-read
//! controller that drives DRAM 604's pins.
//!
//! # The control unit 607
//! Takes word-read requests (valid + address), keeps the open page, and drives the pins: on a
//! page hit straight to the CAS# cycle; on a fault RAS# high for `t_rp`, RAS# low with the new
//! row for `t_rcd`, then the CAS# cycle. Counts reads, page hits and page faults. One request is
//! accepted when the previous one completes (`ready`).
//!
//! Timing parameters and the DRAM are in [`super::dram_604`].

use super::dram_604::{Dram, DramParams};
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::signals;

/// Controller states.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    Idle = 0,
    Precharge = 1,
    RowOpen = 2,
    CasLow = 3,
    CasHigh = 4,
}

/// DRAM control unit 607 (word reads), with the DRAM 604 it drives.
#[derive(Clone, Debug)]
pub struct DramCtrl {
    name: String,
    p: DramParams,
    pub req_valid: Signal,
    pub req_addr: Signal,
    pub ready: Signal,
    pub resp_valid: Signal,
    pub resp_data: Signal,
    pub state: Reg,
    count: Reg,
    open_row: Reg,
    row_open: Reg,
    addr_r: Reg,
    pub dram: Dram,
    pub reads: u64,
    pub page_hits: u64,
    pub page_faults: u64,
    accept: bool,
}

impl DramCtrl {
    pub fn new(name: &str, p: DramParams) -> Result<DramCtrl, String> {
        let dram = Dram::new("dram_604", p)?;
        let ab = 64 - (p.words() - 1).leading_zeros();
        Ok(DramCtrl {
            name: name.into(),
            p,
            req_valid: Signal::bit("req_valid"),
            req_addr: Signal::new("req_addr", Format::uint(ab.max(1))),
            ready: Signal::bit("ready"),
            resp_valid: Signal::bit("resp_valid"),
            resp_data: Signal::new("resp_data", Format::uint(16)),
            state: Reg::new("state", Format::uint(3)),
            count: Reg::new("count", Format::uint(11)),
            open_row: Reg::new("open_row", Format::uint(11)),
            row_open: Reg::new("row_open", Format::uint(1)),
            addr_r: Reg::new("addr_r", Format::uint(ab.max(1))),
            dram,
            reads: 0,
            page_hits: 0,
            page_faults: 0,
            accept: false,
        })
    }

    pub fn params(&self) -> &DramParams {
        &self.p
    }
}

impl Module for DramCtrl {
    fn instance(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> &'static str {
        "control_607"
    }
    fn eval(&mut self) {
        let st = self.state.q().bits();
        let n = self.count.q().bits() as u32;
        let cols = u64::from(self.p.cols);
        // A new request is taken when idle, or in the last cycle of CAS# precharge, so page-mode
        // reads follow each other every t_cas + t_cp cycles.
        let last_cp = st == State::CasHigh as u64 && n >= self.p.t_cp;
        let free = st == State::Idle as u64 || last_cp;
        self.ready.set_bool(free);
        self.accept = free && self.req_valid.is_high();
        let addr = if self.accept {
            self.req_addr.bits()
        } else {
            self.addr_r.q().bits()
        };
        let (row, col) = (addr / cols, addr % cols);
        let open = self.row_open.q().is_high() && self.open_row.q().bits() == row;
        // Pins from the current state (Moore outputs).
        let (ras_n, cas_n, a) = match st {
            s if s == State::Precharge as u64 => (true, true, row),
            s if s == State::RowOpen as u64 => (false, true, row),
            s if s == State::CasLow as u64 => (false, false, col),
            _ => (!self.row_open.q().is_high(), true, col),
        };
        let d = &mut self.dram;
        d.ras_n.set_bool(ras_n);
        d.cas_n.set_bool(cas_n);
        d.oe_n.set_bool(cas_n);
        d.addr.set_bits(a);
        d.eval();
        self.resp_valid.set_bool(false);
        // Next state.
        let (next, cnt) = match st {
            _ if self.accept => {
                if open {
                    (State::CasLow, 1)
                } else {
                    (State::Precharge, 1)
                }
            }
            s if s == State::Idle as u64 => (State::Idle, 0),
            s if s == State::Precharge as u64 => {
                if n >= self.p.t_rp {
                    (State::RowOpen, 1)
                } else {
                    (State::Precharge, n + 1)
                }
            }
            s if s == State::RowOpen as u64 => {
                if n >= self.p.t_rcd {
                    (State::CasLow, 1)
                } else {
                    (State::RowOpen, n + 1)
                }
            }
            s if s == State::CasLow as u64 => {
                if n >= self.p.t_cas {
                    self.resp_valid.set_bool(self.dram.dq_valid.is_high());
                    self.resp_data.follow(&self.dram.dq);
                    (State::CasHigh, 1)
                } else {
                    (State::CasLow, n + 1)
                }
            }
            _ => {
                if last_cp {
                    (State::Idle, 0)
                } else {
                    (State::CasHigh, n + 1)
                }
            }
        };
        self.state.set_next_raw(next as i64);
        self.count.set_next_raw(i64::from(cnt));
        if self.accept {
            self.addr_r.set_next_bits(addr);
            self.open_row.set_next_bits(row);
            self.row_open.set_next_bool(true);
        }
    }
    fn tick(&mut self, reset: bool) {
        if self.accept && !reset {
            self.reads += 1;
            let row = self.req_addr.bits() / u64::from(self.p.cols);
            if self.row_open.q().is_high() && self.open_row.q().bits() == row {
                self.page_hits += 1;
            } else {
                self.page_faults += 1;
            }
        }
        for r in [
            &mut self.state,
            &mut self.count,
            &mut self.open_row,
            &mut self.row_open,
            &mut self.addr_r,
        ] {
            r.tick(reset);
        }
        self.dram.tick(reset);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(&self.name, self.kind());
        signals!(v;
            Input: self.req_valid, self.req_addr;
            Output: self.ready, self.resp_valid, self.resp_data;
            Reg: self.state, self.count, self.open_row, self.row_open);
        self.dram.visit(v);
        v.leave();
    }
}
