//! The inverse square root of unit 156, exhaustively: every mantissa of the input range against
//! the exact integer reference `floor(2^Y / sqrt(m))` (integer square roots, no floating
//! point), for the default parameters and a few others. The measured worst error must stay
//! within the bound derived in `units::bump::rsqrt_156`; it is printed.

use golden::rsqrt::error_bound_ulps;
use hdl::kernel::Sim;
use units::bump::params::RsqrtParams;
use units::bump::rsqrt_156::{rsqrt, Rsqrt, RsqrtTable};

/// Worst |y - 1/sqrt(m)| in ULPs over every mantissa, measured to 1/256 ULP, and the count of
/// inputs whose result is the correctly rounded one.
fn sweep(p: RsqrtParams) -> (f64, u64, u64) {
    let t = RsqrtTable::new(p).unwrap();
    let (m, y) = (p.mant_frac, p.y_frac);
    let mut worst = 0i128;
    let mut correct = 0u64;
    let mut n = 0u64;
    for mm in (1u64 << m)..(4u64 << m) {
        let got = rsqrt(&t, mm) as i128;
        // Exact: z = floor(256 * 2^Y / sqrt(mm / 2^M)) = isqrt(2^(2Y + M + 16) / mm).
        let z = ((1u128 << (2 * y + m + 16)) / u128::from(mm)).isqrt() as i128;
        let err = (got << 8) - z; // in 1/256 ULP, exact value within [z, z+1)
        let e = if err >= 0 { err } else { -err + 1 };
        worst = worst.max(e);
        let nearest = (z + 128) >> 8;
        correct += u64::from(got == nearest);
        n += 1;
    }
    (worst as f64 / 256.0, correct, n)
}

#[test]
fn exhaustive_default_parameters() {
    let p = RsqrtParams::default();
    let (worst, correct, n) = sweep(p);
    let bound = error_bound_ulps(p.table_bits, p.iterations, p.y_frac);
    eprintln!("rsqrt {p:?}: {n} inputs, worst {worst:.3} ULP (bound {bound:.3}), {correct} correctly rounded");
    assert_eq!(n, 3 << p.mant_frac);
    assert!(worst <= bound, "worst {worst} > bound {bound}");
}

#[test]
fn exhaustive_other_parameters() {
    for p in [
        RsqrtParams {
            table_bits: 12,
            iterations: 1,
            mant_frac: 18,
            y_frac: 22,
        },
        RsqrtParams {
            table_bits: 6,
            iterations: 2,
            mant_frac: 16,
            y_frac: 20,
        },
        RsqrtParams {
            table_bits: 10,
            iterations: 0,
            mant_frac: 16,
            y_frac: 16,
        },
        RsqrtParams {
            table_bits: 5,
            iterations: 3,
            mant_frac: 14,
            y_frac: 28,
        },
    ] {
        let (worst, correct, n) = sweep(p);
        let bound = error_bound_ulps(p.table_bits, p.iterations, p.y_frac);
        eprintln!("rsqrt {p:?}: {n} inputs, worst {worst:.3} ULP (bound {bound:.3}), {correct} correctly rounded");
        assert!(worst <= bound, "{p:?}: worst {worst} > bound {bound}");
    }
}

#[test]
fn module_matches_function_with_latency() {
    // The default; a 12-bit table at 8 fraction bits, whose first entry rounds to exactly 1.0
    // (the output's integer bit); three iterations on a small table; the widest formats.
    let sets = [
        RsqrtParams::default(),
        RsqrtParams {
            table_bits: 12,
            iterations: 0,
            mant_frac: 12,
            y_frac: 8,
        },
        RsqrtParams {
            table_bits: 5,
            iterations: 3,
            mant_frac: 30,
            y_frac: 30,
        },
        RsqrtParams {
            table_bits: 14,
            iterations: 1,
            mant_frac: 40,
            y_frac: 40,
        },
    ];
    for p in sets {
        let mut sim = Sim::new(Rsqrt::new("rsqrt", p).unwrap()).check_schedule(true);
        let lat = sim.dut.latency();
        assert_eq!(lat, 1 + p.iterations as usize);
        let t = RsqrtTable::new(p).unwrap();
        let one = 1u64 << p.mant_frac;
        let step = (3 * one) / 500;
        let inputs: Vec<u64> = (0..500u64).map(|k| one + k * step).collect();
        let mut outs = Vec::new();
        for k in 0..inputs.len() + lat {
            sim.dut.m.set_bits(*inputs.get(k).unwrap_or(&one));
            sim.eval();
            if k >= lat {
                outs.push(sim.dut.y.bits());
            }
            sim.tick();
        }
        let want: Vec<u64> = inputs.iter().map(|&m| rsqrt(&t, m)).collect();
        assert_eq!(outs, want, "{p:?}");
        if p.y_frac == 8 {
            assert_eq!(outs[0], 1 << 8, "1/sqrt(1) is 1.0 at 8 bits");
        }
    }
}
