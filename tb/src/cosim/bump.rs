//! Co-simulation adapters of the FIG. 7 units (US 2004/0207631): each unit's model, its
//! twin in `rtl/bump/`, the twin's parameters from the model's and the stimulus.

use super::twin;
use hdl::fx::Format;
use hdl::kernel::Signal;
use std::path::PathBuf;
use units::bump::height_map::HeightMap;
use units::bump::params::{Border, BumpParams};
use verif::cosim::{field, Clocking, CosimModel, CosimUnit, ModelSim, Unmodelled};
/// Blend-factor adjust unit 153 against `rtl/bump/blend_adjust_153.v`.
pub struct BlendAdjustCosim(pub units::bump::blend_adjust_153::BlendAdjustParams);

impl CosimUnit for BlendAdjustCosim {
    fn name(&self) -> &str {
        "blend_adjust_153"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/blend_adjust_153.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![
            ("FRAC_BITS", i64::from(self.0.frac_bits)),
            ("REGISTERED", i64::from(self.0.registered)),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::blend_adjust_153::BlendAdjust;
        let dut = BlendAdjust::new(self.name(), self.0)?;
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut BlendAdjust, v: &[u64]| {
                Signal::set_row(
                    [
                        &mut d.i.valid_in,
                        &mut d.i.bypass,
                        &mut d.i.u_in,
                        &mut d.i.v_in,
                    ],
                    v,
                );
            },
        )))
    }
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let mut st = verif::Stimulus::new(seed);
        let f = self.0.frac_bits;
        let bits = st.draw_n(&(0u64..4, field(f), field(f)), cycles);
        bits.into_iter()
            .map(|(vb, u, v)| vec![vb & 1, vb >> 1, u, v])
            .collect()
    }
}

/// Address unit 150 against `rtl/bump/address_150.v`: positions `sQ<pos_int>.<pos_frac>`,
/// blend factors of `blend_bits`.
pub struct AddressCosim {
    pub pos_int: u32,
    pub pos_frac: u32,
    pub blend_bits: u32,
}

impl Default for AddressCosim {
    fn default() -> Self {
        AddressCosim {
            pos_int: 16,
            pos_frac: 8,
            blend_bits: 8,
        }
    }
}

impl CosimUnit for AddressCosim {
    fn name(&self) -> &str {
        "address_150"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/address_150.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![
            ("POS_INT", i64::from(self.pos_int)),
            ("POS_FRAC", i64::from(self.pos_frac)),
            ("BLEND_BITS", i64::from(self.blend_bits)),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::address_150::AddressUnit;
        let pos = Format::signed(self.pos_int + self.pos_frac, self.pos_frac as i32);
        let dut = AddressUnit::new(self.name(), pos, self.blend_bits)?;
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut AddressUnit, v: &[u64]| {
                Signal::set_row([&mut d.u, &mut d.v, &mut d.colour], v);
            },
        )))
    }
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let mut st = verif::Stimulus::new(seed);
        let w = self.pos_int + self.pos_frac;
        st.draw_n(&(field(w), field(w), 0u64..2), cycles)
            .into_iter()
            .map(|(u, v, c)| vec![u, v, c])
            .collect()
    }
}

/// Replicate unit 152 against `rtl/bump/replicate_152.v`: texels of `texel_bits` bits (8:
/// `uQ6.2`, 4: `uQ3.1`), B-spline or Bezier (Equation 1) control points.
pub struct ReplicateCosim {
    pub texel_bits: u32,
    pub bezier: bool,
}

impl CosimUnit for ReplicateCosim {
    fn name(&self) -> &str {
        "replicate_152"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/replicate_152.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![
            ("TEXEL_BITS", i64::from(self.texel_bits)),
            ("BEZIER", i64::from(self.bezier)),
        ]
    }
    fn clocking(&self) -> Option<Clocking> {
        None
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::replicate_152::Replicate;
        let texel = Format::unsigned(self.texel_bits, self.texel_bits as i32 / 4);
        let dut = Replicate::new(self.name(), texel, self.bezier);
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut Replicate, v: &[u64]| {
                Signal::set_row(d.h.each_mut(), v);
            },
        )))
    }
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let mut st = verif::Stimulus::new(seed);
        let max = (1u64 << self.texel_bits) - 1;
        let texel = proptest::prop_oneof![1 => proptest::strategy::Just(max), 1 => proptest::strategy::Just(0u64), 6 => 0..=max];
        (0..cycles).map(|_| st.draw_n(&texel, 9)).collect()
    }
}

/// A bilinear unit (65-68) against `rtl/bump/bilinear_65_68.v`, in the formats the FIG. 7
/// pipeline gives it: texels of `texel_bits` bits out of replicate 152, blend factors of
/// `blend_bits + 1` bits, the output exact or rounded to `bilinear_frac` fraction bits.
pub struct BilinearCosim {
    pub texel_bits: u32,
    pub blend_bits: u32,
    pub bilinear_frac: Option<u32>,
}

impl BilinearCosim {
    fn params(&self) -> units::bump::params::BumpParams {
        use units::bump::params::{BumpParams, HeightTexel};
        BumpParams {
            blend_bits: self.blend_bits,
            height: if self.texel_bits == 4 {
                HeightTexel::Bits4
            } else {
                HeightTexel::Bits8
            },
            bilinear_frac: self.bilinear_frac,
            // The position must carry at least the blend factor's bits.
            pos_frac: self.blend_bits.max(8),
            ..BumpParams::default()
        }
    }
}

impl CosimUnit for BilinearCosim {
    fn name(&self) -> &str {
        "bilinear_65_68"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/bilinear_65_68.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        let p = self.params();
        let (t, b, o) = (p.replicate_fmt(), p.adj_fmt(), p.bilinear_fmt());
        vec![
            ("TEXEL_W", i64::from(t.width())),
            ("TEXEL_F", i64::from(t.frac())),
            ("BLEND_W", i64::from(b.width())),
            ("OUT_W", i64::from(o.width())),
            ("OUT_F", i64::from(o.frac())),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::bilinear_65_68::Bilinear;
        let p = self.params();
        p.validate()?;
        let dut = Bilinear::new(
            self.name(),
            p.replicate_fmt(),
            p.adj_fmt(),
            p.bilinear_fmt(),
        )?;
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut Bilinear, v: &[u64]| {
                let [p0, p1, p2, p3] = &mut d.p;
                Signal::set_row([p0, p1, p2, p3, &mut d.s, &mut d.t], v);
            },
        )))
    }
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let mut st = verif::Stimulus::new(seed);
        let p = self.params();
        let (tw, bw) = (p.replicate_fmt().width(), p.adj_fmt().width());
        (0..cycles)
            .map(|_| {
                let mut v = st.draw_n(&field(tw), 4);
                v.extend(st.draw_n(&field(bw), 2));
                v
            })
            .collect()
    }
}

/// Tangent unit 155 against `rtl/bump/tangent_155.v`, in the formats of the FIG. 7 pipeline
/// built from `params` (one MIP level, or two with `trilinear`).
pub struct TangentCosim(pub units::bump::params::BumpParams);

impl CosimUnit for TangentCosim {
    fn name(&self) -> &str {
        "tangent_155"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/tangent_155.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        use units::bump::params::Filter;
        let p = &self.0;
        let (bl, s) = (p.bilinear_fmt(), p.scale_fmt());
        let w = |f: Format| i64::from(f.width());
        vec![
            ("BL_W", w(bl)),
            ("BL_F", i64::from(bl.frac())),
            ("F", i64::from(p.blend_bits)),
            ("SCALE_W", w(s)),
            ("SCALE_F", i64::from(s.frac())),
            ("TAN_W", w(p.tangent_fmt())),
            ("H_W", w(p.height_out_fmt())),
            ("TAN_F", i64::from(p.tangent_frac)),
            ("BLINN", i64::from(p.filter == Filter::Blinn)),
            ("TRILINEAR", i64::from(p.trilinear)),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::tangent_155::Tangent;
        self.0.validate()?;
        let dut = Tangent::new(self.name(), &self.0);
        // Inputs in port order: R, G, B, A (of both levels), tu, tv, scale (, tu1, tv1, lod).
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut Tangent, v: &[u64]| {
                let n = d.rgba.len();
                for (s, x) in d.rgba.iter_mut().zip(v) {
                    s.set_bits(*x);
                }
                d.tu.set_bits(v[n]);
                d.tv.set_bits(v[n + 1]);
                d.scale.set_bits(v[n + 2]);
                if let Some(l1) = &mut d.level1 {
                    l1.tu1.set_bits(v[n + 3]);
                    l1.tv1.set_bits(v[n + 4]);
                    l1.lod.set_bits(v[n + 5]);
                }
            },
        )))
    }
    /// One MIP level: the second level's inputs, which `TRILINEAR = 0` leaves unused, tied
    /// to zero.
    fn unmodelled(&self) -> Vec<Unmodelled> {
        let second = ["r1", "g1", "b1", "a1", "tu1", "tv1", "lod"];
        match self.0.trilinear {
            true => Vec::new(),
            false => second.map(|n| Unmodelled::Tied(n.into(), 0)).into(),
        }
    }
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let mut st = verif::Stimulus::new(seed);
        let p = &self.0;
        let (bw, f, sw) = (
            p.bilinear_fmt().width(),
            p.blend_bits,
            p.scale_fmt().width(),
        );
        let levels = if p.trilinear { 2 } else { 1 };
        (0..cycles)
            .map(|_| {
                let mut v = st.draw_n(&field(bw), 4 * levels);
                v.extend(st.draw_n(&field(f), 2));
                v.extend(st.draw_n(&field(sw), 1));
                if p.trilinear {
                    v.extend(st.draw_n(&field(f), 3));
                }
                v
            })
            .collect()
    }
}

/// The inverse-square-root unit inside normal unit 156 against `rtl/bump/rsqrt_156.v`: its
/// table (built at elaboration in Verilog, at construction in the model) and Newton steps.
pub struct RsqrtCosim(pub units::bump::params::RsqrtParams);

impl CosimUnit for RsqrtCosim {
    fn name(&self) -> &str {
        "rsqrt_156"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/rsqrt_156.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        let p = &self.0;
        vec![
            ("TABLE_BITS", i64::from(p.table_bits)),
            ("ITERATIONS", i64::from(p.iterations)),
            ("M_F", i64::from(p.mant_frac)),
            ("Y_F", i64::from(p.y_frac)),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::rsqrt_156::Rsqrt;
        let dut = Rsqrt::new(self.name(), self.0)?;
        Ok(Box::new(ModelSim::new(dut, |d: &mut Rsqrt, v: &[u64]| {
            d.m.set_bits(v[0]);
        })))
    }
    /// Mantissas over the whole port, corners included (below 1 too: the zero path).
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let mut st = verif::Stimulus::new(seed);
        st.draw_n(&field(self.0.mant_frac + 2), cycles)
            .into_iter()
            .map(|m| vec![m])
            .collect()
    }
}

/// Normal unit 156 (its rsqrt included) against `rtl/bump/normal_156.v` and
/// `rtl/bump/rsqrt_156.v`, in the formats of the FIG. 7 pipeline built from `params`.
pub struct NormalCosim(pub units::bump::params::BumpParams);

impl CosimUnit for NormalCosim {
    fn name(&self) -> &str {
        "normal_156"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/normal_156.v", "bump/rsqrt_156.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        let p = &self.0;
        vec![
            ("TAN_W", i64::from(p.tangent_fmt().width())),
            ("TF", i64::from(p.tangent_frac)),
            ("OUT_F", i64::from(p.out_frac)),
            ("TABLE_BITS", i64::from(p.rsqrt.table_bits)),
            ("ITERATIONS", i64::from(p.rsqrt.iterations)),
            ("M_F", i64::from(p.rsqrt.mant_frac)),
            ("Y_F", i64::from(p.rsqrt.y_frac)),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::normal_156::Normal;
        self.0.validate()?;
        let dut = Normal::new(self.name(), &self.0)?;
        Ok(Box::new(ModelSim::new(dut, |d: &mut Normal, v: &[u64]| {
            Signal::set_row([&mut d.du, &mut d.dv], v);
        })))
    }
    /// Tangents in the symmetric range unit 155 produces: corners (0, +-1, +-largest), slopes
    /// within +-4 (most surfaces), and any value.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::{Just, Strategy};
        let f = self.0.tangent_fmt();
        let (w, max) = (f.width(), f.max_raw() as i64);
        let small = 4i64 << self.0.tangent_frac;
        let tangent = proptest::prop_oneof![
            1 => proptest::prop_oneof![Just(0i64), Just(1), Just(-1), Just(max), Just(-max)],
            2 => -small..=small,
            1 => -max..=max,
        ]
        .prop_map(move |x| (x as u64) & (u64::MAX >> (64 - w)));
        let mut st = verif::Stimulus::new(seed);
        st.draw_n(&(tangent.clone(), tangent), cycles)
            .into_iter()
            .map(|(u, v)| vec![u, v])
            .collect()
    }
}

/// A height map of `w x h` texels of `fmt`, drawn from `seed`: corners (0 and the largest
/// texel) an eighth of the time each, otherwise uniform.
pub fn random_map(w: u32, h: u32, fmt: Format, seed: u64) -> HeightMap {
    use proptest::strategy::Just;
    let max = fmt.max_raw() as u8;
    let texel = proptest::prop_oneof![1 => Just(0u8), 1 => Just(max), 6 => 0..=max];
    let mut st = verif::Stimulus::new(verif::Seed(seed));
    let texels = st.draw_n(&texel, (w * h) as usize);
    HeightMap::new(w, h, fmt, texels).expect("a drawn map fits its format")
}

/// `map` as a `$readmemh` image: one texel per line, row-major.
fn memory_image(map: &HeightMap) -> String {
    map.texels().iter().map(|t| format!("{t:02x}\n")).collect()
}

/// The Verilog code of a border mode (`BORDER`, `BORDER_VALUE` of the twins).
fn border_code(b: Border) -> (i64, i64) {
    match b {
        Border::Wrap => (0, 0),
        Border::Clamp => (1, 0),
        Border::Mirror => (2, 0),
        Border::Constant(c) => (3, i64::from(c)),
    }
}

/// Texel fetch unit 151 against `rtl/bump/texel_fetch_151.v`: coordinates of `pos_int + 1`
/// bits (from address unit 150), `params.border`, reading `map` (the twin's ROM image is
/// written as `height_151.hex`).
pub struct TexelFetchCosim {
    pub params: BumpParams,
    pub map: HeightMap,
}

impl TexelFetchCosim {
    /// A `w x h` map of the texel format of `params`, drawn from `map_seed`.
    pub fn new(params: BumpParams, w: u32, h: u32, map_seed: u64) -> TexelFetchCosim {
        let map = random_map(w, h, params.texel_fmt(), map_seed);
        TexelFetchCosim { params, map }
    }
}

impl CosimUnit for TexelFetchCosim {
    fn name(&self) -> &str {
        "texel_fetch_151"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["bump/texel_fetch_151.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        let p = &self.params;
        let (border, value) = border_code(p.border);
        vec![
            ("COORD_W", i64::from(p.coord_fmt().width())),
            ("TEXEL_W", i64::from(p.texel_fmt().width())),
            ("MAP_W", i64::from(self.map.width())),
            ("MAP_H", i64::from(self.map.height())),
            ("BORDER", border),
            ("BORDER_VALUE", value),
        ]
    }
    fn memories(&self) -> Vec<(String, String)> {
        vec![("height_151.hex".into(), memory_image(&self.map))]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::texel_fetch_151::TexelFetch;
        self.params.validate()?;
        let p = &self.params;
        let dut = TexelFetch::new(self.name(), self.map.clone(), p.border, p.coord_fmt())?;
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut TexelFetch, v: &[u64]| {
                Signal::set_row([&mut d.ui, &mut d.vj], v);
            },
        )))
    }
    /// Coordinates over the whole port a quarter of the time (far outside: every border
    /// mode's arithmetic), otherwise within three texels of the map (its edges and corners).
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::Strategy;
        let w = self.params.coord_fmt().width();
        let mask = u64::MAX >> (64 - w);
        let near = |n: u32| (-3i64..=i64::from(n) + 2).prop_map(move |x| x as u64 & mask);
        let coord = |n: u32| proptest::prop_oneof![1 => field(w), 3 => near(n)];
        let mut st = verif::Stimulus::new(seed);
        let (cw, ch) = (coord(self.map.width()), coord(self.map.height()));
        st.draw_n(&(cw, ch), cycles)
            .into_iter()
            .map(|(u, v)| vec![u, v])
            .collect()
    }
}

/// The FIG. 7 pipeline against `rtl/bump/normal_pipeline_fig7.v` (built from the units'
/// twins), over `map` (`height_151.hex`) and, with `params.trilinear`, its next MIP level
/// (`height_151_l1.hex`, the model's own 2x2 average).
pub struct PipelineCosim {
    pub params: BumpParams,
    pub map: HeightMap,
}

impl PipelineCosim {
    /// A `w x h` map of the texel format of `params`, drawn from `map_seed`.
    pub fn new(params: BumpParams, w: u32, h: u32, map_seed: u64) -> PipelineCosim {
        let map = random_map(w, h, params.texel_fmt(), map_seed);
        PipelineCosim { params, map }
    }

    fn coarse(&self) -> Option<HeightMap> {
        self.params.trilinear.then(|| self.map.downsample())
    }
}

/// The twins of every unit of the FIG. 7 pipeline.
const PIPELINE_RTL: [&str; 9] = [
    "bump/normal_pipeline_fig7.v",
    "bump/address_150.v",
    "bump/texel_fetch_151.v",
    "bump/replicate_152.v",
    "bump/blend_adjust_153.v",
    "bump/bilinear_65_68.v",
    "bump/tangent_155.v",
    "bump/normal_156.v",
    "bump/rsqrt_156.v",
];

impl CosimUnit for PipelineCosim {
    fn name(&self) -> &str {
        "normal_pipeline_fig7"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(PIPELINE_RTL.to_vec())
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        use units::bump::params::Filter;
        let p = &self.params;
        let w = |f: Format| i64::from(f.width());
        let (border, value) = border_code(p.border);
        let filter = match p.filter {
            Filter::BSpline => 0,
            Filter::Bezier => 1,
            Filter::Blinn => 2,
        };
        let (w1, h1) = self
            .coarse()
            .map_or((8, 8), |c| (c.width().into(), c.height().into()));
        vec![
            ("POS_INT", p.pos_int.into()),
            ("POS_FRAC", p.pos_frac.into()),
            ("F", p.blend_bits.into()),
            ("TEXEL_BITS", w(p.texel_fmt())),
            ("FILTER", filter),
            ("BORDER", border),
            ("BORDER_VALUE", value),
            ("MAP_W", self.map.width().into()),
            ("MAP_H", self.map.height().into()),
            ("TRILINEAR", p.trilinear.into()),
            ("MAP1_W", w1),
            ("MAP1_H", h1),
            ("BL_W", w(p.bilinear_fmt())),
            ("BL_F", p.bilinear_fmt().frac().into()),
            ("SCALE_W", w(p.scale_fmt())),
            ("SCALE_F", p.scale_frac.into()),
            ("TAN_W", w(p.tangent_fmt())),
            ("H_W", w(p.height_out_fmt())),
            ("TAN_F", p.tangent_frac.into()),
            ("OUT_F", p.out_frac.into()),
            ("TABLE_BITS", p.rsqrt.table_bits.into()),
            ("ITERATIONS", p.rsqrt.iterations.into()),
            ("M_F", p.rsqrt.mant_frac.into()),
            ("Y_F", p.rsqrt.y_frac.into()),
        ]
    }
    fn memories(&self) -> Vec<(String, String)> {
        let mut m = vec![("height_151.hex".to_string(), memory_image(&self.map))];
        if let Some(c) = self.coarse() {
            m.push(("height_151_l1.hex".into(), memory_image(&c)));
        }
        m
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::bump::normal_pipeline_fig7::NormalPipeline;
        let dut = NormalPipeline::new(self.name(), self.params, self.map.clone(), self.coarse())?;
        Ok(Box::new(ModelSim::new(
            dut,
            |d: &mut NormalPipeline, v: &[u64]| {
                Signal::set_row(
                    [
                        &mut d.valid_in,
                        &mut d.u,
                        &mut d.v,
                        &mut d.scale,
                        &mut d.lod,
                    ],
                    v,
                );
            },
        )))
    }
    /// Positions within two texels of the map three times in four (every border crossed),
    /// anywhere otherwise; any scale and MIP weight, corners included; valid at random.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::Strategy;
        let p = &self.params;
        let w = p.pos_fmt().width();
        let mask = u64::MAX >> (64 - w);
        let one = 1i64 << p.pos_frac;
        let near =
            move |n: u32| (-2 * one..=(i64::from(n) + 2) * one).prop_map(move |x| x as u64 & mask);
        let pos = |n: u32| proptest::prop_oneof![1 => field(w), 3 => near(n)];
        let (f, sw) = (p.blend_bits, p.scale_fmt().width());
        let strategy = (
            0u64..2,
            pos(self.map.width()),
            pos(self.map.height()),
            field(sw),
            field(f),
        );
        let mut st = verif::Stimulus::new(seed);
        st.draw_n(&strategy, cycles)
            .into_iter()
            .map(|(valid, u, v, s, l)| vec![valid, u, v, s, l])
            .collect()
    }
}
