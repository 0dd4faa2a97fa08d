//! Testbench of the real-time mipmap generator (`hdl::mipmap`, Schilling & Knittel section 12,
//! Figure 14) and the machinery of `texrtl mipmap`.
//!
//! Video goes in at one texel per clock, frames back to back with no idle cycle, `sof` with
//! each frame's first texel. Each frame's mipmap (read from the generator's frame store when it
//! reports the frame complete) is compared level by level with an integer reference, a plain
//! loop over the whole frame that shares nothing with the hardware's structure, and with the
//! real-valued block averages of `golden::mipmap` against the analytic bound.

use crate::report::TbResult;
use hdl::kernel::{NoTrace, Sim, Trace};
use hdl::mipmap::{FrameBuffer, MipmapGen, MipmapParams, Rounding, Scan};
use serde::Serialize;
use std::path::PathBuf;
use verif::{Coverage, Coverpoint, ErrorStats, Scoreboard, Seed, Stimulus};
use waves::{TraceConfig, VcdTracer};

/// The integer reference: every level from the one before, `(a+b+c+d+2)>>2` (or `>>2`), pairs
/// once a side is 1.
pub fn reference(frame: &[u8], w: u32, h: u32, r: Rounding) -> FrameBuffer {
    let mut levels = vec![frame.to_vec()];
    let (mut w, mut h) = (w as usize, h as usize);
    while w > 1 || h > 1 {
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let prev = levels.last().unwrap();
        let mut next = Vec::with_capacity(nw * nh);
        for y in 0..nh {
            for x in 0..nw {
                let xs: &[usize] = if w > 1 { &[2 * x, 2 * x + 1] } else { &[x] };
                let ys: &[usize] = if h > 1 { &[2 * y, 2 * y + 1] } else { &[y] };
                let mut s = 0u32;
                for &yy in ys {
                    for &xx in xs {
                        s += u32::from(prev[yy * w + xx]);
                    }
                }
                let n = (xs.len() * ys.len()) as u32;
                next.push(match r {
                    Rounding::Round => ((s + n / 2) / n) as u8,
                    Rounding::Truncate => (s / n) as u8,
                });
            }
        }
        levels.push(next);
        w = nw;
        h = nh;
    }
    levels
}

/// A synthetic video sequence: a diagonal gradient moving one texel per frame, with seeded
/// noise and a bright bar, `n` frames of `w x h`.
pub fn synthetic_video(w: u32, h: u32, n: usize, seed: Seed) -> Vec<Vec<u8>> {
    let mut stim = Stimulus::new(seed);
    (0..n)
        .map(|f| {
            let noise = stim.draw_n(&(0u8..32), (w * h) as usize);
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .zip(noise)
                .map(|((x, y), nz)| {
                    let g = ((x + y) * 7 + f as u32 * 5) % 200;
                    let bar = if (x + f as u32) % 16 < 2 { 50 } else { 0 };
                    (g + bar + u32::from(nz)).min(255) as u8
                })
                .collect()
        })
        .collect()
}

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
}

/// Drives `frames` through the generator; `Err` for bad parameters or a hang.
pub fn run_mipmap(
    p: MipmapParams,
    frames: &[Vec<u8>],
    vcd: Option<(PathBuf, TraceConfig)>,
) -> Result<MipmapOutcome, String> {
    let dut = MipmapGen::new("mip", p)?;
    let n = (p.width * p.height) as usize;
    if let Some(k) = frames.iter().position(|f| f.len() != n) {
        return Err(format!(
            "frame {k} has {} texels, {}x{} needs {n}",
            frames[k].len(),
            p.width,
            p.height
        ));
    }
    match vcd {
        Some((path, cfg)) => {
            let t = VcdTracer::create(&path, "mipmap", cfg).map_err(|e| e.to_string())?;
            let sim = Sim::traced(dut, t).map_err(|e| e.to_string())?;
            let (sim, o) = drive(sim, frames)?;
            sim.finish().map_err(|e| e.to_string())?;
            Ok(o)
        }
        None => drive(Sim::<MipmapGen, NoTrace>::new(dut), frames).map(|x| x.1),
    }
}

fn drive<T: Trace>(
    mut sim: Sim<MipmapGen, T>,
    frames: &[Vec<u8>],
) -> Result<(Sim<MipmapGen, T>, MipmapOutcome), String> {
    sim.reset(2);
    let start = sim.cycle();
    let p = *sim.dut.params();
    let (w, h) = (p.width as usize, p.height as usize);
    let order: Vec<usize> = match p.scan {
        Scan::Progressive => (0..h).collect(),
        Scan::InterlacedTop => (0..h).step_by(2).chain((1..h).step_by(2)).collect(),
        Scan::InterlacedBottom => (1..h).step_by(2).chain((0..h).step_by(2)).collect(),
    };
    let mut out: Vec<Option<FrameBuffer>> = vec![None; frames.len()];
    let mut seen = 0;
    let mut collect = |sim: &Sim<MipmapGen, T>, out: &mut Vec<Option<FrameBuffer>>| {
        while seen < sim.dut.completed.len() {
            let (f, _) = sim.dut.completed[seen];
            if let Some(slot) = out.get_mut(f as usize) {
                *slot = Some(sim.dut.buffers[(f % 2) as usize].clone());
            }
            seen += 1;
        }
    };
    for frame in frames {
        for (li, &y) in order.iter().enumerate() {
            for x in 0..w {
                let d = &mut sim.dut;
                d.valid.set_bool(true);
                d.sof.set_bool(li == 0 && x == 0);
                d.texel.set_bits(u64::from(frame[y * w + x]));
                sim.step();
                collect(&sim, &mut out);
            }
        }
    }
    let last_texel = sim.cycle();
    let texels = (frames.len() * w * h) as u64;
    sim.dut.valid.set_bool(false);
    sim.dut.sof.set_bool(false);
    let limit = last_texel + 64 + 4 * w as u64;
    while out.iter().any(Option::is_none) {
        if sim.cycle() > limit {
            return Err(format!(
                "watchdog: mipmap incomplete {} cycles after the last texel",
                sim.cycle() - last_texel
            ));
        }
        sim.step();
        collect(&sim, &mut out);
    }
    sim.eval();
    let error = sim.dut.err_code.bits();
    let done_cycle = sim.dut.completed.last().map(|c| c.1).unwrap_or(last_texel);
    let r = &sim.dut.reducers;
    let m1408: Vec<usize> = r.iter().map(|r| r.fifo1408.max_occupancy()).collect();
    let m1412: Vec<usize> = r.iter().map(|r| r.fifo1412.max_occupancy()).collect();
    let stats = MipmapStats {
        cycles: sim.cycle() - start,
        latency_after_last_texel: done_cycle.saturating_sub(last_texel),
        fifo_max_occupancy: m1408.iter().zip(&m1412).map(|(a, b)| *a.max(b)).collect(),
        fifo1408_max: m1408,
        fifo1412_max: m1412,
        fifo_depth: r.iter().map(|r| r.fifo1408.depth()).collect(),
        texels,
        texels_per_clock: texels as f64 / (last_texel - start) as f64,
        page_activations: sim.dut.activations,
    };
    let frames = out.into_iter().map(|f| f.expect("collected")).collect();
    Ok((
        sim,
        MipmapOutcome {
            frames,
            stats,
            error,
        },
    ))
}

/// One configuration of the regression.
fn check_one(
    res: &mut TbResult,
    cov: &mut Coverage,
    p: MipmapParams,
    frames: &[Vec<u8>],
    vcd: Option<(PathBuf, TraceConfig)>,
    worst: &mut Vec<(String, f64, f64)>,
) -> Result<(), String> {
    let traced = vcd.is_some();
    let o = run_mipmap(p, frames, vcd.clone())?;
    if traced {
        res.vcd = vcd.map(|v| v.0);
    }
    let tag = format!("{}x{} {:?} {:?}", p.width, p.height, p.scan, p.rounding);
    let n_levels = p.levels().len();
    let mut sb: Scoreboard<Vec<u8>, Vec<u8>> =
        Scoreboard::new(|e: &Vec<u8>, a: &Vec<u8>| {
            match e.iter().zip(a).position(|(x, y)| x != y) {
                None => Ok(()),
                Some(i) => Err(format!("texel {i}: {} want {}", a[i], e[i])),
            }
        });
    sb.keep = 5;
    for (f, frame) in frames.iter().enumerate() {
        let want = reference(frame, p.width, p.height, p.rounding);
        for (k, want_k) in want.into_iter().enumerate() {
            sb.expect(want_k);
            sb.observe(f as u64, o.frames[f][k].clone());
            // Against the real-valued averages.
            let avg =
                golden::mipmap::box_average(frame, p.width as usize, p.height as usize, k as u32);
            let mut st = ErrorStats::new();
            for (d, g) in o.frames[f][k].iter().zip(&avg) {
                st.record(f64::from(*d), *g, 1.0);
            }
            let bound = golden::mipmap::error_bound(
                p.width as usize,
                p.height as usize,
                k as u32,
                p.rounding == Rounding::Round,
            );
            if st.max_abs_lsb > bound + 1e-9 {
                res.failures.push(format!(
                    "{tag} frame {f} level {k}: error {} LSB above the bound {bound}",
                    st.max_abs_lsb
                ));
            }
            let name = format!(
                "level {k} {}",
                if p.rounding == Rounding::Round {
                    "round"
                } else {
                    "truncate"
                }
            );
            match worst.iter_mut().find(|w| w.0 == name) {
                Some(w) => {
                    w.1 = w.1.max(st.max_abs_lsb);
                    w.2 = w.2.max(bound);
                }
                None => worst.push((name, st.max_abs_lsb, bound)),
            }
            res.stats.merge(&st);
        }
    }
    for m in sb.mismatches() {
        res.mismatch_log.push(format!(
            "{tag}: frame {:?} level {}: {}",
            m.cycle,
            m.index % n_levels as u64,
            m.detail
        ));
    }
    res.mismatches += sb.mismatch_count();
    res.transactions += frames.len() as u64;
    res.cycles += o.stats.cycles;
    if o.error != 0 {
        res.failures
            .push(format!("{tag}: generator error code {}", o.error));
    }
    for (k, (&m, &d)) in o
        .stats
        .fifo_max_occupancy
        .iter()
        .zip(&o.stats.fifo_depth)
        .enumerate()
    {
        if m > d {
            res.failures.push(format!(
                "{tag}: level {} FIFO occupancy {m} above depth {d}",
                k + 1
            ));
        }
    }
    if o.stats.texels_per_clock != 1.0 {
        res.failures.push(format!(
            "{tag}: {} texels per clock, not 1",
            o.stats.texels_per_clock
        ));
    }
    let max_latency = n_levels as u64 + 2;
    if o.stats.latency_after_last_texel > max_latency {
        res.failures.push(format!(
            "{tag}: latency {} after the last texel, above {max_latency}",
            o.stats.latency_after_last_texel
        ));
    }
    res.latency = Some(
        res.latency
            .unwrap_or(0)
            .max(o.stats.latency_after_last_texel),
    );
    let shape = match (p.width, p.height) {
        (1, _) | (_, 1) => 3,
        (w, h) if w == h => 0,
        (w, h) if w > h => 1,
        _ => 2,
    };
    let scan = match p.scan {
        Scan::Progressive => 0,
        Scan::InterlacedTop => 1,
        Scan::InterlacedBottom => 2,
    };
    cov.sample(&[
        scan,
        i64::from(p.rounding == Rounding::Truncate),
        shape,
        i64::from(frames.len() > 1),
    ]);
    Ok(())
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let s = c.add(
        Coverpoint::new("scan")
            .value("progressive", 0)
            .value("interlaced_top", 1)
            .value("interlaced_bottom", 2),
    );
    let r = c.add(
        Coverpoint::new("rounding")
            .value("round", 0)
            .value("truncate", 1),
    );
    c.add(
        Coverpoint::new("shape")
            .value("square", 0)
            .value("wide", 1)
            .value("tall", 2)
            .value("one_texel_side", 3),
    );
    c.add(
        Coverpoint::new("back_to_back")
            .value("single", 0)
            .value("several", 1),
    );
    c.cross("scan_x_rounding", s, r);
    c
}

/// The mipmap testbench of `texrtl regress`: a synthetic interlaced video sequence and
/// rectangular and degenerate sizes, in every scan order and both roundings.
pub fn regress_suite(
    seed: Seed,
    vcd: Option<PathBuf>,
    trace: TraceConfig,
    shard: verif::Shard,
) -> Result<TbResult, String> {
    let mut res = TbResult::new("mipmap", "mipmap generator 816 (section 12, FIG. 14a-b)");
    res.seed = Some(seed.to_string());
    let mut cov = coverage_model();
    let mut worst = Vec::new();
    let scans = [
        Scan::Progressive,
        Scan::InterlacedTop,
        Scan::InterlacedBottom,
    ];
    let sizes = [
        (64, 32, 3),
        (32, 32, 2),
        (16, 64, 2),
        (128, 8, 1),
        (8, 2, 2),
        (1, 16, 2),
        (16, 1, 1),
        (1, 1, 2),
        (256, 256, 1),
    ];
    let mut first = true;
    let mut config = 0u64;
    for &(w, h, n) in &sizes {
        for scan in scans {
            if h < 2 && scan != Scan::Progressive {
                continue;
            }
            for rounding in [Rounding::Round, Rounding::Truncate] {
                config += 1;
                let traced_config =
                    first && scan == Scan::InterlacedTop && rounding == Rounding::Round;
                if traced_config {
                    first = false;
                }
                if !shard.owns(config - 1) {
                    continue;
                }
                let p = MipmapParams {
                    width: w,
                    height: h,
                    scan,
                    rounding,
                };
                let frames = synthetic_video(w, h, n, seed.derive(u64::from(w * 1000 + h)));
                let v = match (&vcd, traced_config) {
                    (Some(path), true) => Some((path.clone(), trace.clone())),
                    _ => None,
                };
                check_one(&mut res, &mut cov, p, &frames, v, &mut worst)?;
            }
        }
    }
    worst.sort_by(|a, b| a.0.cmp(&b.0));
    for (name, e, b) in &worst {
        res.notes.push(format!(
            "{name}: worst error {e:.3} LSB against the block average (bound {b})"
        ));
    }
    res.set_coverage(cov);
    res.finish_with(shard.is_all());
    Ok(res)
}
