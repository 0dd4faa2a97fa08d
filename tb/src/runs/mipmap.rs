//! `texrtl mipmap` (and the mipmap testbench, the regression vectors and the report's
//! picture): video frames through the real-time mipmap generator 816 at one texel a clock,
//! back to back, `sof` with each frame's first texel; each frame's mipmap read from the
//! generator's frame store when it reports the frame complete, with the run's timing and FIFO
//! statistics.

use crate::mipmap::NAME;
use crate::RunError;
use hdl::kernel::{Sim, Trace};
use serde::Serialize;
use std::path::PathBuf;
use units::mipmap::{FrameBuffer, MipmapGen, MipmapParams, Scan};
use verif::{run_scored, Monitor, PinDriver, RunSpec, Scored, Workload};
use waves::TraceConfig;

/// What a run measured.
#[derive(Clone, Debug, Serialize)]
pub struct MipmapStats {
    pub cycles: u64,
    /// Cycles from the last level-0 texel of the last frame to its complete mipmap.
    pub latency_after_last_texel: u64,
    /// Per level (1..), the larger of FIFO 1408's and FIFO 1412's high-water mark.
    pub fifo_max_occupancy: Vec<usize>,
    pub fifo1408_max: Vec<usize>,
    pub fifo1412_max: Vec<usize>,
    /// Per level (1..), the FIFOs' declared depth.
    pub fifo_depth: Vec<usize>,
    pub texels: u64,
    /// Level-0 texels per clock over the input phase.
    pub texels_per_clock: f64,
    pub page_activations: [u64; 3],
}

/// A run's results.
pub struct MipmapOutcome {
    /// Every frame's levels, in frame order.
    pub frames: Vec<FrameBuffer>,
    pub stats: MipmapStats,
    /// Error code of the generator (0: none).
    pub error: u64,
    /// What the run found wrong with the generator: it hung (a frame never completed), or
    /// it reported a frame twice and another never. `frames` is then empty.
    pub findings: Vec<String>,
}

/// Drives `frames` through the generator; what the run finds wrong with it (a hang, a frame
/// reported twice) fails the run.
pub fn run_mipmap(
    p: MipmapParams,
    frames: &[Vec<u8>],
    vcd: Option<(PathBuf, TraceConfig)>,
) -> Result<MipmapOutcome, RunError> {
    let o = run_mipmap_checked(p, frames, vcd, false)?;
    match o.findings.first() {
        Some(f) => Err(RunError::Failed(f.clone())),
        None => Ok(o),
    }
}

/// The frames through a generator in whatever state `sim` left it (reset first, as every
/// run is).
pub fn run_mipmap_on(sim: Sim<MipmapGen>, frames: &[Vec<u8>]) -> Result<MipmapOutcome, String> {
    drive(sim, frames).map(|(_, o)| o)
}

/// [`run_mipmap`], with the kernel's schedule and edge checks on every cycle when `check`;
/// what the run finds wrong with the generator is in [`MipmapOutcome::findings`], not an error.
pub fn run_mipmap_checked(
    p: MipmapParams,
    frames: &[Vec<u8>],
    vcd: Option<(PathBuf, TraceConfig)>,
    check: bool,
) -> Result<MipmapOutcome, RunError> {
    let dut = MipmapGen::new("mipmap_gen_816", p).map_err(RunError::Input)?;
    let n = (p.width * p.height) as usize;
    if let Some(k) = frames.iter().position(|f| f.len() != n) {
        return Err(RunError::Input(format!(
            "frame {k} has {} texels, {}x{} needs {n}",
            frames[k].len(),
            p.width,
            p.height
        )));
    }
    let work = Workload::traced(vcd);
    let (sim, _) = work.sim(dut, NAME, 0, |_| ()).map_err(RunError::Waveform)?;
    let (sim, o) = drive(sim.check_schedule(check), frames)?;
    work.finish(sim).map_err(RunError::Waveform)?;
    Ok(o)
}

/// One level-0 texel of the video stream, with its start-of-frame flag.
#[derive(Clone, Copy, Debug)]
pub struct VideoTexel {
    pub sof: bool,
    pub texel: u8,
}

/// Drives the video port (`valid`, `sof`, `texel`); the generator takes a texel every cycle.
pub fn drive_video(dut: &mut MipmapGen, t: Option<&VideoTexel>) {
    dut.valid.set_bool(t.is_some());
    dut.sof.set_bool(t.is_some_and(|t| t.sof));
    dut.texel.set_bits(u64::from(t.map_or(0, |t| t.texel)));
}

/// Reports each completed frame (`frame_done`) with its mipmap, read from the frame store.
pub struct FrameMonitor {
    seen: usize,
}

impl Monitor<MipmapGen> for FrameMonitor {
    type Txn = (u64, FrameBuffer);
    fn sample(&mut self, dut: &MipmapGen) -> Option<(u64, FrameBuffer)> {
        let &(f, _) = dut.completed().get(self.seen)?;
        self.seen += 1;
        Some((f, dut.frame_buffer(f).clone()))
    }
}

/// The texels of `frames` in the order the video port delivers them (lines in scan order).
pub fn video_stream(p: &MipmapParams, frames: &[Vec<u8>]) -> Vec<VideoTexel> {
    let (w, h) = (p.width as usize, p.height as usize);
    let order: Vec<usize> = match p.scan {
        Scan::Progressive => (0..h).collect(),
        Scan::InterlacedTop => (0..h).step_by(2).chain((1..h).step_by(2)).collect(),
        Scan::InterlacedBottom => (1..h).step_by(2).chain((0..h).step_by(2)).collect(),
    };
    let mut v = Vec::with_capacity(frames.len() * w * h);
    for frame in frames {
        for (li, &y) in order.iter().enumerate() {
            for x in 0..w {
                v.push(VideoTexel {
                    sof: li == 0 && x == 0,
                    texel: frame[y * w + x],
                });
            }
        }
    }
    v
}

fn drive<T: Trace>(
    mut sim: Sim<MipmapGen, T>,
    frames: &[Vec<u8>],
) -> Result<(Sim<MipmapGen, T>, MipmapOutcome), String> {
    sim.reset(2);
    let start = sim.cycle();
    let p = *sim.dut.params();
    let stream = video_stream(&p, frames);
    let texels = stream.len() as u64;
    let mut out: Vec<Option<FrameBuffer>> = vec![None; frames.len()];
    let mut last_texel = start;
    let limit = texels + 64 + 4 * u64::from(p.width) + 8;
    let mut spec = RunSpec::new(frames.len() as u64, limit);
    let ran = run_scored(
        &mut sim,
        &mut PinDriver::new(drive_video),
        &mut FrameMonitor { seen: 0 },
        stream,
        &mut spec,
        |_, ev| match ev {
            Scored::Sent { cycle, .. } => last_texel = cycle + 1,
            Scored::Received { txn: (f, buf), .. } => {
                if let Some(slot) = out.get_mut(f as usize) {
                    *slot = Some(buf);
                }
            }
        },
    )
    .map_err(|t| format!("mipmap incomplete: {t}"));
    sim.eval();
    let error = sim.dut.err_code.bits();
    let done_cycle = sim
        .dut
        .completed()
        .last()
        .map(|c| c.1)
        .unwrap_or(last_texel);
    let r = &sim.dut.levels;
    let m1408: Vec<usize> = r.iter().map(|r| r.fifo_1408.max_occupancy()).collect();
    let m1412: Vec<usize> = r.iter().map(|r| r.fifo_1412.max_occupancy()).collect();
    let stats = MipmapStats {
        cycles: sim.cycle() - start,
        latency_after_last_texel: done_cycle.saturating_sub(last_texel),
        fifo_max_occupancy: m1408.iter().zip(&m1412).map(|(a, b)| *a.max(b)).collect(),
        fifo1408_max: m1408,
        fifo1412_max: m1412,
        fifo_depth: r.iter().map(|r| r.fifo_1408.depth()).collect(),
        texels,
        texels_per_clock: texels as f64 / (last_texel - start) as f64,
        page_activations: sim.dut.activations(),
    };
    let mut findings: Vec<String> = ran.err().into_iter().collect();
    let frames = match out.into_iter().collect::<Option<Vec<_>>>() {
        Some(f) if findings.is_empty() => f,
        Some(_) => Vec::new(),
        None => {
            if findings.is_empty() {
                findings.push("a frame was reported twice and another never".into());
            }
            Vec::new()
        }
    };
    Ok((
        sim,
        MipmapOutcome {
            frames,
            stats,
            error,
            findings,
        },
    ))
}
