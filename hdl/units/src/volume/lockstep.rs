//! Pre-classified RGBA volumes (section 13): four chips, each holding one component of the
//! classified volume, in lock-step on the same rays. Every chip reads the same addresses, so
//! all four take the same slots and deliver a sample's R, G, B and alpha in the same cycle.
//! Compositing (alpha blending along the ray) is the host's, as the document says; the golden
//! model has one (`golden::volume::composite`). In the waveform: `volume_lockstep.chip_r` ...

use super::layout::{Mode, VolumeParams};
use super::ray_caster_fig15::RayCaster;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

const NAMES: [&str; 4] = ["chip_r", "chip_g", "chip_b", "chip_a"];

/// Four ray casters sharing the ray port.
#[derive(Clone, Debug, Module)]
#[module(kind = "volume_lockstep")]
pub struct VolumeLockstep {
    #[child]
    pub chips: Vec<RayCaster>,
    #[input]
    pub ray_valid: Signal,
    #[output]
    pub ray_ready: Signal,
    #[input]
    pub ray_p: [Signal; 3],
    #[input]
    pub ray_d: [Signal; 3],
    #[input]
    pub ray_steps: Signal,
    /// R, G, B, alpha from the top byte down, valid with `out_valid`.
    #[output]
    pub out_valid: Signal,
    #[output]
    pub out_rgba: Signal,
    /// Set if the chips ever fell out of step (a modelling error, never expected).
    #[reg]
    pub out_of_step: Reg,
}

impl VolumeLockstep {
    /// Component `c` of every voxel (R, G, B, alpha) on chip `c`, value mode.
    pub fn new(p: VolumeParams, planes: &[Vec<u8>; 4]) -> Result<VolumeLockstep, String> {
        let chips = NAMES
            .iter()
            .zip(planes)
            .map(|(n, v)| RayCaster::new(p, Mode::Value, v).map(|c| c.named(n)))
            .collect::<Result<Vec<_>, _>>()?;
        let c = &chips[0];
        let (pos, steps) = (c.ray_p[0].fmt(), c.ray_steps.fmt());
        Ok(VolumeLockstep {
            ray_valid: Signal::bit("ray_valid"),
            ray_ready: Signal::bit("ray_ready"),
            ray_p: ["ray_x", "ray_y", "ray_z"].map(|n| Signal::new(n, pos)),
            ray_d: ["ray_dx", "ray_dy", "ray_dz"].map(|n| Signal::new(n, pos)),
            ray_steps: Signal::new("ray_steps", steps),
            out_valid: Signal::bit("out_valid"),
            out_rgba: Signal::new("out_rgba", Format::uint(32)),
            out_of_step: Reg::new("out_of_step", Format::uint(1)),
            chips,
        })
    }
}

impl VolumeLockstep {
    /// Every chip on the same ray; their results compared.
    pub fn eval(&mut self) {
        for chip in &mut self.chips {
            chip.ray_valid.follow(&self.ray_valid);
            for c in 0..3 {
                chip.ray_p[c].follow(&self.ray_p[c]);
                chip.ray_d[c].follow(&self.ray_d[c]);
            }
            chip.ray_steps.follow(&self.ray_steps);
            chip.eval();
        }
        let ready = self.chips[0].ray_ready.is_high();
        let valid = self.chips[0].out.valid.q().is_high();
        let apart = self
            .chips
            .iter()
            .any(|c| c.ray_ready.is_high() != ready || c.out.valid.q().is_high() != valid);
        if apart {
            self.out_of_step.set_next_bool(true);
        }
        self.ray_ready.set_bool(ready);
        self.out_valid.set_bool(valid);
        let rgba = self
            .chips
            .iter()
            .fold(0u64, |acc, c| acc << 8 | c.out.value.q().bits());
        self.out_rgba.set_bits(rgba);
    }
}
