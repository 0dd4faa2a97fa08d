//! Bilinear unit (one of 65-68 of US 2004/0207631, FIG. 7; the prior-art blend of para.
//! 0017-0021): `lerp(lerp(p00, p10, s), lerp(p01, p11, s), t)`.
//!
//! Both linear blends are computed exactly (`a + s (b - a)` at full precision); the result is
//! then rounded to the output format (nearest, ties to even; it cannot overflow, since the
//! exact result lies between the smallest and largest texel). With the default output format
//! nothing is rounded at all, which is what makes the Bezier path (para. 0083) give the very
//! same bits as the blend-adjust path.
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `p00`, `p10`, `p01`, `p11` | replicate output, `uQ<i>.<f>` (`uQ6.4` for 8-bit texels) |
//! | `s`, `t` | adjusted blend factors `uQ0.(F+1)` |
//! | `q` | `uQ<i>.<bf>`, `bf` = `bilinear_frac`, default `f + 2(F+1)` (exact) |
//!
//! One register stage: latency 1.

use crate::bump::params::{ROUND, SAT};
use crate::fx::{Format, NarrowPath, Narrowing};
use crate::kernel::{Module, Reg, Signal};

/// The one narrowing, with what the formats prove of it: the blend lies between its
/// smallest and largest texel (weights `1 - s`, `s` of each lerp sum to one), so it overflows
/// neither way where the output holds every texel; it is exact where the output keeps every
/// fraction bit.
fn bilinear_narrowing(texel: Format, blend: Format, out: Format) -> Narrowing {
    let f = texel.frac();
    let holds_texels = out.holds(texel.max_raw(), f) && out.holds(texel.min_raw(), f);
    let exact = out.frac() >= f + 2 * blend.frac();
    Narrowing::new("q", out, ROUND, SAT)
        .unreachable_if(
            holds_texels,
            NarrowPath::High,
            "a blend never exceeds its largest texel, which the output holds",
        )
        .unreachable_if(
            holds_texels,
            NarrowPath::Low,
            "a blend is never below its smallest texel, which the output holds",
        )
        .unreachable_if(
            exact,
            NarrowPath::Tie,
            "exact: the output keeps every fraction bit of the blend",
        )
}

/// One bilinear unit.
#[derive(Clone, Debug, Module)]
#[module(kind = "bilinear_65_68")]
pub struct Bilinear {
    #[instance]
    name: String,
    /// Fraction bits of the blend factors (F+1) and of the texels.
    sf: u32,
    pf: u32,
    #[input]
    pub p: [Signal; 4],
    #[input]
    pub s: Signal,
    #[input]
    pub t: Signal,
    #[output]
    pub q: Signal,
    #[reg]
    r: Reg,
    /// The one narrowing: the exact blend into the output format.
    #[narrow]
    round: Narrowing,
}

impl Bilinear {
    pub fn new(name: &str, texel: Format, blend: Format, out: Format) -> Result<Bilinear, String> {
        if texel.width() + 2 * blend.width() + 2 > 62 {
            return Err(format!(
                "bilinear unit: {texel} texels and {blend} factors exceed the 62-bit datapath"
            ));
        }
        Ok(Bilinear {
            name: name.into(),
            sf: blend.frac() as u32,
            pf: texel.frac() as u32,
            p: ["p00", "p10", "p01", "p11"].map(|n| Signal::new(n, texel)),
            s: Signal::new("s", blend),
            t: Signal::new("t", blend),
            q: Signal::new("q", out),
            r: Reg::new("q_r", out),
            round: bilinear_narrowing(texel, blend, out),
        })
    }

    /// The exact blend, raw with `pf + 2 sf` fraction bits. Texels of up to 12 bits and
    /// factors of up to 17 bits keep every intermediate within 48 bits, so `i64` holds it.
    #[inline]
    pub fn exact(p: [i64; 4], s: i64, t: i64, sf: u32) -> i64 {
        let lerp = |a: i64, b: i64, x: i64| (a << sf) + x * (b - a);
        let r0 = lerp(p[0], p[1], s);
        let r1 = lerp(p[2], p[3], s);
        lerp(r0, r1, t)
    }

    /// The unit's result for raw inputs, raw in the output format.
    #[inline]
    pub fn compute(&mut self, p: [i64; 4], s: i64, t: i64) -> i64 {
        let x = Self::exact(p, s, t, self.sf);
        let f = self.pf + 2 * self.sf;
        self.round.raw(i128::from(x), f as i32) as i64
    }
}

impl Bilinear {
    #[inline]
    /// The blend of the four texels, into the output register.
    pub fn eval(&mut self) {
        let p = [
            self.p[0].raw(),
            self.p[1].raw(),
            self.p[2].raw(),
            self.p[3].raw(),
        ];
        let v = self.compute(p, self.s.raw(), self.t.raw());
        self.r.set_next_raw(v);
        self.q.follow(self.r.q());
    }
}
