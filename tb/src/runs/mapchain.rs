//! `texrtl mapchain`: pixels through the clocked chain walker 812 over the TEXRAM stub loaded
//! with a scene's maps, perhaps traced; and section 14's timing claims measured on the clocked
//! walker, which the testbench's conclusion holds against the document.

use crate::mapchain::{scene, Maps, Scene, Shape, CYCLE_PS, NAME, SLOT_CYCLES};
use crate::RunError;
use hdl::kernel::{Sim, Trace};
use units::mapchain::program::ChainRequest;
use units::mapchain::walker_812::{ChainResult, MapChain812};
use units::texram::stub::TexramStub;
use verif::{Driver, Stimulus, StreamDriver, Workload};

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
) -> Result<(Vec<ChainResult>, ChainStats), RunError> {
    let work = Workload::vcd(vcd);
    let stub = sc.stub().map_err(RunError::Input)?;
    let dut = MapChain812::new(sc.file.clone(), stub, SLOT_CYCLES).map_err(RunError::Input)?;
    let (sim, _) = work
        .sim(dut, NAME, CYCLE_PS, |_| ())
        .map_err(RunError::Waveform)?;
    let (cycles, out, mut sim) = clocked_sim(sim, px)?;
    if let Some(e) = sim.dut.banks.error.take() {
        return Err(format!("the banks refused an access: {e}").into());
    }
    work.finish(sim).map_err(RunError::Waveform)?;
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
/// One of section 14's timing claims, measured on the clocked walker.
#[derive(Clone, Debug)]
pub struct Timing {
    pub what: &'static str,
    pub pixels: usize,
    pub accesses: f64,
    pub faults: f64,
    pub ns: f64,
    /// The document's figure, when it gives one.
    pub document_ns: Option<f64>,
}

/// The clocked walker over the stub at full rate: the cycles from the first pixel taken to
/// the last result, and the results.
pub fn clocked(sc: &Scene, px: &[ChainRequest]) -> Result<(u64, Vec<ChainResult>), String> {
    let sim = Sim::new(MapChain812::new(sc.file.clone(), sc.stub()?, SLOT_CYCLES)?);
    clocked_sim(sim, px).map(|(c, r, _)| (c, r))
}

/// The walker over the stub in a (perhaps traced) simulation.
pub type WalkerSim<T> = Sim<MapChain812<TexramStub>, T>;

/// [`clocked`] on a given simulation, which it hands back.
pub fn clocked_sim<T: Trace>(
    mut sim: WalkerSim<T>,
    px: &[ChainRequest],
) -> Result<(u64, Vec<ChainResult>, WalkerSim<T>), String> {
    sim.reset(2);
    let (mut next, mut out, mut first) = (0usize, Vec::with_capacity(px.len()), None);
    let mut port = StreamDriver::new(verif::stream!(MapChain812<TexramStub>, req));
    for _ in 0..200 * (px.len() as u64 + 1) {
        port.drive(&mut sim.dut, px.get(next));
        sim.eval();
        if next < px.len() && port.accepted(&sim.dut) {
            first.get_or_insert(sim.cycle());
            next += 1;
        }
        if sim.dut.out_valid.q().is_high() {
            out.push(sim.dut.result());
        }
        sim.tick();
        if out.len() == px.len() {
            let cycles = sim.cycle() - 1 - first.unwrap_or(0);
            return Ok((cycles, out, sim));
        }
    }
    Err("the walker stalled".into())
}

/// Pixels along a texture row at `lambda`, a third of a texel apart, looking at one face.
fn scanline(n: usize, lambda: i32) -> Vec<ChainRequest> {
    (0..n)
        .map(|i| ChainRequest {
            drf: 0,
            u: 300 + 85 * i as i32,
            v: 9 << 8 | 0x40,
            lambda,
            n: [1200, -800, 16000],
            eye: [2000, 1500, 16100],
            face: 0,
            i_d: 200,
            i_s: 0,
        })
        .collect()
}

/// The chains of section 14's claims and the document's figures: texture + detail (4
/// accesses, about 240 ns) and the longest chain (9 accesses, about 540 ns); beside them
/// texture alone and texture + environment, for which the document gives accesses only.
pub fn timings() -> Result<Vec<Timing>, String> {
    let maps = Maps::new(&mut Stimulus::new(verif::Seed(15)));
    let cases = [
        ("texture, lambda 0.5", Shape::Texture, 128, None),
        (
            "texture + environment, lambda 0.5",
            Shape::Environment,
            128,
            None,
        ),
        (
            "texture + detail, lambda -2.5",
            Shape::Detail,
            -640,
            Some(240.0),
        ),
        (
            "longest chain, lambda -2.5",
            Shape::Longest,
            -640,
            Some(540.0),
        ),
    ];
    let n = 256;
    cases
        .into_iter()
        .map(|(what, shape, lambda, document_ns)| {
            let sc = scene(shape, &maps)?;
            let (cycles, out) = clocked(&sc, &scanline(n, lambda))?;
            let sum = |f: fn(&ChainResult) -> u32| out.iter().map(|r| f64::from(f(r))).sum::<f64>();
            Ok(Timing {
                what,
                pixels: n,
                accesses: sum(|r| r.accesses) / n as f64,
                faults: sum(|r| r.faults) / n as f64,
                ns: cycles as f64 * CYCLE_PS as f64 / 1000.0 / n as f64,
                document_ns,
            })
        })
        .collect()
}
