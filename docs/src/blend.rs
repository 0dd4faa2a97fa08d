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

use hdl::fx::{Format, Overflow, Quant};
use hdl::kernel::{Module, Reg, Signal, Visitor};

/// The colours' and the weight's format, uQ0.8.
pub const COLOUR: Format = Format::unsigned(8, 8);
/// The exact product `alpha (a - b)`: uQ0.8 times sQ1.8, within (-1, 1): sQ1.16.
pub const PRODUCT: Format = Format::signed(18, 16);

/// The two-stage blend.
#[derive(Clone)]
pub struct Blend {
    /// Input: a blend is presented.
    pub valid_in: Signal,
    /// Input: the colour weighted by `alpha`.
    pub a: Signal,
    /// Input: the colour weighted by `1 - alpha`.
    pub b: Signal,
    /// Input: the weight.
    pub alpha: Signal,
    /// Output: `out` is a blend.
    pub out_valid: Signal,
    /// Output: the blend.
    pub out: Signal,
    product_r: Reg,
    b_r: Reg,
    valid1_r: Reg,
    out_r: Reg,
    valid2_r: Reg,
}

impl Default for Blend {
    fn default() -> Blend {
        Blend {
            valid_in: Signal::bit("valid_in"),
            a: Signal::new("a", COLOUR),
            b: Signal::new("b", COLOUR),
            alpha: Signal::new("alpha", COLOUR),
            out_valid: Signal::bit("out_valid"),
            out: Signal::new("out", COLOUR),
            product_r: Reg::new("product_r", PRODUCT),
            b_r: Reg::new("b_r", COLOUR),
            valid1_r: Reg::new("valid1_r", Format::uint(1)),
            out_r: Reg::new("out_r", COLOUR),
            valid2_r: Reg::new("valid2_r", Format::uint(1)),
        }
    }
}

impl Module for Blend {
    fn kind(&self) -> &'static str {
        "blend"
    }

    fn eval(&mut self) {
        // Outputs from the registers (the two-process rule: eval computes, tick commits).
        self.out_valid.follow(self.valid2_r.q());
        self.out.follow(self.out_r.q());
        // Stage 2: the sum of the exact terms, narrowed once.
        self.valid2_r.set_next_bool(self.valid1_r.q().is_high());
        if self.valid1_r.q().is_high() {
            let sum = self.b_r.q().fx() + self.product_r.q().fx();
            let out = sum.convert(COLOUR, Quant::RoundHalfEven, Overflow::Saturate);
            self.out_r.set_next(out);
        }
        // Stage 1: the exact product, stored without loss.
        self.valid1_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            let product = self.alpha.fx() * (self.a.fx() - self.b.fx());
            self.product_r.set_next(product.exact(PRODUCT));
            self.b_r.set_next(self.b.fx());
        }
    }

    fn tick(&mut self, reset: bool) {
        for r in [
            &mut self.product_r,
            &mut self.b_r,
            &mut self.valid1_r,
            &mut self.out_r,
            &mut self.valid2_r,
        ] {
            r.tick(reset);
        }
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        hdl::signals!(v; Input: self.valid_in, self.a, self.b, self.alpha;
            Output: self.out_valid, self.out;
            Reg: self.product_r, self.b_r, self.valid1_r, self.out_r, self.valid2_r);
        v.leave();
    }
}

/// The golden model, from the mathematics: `b + alpha (a - b)` on the reals.
pub fn golden(a: f64, b: f64, alpha: f64) -> f64 {
    b + alpha * (a - b)
}
