//! Footprint assembly end to end (section 10): the rasterizer's setup unit feeding the chip
//! side's generator and accumulator, which drive the TEXRAM chip 802. The setup unit hands a
//! pixel over (`u, v, lambda`, then `dr` and `N`, as one transfer here) when the generator
//! is free, so the setup of pixel i+1 overlaps the assembly of pixel i.

use super::assembly_fig12::{FootprintAssembly, SampleTarget};
use super::setup_fig12::{SetupParams, SetupUnit};
use crate::kernel::Module;
use crate::texram::texram_802::Texram802;

/// The setup unit and the assembly unit with its chip (or Figure 6's texture unit).
#[derive(Clone, Debug, Module)]
#[module(kind = "footprint_fig12")]
pub struct FootprintFig12<T: SampleTarget = Texram802> {
    /// Drive its inputs (`in_valid`, `drf`, `u`, `v`, `r1u` ... `r2v`); `in_ready` says it
    /// took them.
    #[child]
    pub setup: SetupUnit,
    /// Its accumulator's `out_valid`, `out_value`, `out_n` are the pixel's result.
    #[child]
    pub assembly: FootprintAssembly<T>,
}

impl<T: SampleTarget> FootprintFig12<T> {
    pub fn new(p: SetupParams, chip: T) -> Result<FootprintFig12<T>, String> {
        Ok(FootprintFig12 {
            setup: SetupUnit::new("footprint_setup", p)?,
            assembly: FootprintAssembly::new(chip),
        })
    }
}

impl<T: SampleTarget> FootprintFig12<T> {
    /// The assembly unit first (its `px_ready` is the setup unit's `out_ready`), then setup.
    pub fn eval(&mut self) {
        let (s, a) = (&self.setup, &mut self.assembly);
        a.px_valid.follow(s.out_valid.q());
        a.px_drf.follow(s.out_drf.q());
        a.px_u.follow(s.out_u.q());
        a.px_v.follow(s.out_v.q());
        a.px_lambda.follow(s.lambda.q());
        a.px_du.follow(s.du.q());
        a.px_dv.follow(s.dv.q());
        a.px_log2_n.follow(s.log2_n.q());
        a.eval();
        self.setup.out_ready.follow(&self.assembly.px_ready);
        self.setup.eval();
    }
}
