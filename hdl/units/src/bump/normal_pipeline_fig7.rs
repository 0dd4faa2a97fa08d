//! The normal-generation pipeline of FIG. 7 of US 2004/0207631 (para. 0050-0087): height map
//! in, unit normals out, one sample per clock.
//!
//! ```text
//! (u,v) -> address 150 -> texel fetch 151 -> replicate 152 -> bilinear 65..68 -> tangent 155 -> normal 156
//!                      \-> blend adjust 153 ------------------^ (factors)     ^ (tu, tv, scale, lod carried)
//! ```
//!
//! Stages (one register each): address; texel fetch with blend adjust beside it; bilinear
//! units; tangent unit; normal unit (square, rsqrt table, one per Newton-Raphson iteration,
//! multiply). Latency `7 + rsqrt.iterations` cycles (8 by default), throughput one sample per
//! clock. With `trilinear`, a second address unit, fetch, adjust, replicate and four more
//! bilinear units work on the next MIP level at `(u/2, v/2)` in parallel (para. 0081).
//!
//! Variants by [`BumpParams::filter`]: B-spline (unit 153 active), Bezier (unit 153 bypassed,
//! replicate 152 makes Equation 1's Bezier points), Blinn (unit 153 bypassed, tangents G-R and
//! B-R; the alpha unit's result is unused). Outputs: the unit normal and the interpolated,
//! scaled height (para. 0084).
//!
//! # Ports
//! | port | format |
//! |---|---|
//! | `valid_in` / `valid` | `u1` |
//! | `u`, `v` | `sQ<pos_int>.<pos_frac>`, texel units of the finer level |
//! | `scale` | `uQ<scale_int>.<scale_frac>` |
//! | `lod` | `uQ0.F`, weight of the coarser level (trilinear only) |
//! | `nx`, `ny`, `nz` | `sQ2.<out_frac>` |
//! | `height` | `uQ14.<tangent_frac>` |

use crate::bump::address_150::AddressUnit;
use crate::bump::bilinear_65_68::Bilinear;
use crate::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
use crate::bump::height_map::HeightMap;
use crate::bump::normal_156::Normal;
use crate::bump::params::{BumpParams, Filter};
use crate::bump::replicate_152::Replicate;
use crate::bump::tangent_155::Tangent;
use crate::bump::tangent_average_0081::TangentAverage;
use crate::bump::texel_fetch_151::TexelFetch;
use crate::fx::Format;
use crate::kernel::{Delay, Group, Module, Signal, Signals};

/// Per MIP level: address, fetch, adjust, replicate and four bilinear units, each a scope of
/// the pipeline's own.
#[derive(Clone, Debug, Group)]
struct Level {
    addr: AddressUnit,
    fetch: TexelFetch,
    adjust: BlendAdjust,
    rep: Replicate,
    bil: [Bilinear; 4],
}

/// Instance names per MIP level: every unit carries its number; level 1 (the coarser MIP
/// level of the trilinear variant) adds `_l1`.
const LEVEL_NAMES: [[&str; 4]; 2] = [
    [
        "address_150",
        "texel_fetch_151",
        "blend_adjust_153",
        "replicate_152",
    ],
    [
        "address_150_l1",
        "texel_fetch_151_l1",
        "blend_adjust_153_l1",
        "replicate_152_l1",
    ],
];
/// Bilinear units 65 (red), 66 (green), 67 (blue), 68 (alpha) of para. 0060.
const BIL_NAMES: [[&str; 4]; 2] = [
    [
        "bilinear_65_red",
        "bilinear_66_green",
        "bilinear_67_blue",
        "bilinear_68_alpha",
    ],
    [
        "bilinear_65_red_l1",
        "bilinear_66_green_l1",
        "bilinear_67_blue_l1",
        "bilinear_68_alpha_l1",
    ],
];

/// The four bilinear units 65-68 of one level.
fn bilinears(names: [&str; 4], p: &BumpParams) -> Result<[Bilinear; 4], String> {
    let [r, g, b, a] =
        names.map(|n| Bilinear::new(n, p.replicate_fmt(), p.adj_fmt(), p.bilinear_fmt()));
    Ok([r?, g?, b?, a?])
}

impl Level {
    fn new(k: usize, p: &BumpParams, map: HeightMap) -> Result<Level, String> {
        let n = LEVEL_NAMES[k];
        // The coarser level sees (u/2, v/2): the same bits with one more fraction bit.
        let pos = Format::signed(
            p.pos_int + p.pos_frac + k as u32,
            p.pos_frac as i32 + k as i32,
        );
        let addr = AddressUnit::new(n[0], pos, p.blend_bits)?;
        let coord = addr.ui.fmt();
        Ok(Level {
            addr,
            fetch: TexelFetch::new(n[1], map, p.border, coord)?,
            adjust: BlendAdjust::new(
                n[2],
                BlendAdjustParams {
                    frac_bits: p.blend_bits,
                    registered: true,
                },
            )?,
            rep: Replicate::new(n[3], p.texel_fmt(), p.filter == Filter::Bezier),
            bil: bilinears(BIL_NAMES[k], p)?,
        })
    }

    /// Address, fetch/adjust, replicate and bilinear stages for position `(u, v)` raw.
    #[inline]
    fn eval(&mut self, u: i64, v: i64, bypass: bool) {
        // Raw values, not bit patterns: the coarser level's position is one bit wider.
        self.addr.u.set_raw(u);
        self.addr.v.set_raw(v);
        self.addr.eval();
        self.fetch.ui.follow(&self.addr.ui);
        self.fetch.vj.follow(&self.addr.vj);
        self.fetch.eval();
        let a = &mut self.adjust;
        a.i.valid_in.set_bool(true);
        a.i.bypass.set_bool(bypass);
        a.i.u_in.follow(&self.addr.ub);
        a.i.v_in.follow(&self.addr.vb);
        a.eval();
        for k in 0..9 {
            self.rep.h[k].follow(&self.fetch.h[k]);
        }
        self.rep.eval();
        let o = &self.adjust.o;
        // Red (U0, V0), green (U1, V0), blue (U0, V1), alpha (U1, V1): para. 0060.
        let st = [
            (&o.u0, &o.v0),
            (&o.u1, &o.v0),
            (&o.u0, &o.v1),
            (&o.u1, &o.v1),
        ];
        for (w, b) in self.bil.iter_mut().enumerate() {
            for k in 0..4 {
                b.p[k].follow(&self.rep.w[w][k]);
            }
            b.s.follow(st[w].0);
            b.t.follow(st[w].1);
            b.eval();
        }
    }
}

/// Para. 0081's footprint tags of each sample, inputs of a pipeline with the tangent average.
#[derive(Clone, Debug, Signals)]
pub struct FootprintTags {
    /// The pixel's first sample.
    pub first: Signal,
    /// The pixel's last sample.
    pub last: Signal,
    /// log2 of the pixel's sample count.
    pub log2_n: Signal,
}

/// Para. 0081's tangent average and the tags carried to it, 4 stages, from the inputs.
#[derive(Clone, Debug, Group)]
struct Average {
    tags: Delay<3>,
    average: TangentAverage,
}

/// The FIG. 7 pipeline.
#[derive(Clone, Debug, Module)]
#[module(kind = "normal_pipeline_fig7")]
pub struct NormalPipeline {
    #[instance]
    name: String,
    params: BumpParams,
    #[input]
    pub valid_in: Signal,
    #[input]
    pub u: Signal,
    #[input]
    pub v: Signal,
    #[input]
    pub scale: Signal,
    #[input]
    pub lod: Signal,
    #[output]
    pub valid: Signal,
    #[output]
    pub nx: Signal,
    #[output]
    pub ny: Signal,
    #[output]
    pub nz: Signal,
    #[output]
    pub height: Signal,
    #[child]
    levels: Vec<Level>,
    /// tu, tv (and tu1, tv1) from the address units to the tangent unit: 2 stages.
    #[child]
    blend_d: Delay<4>,
    /// scale, lod from the inputs to the tangent unit: 3 stages.
    #[child]
    side_d: Delay<2>,
    #[child]
    pub tangent: Tangent,
    /// Footprint assembly (para. 0081): each sample's `first`, `last` and `log2_n` of its
    /// pixel, carried 4 stages to the tangent unit's output, and the average before 156.
    #[input]
    pub fa: Option<FootprintTags>,
    #[child]
    average: Option<Average>,
    #[child]
    pub normal: Normal,
    #[child]
    height_d: Delay<1>,
    #[child]
    valid_d: Delay<1>,
}

impl NormalPipeline {
    /// The pipeline over `map` (and `coarse`, the next MIP level, when `p.trilinear`).
    pub fn new(
        name: &str,
        p: BumpParams,
        map: HeightMap,
        coarse: Option<HeightMap>,
    ) -> Result<NormalPipeline, String> {
        p.validate()?;
        if map.fmt() != p.texel_fmt() {
            return Err(format!(
                "height map texels are {}, the pipeline expects {}",
                map.fmt(),
                p.texel_fmt()
            ));
        }
        if p.rsqrt.table_bits > p.rsqrt.mant_frac {
            return Err("rsqrt.table_bits must not exceed rsqrt.mant_frac".into());
        }
        let mut levels = vec![Level::new(0, &p, map)?];
        match (p.trilinear, coarse) {
            (true, Some(c)) => levels.push(Level::new(1, &p, c)?),
            (true, None) => return Err("trilinear needs the coarser MIP level".into()),
            (false, _) => {}
        }
        let blend = p.blend_fmt();
        let normal = Normal::new("normal_156", &p)?;
        let latency = 4 + normal.latency();
        Ok(NormalPipeline {
            name: name.into(),
            params: p,
            valid_in: Signal::bit("valid_in"),
            u: Signal::new("u", p.pos_fmt()),
            v: Signal::new("v", p.pos_fmt()),
            scale: Signal::new("scale", p.scale_fmt()),
            lod: Signal::new("lod", blend),
            valid: Signal::bit("valid"),
            nx: Signal::new("nx", p.normal_fmt()),
            ny: Signal::new("ny", p.normal_fmt()),
            nz: Signal::new("nz", p.normal_fmt()),
            height: Signal::new("height", p.height_out_fmt()),
            levels,
            blend_d: Delay::new(
                "blend_carry",
                [("tu", blend), ("tv", blend), ("tu1", blend), ("tv1", blend)],
                2,
                ["tu_d", "tv_d", "tu1_d", "tv1_d"],
            ),
            side_d: Delay::new(
                "side_carry",
                [("scale", p.scale_fmt()), ("lod", blend)],
                3,
                ["scale_d", "lod_d"],
            ),
            tangent: Tangent::new("tangent_155", &p),
            height_d: Delay::new(
                "height_carry",
                [("height", p.height_out_fmt())],
                normal.latency(),
                ["height_d"],
            ),
            normal,
            valid_d: Delay::new(
                "valid_carry",
                [("valid", Format::uint(1))],
                latency,
                ["valid_d"],
            ),
            fa: None,
            average: None,
        })
    }

    /// Para. 0081's tangent average, when the pipeline has one.
    pub fn tangent_average(&self) -> Option<&TangentAverage> {
        self.average.as_ref().map(|a| &a.average)
    }

    /// The pipeline with para. 0081's tangent average between 155 and 156: the samples of a
    /// pixel come in one a clock (`valid_in` and the tags [`NormalPipeline::fa`]), and one
    /// normal a pixel comes out (`valid` with its last sample's).
    pub fn with_tangent_average(mut self) -> NormalPipeline {
        let tags = Delay::new(
            "fa_carry",
            [
                ("first", Format::uint(1)),
                ("last", Format::uint(1)),
                ("log2_n", Format::uint(3)),
            ],
            4,
            ["first_d", "last_d", "log2_n_d"],
        );
        self.fa = Some(FootprintTags {
            first: Signal::bit("fa_first"),
            last: Signal::bit("fa_last"),
            log2_n: Signal::new("fa_log2_n", Format::uint(3)),
        });
        self.average = Some(Average {
            tags,
            average: TangentAverage::new(&self.params),
        });
        self
    }

    /// Cycles from a sample's input to its normal.
    pub fn latency(&self) -> usize {
        self.valid_d.depth()
    }
}

impl NormalPipeline {
    /// Both MIP levels' units, the tangent unit, the average, the normal unit and the carries.
    pub fn eval(&mut self) {
        let bypass = self.params.filter != Filter::BSpline;
        let (u, v) = (self.u.raw(), self.v.raw());
        for l in &mut self.levels {
            l.eval(u, v, bypass);
        }
        // Blend factors and side values, carried to the tangent unit.
        let l0 = &self.levels[0].addr;
        self.blend_d.i[0].follow(&l0.ub);
        self.blend_d.i[1].follow(&l0.vb);
        if let Some(l1) = self.levels.get(1) {
            self.blend_d.i[2].follow(&l1.addr.ub);
            self.blend_d.i[3].follow(&l1.addr.vb);
        }
        self.blend_d.eval();
        self.side_d.i[0].follow(&self.scale);
        self.side_d.i[1].follow(&self.lod);
        self.side_d.eval();
        // Tangent unit 155.
        let t = &mut self.tangent;
        for (k, l) in self.levels.iter().enumerate() {
            for w in 0..4 {
                t.rgba[4 * k + w].follow(&l.bil[w].q);
            }
        }
        t.tu.follow(&self.blend_d.o[0]);
        t.tv.follow(&self.blend_d.o[1]);
        t.scale.follow(&self.side_d.o[0]);
        if let Some(l1) = &mut t.level1 {
            l1.tu1.follow(&self.blend_d.o[2]);
            l1.tv1.follow(&self.blend_d.o[3]);
            l1.lod.follow(&self.side_d.o[1]);
        }
        t.eval();
        // Normal unit 156, through the tangent average when there is one.
        let (du, dv, h) = match (&mut self.average, &self.fa) {
            (Some(Average { tags, average: a }), Some(fa)) => {
                tags.i[0].follow(&fa.first);
                tags.i[1].follow(&fa.last);
                tags.i[2].follow(&fa.log2_n);
                tags.eval();
                a.first.follow(&tags.o[0]);
                a.last.follow(&tags.o[1]);
                a.log2_n.follow(&tags.o[2]);
                a.du_in.follow(&self.tangent.du);
                a.dv_in.follow(&self.tangent.dv);
                a.h_in.follow(&self.tangent.height);
                a.eval();
                (&a.du, &a.dv, &a.height)
            }
            _ => (&self.tangent.du, &self.tangent.dv, &self.tangent.height),
        };
        self.normal.du.follow(du);
        self.normal.dv.follow(dv);
        self.height_d.i[0].follow(h);
        self.normal.eval();
        self.height_d.eval();
        // With the average, a normal is out for each pixel's last sample.
        let last = self.fa.as_ref().is_none_or(|fa| fa.last.is_high());
        self.valid_d.i[0].set_bool(self.valid_in.is_high() && last);
        self.valid_d.eval();
        self.valid.follow(&self.valid_d.o[0]);
        self.nx.follow(&self.normal.nx);
        self.ny.follow(&self.normal.ny);
        self.nz.follow(&self.normal.nz);
        self.height.follow(&self.height_d.o[0]);
    }
}
