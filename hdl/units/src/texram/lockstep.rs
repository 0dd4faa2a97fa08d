//! Configuration 4 of section 6: one colour component per chip, three or four TEXRAM chips
//! 802 in lock-step. Every chip gets the same request; each holds one component's map at
//! full size in the luminance configuration, so all four take the same slots (the same
//! addresses hit and miss the same rows) and their results come out in the same cycle: one
//! RGBA pixel per slot, at full speed. In the waveform: `texram_lockstep.chip_r` ... `chip_a`.

use super::texram_802::{Texram802, TexramParams};
use super::Drf;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal, Signals};
use std::fmt::Debug;

const NAMES: [&str; 4] = ["chip_r", "chip_g", "chip_b", "chip_a"];

/// A chip four of which run in lock-step, one colour component each (the TEXRAM 802 here,
/// the ray caster of Figure 15 in `volume`).
pub trait LockstepChip: Module + Clone + Debug {
    /// The input port every chip of a group shares.
    type Port: crate::kernel::declared::Signals + Clone + Debug;
    /// The group's kind, its scope in the waveform.
    const GROUP: &'static str;
    /// The name of the group's ready output.
    const READY: &'static str;
    /// A port in the chip's formats.
    fn port(&self) -> Self::Port;
    /// Drives the chip's inputs from the group's port.
    fn drive(&mut self, port: &Self::Port);
    /// Whether the chip takes the port's input this cycle.
    fn ready(&self) -> bool;
    /// The chip's output register: whether a result is out, and its component.
    fn out(&self) -> Option<u8>;
}

/// Four chips sharing one input port, their components one RGBA result, their agreement
/// checked every cycle.
#[derive(Clone, Debug, Module)]
#[module(kind = C::GROUP)]
pub struct Lockstep<C: LockstepChip> {
    #[child]
    pub chips: Vec<C>,
    #[input]
    pub port: C::Port,
    #[output]
    pub ready: Signal,
    /// R, G, B, alpha from the top byte down, valid with `out_valid`.
    #[output]
    pub out_valid: Signal,
    #[output]
    pub out_rgba: Signal,
    /// Set if the chips ever fell out of step (a modelling error, never expected).
    #[reg]
    pub out_of_step: Reg,
}

impl<C: LockstepChip> Lockstep<C> {
    /// The four chips (R, G, B, alpha), named `chip_r` ... `chip_a` in the waveform.
    pub fn of(chips: [C; 4], name: fn(C, &'static str) -> C) -> Lockstep<C> {
        let chips: Vec<C> = chips
            .into_iter()
            .zip(NAMES)
            .map(|(c, n)| name(c, n))
            .collect();
        Lockstep {
            port: chips[0].port(),
            ready: Signal::bit(C::READY),
            out_valid: Signal::bit("out_valid"),
            out_rgba: Signal::new("out_rgba", Format::uint(32)),
            out_of_step: Reg::new("out_of_step", Format::uint(1)),
            chips,
        }
    }

    /// Every chip on the same input; their results compared.
    pub fn eval(&mut self) {
        for chip in &mut self.chips {
            chip.drive(&self.port);
            chip.eval();
        }
        let ready = self.chips[0].ready();
        let valid = self.chips[0].out().is_some();
        let apart = self
            .chips
            .iter()
            .any(|c| c.ready() != ready || c.out().is_some() != valid);
        if apart {
            self.out_of_step.set_next_bool(true);
        }
        self.ready.set_bool(ready);
        self.out_valid.set_bool(valid);
        let rgba = self
            .chips
            .iter()
            .fold(0u64, |acc, c| acc << 8 | u64::from(c.out().unwrap_or(0)));
        self.out_rgba.set_bits(rgba);
    }
}

/// The chip's request port as the group shares it (the illumination is not shared: each
/// chip's is its own input).
#[derive(Clone, Debug, Signals)]
pub struct TexramReq {
    pub valid: Signal,
    pub drf: Signal,
    pub u: Signal,
    pub v: Signal,
    pub lambda: Signal,
}

impl LockstepChip for Texram802 {
    type Port = TexramReq;
    const GROUP: &'static str = "texram_lockstep";
    const READY: &'static str = "req_ready";
    fn port(&self) -> TexramReq {
        TexramReq {
            valid: self.req_valid.clone(),
            drf: self.req_drf.clone(),
            u: self.req_u.clone(),
            v: self.req_v.clone(),
            lambda: self.req_lambda.clone(),
        }
    }
    fn drive(&mut self, port: &TexramReq) {
        self.req_valid.follow(&port.valid);
        self.req_drf.follow(&port.drf);
        self.req_u.follow(&port.u);
        self.req_v.follow(&port.v);
        self.req_lambda.follow(&port.lambda);
    }
    fn ready(&self) -> bool {
        self.req_ready.is_high()
    }
    fn out(&self) -> Option<u8> {
        self.output
            .out_valid
            .q()
            .is_high()
            .then(|| self.output.out_value.q().bits() as u8)
    }
}

/// Configuration 4: four TEXRAM chips.
pub type TexramLockstep = Lockstep<Texram802>;

impl Lockstep<Texram802> {
    pub fn new(p: TexramParams) -> Result<TexramLockstep, String> {
        let chip = Texram802::new(p)?;
        let four = [chip.clone(), chip.clone(), chip.clone(), chip];
        Ok(Lockstep::of(four, |c, n| c.named(n)))
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
            sim.dut.port.valid.set_bool(true);
            sim.dut.port.u.set_raw((k * 37 % 800) << 8);
            sim.dut.port.v.set_raw((k * 91 % 800) << 8);
            sim.eval();
            let c = &sim.dut.chips;
            let differ = |f: &dyn Fn(&Texram802) -> bool| c.iter().any(|x| f(x) != f(&c[0]));
            let r = differ(&|x| x.req_ready.is_high());
            let v = differ(&|x| x.output.out_valid.q().is_high());
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
