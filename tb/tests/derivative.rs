//! Para. 0086's derivative filters: the testbench, and the linearity the patent relies on.

use tb::derivative::{filters, DerivativeTb};
use units::bump::derivative_0086::DerivFilter;
use verif::{Seed, Stimulus};

#[test]
fn the_testbench_passes_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(400),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&DerivativeTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.failures, r.mismatch_log);
    assert!(r.coverage_percent > 99.0, "{:?}", r.unhit);
}

/// Filtering bilinearly interpolated heights equals interpolating the filtered heights: for
/// every filter, random heights and weights, in exact integers.
#[test]
fn filtering_bilinear_samples_is_bilinear_of_filtered_samples() {
    let mut stim = Stimulus::new(Seed(86));
    let side = 16i64;
    let heights: Vec<i64> = stim.draw_n(&(0i64..1024), (side * side) as usize);
    let h = |x: i64, y: i64| heights[(y.rem_euclid(side) * side + x.rem_euclid(side)) as usize];
    let mut all = filters().to_vec();
    all.push(DerivFilter::Table(vec![100, -7, 3]));
    for f in all {
        for _ in 0..300 {
            let (i, j) = (stim.draw(&(-20i64..20)), stim.draw(&(-20i64..20)));
            let (a, b) = (stim.draw(&(0i64..=256)), stim.draw(&(0i64..=256)));
            let w = [
                (0, 0, (256 - a) * (256 - b)),
                (1, 0, a * (256 - b)),
                (0, 1, (256 - a) * b),
                (1, 1, a * b),
            ];
            // Bilinear of the filtered: the filter at the four centres, weighted.
            let rhs = w.iter().fold((0, 0), |acc, &(dx, dy, wt)| {
                let (gx, gy) = f.at(&h, i + dx, j + dy);
                (acc.0 + wt * gx, acc.1 + wt * gy)
            });
            // The filter of the bilinear: heights interpolated at every offset, then filtered.
            let bil = |x: i64, y: i64| {
                w.iter()
                    .map(|&(dx, dy, wt)| wt * h(x + dx, y + dy))
                    .sum::<i64>()
            };
            let lhs = f.at(&bil, i, j);
            assert_eq!(lhs, rhs, "{f:?}");
        }
    }
}
