//! Configuration 4 of section 6: one colour component per chip, three or four TEXRAM chips
//! 802 in lock-step. Every chip gets the same request; each holds one component's map at
//! full size in the luminance configuration, so all four take the same slots (the same
//! addresses hit and miss the same rows) and their results come out in the same cycle: one
//! RGBA pixel per slot, at full speed. In the waveform: `texram_lockstep.chip_r` ... `chip_a`.

use super::texram_802::{Texram802, TexramParams};
use super::Drf;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

const NAMES: [&str; 4] = ["chip_r", "chip_g", "chip_b", "chip_a"];

/// Four chips sharing the request port.
#[derive(Clone, Debug, Module)]
#[module(kind = "texram_lockstep")]
pub struct TexramLockstep {
    #[child]
    pub chips: Vec<Texram802>,
    #[input]
    pub req_valid: Signal,
    #[output]
    pub req_ready: Signal,
    #[input]
    pub req_drf: Signal,
    #[input]
    pub req_u: Signal,
    #[input]
    pub req_v: Signal,
    #[input]
    pub req_lambda: Signal,
    /// R, G, B, alpha from the top byte down, valid with `out_valid`.
    #[output]
    pub out_valid: Signal,
    #[output]
    pub out_rgba: Signal,
    /// Set if the chips ever fell out of step (a modelling error, never expected).
    #[reg]
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

impl TexramLockstep {
    /// Every chip on the same request; their results compared.
    pub fn eval(&mut self) {
        for chip in &mut self.chips {
            chip.req_valid.follow(&self.req_valid);
            chip.req_drf.follow(&self.req_drf);
            chip.req_u.follow(&self.req_u);
            chip.req_v.follow(&self.req_v);
            chip.req_lambda.follow(&self.req_lambda);
            chip.eval();
        }
        let ready = self.chips[0].req_ready.is_high();
        let valid = self.chips[0].out_valid.q().is_high();
        let apart = self
            .chips
            .iter()
            .any(|c| c.req_ready.is_high() != ready || c.out_valid.q().is_high() != valid);
        if apart {
            self.out_of_step.set_next_bool(true);
        }
        self.req_ready.set_bool(ready);
        self.out_valid.set_bool(valid);
        let rgba = self
            .chips
            .iter()
            .fold(0u64, |acc, c| acc << 8 | c.out_value.q().bits());
        self.out_rgba.set_bits(rgba);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::{instances, Sim};
    use crate::texram::Border;

    fn group(maps: [u32; 4]) -> TexramLockstep {
        let mut g = TexramLockstep::new(TexramParams::default()).unwrap();
        for (chip, log2) in g.chips.iter_mut().zip(maps) {
            chip.set_drf(0, Drf::new(log2, log2, Border::Wrap)).unwrap();
            chip.load(0, &vec![9; 1 << (2 * log2)]).unwrap();
        }
        g
    }

    #[test]
    fn the_four_chips_are_scopes_of_the_group() {
        let g = group([4; 4]);
        let inst = instances(&g);
        assert_eq!(
            inst[0],
            ("texram_lockstep".to_string(), "texram_lockstep".to_string())
        );
        for n in NAMES {
            assert!(
                inst.iter()
                    .any(|(i, k)| i.ends_with(n) && k == "texram_802"),
                "{n}"
            );
        }
    }

    /// Chips holding maps of different sizes fault at different times: the group notices
    /// in the first cycle they differ, whether in ready or in valid.
    #[test]
    fn chips_out_of_step_are_flagged_at_once() {
        let mut sim = Sim::new(group([10, 10, 10, 2])).check_schedule(true);
        sim.reset(2);
        let mut first_apart = None;
        for k in 0..400i64 {
            sim.dut.req_valid.set_bool(true);
            sim.dut.req_u.set_raw((k * 37 % 800) << 8);
            sim.dut.req_v.set_raw((k * 91 % 800) << 8);
            sim.eval();
            let c = &sim.dut.chips;
            let differ = |f: &dyn Fn(&Texram802) -> bool| c.iter().any(|x| f(x) != f(&c[0]));
            let r = differ(&|x| x.req_ready.is_high());
            let v = differ(&|x| x.out_valid.q().is_high());
            if (r || v) && first_apart.is_none() {
                first_apart = Some(sim.cycle());
            }
            sim.tick();
            if let Some(at) = first_apart {
                assert!(
                    sim.dut.out_of_step.q().is_high(),
                    "apart at cycle {at}, not flagged"
                );
            }
        }
        assert!(first_apart.is_some(), "the chips never fell out of step");
    }
}
