//! The guide's unit: a two-stage alpha blend, `out = b + alpha (a - b)`, in the documented
//! style (`Fx` values and their operators, one declared narrowing).
//!
//! | port | format | |
//! |---|---|---|
//! | `valid_in` | bit | a blend is presented |
//! | `a`, `b`, `alpha` | uQ0.8 | the two colours and the weight of `a`, in [0, 1) |
//! | `out_valid` | bit | `out` holds the blend presented two cycles before |
//! | `out` | uQ0.8 | the blend, rounded half to even, saturated (never reached: a blend lies between `a` and `b`) |
//!
//! Stage 1 registers the exact product `alpha (a - b)` (sQ1.16) and `b`; stage 2 adds them
//! and rounds once to the output format. Latency 2, one blend a cycle.

use hdl::fx::{Bit, Format, Overflow, Quant};
use hdl::kernel::{Module, RegOf, SignalOf};

hdl::formats! {
    /// The colours' and the weight's format, uQ0.8.
    pub Colour = Format::unsigned(8, 8);
    /// The exact product `alpha (a - b)`: uQ0.8 times sQ1.8, within (-1, 1): sQ1.16.
    pub Product = Format::signed(18, 16);
}

/// The two-stage blend. Each port and register is declared once, its type saying its format:
/// `#[derive(Module)]` makes the constructor ([`Blend::new`], every signal named after its
/// field), the clock edge (every `#[reg]` commits) and the hierarchy (every marked field
/// traced and schedule-checked) from the fields; the behaviour is [`Blend::eval`].
#[derive(Clone, Module)]
#[module(kind = "blend", new)]
pub struct Blend {
    /// Input: a blend is presented.
    #[input]
    pub valid_in: SignalOf<Bit>,
    /// Input: the colour weighted by `alpha`.
    #[input]
    pub a: SignalOf<Colour>,
    /// Input: the colour weighted by `1 - alpha`.
    #[input]
    pub b: SignalOf<Colour>,
    /// Input: the weight.
    #[input]
    pub alpha: SignalOf<Colour>,
    /// Output: `out` is a blend.
    #[output]
    pub out_valid: SignalOf<Bit>,
    /// Output: the blend.
    #[output]
    pub out: SignalOf<Colour>,
    #[reg]
    product_r: RegOf<Product>,
    #[reg]
    b_r: RegOf<Colour>,
    #[reg]
    valid1_r: RegOf<Bit>,
    #[reg]
    out_r: RegOf<Colour>,
    #[reg]
    valid2_r: RegOf<Bit>,
}

impl Default for Blend {
    fn default() -> Blend {
        Blend::new()
    }
}

impl Blend {
    /// The combinational process: outputs and next values from the inputs and the registers
    /// (the two-process rule: `eval` computes, the generated `tick` commits).
    pub fn eval(&mut self) {
        // Outputs from the registers (the two-process rule: eval computes, tick commits).
        self.out_valid.follow(self.valid2_r.q());
        self.out.follow(self.out_r.q());
        // Stage 2: the sum of the exact terms, narrowed once.
        self.valid2_r.set_next_bool(self.valid1_r.q().is_high());
        if self.valid1_r.q().is_high() {
            let sum = self.b_r.q().fx() + self.product_r.q().fx();
            let out = sum.convert(Colour::FMT, Quant::RoundHalfEven, Overflow::Saturate);
            self.out_r.set_next(out);
        }
        // Stage 1: the exact product, stored without loss.
        self.valid1_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            let product = self.alpha.fx() * (self.a.fx() - self.b.fx());
            self.product_r.set_next(product.exact(Product::FMT));
            self.b_r.set_next(self.b.fx());
        }
    }
}

/// The golden model, from the mathematics: `b + alpha (a - b)` on the reals.
pub fn golden(a: f64, b: f64, alpha: f64) -> f64 {
    b + alpha * (a - b)
}
