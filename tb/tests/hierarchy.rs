//! Every module's `visit` reaches every child: the instance tree of each top, against the
//! units its figure says it holds (a module count and the kinds, by hand from the figures).

use hdl::kernel::{instances, Module};
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::BumpParams;
use units::mipmap::{MipmapGen, MipmapParams, Rounding, Scan};
use units::texmem::texture_unit_602::{TexParams, TextureUnit};

/// `(kind, count)` of every instance under `top`, sorted by kind.
fn kinds(top: &dyn Module) -> Vec<(String, usize)> {
    let mut m = std::collections::BTreeMap::new();
    for (_, k) in instances(top) {
        *m.entry(k).or_insert(0) += 1;
    }
    m.into_iter().collect()
}

/// The instance paths under `top`; none has an empty name.
fn paths(top: &dyn Module) -> Vec<String> {
    let names: Vec<String> = instances(top).into_iter().map(|(p, _)| p).collect();
    for n in &names {
        assert!(
            n.split('.').all(|s| !s.is_empty()),
            "an unnamed instance: {n}"
        );
    }
    names
}

fn own(v: &[(&str, usize)]) -> Vec<(String, usize)> {
    let mut v: Vec<(String, usize)> = v.iter().map(|(k, n)| (k.to_string(), *n)).collect();
    v.sort();
    v
}

#[test]
fn fig7_pipeline_visits_every_unit_and_delay_line() {
    let p = BumpParams::default();
    let map = tb::maps::builtin("noise", 8, 8, p.texel_fmt()).unwrap();
    let top = NormalPipeline::new("normal_pipeline_fig7", p, map.clone(), None).unwrap();
    // 150, 151, 153, 152, four bilinear units, 155, 156 with its rsqrt; four delay lines of
    // the pipeline and one inside 156.
    let want = [
        ("normal_pipeline_fig7", 1),
        ("address_150", 1),
        ("texel_fetch_151", 1),
        ("blend_adjust_153", 1),
        ("replicate_152", 1),
        ("bilinear_65_68", 4),
        ("tangent_155", 1),
        ("normal_156", 1),
        ("rsqrt_156", 1),
        ("delay", 5),
    ];
    assert_eq!(kinds(&top), own(&want));
    assert_eq!(instances(&top).len(), 17);
    // Each unit's scope is its instance name, the figure's numeral (one hop to the module).
    let names = paths(&top);
    for unit in [
        "address_150",
        "texel_fetch_151",
        "blend_adjust_153",
        "replicate_152",
        "bilinear_65_red",
        "bilinear_68_alpha",
        "tangent_155",
        "normal_156",
        "normal_156.rsqrt_156",
    ] {
        let path = format!("normal_pipeline_fig7.{unit}");
        assert!(names.contains(&path), "{path} not visited: {names:?}");
    }
    // Trilinear: a second address, fetch, adjust, replicate and four bilinear units.
    let tri = BumpParams {
        trilinear: true,
        ..p
    };
    let top = NormalPipeline::new(
        "normal_pipeline_fig7",
        tri,
        map.clone(),
        Some(map.downsample()),
    )
    .unwrap();
    assert_eq!(instances(&top).len(), 17 + 8);
}

#[test]
fn figure6_texture_unit_visits_every_unit() {
    let p = TexParams::new(16, 16);
    let clut = vec![0u32; 256];
    let words = vec![0u16; 2 * 16];
    let top = TextureUnit::new("texture_unit_602", p, &clut, &words).unwrap();
    let names = paths(&top);
    for unit in [
        "texture_unit_602.fill_engine_607",
        "texture_unit_602.lookahead_queue_607",
        "texture_unit_602.control_607",
        "texture_unit_602.control_607.dram_604",
        "texture_unit_602.ccc_decode_608",
        "texture_unit_602.cache_614",
        "texture_unit_602.cache_614.entry_a",
        "texture_unit_602.cache_614.entry_d",
        "texture_unit_602.extract_618",
        "texture_unit_602.bilinear_622",
    ] {
        assert!(
            names.iter().any(|n| n == unit),
            "{unit} not visited: {names:?}"
        );
    }
    // Figure 6's units once each, the cache's four entries.
    let want = [
        ("texture_unit_602", 1),
        ("fill_engine_607", 1),
        ("lookahead_queue_607", 1),
        ("control_607", 1),
        ("dram_604", 1),
        ("ccc_decode_608", 1),
        ("cache_614", 1),
        ("cache_614_entry", 4),
        ("extract_618", 1),
        ("bilinear_622", 1),
    ];
    assert_eq!(kinds(&top), own(&want));
}

#[test]
fn fig14_generator_visits_every_level_and_fifo() {
    let p = MipmapParams {
        width: 16,
        height: 8,
        scan: Scan::InterlacedTop,
        rounding: Rounding::Round,
    };
    let top = MipmapGen::new("mipmap_gen_816", p).unwrap();
    // 16x8 has levels 1..4 (8x4, 4x2, 2x1, 1x1), each with FIFOs 1408 and 1412.
    let want = [
        ("mipmap_gen_816", 1),
        ("page_registers_824", 1),
        ("mipmap_level_fig14", 4),
        ("fifo_1408", 4),
        ("fifo_1412", 4),
        ("mem", 8),
    ];
    assert_eq!(kinds(&top), own(&want));
    let names = paths(&top);
    for unit in [
        "level1",
        "level1.fifo_1408",
        "level4.fifo_1412",
        "level4.fifo_1412.entries",
    ] {
        let path = format!("mipmap_gen_816.{unit}");
        assert!(names.contains(&path), "{path} not visited: {names:?}");
    }
}

/// The signal paths of `top` containing `part`, counted.
fn paths_with(top: &dyn Module, part: &str) -> usize {
    hdl::kernel::signal_paths(top)
        .iter()
        .filter(|p| p.contains(part))
        .count()
}

/// Whether every signal of `top` is under its own scope `scope` (the top's instance name).
fn all_under(top: &dyn Module, scope: &str) -> bool {
    let paths = hdl::kernel::signal_paths(top);
    !paths.is_empty() && paths.iter().all(|p| p.starts_with(&format!("{scope}.")))
}

/// The environment map's units: their signals and their kind.
#[test]
fn the_environment_map_units_visit_every_signal() {
    use units::envmap::cube_face::CubeFace;
    use units::envmap::reflect_eq4::Reflect;
    assert_eq!(paths_with(&CubeFace::new(), "cube_face."), 8);
    // valid_in, six inputs, valid, three outputs, the three narrowings' saturation flags.
    assert_eq!(paths_with(&Reflect::new(), "reflect_eq4."), 14);
    assert_eq!(kinds(&CubeFace::new()), own(&[("cube_face", 1)]));
    assert_eq!(kinds(&Reflect::new()), own(&[("reflect_eq4", 1)]));
}

/// The units beside the TEXRAM chip (video port, footprint assembly, ray caster): every
/// scope their waveforms are read by, with its signals.
#[test]
fn the_texram_side_units_visit_every_scope() {
    use units::footprint::footprint_fig12::FootprintFig12;
    use units::footprint::normals_0081::FootprintNormals;
    use units::footprint::setup_fig12::SetupParams;
    use units::texram::texram_802::{Texram802, TexramParams};
    use units::volume::layout::{Mode, VolumeParams};
    use units::volume::lockstep::VolumeLockstep;
    use units::volume::ray_caster_fig15::RayCaster;
    let chip = Texram802::new(TexramParams::default()).unwrap();
    let fa = FootprintFig12::new(SetupParams::default(), chip).unwrap();
    for (part, n) in [
        // 9 inputs, in_ready, 9 registers, 4 wires.
        ("footprint_setup.", 23),
        ("footprint_assembly.generator.", 7),
        ("footprint_assembly.accumulator.", 9),
        // The access (valid, read, 32 bank words, src, border, weights, colour, index, part,
        // last, illum, modulate), the held request's four and conflicts.
        ("footprint_assembly.texram_802.address_812.", 48),
        ("footprint_assembly.px_", 9),
    ] {
        assert_eq!(paths_with(&fa, part), n, "{part}");
    }
    let p = BumpParams::default();
    let map = tb::maps::builtin("noise", 8, 8, p.texel_fmt()).unwrap();
    let fig7 = NormalPipeline::new("normal_pipeline_fig7", p, map, None).unwrap();
    let fn7 = FootprintNormals::new(fig7);
    for (part, n) in [
        ("footprint_normals_0081.generator.", 8),
        ("tangent_average_0081.", 12),
        ("fa_carry.", 6),
        // fa_first, fa_last, fa_log2_n and the six of the fa_carry delay line.
        ("normal_pipeline_fig7.fa_", 9),
    ] {
        assert_eq!(paths_with(&fn7, part), n, "{part}");
    }
    let vp = VolumeParams::new(4, 4, 4);
    let rc = RayCaster::new(vp, Mode::Gradient, &[0; 64]).unwrap();
    for (part, n) in [
        ("ray_caster_fig15.stepper.", 9),
        ("ray_caster_fig15.page_registers_824.", 4),
        ("ray_caster_fig15.sequencer.", 39),
        ("ray_caster_fig15.trilinear_818.", 11),
        ("ray_caster_fig15.ray_", 9),
    ] {
        assert_eq!(paths_with(&rc, part), n, "{part}");
    }
    let ls =
        VolumeLockstep::new(vp, &[vec![0; 64], vec![0; 64], vec![0; 64], vec![0; 64]]).unwrap();
    for chip in ["chip_r.", "chip_g.", "chip_b.", "chip_a."] {
        assert_eq!(
            paths_with(&ls, chip),
            paths_with(&rc, "ray_caster_fig15."),
            "{chip}"
        );
    }
    assert_eq!(paths_with(&ls, "volume_lockstep.out_"), 3);
    for (top, scope) in [
        (&fa as &dyn Module, "footprint_fig12"),
        (&fn7, "footprint_normals_0081"),
        (&rc, "ray_caster_fig15"),
        (&ls, "volume_lockstep"),
    ] {
        assert!(all_under(top, scope), "{scope}");
    }
    // Every instance's kind, by hand from the modules' documentation.
    let caster = [
        ("ray_caster_fig15", 1),
        ("volume_stepper", 1),
        ("page_registers_824", 1),
        ("access_sequencer", 1),
        ("trilinear_818", 1),
    ];
    assert_eq!(kinds(&rc), own(&caster));
    let four = caster.map(|(k, n)| (k, 4 * n));
    let mut lock = four.to_vec();
    lock.push(("volume_lockstep", 1));
    assert_eq!(kinds(&ls), own(&lock));
    let k = kinds(&fa);
    for kind in [
        "footprint_fig12",
        "footprint_setup",
        "footprint_assembly",
        "footprint_generator",
        "footprint_accumulator",
        "texram_802",
    ] {
        assert!(k.iter().any(|(x, n)| x == kind && *n == 1), "{kind}: {k:?}");
    }
    let k = kinds(&fn7);
    for kind in [
        "footprint_normals_0081",
        "footprint_generator",
        "tangent_average_0081",
        "normal_pipeline_fig7",
    ] {
        assert!(k.iter().any(|(x, n)| x == kind && *n == 1), "{kind}: {k:?}");
    }
}

/// The map chain and the per-pixel units (derivative, bi-quadratic, frames, parallax, PTM): each
/// its own scope named after its kind, with every port and register (counted by hand from the
/// modules' port tables).
#[test]
fn the_map_chain_and_per_pixel_units_visit_every_signal() {
    use units::bump::biquadratic_0087::{Biquadratic0087, ColourMap};
    use units::bump::derivative_0086::{DerivFilter, Derivative, DerivativeUnit};
    use units::bump::params::Border;
    use units::frames::frame_unit::FrameUnit;
    use units::frames::parallax::ParallaxUnit;
    use units::frames::tangent_setup::TangentSetup;
    use units::ptm::fitter_604::Fitter604;
    use units::ptm::shader_608::Shader608;
    use units::ptm::texture_612::PtmFormat;
    let maps = tb::mapchain::Maps::formula();
    let sc = tb::mapchain::scene(tb::mapchain::Shape::Longest, &maps).unwrap();
    let walker =
        units::mapchain::walker_812::MapChain812::new(sc.file.clone(), sc.stub().unwrap(), 6)
            .unwrap();
    // req_valid, 13 pixel fields, req_ready, 18 walk registers, 13 held fields
    // (walker_812.pixel), busy, 3 counts, out_valid, colour, error, 3 out counts; the banks:
    // acc_valid, 5 access fields, rd_value, rd_slots, refused, and the stub's 8 open rows.
    assert_eq!(
        paths_with(&walker, "walker_812."),
        1 + 13 + 1 + 18 + 13 + 1 + 3 + 3 + 3 + (1 + 5 + 3 + 8)
    );
    assert_eq!(paths_with(&walker, "walker_812.banks."), 1 + 5 + 3 + 8);
    // The pixel it holds and the banks are scopes of their own.
    assert_eq!(
        kinds(&walker),
        own(&[
            ("walker_812", 1),
            ("pixel", 1),
            ("bank_port_810", 1),
            ("page_registers_824", 1)
        ])
    );
    let fmt = PtmFormat {
        bits: 8,
        exp: [4; 6],
        bias: [0; 6],
    };
    let p: [Vec<i32>; 6] = std::array::from_fn(|_| vec![1; 8]);
    let fit = Fitter604::new(p, fmt).unwrap();
    // in_valid, in_sample, k, light, out_valid, six lanes, six q, six saturation flags.
    assert_eq!(paths_with(&fit, "ptm_fitter_604."), 23);
    // in_valid, q1..q6, u, v, out_valid, k, visibility, k's saturation flag.
    assert_eq!(
        paths_with(&Shader608::new(fmt).unwrap(), "ptm_shader_608."),
        13
    );
    // valid_in, 6 + 4 + 3 inputs, 12 vector registers, valid, degenerate, zero, the 12
    // narrowings' saturation flags (dP/du, dP/dv, t, b).
    assert_eq!(
        paths_with(&TangentSetup::new(), "tangent_setup."),
        1 + 13 + 12 + 3 + 12
    );
    // valid_in, gram_schmidt, 9 + 3 inputs, 9 outputs, valid, zero, the 12 narrowings'
    // saturation flags (N's unit, Gram-Schmidt's t and b, the perturbed normal).
    assert_eq!(
        paths_with(&FrameUnit::new(), "frame_unit."),
        2 + 12 + 9 + 2 + 12
    );
    // 5 + 2 + 3 inputs, valid, two outputs, the two narrowings' saturation flags.
    assert_eq!(paths_with(&ParallaxUnit::new(), "parallax."), 15);
    let map = tb::maps::builtin("noise", 8, 8, BumpParams::default().texel_fmt()).unwrap();
    let d = DerivativeUnit::new(Derivative::new(DerivFilter::Sobel, map, Border::Wrap, 16));
    // valid_in, u, v, scale, valid, three outputs, their narrowings' saturation flags.
    assert_eq!(paths_with(&d, "derivative_0086."), 11);
    let cm = ColourMap {
        width: 2,
        height: 2,
        rgb: vec![0; 12],
        border: Border::Wrap,
    };
    assert_eq!(
        paths_with(&Biquadratic0087::new(cm).unwrap(), "biquadratic_0087."),
        7 + 3,
        "and the three channels' saturation flags"
    );
    for (top, kind) in [
        (&fit as &dyn Module, "ptm_fitter_604"),
        (&TangentSetup::new(), "tangent_setup"),
        (&FrameUnit::new(), "frame_unit"),
        (&ParallaxUnit::new(), "parallax"),
        (&d, "derivative_0086"),
    ] {
        assert_eq!(kinds(top), own(&[(kind, 1)]));
        assert_eq!(top.instance(), kind);
    }
}
