//! The walker's port to the banks 810 (section 14): the access 812 issues, the value and slots
//! it gets back, and the banks behind it (the stub or the cycle-accurate chip 802) as a child
//! of the walker.
//!
//! # Timing
//! Like a synchronous memory ([`crate::kernel::Mem`]): the walker's `eval` stages one access on
//! the `acc_*` inputs; the clock edge performs it (the banks' open rows and counters change
//! there and nowhere else) and loads `rd_value` and `rd_slots`, which the walker reads from
//! the next cycle on. No access is made under reset. An access the banks refuse (a field out
//! of its format, a DRF or plane that does not exist: a bug of the walker) loads value 0, one
//! slot and sets `refused`, and its message is kept for the testbench.
//!
//! The banks' own state is visited in this scope (the chip's registers and ports, the stub's
//! page registers): from the walker's clock it is state that changes at the edge, so it is
//! traced as registers. The chip runs each access to its end, in its own cycles, within the
//! walker's edge; its waveform here shows the state each access leaves.
//!
//! | port | format |
//! |---|---|
//! | `acc_valid` | u1 |
//! | `acc_drf`, `acc_plane` | u3 |
//! | `acc_u`, `acc_v`, `acc_lambda` | sQ12.8, sQ12.8, sQ5.8 |
//! | `rd_value` | u8 |
//! | `rd_slots` | u2 (1, 2 after a page fault; 3 at most) |
//! | `refused` | u1 |

use super::drf_812::DrfFile;
use crate::fx::{Format, Narrowing};
use crate::kernel::declared::Signals;
use crate::kernel::{Dir, Module, Reg, Signal, Signals, Visitor};
use crate::texram::{TexramAccess, UV_BITS};

/// What the walker asks the banks for.
#[derive(Clone, Debug, Signals)]
pub struct AccessPort {
    pub valid: Signal,
    pub drf: Signal,
    pub plane: Signal,
    pub u: Signal,
    pub v: Signal,
    pub lambda: Signal,
}

impl AccessPort {
    fn new(lambda: Format) -> AccessPort {
        let uv = Format::signed(UV_BITS, 8);
        AccessPort {
            valid: Signal::bit("acc_valid"),
            drf: Signal::new("acc_drf", Format::uint(3)),
            plane: Signal::new("acc_plane", Format::uint(3)),
            u: Signal::new("acc_u", uv),
            v: Signal::new("acc_v", uv),
            lambda: Signal::new("acc_lambda", lambda),
        }
    }
}

/// The banks behind the walker, with the access port and the read registers.
#[derive(Clone)]
pub struct BankPort810<T: TexramAccess> {
    file: DrfFile,
    texram: T,
    /// Driven by the walker's `eval`.
    pub acc: AccessPort,
    pub rd_value: Reg,
    pub rd_slots: Reg,
    pub refused: Reg,
    /// The first access the banks refused.
    pub error: Option<String>,
}

impl<T: TexramAccess> BankPort810<T> {
    /// The port to `texram`, whose maps the DRFs of `file` describe; `lambda` the access's
    /// level format.
    pub fn new(file: DrfFile, texram: T, lambda: Format) -> BankPort810<T> {
        BankPort810 {
            file,
            texram,
            acc: AccessPort::new(lambda),
            rd_value: Reg::new("rd_value", Format::uint(8)),
            rd_slots: Reg::new("rd_slots", Format::uint(2)),
            refused: Reg::new("refused", Format::uint(1)),
            error: None,
        }
    }

    /// The DRFs the walker follows.
    pub fn file(&self) -> &DrfFile {
        &self.file
    }

    /// The access staged on the port, made: its value and slots, or why the banks refused it.
    fn access(&mut self) -> Result<(u8, u32), String> {
        let a = &self.acc;
        let [drf, plane, u, v, l] = [&a.drf, &a.plane, &a.u, &a.v, &a.lambda].map(|s| s.raw());
        let d = self
            .file
            .get(drf as u8)
            .filter(|d| (plane as usize) < d.plane_count())
            .ok_or_else(|| format!("drf {drf} plane {plane}: no such map"))?;
        let r = self
            .texram
            .access_with(&d.access(plane as usize), u as i32, v as i32, l as i32)?;
        Ok((r.value, r.slots.min(3)))
    }
}

/// A visitor that takes every signal for a register: the banks' state, seen from the
/// walker's clock.
struct AsState<'a>(&'a mut dyn Visitor);

impl Visitor for AsState<'_> {
    fn enter(&mut self, instance: &str, kind: &str) {
        self.0.enter(instance, kind);
    }
    fn leave(&mut self) {
        self.0.leave();
    }
    fn signal(&mut self, _: Dir, s: &Signal) {
        self.0.signal(Dir::Reg, s);
    }
    /// A narrowing's flag as state too (a visitor's default would trace it as a wire, which
    /// changes at the walker's edge). The banks' own narrowings count in their own
    /// testbenches, whose cycles they are met in, not in the walker's numeric coverage.
    fn narrowing(&mut self, n: &Narrowing) {
        self.0.signal(Dir::Reg, n.flag());
    }
}

impl<T: TexramAccess> Module for BankPort810<T> {
    fn instance(&self) -> &str {
        "banks"
    }

    fn kind(&self) -> &'static str {
        "bank_port_810"
    }

    /// Nothing combinational: the outputs are registers.
    fn eval(&mut self) {}

    /// The edge: the staged access made, its reply into the read registers.
    fn tick(&mut self, reset: bool) {
        if !reset && self.acc.valid.is_high() {
            let (value, slots) = match self.access() {
                Ok(r) => r,
                Err(e) => {
                    self.error.get_or_insert(e);
                    self.refused.set_next_bool(true);
                    (0, 1)
                }
            };
            self.rd_value.set_next_bits(u64::from(value));
            self.rd_slots.set_next_bits(u64::from(slots));
        }
        for r in [&mut self.rd_value, &mut self.rd_slots, &mut self.refused] {
            r.tick(reset);
        }
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        self.acc.visit_signals(Dir::Input, v);
        for r in [&self.rd_value, &self.rd_slots, &self.refused] {
            v.reg(r);
        }
        self.texram.visit(&mut AsState(v));
        v.leave();
    }
}
