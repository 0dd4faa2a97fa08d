//! The texture memory path (Schilling & Knittel, Figures 4-7): random textures and requests
//! through texture unit 602 in every mode and layout, bit-identical and equal to the integer
//! reference and within half an LSB of the golden model; the cache's timing; the document's
//! CCC format; and `texrtl ccc` / `texrtl texread`, bad input included.

use formats::ccc::Ccc;
use hdl::kernel::Sim;
use proptest::prelude::*;
use tb::runs::texture::{drain, drive, drive_raster, run_texread, Handshakes, TexRequest};
use tb::texture::reference_filter;
use units::texmem::bilinear_622::lerp2;
use units::texmem::cache_614::Lookahead;
use units::texmem::ccc_decode_608::CccBlock;
use units::texmem::layout::Layout;
use units::texmem::texture_unit_602::{TexParams, TextureUnit};
use verif::Handshake;

fn modes() -> Vec<(Layout, bool, Lookahead, u32)> {
    let mut v = Vec::new();
    for layout in [Layout::RowMajor, Layout::Tiled] {
        for (cache, look) in [
            (true, Lookahead::Quadrant),
            (true, Lookahead::Direction),
            (true, Lookahead::Off),
            (false, Lookahead::Off),
        ] {
            for interval in [1, 3] {
                v.push((layout, cache, look, interval));
            }
        }
    }
    v
}

fn random_texture() -> impl Strategy<Value = Ccc> {
    (1u32..=6, 1u32..=6).prop_flat_map(|(bw, bh)| {
        (
            prop::collection::vec(0u32..=0xff_ffff, 256),
            prop::collection::vec((any::<u8>(), any::<u8>(), any::<u16>()), (bw * bh) as usize),
        )
            .prop_map(move |(clut, blocks)| Ccc {
                width: 4 * bw,
                height: 4 * bh,
                clut,
                blocks: blocks
                    .into_iter()
                    .map(|(a, b, bits)| CccBlock { a, b, bits })
                    .collect(),
            })
    })
}

#[test]
fn every_mode_is_bit_identical_and_equals_the_reference() {
    let mut runner = verif::seeded_runner("texture_modes", 48);
    let strat = (
        random_texture(),
        prop::collection::vec((0.0f64..1.0, 0.0f64..1.0, prop::bool::weighted(0.1)), 1..60),
        1u32..=6,
    );
    runner
        .run(&strat, |(tex, pts, frac)| {
            let one = 1u32 << frac;
            let reqs: Vec<TexRequest> = pts
                .iter()
                .map(|&(x, y, nl)| TexRequest {
                    u: ((x * f64::from(tex.width * one)) as u32).min(tex.width * one - 1),
                    v: ((y * f64::from(tex.height * one)) as u32).min(tex.height * one - 1),
                    newline: nl,
                })
                .collect();
            let want: Vec<u32> = reqs
                .iter()
                .map(|r| reference_filter(&tex, r.u, r.v, frac))
                .collect();
            for (layout, cache, look, interval) in modes() {
                let mut p = TexParams::new(tex.width, tex.height);
                p.layout = layout;
                p.cache = cache;
                p.lookahead = look;
                p.frac_bits = frac;
                // Small pages, so page faults and tiles happen on small textures.
                p.dram.cols = 16;
                p.dram.rows = 64;
                let unit = TextureUnit::new("t", p, &tex.clut, &tex.dram_words(&p.block_map()))
                    .map_err(TestCaseError::fail)?;
                let sim = Sim::new(unit).check_schedule(true);
                let (_, run) = drive(sim, &reqs, interval, None).map_err(TestCaseError::fail)?;
                prop_assert!(run.findings.is_empty(), "{:?}", run.findings);
                prop_assert_eq!(
                    &run.rgb,
                    &want,
                    "{:?} cache {} lookahead {}",
                    layout,
                    cache,
                    look.name()
                );
                let s = &run.stats;
                prop_assert_eq!(s.violations, 0);
                prop_assert_eq!(s.dram_reads, 2 * (s.demand_fills + s.prefetch_fills));
                prop_assert_eq!(
                    s.misses,
                    s.misses_cold + s.misses_capacity + s.misses_conflict
                );
                if !cache {
                    prop_assert_eq!(s.demand_fills, s.block_refs);
                }
                // Golden: f64 bilinear of the decoded texture, at most half an LSB away.
                for (r, &got) in reqs.iter().zip(&run.rgb) {
                    let g = golden::texture::bilinear(
                        |x, y| {
                            let c = tex.texel(x, y);
                            [16, 8, 0].map(|s| f64::from(c >> s & 0xff))
                        },
                        tex.width,
                        tex.height,
                        f64::from(r.u) / f64::from(one),
                        f64::from(r.v) / f64::from(one),
                    );
                    for (c, sh) in [16, 8, 0].into_iter().enumerate() {
                        let e = (f64::from(got >> sh & 0xff) - g[c]).abs();
                        prop_assert!(e <= golden::texture::ERROR_BOUND_LSB, "error {} LSB", e);
                    }
                }
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn bilinear_622_arithmetic_exhaustive_over_weights() {
    // Every weight pair for F = 1..=6 with extreme and middle channel values: the two-lerp
    // datapath equals the four-weight sum rounded half up.
    let vals = [0u32, 1, 127, 128, 254, 255];
    for f in 1..=6u32 {
        let w = 1u64 << f;
        for fu in 0..w {
            for fv in 0..w {
                for &a in &vals {
                    for &b in &vals {
                        for &c in &vals {
                            for &d in &vals {
                                let s = u64::from(a) * (w - fu) * (w - fv)
                                    + u64::from(b) * fu * (w - fv)
                                    + u64::from(c) * (w - fu) * fv
                                    + u64::from(d) * fu * fv;
                                let want = (s + (1 << (2 * f - 1))) >> (2 * f);
                                assert_eq!(
                                    u64::from(lerp2(a, b, c, d, fu as u32, fv as u32, f)),
                                    want
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

fn cycles(tex: &Ccc, p: TexParams, pts: &[(u32, u32)]) -> tb::runs::texture::TexRun {
    let reqs: Vec<TexRequest> = pts
        .iter()
        .map(|&(x, y)| TexRequest {
            u: x << p.frac_bits,
            v: y << p.frac_bits,
            newline: false,
        })
        .collect();
    run_texread(tex, p, &reqs, 1, None).unwrap()
}

#[test]
fn miss_penalty_hit_throughput_and_page_faults() {
    // 256x256, row-major, 512-word pages: a page holds 4 block rows (16 texel rows).
    let tex = tb::texture::test_pattern(256, 256);
    let mut p = TexParams::new(256, 256);
    p.lookahead = Lookahead::Off;
    let one = cycles(&tex, p, &[(1, 1)]).stats.cycles;
    // Cold start, cycle by cycle: request taken (1), lookup misses (1), 607 takes word 0 (1),
    // page fault t_rp + t_rcd (6), CAS# low t_cas (3), CAS# high t_cp (3, word 1 taken in its
    // last cycle), CAS# low (3), CLUT a and b (2), lookup hits (1), extract 618 (1), the
    // result out of 622 (1): 23 cycles.
    assert_eq!(one, 23);
    // Hits stream at one request per cycle.
    let many = cycles(&tex, p, &[(1, 1); 50]).stats.cycles;
    assert_eq!(many, one + 49);
    // A second block in the open page: its request enters stage 0 the cycle after the first
    // one's hit, misses (1), 607 takes word 0 (1), t_cas + t_cp + t_cas (9), CLUT (2), lookup,
    // extract, result (3): 14 cycles after the first result.
    let two = cycles(&tex, p, &[(1, 1), (9, 1)]).stats;
    assert_eq!(two.cycles, one + 14);
    assert_eq!((two.page_faults, two.page_hits), (1, 3));
    // A block in another page adds the page fault's 6 cycles.
    let far = cycles(&tex, p, &[(1, 1), (1, 20)]).stats;
    assert_eq!(far.cycles, one + 14 + 6);
    assert_eq!((far.page_faults, far.page_hits), (2, 2));
    // Four blocks (a footprint across a block corner) cost four fills, one after the other:
    // each further fill is the lookup that misses, word 0 taken, 9 cycles of reads, 2 of
    // CLUT = 13 cycles. (Block (1, 0) is in the same page; blocks (0, 1), (1, 1) too.)
    let corner = cycles(&tex, p, &[(3, 3)]).stats;
    assert_eq!(corner.demand_fills, 4);
    assert_eq!(corner.cycles, one + 3 * 13);
}

#[test]
fn lookahead_preloads_the_quadrant_neighbours_when_the_dram_is_idle() {
    let tex = tb::texture::test_pattern(64, 64);
    let mut p = TexParams::new(64, 64);
    // A point in the lower-right quadrant of block (2, 2), offered once every 80 cycles so the
    // DRAM goes idle; then points in the three neighbours, each in the quadrant facing the
    // others (so their own lookahead finds everything present): all hits thanks to the
    // first request's prefetch.
    let reqs = [(10, 10), (13, 10), (10, 13), (13, 13)];
    let run = |p: TexParams| {
        let r: Vec<TexRequest> = reqs
            .iter()
            .map(|&(x, y)| TexRequest {
                u: x << 4,
                v: y << 4,
                newline: false,
            })
            .collect();
        run_texread(&tex, p, &r, 80, None).unwrap().stats
    };
    let with = run(p);
    assert_eq!(with.demand_fills, 1);
    assert_eq!(with.prefetch_fills, 3);
    assert_eq!(with.hits, 3);
    assert_eq!(with.prefetch_hits, 3);
    assert_eq!(
        with.prefetch_dropped, 9,
        "later requests' neighbours were all present"
    );
    p.lookahead = Lookahead::Off;
    let without = run(p);
    assert_eq!((without.prefetch_fills, without.hits), (0, 0));
    assert_eq!(without.demand_fills, 4);
}

#[test]
fn direction_lookahead_preloads_ahead_of_the_motion() {
    // A scanline moving right through block row 2, one request every 40 cycles: with the
    // direction lookahead every block after the first is preloaded (one block ahead, from the
    // second point on); with the quadrant lookahead too, but it also preloads the row above
    // (the points are in the top half of their blocks), which the scanline never uses.
    let tex = tb::texture::test_pattern(64, 64);
    let reqs: Vec<TexRequest> = (0..12u32)
        .map(|i| TexRequest {
            u: (1 + 2 * i) << 4,
            v: 9 << 4,
            newline: i == 0,
        })
        .collect();
    let mut p = TexParams::new(64, 64);
    p.lookahead = Lookahead::Direction;
    let d = run_texread(&tex, p, &reqs, 40, None).unwrap().stats;
    // Blocks 0..=5 of row 2 (x up to 24, footprint to 24); the first two are demand fills:
    // block 0 (cold) and block 1 (the second point, x = 3, is the first with a direction and
    // already needs block 1).
    assert_eq!(d.demand_fills, 2, "{d:?}");
    assert_eq!(d.prefetch_fills, 5, "{d:?}");
    p.lookahead = Lookahead::Quadrant;
    let q = run_texread(&tex, p, &reqs, 40, None).unwrap().stats;
    assert!(q.prefetch_fills > d.prefetch_fills, "{q:?}");
    p.lookahead = Lookahead::Off;
    let o = run_texread(&tex, p, &reqs, 40, None).unwrap().stats;
    assert_eq!(o.demand_fills, 7);
}

#[test]
fn a_newline_request_does_not_prefetch() {
    let tex = tb::texture::test_pattern(64, 64);
    let p = TexParams::new(64, 64);
    let r = [TexRequest {
        u: 10 << 4,
        v: 10 << 4,
        newline: true,
    }];
    let s = run_texread(&tex, p, &r, 1, None).unwrap().stats;
    assert_eq!(s.prefetch_fills, 0);
    let r = [TexRequest {
        newline: false,
        ..r[0]
    }];
    let s = run_texread(&tex, p, &r, 1, None).unwrap().stats;
    assert_eq!(s.prefetch_fills, 3);
}

#[test]
fn the_shadow_cache_splits_misses() {
    use tb::runs::texture::{MissKind, Shadow};
    let mut s = Shadow::new(4);
    assert_eq!(s.reference((0, 0), false), Some(MissKind::Cold));
    assert_eq!(s.reference((2, 0), false), Some(MissKind::Cold));
    // (0, 0) is still in the fully-associative cache: a conflict miss of the real one.
    assert_eq!(s.reference((0, 0), false), Some(MissKind::Conflict));
    for b in 1..=4 {
        s.reference((b, 7), false);
    }
    // Four other blocks since: evicted from the shadow too, a capacity miss.
    assert_eq!(s.reference((2, 0), false), Some(MissKind::Capacity));
    assert_eq!(s.reference((2, 0), true), None);
}

#[test]
fn textures_that_do_not_fit_are_refused() {
    let mut p = TexParams::new(4096, 4096);
    assert!(p.validate().unwrap_err().contains("needs DRAM words"));
    p.dram = units::texmem::dram_604::DramParams::one_meg();
    assert!(p.validate().is_err(), "4096^2 needs 2M words");
    let p = TexParams::new(2048, 1024);
    assert!(
        p.validate().is_ok(),
        "2M texels in 256K x 16 (the document's figure)"
    );
    assert!(TexParams::new(6, 8).validate().is_err());
    assert!(TexParams::new(0, 8).validate().is_err());
    // Sides: multiples of 4 in 4..=4096 (12 coordinate bits); frac_bits 1..=8.
    for (w, h, ok) in [
        (4, 4, true),
        (4096, 4, true),
        (4, 4096, true),
        (4100, 4, false),
    ] {
        assert_eq!(TexParams::new(w, h).validate().is_ok(), ok, "{w}x{h}");
    }
    assert!(TexParams::new(8, 4100)
        .validate()
        .unwrap_err()
        .contains("height 4100"));
    for (f, ok) in [(0, false), (1, true), (8, true), (9, false)] {
        let p = TexParams {
            frac_bits: f,
            ..TexParams::new(8, 8)
        };
        assert_eq!(p.validate().is_ok(), ok, "frac_bits {f}");
    }
}

// ---- the command line ----

#[test]
fn ccc_is_lossless_on_two_colour_blocks_from_few_colours() {
    // Every block holds at most two colours out of a palette of at most 256: the split
    // separates them exactly, median cut gives every colour its own entry, so decoding gives
    // the image back bit for bit; and the file round-trips.
    let mut runner = verif::seeded_runner("ccc_lossless", 32);
    let strat = (1u32..=5, 1u32..=5).prop_flat_map(|(bw, bh)| {
        (
            prop::collection::vec(any::<[u8; 3]>(), 1..=40),
            prop::collection::vec((any::<u8>(), any::<u8>(), any::<u16>()), (bw * bh) as usize),
            Just((bw, bh)),
        )
    });
    runner
        .run(&strat, |(palette, blocks, (bw, bh))| {
            let (w, h) = (4 * bw, 4 * bh);
            let mut px = vec![0u8; (3 * w * h) as usize];
            for (n, &(a, b, bits)) in blocks.iter().enumerate() {
                let (bx, by) = (n as u32 % bw, n as u32 / bw);
                for j in 0..16u32 {
                    let c = if bits >> j & 1 == 1 { b } else { a };
                    let c = palette[usize::from(c) % palette.len()];
                    let (x, y) = (4 * bx + j % 4, 4 * by + j / 4);
                    let k = (3 * (y * w + x)) as usize;
                    px[k..k + 3].copy_from_slice(&c);
                }
            }
            let img = formats::netpbm::Ppm {
                width: w,
                height: h,
                maxval: 255,
                pixels: px,
            };
            let c = formats::ccc::encode(&img).map_err(TestCaseError::fail)?;
            prop_assert_eq!(&c.decode(), &img.pixels);
            prop_assert_eq!(&Ccc::parse(&c.to_bytes()).map_err(TestCaseError::fail)?, &c);
            Ok(())
        })
        .unwrap();
}

/// Misses of a scanline trace on a 64x16 texture: `u` from `u0` in steps of `du` (texel
/// units, either sign), or `v` likewise when `vertical`, one request every 64 cycles (the
/// DRAM is idle between requests, so every lookahead fill arrives in time).
fn scan_misses(look: Lookahead, vertical: bool) -> (u64, u64) {
    let (w, h) = (64, 16);
    let tex = tb::texture::test_pattern(w, h);
    let mut p = TexParams::new(w, h);
    p.lookahead = look;
    // Leftward: u = 15.75, 15.5, ..., 4.0 at v = 1; upward: v = 15.75 ... 4.0 at u = 1.
    let reqs: Vec<TexRequest> = (0..48u32)
        .map(|k| {
            let along = (63 - k) * 4; // 15.75 down to 4.0 in uQ12.4
            let (u, v) = if vertical { (16, along) } else { (along, 16) };
            TexRequest {
                u,
                v,
                newline: k == 0,
            }
        })
        .collect();
    let s = run_texread(&tex, p, &reqs, 64, None).unwrap().stats;
    (s.misses, s.prefetch_fills)
}

/// A defect once found: on leftward or upward scanlines the direction lookahead preloaded
/// block bx-1 into the entry of bx+1 (same parity) while the footprint still spanned bx and
/// bx+1, so it missed more often than no lookahead at all. A preload never evicts a block the
/// current footprint uses: direction lookahead now misses less than none, never more.
#[test]
fn direction_lookahead_never_evicts_a_block_of_the_footprint() {
    for vertical in [false, true] {
        let (off, _) = scan_misses(Lookahead::Off, vertical);
        let (dir, fills) = scan_misses(Lookahead::Direction, vertical);
        let (quad, _) = scan_misses(Lookahead::Quadrant, vertical);
        assert!(
            fills > 0,
            "vertical {vertical}: direction lookahead preloads"
        );
        assert!(
            dir < off,
            "vertical {vertical}: direction lookahead {dir} misses, none {off}"
        );
        assert!(
            quad <= off,
            "vertical {vertical}: quadrant {quad}, none {off}"
        );
    }
}

/// The direction lookahead at the texture's last texel column (row): the footprint is clamped
/// there, as stage 0 reads it, so it holds one block across; moving left (up) the block two
/// before the edge block is preloaded, since it shares no entry with the footprint (a
/// footprint taken one texel past the edge would share one and drop it). Moving right (down)
/// nothing lies beyond the edge to preload.
#[test]
fn direction_lookahead_at_the_last_texel_preloads_back_from_the_edge() {
    let tex = tb::texture::test_pattern(64, 64);
    let mut p = TexParams::new(64, 64);
    p.lookahead = Lookahead::Direction;
    // Two points in texel 63 (x or y), the second 8/16 further left (up) or right (down);
    // the other coordinate in block 2.
    let fills = |vertical: bool, back: bool| {
        let (a, b) = if back {
            (63 * 16 + 12, 63 * 16 + 4)
        } else {
            (63 * 16 + 4, 63 * 16 + 12)
        };
        let r: Vec<TexRequest> = [(a, true), (b, false)]
            .iter()
            .map(|&(s, newline)| {
                let (u, v) = if vertical { (9 << 4, s) } else { (s, 9 << 4) };
                TexRequest { u, v, newline }
            })
            .collect();
        let s = run_texread(&tex, p, &r, 40, None).unwrap().stats;
        (s.demand_fills, s.prefetch_fills)
    };
    for vertical in [false, true] {
        assert_eq!(fills(vertical, true), (1, 1), "vertical {vertical}, back");
        assert_eq!(fills(vertical, false), (1, 0), "vertical {vertical}, on");
    }
}

/// The request for texel point `(x, y)` (no fraction) of a 4-fraction-bit unit.
fn point(x: u32, y: u32, newline: bool) -> TexRequest {
    TexRequest {
        u: x << 4,
        v: y << 4,
        newline,
    }
}

/// A texture unit holding `tex`, just out of reset, clocked by hand (requests presented with
/// [`drive_raster`]).
fn unit_after_reset(tex: &Ccc, p: TexParams) -> Sim<TextureUnit> {
    let words = tex.dram_words(&p.block_map());
    let unit = TextureUnit::new("texture_unit_602", p, &tex.clut, &words).unwrap();
    let mut sim = Sim::new(unit);
    sim.reset(1);
    sim
}

/// Fill engine 607 over one demand fill, cycle by cycle at its ports: the states the waveform
/// shows, in order (DECODE while 610/612 decode the block into cache 614), and its word
/// requests to the word controller: two a fill, each held until the controller takes it
/// (`word_req` with `word_ready`), none raised and then withdrawn.
#[test]
fn a_fill_asks_for_two_words_then_decodes() {
    let tex = tb::texture::test_pattern(64, 64);
    let p = TexParams::new(64, 64);
    let mut sim = unit_after_reset(&tex, p);
    let (mut states, mut taken) = (Vec::new(), Vec::new());
    let mut words = Handshake::new("fill.word_req");
    for c in 0..200u64 {
        // One request inside block (2, 2), a new scanline (so no lookahead follows).
        drive_raster(&mut sim.dut, (c == 0).then_some(&point(10, 10, true)));
        sim.eval();
        let f = &sim.dut.fill;
        assert!(c > 0 || sim.dut.in_ready.is_high(), "the request is taken");
        let st = f.state.q().bits();
        if states.last() != Some(&st) {
            states.push(st);
        }
        let (req, addr) = (f.word_req.is_high(), f.word_addr.bits());
        if words.sample(c, req, f.word_ready.is_high(), addr) {
            taken.push(addr);
        }
        sim.tick();
    }
    assert_eq!(words.check(), Ok(()), "each request held until taken");
    assert_eq!(states, [0, 1, 2, 0], "IDLE, FETCH, DECODE, IDLE");
    let first = p.block_map().block_addr(2, 2);
    assert_eq!(taken, [first, first + 1]);
}

/// The statistics of five small runs, by hand. A cold fill (page fault) takes 19 cycles: a
/// page-mode fill's 13 (the miss penalty above) and the fault's t_rp + t_rcd = 6.
/// - No lookahead, one point twice: one demand fill, the second lookup a hit but no prefetch
///   hit; the first request stalls the 19 cycles.
/// - Quadrant lookahead, the next point (every cycle) in the block being prefetched: a late
///   prefetch, and a stall of 19 and then the 12 cycles left of that fill.
/// - Quadrant, the next point a new scanline hitting the same block: it completes at once and
///   its candidates (none, a new scanline's) replace the queue, so only the candidate taken
///   as the first request completed is fetched.
/// - Direction lookahead, a first point with no newline: no direction yet, no prefetch.
/// - Quadrant lookahead with the cache off: nothing is offered to the queue.
#[test]
fn small_runs_count_fills_hits_late_prefetches_and_stalls() {
    let tex = tb::texture::test_pattern(64, 64);
    let run = |look: Lookahead, cache: bool, pts: &[(u32, u32, bool)], interval: u32| {
        let mut p = TexParams::new(64, 64);
        p.lookahead = look;
        p.cache = cache;
        let r: Vec<TexRequest> = pts.iter().map(|&(x, y, nl)| point(x, y, nl)).collect();
        let s = run_texread(&tex, p, &r, interval, None).unwrap().stats;
        let counts = (s.demand_fills, s.prefetch_fills, s.hits, s.prefetch_hits);
        (counts, s.late_prefetches, s.stall_cycles)
    };
    let (a, b) = ((10, 10, false), (13, 10, false));
    let off = run(Lookahead::Off, true, &[a, a], 80);
    assert_eq!(off, ((1, 0, 1, 0), 0, 19));
    let late = run(Lookahead::Quadrant, true, &[a, b], 1);
    assert_eq!(late, ((1, 3, 0, 0), 1, 31));
    let flushed = run(Lookahead::Quadrant, true, &[a, (9, 9, true)], 1);
    assert_eq!(flushed, ((1, 1, 1, 0), 0, 19));
    let first = run(Lookahead::Direction, true, &[a], 1);
    assert_eq!(first, ((1, 0, 0, 0), 0, 19));
    let uncached = run(Lookahead::Quadrant, false, &[a], 1);
    assert_eq!(uncached.0 .1, 0, "no prefetch without the cache");
}

/// The lookup monitor's masks (`need_mask`, `hit_mask`, one bit per cache entry): a cold
/// footprint across four blocks needs all four entries and hits none; the same point again
/// needs and hits all four.
#[test]
fn the_lookup_masks_show_the_entries_a_footprint_needs_and_hits() {
    let tex = tb::texture::test_pattern(64, 64);
    let p = TexParams::new(64, 64);
    let mut sim = unit_after_reset(&tex, p);
    let mut firsts = Vec::new();
    for c in 0..200u64 {
        let offer = c == 0 || c == 100;
        drive_raster(&mut sim.dut, offer.then_some(&point(3, 3, true)));
        sim.eval();
        let d = &sim.dut;
        if d.lookup.first {
            firsts.push((d.need_mask.bits(), d.hit_mask.bits()));
        }
        sim.tick();
    }
    assert_eq!(firsts, [(0b1111, 0), (0b1111, 0b1111)]);
}

/// A new scanline's first lookup flushes the lookahead queue: the cycle after it no candidate
/// of the previous scanline is left (the queue's `mask` register, shown in the waveform), and
/// none starts a prefetch in it. The second request either hits the first's block or misses
/// far away; its arrival is swept so that some arrivals meet candidates still queued and the
/// fill engine busy (no demand fill can start, so only the newline flushes) or free.
#[test]
fn a_new_scanline_flushes_the_queue() {
    let tex = tb::texture::test_pattern(64, 64);
    let p = TexParams::new(64, 64);
    let (mut busy, mut free) = (0, 0);
    for (second, k) in [9u32, 40]
        .into_iter()
        .flat_map(|x| (1..80u64).map(move |k| (x, k)))
    {
        let mut sim = unit_after_reset(&tex, p);
        // (10, 10) on a scanline, then from cycle k (second, second), a new scanline.
        let (mut sent, mut flushed_at) = (0, None);
        for c in 0..300u64 {
            let offer = (sent == 0) || (sent == 1 && c >= k);
            let next = [point(10, 10, false), point(second, second, true)];
            drive_raster(&mut sim.dut, next.get(sent).filter(|_| offer));
            sim.eval();
            let d = &sim.dut;
            if offer && d.in_ready.is_high() {
                sent += 1;
            }
            if flushed_at == Some(c) {
                let left = d.queue.mask.q().bits();
                assert_eq!(left, 0, "({second}, {k}) cycle {c}: candidates left");
            }
            if d.lookup.first && d.req_newline.q().is_high() {
                if d.queue.mask.q().bits() != 0 {
                    *(if d.fill.is_idle() {
                        &mut free
                    } else {
                        &mut busy
                    }) += 1;
                }
                let prefetch = d.fill.start.is_high() && d.fill.start_prefetch.is_high();
                assert!(!prefetch, "({second}, {k}) cycle {c}: a prefetch started");
                flushed_at = Some(c + 1);
            }
            sim.tick();
        }
        assert_eq!(sent, 2);
    }
    assert!(
        busy > 0 && free > 0,
        "arrivals with candidates queued: {busy} busy, {free} free"
    );
}

#[test]
fn reference_filter_hits_texels_at_integers() {
    let px = (0..64u32)
        .flat_map(|i| [(i % 8 * 30) as u8, (i / 8 * 30) as u8, 7])
        .collect();
    let p = formats::netpbm::Ppm {
        width: 8,
        height: 8,
        maxval: 255,
        pixels: px,
    };
    let c = formats::ccc::encode(&p).unwrap();
    for (x, y) in [(0, 0), (3, 5), (7, 7)] {
        assert_eq!(reference_filter(&c, x << 4, y << 4, 4), c.texel(x, y));
    }
}

/// A first request misses the cold cache: the unit is busy for its fill, and the
/// watchdog says so when its limit comes first, and lets it finish otherwise.
#[test]
fn the_watchdog_fires_only_past_its_limit() {
    let (_, tex) = tb::texture::fixture().unwrap();
    let p = TexParams::new(tex.width, tex.height);
    let words = tex.dram_words(&p.block_map());
    let mut sim = Sim::new(TextureUnit::new("t", p, &tex.clut, &words).unwrap());
    sim.reset(1);
    let first = TexRequest {
        u: 0,
        v: 0,
        newline: true,
    };
    drive_raster(&mut sim.dut, Some(&first));
    sim.step();
    let (mut pins, now) = (Handshakes::default(), sim.cycle());
    let said = drain(&mut sim, &mut pins, now).unwrap_err();
    assert_eq!(said, format!("watchdog: the unit not idle by cycle {now}"));
    drain(&mut sim, &mut pins, now + 1000).unwrap();
    assert!(sim.dut.idle());
    pins.check().unwrap();
}
