//! DRAM 604 and control unit 607: the document's timing figures, data integrity, the timing
//! checks of the DRAM model, and `texrtl dram`.

use hdl::kernel::Sim;
use tb::runs::dram::{drive_dram, run_trace, settle};
use units::texmem::control_607::DramCtrl;
use units::texmem::dram_604::{Dram, DramParams};

#[test]
fn page_mode_and_fault_timing_reproduce_the_document() {
    let p = DramParams::default();
    // Peak: every read a page hit after the first: 30 ns each -> 33.3 M texels/s.
    let n = 1000u64;
    let hits: Vec<u64> = (0..n).map(|k| k % 512).collect();
    let s = run_trace(p, &hits, None).unwrap();
    assert_eq!((s.reads, s.page_faults, s.page_hits), (n, 1, n - 1));
    assert_eq!(
        s.ns,
        30 * n + 30,
        "30 ns per access, 30 ns more for the one fault"
    );
    assert_eq!((s.violations, s.data_errors), (0, 0));
    assert!(
        (s.reads_per_second / 1e6 - 33.3).abs() < 0.05,
        "{}",
        s.reads_per_second
    );
    // Scanlines of 8 texels with 2 page faults each: 300 ns per scanline -> 26.7 M texels/s.
    let mut trace = Vec::new();
    for line in 0..200u64 {
        let (a, b) = (2 * line % 512, (2 * line + 1) % 512);
        for k in 0..4 {
            trace.push(a * 512 + k);
        }
        for k in 0..4 {
            trace.push(b * 512 + k);
        }
    }
    let s = run_trace(p, &trace, None).unwrap();
    assert_eq!(s.page_faults, 400);
    assert_eq!(s.ns, 200 * 300);
    assert!(
        (s.reads_per_second / 1e6 - 26.67).abs() < 0.01,
        "{}",
        s.reads_per_second
    );
    assert_eq!((s.violations, s.data_errors), (0, 0));
}

#[test]
fn random_traces_read_the_right_words_without_violations() {
    let mut stim = verif::seeded_stimulus("dram random");
    for p in [
        DramParams::default(),
        DramParams::one_meg(),
        DramParams {
            t_rp: 1,
            t_rcd: 2,
            t_cas: 2,
            t_cp: 1,
            cycle_ns: 7,
            ..DramParams::default()
        },
    ] {
        let addrs = stim.draw_n(&(0..p.words()), 500);
        let s = run_trace(p, &addrs, None).unwrap();
        assert_eq!(s.reads, 500);
        // The report's page size and time are the controller's own DRAM's.
        let ns = s.cycles * u64::from(p.cycle_ns);
        assert_eq!((s.page_words, s.cycle_ns, s.ns), (p.cols, p.cycle_ns, ns));
        assert_eq!(s.page_hits + s.page_faults, 500);
        assert_eq!((s.violations, s.data_errors), (0, 0), "{p:?}");
        let per = u64::from(p.t_cas + p.t_cp);
        let fault = u64::from(p.t_rp + p.t_rcd);
        assert_eq!(s.cycles, 500 * per + s.page_faults * fault);
    }
}

#[test]
fn the_dram_model_flags_timing_violations() {
    let p = DramParams::default();
    let mut sim = Sim::new(Dram::new("dram", p).unwrap());
    // RAS# low, then CAS# low only one cycle later (t_rcd = 3), held one cycle (t_cas = 3).
    let pins = [
        (true, true),
        (false, true),
        (false, false),
        (false, true),
        (true, true),
        (false, true),
    ];
    for (ras, cas) in pins {
        sim.dut.ras_n.set_bool(ras);
        sim.dut.cas_n.set_bool(cas);
        sim.dut.oe_n.set_bool(true);
        sim.step();
    }
    let d = &sim.dut;
    let text: Vec<String> = d.log().iter().map(|v| v.what.clone()).collect();
    assert!(text.iter().any(|t| t.contains("t_rcd")), "{text:?}");
    assert!(text.iter().any(|t| t.contains("t_cas")), "{text:?}");
    assert!(text.iter().any(|t| t.contains("t_rp")), "{text:?}");
    assert_eq!(d.violations(), 3);
}

/// Drives the pins cycle by cycle: `(ras_n, cas_n, we_n, addr)`; the violations logged.
fn violations(pins: &[(bool, bool, bool, u64)]) -> Vec<String> {
    let mut sim = Sim::new(Dram::new("dram", DramParams::default()).unwrap());
    for &(ras, cas, we, addr) in pins {
        let d = &mut sim.dut;
        d.ras_n.set_bool(ras);
        d.cas_n.set_bool(cas);
        d.we_n.set_bool(we);
        d.oe_n.set_bool(true);
        d.addr.set_bits(addr);
        sim.step();
    }
    assert_eq!(sim.dut.violations(), sim.dut.log().len() as u64);
    sim.dut.log().iter().map(|v| v.what.clone()).collect()
}

/// The model's other rules, each broken once on its own (512 x 512 words, every timing 3
/// cycles): a write, a row or a column beyond the array, CAS# with no open row, a short CAS#
/// precharge; the same cycles with the rules kept log nothing. The back-door load takes
/// exactly the array and no word more.
#[test]
fn the_dram_model_flags_each_rule_it_checks() {
    let open = |row: u64| [(true, true, true, 0), (false, true, true, row)];
    let wait = (false, true, true, 0);
    let cas = |col: u64| [(false, false, true, col); 3];
    // A read of (row, col) with every timing met: RAS# fall, t_rcd, CAS# low t_cas.
    let read = |row: u64, col: u64| {
        let mut v = vec![(true, true, true, 0); 3];
        v.extend(open(row));
        v.extend([wait, wait]);
        v.extend(cas(col));
        v.push(wait);
        v
    };
    assert_eq!(violations(&read(511, 511)), Vec::<String>::new());
    let one = |pins: Vec<(bool, bool, bool, u64)>, what: &str| {
        let v = violations(&pins);
        assert!(v.len() == 1 && v[0].contains(what), "{what}: {v:?}");
    };
    one(read(512, 0), "row 512 beyond 512 rows");
    one(read(0, 512), "column 512 beyond 512 words per page");
    let mut write = read(3, 4);
    write[7].2 = false;
    one(write, "WE# low");
    let mut no_row = vec![(true, true, true, 0); 4];
    no_row.extend([(true, false, true, 0); 3]);
    no_row.push((true, true, true, 0));
    one(no_row, "no open row");
    // Page mode: CAS# high for t_cp cycles between reads is kept, for one cycle it is not.
    let mut page = read(1, 1);
    page.extend([wait, wait]);
    page.extend(cas(2));
    page.push(wait);
    assert_eq!(violations(&page), Vec::<String>::new());
    let mut short = read(1, 1);
    short.extend(cas(2));
    short.push(wait);
    one(short, "CAS# precharge 1 cycles < t_cp 3");
    let mut d = Dram::new("dram", DramParams::default()).unwrap();
    let words = DramParams::default().words();
    assert!(d.load(words - 2, &[1, 2]).is_ok());
    let e = d.load(words - 2, &[1, 2, 3]).unwrap_err();
    assert_eq!(
        e,
        format!(
            "3 words from {} do not fit the DRAM's {words} words",
            words - 2
        )
    );
}

/// A read in flight holds `ready` low for a page fault's cycles: the watchdog says so
/// when its limit comes first, and leaves the run to finish otherwise.
#[test]
fn the_watchdog_fires_only_past_its_limit() {
    let p = DramParams::default();
    let mut sim = Sim::new(DramCtrl::new("control_607", p).unwrap());
    sim.reset(1);
    drive_dram(&mut sim.dut, Some(&700));
    sim.step();
    drive_dram(&mut sim.dut, None);
    let (mut done_at, now) = (None, sim.cycle());
    let said = settle(&mut sim, &mut done_at, now).unwrap_err();
    assert_eq!(
        said,
        format!("watchdog: control unit 607 not ready again by cycle {now}")
    );
    assert_eq!(done_at, None);
    settle(&mut sim, &mut done_at, now + 100).unwrap();
    let worst = u64::from(p.t_rp + p.t_rcd + p.t_cas + p.t_cp);
    let done = done_at.expect("ready again");
    assert!(now < done && done <= now + worst, "{now} {done}");
}
