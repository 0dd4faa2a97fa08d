//! The per-pixel frame unit (bump and normal maps, 003 and 002) and the parallax unit (002):
//! their testbenches against `golden::tangents`, within bounds derived from normal unit
//! 156's inverse square root and the reciprocal's error.

use golden::tangents::{cross, normalize, perturb};
use hdl::kernel::Sim;
use units::frames::frame_unit::{decode_rgb8, Decode, FrameUnit, VEC_FRAC, W_FRAC};
use units::frames::parallax::ParallaxUnit;
use verif::{
    About, Coverage, Coverpoint, Ctx, PinDriver, PinMonitor, RunSpec, Scoreboard, Stimulus,
    TbResult, Testbench,
};
use waves::VcdTracer;

pub const FRAME: &str = "frame_unit";
pub const PARALLAX: &str = "parallax";

/// A pixel for the frame unit: frame (T, B, N raw sQ1.14), weights (a, gx, gy raw sQ3.12),
/// Gram-Schmidt, and the coverage class of the weights (0 bump, 1 offset decode, 2
/// symmetric decode).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FramePx {
    pub frame: [[i64; 3]; 3],
    pub w: [i64; 3],
    pub gs: bool,
    pub kind: i64,
}

impl FramePx {
    /// Whether B is against N x T (a left-handed frame, as where UVs are mirrored).
    pub fn left_handed(&self) -> bool {
        let [t, b, n] = self.frame.map(|v| v.map(|x| x as f64));
        golden::tangents::handedness(n, t, b) < 0.0
    }
}

/// The component error of one normalisation by 156's rsqrt, rounded to sQ1.14.
fn unit_error() -> f64 {
    let r = units::bump::params::RsqrtParams::default();
    golden::rsqrt::error_bound_ulps(r.table_bits, r.iterations, r.y_frac)
        * 2f64.powi(-(r.y_frac as i32))
        + 2f64.powi(-(VEC_FRAC as i32 + 1))
}

/// The f64 normal and the bound on each component: one normalisation's error, and with
/// Gram-Schmidt the errors of the unit's own N, t and b carried through `a N + gx t + gy b`
/// over its length.
pub fn golden_frame(p: &FramePx) -> Option<([f64; 3], f64)> {
    let q = |x: i64, f: u32| x as f64 * 2f64.powi(-(f as i32));
    let frame = p.frame.map(|v| v.map(|x| q(x, VEC_FRAC)));
    let w = p.w.map(|x| q(x, W_FRAC));
    let n = perturb(frame, w, p.gs)?;
    let e = unit_error();
    if !p.gs {
        return Some((n, e));
    }
    let [t, b, nn] = frame;
    let nu = normalize(nn).0;
    let along: f64 = (0..3).map(|c| nu[c] * t[c]).sum();
    let perp = (0..3)
        .map(|c| (t[c] - along * nu[c]).powi(2))
        .sum::<f64>()
        .sqrt();
    let s3 = 3f64.sqrt();
    let dn = s3 * e;
    let dt = s3 * e + 2.0 * dn * (t.iter().map(|x| x * x).sum::<f64>()).sqrt() / perp.max(1e-9);
    let db = 2f64.sqrt() * (dn + dt) + s3 * 2f64.powi(-15);
    let v = perturb(frame, w, true).map(|_| {
        let f = golden::tangents::orthonormal(nu, t, b);
        (0..3)
            .map(|c| (w[0] * nu[c] + w[1] * f.t[c] + w[2] * f.b[c]).powi(2))
            .sum::<f64>()
            .sqrt()
    })?;
    let spread = (w[0].abs() * dn + w[1].abs() * dt + w[2].abs() * db) / v.max(1e-9);
    Some((n, e + 2.0 * spread))
}

/// Random frames near orthonormal (lengths 0.8 to 1.2, a little skew), weights of a bump
/// (a = 1, slopes within 2) or a normal-map texel (either decode), Gram-Schmidt half the time,
/// left-handed (B = T x N, as where a mesh's UVs are mirrored) every other pair.
pub fn frame_pixels(n: usize, stim: &mut Stimulus) -> Vec<FramePx> {
    (0..n)
        .map(|i| {
            let mut dir = || [0, 1, 2].map(|_| f64::from(stim.draw(&(-1000i32..=1000))));
            let (a, b0) = (normalize(dir()).0, dir());
            let t = normalize(cross(a, b0)).0;
            let left = i % 4 >= 2;
            let b = if left { cross(t, a) } else { cross(a, t) };
            let len = f64::from(stim.draw(&(80i32..=120))) / 100.0;
            let skew = f64::from(stim.draw(&(-10i32..=10))) / 100.0;
            let q = |v: [f64; 3], s: f64| v.map(|c| (c * s * 16384.0).round() as i64);
            let frame = [
                q(
                    golden::tangents::add(t, golden::tangents::scale(a, skew)),
                    len,
                ),
                q(b, 1.0),
                q(a, len),
            ];
            let kind = (i % 3) as i64;
            let w = match kind {
                0 => [
                    1 << W_FRAC,
                    stim.draw(&(-8192i64..=8192)),
                    stim.draw(&(-8192i64..=8192)),
                ],
                k => {
                    let rgb = [
                        stim.draw(&(0u8..=255)),
                        stim.draw(&(0u8..=255)),
                        stim.draw(&(100u8..=255)),
                    ];
                    decode_rgb8(
                        rgb,
                        if k == 1 {
                            Decode::Offset
                        } else {
                            Decode::Symmetric
                        },
                    )
                }
            };
            FramePx {
                frame,
                w,
                gs: i % 2 == 1,
                kind,
            }
        })
        .collect()
}

fn drive_frame(dut: &mut FrameUnit, t: Option<&FramePx>) {
    dut.valid_in.set_bool(t.is_some());
    if let Some(p) = t {
        dut.gram_schmidt.set_bool(p.gs);
        for r in 0..3 {
            for c in 0..3 {
                dut.frame[r][c].set_raw(p.frame[r][c]);
            }
            dut.w[r].set_raw(p.w[r]);
        }
    }
}

fn sample_normal(d: &FrameUnit) -> Option<([i64; 3], bool)> {
    d.valid
        .q()
        .is_high()
        .then(|| (d.nout.each_ref().map(|r| r.q().raw()), d.zero.q().is_high()))
}

fn frame_coverage() -> Coverage {
    let mut c = Coverage::new();
    let k = c.add(Coverpoint::new("weights").values(&[
        "bump",
        "normal map c-128",
        "normal map 2c-255",
    ]));
    let g = c.add(Coverpoint::new("gram_schmidt").values(&["off", "on"]));
    c.cross("weights_x_gram_schmidt", k, g);
    let h = c.add(Coverpoint::new("handedness").values(&["right", "left"]));
    c.cross("handedness_x_gram_schmidt", h, g);
    c
}

fn check_frame(p: &FramePx, a: &([i64; 3], bool)) -> Result<(), String> {
    let Some((n, bound)) = golden_frame(p) else {
        return if a.1 {
            Ok(())
        } else {
            Err("a zero normal not flagged".into())
        };
    };
    if a.1 {
        return Err(format!("n {:?} flagged zero; golden {n:?}", a.0));
    }
    let lsb = 2f64.powi(-(VEC_FRAC as i32));
    verif::within(&a.0.map(|x| x as f64 * lsb), &n, bound)
}

/// The frame unit's regress testbench.
pub struct FrameUnitTb;

impl Testbench for FrameUnitTb {
    fn about(&self) -> About {
        About::new(FRAME, "per-pixel frame unit: optional Gram-Schmidt, n' = a N + gx T + gy B through 156's rsqrt; bump slopes and RGB8 normal-map texels (003, 002)")
            .count(3000, "pixels")
    }
    fn coverage(&self) -> Coverage {
        frame_coverage()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let mut stim = Stimulus::new(ctx.seed);
        let px = frame_pixels(ctx.count.max(12), &mut stim);
        let (sim, _) = ctx.sim(
            FrameUnit::new(),
            &format!("{FRAME} {}", ctx.label),
            10_000,
            |_| (),
        )?;
        run_frames(sim, ctx, px)
    }
}

fn run_frames(
    mut sim: Sim<FrameUnit, VcdTracer>,
    ctx: &Ctx,
    px: Vec<FramePx>,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(FRAME, "");
    let mut cov = frame_coverage();
    sim.reset(2);
    let mut sb: Scoreboard<FramePx, ([i64; 3], bool)> = Scoreboard::new(check_frame);
    let n = px.len() as u64;
    let mut spec =
        RunSpec::new(n, 3 * n + 50).pacing(verif::Pacing::random(200, ctx.seed.derive(6)));
    let lsb = 2f64.powi(-(VEC_FRAC as i32));
    let r = sb.run(
        &mut sim,
        &mut PinDriver::new(drive_frame),
        &mut PinMonitor::new(sample_normal),
        px.into_iter().map(|q| (q, q)),
        &mut spec,
        |_, p, txn| {
            if let Some((g, _)) = golden_frame(&p) {
                for (x, gc) in txn.0.iter().zip(g) {
                    res.stats.record(*x as f64 * lsb, gc, lsb);
                }
            }
            cov.sample(&[p.kind, i64::from(p.gs), i64::from(p.left_handed())]);
        },
    );
    res.score(&sb);
    res.ran(&r);
    res.notes.push(format!(
        "{}: {n} pixels, normals within {:.2} LSB of f64 (unit error {:.2} LSB, wider with Gram-Schmidt)",
        ctx.label,
        res.stats.max_abs_lsb,
        unit_error() / lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}

/// A parallax query: uv (sQ12.8), height (u8), scale and bias (sQ3.12), eye (sQ1.14),
/// limited.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParallaxQ {
    pub uv: [i64; 2],
    pub height: u8,
    pub scale: i64,
    pub bias: i64,
    pub eye: [i64; 3],
    pub limited: bool,
}

/// The f64 coordinate and its bound (texels): half an LSB of sQ12.8, plus the reciprocal's
/// 5 x 2^-16 of the full offset.
pub fn golden_parallax(q: &ParallaxQ) -> ([f64; 2], f64) {
    let h = f64::from(q.height) / 256.0 * q.scale as f64 / 4096.0 + q.bias as f64 / 4096.0;
    let eye = q.eye.map(|c| c as f64 / 16384.0);
    let uv = q.uv.map(|c| c as f64 / 256.0);
    // The unit holds the coordinate at its format's ends (sQ13.8: -4096 ..= 4096 - 2^-8).
    let g = golden::tangents::parallax(uv, h, eye, q.limited)
        .map(|x| x.clamp(-4096.0, 4096.0 - 1.0 / 256.0));
    let full = if q.limited {
        0.0
    } else {
        (h * eye[0].abs().max(eye[1].abs()) / eye[2].max(0.125)).abs()
    };
    (g, 0.5 / 256.0 + full * 5.0 * 2f64.powi(-16) + 1e-12)
}

/// Random queries: uv within 1000 texels, any height, scale within 2 and bias within 1
/// texel, eyes above the surface (a fifth of them grazing, V.z under 1/8), half limited.
pub fn parallax_queries(n: usize, stim: &mut Stimulus) -> Vec<ParallaxQ> {
    (0..n)
        .map(|i| {
            let low = i % 5 == 0;
            let z = if low {
                stim.draw(&(1i32..200))
            } else {
                stim.draw(&(200i32..=1000))
            };
            let d = [
                stim.draw(&(-1000i32..=1000)),
                stim.draw(&(-1000i32..=1000)),
                z,
            ]
            .map(f64::from);
            let e = normalize(d).0.map(|c| (c * 16383.0).round() as i64);
            ParallaxQ {
                uv: [0, 1].map(|_| stim.draw(&(-256_000i64..256_000))),
                height: stim.draw(&(0u8..=255)),
                scale: stim.draw(&(-8192i64..8192)),
                bias: stim.draw(&(-4096i64..=4096)),
                eye: e,
                limited: i % 2 == 1,
            }
        })
        .collect()
}

/// Directed queries for what the random ones never reach (they keep uv within 1000 texels
/// and the offset within 25, so the coordinate never comes near the format's ends, and a
/// rounding tie is a 2^-26 chance): each coordinate pushed past either end, in both forms,
/// and offsets of exactly half an LSB (h = 2^-8, V.x = V.y = 1/2: 2^-9) on either side of 0.
pub fn parallax_edges() -> Vec<ParallaxQ> {
    let edge = 4095 * 256 + 128; // 4095.5 texels
    let half = 1 << 13; // 0.5 in sQ1.14
    let mut qs = Vec::new();
    for limited in [false, true] {
        for sign in [1i64, -1] {
            // h = 255/256 x 2 + 1 (about 3 texels), moved by 0.5 (limited) or 1 (divided)
            // texel per texel of height, outward: u past one end, v past the other.
            let eye = [half * sign, -half * sign, half];
            qs.push(ParallaxQ {
                uv: [edge * sign, -edge * sign],
                height: 255,
                scale: 8191,
                bias: 4096,
                eye,
                limited,
            });
        }
        for uv in [[0, 0], [256, -256]] {
            qs.push(ParallaxQ {
                uv,
                height: 0,
                scale: 0,
                bias: 16, // h = 16 2^-12 = 2^-8 texels
                eye: [1 << 13, -(1 << 13), 1 << 14],
                limited,
            });
        }
    }
    qs
}

/// Drives one query onto the unit's inputs (`None`: no query this cycle).
pub fn drive_parallax(d: &mut ParallaxUnit, t: Option<&ParallaxQ>) {
    d.valid_in.set_bool(t.is_some());
    if let Some(q) = t {
        d.limited.set_bool(q.limited);
        d.uv[0].set_raw(q.uv[0]);
        d.uv[1].set_raw(q.uv[1]);
        d.height.set_bits(u64::from(q.height));
        d.scale.set_raw(q.scale);
        d.bias.set_raw(q.bias);
        for c in 0..3 {
            d.eye[c].set_raw(q.eye[c]);
        }
    }
}

fn sample_uv(d: &ParallaxUnit) -> Option<[i64; 2]> {
    d.valid
        .q()
        .is_high()
        .then(|| d.out.each_ref().map(|r| r.q().raw()))
}

fn parallax_coverage() -> Coverage {
    let mut c = Coverage::new();
    let f = c.add(Coverpoint::new("form").values(&["divided", "limited"]));
    let z = c.add(Coverpoint::new("vz").values(&["held at 1/8", "above"]));
    c.cross("form_x_vz", f, z);
    c
}

/// The parallax unit's regress testbench.
pub struct ParallaxTb;

impl Testbench for ParallaxTb {
    fn about(&self) -> About {
        About::new(PARALLAX, "parallax offset uv + h V.xy / V.z (reciprocal by table + Newton) and the offset-limited uv + h V.xy (002's reading list)")
            .count(3000, "queries")
    }
    fn coverage(&self) -> Coverage {
        parallax_coverage()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let mut stim = Stimulus::new(ctx.seed);
        let mut qs = parallax_queries(ctx.count.max(20), &mut stim);
        qs.extend(parallax_edges());
        let title = format!("{PARALLAX} {}", ctx.label);
        let (mut sim, _) = ctx.sim(ParallaxUnit::new(), &title, 10_000, |_| ())?;
        sim.reset(2);
        let mut res = TbResult::new(PARALLAX, "");
        let mut cov = parallax_coverage();
        let mut sb: Scoreboard<ParallaxQ, [i64; 2]> =
            Scoreboard::new(|q: &ParallaxQ, a: &[i64; 2]| {
                let (g, bound) = golden_parallax(q);
                verif::within(&a.map(|x| x as f64 / 256.0), &g, bound)
            });
        let n = qs.len() as u64;
        let mut spec =
            RunSpec::new(n, 3 * n + 50).pacing(verif::Pacing::random(200, ctx.seed.derive(7)));
        let r = sb.run(
            &mut sim,
            &mut PinDriver::new(drive_parallax),
            &mut PinMonitor::new(sample_uv),
            qs.into_iter().map(|q| (q, q)),
            &mut spec,
            |_, q, txn| {
                let (g, _) = golden_parallax(&q);
                for c in 0..2 {
                    res.stats.record(txn[c] as f64 / 256.0, g[c], 1.0 / 256.0);
                }
                cov.sample(&[
                    i64::from(q.limited),
                    i64::from(q.eye[2] >= units::frames::parallax::VZ_MIN),
                ]);
            },
        );
        res.score(&sb);
        res.ran(&r);
        res.notes.push(format!(
            "{}: {n} queries, within {:.3} LSB of f64",
            ctx.label, res.stats.max_abs_lsb
        ));
        res.coverage = Some(cov);
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}
