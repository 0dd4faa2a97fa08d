//! The unit, `acc <= sat(acc + x)`, two-process style: `eval` computes, `tick` only commits.
use hdl::fx::{Format, Overflow, Quant};
use hdl::kernel::{Module, Reg, Signal, Visitor};

pub const X: Format = Format::signed(8, 4); // input sQ4.4: [-8, 8)
pub const ACC: Format = Format::signed(10, 4); // accumulator sQ6.4: [-32, 32)

#[derive(Clone)]
pub struct SatAcc {
    pub valid_in: Signal,
    pub x: Signal,
    pub out_valid: Signal,
    pub acc: Signal,
    acc_r: Reg,
    valid_r: Reg,
}

impl Default for SatAcc {
    fn default() -> SatAcc {
        let (valid_in, x, out_valid) =
            (Signal::bit("valid_in"), Signal::new("x", X), Signal::bit("out_valid"));
        let (acc, acc_r) = (Signal::new("acc", ACC), Reg::new("acc_r", ACC));
        SatAcc { valid_in, x, out_valid, acc, acc_r, valid_r: Reg::new("valid_r", Format::uint(1)) }
    }
}

impl Module for SatAcc {
    fn kind(&self) -> &'static str {
        "sat_acc"
    }
    fn eval(&mut self) {
        self.out_valid.follow(self.valid_r.q());
        self.acc.follow(self.acc_r.q());
        self.valid_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            // Full-precision sum, then one declared narrowing: truncate (exact here), saturate.
            let sum = self.acc_r.q().fx() + self.x.fx();
            self.acc_r.set_next(sum.convert(ACC, Quant::Trunc, Overflow::Saturate));
        }
    }
    fn tick(&mut self, reset: bool) {
        self.acc_r.tick(reset);
        self.valid_r.tick(reset);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        hdl::signals!(v; Input: self.valid_in, self.x;
            Output: self.out_valid, self.acc; Reg: self.acc_r, self.valid_r);
        v.leave();
    }
}

/// The golden model, from the mathematics: `clamp(acc + x)` on the reals, sharing nothing.
pub fn golden(acc: f64, x: f64) -> f64 {
    (acc + x).clamp(-32.0, 32.0 - 1.0 / 16.0)
}
