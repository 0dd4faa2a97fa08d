//! `texrtl mapchain`: pixels through the clocked chain walker 812 over the TEXRAM stub loaded
//! with a scene's maps, perhaps traced.

use crate::mapchain::{clocked_sim, Scene, CYCLE_PS, NAME, SLOT_CYCLES};
use units::mapchain::program::ChainRequest;
use units::mapchain::walker_812::{ChainResult, MapChain812};
use verif::Workload;

/// What `texrtl mapchain` writes to its statistics.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct ChainStats {
    pub pixels: u64,
    pub accesses: u64,
    /// Accesses that found a bank's row closed (each took a second slot).
    pub page_faults: u64,
    pub slots: u64,
    pub errors: u64,
    pub cycles: u64,
    pub ns: f64,
    pub ns_per_pixel: f64,
}

/// The requests through the clocked walker over the stub loaded with `sc`'s maps, traced to
/// `vcd` if given: each pixel's result and the statistics.
pub fn run_mapchain(
    sc: &Scene,
    px: &[ChainRequest],
    vcd: Option<&std::path::Path>,
) -> Result<(Vec<ChainResult>, ChainStats), String> {
    let work = Workload::vcd(vcd);
    let dut = MapChain812::new(sc.file.clone(), sc.stub()?, SLOT_CYCLES)?;
    let (sim, _) = work.sim(dut, NAME, CYCLE_PS, |_| ())?;
    let (cycles, out, mut sim) = clocked_sim(sim, px)?;
    if let Some(e) = sim.dut.banks.error.take() {
        return Err(format!("the banks refused an access: {e}"));
    }
    work.finish(sim)?;
    let sum = |f: fn(&ChainResult) -> u32| out.iter().map(|r| u64::from(f(r))).sum::<u64>();
    let ns = cycles as f64 * CYCLE_PS as f64 / 1000.0;
    let st = ChainStats {
        pixels: px.len() as u64,
        accesses: sum(|r| r.accesses),
        page_faults: sum(|r| r.faults),
        slots: sum(|r| r.slots),
        errors: sum(|r| u32::from(r.error)),
        cycles,
        ns,
        ns_per_pixel: ns / px.len().max(1) as f64,
    };
    Ok((out, st))
}
