//! What video costs the rasterizer: the video port 808 writing interlaced frames into the
//! TEXRAM chip 802 while the rasterizer reads at full rate, measured cycle by cycle on the
//! chip (the video port's table in the report).

use crate::texram::{test_map, CYCLE_PS};
use crate::texram_video::{video_chip, VideoConfig, VideoSource};
use hdl::kernel::Sim;
use units::mipmap::Scan;
use units::texram::texram_802::Texram802;
use verif::{Background, Stimulus};

/// What video at a frame rate costs the rasterizer, measured on the chip over one frame time.
#[derive(Clone, Debug, PartialEq)]
pub struct VideoCost {
    pub width: u32,
    pub height: u32,
    pub frames_per_second: u32,
    /// Cycles of one frame time (5 ns each), and the source's timing in them.
    pub frame_cycles: u64,
    pub period: u64,
    pub blank: u64,
    /// Row transfers and the slots they took.
    pub transfers: u64,
    pub video_slots: u64,
    /// Rasterizer accesses finished in the frame time, with and without the video, and the
    /// slots their page faults added.
    pub accesses_with: u64,
    pub accesses_without: u64,
    pub fault_slots_with: u64,
    pub fault_slots_without: u64,
    pub max_buffered: usize,
    pub error: u64,
}

impl VideoCost {
    /// The rasterizer's accesses lost to the video, as a fraction.
    pub fn lost(&self) -> f64 {
        1.0 - self.accesses_with as f64 / self.accesses_without as f64
    }
}

/// Interlaced `w x h` video at `fps` frames a second (the source's texels spread over 80 % of
/// each line time, the rest line blanking) written into DRF 0 while the rasterizer reads the
/// last frame's map (DRF 1) at full rate along a span: the rasterizer's accesses in one frame
/// time with the video and without, cycle by cycle on the chip.
pub fn video_cost(w: u32, h: u32, fps: u32) -> Result<VideoCost, String> {
    let frame_cycles = 1_000_000_000_000 / (CYCLE_PS * u64::from(fps));
    let line = frame_cycles / u64::from(h);
    let period = (line * 4 / 5 / u64::from(w)).max(1);
    let blank = line.saturating_sub(period * u64::from(w));
    let c = VideoConfig {
        queue: 32,
        ..VideoConfig::of(w, h, Scan::InterlacedTop, period, blank)
    };
    let mut stim = Stimulus::new(verif::Seed(0x25));
    let frame = test_map(w, h, &mut stim);
    let count = |video: bool| -> Result<(Texram802, u64), String> {
        let (mut chip, _) = video_chip(&c, &test_map(32, 32, &mut Stimulus::new(verif::Seed(1))))?;
        chip.load(1, &frame)?;
        let mut sim = Sim::new(chip);
        sim.reset(2);
        let frames = if video {
            vec![frame.clone()]
        } else {
            Vec::new()
        };
        let mut src = VideoSource::new(&c, &frames);
        let (mut k, mut done) = (0i32, 0);
        while sim.cycle() < frame_cycles {
            let d = &mut sim.dut;
            d.req_valid.set_bool(true);
            d.req_drf.set_bits(1);
            d.req_u.set_raw(i64::from(((k % 400) << 8) + 128));
            d.req_v.set_raw(300 << 8 | 128);
            d.req_lambda.set_raw(64);
            src.drive(&mut sim.dut, 0);
            sim.eval();
            k += i32::from(sim.dut.req_ready.is_high());
            done += u64::from(sim.dut.output.out_valid.q().is_high());
            sim.tick();
        }
        Ok((sim.dut, done))
    };
    let (with, accesses_with) = count(true)?;
    let (without, accesses_without) = count(false)?;
    let v = with.video().expect("video set up");
    Ok(VideoCost {
        width: w,
        height: h,
        frames_per_second: fps,
        frame_cycles,
        period,
        blank,
        transfers: v.transfers.q().bits(),
        video_slots: v.slots.q().bits(),
        accesses_with,
        accesses_without,
        fault_slots_with: with.fault_slots.q().bits(),
        fault_slots_without: without.fault_slots.q().bits(),
        max_buffered: v.max_buffered,
        error: v.err_code.q().bits() * v.error.q().bits(),
    })
}
