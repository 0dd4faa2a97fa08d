//! The unit, `acc <= sat(acc + x)`, two-process style: each port and register declared once,
//! its type saying its format (`#[derive(Module)]` makes the constructor, the clock edge and the
//! hierarchy from them); the behaviour is `eval`, written on fixed-point values. The formats
//! are constants, so the arithmetic compiles to the integer code a careful person would write.
use hdl::fx::{Bit, Format, Overflow, Quant};
use hdl::kernel::{Module, RegOf, SignalOf};

hdl::formats! {
    /// Input sQ4.4: [-8, 8).
    pub X = Format::signed(8, 4);
    /// Accumulator sQ6.4: [-32, 32).
    pub Acc = Format::signed(10, 4);
}

#[derive(Clone, Module)]
#[module(kind = "sat_acc", new)]
pub struct SatAcc {
    #[input]
    pub valid_in: SignalOf<Bit>,
    #[input]
    pub x: SignalOf<X>,
    #[output]
    pub out_valid: SignalOf<Bit>,
    #[output]
    pub acc: SignalOf<Acc>,
    #[reg]
    acc_r: RegOf<Acc>,
    #[reg]
    valid_r: RegOf<Bit>,
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
            self.acc_r.set_next(sum.convert(Acc::FMT, Quant::Trunc, Overflow::Saturate));
        }
    }
}

/// The golden model, from the mathematics: `clamp(acc + x)` on the reals, sharing nothing.
pub fn golden(acc: f64, x: f64) -> f64 {
    (acc + x).clamp(-32.0, 32.0 - 1.0 / 16.0)
}
