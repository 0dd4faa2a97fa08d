//! Configuration 4 of section 6: one colour component per chip, three or four TEXRAM chips
//! 802 in lock-step. Every chip gets the same request; each holds one component's map at
//! full size in the luminance configuration, so all four take the same slots (the same
//! addresses hit and miss the same rows) and their results come out in the same cycle: one
//! RGBA pixel per slot, at full speed. In the waveform: `texram_lockstep.chip_r` ... `chip_a`.

use super::texram_802::{Texram802, TexramParams};
use super::Drf;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Visitor};
use crate::signals;

const NAMES: [&str; 4] = ["chip_r", "chip_g", "chip_b", "chip_a"];

/// Four chips sharing the request port.
#[derive(Clone, Debug)]
pub struct TexramLockstep {
    pub chips: Vec<Texram802>,
    pub req_valid: Signal,
    pub req_ready: Signal,
    pub req_drf: Signal,
    pub req_u: Signal,
    pub req_v: Signal,
    pub req_lambda: Signal,
    /// R, G, B, alpha from the top byte down, valid with `out_valid`.
    pub out_valid: Signal,
    pub out_rgba: Signal,
    /// Set if the chips ever fell out of step (a modelling error, never expected).
    pub out_of_step: Reg,
}

impl TexramLockstep {
    pub fn new(p: TexramParams) -> Result<TexramLockstep, String> {
        let chips = NAMES
            .iter()
            .map(|n| Texram802::new(p).map(|c| c.named(n)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(TexramLockstep {
            chips,
            req_valid: Signal::bit("req_valid"),
            req_ready: Signal::bit("req_ready"),
            req_drf: Signal::new("req_drf", Format::uint(3)),
            req_u: Signal::new("req_u", Format::signed(super::UV_BITS, 8)),
            req_v: Signal::new("req_v", Format::signed(super::UV_BITS, 8)),
            req_lambda: Signal::new("req_lambda", Format::signed(14, 8)),
            out_valid: Signal::bit("out_valid"),
            out_rgba: Signal::new("out_rgba", Format::uint(32)),
            out_of_step: Reg::new("out_of_step", Format::uint(1)),
        })
    }

    /// DRF `k` on every chip, and component `c`'s level 0 (R, G, B, alpha) on chip `c`.
    pub fn load(&mut self, k: usize, drf: Drf, planes: &[Vec<u8>; 4]) -> Result<(), String> {
        for (chip, plane) in self.chips.iter_mut().zip(planes) {
            chip.set_drf(k, drf)?;
            chip.load(k, plane)?;
        }
        Ok(())
    }
}

impl Module for TexramLockstep {
    fn kind(&self) -> &'static str {
        "texram_lockstep"
    }

    fn eval(&mut self) {
        for chip in &mut self.chips {
            chip.req_valid.follow(&self.req_valid);
            chip.req_drf.follow(&self.req_drf);
            chip.req_u.follow(&self.req_u);
            chip.req_v.follow(&self.req_v);
            chip.req_lambda.follow(&self.req_lambda);
            chip.eval();
        }
        let ready: Vec<bool> = self.chips.iter().map(|c| c.req_ready.is_high()).collect();
        let valid: Vec<bool> = self
            .chips
            .iter()
            .map(|c| c.out_valid.q().is_high())
            .collect();
        let apart = ready.iter().any(|r| *r != ready[0]) || valid.iter().any(|v| *v != valid[0]);
        if apart {
            self.out_of_step.set_next_bool(true);
        }
        self.req_ready.set_bool(ready[0]);
        self.out_valid.set_bool(valid[0]);
        let rgba = self
            .chips
            .iter()
            .fold(0u64, |acc, c| acc << 8 | c.out_value.q().bits());
        self.out_rgba.set_bits(rgba);
    }

    fn tick(&mut self, reset: bool) {
        for chip in &mut self.chips {
            chip.tick(reset);
        }
        self.out_of_step.tick(reset);
    }

    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        signals!(v;
            Input: self.req_valid, self.req_drf, self.req_u, self.req_v, self.req_lambda;
            Output: self.req_ready, self.out_valid, self.out_rgba;
            Reg: self.out_of_step);
        for chip in &self.chips {
            chip.visit(v);
        }
        v.leave();
    }
}
