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
    pacing: Pacing,
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
    let r = run_scored(
        &mut sim,
        &mut Drv,
        &mut Mon,
        stim,
        &mut RunSpec::new(n as u64, 1000).pacing(pacing),
        |_, ev| match ev {
            Scored::Sent { txn, .. } => sb.expect(u16::from(*txn) + 1),
            Scored::Received { cycle, txn } => {
                sb.observe(cycle, txn);
            }
        },
    );
    (r, sb)
}

#[test]
fn full_rate_latency_two() {
    let (r, sb) = bench(false, Pacing::full(), 100);
    let st = r.unwrap();
    assert!(sb.passed());
    assert_eq!((st.sent, st.received), (100, 100));
    assert_eq!((st.min_latency, st.max_latency), (Some(2), Some(2)));
    assert_eq!(st.cycles, 102, "one per clock after a 2-cycle fill");
    assert_eq!(st.throughput(), 100.0 / 102.0);
    assert_eq!(sb.pending(), 0);
    assert_eq!(
        RunStats::default().throughput(),
        0.0,
        "no cycles, no division"
    );
}

#[test]
fn random_pacing_keeps_order() {
    let (r, sb) = bench(false, Pacing::random(300, Seed(3)), 200);
    let st = r.unwrap();
    assert!(sb.passed());
    assert!(st.cycles > 250, "idle cycles were inserted: {}", st.cycles);
    assert_eq!(st.max_latency, Some(2));
}

#[test]
fn watchdog_stops_a_hung_design() {
    let (r, sb) = bench(true, Pacing::full(), 10);
    assert_eq!(sb.pending(), 10, "all ten still expected");
    let t = r.unwrap_err();
    assert_eq!(t.received, 0);
    assert_eq!(t.sent, 10);
    assert!(t.to_string().contains("1000 cycles"), "{t}");
    assert_eq!(t.cycle, 1 + 1000, "a thousand cycles after the reset cycle");
}

/// The wall-clock limit is read every 1024 cycles, and an exhausted one stops the run.
#[test]
fn the_wall_clock_watchdog_fires() {
    let t0 = std::time::Instant::now() - std::time::Duration::from_millis(5);
    let w = Watchdog {
        max_cycles: 1 << 20,
        max_wall: std::time::Duration::from_millis(1),
    };
    assert_eq!(w.check(1023, &t0), Ok(()), "not read between");
    assert!(w.check(2048, &t0).is_err());
    assert!(
        Watchdog::cycles(10).check(2048, &t0).is_err(),
        "cycles first"
    );
}

/// A two-entry elastic buffer that adds 1, with ready/valid on both sides: `in_ready` while
/// it has room, `out_valid` while it holds an entry, an entry leaves when `out_ready`.
struct Elastic {
    in_valid: Signal,
    in_ready: Signal,
    x: Signal,
    out_valid: Signal,
    out_ready: Signal,
    y: Signal,
    count: Reg,
    slot: [Reg; 2],
}

impl Elastic {
    fn new() -> Elastic {
        let w = Format::uint(9);
        Elastic {
            in_valid: Signal::bit("in_valid"),
            in_ready: Signal::bit("in_ready"),
            x: Signal::new("x", Format::uint(8)),
            out_valid: Signal::bit("out_valid"),
            out_ready: Signal::bit("out_ready"),
            y: Signal::new("y", w),
            count: Reg::new("count", Format::uint(2)),
            slot: [Reg::new("slot0", w), Reg::new("slot1", w)],
        }
    }
}

impl Module for Elastic {
    fn instance(&self) -> &str {
        "e"
    }
    fn kind(&self) -> &'static str {
        "elastic"
    }
    fn eval(&mut self) {
        let n = self.count.q().uint();
        self.in_ready.set_bool(n < 2);
        self.out_valid.set_bool(n > 0);
        self.y.set_bits(self.slot[0].q().bits());
        let pop = n > 0 && self.out_ready.is_high();
        let push = n < 2 && self.in_valid.is_high();
        let (s0, s1) = (self.slot[0].q().bits(), self.slot[1].q().bits());
        let new = self.x.bits() + 1;
        // After a pop the second entry moves up; a push fills the first free slot.
        let (mut a, mut b, mut m) = if pop { (s1, 0, n - 1) } else { (s0, s1, n) };
        if push {
            if m == 0 {
                a = new;
            } else {
                b = new;
            }
            m += 1;
        }
        self.slot[0].set_next_bits(a);
        self.slot[1].set_next_bits(b);
        self.count.set_next_bits(m);
    }
    fn tick(&mut self, reset: bool) {
        self.count.tick(reset);
        for r in &mut self.slot {
            r.tick(reset);
        }
    }
    fn visit(&self, v: &mut dyn Visitor) {
        v.enter("e", "elastic");
        hdl::signals!(v; Input: self.in_valid, self.x, self.out_ready;
            Output: self.in_ready, self.out_valid, self.y; Reg: self.count, self.slot[0], self.slot[1]);
        v.leave();
    }
}

struct EDrv;
impl Driver<Elastic> for EDrv {
    type Txn = u8;
    fn drive(&mut self, dut: &mut Elastic, t: Option<&u8>) {
        dut.in_valid.set_bool(t.is_some());
        dut.x.set_bits(u64::from(t.copied().unwrap_or(0)));
    }
    fn accepted(&self, dut: &Elastic) -> bool {
        dut.in_ready.is_high()
    }
}
struct EMon;
impl Monitor<Elastic> for EMon {
    type Txn = u16;
    fn ready(&mut self, dut: &mut Elastic, ready: bool) {
        dut.out_ready.set_bool(ready);
    }
    fn sample(&mut self, dut: &Elastic) -> Option<u16> {
        (dut.out_valid.is_high() && dut.out_ready.is_high()).then(|| dut.y.bits() as u16)
    }
}

fn elastic(pacing: Pacing, sink: Pacing, n: usize) -> (RunStats, Vec<u16>, Vec<u16>) {
    let mut sim = Sim::new(Elastic::new()).check_schedule(true);
    sim.reset(1);
    let stim = Stimulus::new(Seed(11)).draw_n(&proptest::num::u8::ANY, n);
    let want: Vec<u16> = stim.iter().map(|&x| u16::from(x) + 1).collect();
    let mut got: Vec<u16> = Vec::new();
    let mut spec = RunSpec::new(n as u64, 100 * n as u64)
        .pacing(pacing)
        .sink(sink);
    let st = run(&mut sim, &mut EDrv, &mut EMon, stim, &mut spec, |_, ev| {
        if let Event::Received { txn, .. } = ev {
            got.push(txn);
        }
    })
    .unwrap();
    (st, want, got)
}

#[test]
fn backpressure_on_both_sides_loses_and_duplicates_nothing() {
    for (idle_in, idle_out) in [(0, 0), (0, 600), (600, 0), (400, 700)] {
        let (st, want, got) = elastic(
            Pacing::random(idle_in, Seed(5)),
            Pacing::random(idle_out, Seed(6)),
            500,
        );
        assert_eq!(got, want, "idle {idle_in}/{idle_out} per mille");
        assert_eq!((st.sent, st.received), (500, 500));
        if idle_out > 0 {
            // The sink stalled the buffer, so the driver had to hold transactions.
            assert!(st.busy_cycles > st.sent, "{st:?}");
        }
    }
}

#[test]
fn full_rate_through_the_elastic_buffer() {
    let (st, want, got) = elastic(Pacing::full(), Pacing::full(), 300);
    assert_eq!(got, want);
    assert_eq!(st.cycles, 301, "one per clock, latency 1");
    assert_eq!(st.busy_cycles, 300, "never stalled");
}

#[test]
fn interval_pacing_spaces_transfers() {
    let (st, want, got) = elastic(Pacing::every(4), Pacing::full(), 50);
    assert_eq!(got, want);
    assert_eq!(st.cycles, 4 * 49 + 2);
}

/// A second port beside the stream: driven before every settle, shown the settled design
/// after, in the same cycles as the stream; here it stalls the pipeline for 10 cycles, which
/// the stream's latency shows.
#[test]
fn a_background_port_is_driven_every_cycle_beside_the_stream() {
    struct Stall {
        cycles: Vec<u64>,
        outputs_seen: u64,
    }
    impl Background<Plus1> for Stall {
        fn drive(&mut self, dut: &mut Plus1, cycle: u64) {
            self.cycles.push(cycle);
            dut.stall = (3..13).contains(&cycle);
        }
        fn settled(&mut self, dut: &Plus1, _cycle: u64) {
            self.outputs_seen += u64::from(dut.valid.is_high());
        }
    }
    let mut sim = Sim::new(Plus1::new(false)).check_schedule(true);
    sim.reset(1);
    let start = sim.cycle();
    let mut side = Stall {
        cycles: Vec::new(),
        outputs_seen: 0,
    };
    let mut got: Vec<u16> = Vec::new();
    let mut spec = RunSpec::new(5, 1000);
    let st = run_beside(
        &mut sim,
        &mut Drv,
        &mut Mon,
        [1u8, 2, 3, 4, 5],
        &mut spec,
        &mut side,
        |_, ev| {
            if let Event::Received { txn, .. } = ev {
                got.push(txn);
            }
        },
    );
    // Transactions entering while stalled are dropped by Plus1: only those before cycle 3
    // and after 12 come out; the stream waits for 5 and times out.
    assert!(st.is_err());
    assert_eq!(side.cycles.first(), Some(&start));
    assert!(side.cycles.windows(2).all(|w| w[1] == w[0] + 1));
    assert_eq!(side.outputs_seen, got.len() as u64);
    assert!(got.len() < 5 && !got.is_empty(), "{got:?}");
}

/// A one-entry buffer with backpressure on both sides, its ports two streams: it adds 1.
struct Skid {
    input: hdl::kernel::Stream<Word>,
    output: hdl::kernel::Stream<Word>,
    full: Reg,
    data: Reg,
}

/// A one-field payload bundle.
#[derive(Clone, Debug)]
struct Word {
    x: Signal,
}

impl hdl::kernel::declared::Signals for Word {
    fn visit_signals(&self, dir: hdl::kernel::Dir, v: &mut dyn Visitor) {
        v.signal(dir, &self.x);
    }
}

impl hdl::kernel::Payload<Word> for u16 {
    fn put(&self, port: &mut Word) {
        port.x.set_bits(u64::from(*self));
    }
    fn take(port: &Word) -> u16 {
        port.x.bits() as u16
    }
}

impl Skid {
    fn new() -> Skid {
        let word = |name, bits| Word {
            x: Signal::new(name, Format::uint(bits)),
        };
        Skid {
            input: hdl::kernel::Stream::new("in_valid", "in_ready", word("x", 8)),
            output: hdl::kernel::Stream::new("out_valid", "out_ready", word("y", 9)),
            full: Reg::new("full", Format::uint(1)),
            data: Reg::new("data", Format::uint(8)),
        }
    }
}

impl Module for Skid {
    fn instance(&self) -> &str {
        "skid"
    }
    fn kind(&self) -> &'static str {
        "skid"
    }
    fn eval(&mut self) {
        let full = self.full.q().is_high();
        self.output.valid.set_bool(full);
        self.output.payload.x.set_bits(self.data.q().bits() + 1);
        let taken = full && self.output.ready.is_high();
        self.input.ready.set_bool(!full || taken);
        if self.input.fire() {
            self.full.set_next_bool(true);
            self.data.set_next_bits(self.input.payload.x.bits());
        } else if taken {
            self.full.set_next_bool(false);
        }
    }
    fn tick(&mut self, reset: bool) {
        self.full.tick(reset);
        self.data.tick(reset);
    }
    fn visit(&self, v: &mut dyn Visitor) {
        use hdl::kernel::declared::Signals;
        v.enter("skid", "skid");
        self.input.visit_signals(hdl::kernel::Dir::Input, v);
        self.output.visit_signals(hdl::kernel::Dir::Output, v);
        v.reg(&self.full);
        v.reg(&self.data);
        v.leave();
    }
}

/// The generic stream driver and monitor on a unit with backpressure on both sides, each
/// paced at random: every word arrives once, in order, plus one; a stream's `ready` is
/// visited the other way from its data.
#[test]
fn stream_driver_and_monitor_carry_every_word_through_backpressure() {
    use hdl::kernel::{signal_dirs, Dir};
    let mut sim = Sim::new(Skid::new()).check_schedule(true);
    sim.reset(1);
    let words: Vec<u16> = (0..300).map(|k| (k * 37 % 256) as u16).collect();
    let mut spec = RunSpec::new(300, 3000)
        .pacing(Pacing::random(400, Seed(5)))
        .sink(Pacing::random(400, Seed(6)));
    let mut got: Vec<u16> = Vec::new();
    let mut driver = StreamDriver::new(crate::stream!(Skid, input));
    let mut monitor = StreamMonitor::new(crate::stream!(Skid, output));
    let st = run_scored(
        &mut sim,
        &mut driver,
        &mut monitor,
        words.clone(),
        &mut spec,
        |_, ev| {
            if let Scored::Received { txn, .. } = ev {
                got.push(txn);
            }
        },
    )
    .unwrap();
    let want: Vec<u16> = words.iter().map(|w| w + 1).collect();
    assert_eq!(got, want);
    assert!(st.cycles > 300, "both sides stalled: {} cycles", st.cycles);
    let dirs = signal_dirs(&sim.dut);
    assert_eq!(
        dirs[..6],
        [
            Dir::Input,
            Dir::Input,
            Dir::Output,
            Dir::Output,
            Dir::Output,
            Dir::Input
        ]
    );
}
