//! The texture units' bit-accuracy vectors: for each unit a fixed set of stimuli and the
//! bit-exact outputs, made by the function its descriptor names ([`crate::project`]), kept
//! under `golden/vectors/` and checked by [`verif::vectors`].
//!
//! The stimuli do not depend on any seed: a change of a single output bit fails `cargo test`
//! (`tb/tests/vectors.rs`); `texrtl vectors --bless` rewrites the files after a deliberate
//! change and prints what changed.

use crate::runs::normals::{quantise, run_normals, NormalsRun, Sample};
use hdl::kernel::Sim;
use std::path::{Path, PathBuf};
use units::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
use units::bump::params::{BumpParams, Filter};
use units::mipmap::{MipmapParams, Rounding, Scan};
use verif::vectors::{mask, Field, UnitVectors};

pub fn blend_adjust() -> UnitVectors {
    let p = BlendAdjustParams {
        frac_bits: 8,
        registered: false,
    };
    let mut sim = Sim::new(BlendAdjust::new("blend_adjust_153", p).expect("valid parameters"));
    let mut rows = Vec::new();
    for bypass in [0u64, 1] {
        for u in 0..256u64 {
            let v = (u * 0x9e5 + 7) & 0xff;
            let d = &mut sim.dut;
            d.i.u_in.set_bits(u);
            d.i.v_in.set_bits(v);
            d.i.bypass.set_bits(bypass);
            sim.eval();
            let o = &sim.dut.o;
            rows.push((
                vec![bypass, u, v],
                vec![o.u0.bits(), o.u1.bits(), o.v0.bits(), o.v1.bits()],
            ));
            sim.tick();
        }
    }
    UnitVectors {
        unit: crate::blend_adjust::NAME.into(),
        description:
            "unit 153, F = 8, combinational: every u in both modes, v = (u * 0x9e5 + 7) mod 256"
                .into(),
        inputs: vec![
            Field::new("bypass", 1),
            Field::new("u_in", 8),
            Field::new("v_in", 8),
        ],
        outputs: vec![
            Field::new("u0", 9),
            Field::new("u1", 9),
            Field::new("v0", 9),
            Field::new("v1", 9),
        ],
        rows,
    }
}

/// The groups of the FIG. 7 vectors: filter and built-in 16x16 map, default widths otherwise.
pub const NORMAL_GROUPS: [(Filter, &str); 3] = [
    (Filter::BSpline, "noise"),
    (Filter::Blinn, "smooth"),
    (Filter::BSpline, "steps"),
];

/// The 128 samples of every FIG. 7 vector group.
pub fn normal_samples() -> Vec<Sample> {
    (0..128u32)
        .map(|k| Sample {
            u: f64::from(k * 37 % 4096) / 256.0 - 0.5,
            v: f64::from(k * 91 % 4096) / 256.0,
            scale: f64::from(1 + k % 5) * 0.75,
            lod: 0.0,
        })
        .collect()
}

/// The frame of the FIG. 14 vectors (16x8, seed 5) and their two scan orders.
pub const MIPMAP_SCANS: [Scan; 2] = [Scan::InterlacedTop, Scan::Progressive];

pub fn mipmap_frame() -> Vec<Vec<u8>> {
    crate::mipmap::synthetic_video(16, 8, 1, verif::Seed(5))
}

/// The parameters of the FIG. 14 vectors in `scan` order.
pub fn mipmap_params(scan: Scan) -> MipmapParams {
    MipmapParams {
        width: 16,
        height: 8,
        scan,
        rounding: Rounding::Round,
    }
}

pub fn normals() -> Result<UnitVectors, String> {
    let mut rows = Vec::new();
    let mut desc = Vec::new();
    for (filter, map) in NORMAL_GROUPS {
        let p = BumpParams {
            filter,
            ..BumpParams::default()
        };
        let m = crate::maps::builtin(map, 16, 16, p.texel_fmt())?;
        let samples = normal_samples();
        let o = run_normals(&NormalsRun {
            name: "vectors".into(),
            params: p,
            map: m,
            samples: samples.clone(),
            idle_per_mille: 0,
            vcd: None,
            trace: Default::default(),
            check_accuracy: false,
            check_schedule: false,
            seed: verif::Seed(0),
        })?;
        let (pw, sw, nw, hw) = (
            p.pos_fmt().width(),
            p.scale_fmt().width(),
            p.normal_fmt().width(),
            p.height_out_fmt().width(),
        );
        for (s, n) in samples.iter().zip(&o.outputs) {
            let r = quantise(&p, s)?;
            rows.push((
                vec![
                    u64::from(filter == Filter::Blinn),
                    mask(r.u, pw),
                    mask(r.v, pw),
                    r.scale & ((1 << sw) - 1),
                ],
                vec![
                    mask(n.n[0], nw),
                    mask(n.n[1], nw),
                    mask(n.n[2], nw),
                    n.height & ((1 << hw) - 1),
                ],
            ));
        }
        desc.push(format!("{filter} on {map}"));
    }
    let p = BumpParams::default();
    Ok(UnitVectors {
        unit: crate::normals::NAME.into(),
        description: format!(
            "FIG. 7 pipeline, default widths, 16x16 built-in maps, wrap: 128 samples each of {}",
            desc.join(", ")
        ),
        inputs: vec![
            Field::new("blinn", 1),
            Field::new("u", p.pos_fmt().width()),
            Field::new("v", p.pos_fmt().width()),
            Field::new("scale", p.scale_fmt().width()),
        ],
        outputs: vec![
            Field::new("nx", p.normal_fmt().width()),
            Field::new("ny", p.normal_fmt().width()),
            Field::new("nz", p.normal_fmt().width()),
            Field::new("height", p.height_out_fmt().width()),
        ],
        rows,
    })
}

pub fn mipmap() -> Result<UnitVectors, String> {
    let mut rows = Vec::new();
    for scan in MIPMAP_SCANS {
        let code = u64::from(scan != Scan::Progressive);
        let p = mipmap_params(scan);
        let frames = mipmap_frame();
        let o = crate::runs::mipmap::run_mipmap(p, &frames, None)?;
        // One row per output texel: (scan, level, index) -> value; the frame itself is level 0.
        for (k, level) in o.frames[0].iter().enumerate() {
            for (i, &t) in level.iter().enumerate() {
                rows.push((vec![code, k as u64, i as u64], vec![u64::from(t)]));
            }
        }
    }
    Ok(UnitVectors {
        unit: crate::mipmap::NAME.into(),
        description: "FIG. 14 generator, 16x8 synthetic frame (seed 5), round half up, interlaced top-first then progressive: every texel of every level".into(),
        inputs: vec![Field::new("interlaced", 1), Field::new("level", 4), Field::new("index", 8)],
        outputs: vec![Field::new("texel", 8)],
        rows,
    })
}

/// The TEXRAM chip's vectors: a 32x32 map from an integer formula, each border operation
/// and the index configuration (a CLUT from an integer formula), 256 requests from an integer
/// hash over the map and a texel beyond it, every lambda class: (config, u, v, lambda) ->
/// R, G, B, alpha.
pub fn texram() -> Result<UnitVectors, String> {
    use crate::runs::texram::{run_texram, TexramTexture};
    use crate::texram::TexReq;
    use units::texram::clut_814::Clut;
    use units::texram::{Border, Config, Drf};
    let level0: Vec<u8> = (0..32 * 32u32)
        .map(|k| ((k * 29 + (k >> 5) * 7) % 256) as u8)
        .collect();
    let reqs: Vec<TexReq> = (0..256u32)
        .map(|k| {
            let h = k.wrapping_mul(0x9e37_79b9) ^ k.wrapping_mul(0x85eb_ca6b) >> 7;
            TexReq {
                u: (h % (34 << 8)) as i32 - 256,
                v: ((h >> 9) % (34 << 8)) as i32 - 256,
                lambda: ((h >> 3) % ((14 << 8) + 1)) as i32 - (4 << 8),
            }
        })
        .collect();
    let configs = [
        (Border::Wrap, Config::Luminance),
        (Border::Clamp, Config::Luminance),
        (Border::Mirror, Config::Luminance),
        (Border::Colour(200), Config::Luminance),
        (Border::Mirror, Config::Index),
    ];
    let mut rows = Vec::new();
    for (code, (border, config)) in configs.into_iter().enumerate() {
        let mut drf = Drf::new(5, 5, border);
        drf.config = config;
        let mut tex = TexramTexture::generated(drf, &level0);
        if config == Config::Index {
            let entries = std::array::from_fn(|i| (i as u32).wrapping_mul(0x0103_0507) ^ 0xff);
            tex.clut = Clut { entries };
        }
        let run = run_texram(&tex, &reqs, None)?;
        for (q, rgba) in reqs.iter().zip(&run.values) {
            let raw = |x: i32, w: u32| mask(i64::from(x), w);
            rows.push((
                vec![code as u64, raw(q.u, 21), raw(q.v, 21), raw(q.lambda, 14)],
                vec![u64::from(u32::from_be_bytes(*rgba))],
            ));
        }
    }
    Ok(UnitVectors {
        unit: crate::texram::NAME.into(),
        description: "TEXRAM chip 802, 32x32 map from an integer formula: wrap, clamp, mirror, border:200 (luminance) and mirror in index mode; 256 hashed requests each".into(),
        inputs: vec![Field::new("config", 3), Field::new("u", 21), Field::new("v", 21), Field::new("lambda", 14)],
        outputs: vec![Field::new("rgba", 32)],
        rows,
    })
}

/// Footprint assembly's vectors: 256 hashed pixels (centre over a 32x32 map and a texel
/// beyond, derivatives up to 16 texels, any direction) through the setup unit and the
/// generator and accumulator on the TEXRAM chip (the `texram` vectors' map, wrap and mirror)
/// and on the texture unit 602 (the `texture` vectors' CCC texture): (config, u, v, r1, r2) ->
/// N, R, G, B.
pub fn footprint() -> Result<UnitVectors, String> {
    use crate::footprint::Pixel;
    use crate::runs::footprint::{run_footprint, run_footprint_texture, FootprintRun};
    use units::footprint::setup_fig12::SetupParams;
    use units::texram::{Border, Drf};
    let level0: Vec<u8> = (0..32 * 32u32)
        .map(|k| ((k * 29 + (k >> 5) * 7) % 256) as u8)
        .collect();
    let px: Vec<Pixel> = (0..256u32)
        .map(|k| {
            let h = k.wrapping_mul(0x9e37_79b9) ^ k.wrapping_mul(0x85eb_ca6b) >> 7;
            let g = h.wrapping_mul(0x2545_f491);
            let d = |x: u32| (x % (32 << 8)) as i32 - (16 << 8);
            Pixel {
                u: (h % (34 << 8)) as i32 - 256,
                v: ((h >> 9) % (34 << 8)) as i32 - 256,
                r1: (d(g), d(g >> 7)),
                r2: (d(g >> 13) / 8, d(g >> 19) / 8),
            }
        })
        .collect();
    let p = SetupParams::default();
    let tex = vector_texture();
    let tp = units::texmem::texture_unit_602::TexParams::new(tex.width, tex.height);
    let runs: [FootprintRun; 3] = [
        run_footprint(Drf::new(5, 5, Border::Wrap), &level0, p, &px, None)?,
        run_footprint(Drf::new(5, 5, Border::Mirror), &level0, p, &px, None)?,
        run_footprint_texture(&tex, tp, p, &px, None)?,
    ];
    let mut rows = Vec::new();
    for (code, run) in runs.iter().enumerate() {
        for (q, (a, _)) in px.iter().zip(&run.results) {
            let raw = |x: i32, w: u32| mask(i64::from(x), w);
            rows.push((
                vec![
                    code as u64,
                    raw(q.u, 21),
                    raw(q.v, 21),
                    raw(q.r1.0, 20),
                    raw(q.r1.1, 20),
                    raw(q.r2.0, 20),
                    raw(q.r2.1, 20),
                ],
                vec![u64::from(a.n), u64::from(a.rgb)],
            ));
        }
    }
    Ok(UnitVectors {
        unit: crate::footprint::NAME.into(),
        description: "footprint assembly: setup, generator and accumulator on the TEXRAM chip (32x32 formula map, wrap and mirror) and on texture unit 602 (the texture vectors' CCC texture); 256 hashed pixels each".into(),
        inputs: vec![
            Field::new("config", 2),
            Field::new("u", 21),
            Field::new("v", 21),
            Field::new("r1u", 20),
            Field::new("r1v", 20),
            Field::new("r2u", 20),
            Field::new("r2v", 20),
        ],
        outputs: vec![Field::new("n", 7), Field::new("rgb", 24)],
        rows,
    })
}

/// The ray caster's vectors: a 16x8x6 volume from an integer formula (column-major words,
/// 64-word rows), 64 hashed rays of up to 8 samples anywhere in and around it, in value and in
/// gradient mode: (mode, x0, y0, z0, dx, dy, dz, steps) -> per sample value, gx, gy, gz.
pub fn volume() -> Result<UnitVectors, String> {
    use crate::runs::volume::run_volume;
    use crate::volume::Ray;
    use units::volume::layout::{Mode, VolumeParams};
    let p = VolumeParams {
        row_words: 64,
        ..VolumeParams::new(16, 8, 6)
    };
    let vox: Vec<u8> = (0..16 * 8 * 6u32)
        .map(|k| ((k * 53 + (k >> 4) * 11 + (k >> 7) * 29) % 256) as u8)
        .collect();
    let rays: Vec<Ray> = (0..64u32)
        .map(|k| {
            let h = k.wrapping_mul(0x9e37_79b9) ^ k.wrapping_mul(0x85eb_ca6b) >> 7;
            let g = h.wrapping_mul(0x2545_f491);
            let pos = |x: u32, n: i32| (x % ((n as u32 + 2) << 12)) as i32 - 4096;
            let step = |x: u32| (x % 8192) as i32 - 4096;
            Ray {
                p: [pos(h, 16), pos(h >> 5, 8), pos(h >> 11, 6)],
                d: [step(g), step(g >> 9), step(g >> 17)],
                steps: (1 + (h >> 27) % 8) as u16,
            }
        })
        .collect();
    let mut rows = Vec::new();
    for (code, mode) in [Mode::Value, Mode::Gradient].into_iter().enumerate() {
        let run = run_volume(p, mode, &vox, &rays, None)?;
        for s in &run.samples {
            let r = &rays[s.ray as usize - 1];
            let raw = |x: i32| mask(i64::from(x), 22);
            rows.push((
                vec![
                    code as u64,
                    raw(r.p[0]),
                    raw(r.p[1]),
                    raw(r.p[2]),
                    raw(r.d[0]),
                    raw(r.d[1]),
                    raw(r.d[2]),
                    u64::from(s.k),
                ],
                vec![
                    u64::from(s.value),
                    mask(s.g[0], 14),
                    mask(s.g[1], 14),
                    mask(s.g[2], 14),
                ],
            ));
        }
    }
    Ok(UnitVectors {
        unit: crate::volume::NAME.into(),
        description: "ray caster (section 13): 16x8x6 formula volume, column-major words, 64-word rows; 64 hashed rays in value and gradient mode, one row per sample".into(),
        inputs: vec![
            Field::new("mode", 1),
            Field::new("x0", 22),
            Field::new("y0", 22),
            Field::new("z0", 22),
            Field::new("dx", 22),
            Field::new("dy", 22),
            Field::new("dz", 22),
            Field::new("k", 16),
        ],
        outputs: vec![Field::new("value", 8), Field::new("gx", 14), Field::new("gy", 14), Field::new("gz", 14)],
        rows,
    })
}

/// The map chain: every shape of the testbench over the formula maps, 48 hashed pixels each
/// (lambda over -4 ..= 4, vectors facing +z), through the clocked walker on the stub.
pub fn mapchain() -> Result<UnitVectors, String> {
    use crate::mapchain::{scene, Maps, Shape};
    use crate::runs::mapchain::clocked;
    use units::mapchain::program::ChainRequest;
    use units::mapchain::walker_812::Pixel;
    let maps = Maps::formula();
    let fields = Pixel::fields();
    let mut rows = Vec::new();
    for (code, shape) in Shape::ALL.into_iter().enumerate() {
        let sc = scene(shape, &maps)?;
        let px: Vec<ChainRequest> = (0..48u32)
            .map(|k| {
                let h = (k + 64 * code as u32).wrapping_mul(0x9e37_79b9);
                let g = h.wrapping_mul(0x2545_f491) ^ h >> 15;
                let c = |x: u32, r: i64| i64::from(x % (2 * r as u32)) - r;
                ChainRequest {
                    drf: 0,
                    u: (h % (80 << 8)) as i32 - (8 << 8),
                    v: (g % (80 << 8)) as i32 - (8 << 8),
                    lambda: ((h >> 7) % (8 << 8)) as i32 - (4 << 8),
                    n: [c(h >> 3, 6000), c(g >> 5, 6000), 12000 + c(h >> 11, 4000)],
                    eye: [c(g >> 2, 5000), c(h >> 9, 5000), 14000],
                    face: 0,
                    i_d: (h >> 24) as u8,
                    i_s: (g >> 24) as u8,
                }
            })
            .collect();
        let (_, out) = clocked(&sc, &px)?;
        for (q, r) in px.iter().zip(out) {
            // The port's fields but the DRF and the face, each masked to its format.
            let raw = Pixel::of(q);
            let cols = raw.each().into_iter().zip(fields.each()).skip(1);
            let cols = cols.filter(|(_, f)| f.name != "face");
            let mut inp = vec![code as u64];
            inp.extend(cols.map(|(x, f)| mask(*x, f.fmt.width())));
            let out = [
                r.colour.into(),
                r.accesses,
                r.slots,
                r.faults,
                r.error.into(),
            ];
            rows.push((inp, out.map(u64::from).to_vec()));
        }
    }
    Ok(UnitVectors {
        unit: crate::mapchain::NAME.into(),
        description: "chain walker of 812 (section 14): the testbench's seven chain shapes over integer-formula maps (64x64 texture, offsets and reflectance, 256x256 detail, 32x32 faces), 48 hashed pixels each, results of the clocked walker on the stub".into(),
        inputs: vec![
            Field::new("shape", 3),
            Field::new("u", fields.u.fmt.width()),
            Field::new("v", fields.v.fmt.width()),
            Field::new("lambda", fields.lambda.fmt.width()),
            Field::new("nx", fields.n[0].fmt.width()),
            Field::new("ny", fields.n[1].fmt.width()),
            Field::new("nz", fields.n[2].fmt.width()),
            Field::new("ex", fields.eye[0].fmt.width()),
            Field::new("ey", fields.eye[1].fmt.width()),
            Field::new("ez", fields.eye[2].fmt.width()),
            Field::new("i_d", fields.i_d.fmt.width()),
            Field::new("i_s", fields.i_s.fmt.width()),
        ],
        outputs: vec![
            Field::new("colour", 8),
            Field::new("accesses", 4),
            Field::new("slots", 5),
            Field::new("faults", 4),
            Field::new("error", 1),
        ],
        rows,
    })
}

/// The fitter 604 under a 3 x 8 dome (P from the f64 pseudo-inverse, 8-bit coefficients):
/// 64 texels of hashed samples (binary and grey), one row per texel.
pub fn ptm_fitter() -> Result<UnitVectors, String> {
    use hdl::kernel::Sim;
    use units::ptm::fitter_604::Fitter604;
    use units::ptm::texture_612::PtmFormat;
    let lights = golden::ptm::dome(3, 8);
    let p = crate::ptm::host_pinv(&lights)?;
    let fmt = PtmFormat::for_pinv(&p, 8)?;
    let l = lights.len();
    let samples: Vec<u8> = (0..64 * l as u32)
        .map(|k| {
            let h = k.wrapping_mul(0x9e37_79b9) >> 11;
            if k / l as u32 % 4 == 3 {
                (h % 256) as u8
            } else if h % 3 == 0 {
                0
            } else {
                255
            }
        })
        .collect();
    let (q, _) = crate::ptm::run_fitter(Sim::new(Fitter604::new(p, fmt)?), &samples);
    let rows = q
        .iter()
        .enumerate()
        .map(|(t, c)| {
            let s = &samples[t * l..(t + 1) * l];
            let ins = s
                .chunks(8)
                .map(|c| c.iter().fold(0u64, |a, &x| a << 8 | u64::from(x)))
                .collect();
            (ins, c.to_vec())
        })
        .collect();
    let mut inputs = vec![];
    for k in 0..l.div_ceil(8) {
        inputs.push(Field::new(format!("samples{k}"), 64));
    }
    Ok(UnitVectors {
        unit: crate::ptm::FITTER.into(),
        description: "PTM fitter 604 (001): 3 x 8 dome, P in sQ7.20 from the f64 pseudo-inverse, 8-bit coefficients; 64 texels of hashed samples (every fourth grey), 24 samples a texel packed eight to a word (light 0 in the top byte)".into(),
        inputs,
        outputs: (1..=6).map(|j| Field::new(format!("q{j}"), 8)).collect(),
        rows,
    })
}

/// The shader 608 with the 16-bit format of a 4 x 12 dome: 512 hashed coefficient sets and
/// lights in the unit disc.
pub fn ptm_shader() -> Result<UnitVectors, String> {
    use hdl::kernel::Sim;
    use units::ptm::shader_608::Shader608;
    use units::ptm::texture_612::PtmFormat;
    let p = crate::ptm::host_pinv(&golden::ptm::dome(4, 12))?;
    let fmt = PtmFormat::for_pinv(&p, 16)?;
    let mut sim = Sim::new(Shader608::new(fmt)?);
    sim.reset(1);
    let mut rows = Vec::new();
    for k in 0..512u32 {
        let h = |i: u32| (k * 7 + i).wrapping_mul(0x9e37_79b9) >> 7;
        // Stored values near the middle of each range (where real fits lie) and anywhere.
        let q: [u64; 6] = std::array::from_fn(|j| {
            let x = u64::from(h(j as u32));
            if k % 2 == 0 {
                32768 + x % 4096 - 2048
            } else {
                x % 65536
            }
        });
        let (u, v) = (
            (h(9) % 23170) as i64 - 11585,
            (h(10) % 23170) as i64 - 11585,
        );
        let d = &mut sim.dut;
        d.in_valid.set_bool(true);
        for (s, x) in d.q.iter_mut().zip(q) {
            s.set_bits(x);
        }
        d.u.set_raw(u);
        d.v.set_raw(v);
        sim.step();
        let out = vec![sim.dut.k.q().bits(), sim.dut.visibility.q().bits()];
        let mut ins = q.to_vec();
        ins.extend([mask(u, 16), mask(v, 16)]);
        rows.push((ins, out));
    }
    let mut inputs: Vec<Field> = (1..=6).map(|j| Field::new(format!("q{j}"), 16)).collect();
    inputs.extend([Field::new("u", 16), Field::new("v", 16)]);
    Ok(UnitVectors {
        unit: crate::ptm::SHADER.into(),
        description: format!("PTM shader 608 (001): the 16-bit format of a 4 x 12 dome (exponents {:?}, biases {:?}); 512 hashed coefficient sets and lights inside |u|, |v| < 0.71", fmt.exp, fmt.bias),
        inputs,
        outputs: vec![Field::new("k", 8), Field::new("visibility", 8)],
        rows,
    })
}

/// A hash of `k` and `i` (no RNG: the vectors depend on no seed).
fn mix(k: u32, i: u32) -> u32 {
    (k.wrapping_mul(0x9e37_79b9) ^ i.wrapping_mul(0x85eb_ca6b)).wrapping_mul(0x2545_f491) >> 3
}

/// A value in `-r..r` from a hash.
fn signed(h: u32, r: i64) -> i64 {
    i64::from(h) % (2 * r) - r
}

/// The tangent setup unit on 256 hashed triangles (every eighth with UVs on a line).
#[allow(clippy::needless_range_loop)] // the unit's signals index like the vectors
pub fn tangent_setup() -> Result<UnitVectors, String> {
    use units::frames::tangent_setup::TangentSetup;
    let mut sim = hdl::kernel::Sim::new(TangentSetup::new());
    sim.reset(1);
    let mut rows = Vec::new();
    for k in 0..256u32 {
        let v = [[0, 1, 2], [3, 4, 5]].map(|r| r.map(|i| signed(mix(k, i), 8 << 16)));
        let mut d = [[6, 7], [8, 9]].map(|r| r.map(|i| signed(mix(k, i), 2 << 16)));
        if k % 8 == 7 {
            d[1] = [2 * d[0][0], 2 * d[0][1]];
        }
        let n = [0, 0, 1 << 14];
        let dut = &mut sim.dut;
        dut.valid_in.set_bool(true);
        for r in 0..2 {
            for c in 0..3 {
                dut.v[r][c].set_raw(v[r][c]);
            }
            for c in 0..2 {
                dut.d[r][c].set_raw(d[r][c]);
            }
        }
        for c in 0..3 {
            dut.n[c].set_raw(n[c]);
        }
        sim.step();
        let o = &sim.dut;
        let mut ins: Vec<u64> = v.iter().flatten().map(|&x| mask(x, 24)).collect();
        ins.extend(d.iter().flatten().map(|&x| mask(x, 20)));
        let mut out: Vec<u64> =
            o.t.iter()
                .chain(&o.b)
                .map(|r| mask(r.q().raw(), 16))
                .collect();
        out.extend(o.dpdu.iter().map(|r| mask(r.q().raw(), 40)));
        out.extend([o.degenerate.q().bits(), o.zero.q().bits()]);
        rows.push((ins, out));
    }
    let mut inputs: Vec<Field> = ["v1x", "v1y", "v1z", "v2x", "v2y", "v2z"]
        .iter()
        .map(|n| Field::new(*n, 24))
        .collect();
    inputs.extend(
        ["d1u", "d1v", "d2u", "d2v"]
            .iter()
            .map(|n| Field::new(*n, 20)),
    );
    let mut outputs: Vec<Field> = ["tx", "ty", "tz", "bx", "by", "bz"]
        .iter()
        .map(|n| Field::new(*n, 16))
        .collect();
    outputs.extend(
        ["dpdu_x", "dpdu_y", "dpdu_z"]
            .iter()
            .map(|n| Field::new(*n, 40)),
    );
    outputs.extend([Field::new("degenerate", 1), Field::new("zero", 1)]);
    Ok(UnitVectors {
        unit: crate::tangents::NAME.into(),
        description: "tangent setup (003): 256 hashed triangles (edges within 8, UV edges within 2, every eighth with UVs on a line), n = +z".into(),
        inputs,
        outputs,
        rows,
    })
}

/// The frame unit on 256 hashed frames and weights, Gram-Schmidt on odd rows.
#[allow(clippy::needless_range_loop)] // the unit's signals index like the vectors
pub fn frame_unit() -> Result<UnitVectors, String> {
    use units::frames::frame_unit::FrameUnit;
    let mut sim = hdl::kernel::Sim::new(FrameUnit::new());
    sim.reset(1);
    let mut rows = Vec::new();
    for k in 0..256u32 {
        let one = 1i64 << 14;
        let jit = |i: u32| signed(mix(k, i), 3000);
        let frame = [
            [one + jit(0), jit(1), jit(2)],
            [jit(3), one + jit(4), jit(5)],
            [jit(6), jit(7), one + jit(8)],
        ];
        let w = [1 << 12, signed(mix(k, 9), 8192), signed(mix(k, 10), 8192)];
        let gs = k % 2 == 1;
        let dut = &mut sim.dut;
        dut.valid_in.set_bool(true);
        dut.gram_schmidt.set_bool(gs);
        for r in 0..3 {
            for c in 0..3 {
                dut.frame[r][c].set_raw(frame[r][c]);
            }
            dut.w[r].set_raw(w[r]);
        }
        sim.step();
        let mut ins: Vec<u64> = frame.iter().flatten().map(|&x| mask(x, 16)).collect();
        ins.extend(w.iter().map(|&x| mask(x, 16)));
        ins.push(u64::from(gs));
        let out = sim.dut.nout.iter().map(|r| mask(r.q().raw(), 16)).collect();
        rows.push((ins, out));
    }
    let mut inputs: Vec<Field> = [
        "tx", "ty", "tz", "bx", "by", "bz", "nx", "ny", "nz", "a", "gx", "gy",
    ]
    .iter()
    .map(|n| Field::new(*n, 16))
    .collect();
    inputs.push(Field::new("gram_schmidt", 1));
    Ok(UnitVectors {
        unit: crate::frames::FRAME.into(),
        description: "per-pixel frame unit: 256 hashed near-orthonormal frames, bump weights a = 1, gx, gy within 2; Gram-Schmidt on odd rows".into(),
        inputs,
        outputs: ["nx", "ny", "nz"].iter().map(|n| Field::new(*n, 16)).collect(),
        rows,
    })
}

/// The parallax unit on 256 hashed queries, limited on odd rows.
#[allow(clippy::needless_range_loop)] // the unit's signals index like the vectors
pub fn parallax() -> Result<UnitVectors, String> {
    use units::frames::parallax::ParallaxUnit;
    let mut sim = hdl::kernel::Sim::new(ParallaxUnit::new());
    sim.reset(1);
    let mut rows = Vec::new();
    for k in 0..256u32 {
        let uv = [signed(mix(k, 0), 1 << 18), signed(mix(k, 1), 1 << 18)];
        let height = (mix(k, 2) % 256) as u8;
        let (scale, bias) = (signed(mix(k, 3), 8192), signed(mix(k, 4), 4096));
        let eye = [
            signed(mix(k, 5), 9000),
            signed(mix(k, 6), 9000),
            1000 + i64::from(mix(k, 7) % 15000),
        ];
        let limited = k % 2 == 1;
        let d = &mut sim.dut;
        d.valid_in.set_bool(true);
        d.limited.set_bool(limited);
        d.uv[0].set_raw(uv[0]);
        d.uv[1].set_raw(uv[1]);
        d.height.set_bits(u64::from(height));
        d.scale.set_raw(scale);
        d.bias.set_raw(bias);
        for c in 0..3 {
            d.eye[c].set_raw(eye[c]);
        }
        sim.step();
        let mut ins = vec![
            mask(uv[0], 21),
            mask(uv[1], 21),
            u64::from(height),
            mask(scale, 16),
            mask(bias, 16),
        ];
        ins.extend(eye.iter().map(|&x| mask(x, 16)));
        ins.push(u64::from(limited));
        rows.push((
            ins,
            sim.dut.out.iter().map(|r| mask(r.q().raw(), 21)).collect(),
        ));
    }
    let mut inputs = vec![
        Field::new("u", 21),
        Field::new("v", 21),
        Field::new("height", 8),
        Field::new("scale", 16),
        Field::new("bias", 16),
    ];
    inputs.extend(["vx", "vy", "vz"].iter().map(|n| Field::new(*n, 16)));
    inputs.push(Field::new("limited", 1));
    Ok(UnitVectors {
        unit: crate::frames::PARALLAX.into(),
        description: "parallax: 256 hashed queries (V.z from 1/16 up), offset-limited on odd rows"
            .into(),
        inputs,
        outputs: vec![Field::new("u_out", 21), Field::new("v_out", 21)],
        rows,
    })
}

/// Para. 0086's unit, every filter, on the 16x16 bumps map: 64 hashed samples each.
pub fn derivative() -> Result<UnitVectors, String> {
    use units::bump::derivative_0086::{Derivative, DerivativeUnit};
    use units::bump::params::{Border, BumpParams};
    let map = crate::maps::builtin("bumps", 16, 16, BumpParams::default().texel_fmt())?;
    let mut rows = Vec::new();
    for (code, filt) in crate::derivative::filters().into_iter().enumerate() {
        let d = Derivative::new(filt, map.clone(), Border::Wrap, crate::derivative::POS_FRAC);
        let mut sim = hdl::kernel::Sim::new(DerivativeUnit::new(d));
        sim.reset(1);
        for k in 0..64u32 {
            let (u, v) = (
                i64::from(mix(k, code as u32) % (16 << 16)),
                i64::from(mix(k, 9) % (16 << 16)),
            );
            let s = i64::from(mix(k, 11) % 1024);
            sim.dut.valid_in.set_bool(true);
            sim.dut.u.set_raw(u);
            sim.dut.v.set_raw(v);
            sim.dut.scale.set_raw(s);
            sim.step();
            let out = sim.dut.n.iter().map(|r| mask(r.q().raw(), 16)).collect();
            rows.push((vec![code as u64, mask(u, 32), mask(v, 32), s as u64], out));
        }
    }
    Ok(UnitVectors {
        unit: crate::derivative::NAME.into(),
        description: "para. 0086's derivative filters (0 central, 1 Sobel, 2 Prewitt, 3 the 5-point table) on the 16x16 bumps map, wrap: 64 hashed samples each".into(),
        inputs: vec![Field::new("filter", 2), Field::new("u", 32), Field::new("v", 32), Field::new("scale", 16)],
        outputs: ["nx", "ny", "nz"].iter().map(|n| Field::new(*n, 16)).collect(),
        rows,
    })
}

/// Para. 0087's unit on a formula colour map: 256 hashed samples.
pub fn biquadratic() -> Result<UnitVectors, String> {
    use units::bump::biquadratic_0087::{Biquadratic0087, ColourMap};
    let rgb = (0..16 * 16u32)
        .flat_map(|k| {
            [
                (k * 7 % 256) as u8,
                (k * 13 % 256) as u8,
                (k * 29 % 256) as u8,
            ]
        })
        .collect();
    let map = ColourMap {
        width: 16,
        height: 16,
        rgb,
        border: units::bump::params::Border::Wrap,
    };
    let mut sim = hdl::kernel::Sim::new(Biquadratic0087::new(map)?);
    sim.reset(1);
    let mut rows = Vec::new();
    for k in 0..256u32 {
        let (u, v) = (signed(mix(k, 0), 20 << 16), signed(mix(k, 1), 20 << 16));
        sim.dut.valid_in.set_bool(true);
        sim.dut.u.set_raw(u);
        sim.dut.v.set_raw(v);
        sim.step();
        rows.push((
            vec![mask(u, 32), mask(v, 32)],
            sim.dut.rgb.iter().map(|r| r.q().bits()).collect(),
        ));
    }
    Ok(UnitVectors {
        unit: crate::biquadratic::NAME.into(),
        description:
            "para. 0087's bi-quadratic colour on a 16x16 formula map, wrap: 256 hashed samples"
                .into(),
        inputs: vec![Field::new("u", 32), Field::new("v", 32)],
        outputs: vec![Field::new("r", 8), Field::new("g", 8), Field::new("b", 8)],
        rows,
    })
}

/// The texture of the `texture` vectors: 32x32 texels, CLUT and blocks from integer formulas
/// (no encoder, so no floating point is involved).
pub fn vector_texture() -> formats::ccc::Ccc {
    let clut = (0..256u32)
        .map(|i| ((i * 37) & 0xff) << 16 | ((i * 91) & 0xff) << 8 | ((i * 13 + 5) & 0xff))
        .collect();
    let blocks = (0..64u32)
        .map(|n| units::texmem::ccc_decode_608::CccBlock {
            a: (n * 7 + 3) as u8,
            b: (n * 11 + 100) as u8,
            bits: (n.wrapping_mul(0x9e37_79b9) >> 16) as u16,
        })
        .collect();
    formats::ccc::Ccc {
        width: 32,
        height: 32,
        clut,
        blocks,
    }
}

pub fn texture() -> Result<UnitVectors, String> {
    use crate::runs::texture::TexRequest;
    use units::texmem::texture_unit_602::TexParams;
    let tex = vector_texture();
    // Two horizontal scanlines, then positions from an integer hash (a `newline` every 16).
    let mut reqs = Vec::new();
    for line in 0..2u32 {
        for i in 0..40u32 {
            reqs.push(TexRequest {
                u: 5 + 12 * i,
                v: 40 + 20 * line,
                newline: i == 0,
            });
        }
    }
    for k in 0..176u32 {
        let h = k.wrapping_mul(0x9e37_79b9) ^ k.wrapping_mul(0x85eb_ca6b) >> 7;
        reqs.push(TexRequest {
            u: h % (32 << 4),
            v: (h >> 12) % (32 << 4),
            newline: k % 16 == 0,
        });
    }
    let mut rows = Vec::new();
    use units::texmem::cache_614::Lookahead;
    for (mode, cache, look) in [
        (0u64, true, Lookahead::Quadrant),
        (1, true, Lookahead::Off),
        (2, false, Lookahead::Off),
        (3, true, Lookahead::Direction),
    ] {
        let mut p = TexParams::new(32, 32);
        p.cache = cache;
        p.lookahead = look;
        let run = crate::runs::texture::run_texread(&tex, p, &reqs, 1, None)?;
        for (k, r) in reqs.iter().enumerate() {
            rows.push((
                vec![mode, u64::from(r.u), u64::from(r.v), u64::from(r.newline)],
                vec![u64::from(run.rgb[k]), run.out_cycles[k]],
            ));
        }
    }
    Ok(UnitVectors {
        unit: crate::texture::NAME.into(),
        description: "texture unit 602 (Figure 6), 32x32 texture from integer formulas (vectors::vector_texture), 256 requests uQ12.4 offered every cycle, row-major, 512-word pages; mode 0 cache + quadrant lookahead, 1 cache, 2 no cache, 3 cache + direction lookahead; outputs the colour and the cycle it leaves 622 (from the first request)".into(),
        inputs: vec![Field::new("mode", 2), Field::new("u", 16), Field::new("v", 16), Field::new("newline", 1)],
        outputs: vec![Field::new("rgb", 24), Field::new("cycle", 20)],
        rows,
    })
}

/// `golden/vectors/` of this source tree.
pub fn vectors_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../golden/vectors")
}
