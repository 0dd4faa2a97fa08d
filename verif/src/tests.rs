//! The cycle loop on a small registered design: latency, throughput, pacing, watchdog.

use crate::*;
use hdl::fx::Format;
use hdl::kernel::{Module, Reg, Signal, Sim, Visitor};

/// A two-stage pipeline that adds 1; `stall` makes it never produce output.
struct Plus1 {
    valid_in: Signal,
    x: Signal,
    valid: Signal,
    y: Signal,
    r: [Reg; 4],
    stall: bool,
}

impl Plus1 {
    fn new(stall: bool) -> Plus1 {
        Plus1 {
            valid_in: Signal::bit("valid_in"),
            x: Signal::new("x", Format::uint(8)),
            valid: Signal::bit("valid"),
            y: Signal::new("y", Format::uint(9)),
            r: [
                Reg::new("v1", Format::uint(1)),
                Reg::new("y1", Format::uint(9)),
                Reg::new("v2", Format::uint(1)),
                Reg::new("y2", Format::uint(9)),
            ],
            stall,
        }
    }
}

impl Module for Plus1 {
    fn instance(&self) -> &str {
        "p"
    }
    fn kind(&self) -> &'static str {
        "plus1"
    }
    fn eval(&mut self) {
        let v = self.valid_in.raw() & i64::from(!self.stall);
        let y = self.x.raw() + 1;
        let (v1, y1) = (self.r[0].q().raw(), self.r[1].q().raw());
        self.r[0].set_next_raw(v);
        self.r[1].set_next_raw(y);
        self.r[2].set_next_raw(v1);
        self.r[3].set_next_raw(y1);
        self.valid.set_bits(self.r[2].q().bits());
        self.y.set_bits(self.r[3].q().bits());
    }
    fn tick(&mut self, reset: bool) {
        for r in &mut self.r {
            r.tick(reset);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter("p", "plus1");
        hdl::signals!(v; Input: self.valid_in, self.x; Output: self.valid, self.y);
        v.leave();
    }
}

struct Drv;
impl Driver<Plus1> for Drv {
    type Txn = u8;
    fn drive(&mut self, dut: &mut Plus1, t: Option<&u8>) {
        dut.valid_in.set_bool(t.is_some());
        dut.x.set_bits(u64::from(t.copied().unwrap_or(0)));
    }
}
struct Mon;
impl Monitor<Plus1> for Mon {
    type Txn = u16;
    fn sample(&mut self, dut: &Plus1) -> Option<u16> {
        dut.valid.is_high().then(|| dut.y.bits() as u16)
    }
}

fn bench(
    stall: bool,
    pacing: &mut Pacing,
    n: usize,
) -> (Result<RunStats, Timeout>, Scoreboard<u16, u16>) {
    let mut sim = Sim::new(Plus1::new(stall)).check_schedule(true);
    sim.reset(1);
    let mut sb = Scoreboard::new(|e: &u16, a: &u16| {
        if e == a {
            Ok(())
        } else {
            Err("differs".into())
        }
    });
    let stim = Stimulus::new(Seed(7)).draw_n(&proptest::num::u8::ANY, n);
    let r = run(
        &mut sim,
        &mut Drv,
        &mut Mon,
        stim,
        n as u64,
        pacing,
        Watchdog::cycles(1000),
        |_, ev| match ev {
            Event::Sent { txn, .. } => sb.expect(u16::from(*txn) + 1),
            Event::Received { cycle, txn } => {
                sb.observe(cycle, txn);
            }
        },
    );
    (r, sb)
}

#[test]
fn full_rate_latency_two() {
    let (r, sb) = bench(false, &mut Pacing::full(), 100);
    let st = r.unwrap();
    assert!(sb.passed());
    assert_eq!((st.sent, st.received), (100, 100));
    assert_eq!((st.min_latency, st.max_latency), (Some(2), Some(2)));
    assert_eq!(st.cycles, 102, "one per clock after a 2-cycle fill");
}

#[test]
fn random_pacing_keeps_order() {
    let (r, sb) = bench(false, &mut Pacing::random(300, Seed(3)), 200);
    let st = r.unwrap();
    assert!(sb.passed());
    assert!(st.cycles > 250, "idle cycles were inserted: {}", st.cycles);
    assert_eq!(st.max_latency, Some(2));
}

#[test]
fn watchdog_stops_a_hung_design() {
    let (r, _) = bench(true, &mut Pacing::full(), 10);
    let t = r.unwrap_err();
    assert_eq!(t.received, 0);
    assert_eq!(t.sent, 10);
    assert!(t.to_string().contains("1000 cycles"), "{t}");
}
