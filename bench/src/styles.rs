//! The documented style against raw integers on the same logic: the worked example's unit (the
//! `texrtl new` template's), compiled from its own file in this crate as a user's crate compiles
//! it, and the same accumulator written on `i64` and `set_next_raw`. Both co-simulate with the
//! example's Verilog (the raw one under its own name, `rtl/sat_acc_raw.v`), so the speed table gives both against Verilator in one run.

use hdl::fx::Format;
use hdl::kernel::{Module, Reg, Signal};
use std::path::{Path, PathBuf};
use verif::cosim::Twin;
use verif::project::Unit;

#[path = "../../examples/sat_acc/src/unit.rs"]
#[allow(dead_code)]
mod documented;

/// The example's accumulator on raw integers: the same ports, registers and behaviour.
#[derive(Clone, Module)]
#[module(kind = "sat_acc_raw", new)]
pub struct SatAccRaw {
    #[input(fmt = Format::uint(1))]
    pub valid_in: Signal,
    #[input(fmt = documented::X::FMT)]
    pub x: Signal,
    #[output(fmt = Format::uint(1))]
    pub out_valid: Signal,
    #[output(fmt = documented::Acc::FMT)]
    pub acc: Signal,
    #[reg(fmt = documented::Acc::FMT)]
    acc_r: Reg,
    #[reg(fmt = Format::uint(1))]
    valid_r: Reg,
}

impl SatAccRaw {
    /// `acc <= clamp(acc + x, -512, 511)` on the raw integers (both operands have 4 fraction
    /// bits, so the sum needs no alignment).
    pub fn eval(&mut self) {
        self.out_valid.follow(self.valid_r.q());
        self.acc.follow(self.acc_r.q());
        self.valid_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            let sum = self.acc_r.q().raw() + self.x.raw();
            self.acc_r.set_next_raw(sum.clamp(-512, 511));
        }
    }
}

fn verilog() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/sat_acc/rtl/sat_acc.v")
}

/// The two styles as units of their own, each with the example's Verilog as its twin.
pub fn units() -> [Unit; 2] {
    let documented = Twin::new(documented::SatAcc::new, |d: &mut documented::SatAcc, v| {
        d.valid_in.set_bits(v[0]);
        d.x.set_bits(v[1]);
    })
    .sources([verilog()]);
    let raw = Twin::new(SatAccRaw::new, |d: &mut SatAccRaw, v| {
        d.valid_in.set_bits(v[0]);
        d.x.set_bits(v[1]);
    })
    .sources([
        verilog(),
        Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/sat_acc_raw.v"),
    ]);
    [
        Unit::new(
            "sat_acc",
            "the worked example (documented fixed-point style)",
        )
        .twin(documented),
        Unit::new("sat_acc_raw", "the same accumulator on raw integers").twin(raw),
    ]
}
