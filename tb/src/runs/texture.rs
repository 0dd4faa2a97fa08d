//! `texrtl texread` (and the texture testbench, and the regression vectors): rasterizer
//! requests through texture unit 602 holding a CCC texture, perhaps traced; the results, their
//! cycles, each request's first lookup and the run's statistics, the shadow cache splitting
//! the misses and the unit's two handshakes checked at the pins.

use crate::texture::reference_filter;
use crate::RunError;
use formats::ccc::Ccc;
use hdl::kernel::{Sim, Trace};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;
use std::path::PathBuf;
use units::texmem::texture_unit_602::{TexParams, TextureUnit};
use verif::{
    run, Event, Handshake, Pacing, PinDriver, PinMonitor, ProbeSink, RunSpec, WaveOut, Workload,
};
use waves::{ProbeId, TraceConfig};

/// One rasterizer request: raw `uQ12.F` coordinates and the scanline-change flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexRequest {
    pub u: u32,
    pub v: u32,
    pub newline: bool,
}

/// What a run measured (`--stats` JSON). Units in the names; counts are of blocks (4x4
/// texels, two DRAM words) unless they say otherwise.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct TexReadStats {
    pub requests: u64,
    /// Cycles between requests the rasterizer can offer (1: one per cycle).
    pub interval: u32,
    /// Cycles from the first request presented to the last result out, inclusive.
    pub cycles: u64,
    pub cycle_ns: u32,
    pub ns: u64,
    /// `requests / ns` in pixels per second.
    pub pixels_per_second: f64,
    pub layout: String,
    pub cache: bool,
    /// `off`, `quadrant` or `direction` (`off` whenever the cache is).
    pub lookahead: String,
    pub page_words: u32,
    /// Blocks referenced (1, 2 or 4 per request), found at the first lookup, and `hits/refs`.
    pub block_refs: u64,
    pub hits: u64,
    pub hit_rate: f64,
    /// `block_refs - hits`, split by the shadow cache.
    pub misses: u64,
    pub misses_cold: u64,
    pub misses_capacity: u64,
    pub misses_conflict: u64,
    pub demand_fills: u64,
    pub prefetch_fills: u64,
    /// Hits on blocks a prefetch brought in (first use).
    pub prefetch_hits: u64,
    /// Misses whose block a prefetch was already fetching.
    pub late_prefetches: u64,
    pub prefetch_dropped: u64,
    /// Cycles a request waited in stage 0.
    pub stall_cycles: u64,
    pub dram_reads: u64,
    pub page_hits: u64,
    pub page_faults: u64,
    /// Scanlines (the first request and each one flagged `newline`), and page faults per one.
    pub scanlines: u64,
    pub page_faults_per_scanline: f64,
    /// Timing or protocol violations the DRAM model saw.
    pub violations: u64,
}

/// Results (24-bit RGB, in request order), their output cycles, first-lookup outcomes and statistics.
#[derive(Clone, Debug)]
pub struct TexRun {
    pub rgb: Vec<u32>,
    /// Per result: the cycle it left 622, counted from the cycle the first request was offered.
    pub out_cycles: Vec<u64>,
    /// Per request: blocks of its footprint and how many hit at its first lookup.
    pub lookups: Vec<(u8, u8)>,
    pub stats: TexReadStats,
    /// What the run found wrong in the unit's behaviour: it hung (results stopped, or it never
    /// went idle), or a handshake was broken. The figures above are then up to where it went
    /// wrong.
    pub findings: Vec<String>,
}

/// A fully-associative LRU cache of block tags (the shadow cache).
#[derive(Clone, Debug, Default)]
pub struct Shadow {
    lru: Vec<(u32, u32)>,
    cap: usize,
    seen: HashSet<(u32, u32)>,
}

/// How the shadow classified a reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MissKind {
    Cold,
    Capacity,
    Conflict,
}

impl Shadow {
    pub fn new(cap: usize) -> Shadow {
        Shadow {
            cap,
            ..Shadow::default()
        }
    }

    /// References `blk`; for a miss of the real cache, says which kind it was.
    pub fn reference(&mut self, blk: (u32, u32), real_hit: bool) -> Option<MissKind> {
        let pos = self.lru.iter().position(|&b| b == blk);
        let kind = if real_hit {
            None
        } else if !self.seen.contains(&blk) {
            Some(MissKind::Cold)
        } else if pos.is_none() {
            Some(MissKind::Capacity)
        } else {
            Some(MissKind::Conflict)
        };
        self.seen.insert(blk);
        if let Some(p) = pos {
            self.lru.remove(p);
        }
        self.lru.insert(0, blk);
        self.lru.truncate(self.cap);
        kind
    }
}

/// Runs `reqs` through a texture unit holding `tex`, the rasterizer presenting the next
/// request `interval` cycles after the previous one was taken (1: every cycle). `vcd`: trace
/// the run. What the run finds wrong with the unit (a hang, a broken handshake) fails it.
pub fn run_texread(
    tex: &Ccc,
    p: TexParams,
    reqs: &[TexRequest],
    interval: u32,
    vcd: Option<(PathBuf, TraceConfig)>,
) -> Result<TexRun, RunError> {
    let run = run_texread_checked(tex, p, reqs, interval, vcd, false)?;
    match run.findings.first() {
        Some(f) => Err(RunError::Failed(f.clone())),
        None => Ok(run),
    }
}

/// [`run_texread`], with the kernel's schedule and edge checks on every cycle when `check`;
/// what the run finds wrong with the unit is in [`TexRun::findings`], not an error.
pub fn run_texread_checked(
    tex: &Ccc,
    p: TexParams,
    reqs: &[TexRequest],
    interval: u32,
    vcd: Option<(PathBuf, TraceConfig)>,
    check: bool,
) -> Result<TexRun, RunError> {
    let unit = texread_unit(tex, p, reqs, interval).map_err(RunError::Input)?;
    // Traced at the unit's own clock, whatever the configuration's period.
    let work = Workload {
        wave: vcd.map(|(vcd, trace)| WaveOut {
            vcd,
            trace,
            period_ps: None,
        }),
    };
    let own_period_ps = u64::from(p.dram.cycle_ns) * 1000;
    // The integer reference beside the unit's output, and a flag where they differ.
    let (sim, probes) = work
        .sim(unit, "texread", own_period_ps, |t| {
            (
                t.probe_bits("rgb_reference", 24, Some("tb.texture_unit_602.out_rgb")),
                t.probe_bits("mismatch", 1, Some("tb.texture_unit_602.out_valid")),
            )
        })
        .map_err(RunError::Waveform)?;
    let probes = probes.map(|p| (tex, p));
    let (sim, run) = drive(sim.check_schedule(check), reqs, interval, probes)?;
    work.finish(sim).map_err(RunError::Waveform)?;
    Ok(run)
}

/// The unit holding `tex`, once the run's parameters and requests are found to fit it.
fn texread_unit(
    tex: &Ccc,
    p: TexParams,
    reqs: &[TexRequest],
    interval: u32,
) -> Result<TextureUnit, String> {
    if !(1..=1000).contains(&interval) {
        return Err(format!("rasterizer interval {interval}: 1..=1000 cycles"));
    }
    if (tex.width, tex.height) != (p.width, p.height) {
        return Err(format!(
            "texture is {}x{}, the unit is set up for {}x{}",
            tex.width, tex.height, p.width, p.height
        ));
    }
    p.validate()?;
    if let Some((i, r)) = reqs.iter().enumerate().find(|(_, r)| !p.in_range(r.u, r.v)) {
        return Err(format!(
            "request {i}: ({}, {}) outside the {}x{} texture",
            r.u, r.v, p.width, p.height
        ));
    }
    let words = tex.dram_words(&p.block_map());
    TextureUnit::new("texture_unit_602", p, &tex.clut, &words)
}

/// Reference probes of a traced run: the texture, the reference colour's and the mismatch
/// flag's probes.
pub type RefProbes<'a> = (&'a Ccc, (ProbeId, ProbeId));

/// Presents rasterizer requests (`in_valid`, `in_u`, `in_v`, `in_newline`); a request is
/// taken in a cycle with `in_ready` high.
pub fn drive_raster(dut: &mut TextureUnit, r: Option<&TexRequest>) {
    dut.in_valid.set_bool(r.is_some());
    if let Some(r) = r {
        dut.in_u.set_bits(u64::from(r.u));
        dut.in_v.set_bits(u64::from(r.v));
        dut.in_newline.set_bool(r.newline);
    }
}

/// The unit takes a request in a cycle with `in_ready` high.
pub fn raster_ready(dut: &TextureUnit) -> bool {
    dut.in_ready.is_high()
}

/// Collects the filtered colour of bilinear 622 when `out_valid` is high.
pub fn sample_color(dut: &TextureUnit) -> Option<u32> {
    dut.out_valid.is_high().then(|| dut.out_rgb.bits() as u32)
}

/// First-lookup outcomes and the shadow cache's miss split, sampled every cycle.
#[derive(Default)]
struct LookupLog {
    lookups: Vec<(u8, u8)>,
    shadow: Shadow,
    split: [u64; 3],
}

impl LookupLog {
    fn sample(&mut self, d: &TextureUnit) {
        if !d.lookup.first {
            return;
        }
        let lk = d.lookup;
        let hits = lk.hit[..lk.n].iter().filter(|&&h| h).count() as u8;
        self.lookups.push((lk.n as u8, hits));
        for k in 0..lk.n {
            if let Some(kind) = self.shadow.reference(lk.blocks[k], lk.hit[k]) {
                self.split[kind as usize] += 1;
            }
        }
    }
}

/// The unit's two valid/ready handshakes checked at the pins every cycle: the rasterizer's
/// request into the unit and fill engine 607's word request to the word controller (inside
/// the unit: results may match while it breaks the rules, see [`Handshake`]).
pub struct Handshakes {
    /// `(u, v, newline)`.
    raster: Handshake<(u64, u64, bool)>,
    /// The word address.
    words: Handshake,
}

/// Both handshakes, nothing sampled yet.
impl Default for Handshakes {
    fn default() -> Self {
        Handshakes {
            raster: Handshake::new("texture_unit_602.in_valid"),
            words: Handshake::new("texture_unit_602.control_607.req_valid"),
        }
    }
}

impl Handshakes {
    /// Samples both handshakes' pins in `cycle`.
    pub fn sample(&mut self, cycle: u64, d: &TextureUnit) {
        let req = (d.in_u.bits(), d.in_v.bits(), d.in_newline.is_high());
        let ready = d.in_ready.is_high();
        self.raster.sample(cycle, d.in_valid.is_high(), ready, req);
        let m = &d.mem;
        let valid = m.req_valid.is_high();
        self.words
            .sample(cycle, valid, m.ready.is_high(), m.req_addr.bits());
    }

    /// The first rule either handshake broke.
    pub fn check(&self) -> Result<(), String> {
        self.raster.check().and(self.words.check())
    }
}

/// Drives `reqs` into a unit already in `sim` (see [`run_texread`]); for testbenches that set
/// the simulator up themselves (e.g. with the schedule check on). With `probes`, each result's
/// integer reference and a mismatch flag are set on the tracer. What the run finds wrong with
/// the unit (a hang, a broken handshake) is in [`TexRun::findings`].
pub fn drive<T: Trace + ProbeSink>(
    mut sim: Sim<TextureUnit, T>,
    reqs: &[TexRequest],
    interval: u32,
    probes: Option<RefProbes>,
) -> Result<(Sim<TextureUnit, T>, TexRun), String> {
    sim.reset(1);
    let start = sim.cycle();
    let mut rgb = Vec::with_capacity(reqs.len());
    let mut out_cycles = Vec::with_capacity(reqs.len());
    let mut log = LookupLog {
        shadow: Shadow::new(4),
        ..LookupLog::default()
    };
    let (mut scanlines, mut sent) = (0u64, 0usize);
    let mut pins = Handshakes::default();
    // Worst case per request: four blocks, each two reads with a page fault, plus decode.
    let p = *sim.dut.params();
    let per_req = 4 * (2 * u64::from(p.dram.t_rp + p.dram.t_rcd + p.dram.t_cas + p.dram.t_cp) + 8);
    let limit = 100 + (per_req + u64::from(interval)) * (reqs.len() as u64 + 4);
    let mut spec = RunSpec::new(reqs.len() as u64, limit).pacing(Pacing::every(interval));
    let r = run(
        &mut sim,
        &mut PinDriver::new(drive_raster).ready(raster_ready),
        &mut PinMonitor::new(sample_color),
        reqs.iter().copied(),
        &mut spec,
        |sim, ev| match ev {
            Event::Sent { txn, .. } => {
                scanlines += u64::from(sent == 0 || txn.newline);
                sent += 1;
            }
            Event::Received { cycle, txn } => {
                if let (Some((tex, (pr, pm))), Some(t)) = (probes, sim.trace_mut()) {
                    let r = reqs[rgb.len()];
                    let want = reference_filter(tex, r.u, r.v, p.frac_bits);
                    t.bits(pr, u64::from(want));
                    t.flag(pm, want != txn);
                }
                rgb.push(txn);
                out_cycles.push(cycle - start);
            }
            Event::Settled { cycle } => {
                log.sample(&sim.dut);
                pins.sample(cycle, &sim.dut);
            }
        },
    )
    .map_err(|t| t.to_string());
    let cycles = sim.cycle() - start;
    let mut findings: Vec<String> = match r {
        Ok(_) => drain(&mut sim, &mut pins, start + limit)
            .err()
            .into_iter()
            .collect(),
        Err(t) => vec![t],
    };
    findings.extend(pins.check().err());
    let stats = read_stats(&sim.dut, interval, cycles, scanlines, log.split);
    Ok((
        sim,
        TexRun {
            rgb,
            out_cycles,
            lookups: log.lookups,
            stats,
            findings,
        },
    ))
}

/// Lets prefetches still in flight or queued finish, so the counts add up (a run's time ends
/// with its last result), by cycle `limit` at the latest.
pub fn drain<T: Trace>(
    sim: &mut Sim<TextureUnit, T>,
    pins: &mut Handshakes,
    limit: u64,
) -> Result<(), String> {
    while !sim.dut.idle() {
        sim.dut.in_valid.set_bool(false);
        sim.eval();
        pins.sample(sim.cycle(), &sim.dut);
        sim.tick();
        if sim.cycle() > limit {
            return Err(format!("watchdog: the unit not idle by cycle {limit}"));
        }
    }
    Ok(())
}

/// The statistics of a finished run from the unit's counters.
fn read_stats(
    d: &TextureUnit,
    interval: u32,
    cycles: u64,
    scanlines: u64,
    [cold, cap, conf]: [u64; 3],
) -> TexReadStats {
    let p = d.params();
    let s = d.stats();
    let ns = cycles * u64::from(p.dram.cycle_ns);
    TexReadStats {
        requests: s.requests,
        interval,
        cycles,
        cycle_ns: p.dram.cycle_ns,
        ns,
        pixels_per_second: s.requests as f64 / (ns.max(1) as f64 * 1e-9),
        layout: p.layout.name().into(),
        cache: p.cache,
        lookahead: if p.cache { p.lookahead.name() } else { "off" }.into(),
        page_words: p.dram.cols,
        block_refs: s.block_refs,
        hits: s.hits,
        hit_rate: s.hits as f64 / s.block_refs.max(1) as f64,
        misses: s.block_refs - s.hits,
        misses_cold: cold,
        misses_capacity: cap,
        misses_conflict: conf,
        demand_fills: s.demand_fills,
        prefetch_fills: s.prefetch_fills,
        prefetch_hits: s.prefetch_hits,
        late_prefetches: s.late_prefetches,
        prefetch_dropped: s.prefetch_dropped,
        stall_cycles: s.stall_cycles,
        dram_reads: d.mem.reads.q().bits(),
        page_hits: d.mem.page_hits.q().bits(),
        page_faults: d.mem.page_faults.q().bits(),
        scanlines,
        page_faults_per_scanline: d.mem.page_faults.q().bits() as f64 / scanlines.max(1) as f64,
        violations: d.mem.dram.violations(),
    }
}
