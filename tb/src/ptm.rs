//! PTM micro-occlusion (001, Figs 2, 3 and 6): the host's part (samples by marching toward
//! each light of a dome, the pseudo-inverse), the fitter 604 and the light shader 608, their
//! testbenches (the fit's quality against the ray-marched truth is [`crate::runs::ptm`]).
//!
//! `ptm_fitter_604`: swatches of tileable height fields under domes of lights; each texel's
//! six stored coefficients equal the integer reference (bit for bit) and, dequantised, lie
//! within the derived bound of the f64 QR fit of the same samples. `ptm_shader_608`: random
//! coefficients and lights in the unit disc; K equal to the integer reference and within half
//! an LSB of the f64 polynomial on the dequantised coefficients.

use golden::ptm::{Basis, Light};
use hdl::kernel::{Sim, Trace};
use units::ptm::fitter_604::Fitter604;
use units::ptm::shader_608::Shader608;
use units::ptm::texture_612::{p_raw, PtmFormat};
use verif::{
    run_scored, About, Coverage, Coverpoint, Ctx, PinDriver, PinMonitor, RunSpec, Scoreboard,
    Scored, Stimulus, TbResult, Testbench,
};
use waves::VcdTracer;

pub const FITTER: &str = "ptm_fitter_604";
pub const SHADER: &str = "ptm_shader_608";
/// The units' clock (a 5 ns cycle) \[C\].
const CYCLE_PS: u64 = 5_000;

/// The pseudo-inverse of the quadratic basis over `lights`, rounded to sQ7.20; an error
/// naming the reason when the fit has no unique answer (one ring of lights, too few).
pub fn host_pinv(lights: &[Light]) -> Result<[Vec<i32>; 6], String> {
    if lights.len() < 6 {
        return Err(format!(
            "{} lights: the six coefficients need at least 6",
            lights.len()
        ));
    }
    let rows = Basis::Quadratic.rows(lights);
    let p = golden::ptm::pseudo_inverse(&rows).ok_or(
        "the lights leave the fit singular (one elevation makes u^2 + v^2 constant: use two rings or more)",
    )?;
    let p40: [Vec<i64>; 6] = std::array::from_fn(|j| {
        p[j].iter()
            .map(|x| (x * 2f64.powi(40)).round() as i64)
            .collect()
    });
    p_raw(&p40)
}

/// A swatch: heights (texel units, `n x n`, tiled), lights, and the samples 602 makes:
/// `samples[t L + i]` for texel t and light i, 255 lit, 0 occluded.
pub struct Swatch {
    pub n: usize,
    pub heights: Vec<f64>,
    pub lights: Vec<Light>,
    pub samples: Vec<u8>,
}

impl Swatch {
    /// The samples of `heights` under `lights` (binary, by marching).
    pub fn new(n: usize, heights: Vec<f64>, lights: Vec<Light>) -> Swatch {
        let mut samples = Vec::with_capacity(n * n * lights.len());
        for t in 0..n * n {
            for l in &lights {
                let lit = golden::ptm::lit(&heights, n, t % n, t / n, *l);
                samples.push(if lit { 255 } else { 0 });
            }
        }
        Swatch {
            n,
            heights,
            lights,
            samples,
        }
    }

    pub fn texel_samples(&self, t: usize) -> &[u8] {
        let l = self.lights.len();
        &self.samples[t * l..(t + 1) * l]
    }
}

/// The fitter's result for each texel of `samples` (L a texel), clocked.
pub fn run_fitter<T: Trace>(
    mut sim: Sim<Fitter604, T>,
    samples: &[u8],
) -> (Vec<[u64; 6]>, Sim<Fitter604, T>) {
    sim.reset(2);
    let mut out = Vec::with_capacity(samples.len() / sim.dut.lights().max(1));
    for c in 0..=samples.len() {
        sim.dut.in_valid.set_bool(c < samples.len());
        sim.dut
            .in_sample
            .set_bits(u64::from(samples.get(c).copied().unwrap_or(0)));
        sim.eval();
        if sim.dut.out_valid.q().is_high() {
            out.push(sim.dut.out_q.each_ref().map(|r| r.q().bits()));
        }
        sim.tick();
    }
    (out, sim)
}

/// The integer reference of one texel's fit: plain sums and a floor division.
pub fn ref_fit(p: &[Vec<i32>; 6], fmt: &PtmFormat, samples: &[u8]) -> [u64; 6] {
    std::array::from_fn(|j| {
        let acc: i128 = samples
            .iter()
            .zip(&p[j])
            .map(|(&s, &pj)| {
                let x = 255 - i128::from(s);
                i128::from(pj) * (x + x / 128)
            })
            .sum();
        let step = 1i128 << (fmt.exp[j] + 8);
        let q = (acc - i128::from(fmt.bias[j]) * 256 + step / 2).div_euclid(step);
        q.clamp(0, i128::from(fmt.max_q())) as u64
    })
}

/// The f64 fit of one texel (QR on `K_i = 1 - s_i/255`) and, per coefficient, the bound on
/// the hardware's distance from it: P's rounding (half of 2^-20 an entry), the occlusion's
/// widening (2^-9 times |P_ji| for grey samples) and the final rounding (half a step).
pub fn golden_fit(
    lights: &[Light],
    p: &[Vec<i32>; 6],
    fmt: &PtmFormat,
    s: &[u8],
) -> ([f64; 6], [f64; 6]) {
    let rows = Basis::Quadratic.rows(lights);
    let k: Vec<f64> = s.iter().map(|&x| 1.0 - f64::from(x) / 255.0).collect();
    let c = golden::ptm::fit(&rows, &k).unwrap_or_else(|| vec![0.0; 6]);
    let unit = 2f64.powi(-20);
    let bound = std::array::from_fn(|j| {
        let grey = s.iter().filter(|&&x| x != 0 && x != 255).count() as f64;
        let pmax = p[j]
            .iter()
            .map(|x| f64::from(x.unsigned_abs()))
            .fold(0.0, f64::max)
            * unit;
        lights.len() as f64 * unit / 2.0
            + grey * (pmax + unit) / 510.0
            + 2f64.powi(fmt.exp[j] as i32 - 1) * unit
            + 1e-9
    });
    (std::array::from_fn(|j| c[j]), bound)
}

/// A random tileable height field: woven threads of a random amplitude plus a few bumps.
pub fn random_heights(n: usize, stim: &mut Stimulus) -> Vec<f64> {
    let amp = f64::from(stim.draw(&(5u32..40))) / 10.0;
    let mut h = golden::ptm::woven(n, amp);
    for _ in 0..stim.draw(&(0usize..6)) {
        let (cx, cy) = (stim.draw(&(0..n)), stim.draw(&(0..n)));
        let r = f64::from(stim.draw(&(1u32..4)));
        let top = f64::from(stim.draw(&(5u32..50))) / 10.0;
        for y in 0..n {
            for x in 0..n {
                let d = |a: usize, b: usize| {
                    let d = a.abs_diff(b);
                    d.min(n - d) as f64
                };
                let dist = (d(x, cx).powi(2) + d(y, cy).powi(2)).sqrt();
                h[y * n + x] += (top * (1.0 - dist / r)).max(0.0);
            }
        }
    }
    h
}

/// The fitter testbench's configurations: dome (rings, azimuths), bits, grey samples.
const FIT_CONFIGS: [((usize, usize), u32, bool); 4] = [
    ((3, 8), 8, false),
    ((4, 12), 16, false),
    ((2, 6), 16, true),
    ((5, 16), 8, false),
];

fn drive_sample(dut: &mut Fitter604, t: Option<&u8>) {
    dut.in_valid.set_bool(t.is_some());
    dut.in_sample.set_bits(u64::from(t.copied().unwrap_or(0)));
}

fn sample_texel(dut: &Fitter604) -> Option<[u64; 6]> {
    dut.out_valid
        .q()
        .is_high()
        .then(|| dut.out_q.each_ref().map(|r| r.q().bits()))
}

fn fitter_coverage() -> Coverage {
    let mut c = Coverage::new();
    let occ = c.add(
        Coverpoint::new("occluded_lights")
            .value("none", 0)
            .bin("some", 1, 1)
            .bin("most", 2, 2)
            .value("all", 3),
    );
    let lights = c.add(
        Coverpoint::new("lights")
            .bin("12", 12, 12)
            .bin("24", 24, 24)
            .bin("48", 48, 48)
            .bin("80", 80, 80),
    );
    c.add(Coverpoint::new("samples").values(&["binary", "grey"]));
    c.cross("occluded_x_lights", occ, lights);
    c
}

/// One texel's coverage class of occluded lights: none, up to half, more, all.
fn occluded_class(s: &[u8]) -> i64 {
    let n = s.iter().filter(|&&x| x < 128).count();
    match n {
        0 => 0,
        _ if n == s.len() => 3,
        _ if 2 * n <= s.len() => 1,
        _ => 2,
    }
}

/// The fitter's regress testbench.
pub struct PtmFitterTb;

impl Testbench for PtmFitterTb {
    fn about(&self) -> About {
        About::new(FITTER, "PTM fitter 604: six multiply-accumulate lanes against the pseudo-inverse, one light a cycle (001, Fig. 6, [0049])")
            .count(256, "texels")
    }
    fn configurations(&self) -> Vec<String> {
        FIT_CONFIGS
            .iter()
            .map(|((r, a), bits, grey)| {
                let s = if *grey { "grey" } else { "marched" };
                format!("{r} rings x {a}, {bits}-bit coefficients, {s} samples")
            })
            .collect()
    }
    fn coverage(&self) -> Coverage {
        fitter_coverage()
    }
    fn conclude(&self, merged: &mut TbResult) {
        match crate::pictures::ptm::swatch_picture() {
            Ok((_, side, q)) => {
                merged.notes.push(format!(
                    "{side}x{side} woven swatch, {} lights: fit RMSE a texel {:.3} mean, {:.3} worst (occlusion in [0, 1], the 8-bit PTM against the marched samples)",
                    q.lights, q.rmse_mean, q.rmse_max
                ));
                merged.tables.push(format!(
                    "| PTM storage ({side}x{side} texels, {} lights) | bytes |\n|---|---|\n| PTM, six {}-bit coefficients a texel | {} |\n| the binary sample images | {} |\n| 4096 x 4096 shadow maps of 32-bit depths, one a light | {} |\n",
                    q.lights, q.bits, q.ptm_bytes, q.images_bytes, q.shadow_map_bytes
                ));
            }
            Err(e) => merged.failures.push(e),
        }
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let ((rings, az), bits, grey) = FIT_CONFIGS[ctx.index];
        let mut stim = Stimulus::new(ctx.seed);
        let lights = golden::ptm::dome(rings, az);
        let n = ((ctx.count as f64).sqrt().ceil() as usize).max(2);
        let mut sw = Swatch::new(n, random_heights(n, &mut stim), lights.clone());
        if grey {
            sw.samples = stim.draw_n(&(0u8..=255), sw.samples.len());
        }
        // Directed texels: every light lit, every light occluded, one occluded, one lit.
        let l = lights.len();
        for (first, rest) in [(255, 255), (0, 0), (0, 255), (255, 0)] {
            sw.samples.push(first);
            sw.samples.extend(std::iter::repeat_n(rest, l - 1));
        }
        let p = host_pinv(&lights)?;
        let fmt = PtmFormat::for_pinv(&p, bits)?;
        let (sim, _) = ctx.sim(
            Fitter604::new(p.clone(), fmt)?,
            &format!("{FITTER} {}", ctx.label),
            CYCLE_PS,
            |_| (),
        )?;
        let mut res = run_fitter_tb(sim, ctx, &sw, &p, &fmt, grey)?;
        res.notes.insert(
            0,
            format!(
                "{}: {} texels of {l} lights",
                ctx.label,
                sw.samples.len() / l
            ),
        );
        Ok(res)
    }
}

/// Drives a swatch's samples with random gaps; scores each texel bit for bit against the
/// reference and against the f64 fit within its bound (error in steps of each coefficient).
fn run_fitter_tb(
    mut sim: Sim<Fitter604, VcdTracer>,
    ctx: &Ctx,
    sw: &Swatch,
    p: &[Vec<i32>; 6],
    fmt: &PtmFormat,
    grey: bool,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(FITTER, "");
    let mut cov = fitter_coverage();
    sim.reset(2);
    let l = sw.lights.len();
    let texels = sw.samples.len() / l;
    let mut sb: Scoreboard<[u64; 6], [u64; 6]> = Scoreboard::new(|e: &[u64; 6], a: &[u64; 6]| {
        if e == a {
            Ok(())
        } else {
            Err(format!("fitter {a:?}, reference {e:?}"))
        }
    });
    let (mut sent, mut seen, mut outside) = (0usize, 0usize, 0u64);
    let pacing = verif::Pacing::random(150, ctx.seed.derive(3));
    let mut spec = RunSpec::new(texels as u64, 4 * sw.samples.len() as u64 + 100).pacing(pacing);
    let r = run_scored(
        &mut sim,
        &mut PinDriver::new(drive_sample),
        &mut PinMonitor::new(sample_texel),
        sw.samples.clone(),
        &mut spec,
        |_, ev| match ev {
            Scored::Sent { .. } => {
                sent += 1;
                if sent % l == 0 {
                    sb.expect(ref_fit(p, fmt, sw.texel_samples(sent / l - 1)));
                }
            }
            Scored::Received { cycle, txn } => {
                let s = sw.texel_samples(seen);
                seen += 1;
                sb.observe(cycle, txn);
                let (c, bound) = golden_fit(&sw.lights, p, fmt, s);
                for j in 0..6 {
                    let got = fmt.coefficient(j, txn[j]) as f64 * 2f64.powi(-20);
                    let step = 2f64.powi(fmt.exp[j] as i32 - 20);
                    res.stats.record(got, c[j], step);
                    outside += u64::from((got - c[j]).abs() > bound[j]);
                }
                cov.sample(&[occluded_class(s), l as i64, i64::from(grey)]);
            }
        },
    );
    res.score(&sb);
    res.ran(&r);
    if outside > 0 {
        res.failures.push(format!(
            "{outside} coefficients outside their bound of the f64 fit"
        ));
    }
    res.notes.push(format!(
        "{}: coefficients within {:.2} steps of the f64 QR fit (bound: P's rounding, the occlusion's widening, half a step)",
        ctx.label, res.stats.max_abs_lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}

/// A light query of the shader: a texel's stored coefficients and `(u, v)` raw sQ1.14.
pub type Query = ([u64; 6], i64, i64);

/// The f64 occlusion of `q` at `(u, v)` on the dequantised coefficients, held to [0, 1].
pub fn golden_k(fmt: &PtmFormat, q: &[u64; 6], u: i64, v: i64) -> f64 {
    let c: [f64; 6] = std::array::from_fn(|j| fmt.coefficient(j, q[j]) as f64 * 2f64.powi(-20));
    let s = 2f64.powi(-14);
    golden::ptm::evaluate(&c, u as f64 * s, v as f64 * s)
}

/// The integer reference of the shader: the polynomial term by term, exact, rounded half
/// up, held to 0 ..= 255.
pub fn ref_k(fmt: &PtmFormat, q: &[u64; 6], u: i64, v: i64) -> u8 {
    let a: [i128; 6] =
        std::array::from_fn(|j| ((q[j] as i128) << fmt.exp[j]) + i128::from(fmt.bias[j]));
    let (u, v) = (i128::from(u), i128::from(v));
    // A in 2^-20, u and v 2^-14: every term in 2^-48.
    let k = a[0] * u * u
        + ((a[1] * u) << 14)
        + a[2] * u * v
        + ((a[3] * v) << 14)
        + a[4] * v * v
        + (a[5] << 28);
    let unit = 1i128 << 40;
    (k + unit / 2).div_euclid(unit).clamp(0, 255) as u8
}

const SHADE_CONFIGS: [((usize, usize), u32); 2] = [((3, 8), 8), ((4, 12), 16)];

fn drive_query(dut: &mut Shader608, t: Option<&Query>) {
    dut.in_valid.set_bool(t.is_some());
    if let Some((q, u, v)) = t {
        for (s, x) in dut.q.iter_mut().zip(q) {
            s.set_bits(*x);
        }
        dut.u.set_raw(*u);
        dut.v.set_raw(*v);
    }
}

fn sample_k(dut: &Shader608) -> Option<(u8, u8)> {
    dut.out_valid
        .q()
        .is_high()
        .then(|| (dut.k.q().bits() as u8, dut.visibility.q().bits() as u8))
}

fn shader_coverage() -> Coverage {
    let mut c = Coverage::new();
    let k = c.add(
        Coverpoint::new("k")
            .value("0 (held)", 0)
            .bin("inside", 1, 254)
            .value("255 (held)", 255),
    );
    let quad =
        c.add(Coverpoint::new("light_quadrant").values(&["+u +v", "-u +v", "+u -v", "-u -v"]));
    c.cross("k_x_quadrant", k, quad);
    c
}

/// Queries: half of them coefficients of real fits (a marched swatch), half random stored
/// values; lights uniform in the unit disc.
pub fn queries(
    lights: &[Light],
    p: &[Vec<i32>; 6],
    fmt: &PtmFormat,
    n: usize,
    stim: &mut Stimulus,
) -> Vec<Query> {
    let side = 8;
    let sw = Swatch::new(side, random_heights(side, stim), lights.to_vec());
    let fits: Vec<[u64; 6]> = (0..side * side)
        .map(|t| ref_fit(p, fmt, sw.texel_samples(t)))
        .collect();
    let one = 1i64 << 14;
    (0..n)
        .map(|i| {
            let q = if i % 2 == 0 {
                fits[stim.draw(&(0..fits.len()))]
            } else {
                std::array::from_fn(|_| stim.draw(&(0..=fmt.max_q())))
            };
            loop {
                let (u, v) = (stim.draw(&(-one..=one)), stim.draw(&(-one..=one)));
                if u * u + v * v <= one * one {
                    return (q, u, v);
                }
            }
        })
        .collect()
}

/// The shader's regress testbench.
pub struct PtmShaderTb;

impl Testbench for PtmShaderTb {
    fn about(&self) -> About {
        About::new(SHADER, "PTM evaluator of the light shader 608: K = (A1 u + A3 v + A2) u + (A5 v + A4) v + A6, visibility 1 - K (001, Fig. 6, [0030])")
            .count(4000, "light queries")
    }
    fn configurations(&self) -> Vec<String> {
        SHADE_CONFIGS
            .iter()
            .map(|((r, a), bits)| format!("{r} rings x {a}, {bits}-bit coefficients"))
            .collect()
    }
    fn coverage(&self) -> Coverage {
        shader_coverage()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let ((rings, az), bits) = SHADE_CONFIGS[ctx.index];
        let mut stim = Stimulus::new(ctx.seed);
        let lights = golden::ptm::dome(rings, az);
        let p = host_pinv(&lights)?;
        let fmt = PtmFormat::for_pinv(&p, bits)?;
        let qs = queries(&lights, &p, &fmt, ctx.count.max(64), &mut stim);
        let (sim, _) = ctx.sim(
            Shader608::new(fmt)?,
            &format!("{SHADER} {}", ctx.label),
            CYCLE_PS,
            |_| (),
        )?;
        run_shader_tb(sim, ctx, &fmt, qs)
    }
}

fn run_shader_tb(
    mut sim: Sim<Shader608, VcdTracer>,
    ctx: &Ctx,
    fmt: &PtmFormat,
    qs: Vec<Query>,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(SHADER, "");
    let mut cov = shader_coverage();
    sim.reset(2);
    let f = *fmt;
    let mut sb: Scoreboard<Query, (u8, u8)> =
        Scoreboard::new(move |(q, u, v): &Query, a: &(u8, u8)| {
            let k = ref_k(&f, q, *u, *v);
            let g = golden_k(&f, q, *u, *v) * 256.0;
            // Half an LSB, or one where the f64 value reaches 1 (the hardware holds 255/256).
            let bound = if g > 255.5 { 1.0 } else { 0.5 } + 1e-9;
            if *a != (k, 255 - k) {
                Err(format!("shader {a:?}, reference {k}"))
            } else if (f64::from(k) - g.min(256.0)).abs() > bound {
                Err(format!(
                    "K {k} is {:.3} from the f64 {g:.3}",
                    (f64::from(k) - g).abs()
                ))
            } else {
                Ok(())
            }
        });
    let n = qs.len() as u64;
    let mut spec =
        RunSpec::new(n, 3 * n + 50).pacing(verif::Pacing::random(200, ctx.seed.derive(4)));
    let r = sb.run(
        &mut sim,
        &mut PinDriver::new(drive_query),
        &mut PinMonitor::new(sample_k),
        qs.into_iter().map(|q| (q, q)),
        &mut spec,
        |_, (q, u, v), txn| {
            let g = golden_k(fmt, &q, u, v) * 256.0;
            res.stats.record(f64::from(txn.0), g.min(255.0), 1.0);
            cov.sample(&[i64::from(txn.0), i64::from(u < 0) + 2 * i64::from(v < 0)]);
        },
    );
    res.score(&sb);
    res.ran(&r);
    res.notes.push(format!(
        "{}: {n} queries, K within {:.3} LSB of the f64 polynomial on the stored coefficients",
        ctx.label, res.stats.max_abs_lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}
