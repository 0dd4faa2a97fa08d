//! The texture project: every unit of the source documents that texrtl models, described once
//! by a [`verif::project::Unit`] (its testbench, its Verilog twin in `rtl/`, its bit-accuracy
//! vectors under `golden/vectors/`, its report pictures), in the order of the documents and
//! their figures. Every list the `texrtl` command uses is read from [`project`]; adding a unit
//! is one more descriptor here (see CONTRIBUTING.md).

use crate::cosim::{self as c, vectors as directed};
use crate::pictures::{self, one};
use crate::vectors as v;
use units::mipmap::mipmap_gen_816::{MipmapParams, Rounding, Scan};
use units::texmem::texture_unit_602::TexParams;
use verif::project::{Project, Unit};

/// The texture project, as the `texrtl` command runs it.
pub fn project() -> Project {
    let p = Project::new("texrtl", env!("CARGO_PKG_VERSION")).vectors_dir(v::vectors_dir());
    let p = fenney_fig7(p);
    let p = figure_6_memory_path(p);
    let p = texram_figure_8(figure_14(p));
    ptm_and_frames(p)
}

/// Schilling & Knittel Figure 6: DRAM 604 and its control unit 607, the cache 614, the
/// texture mapping unit 602 end to end.
fn figure_6_memory_path(p: Project) -> Project {
    p.unit(
        Unit::new(
            crate::dram::NAME,
            "DRAM control unit 607 with the DRAM 604: word reads, block fetch",
        )
        .testbench(crate::dram::DramTb)
        .twin(c::ControlCosim(Default::default()))
        .without_vectors("none kept yet: its pins are co-simulated cycle for cycle in every regression"),
    )
        .unit(
            Unit::new("lookahead_queue_607", "lookahead queue of the DRAM control unit 607")
                .twin(c::LookaheadCosim {
                    mode: Default::default(),
                    blocks: (16, 16),
                    frac_bits: 4,
                }),
        )
        .unit(
            Unit::new("cache_614", "texture cache 614, four entries (Figure 7)")
                .twin(c::CacheCosim { tag_bits: 9 }),
        )
        .unit(
            Unit::new("fill_engine_607", "block fill engine of the DRAM control unit 607").twin(
                c::FillCosim {
                    layout: units::texmem::layout::Layout::RowMajor,
                    blocks: (16, 16),
                    base: 0,
                    dram: Default::default(),
                },
            ),
        )
        .unit(
            Unit::new(
                crate::texture::NAME,
                "texture mapping unit 602 (Schilling & Knittel Figure 6): DRAM 604, control 607, CCC decode 608-612, cache 614, extract 618, bilinear 622",
            )
            .testbench(crate::texture::TextureTb)
            .twin(c::TextureCosim(TexParams::new(64, 64)))
            .vectors(v::texture)
            .pictures(pictures::memory),
        )
}

/// Schilling & Knittel Figure 14: the real-time mipmap generator.
fn figure_14(p: Project) -> Project {
    p.unit(
        Unit::new(
            crate::mipmap::NAME,
            "mipmap generation unit 816 (Figure 14)",
        )
        .testbench(crate::mipmap::MipmapTb)
        .twin(c::MipmapCosim::new(MipmapParams {
            width: 16,
            height: 16,
            scan: Scan::Progressive,
            rounding: Rounding::Round,
        }))
        .vectors(v::mipmap)
        .directed(|| Ok(directed::mipmap()))
        .pictures(one(pictures::mipmap_picture)),
    )
}

/// Fenney's FIG. 7 (000): the pipeline's units, the pipeline, and paragraphs 0081-0087.
fn fenney_fig7(p: Project) -> Project {
    p.unit(
        Unit::new("address_150", "address unit 150 (Fenney FIG. 7)")
            .twin(c::AddressCosim::default()),
    )
    .unit(
        Unit::new("texel_fetch_151", "texel fetch 151").twin(c::TexelFetchCosim::new(
            Default::default(),
            16,
            16,
            1,
        )),
    )
    .unit(
        Unit::new("replicate_152", "replicate unit 152").twin(c::ReplicateCosim {
            texel_bits: 8,
            bezier: false,
        }),
    )
    .unit(
        Unit::new(crate::blend_adjust::NAME, "blend-factor adjust 153")
            .testbench(crate::blend_adjust::BlendAdjustTb::default())
            .twin(c::BlendAdjustCosim(Default::default()))
            .vectors(|| Ok(v::blend_adjust()))
            .directed(|| Ok(vec![directed::blend_adjust()])),
    )
    .unit(
        Unit::new("bilinear_65_68", "bilinear units 65, 66, 67, 68").twin(c::BilinearCosim {
            texel_bits: 8,
            blend_bits: 8,
            bilinear_frac: None,
        }),
    )
    .unit(Unit::new("tangent_155", "tangent unit 155").twin(c::TangentCosim(Default::default())))
    .unit(
        Unit::new("rsqrt_156", "inverse square root of the normal unit 156")
            .twin(c::RsqrtCosim(Default::default())),
    )
    .unit(Unit::new("normal_156", "normal unit 156").twin(c::NormalCosim(Default::default())))
    .unit(
        Unit::new(crate::normals::NAME, "the FIG. 7 per-pixel normal pipeline")
            .testbench(crate::normals::NormalsTb)
            .twin(c::PipelineCosim::new(Default::default(), 16, 16, 1))
            .vectors(v::normals)
            .directed(directed::pipeline)
            .pictures(one(pictures::normals_picture)),
    )
    .unit(
        Unit::new(
            crate::footprint_normals::NAME,
            "footprint generator and tangent average before the FIG. 7 pipeline (para. 0081)",
        )
        .testbench(crate::footprint_normals::FootprintNormalsTb)
        .without_vectors("none kept yet: the FIG. 7 pipeline's vectors pin the normals after it"),
    )
    .unit(
        Unit::new(crate::derivative::NAME, "derivative filters (para. 0086)")
            .testbench(crate::derivative::DerivativeTb)
            .vectors(v::derivative)
            .pictures(one(pictures::derivative_picture)),
    )
    .unit(
        Unit::new(crate::biquadratic::NAME, "bi-quadratic colour (para. 0087)")
            .testbench(crate::biquadratic::BiquadraticTb)
            .vectors(v::biquadratic),
    )
}

/// The TEXRAM chip of Figure 8 and what is built on it (sections 4-14).
fn texram_figure_8(p: Project) -> Project {
    p.unit(
        Unit::new(
            crate::texram::NAME,
            "TEXRAM chip 802 (Schilling & Knittel Figure 8)",
        )
        .testbench(crate::texram::TexramTb)
        .twin(c::TexramCosim { slot_cycles: 6 })
        .vectors(v::texram)
        .pictures(one(pictures::texram_plot)),
    )
    .unit(
        Unit::new(
            crate::texram_video::NAME,
            "video port 808 and shift registers 826",
        )
        .testbench(crate::texram_video::VideoPortTb)
        .without_vectors("none kept yet: its testbench checks every frame against the reference"),
    )
    .unit(
        Unit::new(
            crate::footprint::NAME,
            "footprint assembly (section 10, Figures 12-13)",
        )
        .testbench(crate::footprint::FootprintTb)
        .vectors(v::footprint)
        .pictures(one(pictures::footprint_picture)),
    )
    .unit(
        Unit::new(
            crate::volume::NAME,
            "the TEXRAM as a ray caster (section 13, Figure 15)",
        )
        .testbench(crate::volume::VolumeTb)
        .vectors(v::volume)
        .pictures(one(pictures::volume_picture)),
    )
    .unit(
        Unit::new(
            crate::mapchain::NAME,
            "chain walker of 812 with the output stage 820 (section 14)",
        )
        .testbench(crate::mapchain::WalkerTb)
        .twin(c::WalkerCosim { slot_cycles: 6 })
        .vectors(v::mapchain)
        .pictures(one(pictures::mapchain_picture)),
    )
}

/// PTM micro-occlusion (001) and the tangent frames (003, 002).
fn ptm_and_frames(p: Project) -> Project {
    p.unit(
        Unit::new(crate::ptm::FITTER, "PTM fitter 604 (001, Fig. 6)")
            .testbench(crate::ptm::PtmFitterTb)
            .vectors(v::ptm_fitter)
            .pictures(one(pictures::ptm_picture)),
    )
    .unit(
        Unit::new(crate::ptm::SHADER, "PTM light shader 608 (001, Fig. 6)")
            .testbench(crate::ptm::PtmShaderTb)
            .vectors(v::ptm_shader),
    )
    .unit(
        Unit::new(crate::tangents::NAME, "tangent setup (003)")
            .testbench(crate::tangents::TangentSetupTb)
            .vectors(v::tangent_setup),
    )
    .unit(
        Unit::new(crate::frames::FRAME, "per-pixel frame unit (003, 002)")
            .testbench(crate::frames::FrameUnitTb)
            .vectors(v::frame_unit),
    )
    .unit(
        Unit::new(crate::frames::PARALLAX, "parallax (002)")
            .testbench(crate::frames::ParallaxTb)
            .vectors(v::parallax),
    )
}
