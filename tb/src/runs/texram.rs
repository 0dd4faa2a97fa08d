//! `texrtl texram`: requests back to back through the TEXRAM chip 802 holding a map, every
//! result checked against the integer reference or the behavioural stub; and the document's
//! pixel rates (section 5) measured on the chip, which the testbench's conclusion holds
//! against the document.

use crate::texram::{ref_border, sample_tex, RefMipmap, TexDriver, TexReq, CYCLE_PS};
use crate::RunError;
use hdl::kernel::Sim;
use units::texram::clut_814::Clut;
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::{Border, Drf};
use verif::{run, Event, PinMonitor, RunSpec, Workload};

/// What `texrtl texram` measured (its `--stats`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct TexramStats {
    /// Pixels asked for.
    pub requests: u64,
    /// Bank accesses: one a request, four for the planar and literal colour layouts.
    pub accesses: u64,
    pub slots: u64,
    /// Slots added by page faults (a round of an access in which a bank missed its open row).
    pub page_faults: u64,
    /// Banks that missed their open row, summed over the accesses.
    pub bank_misses: u64,
    /// Accesses that asked one bank for several words (only the literal colour layout).
    pub bank_conflicts: u64,
    /// Slots taken by the video port 808 (0 when the chip has no video, as in `texrtl texram`).
    pub video_slots: u64,
    pub cycles: u64,
    pub ns: u64,
    pub pixels_per_second: f64,
}

/// A run of the chip over requests (raw sQ12.8 u, v and sQ5.8 lambda): one result per request
/// in order, and the statistics.
pub struct TexramRun {
    /// R, G, B, alpha per request.
    pub values: Vec<[u8; 4]>,
    pub stats: TexramStats,
}

/// A map as the host hands it to the chip: its DRF, every level, the CLUT (index maps).
pub struct TexramTexture {
    pub drf: Drf,
    pub levels: Vec<Vec<u8>>,
    pub clut: Clut,
}

impl TexramTexture {
    /// Level 0 and the levels the generator 816 makes from it (luminance and colour maps).
    pub fn generated(drf: Drf, level0: &[u8]) -> TexramTexture {
        let mut levels = vec![level0.to_vec()];
        for k in 0..drf.max_level() {
            let (w, h) = drf.level_size(k);
            let next = units::texram::stub::next_level(w, h, &levels[k as usize]);
            levels.push(next);
        }
        TexramTexture {
            drf,
            levels,
            clut: Clut::identity(),
        }
    }

    /// The chip and the stub with the map in DRF 0 (every level) and the CLUT.
    fn load(&self) -> Result<(Texram802, units::texram::stub::TexramStub), String> {
        use units::texram::TexramAccess;
        let mut chip = Texram802::new(TexramParams::default())?;
        chip.set_drf(0, self.drf)?;
        let mut stub = units::texram::stub::TexramStub::new();
        stub.set_drf(0, self.drf)?;
        for (k, level) in self.levels.iter().enumerate() {
            chip.write_level(0, k as u32, level)?;
            stub.write_level(0, k as u32, level)?;
        }
        chip.set_clut(self.clut.clone());
        stub.set_clut(self.clut.clone());
        Ok((chip, stub))
    }
}

/// Runs `reqs` back to back through the chip holding `tex`, every result checked (a
/// difference fails the run: the command must not print a wrong texel): luminance against the
/// integer reference, the other configurations against the behavioural stub. Traced to `vcd`
/// when given.
pub fn run_texram(
    tex: &TexramTexture,
    reqs: &[TexReq],
    vcd: Option<&std::path::Path>,
) -> Result<TexramRun, RunError> {
    use units::texram::{Config, TexramAccess, TexramRequest};
    let drf = tex.drf;
    let (chip, mut stub) = tex.load().map_err(RunError::Input)?;
    let level0 = &tex.levels[0];
    let (wl, hl, border) = (drf.width_log2, drf.height_log2, drf.border);
    let work = Workload::vcd(vcd);
    let (mut sim, _) = work
        .sim(chip, "texram_802", CYCLE_PS, |_| ())
        .map_err(RunError::Waveform)?;
    sim.reset(2);
    let reference = RefMipmap::build(1 << wl, 1 << hl, level0);
    let n = reqs.len() as u64;
    let mut values: Vec<[u8; 4]> = Vec::with_capacity(reqs.len());
    // A literal colour request: four components, each up to four rounds of two slots.
    let mut spec = RunSpec::new(n, 200 * n + 100);
    let mut wrong = None;
    let st = run(
        &mut sim,
        &mut TexDriver::default(),
        &mut PinMonitor::new(sample_tex),
        reqs.to_vec(),
        &mut spec,
        |_, ev| {
            if let Event::Received { txn, .. } = ev {
                let q = reqs[values.len()];
                let want = if drf.config == Config::Luminance {
                    [reference.access(q.u, q.v, q.lambda, ref_border(border)).1; 4]
                } else {
                    let r = TexramRequest {
                        drf: 0,
                        u: q.u,
                        v: q.v,
                        lambda: q.lambda,
                    };
                    match stub.access(r) {
                        Ok(r) => r.rgba,
                        Err(e) => {
                            wrong.get_or_insert(format!("request {}: {e}", values.len()));
                            [0; 4]
                        }
                    }
                };
                if txn.rgba != want && wrong.is_none() {
                    let k = values.len();
                    wrong = Some(format!("request {k}: chip {:?}, model {want:?}", txn.rgba));
                }
                values.push(txn.rgba);
            }
        },
    )
    .map_err(|e| e.to_string())?;
    if let Some(w) = wrong {
        return Err(RunError::Failed(w));
    }
    let stats = TexramStats::of(&sim.dut, n, st.cycles);
    work.finish(sim).map_err(RunError::Waveform)?;
    Ok(TexramRun { values, stats })
}

impl TexramStats {
    /// The chip's counters after `requests` requests in `cycles` cycles.
    fn of(d: &Texram802, requests: u64, cycles: u64) -> TexramStats {
        let ns = cycles * CYCLE_PS / 1000;
        TexramStats {
            requests,
            accesses: d.accesses.q().bits(),
            slots: d.slots.q().bits(),
            page_faults: d.fault_slots.q().bits(),
            bank_misses: d.faults.q().bits(),
            bank_conflicts: d.address.conflicts.q().bits(),
            video_slots: d.video().map_or(0, |v| v.slots.q().bits()),
            cycles,
            ns,
            pixels_per_second: if ns == 0 {
                0.0
            } else {
                requests as f64 / ns as f64 * 1e9
            },
        }
    }
}
// ---------------------------------------------------------------------------------------
// The document's pixel rates, measured on the chip from its page-register state.

/// One measured rate against the document's.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    pub what: &'static str,
    pub pixels: u64,
    pub slots: u64,
    /// Clock cycles from the first result to one slot after the last (the pixels' time).
    pub cycles: u64,
    pub pixels_per_second: f64,
    /// The document's figure (pixels per second), where it gives one.
    pub document: Option<f64>,
}

/// Runs `reqs` (DRF, u, v, lambda) back to back through `chip`: cycles from the first result
/// (a warm-up request's) to the last, and the slots the chip counted after the warm-up.
fn time_stream(chip: Texram802, reqs: &[(u8, i32, i32, i32)]) -> (u64, u64) {
    let mut sim = Sim::new(chip);
    sim.reset(2);
    let (mut next, mut first, mut last, mut seen) = (0, None, 0, 0);
    while seen < reqs.len() {
        let d = &mut sim.dut;
        d.req_valid.set_bool(next < reqs.len());
        if let Some(&(drf, u, v, l)) = reqs.get(next) {
            d.req_drf.set_bits(u64::from(drf));
            d.req_u.set_raw(i64::from(u));
            d.req_v.set_raw(i64::from(v));
            d.req_lambda.set_raw(i64::from(l));
        }
        sim.eval();
        if sim.dut.req_valid.is_high() && sim.dut.req_ready.is_high() {
            next += 1;
        }
        if sim.dut.output.out_valid.q().is_high() {
            first.get_or_insert(sim.cycle());
            last = sim.cycle();
            seen += 1;
        }
        sim.tick();
    }
    (last - first.unwrap_or(last), sim.dut.slots.q().bits())
}

/// A chip with a map in DRF 0 (1024 x 1024, or 512 x 512 to leave room for a second) and a
/// 256 x 256 map in DRF 1 stored after it in every bank.
fn figure_chip(log2: u32) -> Texram802 {
    let mut chip = Texram802::new(TexramParams::default()).expect("default parameters");
    let big = Drf::new(log2, log2, Border::Wrap);
    let mut env = Drf::new(8, 8, Border::Clamp);
    env.base_even = units::texram::banks_810::group_words(&big, 0);
    env.base_odd = units::texram::banks_810::group_words(&big, 1);
    chip.set_drf(0, big).expect("fits");
    chip.set_drf(1, env).expect("fits");
    let level0: Vec<u8> = (0..1 << 20).map(|k: u32| (k % 251) as u8).collect();
    chip.load(0, &level0[..1 << (2 * log2)]).expect("loads");
    if log2 < 10 {
        chip.load(1, &level0[..1 << 16]).expect("loads");
    }
    chip
}

/// The rates of section 5, from the slots the chip takes: one pixel per hit access (33.3 M),
/// scanlines of 8 pixels with 2 page faults (about 27 M), two accesses per pixel (texture and
/// environment, 16.7 M without faults) and four (all colours from one chip, 8.3 M). The last
/// row is what the page registers make of two maps in different rows of the same banks.
pub fn figures() -> Vec<Figure> {
    let texel = |x: i32| (x << 8) + 128;
    let pixel = |u: i32, v: i32| (0u8, texel(u), texel(v), 0);
    let mut out = Vec::new();
    // `per` accesses per pixel; `reqs` after a warm-up access that opens rows far away.
    let mut measure = |what, per: u64, reqs: Vec<(u8, i32, i32, i32)>, document: Option<f64>| {
        // The two-map figure needs room for the second map.
        let log2 = if document.is_none() { 9 } else { 10 };
        let mut all = vec![pixel(0, 400)];
        all.extend(&reqs);
        let (cycles, slots) = time_stream(figure_chip(log2), &all);
        let ns = cycles as f64 * CYCLE_PS as f64 / 1000.0;
        let pixels = reqs.len() as u64 / per;
        out.push(Figure {
            what,
            pixels,
            slots: slots - 2,
            cycles,
            pixels_per_second: pixels as f64 / ns * 1e9,
            document,
        });
    };
    // Peak: a span along a scanline, every access in the rows the first opened.
    let span: Vec<_> = (0..1000).map(|k| pixel(k % 500, 7)).collect();
    measure("one access per pixel, no page fault", 1, span, Some(33.3e6));
    // Scanlines of 8 pixels; each opens new rows at its start and once more half way.
    let mut lines = Vec::new();
    for s in 0..200 {
        let v = 8 * s;
        lines.extend((0..4).map(|k| pixel(100 + k, v)));
        lines.extend((4..8).map(|k| pixel(100 + k, v + 2)));
    }
    measure(
        "8 pixels and 2 page faults per scanline",
        1,
        lines,
        Some(26.7e6),
    );
    // Two and four accesses per pixel in the open rows.
    let two: Vec<_> = (0..2000).map(|k| pixel(k / 2 % 500, 7)).collect();
    measure(
        "2 accesses per pixel (texture + environment), no fault",
        2,
        two,
        Some(16.7e6),
    );
    let four: Vec<_> = (0..4000).map(|k| pixel(k / 4 % 500, 7)).collect();
    measure(
        "4 accesses per pixel (all colours on one chip)",
        4,
        four,
        Some(8.33e6),
    );
    // Texture (DRF 0) and environment (DRF 1) alternating: each access reopens its rows.
    let alt: Vec<_> = (0..2000)
        .map(|k| (k as u8 % 2, texel(k / 2 % 200), texel(7), 0))
        .collect();
    measure("texture + environment maps in different rows", 2, alt, None);
    out
}
