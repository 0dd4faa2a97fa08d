//! The testbench: seeded stimulus, a scoreboard against golden, coverage, probes in the waveform.
use crate::unit::{golden, SatAcc};
use verif::{run_scored, Coverage, Coverpoint, Ctx, Driver, Monitor, Pacing, RunSpec, Scoreboard, Scored};
use verif::{ProbeSink, TbResult, Testbench};

struct Drv; // a transaction, the raw value of `x`, to the pins
impl Driver<SatAcc> for Drv {
    type Txn = i64;
    fn drive(&mut self, d: &mut SatAcc, x: Option<&i64>) {
        d.valid_in.set_bool(x.is_some());
        d.x.set_raw(x.copied().unwrap_or(0));
    }
}
struct Mon; // the accumulator whenever `out_valid` is high
impl Monitor<SatAcc> for Mon {
    type Txn = f64;
    fn sample(&mut self, d: &SatAcc) -> Option<f64> {
        d.out_valid.is_high().then(|| d.acc.fx().to_f64())
    }
}

pub struct SatAccTb;
impl Testbench for SatAccTb {
    fn name(&self) -> &'static str {
        "sat_acc"
    }
    fn unit(&self) -> &'static str {
        "a saturating accumulator"
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
        let txns: Vec<i64> = xs.map(|(i, x)| if (i / 200) % 2 == 0 { x.abs() / 2 } else { x }).collect();
        let mut sb =
            Scoreboard::new(|g: &f64, d: &f64| (g == d).then_some(()).ok_or(format!("acc {d} != {g}")));
        let (mut res, mut cov, mut acc) = (TbResult::new(self.name(), self.unit()), self.coverage(), 0.0);
        let pacing = if ctx.index == 0 { Pacing::full() } else { Pacing::random(300, ctx.seed) };
        let mut spec = RunSpec::new(txns.len() as u64, 4 * txns.len() as u64 + 10).pacing(pacing);
        let r = run_scored(&mut sim, &mut Drv, &mut Mon, txns, &mut spec, |sim, ev| match ev {
            Scored::Sent { txn, .. } => {
                acc = golden(acc, *txn as f64 / 16.0);
                sb.expect(acc);
                cov.sample(&[(acc * 16.0) as i64]);
            }
            Scored::Received { cycle, txn } => {
                let out = sb.observe(cycle, txn);
                if let (Some((g, m)), Some(t), Some(e)) = (probe, sim.trace_mut(), out.expected) {
                    t.real(g, e);
                    t.flag(m, !out.ok);
                }
                res.stats.record(txn, out.expected.unwrap_or(txn), 1.0 / 16.0);
            }
        });
        res.score(&sb);
        res.cycles = r.map_err(|t| t.to_string())?.cycles;
        res.coverage = Some(cov);
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}
