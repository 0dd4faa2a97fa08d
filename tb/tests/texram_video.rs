//! The video port 808 on the TEXRAM chip: the generator 816 writing its mipmaps
//! into the banks through the shift registers 826, beside the rasterizer.

use hdl::kernel::Sim;
use tb::texram::test_map;
use tb::texram_video::{video_chip, VideoConfig, VideoPortTb, VideoSource};
use units::mipmap::Scan;
use verif::Background;

/// The regress testbench over every configuration: each frame's mipmap in the banks equals
/// the reference, the rasterizer's results the stub's, slots and transfers add up.
#[test]
fn the_testbench_passes_and_covers_every_bin() {
    let opts = verif::RunOptions {
        count: Some(400),
        // Every cycle evaluated twice: the port's eval must not move state.
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&VideoPortTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?}", r.failures);
    assert_eq!(r.mismatches, 0);
    assert!(r.coverage_percent > 99.0, "{}", r.coverage_percent);
}

/// Video alone through a chip: clocks until every frame is ready or `limit` cycles.
fn video_only(
    c: &VideoConfig,
    frames: usize,
    limit: u64,
) -> (
    Sim<units::texram::texram_802::Texram802, hdl::kernel::NoTrace>,
    VideoSource,
) {
    video_only_watching(c, frames, limit, |_| {})
}

/// [`video_only`], showing `each` the chip in every cycle (settled, before the edge).
fn video_only_watching(
    c: &VideoConfig,
    frames: usize,
    limit: u64,
    each: impl FnMut(&units::texram::texram_802::Texram802),
) -> (
    Sim<units::texram::texram_802::Texram802, hdl::kernel::NoTrace>,
    VideoSource,
) {
    let mut stim = verif::seeded_stimulus("texram video");
    let level0 = test_map(32, 32, &mut stim);
    let (chip, _) = video_chip(c, &level0).unwrap();
    let frames: Vec<Vec<u8>> = (0..frames)
        .map(|_| test_map(c.width, c.height, &mut stim))
        .collect();
    let mut sim = Sim::new(chip);
    sim.reset(2);
    let src = clock_video_watching(&mut sim, c, &frames, limit, each);
    (sim, src)
}

/// `frames` from a new source into the chip until each is ready or the sim's cycle `limit`.
fn clock_video(
    sim: &mut Sim<units::texram::texram_802::Texram802, hdl::kernel::NoTrace>,
    c: &VideoConfig,
    frames: &[Vec<u8>],
    limit: u64,
) -> VideoSource {
    clock_video_watching(sim, c, frames, limit, |_| {})
}

/// [`clock_video`], showing `each` the chip in every cycle (settled, before the edge).
fn clock_video_watching(
    sim: &mut Sim<units::texram::texram_802::Texram802, hdl::kernel::NoTrace>,
    c: &VideoConfig,
    frames: &[Vec<u8>],
    limit: u64,
    mut each: impl FnMut(&units::texram::texram_802::Texram802),
) -> VideoSource {
    let mut src = VideoSource::new(c, frames);
    while sim.cycle() < limit && src.frames_checked() < frames.len() {
        src.drive(&mut sim.dut, 0);
        sim.eval();
        src.settled(&sim.dut, 0);
        each(&sim.dut);
        sim.tick();
    }
    src
}

/// Interlaced video with no line blanking: the partner line cannot be read before the next
/// line's first texel; the port flags an underrun (code 2) instead of adding stale texels.
#[test]
fn interlaced_video_without_blanking_underruns() {
    let c = VideoConfig::of(32, 8, Scan::InterlacedTop, 1, 0);
    let (sim, _) = video_only(&c, 1, 5_000);
    let v = sim.dut.video().unwrap();
    assert!(v.error.q().is_high());
    assert_eq!(v.err_code.q().bits(), 2);
    // With enough blanking the same video is fine.
    let c = VideoConfig::of(32, 8, Scan::InterlacedTop, 1, 30);
    let (sim, src) = video_only(&c, 1, 50_000);
    let v = sim.dut.video().unwrap();
    assert!(!v.error.q().is_high(), "code {}", v.err_code.q().bits());
    assert!(src.mismatches.is_empty(), "{:?}", src.mismatches);
    assert_eq!(src.frames_checked(), 1);
}

/// One row buffer for lines that make two segments: an overrun (code 1).
#[test]
fn too_few_row_buffers_overrun() {
    let mut c = VideoConfig::of(16, 4, Scan::Progressive, 1, 50);
    c.queue = 1;
    let (sim, _) = video_only(&c, 1, 5_000);
    let v = sim.dut.video().unwrap();
    assert!(v.error.q().is_high());
    assert_eq!(v.err_code.q().bits(), 1);
}

/// `queue` row buffers hold `queue` segments: video that needs exactly as many (the most a
/// run buffered, `max_buffered`) is clean, with one fewer it overruns (code 1).
#[test]
fn video_needing_exactly_the_row_buffers_there_are_does_not_overrun() {
    let mut c = VideoConfig::of(16, 4, Scan::Progressive, 1, 0);
    let (sim, _) = video_only(&c, 2, 50_000);
    let need = sim.dut.video().unwrap().max_buffered;
    assert!((2..32).contains(&need), "{need} buffered");
    for (queue, code) in [(need, 0), (need - 1, 1)] {
        c.queue = queue;
        let (sim, _) = video_only(&c, 2, 50_000);
        let v = sim.dut.video().unwrap();
        assert_eq!(v.max_buffered, need, "the same run");
        assert_eq!(v.err_code.q().bits(), code, "{queue} row buffers");
    }
}

/// Sections 11-12, "without slowing down the accesses of the rasterizer", cycle by cycle:
/// interlaced 1024 x 512 video at 25 frames a second (the largest power-of-two frame at least
/// 768 wide whose two frame buffers fit the chip; 2,559 row transfers a frame) written
/// while the rasterizer reads the last frame at full rate. Counted from the chip's page
/// registers and slots over one frame time (40 ms): under 1 % of its accesses lost.
#[test]
fn video_at_25_frames_a_second_costs_the_rasterizer_under_one_percent() {
    use units::texram::{Border, Drf};
    let c = tb::runs::texram_video::video_cost(1024, 512, 25).unwrap();
    eprintln!("{c:?}: {:.3} % of the accesses lost", 100.0 * c.lost());
    assert_eq!(c.error, 0);
    assert_eq!(c.frame_cycles, 8_000_000);
    let map = Drf::new(10, 9, Border::Wrap);
    let want = tb::texram_video::expected_transfers(Scan::InterlacedTop, [map, map], 1);
    assert_eq!(c.transfers, want);
    // A round writes or reads several banks at once: fewer slots than transfers.
    assert!(c.video_slots < c.transfers && c.video_slots * 3 > c.transfers);
    assert!(c.accesses_without > 1_300_000, "{}", c.accesses_without);
    assert!(c.lost() > 0.0 && c.lost() < 0.01, "{}", c.lost());
    // The rows the video opens make the rasterizer fault more often.
    assert!(c.fault_slots_with > c.fault_slots_without);
}

/// The video run's waveform: the port, the generator and the shift registers each a scope
/// under the chip, beside the chip's other units; the .gtkw view opens it.
#[test]
fn the_video_waveform_has_a_scope_per_unit() {
    let dir = std::env::temp_dir().join(format!("texrtl-video-{}", std::process::id()));
    let opts = verif::RunOptions {
        count: Some(50),
        ..verif::RunOptions::with_waves(&dir)
    };
    let r = verif::run_testbench(&VideoPortTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?}", r.failures);
    let vcd = dir.join("video_port_808.vcd");
    let rb = waves::check::read_vcd(&vcd).unwrap();
    for scope in [
        "texram_802.banks_810",
        "texram_802.page_registers_824",
        "texram_802.video_port_808",
        "texram_802.video_port_808.mipmap_gen_816.level1.fifo_1412",
        "texram_802.video_port_808.shift_registers_826",
    ] {
        let scope = format!("tb.{scope}.");
        assert!(
            rb.vars.keys().any(|n| n.starts_with(&scope)),
            "no scope {scope}"
        );
    }
    assert!(rb
        .vars
        .contains_key("tb.texram_802.video_port_808.shift_registers_826.video_slots"));
    waves::check::check_gtkw(&vcd, &rb).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Video one texel wide with a one-cycle line blanking: a frame time of 16 cycles. The banks,
/// taken each in its own order, have not finished frame 0 when frame 2 starts into the same
/// map; that is flagged (code 1) instead of frame 0 being reported ready holding frame 2's
/// texels. With four cycles of blanking the same video is fine.
#[test]
fn a_frame_overtaking_the_one_two_before_it_overruns() {
    // No blanking and every row buffer (two levels' lines then leave in one cycle) as well.
    let mut fast = VideoConfig::of(1, 8, Scan::Progressive, 1, 0);
    fast.queue = 64;
    for c in [VideoConfig::of(1, 8, Scan::Progressive, 1, 1), fast] {
        let (sim, src) = video_only(&c, 3, 5_000);
        let v = sim.dut.video().unwrap();
        assert!(v.error.q().is_high(), "{c:?}");
        assert_eq!(v.err_code.q().bits(), 1, "{c:?}");
        assert_eq!(src.frames_checked(), 3, "{c:?}");
    }
    let c = VideoConfig::of(1, 8, Scan::Progressive, 1, 4);
    let (sim, src) = video_only(&c, 3, 5_000);
    assert!(!sim.dut.video().unwrap().error.q().is_high());
    assert!(src.mismatches.is_empty(), "{:?}", src.mismatches);
    assert_eq!(src.frames_checked(), 3);
}

/// Interlaced video one texel wide, too little blanking for the partner reads: a line's read
/// is asked for while the last one's is still waiting. An underrun (code 2), and the reads
/// counted through to the end (no count wraps).
#[test]
fn overlapping_partner_reads_underrun() {
    for scan in [Scan::InterlacedTop, Scan::InterlacedBottom] {
        let c = VideoConfig::of(1, 8, scan, 1, 4);
        let (sim, src) = video_only(&c, 3, 5_000);
        let v = sim.dut.video().unwrap();
        assert!(v.error.q().is_high(), "{scan:?}");
        assert_eq!(v.err_code.q().bits(), 2, "{scan:?}");
        assert_eq!(src.frames_checked(), 3, "{scan:?}");
    }
}

/// A reset starts the record of ready frames again, as the generator numbers frames from 0
/// again: after three frames and a reset, video too fast for the banks is flagged as on a
/// fresh chip, and the frames then reported ready are the new ones.
#[test]
fn after_a_reset_a_frame_overtaking_still_overruns() {
    let slow = VideoConfig::of(1, 8, Scan::Progressive, 1, 4);
    let (mut sim, src) = video_only(&slow, 3, 5_000);
    assert_eq!(src.frames_checked(), 3);
    sim.reset(2);
    let fast = VideoConfig::of(1, 8, Scan::Progressive, 1, 1);
    let mut stim = verif::seeded_stimulus("texram video after reset");
    let frames: Vec<Vec<u8>> = (0..3).map(|_| test_map(1, 8, &mut stim)).collect();
    let src = clock_video(&mut sim, &fast, &frames, 20_000);
    assert_eq!(src.frames_checked(), 3);
    let v = sim.dut.video().unwrap();
    assert!(v.error.q().is_high());
    assert_eq!(v.err_code.q().bits(), 1);
}

/// A video round holds the banks for its slots: the cycles the bank stage serves the video
/// port (`vid_round` non-zero) are `slot_cycles` (6) times the slots counted, one slot a round,
/// two when a bank has another row open (so the first round after a reset takes two: every
/// row starts closed); progressive and interlaced.
#[test]
fn video_rounds_hold_the_banks_six_cycles_a_slot() {
    for (scan, frames) in [(Scan::Progressive, 2), (Scan::InterlacedTop, 1)] {
        let c = VideoConfig::of(32, 8, scan, 1, 30);
        let (mut serving, mut first_round) = (0u64, None);
        let (sim, src) = video_only_watching(&c, frames, 50_000, |chip| {
            serving += u64::from(chip.banks.vid_round.q().bits() != 0);
            // Slots are counted at the edge a round starts: the first count seen is its.
            let slots = chip.video().unwrap().slots.q().bits();
            if first_round.is_none() && slots > 0 {
                first_round = Some(slots);
            }
        });
        assert_eq!(src.frames_checked(), frames, "{scan:?}");
        assert_eq!(first_round, Some(2), "{scan:?}: every row starts closed");
        let v = sim.dut.video().unwrap();
        let slots = v.slots.q().bits();
        assert!(
            slots > v.transfers.q().bits() / 4,
            "{scan:?}: {slots} slots"
        );
        assert_eq!(serving, 6 * slots, "{scan:?}");
    }
}

/// Frame `f` is ready (`frames_ready`) at the edge its last segment, the top level's one
/// texel, is written into its map (DRF `f % 2`), and is stamped with the port's cycle (edges
/// since power-up, the reset's included), so: seen in the cycle after that edge, stamped with
/// it, the top texel now the frame's and in the cycle before still the map's old one. Frames
/// of one grey each (10, 60, 110, 160), so a top texel is known without a reference; 16 x 4
/// progressive with no blanking, so the next frame's rows are already buffered.
#[test]
fn a_frame_is_ready_at_the_edge_its_last_segment_is_written() {
    let c = VideoConfig::of(16, 4, Scan::Progressive, 1, 0);
    let grey = |f: usize| 10 + 50 * f as u8;
    let frames: Vec<Vec<u8>> = (0..4).map(|f| vec![grey(f); 64]).collect();
    let mut stim = verif::seeded_stimulus("texram video");
    let (chip, _) = video_chip(&c, &test_map(32, 32, &mut stim)).unwrap();
    let top = |chip: &units::texram::texram_802::Texram802, f: usize| {
        chip.read_level(f % 2, 4).unwrap()[0]
    };
    let mut sim = Sim::new(chip);
    sim.reset(2);
    for f in 0..2 {
        assert_ne!(
            top(&sim.dut, f),
            grey(f),
            "map {f} starts with another top texel"
        );
    }
    let (mut now, mut before, mut seen) = (2u64, None, Vec::new());
    let src = clock_video_watching(&mut sim, &c, &frames, 50_000, |chip| {
        let f = seen.len();
        let v = chip.video().unwrap();
        if let Some(&(ready, at)) = v.frames_ready.get(f) {
            seen.push((ready, at, now, before, top(chip, f)));
        }
        before = Some(top(chip, seen.len()));
        now += 1;
    });
    assert_eq!(src.frames_checked(), 4);
    for (f, &(ready, at, now, before, after)) in seen.iter().enumerate() {
        assert_eq!((ready, at), (f as u64, now), "frame {f}'s stamp");
        assert_eq!(after, grey(f), "frame {f} ready: its top texel written");
        assert_ne!(
            before,
            Some(grey(f)),
            "frame {f}: written in the cycle before"
        );
    }
}
