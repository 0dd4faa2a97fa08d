//! Normal unit 156 of US 2004/0207631 (FIG. 7, para. 0076-0080): the cross product of the
//! tangents, then normalisation by "squaring the N vector, computing the inverse of the square
//! root of the result, and multiplying that scalar by the original components".
//!
//! With tangents `T1 = (1, 0, dH/du)` and `T2 = (0, 1, dH/dv)` (x along +u, y along +v, z up,
//! texel units) the cross product is `N = (-dH/du, -dH/dv, 1)`: the patent's simplification
//! of para. 0077-0079 in these axes. Then
//!
//! ```text
//! s = N.N = du^2 + dv^2 + 1        (exact)
//! s = m * 4^k,  m in [1, 4)        (leading-one detect; m truncated to M fraction bits)
//! y = rsqrt(m)                     (table + Newton-Raphson, see `rsqrt`)
//! n = N * y * 2^-k                 (rounded to nearest, ties to even; saturating)
//! ```
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `du`, `dv` | tangent `sQ16.<tf>` (symmetric range, so negation is exact) |
//! | `nx`, `ny`, `nz` | `sQ2.<out_frac>` (default `sQ2.16`) |
//! | internal `m`, `k` | `uQ2.M`, `u6` |
//!
//! Pipeline: square/normalise stage, the rsqrt stages, multiply stage: latency
//! `3 + iterations`.

use crate::bump::params::{BumpParams, RsqrtParams, ROUND, SAT};
use crate::bump::rsqrt_156::{m_fmt, rsqrt, Rsqrt, RsqrtTable};
use crate::fx::{quantise, Format, Narrowing};
use crate::kernel::{Delay, Module, Reg, Signal};

/// `(k, m)` with `s * 2^-s_frac = m * 4^k`, `m` truncated to `mant_frac` fraction bits.
#[inline]
pub fn normalise(s: u128, s_frac: u32, mant_frac: u32) -> (u32, u64) {
    debug_assert!(s >> s_frac >= 1, "s < 1");
    let l = 128 - s.leading_zeros(); // bit length
    let k = (l - 1 - s_frac) / 2;
    let shift = (s_frac + 2 * k) as i32 - mant_frac as i32;
    let m = if shift >= 0 {
        s >> shift
    } else {
        s << (-shift)
    };
    (k, m as u64)
}

/// Normal unit 156.
/// Fraction bits of a unit vector from [`unit_vector`] (sQ1.14).
pub const UNIT_FRAC: u32 = 14;

/// `v / |v|` by normal unit 156's normalisation and inverse square root, each component
/// rounded once to sQ1.14 ([`UNIT_FRAC`]), for any nonzero `v`. The quotient has
/// no units, so `v`'s binary point does not matter and `v` is read as an integer:
/// `|v|^2 = m 4^k` with `m` in [1, 4) (unit 156's `normalise`), `y = rsqrt(m)`, then
/// `v_c y 2^-k`.
pub fn unit_vector(v: [i128; 3], table: &RsqrtTable, p: &RsqrtParams) -> [i64; 3] {
    let out = Format::signed(16, UNIT_FRAC as i32);
    unit_vector_by(v, table, p, |_, x, frac| {
        quantise(x, frac, out, ROUND, SAT) as i64
    })
}

/// [`unit_vector`] through a unit's named narrowings (see [`unit_narrowings`]), counted when
/// numeric tracking is on; the same result.
pub fn unit_vector_in(
    v: [i128; 3],
    table: &RsqrtTable,
    p: &RsqrtParams,
    n: &mut [Narrowing; 3],
) -> [i64; 3] {
    unit_vector_by(v, table, p, |c, x, frac| n[c].raw(x, frac) as i64)
}

/// The normalisation, each component `v_c y` (`frac` fraction bits) narrowed by `round`.
#[inline]
fn unit_vector_by(
    v: [i128; 3],
    table: &RsqrtTable,
    p: &RsqrtParams,
    mut round: impl FnMut(usize, i128, i32) -> i64,
) -> [i64; 3] {
    let s: u128 = v.iter().map(|c| (c * c) as u128).sum();
    let (k, m) = normalise(s, 0, p.mant_frac);
    let y = i128::from(rsqrt(table, m));
    // v_c y 2^-k: fraction bits y_frac + k.
    let frac = (p.y_frac + k) as i32;
    std::array::from_fn(|c| round(c, v[c] * y, frac))
}

/// The three narrowings of a [`unit_vector_in`] (the components into sQ1.14), named
/// `names`; both saturations are unreachable, as every component of a unit vector is.
pub fn unit_narrowings(names: [&'static str; 3]) -> [Narrowing; 3] {
    names.map(|n| {
        Narrowing::new(n, Format::signed(16, UNIT_FRAC as i32), ROUND, SAT)
            .never_overflows(UNIT_BOUND)
    })
}

/// Why a unit vector's components never saturate.
const UNIT_BOUND: &str = "|n| = 1 within the rsqrt's error: every component is far inside (-2, 2)";

#[derive(Clone, Debug, Module)]
#[module(kind = "normal_156")]
pub struct Normal {
    #[instance]
    name: String,
    tf: u32,
    mf: u32,
    yf: u32,
    #[input]
    pub du: Signal,
    #[input]
    pub dv: Signal,
    #[output]
    pub nx: Signal,
    #[output]
    pub ny: Signal,
    #[output]
    pub nz: Signal,
    /// Square stage: -du, -dv, k, m.
    #[reg]
    sq: [Reg; 4],
    #[child]
    pub rsqrt: Rsqrt,
    #[child]
    carry: Delay<3>,
    /// Multiply stage: nx, ny, nz.
    #[reg]
    mul: [Reg; 3],
    /// The multiply stage's narrowings, `N y 2^-k` into the output format: nx, ny, nz.
    #[narrow]
    scaled: [Narrowing; 3],
}

const K_FMT: Format = Format::uint(6);

impl Normal {
    pub fn new(name: &str, p: &BumpParams) -> Result<Normal, String> {
        let tan = p.tangent_fmt();
        let out = p.normal_fmt();
        let rsqrt = Rsqrt::new("rsqrt_156", p.rsqrt)?;
        let carry = Delay::new(
            "carry",
            [("nx_in", tan), ("ny_in", tan), ("k_in", K_FMT)],
            rsqrt.latency(),
            ["nx_d", "ny_d", "k_d"],
        );
        Ok(Normal {
            name: name.into(),
            tf: p.tangent_frac,
            mf: p.rsqrt.mant_frac,
            yf: p.rsqrt.y_frac,
            du: Signal::new("du", tan),
            dv: Signal::new("dv", tan),
            nx: Signal::new("nx", out),
            ny: Signal::new("ny", out),
            nz: Signal::new("nz", out),
            sq: [
                Reg::new("nx_sq", tan),
                Reg::new("ny_sq", tan),
                Reg::new("k_sq", K_FMT),
                Reg::new("m_sq", m_fmt(&p.rsqrt)),
            ],
            rsqrt,
            carry,
            mul: [
                Reg::new("nx_r", out),
                Reg::new("ny_r", out),
                Reg::new("nz_r", out),
            ],
            scaled: ["nx", "ny", "nz"].map(|n| {
                // A unit vector's components are within [-1, 1]; the rsqrt's relative error
                // (a few LSBs of y) cannot take them to 2.
                Narrowing::new(n, out, ROUND, SAT).never_overflows(UNIT_BOUND)
            }),
        })
    }

    pub fn latency(&self) -> usize {
        2 + self.rsqrt.latency()
    }

    /// The multiply stage on raw values: `N * y * 2^-k` into the output format.
    #[inline]
    fn scale(&mut self, c: usize, n: i64, y: u64, k: u32) -> i64 {
        let x = i128::from(n) * i128::from(y);
        self.scaled[c].raw(x, (self.tf + self.yf + k) as i32) as i64
    }
}

impl Normal {
    #[inline]
    /// The square, rsqrt and multiply stages.
    pub fn eval(&mut self) {
        // Square stage.
        let (du, dv) = (self.du.raw(), self.dv.raw());
        let s =
            (du as i128 * du as i128 + dv as i128 * dv as i128) as u128 + (1u128 << (2 * self.tf));
        let (k, m) = normalise(s, 2 * self.tf, self.mf);
        self.sq[0].set_next_raw(-du);
        self.sq[1].set_next_raw(-dv);
        self.sq[2].set_next_raw(i64::from(k));
        self.sq[3].set_next_bits(m);
        // Rsqrt stages and the carried components.
        self.rsqrt.m.follow(self.sq[3].q());
        self.rsqrt.eval();
        self.carry.i[0].follow(self.sq[0].q());
        self.carry.i[1].follow(self.sq[1].q());
        self.carry.i[2].follow(self.sq[2].q());
        self.carry.eval();
        // Multiply stage.
        let y = self.rsqrt.y.bits();
        let k = self.carry.o[2].bits() as u32;
        let nx = self.scale(0, self.carry.o[0].raw(), y, k);
        let ny = self.scale(1, self.carry.o[1].raw(), y, k);
        let nz = self.scale(2, 1i64 << self.tf, y, k);
        self.mul[0].set_next_raw(nx);
        self.mul[1].set_next_raw(ny);
        self.mul[2].set_next_raw(nz);
        self.nx.follow(self.mul[0].q());
        self.ny.follow(self.mul[1].q());
        self.nz.follow(self.mul[2].q());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bump::params::RsqrtParams;
    use crate::kernel::Sim;

    /// `m = floor(s * 2^(M - s_frac) / 4^k)` with `m` in `[2^M, 2^(M+2))`, whichever way the
    /// mantissa is shifted (right when `s` has more fraction bits than `m`, left when fewer).
    #[test]
    fn normalise_takes_out_powers_of_four_both_ways() {
        for (s_frac, mf) in [(32, 22), (16, 22), (16, 40), (48, 8), (16, 16)] {
            let ones = [1u128, 2, 3, 4, 5, 15, 16, 17, 1000, 65535, 1 << 20];
            for s in ones
                .iter()
                .map(|&x| x << s_frac)
                .chain([(1u128 << s_frac) + 1])
            {
                let (k, m) = normalise(s, s_frac, mf);
                let m = u128::from(m);
                assert!(
                    (1 << mf..4 << mf).contains(&m),
                    "s {s:#x}/{s_frac}: m {m:#x}"
                );
                // Compare m * 4^k * 2^s_frac with s * 2^M: equal up to the truncation.
                let (lhs, rhs) = (m << (2 * k + s_frac), s << mf);
                assert!(
                    lhs <= rhs && rhs - lhs < 1 << (2 * k + s_frac),
                    "s {s:#x}/{s_frac}"
                );
            }
        }
    }

    /// Latency `3 + iterations`: (0, 0) gives (0, 0, 1) exactly that many edges later.
    #[test]
    fn latency_follows_the_iterations_and_narrow_tangents_work() {
        for iterations in 0..=3 {
            let p = BumpParams {
                tangent_frac: 8,
                rsqrt: RsqrtParams {
                    iterations,
                    ..RsqrtParams::default()
                },
                ..BumpParams::default()
            };
            let mut sim = Sim::new(Normal::new("normal_156", &p).unwrap()).check_schedule(true);
            let lat = sim.dut.latency();
            assert_eq!(lat, 3 + iterations as usize);
            sim.reset(1);
            for c in 0..=lat {
                sim.dut.du.set_raw(if c == 0 { 0 } else { 200 << 8 });
                sim.dut.dv.set_raw(0);
                sim.eval();
                let nz = sim.dut.nz.raw();
                if c < lat {
                    assert_eq!(nz, 0, "iterations {iterations}: cycle {c}");
                } else {
                    // The table alone is within 2^-(table_bits+1) relative of 1.
                    assert!((nz - 65536).abs() <= 65536 >> 9, "{iterations}: nz {nz}");
                }
                sim.tick();
            }
        }
    }
}
