//! Footprint assembly (Schilling & Knittel section 10): the integer reference (its own setup,
//! sample points and sums, plain loops over `RefMipmap`), the regress testbench of the
//! setup unit, generator and accumulator in front of the TEXRAM chip. The quality harness (a
//! tilted plane, against the f64 box average over each pixel's exact footprint) is
//! [`crate::runs::footprint::quality`].

use crate::runs::footprint::{on_texram, on_texture, quality, TILTS};
use crate::texram::{border_class, ref_border, test_map, RefBorder, RefMipmap, CYCLE_PS};
use crate::texture::reference_sums;
use formats::ccc::Ccc;
use hdl::kernel::{Sim, Trace};
use proptest::prelude::*;
use units::footprint::assembly_fig12::SampleTarget;
use units::footprint::footprint_fig12::FootprintFig12;
use units::footprint::setup_fig12::{NRounding, SetupParams};
use units::texram::{Border, Drf};
use verif::{
    run, About, Coverage, Coverpoint, Ctx, Event, Handshake, Pacing, PinDriver, PinMonitor,
    RunSpec, Scoreboard, Stimulus, TbResult, Testbench,
};

pub const NAME: &str = "footprint_fig12";

/// One pixel: its centre (sQ12.8) and screen derivatives r1, r2 (sQ11.8), raw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pixel {
    pub u: i32,
    pub v: i32,
    pub r1: (i32, i32),
    pub r2: (i32, i32),
}

/// What the reference (and the unit) give for a pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Assembled {
    pub value: u8,
    pub n: u32,
    /// R, G, B (luminance three times).
    pub rgb: u32,
}

/// The integer reference's own setup: N and the step (raw sQ.14 along the longer edge), and
/// lambda (raw sQ5.8) from its own table of `log2(1 + i/64)`.
pub fn ref_setup(p: &SetupParams, px: &Pixel) -> (u32, (i64, i64), i32) {
    let (a, b) = (px.r1, px.r2);
    let sq = |x: i64, y: i64| (x * x + y * y) as u128;
    let (a0, a1, b0, b1) = (
        i64::from(a.0),
        i64::from(a.1),
        i64::from(b.0),
        i64::from(b.1),
    );
    let lens = [
        sq(a0, a1),
        sq(b0, b1),
        sq(a0 + b0, a1 + b1),
        sq(a0 - b0, a1 - b1),
    ];
    let q2 = *lens.iter().min().expect("four");
    let m2 = lens[0].max(lens[1]);
    let mut n = 1u32;
    if m2 > 0 && q2 == 0 {
        n = 1 << p.max_log2_n;
    } else if m2 > 0 {
        // The power of two nearest m/q: in the log domain compare (m/q)^2 with 2 N^2.
        let up = |n: u32| match p.rounding {
            NRounding::Log => m2 >= 2 * q2 * u128::from(n) * u128::from(n),
            NRounding::Linear => 4 * m2 >= 9 * q2 * u128::from(n) * u128::from(n),
        };
        while n < 1 << p.max_log2_n && up(n) {
            n *= 2;
        }
    }
    let r = if lens[1] > lens[0] { b } else { a };
    // sQ.8 to sQ.14 divided by N.
    let step = (
        i64::from(r.0) * 64 / i64::from(n),
        i64::from(r.1) * 64 / i64::from(n),
    );
    (n, step, ref_lambda(q2 as u64))
}

/// `1/2 log2(x / 2^16)`: the leading one and six bits after it, the table made in f64 here
/// (the unit makes it by integer squaring), the sum halved half up, held to -4..10.
fn ref_lambda(x: u64) -> i32 {
    if x == 0 {
        return -4 * 256;
    }
    let lead = x.ilog2() as i32;
    let six = if lead >= 6 {
        (x >> (lead - 6)) as i32 - 64
    } else {
        (x << (6 - lead)) as i32 - 64
    };
    let table = (256.0 * (1.0 + f64::from(six) / 64.0).log2()).round() as i32;
    let full = (lead - 16) * 256 + table;
    (full + 1).div_euclid(2).clamp(-4 * 256, 10 * 256)
}

/// The reference's pixel: N sample points `p + (2i - (N - 1)) step / 2` in sQ.15, each
/// rounded half up to sQ.8, the exact trilinear sums added, their mean rounded once.
pub fn ref_assemble(
    map: &RefMipmap,
    border: RefBorder,
    p: &SetupParams,
    px: &Pixel,
) -> (Assembled, Vec<(i32, i32)>) {
    let (n, step, lambda) = ref_setup(p, px);
    let lim = 1i64 << 20;
    let coord = |c: i32, s: i64, i: u32| {
        let q15 = i64::from(c) * 128 + (2 * i64::from(i) - (i64::from(n) - 1)) * s;
        ((q15 + 64).div_euclid(128)).clamp(-lim, lim - 1) as i32
    };
    let mut total = 0i64;
    let mut points = Vec::new();
    for i in 0..n {
        let (u, v) = (coord(px.u, step.0, i), coord(px.v, step.1, i));
        total += map.sum(u, v, lambda, border);
        points.push((u, v));
    }
    let scale = i64::from(n) << 24;
    let value = ((total + scale / 2) / scale) as u8;
    let rgb = u32::from(value) * 0x01_01_01;
    (Assembled { value, n, rgb }, points)
}

/// Drives the setup unit's inputs.
pub fn drive_pixel<U: SampleTarget>(dut: &mut FootprintFig12<U>, t: Option<&Pixel>) {
    let s = &mut dut.setup;
    s.in_valid.set_bool(t.is_some());
    let t = t.copied().unwrap_or(Pixel {
        u: 0,
        v: 0,
        r1: (0, 0),
        r2: (0, 0),
    });
    s.u.set_raw(i64::from(t.u));
    s.v.set_raw(i64::from(t.v));
    for (sig, x) in [
        (&mut s.r1u, t.r1.0),
        (&mut s.r1v, t.r1.1),
        (&mut s.r2u, t.r2.0),
        (&mut s.r2v, t.r2.1),
    ] {
        sig.set_raw(i64::from(x));
    }
}

/// The setup unit takes a pixel in a cycle with `in_ready` high.
pub fn pixel_ready<U: SampleTarget>(dut: &FootprintFig12<U>) -> bool {
    dut.setup.in_ready.is_high()
}

/// Reports each assembled pixel.
pub fn sample_pixel<U: SampleTarget>(dut: &FootprintFig12<U>) -> Option<Assembled> {
    let a = &dut.assembly;
    let r = &a.acc;
    r.out_valid.q().is_high().then(|| Assembled {
        value: r.out_value.q().bits() as u8,
        n: r.out_n.q().bits() as u32,
        rgb: r.out_rgb.q().bits() as u32,
    })
}

/// The reference on Figure 6's texture unit 602 (`F` fraction bits): the same sample points,
/// each less half a texel and rounded half up to the unit's grid, held inside the texture;
/// the unit reference's exact bilinear sums added per channel, each mean rounded once.
/// Also returns the exact mean of R (for the error against the mathematics).
pub fn ref_assemble_texture(
    t: &Ccc,
    frac_bits: u32,
    p: &SetupParams,
    px: &Pixel,
) -> (Assembled, f64) {
    let (n, step, _) = ref_setup(p, px);
    let f = frac_bits;
    let coord = |c: i32, s: i64, i: u32, size: u32| {
        let q15 = i64::from(c) * 128 + (2 * i64::from(i) - (i64::from(n) - 1)) * s - (1 << 14);
        let unit = 1i64 << (15 - f);
        let r = (q15 + unit / 2).div_euclid(unit);
        r.clamp(0, (i64::from(size) << f) - 1) as u32
    };
    let mut total = [0u64; 3];
    for i in 0..n {
        let (u, v) = (
            coord(px.u, step.0, i, t.width),
            coord(px.v, step.1, i, t.height),
        );
        for (acc, s) in total.iter_mut().zip(reference_sums(t, u, v, f)) {
            *acc += s;
        }
    }
    let scale = u64::from(n) << (2 * f);
    let ch = total.map(|s| ((s + scale / 2) / scale) as u32);
    let a = Assembled {
        value: ch[0] as u8,
        n,
        rgb: ch[0] << 16 | ch[1] << 8 | ch[2],
    };
    (a, total[0] as f64 / scale as f64)
}

/// Random pixels over a `2^wl x 2^hl` map and beyond it: footprints from a sixteenth of a
/// texel to 64 texels across, anisotropy 1 to 32, any direction, some shear.
pub fn pixels(wl: u32, hl: u32, n: usize, stim: &mut Stimulus) -> Vec<Pixel> {
    let (w, h) = ((1i32 << wl) << 8, (1i32 << hl) << 8);
    let s = (
        -512..w + 512,
        -512..h + 512,
        -4.0f64..6.0,
        0.0f64..5.0,
        0.0f64..std::f64::consts::TAU,
        -0.6f64..0.6,
    )
        .prop_map(|(u, v, size, aniso, angle, shear)| {
            let (long, short) = ((size + aniso).exp2(), size.exp2());
            let raw = |x: f64| ((x * 256.0).round() as i32).clamp(-(1 << 19), (1 << 19) - 1);
            let (c, s) = (angle.cos(), angle.sin());
            let (c2, s2) = ((angle + shear).cos(), (angle + shear).sin());
            Pixel {
                u,
                v,
                r1: (raw(long * c), raw(long * s)),
                r2: (raw(-short * s2), raw(short * c2)),
            }
        });
    stim.draw_n(&s, n)
}

/// Pixels every configuration gets first, so that its coverage does not depend on the
/// count: isotropic, Figure 12's two cases, none, collapsed, the longest, and for every N up
/// to `2^max_k` a footprint of squares magnified (q = 1/2 texel), between levels (q = 2) and
/// of the last level (q = 2^lmax), each as long as the raw format allows.
fn directed(lmax: u32, max_k: u32) -> Vec<Pixel> {
    let px = |r1, r2| Pixel {
        u: 1000,
        v: 2000,
        r1,
        r2,
    };
    let mut v = vec![
        px((256, 0), (0, 256)),
        px((512, 0), (0, 256)),
        px((0, 256), (-1024, 0)),
        px((0, 0), (0, 0)),
        px((700, 700), (700, 700)),
        px((1 << 16, 0), (0, 64)),
        px((3, 1), (-1, 2)),
    ];
    for k in 0..=max_k {
        for q in [128i64, 512, 256 << lmax] {
            let long = (q << k).min((1 << 19) - 1) as i32;
            v.push(px((long, 0), (0, q as i32)));
        }
    }
    v
}

/// What the generator drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unit {
    /// The TEXRAM chip 802.
    Texram,
    /// Figure 6's texture unit 602 with `F` fraction bits, its cache on or off.
    Texture(u32, bool),
}

/// The configurations: map size (log2), border, N limit, rounding, unit.
const CONFIGS: [(u32, u32, Border, u32, NRounding, Unit); 6] = [
    (6, 6, Border::Wrap, 4, NRounding::Log, Unit::Texram),
    (8, 8, Border::Mirror, 4, NRounding::Log, Unit::Texram),
    (6, 5, Border::Clamp, 6, NRounding::Linear, Unit::Texram),
    (5, 3, Border::Colour(40), 2, NRounding::Log, Unit::Texram),
    (
        6,
        6,
        Border::Clamp,
        4,
        NRounding::Log,
        Unit::Texture(4, true),
    ),
    (
        5,
        4,
        Border::Clamp,
        6,
        NRounding::Linear,
        Unit::Texture(8, false),
    ),
];

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let n = c.add(
        Coverpoint::new("n")
            .values(&["1", "2", "4", "8", "16"])
            .bin("32..64", 5, 6),
    );
    let l = c.add(Coverpoint::new("lambda").values(&["magnified", "between_levels", "last_level"]));
    c.add(Coverpoint::new("border").values(&["wrap", "clamp", "mirror", "colour"]));
    c.add(Coverpoint::new("rounding").values(&["log", "linear"]));
    let u = c.add(Coverpoint::new("unit").values(&["texram_802", "texture_unit_602"]));
    c.cross("n_x_lambda", n, l);
    c.cross("n_x_unit", n, u);
    c
}

/// The regress testbench: setup unit, generator and accumulator with the chip, pixel by
/// pixel against the integer reference (value and N, bit-exact) and the f64 mean of the
/// chip's accesses (error in LSBs, bound 0.5).
pub struct FootprintTb;

impl Testbench for FootprintTb {
    fn about(&self) -> About {
        About::new(NAME, "footprint assembly, section 10: setup unit, sample generator and accumulator before the TEXRAM chip 802")
            .count(1500, "random pixels")
    }
    fn configurations(&self) -> Vec<String> {
        CONFIGS
            .iter()
            .map(|(w, h, b, k, r, unit)| {
                let on = match unit {
                    Unit::Texram => format!("texram_802, {}", b.name()),
                    Unit::Texture(f, cache) => format!(
                        "texture_unit_602 (CCC, F = {f}, cache {})",
                        if *cache { "on" } else { "off" }
                    ),
                };
                format!(
                    "{}x{} on {on}, N <= {}, {r:?} rounding",
                    1u32 << w,
                    1u32 << h,
                    1u32 << k
                )
            })
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn conclude(&self, merged: &mut TbResult) {
        let mut table = String::from(
            "| plane tilt | pixels | RMSE trilinear (LSB) | RMSE footprint assembly (LSB) | mean N | slots | bank faults | M pixels/s |\n|---|---|---|---|---|---|---|---|\n",
        );
        for tilt in TILTS {
            let r = match quality(tilt, &SetupParams::default()) {
                Ok(r) => r,
                Err(e) => {
                    merged
                        .failures
                        .push(format!("quality at {tilt} degrees: {e}"));
                    continue;
                }
            };
            table.push_str(&format!(
                "| {tilt} | {} | {:.2} | {:.2} | {:.2} | {} | {} | {:.2} |\n",
                r.pixels,
                r.rmse_trilinear,
                r.rmse_footprint,
                r.mean_n,
                r.slots,
                r.faults,
                r.pixels_per_second / 1e6
            ));
            merged.notes.push(format!(
                "plane at {tilt} degrees: RMSE {:.2} LSB trilinear, {:.2} footprint assembly (mean N {:.2})",
                r.rmse_trilinear, r.rmse_footprint, r.mean_n
            ));
            if tilt >= 75.0 && r.rmse_footprint >= r.rmse_trilinear {
                merged.failures.push(format!(
                    "at {tilt} degrees footprint assembly ({:.2} LSB) does not beat trilinear ({:.2})",
                    r.rmse_footprint, r.rmse_trilinear
                ));
            }
        }
        merged.tables.push(table);
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (wl, hl, border, k, rounding, unit) = CONFIGS[ctx.index];
        let p = SetupParams {
            max_log2_n: k,
            rounding,
        };
        let mut stim = Stimulus::new(ctx.seed);
        let mut px = directed(wl.max(hl), k);
        let title = format!("{NAME} {}", ctx.label);
        let cfg = (p, wl.max(hl) as i32, border);
        match unit {
            Unit::Texram => {
                let level0 = test_map(1 << wl, 1 << hl, &mut stim);
                px.extend(pixels(wl, hl, ctx.count, &mut stim));
                let dut = on_texram(p, Drf::new(wl, hl, border), &level0)?;
                let (sim, _) = ctx.sim(dut, &title, CYCLE_PS, |_| ())?;
                let reference = RefMipmap::build(1 << wl, 1 << hl, &level0);
                let expect = |q: &Pixel| expect(&reference, border, &p, q);
                let (sim, mut res) = run_pixels(sim, ctx, cfg, px, expect)?;
                let chip = &sim.dut.assembly.chip;
                res.notes.push(format!(
                    "{}: {} accesses in {} slots",
                    ctx.label,
                    chip.accesses.q().bits(),
                    chip.slots.q().bits()
                ));
                ctx.finish(sim, &mut res)?;
                Ok(res)
            }
            Unit::Texture(f, cache) => {
                let tex = crate::texture::test_pattern(1 << wl, 1 << hl);
                px.extend(pixels(wl, hl, ctx.count, &mut stim));
                let mut tp = units::texmem::texture_unit_602::TexParams::new(1 << wl, 1 << hl);
                (tp.frac_bits, tp.cache) = (f, cache);
                let dut = on_texture(p, &tex, tp)?;
                let (sim, _) = ctx.sim(dut, &title, CYCLE_PS, |_| ())?;
                let expect = |q: &Pixel| {
                    let (a, mean) = ref_assemble_texture(&tex, f, &p, q);
                    (*q, a, mean)
                };
                let (sim, mut res) = run_pixels(sim, ctx, cfg, px, expect)?;
                ctx.finish(sim, &mut res)?;
                Ok(res)
            }
        }
    }
}

/// What a pixel should give: the reference's result, and the f64 mean of the trilinear
/// accesses at its sample points (truncated weights, as the chip forms them).
type Expected = (Pixel, Assembled, f64);

fn expect(map: &RefMipmap, border: Border, p: &SetupParams, px: &Pixel) -> Expected {
    let (want, points) = ref_assemble(map, ref_border(border), p, px);
    let (_, _, lambda) = ref_setup(p, px);
    let golden_border = crate::texram::golden_border(border);
    let g = golden::texram::Mipmap {
        width: map.width as usize,
        height: map.height as usize,
        levels: &map.levels,
        border: golden_border,
    };
    let lmax = map.levels.len() - 1;
    let mean = points
        .iter()
        .map(|&(u, v)| {
            let w = golden::texram::Weights::truncated(
                f64::from(u) / 256.0,
                f64::from(v) / 256.0,
                f64::from(lambda) / 256.0,
                lmax,
            );
            golden::texram::trilinear(&g, &w)
        })
        .sum::<f64>()
        / points.len() as f64;
    (*px, want, mean)
}

/// The fields the setup unit hands the assembly unit with `px_valid`: `(drf, u, v, lambda,
/// du, dv, log2_n)`.
type Handover = (u64, u64, u64, u64, u64, u64, u64);

/// The pixel hand-over from setup to assembly at the pins: `(valid, ready, fields)`.
fn handover<U: SampleTarget>(d: &FootprintFig12<U>) -> (bool, bool, Handover) {
    let a = &d.assembly;
    let fields = (
        a.px_drf.bits(),
        a.px_u.bits(),
        a.px_v.bits(),
        a.px_lambda.bits(),
        a.px_du.bits(),
        a.px_dv.bits(),
        a.px_log2_n.bits(),
    );
    (a.px_valid.is_high(), a.px_ready.is_high(), fields)
}

/// Drives the pixels with random gaps and scores each against `expect` (the reference's
/// result and the exact mean).
fn run_pixels<U: SampleTarget, T: Trace>(
    mut sim: Sim<FootprintFig12<U>, T>,
    ctx: &Ctx,
    (p, lmax, border): (SetupParams, i32, Border),
    px: Vec<Pixel>,
    expect: impl Fn(&Pixel) -> Expected,
) -> Result<(Sim<FootprintFig12<U>, T>, TbResult), String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let n = px.len() as u64;
    let mut sb: Scoreboard<Expected, Assembled> =
        Scoreboard::new(|(_, e, _): &Expected, a: &Assembled| {
            if e == a {
                Ok(())
            } else {
                Err(format!("got {a:?}, want {e:?}"))
            }
        });
    let unit = i64::from(sim.dut.assembly.chip.channels() == 3);
    let pacing = Pacing::random(300, ctx.seed.derive(5));
    let mut spec = RunSpec::new(n, 200 * 64 * n + 1000).pacing(pacing);
    let mut samples = 0u64;
    let mut pins = Handshake::<Handover>::new("footprint_fig12.footprint_assembly.px_valid");
    let r = run(
        &mut sim,
        &mut PinDriver::new(drive_pixel).ready(pixel_ready),
        &mut PinMonitor::new(sample_pixel),
        px,
        &mut spec,
        |sim, ev| match ev {
            Event::Sent { txn, .. } => sb.expect(expect(txn)),
            Event::Received { cycle, txn } => {
                samples += u64::from(txn.n);
                if let Some((q, _, want)) = sb.observe(cycle, txn).expected {
                    res.stats.record(f64::from(txn.value), want, 1.0);
                    let (_, _, lambda) = ref_setup(&p, &q);
                    let l = if lambda < 0 {
                        0
                    } else if lambda >> 8 >= lmax {
                        2
                    } else {
                        1
                    };
                    let r = i64::from(p.rounding == NRounding::Linear);
                    let b = border_class(border);
                    cov.sample(&[i64::from(txn.n.trailing_zeros()), l, b, r, unit]);
                }
            }
            Event::Settled { cycle } => {
                let (valid, ready, fields) = handover(&sim.dut);
                pins.sample(cycle, valid, ready, fields);
            }
        },
    );
    res.score(&sb);
    res.ran(&r);
    if let Err(e) = pins.check() {
        res.failures.push(e);
    }
    // The assembly's pixel counter (a waveform aid) counts the pixels that came out.
    let counted = sim.dut.assembly.acc.pixels.q().bits();
    if counted != res.transactions {
        res.failures.push(format!(
            "the pixel counter says {counted}, {} pixels came out",
            res.transactions
        ));
    }
    if res.stats.max_abs_lsb > golden::texram::ERROR_BOUND_LSB {
        res.failures.push(format!(
            "error {:.4} LSB against the f64 mean, bound 0.5",
            res.stats.max_abs_lsb
        ));
    }
    res.notes.push(format!(
        "{}: {n} pixels, {samples} samples ({:.2} a pixel)",
        ctx.label,
        samples as f64 / n.max(1) as f64
    ));
    res.coverage = Some(cov);
    Ok((sim, res))
}
