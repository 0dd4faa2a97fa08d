//! Tangent unit 155 of US 2004/0207631 (FIG. 7, para. 0062-0075), with the height scale of
//! para. 0082, the interpolated height of para. 0084, Blinn's tangents of para. 0085 and the
//! trilinear blend of para. 0081.
//!
//! From the bilinear results R, G, B, A and the original blend factors `(tu, tv)`:
//!
//! ```text
//! B-spline / Bezier:  dH/du = 2 lerp(tv, G - R, A - B)      dH/dv = 2 lerp(tu, B - R, A - G)
//!                     H     = lerp(tv, lerp(tu, R, G), lerp(tu, B, A))
//! Blinn:              dH/du = G - R    dH/dv = B - R    H = R
//! ```
//!
//! The factor 2 is the derivative of a quadratic Bezier segment, twice the difference of its
//! last de Casteljau points, which the patent's listing leaves implicit (para. 0062-0074 give
//! `lerp(...)` alone); the golden model differentiates the B-spline and agrees with it.
//! Trilinear: `dH/du = lerp(lod, dH0/du, dH1/du / 2)` (the coarser level's texels are twice as
//! wide), `H = lerp(lod, H0, H1)`. Then both tangents and the height are multiplied by the
//! height scale.
//!
//! Everything is exact up to one rounding per output (nearest, ties to even). Tangents
//! saturate symmetrically (so normal unit 156 can negate them without overflow).
//!
//! # Formats
//! | port | format |
//! |---|---|
//! | `r`,`g`,`b`,`a` (and `r1`.. for the second MIP level) | bilinear output `uQ6.<bf>` |
//! | `tu`, `tv` (and `tu1`, `tv1`), `lod` | `uQ0.F` |
//! | `scale` | `uQ<scale_int>.<scale_frac>` (default `uQ8.8`) |
//! | `du`, `dv` | `sQ<16>.<tangent_frac>` (default `sQ16.16`) |
//! | `height` | `uQ<14>.<tangent_frac>` |
//!
//! One register stage: latency 1.

use crate::bump::params::{BumpParams, Filter, ROUND};
use crate::fx::{Format, NarrowPath, Narrowing, Overflow};
use crate::kernel::{Module, Reg, Signal, Signals};

/// The output narrowings, with what the formats prove of them. A slope is at most twice the
/// largest bilinear result (B-spline; once for Blinn; the trilinear blend of a level's slope
/// and half the next one's is no larger) times the largest scale; the height at most the
/// largest result times the scale, and never negative (texels and scale are unsigned).
fn narrowings(p: &BumpParams) -> [Narrowing; 3] {
    let (bl, sc) = (p.bilinear_fmt(), p.scale_fmt());
    let f = bl.frac() + sc.frac();
    let top = bl.max_raw().checked_mul(sc.max_raw());
    let slope = top.and_then(|t| t.checked_mul(2));
    let fits =
        |fmt: Format, v: Option<i128>| v.is_some_and(|v| fmt.holds(v, f) && fmt.holds(-v, f));
    let slopes_fit = fits(p.tangent_fmt(), slope);
    let height_fits = top.is_some_and(|t| p.height_out_fmt().holds(t, f));
    const STEEPEST: &str =
        "|slope| <= 2 x the largest bilinear result x the largest scale, which the format holds";
    let slope = |n| {
        Narrowing::new(n, p.tangent_fmt(), ROUND, Overflow::SaturateSymmetric)
            .unreachable_if(slopes_fit, NarrowPath::High, STEEPEST)
            .unreachable_if(slopes_fit, NarrowPath::Low, STEEPEST)
    };
    [
        slope("du"),
        slope("dv"),
        Narrowing::new("height", p.height_out_fmt(), ROUND, Overflow::Saturate)
            .unreachable_if(
                height_fits,
                NarrowPath::High,
                "height <= the largest bilinear result x the largest scale, which the format holds",
            )
            .unreachable(
                NarrowPath::Low,
                "texels and scale are unsigned: the height is never negative",
            ),
    ]
}

/// Signed machine integers the tangent datapath can be computed in: `i64` when the widths
/// allow (decided once, at construction), `i128` otherwise. Same bits either way.
trait Word: num_traits::PrimInt + num_traits::Signed + From<i64> + Into<i128> {}
impl Word for i64 {}
impl Word for i128 {}

/// One level's exact results: `(dU, dV, fraction bits)`, `(H, fraction bits)`.
#[inline]
fn level<T: Word>(
    rgba: [i64; 4],
    tu: i64,
    tv: i64,
    f: u32,
    fb: u32,
    blinn: bool,
) -> (T, T, u32, T, u32) {
    let [r, g, b, a] = rgba.map(<T as From<i64>>::from);
    if blinn {
        return (g - r, b - r, fb, r, fb);
    }
    let (tu, tv) = (<T as From<i64>>::from(tu), <T as From<i64>>::from(tv));
    let lerp = |x: T, y: T, t: T| (x << f as usize) + t * (y - x);
    let du = lerp(g - r, a - b, tv);
    let dv = lerp(b - r, a - g, tu);
    let h = lerp(lerp(r, g, tu), lerp(b, a, tu), tv);
    // x2: the same bits with one fraction bit less.
    (du, dv, fb + f - 1, h, fb + 2 * f)
}

/// Raw inputs of one evaluation: R, G, B, A of level 0 (and of level 1 in `rgba[4..]` when
/// trilinear), the blend factors of both levels, the MIP weight and the height scale.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TangentIn {
    pub rgba: [i64; 8],
    pub tu: i64,
    pub tv: i64,
    pub tu1: i64,
    pub tv1: i64,
    pub lod: i64,
    pub scale: i64,
}

/// Tangent unit 155.
/// The trilinear variant's inputs for the coarser MIP level: its blend factors and the
/// level-of-detail fraction that mixes the two levels.
#[derive(Clone, Debug, Signals)]
pub struct Level1 {
    pub tu1: Signal,
    pub tv1: Signal,
    pub lod: Signal,
}

#[derive(Clone, Debug, Module)]
#[module(kind = "tangent_155")]
pub struct Tangent {
    #[instance]
    name: String,
    f: u32,
    fb: u32,
    sf: u32,
    /// Every intermediate fits 62 bits: compute in `i64`.
    narrow: bool,
    blinn: bool,
    trilinear: bool,
    /// R, G, B, A of level 0 then (trilinear) of level 1.
    #[input]
    pub rgba: Vec<Signal>,
    #[input]
    pub tu: Signal,
    #[input]
    pub tv: Signal,
    #[input]
    pub scale: Signal,
    /// Present in the trilinear variant.
    #[input]
    pub level1: Option<Level1>,
    #[output]
    pub du: Signal,
    #[output]
    pub dv: Signal,
    #[output]
    pub height: Signal,
    #[reg]
    r: [Reg; 3],
    /// The output narrowings: du, dv (symmetric saturation), height.
    #[narrow]
    round: [Narrowing; 3],
}

impl Tangent {
    pub fn new(name: &str, p: &BumpParams) -> Tangent {
        let bl = p.bilinear_fmt();
        let blend = p.blend_fmt();
        let names: &[&'static str] = if p.trilinear {
            &["r", "g", "b", "a", "r1", "g1", "b1", "a1"]
        } else {
            &["r", "g", "b", "a"]
        };
        Tangent {
            name: name.into(),
            f: p.blend_bits,
            fb: bl.frac() as u32,
            sf: p.scale_frac,
            // |H| < 2^bw scaled by 2^(2F) and the scale; slopes by less.
            narrow: !p.trilinear && bl.width() + 2 * p.blend_bits + p.scale_fmt().width() <= 61,
            blinn: p.filter == Filter::Blinn,
            trilinear: p.trilinear,
            rgba: names.iter().map(|n| Signal::new(n, bl)).collect(),
            tu: Signal::new("tu", blend),
            tv: Signal::new("tv", blend),
            level1: p.trilinear.then(|| Level1 {
                tu1: Signal::new("tu1", blend),
                tv1: Signal::new("tv1", blend),
                lod: Signal::new("lod", blend),
            }),
            scale: Signal::new("scale", p.scale_fmt()),
            du: Signal::new("du", p.tangent_fmt()),
            dv: Signal::new("dv", p.tangent_fmt()),
            height: Signal::new("height", p.height_out_fmt()),
            r: [
                Reg::new("du_r", p.tangent_fmt()),
                Reg::new("dv_r", p.tangent_fmt()),
                Reg::new("height_r", p.height_out_fmt()),
            ],
            round: narrowings(p),
        }
    }

    /// Raw `(du, dv, height)` for raw inputs.
    #[inline]
    pub fn compute(&mut self, x: &TangentIn) -> (i64, i64, i64) {
        if self.narrow {
            self.compute_in::<i64>(x)
        } else {
            self.compute_in::<i128>(x)
        }
    }

    #[inline]
    fn compute_in<T: Word>(&mut self, x: &TangentIn) -> (i64, i64, i64) {
        let TangentIn {
            rgba,
            tu,
            tv,
            tu1,
            tv1,
            lod,
            scale,
        } = *x;
        let (f, fb) = (self.f, self.fb);
        let l0 = [rgba[0], rgba[1], rgba[2], rgba[3]];
        let (mut du, mut dv, mut fd, mut h, mut fh) = level::<T>(l0, tu, tv, f, fb, self.blinn);
        if self.trilinear {
            let l1 = [rgba[4], rgba[5], rgba[6], rgba[7]];
            let (du1, dv1, _, h1, _) = level::<T>(l1, tu1, tv1, f, fb, self.blinn);
            let lod = <T as From<i64>>::from(lod);
            let sh = f as usize;
            // Level 1's slopes are halved: same raw value, one more fraction bit.
            let mix = |x0: T, x1: T| ((x0 << 1) << sh) + lod * (x1 - (x0 << 1));
            du = mix(du, du1);
            dv = mix(dv, dv1);
            fd += 1 + f;
            h = (h << sh) + lod * (h1 - h);
            fh += f;
        }
        let s = <T as From<i64>>::from(scale);
        let sf = self.sf;
        let [rdu, rdv, rh] = &mut self.round;
        // Three calls written out: a closure for them was left out of line.
        (
            rdu.raw((du * s).into(), (fd + sf) as i32) as i64,
            rdv.raw((dv * s).into(), (fd + sf) as i32) as i64,
            rh.raw((h * s).into(), (fh + sf) as i32) as i64,
        )
    }
}

impl Tangent {
    #[inline]
    /// The slopes and height of the blended texels, into the output registers.
    pub fn eval(&mut self) {
        let l1 = self.level1.as_ref();
        let mut rgba = [0i64; 8];
        for (k, s) in self.rgba.iter().enumerate() {
            rgba[k] = s.raw();
        }
        let (du, dv, h) = self.compute(&TangentIn {
            rgba,
            tu: self.tu.raw(),
            tv: self.tv.raw(),
            tu1: l1.map_or(0, |l| l.tu1.raw()),
            tv1: l1.map_or(0, |l| l.tv1.raw()),
            lod: l1.map_or(0, |l| l.lod.raw()),
            scale: self.scale.raw(),
        });
        self.r[0].set_next_raw(du);
        self.r[1].set_next_raw(dv);
        self.r[2].set_next_raw(h);
        self.du.follow(self.r[0].q());
        self.dv.follow(self.r[1].q());
        self.height.follow(self.r[2].q());
    }
}
