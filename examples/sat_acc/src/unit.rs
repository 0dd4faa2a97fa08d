//! The unit, `acc <= sat(acc + x)`, two-process style: each port and register declared once,
//! with its format (`#[derive(Module)]` makes the constructor, the clock edge and the
//! hierarchy from them); the behaviour is `eval`.
use hdl::fx::{Format, Overflow, Quant};
use hdl::kernel::{Module, Reg, Signal};

pub const X: Format = Format::signed(8, 4); // input sQ4.4: [-8, 8)
pub const ACC: Format = Format::signed(10, 4); // accumulator sQ6.4: [-32, 32)
pub const BIT: Format = Format::uint(1);

#[derive(Clone, Module)]
#[module(kind = "sat_acc", new)]
pub struct SatAcc {
    #[input(fmt = BIT)]
    pub valid_in: Signal,
    #[input(fmt = X)]
    pub x: Signal,
    #[output(fmt = BIT)]
    pub out_valid: Signal,
    #[output(fmt = ACC)]
    pub acc: Signal,
    #[reg(fmt = ACC)]
    acc_r: Reg,
    #[reg(fmt = BIT)]
    valid_r: Reg,
}

impl Default for SatAcc {
    fn default() -> SatAcc {
        SatAcc::new()
    }
}

impl SatAcc {
    pub fn eval(&mut self) {
        self.out_valid.follow(self.valid_r.q());
        self.acc.follow(self.acc_r.q());
        self.valid_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            // Full-precision sum, then one declared narrowing: truncate (exact here), saturate.
            let sum = self.acc_r.q().fx() + self.x.fx();
            self.acc_r.set_next(sum.convert(ACC, Quant::Trunc, Overflow::Saturate));
        }
    }
}

/// The golden model, from the mathematics: `clamp(acc + x)` on the reals, sharing nothing.
pub fn golden(acc: f64, x: f64) -> f64 {
    (acc + x).clamp(-32.0, 32.0 - 1.0 / 16.0)
}
