//! Tangent unit 155 against the real-valued formulas of para. 0062-0075 (with the factor 2),
//! and normal unit 156 against f64 normalisation, on seeded random inputs.

use golden::rsqrt::error_bound_ulps;
use hdl::bump::normal_156::Normal;
use hdl::bump::params::{BumpParams, Filter};
use hdl::bump::tangent_155::Tangent;
use hdl::kernel::Sim;
use proptest::prelude::*;
use verif::{seeded_runner, seeded_stimulus};

#[test]
fn tangent_formulas() {
    let mut runner = seeded_runner("tangent 155", 5000);
    let strat = (
        proptest::array::uniform4(0i64..(64 << 22)),
        0i64..256,
        0i64..256,
        0i64..(1 << 16),
        any::<bool>(),
    );
    runner
        .run(&strat, |(rgba, tu, tv, scale, blinn)| {
            let p = BumpParams {
                filter: if blinn {
                    Filter::Blinn
                } else {
                    Filter::BSpline
                },
                ..BumpParams::default()
            };
            let t = Tangent::new("tan", &p);
            let mut x = hdl::bump::tangent_155::TangentIn {
                tu,
                tv,
                scale,
                ..Default::default()
            };
            x.rgba[..4].copy_from_slice(&rgba);
            let (du, dv, h) = t.compute(&x);
            let fb = p.bilinear_fmt().frac();
            let [r, g, b, a] = rgba.map(|x| x as f64 / (fb as f64).exp2());
            let (su, sv, k) = (tu as f64 / 256.0, tv as f64 / 256.0, scale as f64 / 256.0);
            let lerp = |x: f64, y: f64, s: f64| x + s * (y - x);
            let (wu, wv, wh) = if blinn {
                (g - r, b - r, r)
            } else {
                (
                    2.0 * lerp(g - r, a - b, sv),
                    2.0 * lerp(b - r, a - g, su),
                    lerp(lerp(r, g, su), lerp(b, a, su), sv),
                )
            };
            let lsb = 1.0 / 65536.0;
            for (got, want) in [(du, wu * k), (dv, wv * k), (h, wh * k)] {
                let got = got as f64 * lsb;
                let want = want.clamp(-(2f64.powi(15)) + lsb, 2f64.powi(15) - lsb);
                prop_assert!(
                    (got - want).abs() <= lsb / 2.0 + want.abs() * 1e-15,
                    "got {} want {}",
                    got,
                    want
                );
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn normal_unit_normalises() {
    let p = BumpParams::default();
    let mut sim = Sim::new(Normal::new("normal", &p).unwrap()).check_schedule(true);
    let lat = sim.dut.latency();
    assert_eq!(lat, 4);
    let mut stim = seeded_stimulus("normal 156");
    let s = (
        -(1i64 << 31) + 1..(1i64 << 31),
        -(1i64 << 31) + 1..(1i64 << 31),
        0u32..31,
    );
    let tangents: Vec<(i64, i64)> = (0..3000)
        .map(|_| {
            let (a, b, sh) = stim.draw(&s);
            (a >> sh, b >> (sh / 2))
        })
        .chain([
            (0, 0),
            ((1 << 31) - 1, 0),
            (-(1 << 31) + 1, (1 << 31) - 1),
            (1, -1),
        ])
        .collect();
    let tol = (error_bound_ulps(p.rsqrt.table_bits, p.rsqrt.iterations, p.rsqrt.y_frac)
        * (-(p.rsqrt.y_frac as f64)).exp2()
        + 2f64.powi(-22))
        + 0.5 / 65536.0;
    let mut worst = 0.0f64;
    for k in 0..tangents.len() + lat {
        let (du, dv) = *tangents.get(k).unwrap_or(&(0, 0));
        sim.dut.du.set_raw(du);
        sim.dut.dv.set_raw(dv);
        sim.eval();
        if k >= lat {
            let (du, dv) = tangents[k - lat];
            let n = [-(du as f64), -(dv as f64), 65536.0];
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let got = [&sim.dut.nx, &sim.dut.ny, &sim.dut.nz].map(|s| s.raw() as f64 / 65536.0);
            for c in 0..3 {
                let e = (got[c] - n[c] / l).abs();
                worst = worst.max(e);
                assert!(
                    e <= tol,
                    "({du},{dv}) component {c}: {} vs {} (tol {tol:e})",
                    got[c],
                    n[c] / l
                );
            }
        }
        sim.tick();
    }
    eprintln!("normal 156: worst component error {worst:.3e} (tolerance {tol:.3e})");
}
