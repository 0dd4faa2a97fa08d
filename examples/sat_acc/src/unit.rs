//! The unit, `acc <= sat(acc + x)`, two-process style: each port, register and narrowing
//! declared once, its type saying its format (`#[derive(Module)]` makes the constructor, the
//! clock edge and the hierarchy from them); the behaviour is `eval`, written on fixed-point
//! values. The formats are constants, so the arithmetic compiles to the integer code a careful
//! person would write. The one narrowing is named: a regression counts its saturations.
use hdl::fx::{Bit, Format, NarrowingOf, Overflow, Quant};
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
    /// The sum back into the accumulator: truncate (exact here), saturate.
    #[narrow(quant = Quant::Trunc, overflow = Overflow::Saturate)]
    to_acc: NarrowingOf<Acc>,
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
            // Full-precision sum, then its one declared narrowing.
            let sum = self.acc_r.q().fx() + self.x.fx();
            self.acc_r.set_next(self.to_acc.fx(sum));
        }
    }
}

/// The golden model, from the mathematics: `clamp(acc + x)` on the reals, sharing nothing.
pub fn golden(acc: f64, x: f64) -> f64 {
    (acc + x).clamp(-32.0, 32.0 - 1.0 / 16.0)
}
