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

#[cfg(test)]
mod tests {
    use super::*;
    use verif::Shard;

    /// The shards of every split deal out each configuration once: their counts add up to the
    /// whole run's, testbench by testbench and over all.
    #[test]
    fn shards_own_every_configuration_once() {
        let project = project();
        let reg = project.registry();
        let whole: u64 = reg.iter().map(|t| t.configurations().len() as u64).sum();
        assert!(
            whole > reg.names().len() as u64,
            "some testbench has several"
        );
        assert_eq!(reg.owned_configurations(Shard::default(), &[]), whole);
        for count in [2, 3, 7] {
            let shards = (1..=count).map(|index| Shard { index, count });
            let parts: Vec<u64> = shards.map(|s| reg.owned_configurations(s, &[])).collect();
            assert_eq!(parts.iter().sum::<u64>(), whole, "{count} shards");
        }
        for (i, t) in reg.iter().enumerate() {
            let only = [t.name().to_string()];
            let n = reg.owned_configurations(Shard::default(), &only);
            assert_eq!(n, t.configurations().len() as u64, "{}", t.name());
            assert_eq!(reg.position(t.name()), Some(i));
        }
    }

    /// The progress line's unit: the default for a testbench of random transactions, its own
    /// for one that counts something else.
    #[test]
    fn each_testbench_says_what_its_count_counts() {
        let project = project();
        let reg = project.registry();
        let unit = |n: &str| reg.get(n).unwrap().count_unit();
        assert_eq!(unit(crate::blend_adjust::NAME), "random transactions");
        assert_ne!(unit(crate::texture::NAME), "random transactions");
        assert!(reg.iter().all(|t| !t.count_unit().is_empty()));
    }
}

#[cfg(test)]
mod lists {
    use super::project;
    use std::collections::BTreeSet;
    use std::path::Path;

    fn read(rel: &str) -> String {
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
    }

    /// The backticked names of a column of a markdown table (rows starting with `|` or `//! |`).
    fn column(text: &str, col: usize) -> BTreeSet<String> {
        let mut names = BTreeSet::new();
        for line in text.lines() {
            let line = line.trim_start_matches("//!").trim();
            if !line.starts_with('|') || line.starts_with("|---") {
                continue;
            }
            if let Some(cell) = line.split('|').nth(col + 1) {
                for part in cell.split('`').skip(1).step_by(2) {
                    names.insert(part.to_string());
                }
            }
        }
        names
    }

    /// The unit table of the units crate names every unit of the project as a kind (or an
    /// instance), every testbench it names is one of the project's, and it names every twin's
    /// sources and every unit's kept vectors, which exist.
    #[test]
    fn the_unit_table_agrees_with_the_project() {
        let p = project();
        let table = read("../hdl/units/src/lib.rs");
        let kinds = column(&table, 2);
        for u in p.units() {
            assert!(
                kinds.contains(u.name()),
                "{} is not in the unit table",
                u.name()
            );
        }
        let tbs = column(&table, 3);
        for t in tbs
            .iter()
            .filter(|t| !t.contains('/') && !t.ends_with(".rs"))
        {
            assert!(
                p.registry().get(t).is_some(),
                "the unit table names testbench {t}"
            );
        }
        for t in p.registry().names() {
            assert!(tbs.contains(t), "testbench {t} is not in the unit table");
        }
        let twins = column(&table, 5);
        for f in &twins {
            let path = crate::cosim::rtl_dir().join(f);
            assert!(path.exists(), "the unit table names twin {f}, not in rtl/");
        }
        for u in p.twins() {
            for f in u.rtl() {
                let f = f.to_string_lossy();
                let name = &f[f.rfind("rtl/").map_or(0, |k| k + 4)..];
                assert!(twins.contains(name), "{} is not in the unit table", name);
            }
        }
        let vectors = column(&table, 6);
        for f in &vectors {
            let path = crate::vectors::vectors_dir().join(f);
            assert!(path.exists(), "the unit table names vectors {f}, not kept");
        }
        for u in p.units().filter(|u| u.vectors_fn().is_some()) {
            let f = format!("{}.json", u.name());
            assert!(vectors.contains(&f), "{f} is not in the unit table");
        }
    }

    /// Every unit with a testbench keeps bit-accuracy vectors, or says in its descriptor why not.
    #[test]
    fn every_testbench_unit_has_vectors_or_a_reason() {
        let p = project();
        for u in p.units().filter(|u| !p.testbenches_of(u.name()).is_empty()) {
            assert!(
                u.vectors_fn().is_some() || u.no_vectors_reason().is_some(),
                "{} has a testbench but no vectors and no reason",
                u.name()
            );
        }
    }

    /// No list of unit names is kept by hand beside the project: no `UNITS` constant, no
    /// `registry()` and no `match` on unit names in the crates that serve the command line.
    #[test]
    fn no_other_list_of_units() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut files = Vec::new();
        for dir in ["tb/src", "cli/src", "bench/src", "verif/src"] {
            collect(&root.join(dir), &mut files);
        }
        let names: Vec<String> = project()
            .names()
            .iter()
            .map(|n| format!("\"{n}\" =>"))
            .collect();
        for f in files.iter().filter(|f| !f.ends_with("tb/src/project.rs")) {
            let text = std::fs::read_to_string(f).unwrap();
            for bad in ["const UNITS", "fn registry()", "fn unit_vectors("] {
                assert!(!text.contains(bad), "{}: {bad}", f.display());
            }
            for n in &names {
                assert!(
                    !text.contains(n.as_str()),
                    "{}: a match on {n}",
                    f.display()
                );
            }
        }
    }

    fn collect(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                collect(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
}
