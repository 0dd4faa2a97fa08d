//! `texrtl texram`: requests back to back through the TEXRAM chip 802 holding a map, every
//! result checked against the integer reference or the behavioural stub.

use crate::texram::{ref_border, sample_tex, RefMipmap, TexDriver, TexReq, CYCLE_PS};
use units::texram::clut_814::Clut;
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::Drf;
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
/// difference is an error: the command must not print a wrong texel): luminance against the
/// integer reference, the other configurations against the behavioural stub. Traced to `vcd`
/// when given.
pub fn run_texram(
    tex: &TexramTexture,
    reqs: &[TexReq],
    vcd: Option<&std::path::Path>,
) -> Result<TexramRun, String> {
    use units::texram::{Config, TexramAccess, TexramRequest};
    let drf = tex.drf;
    let (chip, mut stub) = tex.load()?;
    let level0 = &tex.levels[0];
    let (wl, hl, border) = (drf.width_log2, drf.height_log2, drf.border);
    let work = Workload::vcd(vcd);
    let (mut sim, _) = work.sim(chip, "texram_802", CYCLE_PS, |_| ())?;
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
        return Err(w);
    }
    let stats = TexramStats::of(&sim.dut, n, st.cycles);
    work.finish(sim)?;
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
