//! `texrtl footprint`: pixels through the cycle-accurate setup, generator and accumulator of
//! Figure 12 and the TEXRAM chip 802 or texture unit 602, each checked against the reference.

use crate::footprint::{
    drive_pixel, pixel_ready, ref_assemble, ref_assemble_texture, ref_setup, sample_pixel,
    Assembled, Pixel, NAME,
};
use crate::texram::{ref_border, RefMipmap, CYCLE_PS};
use formats::ccc::Ccc;
use units::footprint::assembly_fig12::SampleTarget;
use units::footprint::footprint_fig12::FootprintFig12;
use units::footprint::setup_fig12::SetupParams;
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::Drf;
use verif::{run, Event, PinDriver, PinMonitor, RunSpec, Workload};

/// What a run of pixels cost.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FootprintStats {
    pub pixels: u64,
    /// Samples (accesses of the chip, requests of the texture unit).
    pub accesses: u64,
    pub mean_n: f64,
    /// TEXRAM: slots, the slots page faults added, the banks that missed. Texture unit 602:
    /// DRAM page faults (reads that opened another row).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slots: Option<u64>,
    pub page_faults: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bank_misses: Option<u64>,
    pub cycles: u64,
    pub ns: u64,
    pub pixels_per_second: f64,
}

/// Each pixel's result (value, N, R G B, lambda raw sQ5.8) and the run's costs.
pub struct FootprintRun {
    pub results: Vec<(Assembled, i32)>,
    pub stats: FootprintStats,
}

/// Drives `pixels` through `dut` (traced into `vcd` at `period_ps`), each result checked
/// against `want(k)`: the results, the cycles, the design after.
fn drive_pixels<U: SampleTarget>(
    dut: FootprintFig12<U>,
    pixels: &[Pixel],
    (vcd, period_ps): (Option<&std::path::Path>, u64),
    want: impl Fn(usize) -> Assembled,
) -> Result<(Vec<Assembled>, u64, FootprintFig12<U>), crate::RunError> {
    let work = Workload::vcd(vcd);
    let (mut sim, _) = work
        .sim(dut, NAME, period_ps, |_| ())
        .map_err(crate::RunError::Waveform)?;
    sim.reset(2);
    let n = pixels.len() as u64;
    let mut results = Vec::with_capacity(pixels.len());
    let mut wrong = None;
    let mut spec = RunSpec::new(n, 200 * 64 * n + 1000);
    let st = run(
        &mut sim,
        &mut PinDriver::new(drive_pixel).ready(pixel_ready),
        &mut PinMonitor::new(sample_pixel),
        pixels.to_vec(),
        &mut spec,
        |_, ev| {
            if let Event::Received { txn, .. } = ev {
                let k = results.len();
                let w = want(k);
                if txn != w && wrong.is_none() {
                    wrong = Some(format!("pixel {k}: the unit {txn:?}, the reference {w:?}"));
                }
                results.push(txn);
            }
        },
    )
    .map_err(|e| e.to_string())?;
    if let Some(e) = wrong {
        return Err(e.into());
    }
    let dut = work.finish(sim).map_err(crate::RunError::Waveform)?;
    Ok((results, st.cycles, dut))
}

/// The costs common to both units.
fn stats_of(results: &[Assembled], cycles: u64, period_ps: u64) -> FootprintStats {
    let n = results.len() as u64;
    let accesses: u64 = results.iter().map(|r| u64::from(r.n)).sum();
    let ns = cycles * period_ps / 1000;
    FootprintStats {
        pixels: n,
        accesses,
        mean_n: accesses as f64 / n.max(1) as f64,
        slots: None,
        page_faults: 0,
        bank_misses: None,
        cycles,
        ns,
        pixels_per_second: if ns == 0 {
            0.0
        } else {
            n as f64 / ns as f64 * 1e9
        },
    }
}

/// `pixels` through [`FootprintFig12`] with the map `level0` in DRF 0 of the TEXRAM chip,
/// each result checked against the integer reference (`Err` names the first that differs).
pub fn run_footprint(
    drf: Drf,
    level0: &[u8],
    p: SetupParams,
    pixels: &[Pixel],
    vcd: Option<&std::path::Path>,
) -> Result<FootprintRun, crate::RunError> {
    let mut chip = Texram802::new(TexramParams::default())?;
    chip.set_drf(0, drf)?;
    chip.load(0, level0)?;
    let dut = FootprintFig12::new(p, chip)?;
    let (w, h) = (1 << drf.width_log2, 1 << drf.height_log2);
    let reference = RefMipmap::build(w, h, level0);
    let border = ref_border(drf.border);
    let want = |k: usize| ref_assemble(&reference, border, &p, &pixels[k]).0;
    let (results, cycles, dut) = drive_pixels(dut, pixels, (vcd, CYCLE_PS), want)?;
    let c = &dut.assembly.chip;
    let mut stats = stats_of(&results, cycles, CYCLE_PS);
    stats.slots = Some(c.slots.q().bits());
    stats.page_faults = c.fault_slots.q().bits();
    stats.bank_misses = Some(c.faults.q().bits());
    let results = results
        .into_iter()
        .zip(pixels)
        .map(|(r, q)| (r, ref_setup(&p, q).2))
        .collect();
    Ok(FootprintRun { results, stats })
}

/// `pixels` through [`FootprintFig12`] driving Figure 6's texture unit 602 (`tp`) with the
/// CCC texture `tex`, each result checked against the integer reference.
pub fn run_footprint_texture(
    tex: &Ccc,
    tp: units::texmem::texture_unit_602::TexParams,
    p: SetupParams,
    pixels: &[Pixel],
    vcd: Option<&std::path::Path>,
) -> Result<FootprintRun, crate::RunError> {
    use units::texmem::texture_unit_602::TextureUnit;
    if (tex.width, tex.height) != (tp.width, tp.height) {
        return Err(format!(
            "texture is {}x{}, the unit is set up for {}x{}",
            tex.width, tex.height, tp.width, tp.height
        )
        .into());
    }
    tp.validate()?;
    let words = tex.dram_words(&tp.block_map());
    let unit = TextureUnit::new("texture_unit_602", tp, &tex.clut, &words)?;
    let dut = FootprintFig12::new(p, unit)?;
    let period = u64::from(tp.dram.cycle_ns) * 1000;
    let want = |k: usize| ref_assemble_texture(tex, tp.frac_bits, &p, &pixels[k]).0;
    let (results, cycles, dut) = drive_pixels(dut, pixels, (vcd, period), want)?;
    let mut stats = stats_of(&results, cycles, period);
    stats.page_faults = dut.assembly.chip.mem.page_faults.q().bits();
    let results = results
        .into_iter()
        .zip(pixels)
        .map(|(r, q)| (r, ref_setup(&p, q).2))
        .collect();
    Ok(FootprintRun { results, stats })
}
