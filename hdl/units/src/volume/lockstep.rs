//! Pre-classified RGBA volumes (section 13): four chips, each holding one component of the
//! classified volume, in lock-step on the same rays. Every chip reads the same addresses, so
//! all four take the same slots and deliver a sample's R, G, B and alpha in the same cycle.
//! Compositing (alpha blending along the ray) is the host's, as the document says; the golden
//! model has one (`golden::volume::composite`). In the waveform: `volume_lockstep.chip_r` ...

use super::layout::{Mode, VolumeParams};
use super::ray_caster_fig15::{RayCaster, RayIn};
use crate::texram::lockstep::{Lockstep, LockstepChip};

impl LockstepChip for RayCaster {
    type Port = RayIn;
    const GROUP: &'static str = "volume_lockstep";
    const READY: &'static str = "ray_ready";
    fn port(&self) -> RayIn {
        self.ray.clone()
    }
    fn drive(&mut self, port: &RayIn) {
        self.ray.follow(port);
    }
    fn ready(&self) -> bool {
        self.ray_ready.is_high()
    }
    fn out(&self) -> Option<u8> {
        let o = &self.out;
        o.valid.q().is_high().then(|| o.value.q().bits() as u8)
    }
}

/// Four ray casters sharing the ray port.
pub type VolumeLockstep = Lockstep<RayCaster>;

impl Lockstep<RayCaster> {
    /// Component `c` of every voxel (R, G, B, alpha) on chip `c`, value mode.
    pub fn new(p: VolumeParams, planes: &[Vec<u8>; 4]) -> Result<VolumeLockstep, String> {
        let [r, g, b, a] = planes;
        let chip = |v: &Vec<u8>| RayCaster::new(p, Mode::Value, v);
        Ok(Lockstep::of(
            [chip(r)?, chip(g)?, chip(b)?, chip(a)?],
            RayCaster::named,
        ))
    }
}
