//! The documented style against raw integers on the same logic: the worked example's unit (the
//! `texrtl new` template's) and the user guide's two-stage blend, each compiled from its own
//! file in this crate as a user's crate compiles it, and each written again on `i64` and
//! `set_next_raw` with run-time-format signals, the style of texrtl's own units. Each pair
//! co-simulates with the one Verilog (the raw model instantiating it as its top), so the speed
//! table gives all four against Verilator in one run.

use hdl::fx::Format;
use hdl::kernel::{Module, Reg, Signal};
use std::path::{Path, PathBuf};
use verif::cosim::Twin;
use verif::project::Unit;

// The example is formatted by its own crate's rustfmt.toml, not this workspace's.
#[path = "../../examples/sat_acc/src/unit.rs"]
#[allow(dead_code)]
#[rustfmt::skip]
mod documented;

#[path = "../../docs/src/blend.rs"]
#[allow(dead_code)]
mod blend;

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

fn here(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(file)
}

/// The guide's blend on raw integers: the same ports, registers and behaviour.
#[derive(Clone, Module)]
#[module(kind = "blend_raw", new)]
pub struct BlendRaw {
    #[input(fmt = Format::uint(1))]
    pub valid_in: Signal,
    #[input(fmt = blend::Colour::FMT)]
    pub a: Signal,
    #[input(fmt = blend::Colour::FMT)]
    pub b: Signal,
    #[input(fmt = blend::Colour::FMT)]
    pub alpha: Signal,
    #[output(fmt = Format::uint(1))]
    pub out_valid: Signal,
    #[output(fmt = blend::Colour::FMT)]
    pub out: Signal,
    #[reg(fmt = blend::Product::FMT)]
    product_r: Reg,
    #[reg(fmt = blend::Colour::FMT)]
    b_r: Reg,
    #[reg(fmt = Format::uint(1))]
    valid1_r: Reg,
    #[reg(fmt = blend::Colour::FMT)]
    out_r: Reg,
    #[reg(fmt = Format::uint(1))]
    valid2_r: Reg,
}

impl BlendRaw {
    /// Stage 1 `alpha (a - b)` exact (16 fraction bits); stage 2 `b << 8` plus it, rounded
    /// half to even by 8 bits and clamped to 0..=255.
    pub fn eval(&mut self) {
        self.out_valid.follow(self.valid2_r.q());
        self.out.follow(self.out_r.q());
        self.valid2_r.set_next_bool(self.valid1_r.q().is_high());
        if self.valid1_r.q().is_high() {
            let sum = (self.b_r.q().raw() << 8) + self.product_r.q().raw();
            let floor = sum >> 8;
            let (half, sticky) = (sum & 0x80 != 0, sum & 0x7f != 0);
            let up = half && (sticky || floor & 1 == 1);
            self.out_r
                .set_next_raw((floor + i64::from(up)).clamp(0, 255));
        }
        self.valid1_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            let d = self.a.raw() - self.b.raw();
            self.product_r.set_next_raw(self.alpha.raw() * d);
            self.b_r.set_next_raw(self.b.raw());
        }
    }
}

/// The four models as units of their own, each with its Verilog as its twin.
pub fn units() -> [Unit; 4] {
    let sat_acc = |d: &mut documented::SatAcc, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.x], v);
    };
    let sat_acc_raw = |d: &mut SatAccRaw, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.x], v);
    };
    let blend = |d: &mut blend::Blend, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.a, &mut d.b, &mut d.alpha], v);
    };
    let blend_raw = |d: &mut BlendRaw, v: &[u64]| {
        Signal::set_row([&mut d.valid_in, &mut d.a, &mut d.b, &mut d.alpha], v);
    };
    let sat_acc_v = here("../examples/sat_acc/rtl/sat_acc.v");
    let blend_v = here("../docs/rtl/blend.v");
    [
        Unit::new(
            "sat_acc",
            "the worked example (documented fixed-point style)",
        )
        .twin(Twin::with_drive(documented::SatAcc::new, sat_acc).sources([sat_acc_v.clone()])),
        Unit::new("sat_acc_raw", "the same accumulator on raw integers").twin(
            Twin::with_drive(SatAccRaw::new, sat_acc_raw)
                .top("sat_acc")
                .sources([sat_acc_v]),
        ),
        Unit::new(
            "blend",
            "the user guide's blend (documented fixed-point style)",
        )
        .twin(Twin::with_drive(blend::Blend::new, blend).sources([blend_v.clone()])),
        Unit::new("blend_raw", "the same blend on raw integers").twin(
            Twin::with_drive(BlendRaw::new, blend_raw)
                .top("blend")
                .sources([blend_v]),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use hdl::kernel::Sim;

    /// A cheap generator of input bits (the same in both models).
    fn bits(state: &mut u64) -> u64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *state >> 24
    }

    /// Each raw-integer model is the same logic as its documented-style twin: every output,
    /// every cycle, on 200 k cycles of random inputs (long runs of one sign reach both rails).
    #[test]
    fn the_raw_models_are_the_same_logic() {
        let (mut doc, mut raw) = (
            Sim::new(documented::SatAcc::new()),
            Sim::new(SatAccRaw::new()),
        );
        let (mut bl, mut blr) = (Sim::new(blend::Blend::new()), Sim::new(BlendRaw::new()));
        doc.reset(1);
        raw.reset(1);
        bl.reset(1);
        blr.reset(1);
        let mut s = 7;
        for i in 0..200_000u64 {
            let (v, r) = (bits(&mut s), bits(&mut s));
            let x = if (i / 300) % 2 == 0 {
                r & 0x7f
            } else {
                r & 0xff
            };
            doc.dut.valid_in.set_bits(v & 1);
            doc.dut.x.set_bits(x);
            raw.dut.valid_in.set_bits(v & 1);
            raw.dut.x.set_bits(x);
            bl.dut.valid_in.set_bits(v & 1);
            blr.dut.valid_in.set_bits(v & 1);
            let (a, b, alpha) = ((r >> 8) & 0xff, (r >> 16) & 0xff, (r >> 24) & 0xff);
            bl.dut.a.set_bits(a);
            bl.dut.b.set_bits(b);
            bl.dut.alpha.set_bits(alpha);
            blr.dut.a.set_bits(a);
            blr.dut.b.set_bits(b);
            blr.dut.alpha.set_bits(alpha);
            doc.step();
            raw.step();
            bl.step();
            blr.step();
            let got = (doc.dut.acc.bits(), doc.dut.out_valid.bits());
            assert_eq!(
                got,
                (raw.dut.acc.bits(), raw.dut.out_valid.bits()),
                "cycle {i}"
            );
            let got = (bl.dut.out.bits(), bl.dut.out_valid.bits());
            assert_eq!(
                got,
                (blr.dut.out.bits(), blr.dut.out_valid.bits()),
                "cycle {i}"
            );
        }
    }
}
