//! The derivative filters of para. 0086 (Fenney, US 2004/0207631: FIG. 9 is absent): instead
//! of the bi-quadratic surface, the height's slope by a linear filter at each of the four
//! texel centres around the sample point, then the standard bilinear interpolation of the
//! four (with the half-texel subtraction): by linearity the same as filtering bilinearly
//! interpolated heights (`tb/tests/derivative.rs` tests the equality exactly). The normal is
//! `normalize(-Dx s, -Dy s, 1)` through normal unit 156's inverse square root.
//!
//! Filters \[C\] (numerators over a denominator, all integers):
//!
//! | filter | Dx at texel (x, y) | window | texels a sample |
//! |---|---|---|---|
//! | central differences | `(h[x+1] - h[x-1]) / 2` | cross | 12 |
//! | Sobel | `[-1 0 1; -2 0 2; -1 0 1] / 8` | 3 x 3 | 16 |
//! | Prewitt | `[-1 0 1] x 3 rows / 6` | 3 x 3 | 16 |
//! | table | `sum_k c_k (h[x+k] - h[x-k]) / 2^12`, antisymmetric taps `c_1..c_K` (default the 5-point `(8, -1)/12`) | 1 x (2K+1) | 8K + 4 |
//!
//! Dy likewise along y. The 1/6 of Prewitt is no shift: nothing divides here, the
//! denominator goes into the normal's z component (the vector `(-Dx_num s, -Dy_num s, den)`
//! has the normal's direction exactly), so the only rounding is the normalisation's.
//!
//! | value | format |
//! |---|---|
//! | heights | the map's texels (`uQ6.2` by default) |
//! | `u`, `v` | `sQ.<pos_frac>` texel units (texel centres at k + 1/2), weights truncated to `w_frac` bits |
//! | `scale` | `uQ8.8` |
//! | normal | `sQ1.14` |

use crate::bump::height_map::HeightMap;
use crate::bump::normal_156::{unit_narrowings, unit_vector as unit, unit_vector_in};
use crate::bump::params::{Border, RsqrtParams};
use crate::bump::rsqrt_156::RsqrtTable;
use crate::bump::texel_fetch_151::border_index;
use crate::fx::{Format, Narrowing};
use crate::kernel::{Module, Reg, Signal};

/// A derivative filter of para. 0086.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DerivFilter {
    Central,
    Sobel,
    Prewitt,
    /// Antisymmetric taps `c_1 .. c_K` in units of 2^-12 along each axis.
    Table(Vec<i64>),
}

/// The default table: the 5-point derivative `(8 (h1 - h-1) - (h2 - h-2)) / 12` in 2^-12.
pub fn five_point() -> Vec<i64> {
    vec![2731, -341]
}

impl DerivFilter {
    /// `central`, `sobel`, `prewitt`, `table` (the default taps) or `table:c1,c2,...`.
    pub fn parse(s: &str) -> Option<DerivFilter> {
        match s {
            "central" => Some(DerivFilter::Central),
            "sobel" => Some(DerivFilter::Sobel),
            "prewitt" => Some(DerivFilter::Prewitt),
            "table" => Some(DerivFilter::Table(five_point())),
            _ => {
                let taps = s.strip_prefix("table:")?;
                let c: Option<Vec<i64>> = taps.split(',').map(|t| t.trim().parse().ok()).collect();
                c.filter(|c| (1..=4).contains(&c.len()) && c.iter().all(|x| x.abs() < 1 << 14))
                    .map(DerivFilter::Table)
            }
        }
    }

    pub fn name(&self) -> String {
        match self {
            DerivFilter::Central => "central".into(),
            DerivFilter::Sobel => "sobel".into(),
            DerivFilter::Prewitt => "prewitt".into(),
            DerivFilter::Table(c) => {
                let t: Vec<String> = c.iter().map(i64::to_string).collect();
                format!("table:{}", t.join(","))
            }
        }
    }

    /// The denominator of the filter's numerators.
    pub fn denominator(&self) -> i64 {
        match self {
            DerivFilter::Central => 2,
            DerivFilter::Sobel => 8,
            DerivFilter::Prewitt => 6,
            DerivFilter::Table(_) => 1 << 12,
        }
    }

    /// How far the filter reaches from its centre.
    pub fn reach(&self) -> i64 {
        match self {
            DerivFilter::Table(c) => c.len() as i64,
            _ => 1,
        }
    }

    /// `(Dx, Dy)` numerators at texel `(x, y)` with heights `h(x, y)` (raw).
    pub fn at(&self, h: &dyn Fn(i64, i64) -> i64, x: i64, y: i64) -> (i64, i64) {
        let rows = |w: [i64; 3]| -> (i64, i64) {
            let dx = (-1..=1)
                .map(|d| w[(d + 1) as usize] * (h(x + 1, y + d) - h(x - 1, y + d)))
                .sum();
            let dy = (-1..=1)
                .map(|d| w[(d + 1) as usize] * (h(x + d, y + 1) - h(x + d, y - 1)))
                .sum();
            (dx, dy)
        };
        match self {
            DerivFilter::Central => (h(x + 1, y) - h(x - 1, y), h(x, y + 1) - h(x, y - 1)),
            DerivFilter::Sobel => rows([1, 2, 1]),
            DerivFilter::Prewitt => rows([1, 1, 1]),
            DerivFilter::Table(c) => {
                let k = |i: usize| i as i64 + 1;
                let dx = c
                    .iter()
                    .enumerate()
                    .map(|(i, ci)| ci * (h(x + k(i), y) - h(x - k(i), y)))
                    .sum();
                let dy = c
                    .iter()
                    .enumerate()
                    .map(|(i, ci)| ci * (h(x, y + k(i)) - h(x, y - k(i))))
                    .sum();
                (dx, dy)
            }
        }
    }

    /// Distinct texels one sample reads (the four centres' windows together).
    pub fn texels_per_sample(&self) -> usize {
        let mut set = std::collections::BTreeSet::new();
        for (cx, cy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let r = self.reach();
            for y in cy - r..=cy + r {
                for x in cx - r..=cx + r {
                    // A texel counts when the filter's result depends on it.
                    let bump = |a: i64, b: i64| i64::from(a == x && b == y);
                    let (dx, dy) = self.at(&bump, cx, cy);
                    if dx != 0 || dy != 0 {
                        set.insert((x, y));
                    }
                }
            }
        }
        set.len()
    }
}

/// The unit's arithmetic on a map.
pub struct Derivative {
    pub filter: DerivFilter,
    map: HeightMap,
    border: Border,
    pos_frac: u32,
    w_frac: u32,
    table: RsqrtTable,
    p: RsqrtParams,
}

impl Derivative {
    pub fn new(filter: DerivFilter, map: HeightMap, border: Border, pos_frac: u32) -> Derivative {
        let p = RsqrtParams::default();
        Derivative {
            filter,
            map,
            border,
            pos_frac,
            w_frac: 8,
            table: RsqrtTable::new(p).expect("the default parameters are valid"),
            p,
        }
    }

    /// The height (raw) at texel `(x, y)` after the border.
    pub fn height(&self, x: i64, y: i64) -> i64 {
        let (w, h) = (self.map.width(), self.map.height());
        match (
            border_index(x, w, self.border),
            border_index(y, h, self.border),
        ) {
            (Some(i), Some(j)) => i64::from(self.map.get(i, j)),
            _ => match self.border {
                Border::Constant(c) => i64::from(c),
                _ => 0,
            },
        }
    }

    /// The texel pair and weight (uQ0.w_frac, truncated) of coordinate `c` (raw).
    pub fn axis(&self, c: i64) -> (i64, i64) {
        let half = 1i64 << (self.pos_frac - 1);
        let x = c - half;
        let i = x >> self.pos_frac;
        let frac = x & ((1 << self.pos_frac) - 1);
        (i, frac >> (self.pos_frac - self.w_frac))
    }

    /// `(Dx, Dy)` bilinearly interpolated at `(u, v)`: numerators over `den 2^(2 w_frac)` in
    /// height units.
    pub fn slope(&self, u: i64, v: i64) -> (i64, i64) {
        let ((i, a), (j, b)) = (self.axis(u), self.axis(v));
        let one = 1i64 << self.w_frac;
        let h = |x: i64, y: i64| self.height(x, y);
        let mut s = (0, 0);
        for (dy, wy) in [(0, one - b), (1, b)] {
            for (dx, wx) in [(0, one - a), (1, a)] {
                let (gx, gy) = self.filter.at(&h, i + dx, j + dy);
                s.0 += gx * wx * wy;
                s.1 += gy * wx * wy;
            }
        }
        s
    }

    /// The unit normal (sQ1.14) at `(u, v)` with height scale `scale` (uQ8.8): the exact
    /// vector `(-Dx s, -Dy s, den 2^(2 w_frac) 2^hf 2^8)` normalised.
    pub fn normal(&self, u: i64, v: i64, scale: i64) -> [i64; 3] {
        unit(self.exact_normal(u, v, scale), &self.table, &self.p)
    }

    /// [`Derivative::normal`] through named narrowings (counted when numeric tracking is on).
    pub fn normal_in(&self, u: i64, v: i64, scale: i64, n: &mut [Narrowing; 3]) -> [i64; 3] {
        unit_vector_in(self.exact_normal(u, v, scale), &self.table, &self.p, n)
    }

    /// The normal before normalisation, exact.
    fn exact_normal(&self, u: i64, v: i64, scale: i64) -> [i128; 3] {
        let (dx, dy) = self.slope(u, v);
        let hf = self.map.fmt().frac() as u32;
        let z = i128::from(self.filter.denominator()) << (2 * self.w_frac + hf + 8);
        [
            -i128::from(dx) * i128::from(scale),
            -i128::from(dy) * i128::from(scale),
            z,
        ]
    }
}

/// The unit: one register stage around [`Derivative::normal`].
#[derive(Module)]
#[module(kind = "derivative_0086")]
pub struct DerivativeUnit {
    pub math: Derivative,
    #[input]
    pub valid_in: Signal,
    #[input]
    pub u: Signal,
    #[input]
    pub v: Signal,
    #[input]
    pub scale: Signal,
    #[reg]
    pub valid: Reg,
    #[reg]
    pub n: [Reg; 3],
    /// The normal's components into sQ1.14.
    #[narrow]
    round: [Narrowing; 3],
}

impl DerivativeUnit {
    pub fn new(math: Derivative) -> DerivativeUnit {
        let pos = Format::signed(32, math.pos_frac as i32);
        DerivativeUnit {
            valid_in: Signal::bit("valid_in"),
            u: Signal::new("u", pos),
            v: Signal::new("v", pos),
            scale: Signal::new("scale", Format::unsigned(16, 8)),
            valid: Reg::new("valid", Format::uint(1)),
            n: ["nx", "ny", "nz"].map(|x| Reg::new(x, Format::signed(16, 14))),
            round: unit_narrowings(["nx", "ny", "nz"]),
            math,
        }
    }
}

impl DerivativeUnit {
    /// The normal of a valid query, into the output registers.
    pub fn eval(&mut self) {
        let valid = self.valid_in.is_high();
        self.valid.set_next_bool(valid);
        if valid {
            let (u, v, s) = (self.u.raw(), self.v.raw(), self.scale.raw());
            let n = self.math.normal_in(u, v, s, &mut self.round);
            for (r, x) in self.n.iter_mut().zip(n) {
                r.set_next_raw(x);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texels_a_sample_reads() {
        assert_eq!(DerivFilter::Central.texels_per_sample(), 12);
        assert_eq!(DerivFilter::Sobel.texels_per_sample(), 16);
        assert_eq!(DerivFilter::Prewitt.texels_per_sample(), 16);
        assert_eq!(DerivFilter::Table(five_point()).texels_per_sample(), 20);
        for f in ["central", "sobel", "prewitt", "table", "table:3,-1"] {
            let d = DerivFilter::parse(f).unwrap();
            assert_eq!(DerivFilter::parse(&d.name()), Some(d));
        }
        assert!(DerivFilter::parse("table:1,2,3,4,5").is_none());
        // Taps below 2^14 in magnitude (sQ1.12 with room for the sums).
        assert!(DerivFilter::parse("table:16383,-16383").is_some());
        assert!(DerivFilter::parse("table:16384").is_none());
        assert!(DerivFilter::parse("table:-16384").is_none());
    }

    /// Heights outside the map: the border's texel, or the constant.
    #[test]
    fn heights_across_the_border() {
        let fmt = crate::fx::Format::unsigned(8, 2);
        let map = HeightMap::new(2, 2, fmt, vec![10, 20, 30, 40]).unwrap();
        let d = |b| Derivative::new(DerivFilter::Central, map.clone(), b, 16);
        assert_eq!(d(Border::Constant(7)).height(-1, 0), 7);
        assert_eq!(d(Border::Constant(7)).height(1, 1), 40);
        assert_eq!(d(Border::Clamp).height(5, -2), 20);
        assert_eq!(d(Border::Wrap).height(2, 3), 30);
    }

    /// A ramp `h = 3x + 5y` (raw) has the slope (3, 5) by every filter, exactly.
    #[test]
    fn a_ramp_has_its_slope() {
        let h = |x: i64, y: i64| 3 * x + 5 * y;
        for f in [
            DerivFilter::Central,
            DerivFilter::Sobel,
            DerivFilter::Prewitt,
        ] {
            let (dx, dy) = f.at(&h, 7, -2);
            assert_eq!(
                (dx, dy),
                (3 * f.denominator(), 5 * f.denominator()),
                "{f:?}"
            );
        }
        // The 5-point table is exact to its rounding of 8/12 and 1/12: 2731*2 - 341*4 = 4098.
        let (dx, _) = DerivFilter::Table(five_point()).at(&h, 0, 0);
        assert_eq!(dx, 3 * 4098);
    }
}
