//! The testbench of the video port 808 on the TEXRAM chip: video frames enter the
//! chip's serial port while the rasterizer reads another map at the request port; the mipmap
//! generator 816 makes the upper levels and the shift registers 826 write every line into the
//! banks in slots taken from the rasterizer.
//!
//! Checked: each frame's mipmap, read back from the banks when the chip reports the frame
//! ready, equals the integer reference (`RefMipmap`, its own loops) level by level; the
//! rasterizer's results are the stub's (the video changes when they come, not what they are);
//! the slots add up (`slots = accesses + fault slots + video slots`); the transfers are the
//! row segments the frames' lines make; no video error (overrun, underrun, generator).

use crate::runs::mipmap::{video_stream, VideoTexel};
use crate::texram::{sample_tex, test_map, RefMipmap, TexDriver, TexOut, TexReq, CYCLE_PS};
use hdl::kernel::{Sim, Trace};
use proptest::prelude::*;
use units::mipmap::{MipmapParams, Rounding, Scan};
use units::texram::banks_810::{group_words, locate, ROW_WORDS};
use units::texram::stub::TexramStub;
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::video_port_808::VideoParams;
use units::texram::{Border, Drf, TexramAccess, TexramRequest};
use verif::{
    run_scored_beside, About, Background, Coverage, Coverpoint, Ctx, Pacing, PinMonitor, RunSpec,
    Scoreboard, Scored, Stimulus, TbResult, Testbench,
};

pub const NAME: &str = "video_port_808";

/// Frames per configuration: both frame buffers, then the first again.
const FRAMES: usize = 3;
/// The rasterizer's map (DRF 2): 32 x 32, stored after the two video maps.
const STATIC_LOG2: u32 = 5;

/// One configuration: the video's size and scan, the source's timing, the row buffers.
#[derive(Clone, Copy, Debug)]
pub struct VideoConfig {
    pub width: u32,
    pub height: u32,
    pub scan: Scan,
    /// Cycles per video texel, and blanking cycles after each line.
    pub period: u64,
    pub blank: u64,
    pub queue: usize,
}

const CONFIGS: [VideoConfig; 6] = [
    VideoConfig::of(32, 16, Scan::InterlacedTop, 2, 24),
    VideoConfig::of(32, 16, Scan::InterlacedBottom, 1, 40),
    VideoConfig::of(16, 16, Scan::Progressive, 3, 0),
    VideoConfig::of(64, 2, Scan::InterlacedTop, 1, 40),
    VideoConfig::of(1, 8, Scan::Progressive, 1, 4),
    VideoConfig::of(128, 64, Scan::InterlacedTop, 4, 64),
];

impl VideoConfig {
    pub const fn of(width: u32, height: u32, scan: Scan, period: u64, blank: u64) -> Self {
        VideoConfig {
            width,
            height,
            scan,
            period,
            blank,
            queue: 32,
        }
    }

    pub fn mipmap(&self) -> MipmapParams {
        MipmapParams {
            width: self.width,
            height: self.height,
            scan: self.scan,
            rounding: Rounding::Round,
        }
    }

    fn label(&self) -> String {
        let scan = match self.scan {
            Scan::Progressive => "progressive",
            Scan::InterlacedTop => "interlaced-top",
            Scan::InterlacedBottom => "interlaced-bottom",
        };
        format!(
            "{}x{} {scan}, a texel every {} cycles, {} blanking",
            self.width, self.height, self.period, self.blank
        )
    }
}

/// The chip with the video maps in DRFs 0 and 1 (one after the other in every bank), the
/// rasterizer's map in DRF 2 after them, and the video port set up for `c`.
pub fn video_chip(c: &VideoConfig, level0: &[u8]) -> Result<(Texram802, [Drf; 3]), String> {
    let (wl, hl) = (c.width.trailing_zeros(), c.height.trailing_zeros());
    let mut chip = Texram802::new(TexramParams::default())?;
    let mut at = (0, 0);
    let mut place = |mut d: Drf| {
        (d.base_even, d.base_odd) = at;
        at = (at.0 + group_words(&d, 0), at.1 + group_words(&d, 1));
        d
    };
    let video = [Drf::new(wl, hl, Border::Wrap); 2].map(&mut place);
    let stat = place(Drf::new(STATIC_LOG2, STATIC_LOG2, Border::Mirror));
    for (k, d) in video.into_iter().chain([stat]).enumerate() {
        chip.set_drf(k, d)?;
    }
    chip.load(2, level0)?;
    let mut p = VideoParams::new(c.mipmap());
    p.queue = c.queue;
    chip.attach_video(p)?;
    Ok((chip, [video[0], video[1], stat]))
}

/// The video source at port 808 and the checks of what it writes.
pub struct VideoSource {
    texels: Vec<VideoTexel>,
    width: usize,
    period: u64,
    blank: u64,
    next: usize,
    wait: u64,
    /// The frames' reference mipmaps, and how many were found in the banks so far.
    reference: Vec<RefMipmap>,
    checked: usize,
    pub mismatches: Vec<String>,
    last: (u64, u64),
    pub cov: Coverage,
    scan: i64,
}

impl VideoSource {
    pub fn new(c: &VideoConfig, frames: &[Vec<u8>]) -> VideoSource {
        VideoSource {
            texels: video_stream(&c.mipmap(), frames),
            width: c.width as usize,
            period: c.period.max(1),
            blank: c.blank,
            next: 0,
            wait: 0,
            reference: frames
                .iter()
                .map(|f| RefMipmap::build(c.width, c.height, f))
                .collect(),
            checked: 0,
            mismatches: Vec::new(),
            last: (0, 0),
            cov: coverage_model(),
            scan: c.scan as i64,
        }
    }

    /// Every texel went in.
    pub fn done(&self) -> bool {
        self.next == self.texels.len()
    }

    /// Frames found complete and checked in the banks.
    pub fn frames_checked(&self) -> usize {
        self.checked
    }

    /// A frame reported ready: its levels in the banks against the reference.
    fn check_frame(&mut self, chip: &Texram802, f: u64) {
        let drf = (f % 2) as usize;
        let Some(want) = self.reference.get(f as usize) else {
            self.mismatches
                .push(format!("frame {f} reported, never sent"));
            return;
        };
        for (k, level) in want.levels.iter().enumerate() {
            match chip.read_level(drf, k as u32) {
                Ok(got) if &got == level => {}
                Ok(got) => {
                    let at = got.iter().zip(level).position(|(a, b)| a != b);
                    self.mismatches
                        .push(format!("frame {f} level {k}: texel {at:?} differs"));
                }
                Err(e) => self.mismatches.push(e),
            }
        }
        self.cov.sample(&[self.scan, drf as i64, -1, -1]);
    }
}

impl Background<Texram802> for VideoSource {
    fn drive(&mut self, dut: &mut Texram802, _cycle: u64) {
        let Some(port) = dut.video_mut() else {
            return;
        };
        let now = self.wait == 0 && self.next < self.texels.len();
        port.valid.set_bool(now);
        if now {
            let t = self.texels[self.next];
            port.texel.set_bits(u64::from(t.texel));
            port.sof.set_bool(t.sof);
            self.next += 1;
            let line_end = self.next.is_multiple_of(self.width);
            self.wait = self.period - 1 + if line_end { self.blank } else { 0 };
        } else {
            self.wait = self.wait.saturating_sub(1);
        }
    }

    fn settled(&mut self, dut: &Texram802, _cycle: u64) {
        let Some(v) = dut.video() else {
            return;
        };
        while let Some(&(f, _)) = v.frames_ready.get(self.checked) {
            self.checked += 1;
            self.check_frame(dut, f);
        }
        // A bank round started at the last edge: its segments and slots.
        let now = (v.transfers.q().bits(), v.slots.q().bits());
        if now.0 != self.last.0 {
            let segments = (now.0 - self.last.0) as i64;
            let slots = (now.1 - self.last.1) as i64;
            self.cov.sample(&[self.scan, -1, segments, slots]);
        }
        self.last = now;
    }
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    c.add(
        Coverpoint::new("scan")
            .value("progressive", Scan::Progressive as i64)
            .value("interlaced_top", Scan::InterlacedTop as i64)
            .value("interlaced_bottom", Scan::InterlacedBottom as i64),
    );
    c.add(Coverpoint::new("frame_ready_in").values(&["drf0", "drf1"]));
    c.add(
        Coverpoint::new("segments_per_round")
            .value("1", 1)
            .value("2", 2)
            .bin("3..8", 3, 8),
    );
    c.add(
        Coverpoint::new("round_slots")
            .value("hit", 1)
            .value("fault", 2),
    );
    c
}

/// The row segments (transfers) `frames` frames make, frame f in the map of `maps[f % 2]`:
/// per line of every level one for each bank and row its texels are in, and per
/// second-field line (interlaced) the partner line's.
pub fn expected_transfers(scan: Scan, maps: [Drf; 2], frames: u64) -> u64 {
    let segments = |d: &Drf, k: u32, y: u32| {
        let (w, _) = d.level_size(k);
        let mut rows: Vec<(usize, u32)> = (0..w)
            .map(|x| {
                let (b, word) = locate(d, k, x, y);
                (b, word / ROW_WORDS)
            })
            .collect();
        rows.sort_unstable();
        rows.dedup();
        rows.len() as u64
    };
    let per_frame = |d: &Drf| {
        let mut n = 0;
        for k in 0..=d.max_level() {
            n += (0..d.level_size(k).1)
                .map(|y| segments(d, k, y))
                .sum::<u64>();
        }
        if scan != Scan::Progressive {
            // The partner of each second-field line is a first-field line: half the lines.
            let (first, h) = (u32::from(scan == Scan::InterlacedBottom), d.level_size(0).1);
            n += (first..h)
                .step_by(2)
                .map(|y| segments(d, 0, y))
                .sum::<u64>();
        }
        n
    };
    (0..frames)
        .map(|f| per_frame(&maps[(f % 2) as usize]))
        .sum()
}

/// Random requests to the rasterizer's map, over it and beyond its edges.
fn requests(n: usize, stim: &mut Stimulus) -> Vec<TexReq> {
    let side = (1i32 << STATIC_LOG2) << 8;
    let s = (-300..side + 300, -300..side + 300, -256..6 * 256).prop_map(|(u, v, lambda)| TexReq {
        u,
        v,
        lambda,
    });
    stim.draw_n(&s, n)
}

pub struct VideoPortTb;

impl Testbench for VideoPortTb {
    fn about(&self) -> About {
        About::new(NAME, "TEXRAM video port 808, mipmap generator 816 on the banks, shift registers 826 (sections 11-12)")
            .count(2000, "rasterizer requests beside the video")
    }
    fn configurations(&self) -> Vec<String> {
        CONFIGS.iter().map(VideoConfig::label).collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let c = CONFIGS[ctx.index];
        let mut stim = Stimulus::new(ctx.seed);
        let side = 1 << STATIC_LOG2;
        let level0 = test_map(side, side, &mut stim);
        let (chip, maps) = video_chip(&c, &level0)?;
        let frames: Vec<Vec<u8>> = (0..FRAMES)
            .map(|_| test_map(c.width, c.height, &mut stim))
            .collect();
        let (sim, _) = ctx.sim(chip, &format!("{NAME} {}", ctx.label), CYCLE_PS, |_| ())?;
        let mut stub = TexramStub::new();
        stub.set_drf(2, maps[2])?;
        stub.load(2, &level0)?;
        let reqs = requests(ctx.count, &mut stim);
        let (sim, mut res) = run_video(sim, ctx, (&c, [maps[0], maps[1]]), &frames, stub, reqs)?;
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}

/// Drives the requests and the video, then clocks until every frame is ready; scores both.
fn run_video<T: Trace>(
    mut sim: Sim<Texram802, T>,
    ctx: &Ctx,
    (c, maps): (&VideoConfig, [Drf; 2]),
    frames: &[Vec<u8>],
    mut stub: TexramStub,
    reqs: Vec<TexReq>,
) -> Result<(Sim<Texram802, T>, TbResult), String> {
    let mut res = TbResult::new(NAME, "");
    sim.reset(2);
    let mut source = VideoSource::new(c, frames);
    let n = reqs.len() as u64;
    let mut sb: Scoreboard<TexOut, TexOut> = Scoreboard::new(|e: &TexOut, a: &TexOut| {
        // The fault flag is the video's doing (it opens rows); the values are the map's.
        if (e.value, e.rgba, e.texels) == (a.value, a.rgba, a.texels) {
            Ok(())
        } else {
            Err(format!("got {a:?}, want {e:?}"))
        }
    });
    let video_cycles = source.texels.len() as u64 * (c.period + c.blank);
    let pacing = Pacing::random(300, ctx.seed.derive(3));
    let mut spec = RunSpec::new(n, 40 * n + 2 * video_cycles + 10_000).pacing(pacing);
    let r = run_scored_beside(
        &mut sim,
        &mut TexDriver { drf: 2 },
        &mut PinMonitor::new(sample_tex),
        reqs,
        &mut spec,
        &mut source,
        |_, ev| match ev {
            Scored::Sent { txn, .. } => sb.expect(stub_result(&mut stub, txn)),
            Scored::Received { cycle, txn } => {
                sb.observe(cycle, txn);
            }
        },
    );
    res.ran(&r);
    // The rest of the video, with the request port idle.
    let limit = sim.cycle() + 2 * video_cycles + 10_000;
    while (!source.done() || source.frames_checked() < frames.len()) && sim.cycle() < limit {
        source.drive(&mut sim.dut, 0);
        sim.eval();
        let cycle = sim.cycle();
        source.settled(&sim.dut, cycle);
        sim.tick();
    }
    res.score(&sb);
    settle(&mut res, &sim.dut, &source, (c, maps), frames.len());
    res.coverage = Some(std::mem::replace(&mut source.cov, coverage_model()));
    Ok((sim, res))
}

/// The stub's result for a request to the rasterizer's map (DRF 2).
fn stub_result(stub: &mut TexramStub, q: &TexReq) -> TexOut {
    let r = stub
        .access(TexramRequest {
            drf: 2,
            u: q.u,
            v: q.v,
            lambda: q.lambda,
        })
        .expect("requests are inside the limits");
    TexOut {
        value: r.value,
        rgba: r.rgba,
        texels: r.texels,
        fault: r.faults > 0,
    }
}

/// The checks after the run: frames, errors, slots and transfers adding up.
fn settle(
    res: &mut TbResult,
    chip: &Texram802,
    source: &VideoSource,
    (c, maps): (&VideoConfig, [Drf; 2]),
    n: usize,
) {
    let v = chip.video().expect("video set up");
    res.failures.extend(source.mismatches.iter().cloned());
    if source.frames_checked() != n {
        res.failures
            .push(format!("{} of {n} frames ready", source.frames_checked()));
    }
    for (what, code) in [
        ("video port", v.err_code.q().bits() * v.error.q().bits()),
        ("generator 816", v.gen.err_code.bits() * v.gen.error.bits()),
    ] {
        if code != 0 {
            res.failures.push(format!("{what}: error code {code}"));
        }
    }
    let (slots, video) = (chip.slots.q().bits(), v.slots.q().bits());
    let raster = chip.accesses.q().bits() + chip.fault_slots.q().bits();
    if slots != raster + video {
        res.failures.push(format!(
            "{slots} slots: {raster} of the rasterizer and {video} of the video"
        ));
    }
    let transfers = v.transfers.q().bits();
    let want = expected_transfers(c.scan, maps, n as u64);
    if transfers != want {
        res.failures.push(format!(
            "{transfers} transfers, the frames' lines make {want}"
        ));
    }
    res.notes.push(format!(
        "{}: {n} frames, {transfers} row transfers in {video} slots beside {} rasterizer accesses",
        c.label(),
        chip.accesses.q().bits()
    ));
}
