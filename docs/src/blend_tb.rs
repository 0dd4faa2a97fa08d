//! The guide's testbench of [`Blend`]: seeded blends through a driver and a monitor, a
//! scoreboard against the golden model within the error the one rounding allows, a coverage
//! model, and the golden value beside `out` in the waveform.

use crate::blend::{golden, Blend};
use verif::{About, Coverage, Coverpoint, Ctx, Pacing, PinDriver, PinMonitor, ProbeSink, RunSpec};
use verif::{Scoreboard, Stimulus, TbResult, Testbench};

/// One blend: the raw codes of `a`, `b` and `alpha` (LSB 2^-8).
pub type Txn = (u64, u64, u64);

/// The output's LSB.
const LSB: f64 = 1.0 / 256.0;

/// The driver: a blend onto the pins (an idle cycle drives `valid_in` low).
fn drive(d: &mut Blend, t: Option<&Txn>) {
    let &(a, b, alpha) = t.unwrap_or(&(0, 0, 0));
    d.valid_in.set_bool(t.is_some());
    d.a.set_bits(a);
    d.b.set_bits(b);
    d.alpha.set_bits(alpha);
}

/// The monitor: `out` in each cycle `out_valid` is high.
fn sample(d: &Blend) -> Option<f64> {
    d.out_valid.is_high().then(|| d.out.fx().to_f64())
}

/// The blend's testbench: two configurations, back-to-back blends and random idle cycles.
pub struct BlendTb;

impl Testbench for BlendTb {
    fn about(&self) -> About {
        About::new("blend", "a two-stage alpha blend, out = b + alpha (a - b)")
    }
    fn configurations(&self) -> Vec<String> {
        vec!["back to back".into(), "random idle cycles".into()]
    }
    fn coverage(&self) -> Coverage {
        let mut c = Coverage::new();
        c.add(
            Coverpoint::new("alpha")
                .value("0", 0)
                .ranges("inside", 1, 254, 4)
                .value("max", 255),
        );
        c.add(Coverpoint::new("a - b").ranges("sign", -1, 1, 3));
        c
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (mut sim, probe) = ctx.sim(Blend::default(), "alpha blend", 10_000, |t| {
            t.probe_real("out_golden", Some("tb.blend.out"))
        })?;
        sim.reset(2);
        let mut stim = Stimulus::new(ctx.seed);
        let codes = stim.draw_n(&(0u64..256), 3 * ctx.count);
        let mut txns: Vec<Txn> = codes.chunks(3).map(|c| (c[0], c[1], c[2])).collect();
        // The weight's ends, which random draws reach rarely.
        txns.extend([(200, 10, 0), (10, 200, 255), (255, 0, 255), (0, 255, 0)]);
        // Each blend with what the scoreboard expects of it: itself (for coverage) and the
        // golden model's value.
        let real = |code: u64| code as f64 * LSB;
        let n = txns.len() as u64;
        let pairs = txns
            .into_iter()
            .map(|t| (t, (t, golden(real(t.0), real(t.1), real(t.2)))));
        // One rounding of an exact value: within half an LSB of the golden blend.
        let mut sb = Scoreboard::new(|&(_, g): &(Txn, f64), d: &f64| {
            ((d - g).abs() <= LSB / 2.0)
                .then_some(())
                .ok_or(format!("out {d} vs golden {g}"))
        });
        let (mut res, mut cov) = (TbResult::new(self.name(), self.unit()), self.coverage());
        let pacing = match ctx.index {
            0 => Pacing::full(),
            _ => Pacing::random(500, ctx.seed),
        };
        let mut spec = RunSpec::new(n, 4 * n + 10).pacing(pacing);
        let (drv, mon) = (&mut PinDriver::new(drive), &mut PinMonitor::new(sample));
        let r = sb.run(
            &mut sim,
            drv,
            mon,
            pairs,
            &mut spec,
            |sim, ((a, b, alpha), g), out| {
                if let (Some(p), Some(t)) = (probe, sim.trace_mut()) {
                    t.real(p, g);
                }
                res.stats.record(out, g, LSB);
                cov.sample(&[alpha as i64, (a as i64 - b as i64).signum()]);
            },
        );
        res.score(&sb);
        res.ran(&r); // its cycles, or a hang (the watchdog) as a failure of this job
        res.coverage = Some(cov);
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}
