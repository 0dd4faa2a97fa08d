//! texrtl's texture-mapping units: the datapath models of the source documents, built on the
//! RTL kernel and fixed point of `texrtl-hdl` (re-exported here as [`kernel`] and [`fx`]).
//!
//! No floating point is used inside a model: values are integers with a declared
//! [`fx::Format`]; conversions to `f64` exist only at the edges (tracing, golden comparison).
//!
//! # The documents
//! The units model five source documents, cited by number: **000** US 2004/0207631 (Fenney
//! and Fazzini, bump mapping with height maps: the FIG. 7 pipeline and paragraphs 0055-0087);
//! **001** US 2005/0190194 (Kraemer, polynomial texture maps for micro-scale occlusion: the PTM
//! fitter and shader); **002** West (2007), an investigation of surface mapping techniques
//! (normal and parallax mapping); **003** the 3ds Max SDK's notes on bump mapping (tangent
//! frames); **004** Schilling and Knittel's TEXRAM (texture unit 602, the TEXRAM chip 802,
//! the mipmap generator 816, footprint assembly, map chains, environment maps, volume
//! rendering). Unit numbers are the documents' reference numerals; "para. 0081" is a
//! paragraph of 000.
//!
//! **\[C\]** marks a choice texrtl made where a document is silent (a width, a rounding, a
//! layout, a timing): documented where it is made and, where it matters, a parameter.
//!
//! # From unit number to waveform, in one hop
//! Every numbered unit is one file named after it and its number; its module's kind and
//! instance carry the same name, its testbench (a `verif::Testbench` in `tb/src`), its scope
//! in the waveform, its Verilog twin and its bit-accuracy vectors too. The table is tested
//! against the project's descriptors (`tb/src/project.rs`): every unit there is a kind here,
//! every testbench here is one there, every twin's sources and every unit's vectors are named
//! here and exist.
//!
//! | unit (document) | module (`hdl/units/src/…`) | kind = instance | testbench | waveform scope | twin (in rtl/) | vectors (in golden/vectors/) |
//! |---|---|---|---|---|---|---|
//! | address unit 150 (Fenney FIG. 7) | `bump/address_150.rs` | `address_150` | `normal_pipeline_fig7`; `tb/tests/unit_address.rs` | `tb.normal_pipeline_fig7.address_150` | `bump/address_150.v` | - |
//! | texel fetch 151 | `bump/texel_fetch_151.rs` | `texel_fetch_151` | `normal_pipeline_fig7`; `tb/tests/unit_texel_fetch.rs` | `tb.normal_pipeline_fig7.texel_fetch_151` | `bump/texel_fetch_151.v` | - |
//! | replicate 152 | `bump/replicate_152.rs` | `replicate_152` | `normal_pipeline_fig7`; `tb/tests/unit_replicate.rs` | `tb.normal_pipeline_fig7.replicate_152` | `bump/replicate_152.v` | - |
//! | blend-factor adjust 153 | `bump/blend_adjust_153.rs` | `blend_adjust_153` | `blend_adjust_153` | `tb.blend_adjust_153` | `bump/blend_adjust_153.v` | `blend_adjust_153.json` |
//! | bilinear units 65, 66, 67, 68 | `bump/bilinear_65_68.rs` | `bilinear_65_68` = `bilinear_65_red`, `bilinear_66_green`, `bilinear_67_blue`, `bilinear_68_alpha` | `normal_pipeline_fig7`; `tb/tests/unit_bilinear.rs` | `tb.normal_pipeline_fig7.bilinear_65_red` … | `bump/bilinear_65_68.v` | - |
//! | tangent unit 155 | `bump/tangent_155.rs` | `tangent_155` | `normal_pipeline_fig7`; `tb/tests/unit_tangent_normal.rs` | `tb.normal_pipeline_fig7.tangent_155` | `bump/tangent_155.v` | - |
//! | normal unit 156 and its inverse square root | `bump/normal_156.rs`, `bump/rsqrt_156.rs` | `normal_156`, `rsqrt_156` | `normal_pipeline_fig7`; `tb/tests/unit_rsqrt.rs` | `tb.normal_pipeline_fig7.normal_156.rsqrt_156` | `bump/normal_156.v`, `bump/rsqrt_156.v` | - |
//! | the FIG. 7 pipeline | `bump/normal_pipeline_fig7.rs` | `normal_pipeline_fig7` | `normal_pipeline_fig7` | `tb.normal_pipeline_fig7` | `bump/normal_pipeline_fig7.v` | `normal_pipeline_fig7.json` |
//! | texture mapping unit 602 (Schilling & Knittel Figure 6) | `texmem/texture_unit_602.rs` | `texture_unit_602` | `texture_unit_602` | `tb.texture_unit_602` | `texmem/texture_unit_602.v` | `texture_unit_602.json` |
//! | DRAM 604 (its timing checks a traced `violation` wire, one bit a rule, and a `violations` count) | `texmem/dram_604.rs` | `dram_604` | `control_607` | `tb.control_607.dram_604` | `texmem/dram_604.v` | - |
//! | DRAM control unit 607: word reads, block fetch, lookahead queue | `texmem/control_607.rs` | `control_607`, `fill_engine_607`, `lookahead_queue_607` | `control_607` (word reads), `texture_unit_602` | `tb.control_607`, `tb.texture_unit_602.fill_engine_607` | `texmem/control_607.v`, `texmem/fill_engine_607.v`, `texmem/lookahead_queue_607.v` | - |
//! | register 608, multiplexer 610, CLUT 612 | `texmem/ccc_decode_608.rs` | `ccc_decode_608` | `texture_unit_602` | `tb.texture_unit_602.ccc_decode_608` | `texmem/ccc_decode_608.v` | - |
//! | cache 614 (four entries, Figure 7) | `texmem/cache_614.rs` | `cache_614`, entries `cache_614_entry` | `texture_unit_602` | `tb.texture_unit_602.cache_614.entry_a` … | `texmem/cache_614.v` | - |
//! | colour extract 618 | `texmem/extract_618.rs` | `extract_618` | `texture_unit_602` | `tb.texture_unit_602.extract_618` | `texmem/extract_618.v` | - |
//! | bilinear interpolator 622 | `texmem/bilinear_622.rs` | `bilinear_622` | `texture_unit_602` | `tb.texture_unit_602.bilinear_622` | `texmem/bilinear_622.v` | - |
//! | mipmap generation unit 816 (FIG. 14) with page registers 824 and shift register 826 | `mipmap/mipmap_gen_816.rs` | `mipmap_gen_816` | `mipmap_gen_816` | `tb.mipmap_gen_816` | `mipmap/mipmap_gen_816.v` | `mipmap_gen_816.json` |
//! | a level of FIG. 14a/b: adders 1402, 1410, register 1404 | `mipmap/level_fig14.rs` | `mipmap_level_fig14` = `level1` … | `mipmap_gen_816` | `tb.mipmap_gen_816.level1` | `mipmap/level_fig14.v` | - |
//! | FIFOs 1408 and 1412 | `mipmap/fifo.rs` | `fifo_1408`, `fifo_1412` | `mipmap_gen_816` | `tb.mipmap_gen_816.level1.fifo_1408` | `mipmap/fifo_fig14.v` | - |
//! | TEXRAM chip 802 (Schilling & Knittel Figure 8): request port, its units as children, its memory | `texram/texram_802.rs` | `texram_802` | `texram_802`; `tb/tests/texram.rs` | `tb.texram_802` | `texram/texram_802.v` | `texram_802.json` |
//! | address and control unit 812: levels, weights, border operations, the access registers | `texram/address_812.rs` | `address_812` | `texram_802` | `tb.texram_802.address_812` | `texram/address_812.v` | - |
//! | page registers 824: open rows, slots (also of the ray caster and the mipmap generator's own store) | `pages/page_registers_824.rs` | `page_registers_824` | `texram_802` | `tb.texram_802.page_registers_824` | `texram/page_registers_824.v` | - |
//! | banks 810 and their address decoders 822: the two-level layout | `texram/banks_810.rs` | `banks_810` (the bank stage), scope `banks_810.address_decoders_822` | `texram_802` | `tb.texram_802.banks_810.address_decoders_822` | `texram/banks_810.v` | - |
//! | trilinear interpolator 818 | `texram/trilinear_818.rs` | `trilinear_818` | `texram_802` | `tb.texram_802.trilinear_818` | `texram/trilinear_818.v` | - |
//! | CLUT 814 | `texram/clut_814.rs` | `clut_814` (the eight entries an index access looked up) | `texram_802`; `tb/tests/texram.rs` | `tb.texram_802.clut_814` | `texram/clut_814.v` | - |
//! | output and combination stage 820 (eq. 5) | `texram/output_820.rs` | `output_820` | `texram_802`; `tb/tests/texram.rs` | `tb.texram_802.output_820` | `texram/output_820.v` | - |
//! | one colour component per chip, four chips 802 in lock-step | `texram/lockstep.rs` | `texram_lockstep`, chips `chip_r` … | `tb/tests/texram.rs` | `texram_lockstep.chip_r` … | - | - |
//! | footprint assembly setup unit (section 10, eqs 19-21) | `footprint/setup_fig12.rs` | `footprint_setup` | `footprint_fig12`; `tb/tests/footprint.rs` | `tb.footprint_fig12.footprint_setup` | - | - |
//! | footprint sample generator and accumulator (eq. 22) | `footprint/assembly_fig12.rs` | `footprint_assembly`, scopes `generator`, `accumulator` | `footprint_fig12` | `tb.footprint_fig12.footprint_assembly.generator` … | - | - |
//! | the two before the chip (or texture unit 602) | `footprint/footprint_fig12.rs` | `footprint_fig12` | `footprint_fig12` | `tb.footprint_fig12` | - | `footprint_fig12.json` |
//! | tangent average of para. 0081 (Fenney FIG. 7, between 155 and 156) | `bump/tangent_average_0081.rs` | scope `tangent_average_0081` | `footprint_normals_0081` | `tb.footprint_normals_0081.normal_pipeline_fig7.tangent_average_0081` | - | - |
//! | footprint generator before the FIG. 7 pipeline (para. 0081) | `footprint/normals_0081.rs` | `footprint_normals_0081` | `footprint_normals_0081` | `tb.footprint_normals_0081.generator` | - | - |
//! | ray caster (section 13, Figure 15) | `volume/ray_caster_fig15.rs` (`layout.rs`, `interp.rs`) | `ray_caster_fig15`, scopes `stepper`, `page_registers_824`, `sequencer`, `trilinear_818` | `ray_caster_fig15`; `tb/tests/volume.rs` | `tb.ray_caster_fig15.stepper` … | - | `ray_caster_fig15.json` |
//! | RGBA on four ray casters in lock-step | `volume/lockstep.rs` | `volume_lockstep`, chips `chip_r` … | `tb/tests/volume.rs` | `volume_lockstep.chip_r` … | - | - |
//! | video port 808 and shift registers 826, with the mipmap generator 816 on the banks | `texram/video_port_808.rs` | scope `video_port_808` | `video_port_808`; `tb/tests/texram_video.rs` | `tb.texram_802.video_port_808`, `….mipmap_gen_816`, `….shift_registers_826` | - | - |
//! | reflection vector, eq. 4, and cube-face selection (section 7) | `envmap/reflect_eq4.rs`, `envmap/cube_face.rs` | `reflect_eq4`, `cube_face`; in the walker's `ENV_COORDS` state | `walker_812`; `tb/tests/envmap.rs` | `tb.walker_812` (`face`, `s`, `t`) | - | - |
//! | description register files of 812 (section 14) | `mapchain/drf_812.rs` | (registers of the walker) | `walker_812` | - | - | - |
//! | chain walker of 812 with the output stage 820's eqs 5-7 | `mapchain/walker_812.rs`, `mapchain/program.rs` | `walker_812` | `walker_812`; `tb/tests/mapchain.rs` | `tb.walker_812` | `mapchain/walker_812.v` | `walker_812.json` |
//! | the walker's port to the banks 810 (the stub's or the chip 802's, traced as state) | `mapchain/bank_port_810.rs` | `bank_port_810`, instance `banks` | `walker_812` | `tb.walker_812.banks` | - | - |
//! | detail path, units 902-914 (Figs 9a/9b) | `mapchain/detail_fig9.rs` | (the walker's offset and detail states) | `walker_812` | `tb.walker_812` | - | - |
//! | PTM fitter 604 and light shader 608 (001, Fig. 6), occlusion PTM 612 | `ptm/fitter_604.rs`, `ptm/shader_608.rs`, `ptm/texture_612.rs` | `ptm_fitter_604`, `ptm_shader_608` | `ptm_fitter_604`, `ptm_shader_608`; `tb/tests/ptm.rs` | `tb.ptm_fitter_604`, `tb.ptm_shader_608` | - | `ptm_fitter_604.json`, `ptm_shader_608.json` |
//! | tangent setup (003) | `frames/tangent_setup.rs` | `tangent_setup` | `tangent_setup`; `tb/tests/tangents.rs` | `tb.tangent_setup` | - | `tangent_setup.json` |
//! | per-pixel frame unit (003, 002) and parallax (002) | `frames/frame_unit.rs`, `frames/parallax.rs` | `frame_unit`, `parallax` | `frame_unit`, `parallax`; `tb/tests/frames.rs` | `tb.frame_unit`, `tb.parallax` | - | `frame_unit.json`, `parallax.json` |
//! | derivative filters (para. 0086), bi-quadratic colour (0087), packed heights (0055) | `bump/derivative_0086.rs`, `bump/biquadratic_0087.rs`, `bump/packed_0055.rs` | `derivative_0086`, `biquadratic_0087` | `derivative_0086`, `biquadratic_0087`; `tb/tests/derivative.rs`, `tb/tests/biquadratic.rs` | `tb.derivative_0086`, `tb.biquadratic_0087` | - | `derivative_0086.json`, `biquadratic_0087.json` |

pub use hdl::{fx, kernel, signals};

/// `FromStr` for an enum of named values: `parse_names!(T, "name" => T::A, ...)`; an
/// unknown name is refused with the type and every name (`unknown t 'x' (one of a, b)`).
macro_rules! parse_names {
    ($t:ty, $($name:literal => $v:expr),+) => {
        impl std::str::FromStr for $t {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                match s {
                    $($name => Ok($v),)+
                    _ => Err(format!("unknown {} '{s}' (one of {})", stringify!($t).to_lowercase(), [$($name),+].join(", "))),
                }
            }
        }
    };
}

/// FIG. 7 of US 2004/0207631: the per-pixel normal pipeline.
pub mod bump;
/// Section 7 of Schilling & Knittel: environment mapping (frame, reflection, cube face).
pub mod envmap;
/// Section 10 and Figures 12-13 of Schilling & Knittel: footprint assembly.
pub mod footprint;
/// Tangent frames (003): the tangent setup unit.
pub mod frames;
/// Map linking, detail, reflectance and environment maps (TEXRAM sections 7-9, 14).
pub mod mapchain;
/// FIG. 14 of Schilling & Knittel: the real-time mipmap generator.
pub mod mipmap;
/// Section 5 of Schilling & Knittel: the page registers 824 of DRAM banks.
pub mod pages;
/// PTM micro-occlusion (001, Fig. 6): the fitter 604, the occlusion PTM 612 and the light shader 608.
pub mod ptm;
/// Figure 6 of Schilling & Knittel: the texture memory path.
pub mod texmem;
/// Figure 8 of Schilling & Knittel: the TEXRAM chip, its interface and behavioural stub.
pub mod texram;
/// Section 13 and Figure 15 of Schilling & Knittel: the TEXRAM as a ray caster.
pub mod volume;
