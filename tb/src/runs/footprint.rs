//! `texrtl footprint`: pixels through the cycle-accurate setup, generator and accumulator of
//! Figure 12 and the TEXRAM chip 802 or texture unit 602, each checked against the reference;
//! and the quality claim of section 4 (footprint assembly against isotropic trilinear
//! filtering on a tilted plane), which the testbench's conclusion tabulates.

use crate::footprint::{
    drive_pixel, pixel_ready, ref_assemble, ref_assemble_texture, ref_setup, sample_pixel,
    Assembled, Pixel, NAME,
};
use crate::texram::{ref_border, RefMipmap, CYCLE_PS};
use formats::ccc::Ccc;
use units::footprint::assembly_fig12::SampleTarget;
use units::footprint::footprint_fig12::FootprintFig12;
use units::footprint::setup_fig12::SetupParams;
use units::texmem::texture_unit_602::{TexParams, TextureUnit};
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::{Border, Drf};
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

/// Figure 12's units before a TEXRAM chip holding the map `level0` in DRF 0 as `drf` says.
pub fn on_texram(
    p: SetupParams,
    drf: Drf,
    level0: &[u8],
) -> Result<FootprintFig12<Texram802>, String> {
    let mut chip = Texram802::new(TexramParams::default())?;
    chip.set_drf(0, drf)?;
    chip.load(0, level0)?;
    FootprintFig12::new(p, chip)
}

/// Figure 12's units before texture unit 602 (`tp`) holding the CCC texture `tex`.
pub fn on_texture(
    p: SetupParams,
    tex: &Ccc,
    tp: TexParams,
) -> Result<FootprintFig12<TextureUnit>, String> {
    let words = tex.dram_words(&tp.block_map());
    let unit = TextureUnit::new("texture_unit_602", tp, &tex.clut, &words)?;
    FootprintFig12::new(p, unit)
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
    let dut = on_texram(p, drf, level0)?;
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
    Ok(FootprintRun::new(results, pixels, &p, stats))
}

impl FootprintRun {
    /// The run's results, each beside its pixel's level of detail by the reference setup.
    fn new(
        results: Vec<Assembled>,
        pixels: &[Pixel],
        p: &SetupParams,
        stats: FootprintStats,
    ) -> FootprintRun {
        let results = results
            .into_iter()
            .zip(pixels)
            .map(|(r, q)| (r, ref_setup(p, q).2))
            .collect();
        FootprintRun { results, stats }
    }
}

/// `pixels` through [`FootprintFig12`] driving Figure 6's texture unit 602 (`tp`) with the
/// CCC texture `tex`, each result checked against the integer reference.
pub fn run_footprint_texture(
    tex: &Ccc,
    tp: TexParams,
    p: SetupParams,
    pixels: &[Pixel],
    vcd: Option<&std::path::Path>,
) -> Result<FootprintRun, crate::RunError> {
    if (tex.width, tex.height) != (tp.width, tp.height) {
        return Err(format!(
            "texture is {}x{}, the unit is set up for {}x{}",
            tex.width, tex.height, tp.width, tp.height
        )
        .into());
    }
    tp.validate()?;
    let dut = on_texture(p, tex, tp)?;
    let period = u64::from(tp.dram.cycle_ns) * 1000;
    let want = |k: usize| ref_assemble_texture(tex, tp.frac_bits, &p, &pixels[k]).0;
    let (results, cycles, dut) = drive_pixels(dut, pixels, (vcd, period), want)?;
    let mut stats = stats_of(&results, cycles, period);
    stats.page_faults = dut.assembly.chip.mem.page_faults.q().bits();
    Ok(FootprintRun::new(results, pixels, &p, stats))
}

// ---------------------------------------------------------------------------------------
// The quality claim of section 4: footprint assembly against isotropic trilinear filtering.

/// Side of the quality map (level 0).
pub const QUALITY_LOG2: u32 = 10;

/// A 1024 x 1024 map with detail at every scale: a checker of 16-texel squares and, in
/// every other 64-texel band, "text": rows of one-texel strokes in 5 x 7 cells.
pub fn quality_map() -> Vec<u8> {
    let n = 1u32 << QUALITY_LOG2;
    (0..n * n)
        .map(|k| {
            let (x, y) = (k % n, k / n);
            let checker = (x / 16 + y / 16) % 2 == 0;
            let band = (y / 64) % 2 == 1;
            let (cx, cy) = (x % 6, y % 9);
            // A stroke pattern that changes from cell to cell, like letters.
            let cell = (x / 6).wrapping_mul(2_654_435_761) ^ (y / 9).wrapping_mul(40_503);
            let stroke = cx < 5 && cy < 7 && (cell >> (cx + 5 * (cy % 3))) & 1 == 1;
            match (band && stroke, checker) {
                (true, _) => 20,
                (false, true) => 200,
                (false, false) => 110,
            }
        })
        .collect()
}

/// One tilt's measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct QualityRow {
    pub tilt_degrees: f64,
    pub pixels: usize,
    /// RMSE against the box average, in LSBs: isotropic trilinear, footprint assembly.
    pub rmse_trilinear: f64,
    pub rmse_footprint: f64,
    pub mean_n: f64,
    /// Slots (30 ns) and bank faults of the footprint-assembly accesses.
    pub slots: u64,
    pub faults: u64,
    pub pixels_per_second: f64,
}

/// Screen position to texture position on a plane tilted `tilt` from facing the camera:
/// focal length 256 pixels, the plane 256 units away, 1.5 texels a pixel where it faces.
fn plane_uv(x: f64, y: f64, tilt: f64) -> Option<(f64, f64)> {
    let (f, d, k) = (256.0, 256.0, 1.5);
    let den = f * tilt.cos() - y * tilt.sin();
    if den <= 1e-9 {
        return None;
    }
    let t = y * d / den;
    let s = x * (d + t * tilt.sin()) / f;
    Some((s * k + 512.0, t * k + 512.0))
}

/// One pixel of a view: the box average, isotropic trilinear, footprint assembly, N, and the
/// assembly's slots and bank faults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewPixel {
    pub reference: f64,
    pub trilinear: u8,
    pub footprint: u8,
    pub n: u32,
    pub slots: u32,
    pub faults: u32,
}

/// Side of a view in pixels.
pub const VIEW: usize = 64;

/// A 64 x 64-pixel view of the quality map on a plane at `tilt_degrees`, row by row: every
/// pixel whose footprint is at most 128 texels long (else `None`): isotropic trilinear (one
/// access at `log2 m`) and footprint assembly (N accesses at `log2 q`), both on the TEXRAM
/// stub, and the mean of level 0 over the pixel's exact parallelogram (at least two samples
/// a texel along each edge).
pub fn view(tilt_degrees: f64, p: &SetupParams) -> Result<Vec<Option<ViewPixel>>, String> {
    use units::footprint::assembly_fig12::assemble;
    use units::footprint::setup_fig12::{setup, SetupUnit};
    use units::texram::stub::TexramStub;
    use units::texram::{TexramAccess, TexramRequest};
    let level0 = quality_map();
    let n = 1usize << QUALITY_LOG2;
    let map = golden::footprint::Map {
        width: n,
        height: n,
        texels: &level0,
    };
    let drf = Drf::new(QUALITY_LOG2, QUALITY_LOG2, Border::Wrap);
    let (mut iso, mut fa) = (TexramStub::new(), TexramStub::new());
    for chip in [&mut iso, &mut fa] {
        chip.set_drf(0, drf)?;
        chip.load(0, &level0)?;
    }
    let table = *SetupUnit::new("setup", *p)?.table();
    let tilt = tilt_degrees.to_radians();
    let raw = |x: f64| (x * 256.0).round() as i32;
    let mut out = Vec::with_capacity(VIEW * VIEW);
    for py in 0..VIEW {
        for px in 0..VIEW {
            let (x, y) = (px as f64 - 31.5, py as f64 - 47.5);
            let h = 1e-3;
            let (Some(c), Some(dx), Some(dy)) = (
                plane_uv(x, y, tilt),
                plane_uv(x + h, y, tilt),
                plane_uv(x, y + h, tilt),
            ) else {
                out.push(None);
                continue;
            };
            let r1 = ((dx.0 - c.0) / h, (dx.1 - c.1) / h);
            let r2 = ((dy.0 - c.0) / h, (dy.1 - c.1) / h);
            let (l1, l2) = (r1.0.hypot(r1.1), r2.0.hypot(r2.1));
            if l1.max(l2) > 128.0 {
                out.push(None);
                continue;
            }
            let k = |l: f64| ((2.0 * l).ceil() as usize).max(16);
            let reference = map.box_average(c, r1, r2, (k(l1), k(l2)));
            let s = setup(p, (raw(r1.0), raw(r1.1)), (raw(r2.0), raw(r2.1)), &table);
            let (u, v) = (raw(c.0), raw(c.1));
            let t = iso.access(TexramRequest {
                drf: 0,
                u,
                v,
                lambda: s.lambda_iso,
            })?;
            let a = assemble(&mut fa, 0, (u, v), &s)?;
            out.push(Some(ViewPixel {
                reference,
                trilinear: t.value,
                footprint: a.value,
                n: a.n,
                slots: a.slots,
                faults: a.faults,
            }));
        }
    }
    Ok(out)
}

/// [`view`] summed up: RMSE of both filters against the box average, mean N, the assembly's
/// slots, faults and pixel rate.
pub fn quality(tilt_degrees: f64, p: &SetupParams) -> Result<QualityRow, String> {
    let v = view(tilt_degrees, p)?;
    let px: Vec<&ViewPixel> = v.iter().flatten().collect();
    let c = px.len().max(1) as f64;
    let rmse = |f: &dyn Fn(&ViewPixel) -> u8| {
        (px.iter()
            .map(|q| (f64::from(f(q)) - q.reference).powi(2))
            .sum::<f64>()
            / c)
            .sqrt()
    };
    let slots: u64 = px.iter().map(|q| u64::from(q.slots)).sum();
    Ok(QualityRow {
        tilt_degrees,
        pixels: px.len(),
        rmse_trilinear: rmse(&|q| q.trilinear),
        rmse_footprint: rmse(&|q| q.footprint),
        mean_n: px.iter().map(|q| f64::from(q.n)).sum::<f64>() / c,
        slots,
        faults: px.iter().map(|q| u64::from(q.faults)).sum(),
        pixels_per_second: c / (slots as f64 * 30e-9),
    })
}

/// The tilts of the quality table.
pub const TILTS: [f64; 4] = [0.0, 60.0, 75.0, 85.0];
