//! Bilinear units 65-68: exact against the real-valued blend, and the D3D11 rules as properties
//! (the result lies between the smallest and largest texel, and is monotonic in each blend
//! factor), also with a narrowed output that rounds.

use hdl::fx::Format;
use proptest::prelude::*;
use units::bump::bilinear_65_68::Bilinear;
use verif::seeded_runner;

fn unit(out_frac: Option<u32>) -> Bilinear {
    let texel = Format::unsigned(10, 4);
    let blend = Format::unsigned(9, 9);
    let f = out_frac.unwrap_or(4 + 18);
    Bilinear::new("bl", texel, blend, Format::unsigned(6 + f, f as i32)).unwrap()
}

fn eval(b: &mut Bilinear, p: [i64; 4], s: i64, t: i64, out_frac: u32) -> f64 {
    b.compute(p, s, t) as f64 / f64::from(1u32 << out_frac)
}

#[test]
fn exact_and_d3d11_rules() {
    let mut runner = seeded_runner("bilinear rules", 3000);
    let strat = (
        proptest::array::uniform4(0i64..1024),
        0i64..512,
        0i64..512,
        prop_oneof![Just(None), Just(Some(6u32)), Just(Some(10u32))],
    );
    runner
        .run(&strat, |(p, s, t, of)| {
            let mut b = unit(of);
            let f = of.unwrap_or(22);
            let q = eval(&mut b, p, s, t, f);
            let pf = p.map(|x| x as f64 / 16.0);
            let (sf, tf) = (s as f64 / 512.0, t as f64 / 512.0);
            let exact = (1.0 - tf) * ((1.0 - sf) * pf[0] + sf * pf[1])
                + tf * ((1.0 - sf) * pf[2] + sf * pf[3]);
            let lsb = (-(f as f64)).exp2();
            prop_assert!(
                (q - exact).abs() <= lsb / 2.0 + 1e-12,
                "q {} exact {}",
                q,
                exact
            );
            if of.is_none() {
                prop_assert_eq!(q, exact);
            }
            let (lo, hi) = (
                pf.iter().cloned().fold(f64::MAX, f64::min),
                pf.iter().cloned().fold(f64::MIN, f64::max),
            );
            prop_assert!(q >= lo && q <= hi);
            // Monotonic in s (at this t) and in t (at this s): sweep one factor.
            for (which, fixed) in [(0, t), (1, s)] {
                let seq: Vec<f64> = (0..512)
                    .step_by(7)
                    .map(|x| {
                        if which == 0 {
                            eval(&mut b, p, x, fixed, f)
                        } else {
                            eval(&mut b, p, fixed, x, f)
                        }
                    })
                    .collect();
                let up = seq.windows(2).all(|w| w[1] >= w[0]);
                let down = seq.windows(2).all(|w| w[1] <= w[0]);
                prop_assert!(up || down, "not monotonic: {:?}", seq);
            }
            Ok(())
        })
        .unwrap();
}
