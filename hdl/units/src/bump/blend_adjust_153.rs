//! Blend-factor adjust unit 153 of US 2004/0207631 (Fenney), FIG. 7, para. 0058-0061; bypass
//! for Blinn's height function, para. 0085.
//!
//! From the blend factors `Ublend`, `Vblend` of address unit 150 it makes the two pairs of
//! blend factors that let four ordinary bilinear units evaluate the bi-quadratic B-spline:
//!
//! ```text
//! Ublend0 = 1/2 + Ublend/2      Ublend1 = Ublend/2      (and the same for V)
//! ```
//!
//! distributed to the bilinear units as red (U0, V0), green (U1, V0), blue (U0, V1), alpha
//! (U1, V1) (para. 0060).
//!
//! # Formats
//! | port            | format        | meaning                                             |
//! |-----------------|---------------|-----------------------------------------------------|
//! | `u_in`, `v_in`  | `uQ0.F`       | blend factor in [0, 1), `F` = `frac_bits` (4..=16)  |
//! | `u0`,`u1`,`v0`,`v1` | `uQ0.(F+1)` | adjusted factors in [0, 1)                        |
//! | `bypass`        | `u1`          | 1: Blinn variant, factors pass unchanged            |
//! | `valid_in`/`valid` | `u1`       | sample qualifier                                    |
//!
//! Both results are exact: halving adds one fraction bit and `1/2 + x/2` with `x < 1` stays
//! below 1, so no rounding or overflow mode is needed. In hardware it is wiring, which is why
//! the patent says it costs nothing (para. 0059): `U0 = {1'b1, u}` and `U1 = {1'b0, u}`. In
//! bypass both outputs are `u` itself, widened to `F+1` fraction bits (`{u, 1'b0}`).
//!
//! # Timing
//! With `registered` the outputs come from one pipeline register stage (latency 1, one sample
//! per clock); without it the unit is purely combinational (latency 0). Synchronous reset
//! clears the output registers.

use crate::fx::Format;
use crate::kernel::{Module, Reg, Regs, Signal, Signals};

/// Parameters an architect may sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlendAdjustParams {
    /// Fraction bits `F` of the incoming blend factors, 4..=16.
    pub frac_bits: u32,
    /// One output register stage (latency 1) or none (latency 0).
    pub registered: bool,
}

impl Default for BlendAdjustParams {
    fn default() -> Self {
        BlendAdjustParams {
            frac_bits: 8,
            registered: true,
        }
    }
}

impl BlendAdjustParams {
    pub const FRAC_RANGE: std::ops::RangeInclusive<u32> = 4..=16;

    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), String> {
        if !Self::FRAC_RANGE.contains(&self.frac_bits) {
            return Err(format!(
                "blend_adjust: frac_bits {} outside {:?}",
                self.frac_bits,
                Self::FRAC_RANGE
            ));
        }
        Ok(())
    }
    /// Format of the incoming blend factors, `uQ0.F`.
    pub fn in_fmt(&self) -> Format {
        Format::unsigned(self.frac_bits, self.frac_bits as i32)
    }
    /// Format of the adjusted blend factors, `uQ0.(F+1)`.
    pub fn out_fmt(&self) -> Format {
        Format::unsigned(self.frac_bits + 1, self.frac_bits as i32 + 1)
    }
    /// Cycles from input to output.
    pub fn latency(&self) -> u32 {
        u32::from(self.registered)
    }
}

/// Input ports.
#[derive(Clone, Debug, Signals)]
pub struct BlendAdjustIn {
    pub valid_in: Signal,
    pub bypass: Signal,
    pub u_in: Signal,
    pub v_in: Signal,
}

/// Output ports.
#[derive(Clone, Debug, Signals)]
pub struct BlendAdjustOut {
    pub valid: Signal,
    pub u0: Signal,
    pub u1: Signal,
    pub v0: Signal,
    pub v1: Signal,
}

/// Blend-factor adjust unit 153.
#[derive(Clone, Debug, Module)]
#[module(kind = "blend_adjust_153")]
pub struct BlendAdjust {
    #[instance]
    name: String,
    params: BlendAdjustParams,
    #[input]
    pub i: BlendAdjustIn,
    #[output]
    pub o: BlendAdjustOut,
    /// Output register stage, when `registered`.
    #[reg]
    r: Option<BlendAdjustRegs>,
}

/// The output register stage: one register per output port.
#[derive(Clone, Debug, Regs)]
struct BlendAdjustRegs {
    valid: Reg,
    u0: Reg,
    u1: Reg,
    v0: Reg,
    v1: Reg,
}

impl BlendAdjust {
    /// An instance named `name`; invalid parameters are an error (see
    /// [`BlendAdjustParams::validate`]).
    pub fn new(name: &str, params: BlendAdjustParams) -> Result<BlendAdjust, String> {
        params.validate()?;
        let (fi, fo) = (params.in_fmt(), params.out_fmt());
        Ok(BlendAdjust {
            name: name.to_string(),
            params,
            i: BlendAdjustIn {
                valid_in: Signal::bit("valid_in"),
                bypass: Signal::bit("bypass"),
                u_in: Signal::new("u_in", fi),
                v_in: Signal::new("v_in", fi),
            },
            o: BlendAdjustOut {
                valid: Signal::bit("valid"),
                u0: Signal::new("u0", fo),
                u1: Signal::new("u1", fo),
                v0: Signal::new("v0", fo),
                v1: Signal::new("v1", fo),
            },
            r: params.registered.then(|| BlendAdjustRegs {
                valid: Reg::new("valid_r", Format::uint(1)),
                u0: Reg::new("u0_r", fo),
                u1: Reg::new("u1_r", fo),
                v0: Reg::new("v0_r", fo),
                v1: Reg::new("v1_r", fo),
            }),
        })
    }

    pub fn params(&self) -> BlendAdjustParams {
        self.params
    }

    /// The adjusted pair for one blend factor's bits: `({1, b}, {0, b})`, or `({b, 0}, {b, 0})`
    /// in bypass.
    // `(1 << f) | b` equals `^` and `+` here (b < 2^f): cargo-mutants' `|` -> `^` survives as an
    // equivalent mutant.
    #[inline]
    fn adjust(f: u32, b: u64, bypass: bool) -> (u64, u64) {
        if bypass {
            (b << 1, b << 1)
        } else {
            ((1 << f) | b, b)
        }
    }
}

impl BlendAdjust {
    /// The combinational process (the generated `tick` commits the register stage).
    #[inline]
    pub fn eval(&mut self) {
        let f = self.params.frac_bits;
        let bypass = self.i.bypass.is_high();
        let (u0, u1) = Self::adjust(f, self.i.u_in.bits(), bypass);
        let (v0, v1) = Self::adjust(f, self.i.v_in.bits(), bypass);
        let valid = self.i.valid_in.bits();
        let comb = [valid, u0, u1, v0, v1];
        let o = &mut self.o;
        let outs = [&mut o.valid, &mut o.u0, &mut o.u1, &mut o.v0, &mut o.v1];
        if let Some(r) = &mut self.r {
            let regs = [&mut r.valid, &mut r.u0, &mut r.u1, &mut r.v0, &mut r.v1];
            for ((reg, out), next) in regs.into_iter().zip(outs).zip(comb) {
                reg.set_next_raw(next as i64);
                out.set_bits(reg.q().bits());
            }
        } else {
            for (out, v) in outs.into_iter().zip(comb) {
                out.set_bits(v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fx::Fx;
    use crate::kernel::Sim;

    /// The instance is the name it was given (its waveform scope, `tb.blend_adjust_153`).
    #[test]
    fn the_instance_is_named_as_asked() {
        let p = BlendAdjustParams::default();
        let u = BlendAdjust::new("blend_adjust_153", p).unwrap();
        assert_eq!(
            (u.instance(), u.kind()),
            ("blend_adjust_153", "blend_adjust_153")
        );
        assert_eq!(BlendAdjust::new("other", p).unwrap().instance(), "other");
    }

    #[test]
    fn adjust_is_half_plus_half_b_exhaustive_f4_to_f16() {
        for f in BlendAdjustParams::FRAC_RANGE {
            let p = BlendAdjustParams {
                frac_bits: f,
                registered: false,
            };
            let half = Fx::from_raw(Format::unsigned(1, 1), 1);
            let mut sim =
                Sim::new(BlendAdjust::new("blend_adjust_153", p).unwrap()).check_schedule(f < 6);
            for b in 0..(1u64 << f) {
                sim.dut.i.u_in.set_bits(b);
                sim.dut.i.v_in.set_bits((1 << f) - 1 - b);
                sim.eval();
                let bx = sim.dut.i.u_in.fx();
                // Full-precision arithmetic of the fx layer, independent of the wiring.
                let want0 = (half + bx.scale_pow2(-1)).exact(p.out_fmt());
                let want1 = bx.scale_pow2(-1).exact(p.out_fmt());
                assert_eq!(sim.dut.o.u0.fx(), want0, "F={f} b={b}");
                assert_eq!(sim.dut.o.u1.fx(), want1, "F={f} b={b}");
                sim.tick();
            }
        }
    }

    #[test]
    fn registered_has_latency_one_and_resets() {
        let p = BlendAdjustParams::default();
        let mut sim =
            Sim::new(BlendAdjust::new("blend_adjust_153", p).unwrap()).check_schedule(true);
        sim.dut.i.valid_in.set_bool(true);
        sim.dut.i.u_in.set_bits(0x80);
        sim.eval();
        assert!(!sim.dut.o.valid.is_high(), "output before the edge");
        sim.tick();
        sim.dut.i.valid_in.set_bool(false);
        sim.eval();
        assert!(sim.dut.o.valid.is_high());
        assert_eq!(sim.dut.o.u0.bits(), 0x180);
        assert_eq!(sim.dut.o.u1.bits(), 0x080);
        sim.set_reset(true);
        sim.step();
        sim.set_reset(false);
        sim.eval();
        assert_eq!(sim.dut.o.u0.bits(), 0);
        assert!(!sim.dut.o.valid.is_high());
    }

    #[test]
    #[should_panic(expected = "does not fit")]
    fn out_of_range_input_is_caught() {
        let mut ba = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
        ba.i.u_in.set_bits(0x100);
    }

    #[test]
    fn bad_params_rejected() {
        let p = BlendAdjustParams {
            frac_bits: 3,
            registered: true,
        };
        let Err(e) = BlendAdjust::new("blend_adjust_153", p) else {
            panic!("F = 3 is refused");
        };
        assert!(e.contains("frac_bits 3"), "{e}");
    }
}
