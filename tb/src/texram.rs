//! The TEXRAM chip's integer reference: plain loops over a mipmap held level by level (no
//! banks), its own border folding and its own weight arithmetic (integer division, not
//! shifts), for bit-exact comparison with `units::texram` (the stub now, the cycle-accurate
//! chip later). Its definitions are the module documentation of `units::texram`.

/// A mipmap held as levels: `levels[k]` row-major, `max(W >> k, 1) x max(H >> k, 1)`.
#[derive(Clone, Debug)]
pub struct RefMipmap {
    pub width: u32,
    pub height: u32,
    pub levels: Vec<Vec<u8>>,
}

/// The border operation by name (the reference's own enumeration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefBorder {
    Wrap,
    Clamp,
    Mirror,
    Colour(u8),
}

impl RefMipmap {
    /// Level 0 and every level above it, each texel the rounded mean of the 2x2 (or the pair,
    /// once a side is 1) below it.
    pub fn build(width: u32, height: u32, level0: &[u8]) -> RefMipmap {
        let mut levels = vec![level0.to_vec()];
        let (mut w, mut h) = (width, height);
        while w > 1 || h > 1 {
            let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
            let prev = levels.last().expect("level 0");
            let mut next = vec![0u8; (nw * nh) as usize];
            for y in 0..nh {
                for x in 0..nw {
                    let xs: Vec<u32> = if w > 1 {
                        vec![2 * x, 2 * x + 1]
                    } else {
                        vec![x]
                    };
                    let ys: Vec<u32> = if h > 1 {
                        vec![2 * y, 2 * y + 1]
                    } else {
                        vec![y]
                    };
                    let mut sum = 0u32;
                    for yy in &ys {
                        for xx in &xs {
                            sum += u32::from(prev[(yy * w + xx) as usize]);
                        }
                    }
                    let n = (xs.len() * ys.len()) as u32;
                    next[(y * nw + x) as usize] = ((2 * sum + n) / (2 * n)) as u8;
                }
            }
            levels.push(next);
            (w, h) = (nw, nh);
        }
        RefMipmap {
            width,
            height,
            levels,
        }
    }

    fn last(&self) -> i64 {
        self.levels.len() as i64 - 1
    }

    fn texel(&self, k: usize, i: i64, j: i64, border: RefBorder) -> u8 {
        let w = i64::from((self.width >> k).max(1));
        let h = i64::from((self.height >> k).max(1));
        let fold = |t: i64, n: i64| -> Option<i64> {
            match border {
                RefBorder::Wrap => Some(t.rem_euclid(n)),
                RefBorder::Clamp => Some(t.max(0).min(n - 1)),
                RefBorder::Mirror => {
                    let m = t.rem_euclid(2 * n);
                    Some(if m < n { m } else { 2 * n - 1 - m })
                }
                RefBorder::Colour(_) => (t >= 0 && t < n).then_some(t),
            }
        };
        match (fold(i, w), fold(j, h)) {
            (Some(x), Some(y)) => self.levels[k][(y * w + x) as usize],
            _ => match border {
                RefBorder::Colour(c) => c,
                _ => unreachable!(),
            },
        }
    }

    /// The access at raw sQ12.8 `u`, `v` and sQ5.8 `lambda`: the eight texels and the result.
    pub fn access(&self, u: i32, v: i32, lambda: i32, border: RefBorder) -> ([u8; 8], u8) {
        self.access_mapped(u, v, lambda, border, &|t| t)
    }

    /// The same with each texel replaced by `map(texel)` before it is weighed (one component
    /// of a colour table, for the index configuration); the texels returned are unmapped.
    pub fn access_mapped(
        &self,
        u: i32,
        v: i32,
        lambda: i32,
        border: RefBorder,
        map: &dyn Fn(u8) -> u8,
    ) -> ([u8; 8], u8) {
        let (texels, sum) = self.weighed(u, v, lambda, border, map);
        (texels, ((sum + (1 << 23)) / (1 << 24)) as u8)
    }

    /// The access's exact weighted sum (the result times `2^24`, before its rounding).
    pub fn sum(&self, u: i32, v: i32, lambda: i32, border: RefBorder) -> i64 {
        self.weighed(u, v, lambda, border, &|t| t).1
    }

    fn weighed(
        &self,
        u: i32,
        v: i32,
        lambda: i32,
        border: RefBorder,
        map: &dyn Fn(u8) -> u8,
    ) -> ([u8; 8], i64) {
        let l = i64::from(lambda).div_euclid(256);
        let (fine, f) = if l < 0 {
            (0, 0)
        } else if l >= self.last() {
            (self.last(), 0)
        } else {
            (l, i64::from(lambda).rem_euclid(256))
        };
        let coarse = (fine + 1).min(self.last());
        let mut texels = [0u8; 8];
        let mut sum: i64 = 0;
        for (n, k) in [fine, coarse].into_iter().enumerate() {
            // c / 2^k - 1/2 in units of 2^-(8 + k): c - 128 * 2^k.
            let scale = 256i64 << k;
            let x = i64::from(u) - (128i64 << k);
            let y = i64::from(v) - (128i64 << k);
            let (i, j) = (x.div_euclid(scale), y.div_euclid(scale));
            let a = x.rem_euclid(scale) * 256 / scale;
            let b = y.rem_euclid(scale) * 256 / scale;
            let wl = if n == 0 { 256 - f } else { f };
            let corners = [
                (0, 0, (256 - a) * (256 - b)),
                (1, 0, a * (256 - b)),
                (0, 1, (256 - a) * b),
                (1, 1, a * b),
            ];
            for (t, (di, dj, w)) in corners.into_iter().enumerate() {
                let tex = self.texel(k as usize, i + di, j + dj, border);
                texels[4 * n + t] = tex;
                sum += i64::from(map(tex)) * w * wl;
            }
        }
        (texels, sum)
    }
}

// ---------------------------------------------------------------------------------------
// The testbench of the cycle-accurate chip.

use crate::runs::texram::figures;
use hdl::kernel::{Sim, Trace};
use proptest::prelude::*;
use units::texram::clut_814::Clut;
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::{Border, Config, Drf};
use verif::{
    run_scored, About, Coverage, Coverpoint, Ctx, Driver, Pacing, PinMonitor, RunSpec, Scoreboard,
    Scored, Stimulus, TbResult, Testbench,
};

/// The testbench's name: the chip's.
pub const NAME: &str = "texram_802";
/// The chip's clock (5 ns).
pub const CYCLE_PS: u64 = 5_000;

/// One request: raw sQ12.8 `u`, `v`, sQ5.8 `lambda`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexReq {
    pub u: i32,
    pub v: i32,
    pub lambda: i32,
}

/// One result.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexOut {
    pub value: u8,
    /// R, G, B, alpha (luminance: the value four times).
    pub rgba: [u8; 4],
    pub texels: [u8; 8],
    pub fault: bool,
}

/// Drives the request port with requests to DRF `drf`.
#[derive(Default)]
pub struct TexDriver {
    pub drf: u8,
}

impl Driver<Texram802> for TexDriver {
    type Txn = TexReq;
    fn drive(&mut self, dut: &mut Texram802, t: Option<&TexReq>) {
        dut.req_valid.set_bool(t.is_some());
        let t = t.copied().unwrap_or(TexReq {
            u: 0,
            v: 0,
            lambda: 0,
        });
        dut.req_drf.set_bits(u64::from(self.drf));
        dut.req_u.set_raw(i64::from(t.u));
        dut.req_v.set_raw(i64::from(t.v));
        dut.req_lambda.set_raw(i64::from(t.lambda));
    }
    fn accepted(&self, dut: &Texram802) -> bool {
        dut.req_ready.is_high()
    }
}

/// The output unit's result, in a cycle with `out_valid` high.
pub fn sample_tex(dut: &Texram802) -> Option<TexOut> {
    dut.output.out_valid.q().is_high().then(|| TexOut {
        value: dut.output.out_value.q().bits() as u8,
        rgba: (dut.output.out_rgba.q().bits() as u32).to_be_bytes(),
        texels: dut.output.out_texels.q().bits().to_le_bytes(),
        fault: dut.output.out_fault.q().is_high(),
    })
}

/// The configurations: map sizes (log2) and border operations.
const CONFIGS: [(u32, u32, Border, Config); 11] = [
    (6, 6, Border::Wrap, Config::Luminance),
    (6, 6, Border::Clamp, Config::Luminance),
    (6, 6, Border::Mirror, Config::Luminance),
    (6, 6, Border::Colour(77), Config::Luminance),
    (10, 10, Border::Wrap, Config::Luminance),
    (8, 5, Border::Mirror, Config::Luminance),
    (0, 5, Border::Clamp, Config::Luminance),
    (5, 0, Border::Colour(200), Config::Luminance),
    (6, 6, Border::Wrap, Config::Index),
    (6, 6, Border::Clamp, Config::Planar),
    (6, 6, Border::Mirror, Config::Literal),
];

fn config_class(c: Config) -> i64 {
    match c {
        Config::Luminance => 0,
        Config::Index => 1,
        Config::Planar => 2,
        Config::Literal => 3,
    }
}

/// The reference's border operation of a DRF's.
pub fn ref_border(b: Border) -> RefBorder {
    match b {
        // A tile border is the wrap at the map's edge; its fold inside the tile needs the
        // sample point and is checked by the map chain's testbench (`walker_812`).
        Border::Wrap | Border::Tile(_) => RefBorder::Wrap,
        Border::Clamp => RefBorder::Clamp,
        Border::Mirror => RefBorder::Mirror,
        Border::Colour(c) => RefBorder::Colour(c),
    }
}

/// The golden model's border operation of a DRF's (a tile border: the wrap at the map's
/// edge, see [`ref_border`]).
pub fn golden_border(b: Border) -> golden::texram::Border {
    match b {
        Border::Wrap | Border::Tile(_) => golden::texram::Border::Wrap,
        Border::Clamp => golden::texram::Border::Clamp,
        Border::Mirror => golden::texram::Border::Mirror,
        Border::Colour(c) => golden::texram::Border::Colour(f64::from(c)),
    }
}

/// A level 0 with structure at every scale: a ramp, a checker and seeded noise.
pub fn test_map(w: u32, h: u32, stim: &mut Stimulus) -> Vec<u8> {
    let noise = stim.draw_n(&(0u8..48), (w * h) as usize);
    (0..w * h)
        .map(|k| {
            let (x, y) = (k % w, k / w);
            let checker = if (x / 4 + y / 4) % 2 == 0 { 60 } else { 0 };
            ((x * 3 + y * 5) % 140 + checker + u32::from(noise[k as usize])).min(255) as u8
        })
        .collect()
}

/// Random requests over the map and two texels beyond it; lambda over -4..10 with integers
/// and the last level a quarter of the time.
fn requests(wl: u32, hl: u32, n: usize, stim: &mut Stimulus) -> Vec<TexReq> {
    let (w, h) = ((1i32 << wl) << 8, (1i32 << hl) << 8);
    let lmax = wl.max(hl) as i32;
    let lambda = prop_oneof![
        2 => -4 * 256..=10 * 256,
        1 => (-4..=10i32).prop_map(|l| l << 8),
        1 => Just(lmax << 8),
    ];
    let s =
        (-512..w + 512, -512..h + 512, lambda).prop_map(|(u, v, lambda)| TexReq { u, v, lambda });
    stim.draw_n(&s, n)
}

/// Requests every configuration gets before its random ones, so that its coverage does not
/// depend on the count: each lambda class and level range inside the map and beyond an edge,
/// and a repeat
/// (a page hit after the fault of the first access).
fn directed(wl: u32, hl: u32) -> Vec<TexReq> {
    let lmax = wl.max(hl) as i32;
    let mut v = Vec::new();
    for lambda in [-256, 256.min(lmax << 8), 128, 3 << 8, 7 << 8, lmax << 8] {
        for (u, v_) in [(384, 384), (-600, 200)] {
            v.push(TexReq { u, v: v_, lambda });
        }
    }
    v.push(v[0]);
    v
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let b = c.add(Coverpoint::new("border").values(&["wrap", "clamp", "mirror", "colour"]));
    let l =
        c.add(Coverpoint::new("lambda").values(&["negative", "integer", "fraction", "last_level"]));
    c.add(Coverpoint::new("position").values(&["inside", "beyond_an_edge"]));
    c.add(Coverpoint::new("page").values(&["hit", "fault"]));
    c.add(
        Coverpoint::new("level")
            .values(&["0", "1"])
            .bin("2..4", 2, 4)
            .bin("5..9", 5, 9)
            .value("10", 10),
    );
    c.add(Coverpoint::new("config").values(&["luminance", "index", "planar", "literal"]));
    c.cross("border_x_lambda", b, l);
    c
}

fn lambda_class(lambda: i32, lmax: u32) -> i64 {
    if lambda < 0 {
        0
    } else if lambda >> 8 >= lmax as i32 {
        3
    } else if lambda & 0xFF == 0 {
        1
    } else {
        2
    }
}

/// A border operation's coverage bin: wrap (and tile) 0, clamp 1, mirror 2, colour 3.
pub fn border_class(b: Border) -> i64 {
    match b {
        Border::Wrap | Border::Tile(_) => 0,
        Border::Clamp => 1,
        Border::Mirror => 2,
        Border::Colour(_) => 3,
    }
}

/// The testbench of the TEXRAM chip 802: per configuration (map size, border operation)
/// random requests with random input pacing, each scored against the integer reference
/// (value and texels, bit-exact), the stub (its page fault) and the f64 golden model (error
/// in LSBs, bound 0.5).
pub struct TexramTb;

/// What one request is expected to give: the reference's result, the stub's fault, golden.
type Expected = (TexReq, TexOut, f64);

impl Testbench for TexramTb {
    fn about(&self) -> About {
        About::new(NAME, "TEXRAM chip 802: units 810, 812, 818, 824 (Schilling & Knittel, Figure 8, sections 5-6)")
            .count(3000, "random transactions")
    }
    fn configurations(&self) -> Vec<String> {
        CONFIGS
            .iter()
            .map(|(w, h, b, c)| {
                let c = format!("{c:?}").to_lowercase();
                format!("{}x{} {} {c}", 1u32 << w, 1u32 << h, b.name())
            })
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn conclude(&self, merged: &mut TbResult) {
        let mut table = String::from(
            "| TEXRAM pixel rate (section 5) | pixels | slots | ns | M pixels/s | document |\n|---|---|---|---|---|---|\n",
        );
        for f in figures() {
            let doc = f.document.map_or("-".into(), |d| format!("{:.1}", d / 1e6));
            table.push_str(&format!(
                "| {} | {} | {} | {} | {:.2} | {doc} |\n",
                f.what,
                f.pixels,
                f.slots,
                f.cycles * CYCLE_PS / 1000,
                f.pixels_per_second / 1e6
            ));
            merged.notes.push(format!(
                "{}: {:.2} M pixels/s ({} slots for {} pixels)",
                f.what,
                f.pixels_per_second / 1e6,
                f.slots,
                f.pixels
            ));
            if let Some(d) = f.document {
                if (f.pixels_per_second / d - 1.0).abs() > 0.01 {
                    merged.failures.push(format!(
                        "{}: {:.2} M pixels/s, the document {:.2} M",
                        f.what,
                        f.pixels_per_second / 1e6,
                        d / 1e6
                    ));
                }
            }
        }
        merged.tables.push(table);
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (wl, hl, border, config) = CONFIGS[ctx.index];
        let mut stim = Stimulus::new(ctx.seed);
        let level0 = test_map(1 << wl, 1 << hl, &mut stim);
        let mut drf = Drf::new(wl, hl, border);
        drf.config = config;
        let entries: Vec<u32> = stim.draw_n(&any::<u32>(), 256);
        let clut = Clut {
            entries: entries.try_into().expect("256 entries"),
        };
        let mut chip = Texram802::new(TexramParams::default())?;
        chip.set_drf(0, drf)?;
        chip.load(0, &level0)?;
        chip.set_clut(clut.clone());
        let title = format!("texram_802 {}", ctx.label);
        let (sim, _) = ctx.sim(chip, &title, CYCLE_PS, |_| ())?;
        let (sim, mut res) = one_config(sim, ctx, (drf, &clut), &level0, &mut stim)?;
        ctx.finish(sim, &mut res)?;
        Ok(res)
    }
}

/// What each request should give: the integer reference's texels and value, the stub's
/// page fault, the golden model's value.
struct Oracles<'a> {
    reference: &'a RefMipmap,
    stub: units::texram::stub::TexramStub,
    golden: golden::texram::Mipmap<'a>,
    border: Border,
    lmax: u32,
    config: Config,
}

impl Oracles<'_> {
    /// The stub's access for `q` (to DRF 0).
    fn stub_access(&mut self, q: &TexReq) -> units::texram::TexramReply {
        use units::texram::{TexramAccess, TexramRequest};
        let (u, v, lambda) = (q.u, q.v, q.lambda);
        let req = TexramRequest {
            drf: 0,
            u,
            v,
            lambda,
        };
        self.stub.access(req).expect("requests are in range")
    }

    /// The expectation of a colour or index request: the stub's colour (the reference and
    /// golden are per component maps, held against the stub in `tb/tests/texram.rs`).
    fn expect_colour(&mut self, q: &TexReq) -> Expected {
        let r = self.stub_access(q);
        (
            *q,
            TexOut {
                value: r.value,
                rgba: r.rgba,
                texels: r.texels,
                fault: r.slots > 1,
            },
            f64::NAN,
        )
    }

    fn expect(&mut self, q: &TexReq) -> Expected {
        if self.config != Config::Luminance {
            return self.expect_colour(q);
        }
        let (texels, value) = self
            .reference
            .access(q.u, q.v, q.lambda, ref_border(self.border));
        let s = self.stub_access(q);
        let f = |x: i32| f64::from(x) / 256.0;
        let lmax = self.lmax as usize;
        let wts = golden::texram::Weights::truncated(f(q.u), f(q.v), f(q.lambda), lmax);
        let want = golden::texram::trilinear(&self.golden, &wts);
        (
            *q,
            TexOut {
                value,
                rgba: [value; 4],
                texels,
                fault: s.slots == 2,
            },
            want,
        )
    }
}

/// Runs one configuration's requests through the chip and scores them.
fn one_config<T: Trace>(
    mut sim: Sim<Texram802, T>,
    ctx: &Ctx,
    (drf, clut): (Drf, &Clut),
    level0: &[u8],
    stim: &mut Stimulus,
) -> Result<(Sim<Texram802, T>, TbResult), String> {
    use units::texram::TexramAccess;
    let (wl, hl, border, config) = (drf.width_log2, drf.height_log2, drf.border, drf.config);
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let reference = RefMipmap::build(1 << wl, 1 << hl, level0);
    let mut stub = units::texram::stub::TexramStub::new();
    stub.set_drf(0, drf)?;
    stub.load(0, level0)?;
    stub.set_clut(clut.clone());
    let golden = golden::texram::Mipmap {
        width: 1 << wl,
        height: 1 << hl,
        levels: &reference.levels,
        border: golden_border(border),
    };
    let lmax = wl.max(hl);
    let mut oracles = Oracles {
        reference: &reference,
        stub,
        golden,
        border,
        lmax,
        config,
    };
    let mut reqs = directed(wl, hl);
    reqs.extend(requests(wl, hl, ctx.count, stim));
    let n = reqs.len() as u64;
    // Luminance: every field; colour: the colour (its texels are of the last component).
    let whole = config == Config::Luminance;
    let mut sb: Scoreboard<Expected, TexOut> =
        Scoreboard::new(move |(_, e, _): &Expected, a: &TexOut| {
            if (whole && e == a) || (!whole && e.rgba == a.rgba) {
                Ok(())
            } else {
                Err(format!("got {a:?}, want {e:?}"))
            }
        });
    let pacing = Pacing::random(200, stim.seed().derive(7));
    // Up to four components of four rounds of two slots each, a request.
    let mut spec = RunSpec::new(n, 200 * n + 100).pacing(pacing);
    let (w, h) = ((1i32 << wl) << 8, (1i32 << hl) << 8);
    let r = run_scored(
        &mut sim,
        &mut TexDriver::default(),
        &mut PinMonitor::new(sample_tex),
        reqs,
        &mut spec,
        |_, ev| match ev {
            Scored::Sent { txn, .. } => sb.expect(oracles.expect(txn)),
            Scored::Received { cycle, txn } => {
                if let Some((q, _, want)) = sb.observe(cycle, txn).expected {
                    if want.is_finite() {
                        res.stats.record(f64::from(txn.value), want, 1.0);
                    }
                    let beyond = q.u < 0 || q.v < 0 || q.u >= w || q.v >= h;
                    let (b, l) = (border_class(border), lambda_class(q.lambda, lmax));
                    let c = config_class(config);
                    let level = i64::from((q.lambda >> 8).clamp(0, lmax as i32));
                    let f = i64::from(txn.fault);
                    cov.sample(&[b, l, i64::from(beyond), f, level, c]);
                }
            }
        },
    );
    res.score(&sb);
    res.ran(&r);
    settle_config(
        &mut res,
        sim.dut.slots.q().bits(),
        &oracles.stub,
        &ctx.label,
    );
    res.coverage = Some(cov);
    Ok((sim, res))
}

/// The configuration's slot count against the stub's, its note, the error bound.
fn settle_config(
    res: &mut TbResult,
    slots: u64,
    stub: &units::texram::stub::TexramStub,
    label: &str,
) {
    use units::texram::TexramAccess;
    if slots != stub.slots() {
        res.failures
            .push(format!("{slots} slots, the stub took {}", stub.slots()));
    }
    let (accesses, faults) = stub.counts();
    res.notes.push(format!(
        "{label}: {accesses} accesses in {slots} slots, {faults} bank faults"
    ));
    if res.stats.max_abs_lsb > golden::texram::ERROR_BOUND_LSB {
        res.failures.push(format!(
            "error {:.4} LSB against golden, bound {}",
            res.stats.max_abs_lsb,
            golden::texram::ERROR_BOUND_LSB
        ));
    }
}
