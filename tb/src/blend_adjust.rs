//! Testbench of the blend-factor adjust unit 153 (`units::bump::blend_adjust_153`).
//!
//! Stimulus, for every blend-factor width F = 4..=16:
//! * **sweep**: every value of `u` (all 2^F), in both modes (adjust and Blinn bypass), at one
//!   transaction per clock; `v` takes every value too, paired with `u` by the permutation
//!   `v = (u * 0x9E5 + 7) mod 2^F` so the two channels never carry the same sequence;
//! * **random**: seeded constrained-random transactions with independent `u`, `v`, `bypass`,
//!   corner values weighted up, and random idle cycles between them.
//!
//! Every output is scored against `golden::blend_adjust` with zero tolerance: the adjustment is
//! exact in `F + 1` fraction bits, so any error at all is a bug. Coverage: width x mode,
//! `u`/`v` classes (zero, max, interior ranges) crossed with the mode. The run at the traced
//! width (default F = 8) writes `blend_adjust_153.vcd` with the golden values beside the outputs.

use hdl::kernel::{Sim, Trace};
use proptest::prelude::*;
use units::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
use verif::{
    run_scored, About, Coverage, Coverpoint, Ctx, Monitor, Pacing, PinDriver, ProbeSink, RunSpec,
    Scoreboard, Scored, Stimulus, TbResult, Testbench,
};
use waves::ProbeId;

/// An input transaction: one pair of blend factors (raw `uQ0.F` bits) and the mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BaIn {
    pub u: u32,
    pub v: u32,
    pub bypass: bool,
}

/// An output transaction: the four adjusted factors, raw `uQ0.(F+1)` bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BaOut {
    pub u0: u32,
    pub u1: u32,
    pub v0: u32,
    pub v1: u32,
}

/// Drives `valid_in`, `bypass`, `u_in`, `v_in`.
pub fn drive_ba(dut: &mut BlendAdjust, t: Option<&BaIn>) {
    dut.i.valid_in.set_bool(t.is_some());
    let t = t.copied().unwrap_or(BaIn {
        u: 0,
        v: 0,
        bypass: false,
    });
    dut.i.bypass.set_bool(t.bypass);
    dut.i.u_in.set_bits(u64::from(t.u));
    dut.i.v_in.set_bits(u64::from(t.v));
}

/// Collects the four outputs whenever `valid` is high. With `fault`, flips the LSB of `u1` in
/// transaction number `fault` (to show that the testbench catches a one-bit error).
pub struct BaMonitor {
    pub fault: Option<u64>,
    seen: u64,
}

impl Monitor<BlendAdjust> for BaMonitor {
    type Txn = BaOut;
    fn sample(&mut self, dut: &BlendAdjust) -> Option<BaOut> {
        if !dut.o.valid.is_high() {
            return None;
        }
        let mut o = BaOut {
            u0: dut.o.u0.bits() as u32,
            u1: dut.o.u1.bits() as u32,
            v0: dut.o.v0.bits() as u32,
            v1: dut.o.v1.bits() as u32,
        };
        if self.fault == Some(self.seen) {
            o.u1 ^= 1;
        }
        self.seen += 1;
        Some(o)
    }
}

/// The golden result of a transaction, as real numbers `[u0, u1, v0, v1]`.
pub fn golden(t: &BaIn, frac_bits: u32) -> [f64; 4] {
    let scale = (frac_bits as f64).exp2();
    let (u0, u1) = golden::blend_adjust::adjust(f64::from(t.u) / scale, t.bypass);
    let (v0, v1) = golden::blend_adjust::adjust(f64::from(t.v) / scale, t.bypass);
    [u0, u1, v0, v1]
}

/// The testbench of unit 153: one configuration per blend-factor width F.
#[derive(Clone, Debug)]
pub struct BlendAdjustTb {
    /// The widths to run (every one the unit takes, by default; fewer leave coverage holes).
    pub widths: std::ops::RangeInclusive<u32>,
    pub registered: bool,
    /// Corrupt one output transaction (see [`BaMonitor`]).
    pub fault: Option<u64>,
}

impl Default for BlendAdjustTb {
    fn default() -> Self {
        BlendAdjustTb {
            widths: BlendAdjustParams::FRAC_RANGE,
            registered: true,
            fault: None,
        }
    }
}

/// The testbench's name: the unit's (its waveform is `blend_adjust_153.vcd`).
pub const NAME: &str = "blend_adjust_153";

/// The width whose run is traced.
const TRACED_FRAC: u32 = 8;

impl Testbench for BlendAdjustTb {
    fn about(&self) -> About {
        About::new(NAME, "unit 153 (FIG. 7, para. 0058-0061, 0085)")
            .count(2000, "random transactions")
            .traced(TRACED_FRAC.saturating_sub(*self.widths.start()) as usize)
    }
    fn configurations(&self) -> Vec<String> {
        self.widths.clone().map(|f| format!("F={f}")).collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let f = self.widths.start() + ctx.index as u32;
        let params = BlendAdjustParams {
            frac_bits: f,
            registered: self.registered,
        };
        params.validate()?;
        let dut = BlendAdjust::new("blend_adjust_153", params)?;
        // The golden factors beside the unit's, and a flag where they differ.
        let (sim, probes) = ctx.sim(dut, &format!("blend_adjust F={f}"), 10_000, |t| {
            let probes = [
                t.probe_real("u0_golden", Some("tb.blend_adjust_153.u0")),
                t.probe_real("u1_golden", Some("tb.blend_adjust_153.u1")),
                t.probe_real("v0_golden", Some("tb.blend_adjust_153.v0")),
                t.probe_real("v1_golden", Some("tb.blend_adjust_153.v1")),
            ];
            (
                probes,
                t.probe_bits("mismatch", 1, Some("tb.blend_adjust_153.valid")),
            )
        })?;
        let (sim, mut res) = one_width(sim, self, ctx, f, probes);
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}

fn sweep(f: u32) -> Vec<BaIn> {
    let n = 1u32 << f;
    let mut v = Vec::with_capacity(2 * n as usize);
    for bypass in [false, true] {
        for u in 0..n {
            v.push(BaIn {
                u,
                v: (u.wrapping_mul(0x9e5).wrapping_add(7)) & (n - 1),
                bypass,
            });
        }
    }
    v
}

fn random(f: u32, n: usize, stim: &mut Stimulus) -> Vec<BaIn> {
    let max = (1u32 << f) - 1;
    // Corners (0, 1, max-1, max) a quarter of the time, otherwise uniform.
    let val = prop_oneof![
        1 => prop_oneof![Just(0u32), Just(1), Just(max - 1), Just(max)],
        3 => 0..=max,
    ];
    let s = (val.clone(), val, any::<bool>()).prop_map(|(u, v, bypass)| BaIn { u, v, bypass });
    stim.draw_n(&s, n)
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let w = c.add(Coverpoint::new("frac_bits").ranges("F", 4, 16, 13));
    let m = c.add(Coverpoint::new("mode").values(&["adjust", "bypass"]));
    let classes = |name: &str| {
        Coverpoint::new(name)
            .value("zero", 0)
            .value("max", 1 << 16)
            .ranges("interior", 1, (1 << 16) - 1, 8)
    };
    let u = c.add(classes("u"));
    c.add(classes("v"));
    c.cross("frac_bits_x_mode", w, m);
    c.cross("mode_x_u", m, u);
    c
}

/// A value's coverage class on a common scale: 0 for zero, 2^16 for the maximum, otherwise
/// the value scaled to 16 bits (1..2^16-1).
fn class(x: u32, f: u32) -> i64 {
    let max = (1u32 << f) - 1;
    if x == 0 {
        0
    } else if x == max {
        1 << 16
    } else {
        (i64::from(x) << (16 - f)).max(1)
    }
}

type Probes = ([ProbeId; 4], ProbeId);

/// Resets the unit, runs the full-rate sweep and the randomly paced transactions of one width.
fn one_width<T: Trace + ProbeSink>(
    mut sim: Sim<BlendAdjust, T>,
    tb: &BlendAdjustTb,
    ctx: &Ctx,
    f: u32,
    probes: Option<Probes>,
) -> (Sim<BlendAdjust, T>, TbResult) {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    let mut stim = Stimulus::new(ctx.seed);
    sim.reset(2);
    let lsb = (-(f as f64 + 1.0)).exp2();
    let latency = u64::from(sim.dut.params().latency());
    let mut monitor = BaMonitor {
        fault: tb.fault,
        seen: 0,
    };
    for (phase, stimulus) in [
        ("sweep", sweep(f)),
        ("random", random(f, ctx.count, &mut stim)),
    ] {
        let n = stimulus.len() as u64;
        let pacing = if phase == "sweep" {
            Pacing::full()
        } else {
            Pacing::random(250, stim.seed().derive(u64::from(f)))
        };
        let mut sb = scoreboard(lsb);
        let mut spec = RunSpec::new(n, 8 * n + 100).pacing(pacing);
        let r = run_scored(
            &mut sim,
            &mut PinDriver::new(drive_ba),
            &mut monitor,
            stimulus,
            &mut spec,
            |sim, ev| match ev {
                Scored::Sent { txn, .. } => {
                    cov.sample(&[
                        f as i64,
                        i64::from(txn.bypass),
                        class(txn.u, f),
                        class(txn.v, f),
                    ]);
                    sb.expect((*txn, golden(txn, f)));
                }
                Scored::Received { cycle, txn } => {
                    let out = sb.observe(cycle, txn);
                    let got = [txn.u0, txn.u1, txn.v0, txn.v1].map(|x| f64::from(x) * lsb);
                    if let Some((_, g)) = out.expected {
                        for k in 0..4 {
                            res.stats.record(got[k], g[k], lsb);
                        }
                        if let (Some((p, miss)), Some(t)) = (probes, sim.trace_mut()) {
                            for k in 0..4 {
                                t.real(p[k], g[k]);
                            }
                            t.flag(miss, !out.ok);
                        }
                    }
                }
            },
        );
        res.transactions += n;
        res.mismatches += sb.mismatch_count();
        for m in sb.mismatches().iter().take(10) {
            res.mismatch_log.push(format!(
                "{phase}: {} (cycle {:?}): {}",
                m.index, m.cycle, m.detail
            ));
        }
        match r {
            Ok(st) => {
                res.cycles += st.cycles;
                if phase == "sweep" {
                    // One per clock: n transactions take n + latency cycles.
                    if st.cycles != n + latency
                        || st.min_latency != Some(latency)
                        || st.max_latency != Some(latency)
                    {
                        res.failures.push(format!(
                            "{} cycles for {n} transactions, latency {:?}..{:?}, want {} and {latency}",
                            st.cycles,
                            st.min_latency,
                            st.max_latency,
                            n + latency
                        ));
                    }
                    res.latency = Some(latency);
                }
            }
            Err(t) => res.failures.push(format!("{phase}: {t}")),
        }
    }
    res.coverage = Some(cov);
    (sim, res)
}

type BaScoreboard = Scoreboard<(BaIn, [f64; 4]), BaOut>;

/// Exact comparison of the four factors against golden, in units of `lsb`.
fn scoreboard(lsb: f64) -> BaScoreboard {
    Scoreboard::new(move |(_, g): &(BaIn, [f64; 4]), a: &BaOut| {
        let got = [a.u0, a.u1, a.v0, a.v1].map(|x| f64::from(x) * lsb);
        let names = ["u0", "u1", "v0", "v1"];
        let bad: Vec<String> = (0..4)
            .filter(|&k| got[k] != g[k])
            .map(|k| format!("{}={} want {}", names[k], got[k], g[k]))
            .collect();
        if bad.is_empty() {
            Ok(())
        } else {
            Err(bad.join(", "))
        }
    })
}
