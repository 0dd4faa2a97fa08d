//! Para. 0087's bi-quadratic colour: the testbench and the properties of a B-spline.

use tb::biquadratic::{test_map, BiquadraticTb};
use units::bump::biquadratic_0087::{filter, sums, ColourMap, POS_FRAC};
use units::bump::params::Border;
use verif::{Seed, Stimulus};

#[test]
fn the_testbench_passes_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(400),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&BiquadraticTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.failures, r.mismatch_log);
    assert!(r.coverage_percent > 99.0, "{:?}", r.unhit);
}

/// On a linear ramp the exact sum (before its rounding) is the ramp at the sample point
/// (t quantised): the quadratic B-spline reproduces linear functions; a constant map gives
/// its constant; every result lies within the min and max of its 3 x 3.
#[test]
fn ramps_constants_and_the_neighbourhood_bound() {
    let n = 16u32;
    // R = 5x + 3y + 10 (never past 255 inside), G constant 77, B = 2x.
    let rgb = (0..n * n)
        .flat_map(|k| {
            [
                (5 * (k % n) + 3 * (k / n) + 10) as u8,
                77,
                (2 * (k % n)) as u8,
            ]
        })
        .collect();
    let ramp = ColourMap {
        width: n,
        height: n,
        rgb,
        border: Border::Clamp,
    };
    let mut stim = Stimulus::new(Seed(87));
    for _ in 0..2000 {
        // Inside, a texel from the edges, so that the clamp does not bend the ramp.
        let (u, v) = (
            stim.draw(&(2i64 << 16..14 << 16)),
            stim.draw(&(2i64 << 16..14 << 16)),
        );
        let s = sums(&ramp, u, v);
        // The ramp at the point: texel centre x + 1/2 holds 5x..., so R(p) = 5 (p - 1/2) + ...,
        // p = the nearest texel + t (t of 8 bits): exact in units of 2^-34.
        let p = |c: i64| ((c >> (POS_FRAC - 8)) << 26) - (1 << 33);
        let want_r = 5 * p(u) + 3 * p(v) + (10 << 34);
        assert_eq!(s[0], want_r, "({u}, {v})");
        assert_eq!(s[1], 77 << 34);
        assert_eq!(s[2], 2 * p(u));
    }
    let m = test_map(16, Border::Wrap, &mut stim);
    for _ in 0..2000 {
        let (u, v) = (stim.draw(&(0i64..16 << 16)), stim.draw(&(0i64..16 << 16)));
        let got = filter(&m, u, v);
        let (i, j) = (u >> 16, v >> 16);
        #[allow(clippy::needless_range_loop)] // channel c of the texels and of the result
        for c in 0..3 {
            let near: Vec<u8> = (-1..=1)
                .flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
                .map(|(dx, dy)| m.texel(i + dx, j + dy)[c])
                .collect();
            let (lo, hi) = (*near.iter().min().unwrap(), *near.iter().max().unwrap());
            assert!(
                got[c] >= lo && got[c] <= hi,
                "{c}: {} not in {lo}..={hi}",
                got[c]
            );
        }
        // At a texel centre: (a + 6b + c)/8 along each axis, i.e. the 1-6-1 tensor.
        let centre = filter(&m, (i << 16) + (1 << 15), (j << 16) + (1 << 15));
        #[allow(clippy::needless_range_loop)] // channel c of the texels and of the result
        for c in 0..3 {
            let w = [1i64, 6, 1];
            let mut sum = 0;
            for dy in 0..3 {
                for dx in 0..3 {
                    sum +=
                        w[dx] * w[dy] * i64::from(m.texel(i + dx as i64 - 1, j + dy as i64 - 1)[c]);
                }
            }
            assert_eq!(i64::from(centre[c]), (sum + 32) >> 6);
        }
    }
}
