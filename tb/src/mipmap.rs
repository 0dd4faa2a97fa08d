//! Testbench of the real-time mipmap generator (`units::mipmap`, Schilling & Knittel section 12,
//! Figure 14) over the run of `texrtl mipmap` ([`crate::runs::mipmap`]).
//!
//! Video goes in at one texel per clock, frames back to back with no idle cycle, `sof` with
//! each frame's first texel. Each frame's mipmap (read from the generator's frame store when it
//! reports the frame complete) is compared level by level with an integer reference, a plain
//! loop over the whole frame that shares nothing with the hardware's structure, and with the
//! real-valued block averages of `golden::mipmap` against the analytic bound.

use crate::runs::mipmap::{run_mipmap_checked, MipmapOutcome, MipmapStats};
use serde::{Deserialize, Serialize};
use units::mipmap::{FrameBuffer, MipmapParams, Rounding, Scan};
use verif::{
    About, Coverage, Coverpoint, Ctx, ErrorStats, Scoreboard, Seed, Stimulus, TbResult, Testbench,
};

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

/// One configuration of the regression: runs the frames, scores every level, checks the
/// generator's timing and FIFOs, samples coverage.
fn check_one(
    res: &mut TbResult,
    cov: &mut Coverage,
    p: MipmapParams,
    frames: &[Vec<u8>],
    ctx: &Ctx,
) -> Result<(), String> {
    let vcd = ctx
        .waves
        .as_ref()
        .map(|w| (w.vcd.clone(), w.config(10_000)));
    let traced = vcd.as_ref().map(|v| v.0.clone());
    let o = run_mipmap_checked(p, frames, vcd, ctx.check_schedule)?;
    res.vcd = traced;
    let tag = format!("{}x{} {:?} {:?}", p.width, p.height, p.scan, p.rounding);
    if !o.findings.is_empty() {
        // A hang, or frames out of order: no levels to score; that is the finding.
        (res.failures).extend(o.findings.iter().map(|f| format!("{tag}: {f}")));
        res.cycles += o.stats.cycles;
        return Ok(());
    }
    score_levels(res, p, frames, &o, &tag);
    res.transactions += frames.len() as u64;
    res.cycles += o.stats.cycles;
    if o.error != 0 {
        res.failures
            .push(format!("{tag}: generator error code {}", o.error));
    }
    check_timing(res, &o.stats, p.levels().len() as u64, &tag);
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
    for f in 0..frames.len() {
        let truncate = i64::from(p.rounding == Rounding::Truncate);
        cov.sample(&[scan, truncate, shape, i64::from(f > 0)]);
    }
    Ok(())
}

/// Every level of every frame against the integer reference (bit-exact) and the real-valued
/// block averages (within the analytic bound); one record per level with its worst error.
fn score_levels(
    res: &mut TbResult,
    p: MipmapParams,
    frames: &[Vec<u8>],
    o: &MipmapOutcome,
    tag: &str,
) {
    let mut sb: Scoreboard<Vec<u8>, Vec<u8>> =
        Scoreboard::new(|e: &Vec<u8>, a: &Vec<u8>| {
            match e.iter().zip(a).position(|(x, y)| x != y) {
                None => Ok(()),
                Some(i) => Err(format!("texel {i}: {} want {}", a[i], e[i])),
            }
        });
    sb.keep = 5;
    let (w, h) = (p.width as usize, p.height as usize);
    let round = p.rounding == Rounding::Round;
    for (f, frame) in frames.iter().enumerate() {
        let want = reference(frame, p.width, p.height, p.rounding);
        for (k, want_k) in want.into_iter().enumerate() {
            sb.expect(want_k);
            sb.observe(f as u64, o.frames[f][k].clone());
            let avg = golden::mipmap::box_average(frame, w, h, k as u32);
            let mut st = ErrorStats::new();
            for (d, g) in o.frames[f][k].iter().zip(&avg) {
                st.record(f64::from(*d), *g, 1.0);
            }
            let bound = golden::mipmap::error_bound(w, h, k as u32, round);
            if st.max_abs_lsb > bound + 1e-9 {
                res.failures.push(format!(
                    "{tag} frame {f} level {k}: error {} LSB above the bound {bound}",
                    st.max_abs_lsb
                ));
            }
            let mode = if round { "round" } else { "truncate" };
            res.record(&LevelError {
                level: format!("level {k} {mode}"),
                error: st.max_abs_lsb,
                bound,
            });
            if let Err(e) = res.stats.merge(&st) {
                res.failures.push(e);
            }
        }
    }
    let n_levels = p.levels().len() as u64;
    for m in sb.mismatches() {
        res.mismatch_log.push(format!(
            "{tag}: frame {:?} level {}: {}",
            m.cycle,
            m.index % n_levels,
            m.detail
        ));
    }
    res.mismatches += sb.mismatch_count();
}

/// FIFO occupancies within their depths, one texel per clock, the mipmap complete at most
/// `levels + 2` cycles after the last texel.
fn check_timing(res: &mut TbResult, s: &MipmapStats, levels: u64, tag: &str) {
    for (k, (&m, &d)) in s.fifo_max_occupancy.iter().zip(&s.fifo_depth).enumerate() {
        if m > d {
            res.failures.push(format!(
                "{tag}: level {} FIFO occupancy {m} above depth {d}",
                k + 1
            ));
        }
    }
    if s.texels_per_clock != 1.0 {
        res.failures.push(format!(
            "{tag}: {} texels per clock, not 1",
            s.texels_per_clock
        ));
    }
    let max_latency = levels + 2;
    if s.latency_after_last_texel > max_latency {
        res.failures.push(format!(
            "{tag}: latency {} after the last texel, above {max_latency}",
            s.latency_after_last_texel
        ));
    }
    res.latency = Some(res.latency.unwrap_or(0).max(s.latency_after_last_texel));
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let s = c.add(Coverpoint::new("scan").values(&[
        "progressive",
        "interlaced_top",
        "interlaced_bottom",
    ]));
    let r = c.add(Coverpoint::new("rounding").values(&["round", "truncate"]));
    c.add(Coverpoint::new("shape").values(&["square", "wide", "tall", "one_texel_side"]));
    c.add(Coverpoint::new("frame").values(&["first", "back_to_back"]));
    c.cross("scan_x_rounding", s, r);
    c
}

/// The testbench's name: the unit's.
pub const NAME: &str = "mipmap_gen_816";

/// The frame sizes of the mipmap testbench: square, wide, tall, one texel wide or high, 1x1.
pub const SIZES: [(u32, u32); 9] = [
    (64, 32),
    (32, 32),
    (16, 64),
    (128, 8),
    (8, 2),
    (1, 16),
    (16, 1),
    (1, 1),
    (256, 256),
];

/// The mipmap testbench of `texrtl regress`: a synthetic video sequence in every size of
/// [`SIZES`], every scan order (interlaced needs two lines) and both roundings, one
/// configuration each; the traced one is 64x32 interlaced, top field first, rounding.
pub struct MipmapTb;

/// A level's worst error against the block averages in one configuration.
#[derive(Serialize, Deserialize)]
struct LevelError {
    level: String,
    error: f64,
    bound: f64,
}

impl MipmapTb {
    fn params() -> Vec<MipmapParams> {
        let scans = [
            Scan::Progressive,
            Scan::InterlacedTop,
            Scan::InterlacedBottom,
        ];
        let mut v = Vec::new();
        for (width, height) in SIZES {
            for scan in scans {
                if height < 2 && scan != Scan::Progressive {
                    continue;
                }
                for rounding in [Rounding::Round, Rounding::Truncate] {
                    v.push(MipmapParams {
                        width,
                        height,
                        scan,
                        rounding,
                    });
                }
            }
        }
        v
    }
}

impl Testbench for MipmapTb {
    fn about(&self) -> About {
        About::new(NAME, "mipmap generator 816 (section 12, FIG. 14a-b)")
            .count(2, "frames per configuration")
            // 64x32, interlaced top field first, rounding.
            .traced(2)
    }
    fn configurations(&self) -> Vec<String> {
        MipmapTb::params()
            .iter()
            .map(|p| format!("{}x{} {:?} {:?}", p.width, p.height, p.scan, p.rounding))
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let p = MipmapTb::params()[ctx.index];
        let mut res = TbResult::new(self.name(), self.unit());
        let mut cov = coverage_model();
        let frames = synthetic_video(p.width, p.height, ctx.count, ctx.seed);
        check_one(&mut res, &mut cov, p, &frames, ctx)?;
        res.coverage = Some(cov);
        Ok(res)
    }
    fn conclude(&self, merged: &mut TbResult) {
        let mut worst: Vec<LevelError> = Vec::new();
        for e in merged.records_of::<LevelError>() {
            match worst.iter_mut().find(|w| w.level == e.level) {
                Some(w) => {
                    w.error = w.error.max(e.error);
                    w.bound = w.bound.max(e.bound);
                }
                None => worst.push(e),
            }
        }
        worst.sort_by(|a, b| a.level.cmp(&b.level));
        for w in worst {
            merged.notes.push(format!(
                "{}: worst error {:.3} LSB against the block average (bound {})",
                w.level, w.error, w.bound
            ));
        }
    }
}
