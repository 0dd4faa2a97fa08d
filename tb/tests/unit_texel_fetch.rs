//! Texel fetch unit 151: the 3x3 grid for every coordinate of a range around a small map, in
//! every border mode, against the golden model's border addressing.

use golden::bump::{Border as GB, Heights};
use hdl::fx::Format;
use hdl::kernel::Sim;
use units::bump::height_map::HeightMap;
use units::bump::params::Border;
use units::bump::texel_fetch_151::TexelFetch;

#[test]
fn grid_in_every_border_mode() {
    let fmt = Format::unsigned(8, 2);
    // Power-of-two sides take the modulo as a mask, the others divide: both kinds, both axes.
    for (w, h) in [(5u32, 3u32), (2, 2), (7, 4), (4, 8)] {
        let t: Vec<u8> = (0..w * h).map(|k| (k * 37 % 251) as u8).collect();
        let map = HeightMap::new(w, h, fmt, t.clone()).unwrap();
        let gold = Heights::from_raw(w as usize, h as usize, &t, 0);
        for (b, gb) in [
            (Border::Wrap, GB::Wrap),
            (Border::Clamp, GB::Clamp),
            (Border::Mirror, GB::Mirror),
            (Border::Constant(77), GB::Constant(77.0)),
        ] {
            let mut sim =
                Sim::new(TexelFetch::new("fetch", map.clone(), b, Format::sint(17)).unwrap())
                    .check_schedule(true);
            for j in -13i64..13 {
                for i in -13i64..13 {
                    sim.dut.ui.set_raw(i);
                    sim.dut.vj.set_raw(j);
                    sim.step();
                    sim.eval();
                    for (k, s) in sim.dut.h.iter().enumerate() {
                        let (di, dj) = (k as i64 % 3 - 1, k as i64 / 3 - 1);
                        assert_eq!(
                            f64::from(s.bits() as u32),
                            gold.texel(i + di, j + dj, gb),
                            "{w}x{h} {b} ({i},{j}) texel {k}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn maps_are_validated() {
    let fmt = Format::unsigned(4, 1);
    assert!(
        HeightMap::new(1, 5, fmt, vec![0; 5]).is_err(),
        "1-texel-wide map"
    );
    assert!(HeightMap::new(2, 2, fmt, vec![0; 3]).is_err());
    assert!(
        HeightMap::new(2, 2, fmt, vec![0, 0, 0, 16]).is_err(),
        "texel beyond 4 bits"
    );
    assert!(HeightMap::new(2, 2, fmt, vec![0, 0, 0, 15]).is_ok());
}
