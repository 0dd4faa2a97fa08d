//! A user's first unit: a saturating accumulator, `acc <= sat(acc + x)`, with its golden model
//! and a testbench. `cargo run --example saturating_accumulator` writes its waveform.
use hdl::fx::{Format, Overflow, Quant};
use hdl::kernel::{Module, Reg, Signal, Visitor};
use verif::{run, Coverage, Coverpoint, Ctx, Driver, Event, Monitor, Pacing, RunSpec, Scoreboard};
use verif::{ProbeSink, RunOptions, TbResult, Testbench};

const X: Format = Format::signed(8, 4); // input sQ4.4: [-8, 8)
const ACC: Format = Format::signed(10, 4); // accumulator sQ6.4: [-32, 32)

/// The unit: two-process style, `eval` computes, `tick` only commits registers.
struct SatAcc {
    valid_in: Signal,
    x: Signal,
    out_valid: Signal,
    acc: Signal,
    acc_r: Reg,
    valid_r: Reg,
}

impl Module for SatAcc {
    fn kind(&self) -> &'static str {
        "sat_acc"
    }
    fn eval(&mut self) {
        self.out_valid.follow(self.valid_r.q());
        self.acc.follow(self.acc_r.q());
        self.valid_r.set_next_bool(self.valid_in.is_high());
        if self.valid_in.is_high() {
            // Full-precision sum, then one declared narrowing: truncate (exact here), saturate.
            let sum = self.acc_r.q().fx() + self.x.fx();
            self.acc_r.set_next(sum.convert(ACC, Quant::Trunc, Overflow::Saturate));
        }
    }
    fn tick(&mut self, reset: bool) {
        self.acc_r.tick(reset);
        self.valid_r.tick(reset);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter(self.instance(), self.kind());
        hdl::signals!(v; Input: self.valid_in, self.x;
            Output: self.out_valid, self.acc; Reg: self.acc_r, self.valid_r);
        v.leave();
    }
}

/// Drives a transaction, the raw value of `x`, with `valid_in`.
struct Drv;
impl Driver<SatAcc> for Drv {
    type Txn = i64;
    fn drive(&mut self, d: &mut SatAcc, x: Option<&i64>) {
        d.valid_in.set_bool(x.is_some());
        d.x.set_raw(x.copied().unwrap_or(0));
    }
}
/// Collects the accumulator's value whenever `out_valid` is high.
struct Mon;
impl Monitor<SatAcc> for Mon {
    type Txn = f64;
    fn sample(&mut self, d: &SatAcc) -> Option<f64> {
        d.out_valid.is_high().then(|| d.acc.fx().to_f64())
    }
}

/// The golden model, from the mathematics: `clamp(acc + x)` on the reals.
fn golden(acc: f64, x: i64) -> f64 {
    (acc + x as f64 / 16.0).clamp(-32.0, 32.0 - 1.0 / 16.0)
}

struct SatAccTb;
impl Testbench for SatAccTb {
    fn name(&self) -> &'static str {
        "sat_acc"
    }
    fn unit(&self) -> &'static str {
        "a saturating accumulator (the user guide's example)"
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
        let dut = SatAcc {
            valid_in: Signal::bit("valid_in"),
            x: Signal::new("x", X),
            out_valid: Signal::bit("out_valid"),
            acc: Signal::new("acc", ACC),
            acc_r: Reg::new("acc_r", ACC),
            valid_r: Reg::new("valid_r", Format::uint(1)),
        };
        let (mut sim, probe) = ctx.sim(dut, "saturating accumulator", 10_000, |t| {
            let g = t.probe_real("acc_golden", Some("tb.sat_acc.acc"));
            (g, t.probe_bits("mismatch", 1, Some("tb.sat_acc.out_valid")))
        })?;
        sim.reset(1);
        // Seeded stimulus; long runs of one sign drive the accumulator into both rails.
        let mut stim = verif::Stimulus::new(ctx.seed);
        let xs = stim.draw_n(&(-128i64..128), ctx.count).into_iter().enumerate();
        let txns: Vec<i64> = xs.map(|(i, x)| if (i / 200) % 2 == 0 { x.abs() / 2 } else { x }).collect();
        let mut sb =
            Scoreboard::new(|g: &f64, d: &f64| (g == d).then_some(()).ok_or(format!("acc {d} != {g}")));
        let (mut res, mut cov, mut acc) = (TbResult::new(self.name(), self.unit()), self.coverage(), 0.0);
        let pacing = if ctx.index == 0 { Pacing::full() } else { Pacing::random(300, ctx.seed) };
        let mut spec = RunSpec::new(txns.len() as u64, 4 * txns.len() as u64 + 10).pacing(pacing);
        let r = run(&mut sim, &mut Drv, &mut Mon, txns, &mut spec, |sim, ev| match ev {
            Event::Sent { txn, .. } => {
                acc = golden(acc, *txn);
                sb.expect(acc);
                cov.sample(&[(acc * 16.0) as i64]);
            }
            Event::Received { cycle, txn } => {
                let out = sb.observe(cycle, txn);
                if let (Some((g, m)), Some(t), Some(e)) = (probe, sim.trace_mut(), out.expected) {
                    t.real(g, e);
                    t.flag(m, !out.ok);
                }
                res.stats.record(txn, out.expected.unwrap_or(txn), 1.0 / 16.0);
            }
            Event::Settled { .. } => {}
        });
        res.score(&sb);
        res.cycles = r.map_err(|t| t.to_string())?.cycles;
        res.coverage = Some(cov);
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}

fn main() {
    let out = std::path::Path::new("target/texrtl-example");
    let r = verif::run_testbench(&SatAccTb, &RunOptions::with_waves(out), &mut |c| eprintln!("running {c}"));
    let r = r.expect("the testbench runs");
    println!("{}\nwaveform: gtkwave {}", r.summary(), out.join("sat_acc.gtkw").display());
    std::process::exit(i32::from(!r.passed));
}

#[test]
fn the_accumulator_matches_golden_and_the_waveform_reads_back() {
    let dir = std::env::temp_dir().join(format!("texrtl-example-{}", std::process::id()));
    let opts = RunOptions { check_schedule: true, ..RunOptions::with_waves(&dir) };
    let r = verif::run_testbench(&SatAccTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.mismatch_log, r.failures);
    let vcd = dir.join("sat_acc.vcd");
    waves::check::check_gtkw(&vcd, &waves::check::read_vcd(&vcd).unwrap()).unwrap();
}
