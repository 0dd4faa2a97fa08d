//! The mipmap generator of FIG. 14: bit-identical to the integer reference in every scan order
//! and rounding, sizes down to one texel, FIFOs within their depths, one texel per clock with
//! frames back to back, errors reported; and the `texrtl mipmap` command.

use hdl::kernel::Sim;
use tb::mipmap::{reference, synthetic_video};
use tb::runs::mipmap::{drive_video, run_mipmap, video_stream};
use units::mipmap::{MipmapGen, MipmapParams, Rounding, Scan};
use verif::{seeded_stimulus, Seed};

const SCANS: [Scan; 3] = [
    Scan::Progressive,
    Scan::InterlacedTop,
    Scan::InterlacedBottom,
];

#[test]
fn every_scan_order_gives_the_reference_bit_for_bit() {
    let mut stim = seeded_stimulus("mipmap sizes");
    let mut sizes: Vec<(u32, u32)> = vec![
        (1, 1),
        (1, 2),
        (2, 1),
        (2, 2),
        (4, 1),
        (1, 8),
        (8, 2),
        (32, 16),
        (16, 64),
    ];
    for _ in 0..6 {
        let (a, b) = stim.draw(&(0u32..8, 1u32..8));
        sizes.push((1 << a, 1 << b));
    }
    for (w, h) in sizes {
        let frames = synthetic_video(w, h, 3, Seed(u64::from(w * 131 + h)));
        for rounding in [Rounding::Round, Rounding::Truncate] {
            let mut results = Vec::new();
            for scan in SCANS {
                if h < 2 && scan != Scan::Progressive {
                    continue;
                }
                let p = MipmapParams {
                    width: w,
                    height: h,
                    scan,
                    rounding,
                };
                let o = run_mipmap(p, &frames, None).unwrap();
                assert_eq!(o.error, 0, "{w}x{h} {scan:?}");
                for (f, frame) in frames.iter().enumerate() {
                    assert_eq!(
                        o.frames[f],
                        reference(frame, w, h, rounding),
                        "{w}x{h} {scan:?} {rounding:?} frame {f}"
                    );
                }
                let s = &o.stats;
                assert_eq!(s.texels_per_clock, 1.0, "back to back, one texel per clock");
                for (k, (&m, &d)) in s.fifo_max_occupancy.iter().zip(&s.fifo_depth).enumerate() {
                    assert!(m <= d, "{w}x{h} level {}: occupancy {m} > depth {d}", k + 1);
                    // Depths halve from level to level: half a level-0 line at level 1.
                    assert_eq!(d as u32, (w >> (k + 1)).max(1));
                }
                assert!(s.latency_after_last_texel <= p.levels().len() as u64 + 2);
                results.push(o.frames);
            }
            assert!(
                results.windows(2).all(|p| p[0] == p[1]),
                "scan order changed a bit at {w}x{h}"
            );
        }
    }
}

#[test]
fn sync_errors_are_reported() {
    let p = MipmapParams {
        width: 4,
        height: 4,
        scan: Scan::InterlacedTop,
        rounding: Rounding::Round,
    };
    let mut sim = Sim::new(MipmapGen::new("mipmap_gen_816", p).unwrap()).check_schedule(true);
    sim.reset(1);
    for k in 0..6 {
        sim.dut.valid.set_bool(true);
        sim.dut.sof.set_bool(k == 3); // sof in the middle of a line
        sim.dut.texel.set_bits(k);
        sim.step();
    }
    sim.eval();
    assert!(sim.dut.error.is_high());
    assert_eq!(sim.dut.err_code.bits(), 3);
}

#[test]
fn sizes_are_checked() {
    // Powers of two in 1..=1024 on either side; interlaced video needs two lines.
    for (w, h, scan, ok) in [
        (3, 4, Scan::Progressive, false),
        (4, 2048, Scan::Progressive, false),
        (8, 1, Scan::InterlacedTop, false),
        (0, 4, Scan::Progressive, false),
        (1, 1, Scan::Progressive, true),
        (1024, 1, Scan::Progressive, true),
        (1, 1024, Scan::Progressive, true),
        (8, 2, Scan::InterlacedBottom, true),
    ] {
        let p = MipmapParams {
            width: w,
            height: h,
            scan,
            rounding: Rounding::Round,
        };
        assert_eq!(p.validate().is_ok(), ok, "{w}x{h}");
        assert_eq!(MipmapGen::new("m", p).is_ok(), ok, "{w}x{h}");
    }
}

/// A reset 16 x 8 generator in `scan`, and two frames of video for it.
fn generator_16x8(scan: Scan, seed: Seed) -> (MipmapParams, Vec<Vec<u8>>, Sim<MipmapGen>) {
    let p = MipmapParams {
        width: 16,
        height: 8,
        scan,
        rounding: Rounding::Round,
    };
    let mut sim = Sim::new(MipmapGen::new("mipmap_gen_816", p).unwrap());
    sim.reset(1);
    (p, synthetic_video(16, 8, 2, seed), sim)
}

/// The skipped evaluation is exact: whenever the generator leaves an upper level
/// unevaluated (nothing arriving, the level `quiescent`), evaluating it would have changed
/// nothing, ports, registers' next values or store alike; and it is the common case (most
/// of an upper level's cycles), as its documentation says.
#[test]
fn a_quiescent_level_is_left_exactly_as_evaluating_it_would_leave_it() {
    let (p, frames, mut sim) = generator_16x8(Scan::InterlacedTop, Seed(11));
    let stream = video_stream(&p, &frames);
    let (mut skipped, mut checked) = (0usize, 0usize);
    for (i, t) in stream.iter().map(Some).chain([None; 64]).enumerate() {
        drive_video(&mut sim.dut, t);
        sim.eval();
        let levels = &sim.dut.levels;
        for k in 1..levels.len() {
            checked += 1;
            if levels[k - 1].out_valid.is_high() || !levels[k].quiescent() {
                continue;
            }
            skipped += 1;
            let mut now = levels[k].clone();
            now.in_valid.follow(&levels[k - 1].out_valid);
            now.in_texel.follow(&levels[k - 1].out_texel);
            let mut evaluated = now.clone();
            evaluated.eval();
            assert_eq!(
                format!("{evaluated:?}"),
                format!("{now:?}"),
                "level {k}, cycle {i}"
            );
        }
        sim.tick();
    }
    assert!(sim.dut.err_code.bits() == 0);
    assert!(2 * skipped > checked, "{skipped} of {checked}");
}

/// A reset restores every level whatever it was doing: a generator left idle part way into
/// its second frame (each level's line and frame counters mid-way), then reset, gives the
/// frames a fresh one gives.
#[test]
fn a_reset_part_way_restores_every_level() {
    let (p, frames, mut sim) = generator_16x8(Scan::Progressive, Seed(12));
    let fresh = run_mipmap(p, &frames, None).unwrap();
    for t in &video_stream(&p, &frames)[..128 + 40] {
        drive_video(&mut sim.dut, Some(t));
        sim.step();
    }
    drive_video(&mut sim.dut, None);
    for _ in 0..50 {
        sim.step();
    }
    let again = tb::runs::mipmap::run_mipmap_on(sim, &frames).unwrap();
    assert_eq!(again.frames, fresh.frames);
    assert_eq!(again.error, 0);
}

/// The rows each page register 824 of the generator's own frame store opens, in order: the
/// row it holds after each cycle whose access left the row it had open (never two a bank in
/// a cycle), with the activation count they make. On the way: each frame completes once,
/// recorded with its edge's cycle, and no error is flagged.
fn opened_rows(p: MipmapParams, frames: &[Vec<u8>]) -> [Vec<u32>; 3] {
    let mut sim = Sim::new(MipmapGen::new("mipmap_gen_816", p).unwrap());
    sim.reset(1);
    let mut rows: [Vec<u32>; 3] = Default::default();
    for t in video_stream(&p, frames).iter().map(Some).chain([None; 256]) {
        drive_video(&mut sim.dut, t);
        let (before, done) = (sim.dut.activations(), sim.dut.completed().len());
        sim.step();
        // A frame completes at this edge: recorded with the edge's cycle.
        if sim.dut.completed().len() > done {
            assert_eq!(sim.dut.completed()[done].1, sim.cycle());
        }
        for (b, r) in rows.iter_mut().enumerate() {
            let n = sim.dut.activations()[b] - before[b];
            assert!(n <= 1, "bank {b}: {n} rows opened in a cycle");
            if n == 1 {
                r.push(sim.dut.open_row(b).expect("a row opened") as u32);
            }
        }
    }
    assert_eq!(
        sim.dut.activations(),
        rows.each_ref().map(|r| r.len() as u64)
    );
    assert_eq!(sim.dut.completed().len(), frames.len());
    // Clean video: no error flagged, with or without a code.
    assert!(!sim.dut.error.is_high() && sim.dut.err_code.bits() == 0);
    rows
}

/// The page registers 824: level-0 line y is written into bank y % 2, row y / 2 (every
/// texel of a line into one row, consecutive lines into different ones, so each line opens
/// its row), and interlaced (top field first), before each line 2r + 1 of the second field,
/// its partner 2r is read back from bank 0, row r. Level k's line r goes to bank 2, row
/// (k - 1) * 1024 + r, in the order the levels finish them.
#[test]
fn the_page_registers_open_the_rows_the_lines_are_in() {
    for (w, h) in [(8u32, 8u32), (16, 4), (4, 16), (32, 16)] {
        let frames = synthetic_video(w, h, 3, Seed(7));
        let per_bank: Vec<u32> = (0..h / 2).collect();
        let levels = w.max(h).trailing_zeros();
        let mut bank2: Vec<u32> = (0..levels)
            .flat_map(|k| (0..(h >> (k + 1)).max(1)).map(move |r| k << 10 | r))
            .collect();
        bank2 = bank2.repeat(frames.len());
        bank2.sort_unstable();
        for scan in [Scan::Progressive, Scan::InterlacedTop] {
            let p = MipmapParams {
                width: w,
                height: h,
                scan,
                rounding: Rounding::Round,
            };
            let mut got = opened_rows(p, &frames);
            let reads = usize::from(scan != Scan::Progressive);
            assert_eq!(
                got[0],
                per_bank.repeat((1 + reads) * frames.len()),
                "{w}x{h} {scan:?}"
            );
            assert_eq!(got[1], per_bank.repeat(frames.len()), "{w}x{h} {scan:?}");
            got[2].sort_unstable();
            assert_eq!(got[2], bank2, "{w}x{h} {scan:?}");
        }
    }
}
