//! Tangent unit 155 against the real-valued formulas of para. 0062-0075 (with the factor 2),
//! and normal unit 156 against f64 normalisation, on seeded random inputs.

use golden::rsqrt::error_bound_ulps;
use hdl::kernel::Sim;
use proptest::prelude::*;
use units::bump::normal_156::Normal;
use units::bump::params::{BumpParams, Filter, HeightTexel};
use units::bump::tangent_155::{Tangent, TangentIn};
use verif::{seeded_runner, seeded_stimulus};

/// A parameter at either end of its range or anywhere between.
fn range(lo: u32, hi: u32) -> impl Strategy<Value = u32> {
    prop_oneof![Just(lo), Just(hi), lo..=hi]
}

/// Every width parameter unit 155 reads, ends of the ranges included, and each variant.
fn tangent_params() -> impl Strategy<Value = BumpParams> {
    let widths = (range(4, 16), range(8, 24), range(1, 12), range(0, 16));
    let kinds = (any::<bool>(), any::<bool>(), any::<bool>(), any::<bool>());
    (widths, kinds, 0u32..=40).prop_map(|((f, tf, si, sf), (four, blinn, tri, exact), bf)| {
        let mut p = BumpParams {
            blend_bits: f,
            pos_frac: f,
            tangent_frac: tf,
            scale_int: si,
            scale_frac: sf,
            height: if four {
                HeightTexel::Bits4
            } else {
                HeightTexel::Bits8
            },
            filter: if blinn {
                Filter::Blinn
            } else {
                Filter::BSpline
            },
            trilinear: tri,
            ..BumpParams::default()
        };
        let lo = p.replicate_fmt().frac() as u32;
        p.bilinear_frac = (!exact).then_some(lo + bf % (41 - lo));
        p
    })
}

/// Para. 0062-0075 in reals for one level: `(dH/du, dH/dv, H)` from R, G, B, A and `(su, sv)`.
fn level_formulas(c: [f64; 4], su: f64, sv: f64, blinn: bool) -> [f64; 3] {
    let [r, g, b, a] = c;
    let lerp = |x: f64, y: f64, s: f64| x + s * (y - x);
    if blinn {
        [g - r, b - r, r]
    } else {
        [
            2.0 * lerp(g - r, a - b, sv),
            2.0 * lerp(b - r, a - g, su),
            lerp(lerp(r, g, su), lerp(b, a, su), sv),
        ]
    }
}

#[test]
fn tangent_formulas() {
    let mut runner = seeded_runner("tangent 155", 5000);
    let inputs = (tangent_params(), any::<[u64; 8]>(), any::<[u64; 6]>());
    runner
        .run(&inputs, |(p, raw, factors)| {
            prop_assert_eq!(p.validate(), Ok(()));
            let mut t = Tangent::new("tan", &p);
            let (bl, f, sc) = (p.bilinear_fmt(), p.blend_bits, p.scale_fmt());
            let blend = |k: usize| (factors[k] % (1 << f)) as i64;
            let x = TangentIn {
                rgba: raw.map(|v| (v & bl.max_raw() as u64) as i64),
                tu: blend(0),
                tv: blend(1),
                tu1: blend(2),
                tv1: blend(3),
                lod: blend(4),
                scale: (factors[5] & sc.max_raw() as u64) as i64,
            };
            let (du, dv, h) = t.compute(&x);
            let real = |v: i64, frac: i32| v as f64 / f64::from(frac).exp2();
            let c = x.rgba.map(|v| real(v, bl.frac()));
            let fr = |v: i64| real(v, f as i32);
            let mut want =
                level_formulas([c[0], c[1], c[2], c[3]], fr(x.tu), fr(x.tv), t_blinn(&p));
            if p.trilinear {
                // Para. 0081: the coarser level's slopes are per coarse texel, half as steep.
                let one =
                    level_formulas([c[4], c[5], c[6], c[7]], fr(x.tu1), fr(x.tv1), t_blinn(&p));
                let l = fr(x.lod);
                want = [
                    want[0] + l * (one[0] / 2.0 - want[0]),
                    want[1] + l * (one[1] / 2.0 - want[1]),
                    want[2] + l * (one[2] - want[2]),
                ];
            }
            let k = real(x.scale, sc.frac());
            let (tan, hf) = (p.tangent_fmt(), p.height_out_fmt());
            let lsb = real(1, p.tangent_frac as i32);
            let (tmax, hmax) = (
                real(tan.max_raw() as i64, tan.frac()),
                real(hf.max_raw() as i64, hf.frac()),
            );
            let clamped = [
                (want[0] * k).clamp(-tmax, tmax),
                (want[1] * k).clamp(-tmax, tmax),
                (want[2] * k).clamp(0.0, hmax),
            ];
            for (got, want) in [du, dv, h].into_iter().zip(clamped) {
                let got = got as f64 * lsb;
                prop_assert!(
                    (got - want).abs() <= lsb / 2.0 + want.abs() * 1e-15,
                    "{p:?} {x:?}: got {got} want {want}"
                );
            }
            Ok(())
        })
        .unwrap();
}

fn t_blinn(p: &BumpParams) -> bool {
    p.filter == Filter::Blinn
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
