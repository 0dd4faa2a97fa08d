//! The testbench: seeded stimulus, a scoreboard against golden, coverage, probes in the waveform.
use crate::unit::{golden, SatAcc};
use verif::{
    About, Coverage, Coverpoint, Ctx, Pacing, PinDriver, PinMonitor, ProbeSink, RunSpec, Scoreboard,
};
use verif::{TbResult, Testbench};

/// A transaction, the raw value of `x`, to the pins.
fn drive(d: &mut SatAcc, x: Option<&i64>) {
    d.valid_in.set_bool(x.is_some());
    d.x.set_raw(x.copied().unwrap_or(0));
}

/// The accumulator whenever `out_valid` is high.
fn sample(d: &SatAcc) -> Option<f64> {
    d.out_valid.is_high().then(|| d.acc.fx().to_f64())
}

pub struct SatAccTb;
impl Testbench for SatAccTb {
    fn about(&self) -> About {
        About::new("sat_acc", "a saturating accumulator")
    }
    fn configurations(&self) -> Vec<String> {
        vec!["full rate".into(), "random idle cycles".into()]
    }
    fn coverage(&self) -> Coverage {
        let mut c = Coverage::new();
        c.add(Coverpoint::new("acc").value("min", -512).ranges("inside", -511, 510, 4).value("max", 511));
        c
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (mut sim, probe) = ctx.sim(SatAcc::default(), "saturating accumulator", 10_000, |t| {
            let g = t.probe_real("acc_golden", Some("tb.sat_acc.acc"));
            (g, t.probe_bits("mismatch", 1, Some("tb.sat_acc.out_valid")))
        })?;
        sim.reset(1);
        // Seeded; long runs of one sign drive the accumulator into both rails.
        let mut stim = verif::Stimulus::new(ctx.seed);
        let xs = stim.draw_n(&(-128i64..128), ctx.count).into_iter().enumerate();
        let txns = xs.map(|(i, x)| if (i / 200) % 2 == 0 { x.abs() / 2 } else { x });
        // Each transaction with the accumulator the golden model expects after it.
        let mut acc = 0.0;
        let pairs: Vec<(i64, f64)> = txns
            .map(|x| {
                acc = golden(acc, x as f64 / 16.0);
                (x, acc)
            })
            .collect();
        let mut sb =
            Scoreboard::new(|g: &f64, d: &f64| (g == d).then_some(()).ok_or(format!("acc {d} != {g}")));
        let (mut res, mut cov) = (TbResult::new(self.name(), self.unit()), self.coverage());
        let pacing = if ctx.index == 0 { Pacing::full() } else { Pacing::random(300, ctx.seed) };
        let mut spec = RunSpec::new(pairs.len() as u64, 4 * pairs.len() as u64 + 10).pacing(pacing);
        let (drv, mon) = (&mut PinDriver::new(drive), &mut PinMonitor::new(sample));
        let r = sb.run(&mut sim, drv, mon, pairs, &mut spec, |sim, g, d| {
            if let (Some((p, m)), Some(t)) = (probe, sim.trace_mut()) {
                t.real(p, g);
                t.flag(m, d != g);
            }
            res.stats.record(d, g, 1.0 / 16.0);
            cov.sample(&[(g * 16.0) as i64]);
        });
        res.score(&sb);
        res.ran(&r); // its cycles, or a hang (the watchdog) as a failure of this job
        res.coverage = Some(cov);
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}
