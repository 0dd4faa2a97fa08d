//! Address unit 150: every position of a range, both modes, against floor arithmetic.

use hdl::fx::Format;
use hdl::kernel::{Module, Sim};
use units::bump::address_150::AddressUnit;

#[test]
fn every_position_both_modes() {
    for (pos_frac, f) in [(8u32, 8u32), (10, 8), (4, 4), (16, 16)] {
        let pos = Format::signed(16 + pos_frac, pos_frac as i32);
        let mut sim = Sim::new(AddressUnit::new("addr", pos, f).unwrap()).check_schedule(true);
        let scale = f64::from(1u32 << pos_frac);
        let lim = 5i64 << pos_frac;
        let mut prev = None;
        for raw in (-lim..lim).chain([pos.min_raw() as i64 + 1, pos.max_raw() as i64]) {
            for colour in [false, true] {
                sim.dut.u.set_raw(raw);
                sim.dut.v.set_raw(-raw - 1);
                sim.dut.colour.set_bool(colour);
                sim.step();
                sim.eval();
                // Golden: U' = U - 1/2 in colour mode; Ui = floor(U'); blend = floor(frac * 2^F) / 2^F.
                let check = |x: i64, ui: i64, ub: u64| {
                    let up = x as f64 / scale - if colour { 0.5 } else { 0.0 };
                    let want_i = up.floor();
                    let want_b = ((up - want_i) * f64::from(1u32 << f)).floor();
                    assert_eq!(ui as f64, want_i, "pos {x} colour {colour}");
                    assert_eq!(ub as f64, want_b, "pos {x} colour {colour}");
                };
                check(raw, sim.dut.ui.raw(), sim.dut.ub.bits());
                check(-raw - 1, sim.dut.vj.raw(), sim.dut.vb.bits());
                prev = Some(raw);
            }
        }
        assert!(prev.is_some());
    }
}

#[test]
fn latency_one() {
    let pos = Format::signed(24, 8);
    let mut a = AddressUnit::new("addr", pos, 8).unwrap();
    a.u.set_raw(0x180);
    a.eval();
    assert_eq!(a.ui.raw(), 0, "registered: nothing before the edge");
    a.tick(false);
    a.eval();
    assert_eq!((a.ui.raw(), a.ub.bits()), (1, 0x80));
}
