//! The texture memory path testbench (Schilling & Knittel, Figure 6): texture unit 602 with
//! DRAM 604, control unit 607, CCC decode, cache 614 and bilinear 622, on scanline traces:
//! the `texture` testbench of `texrtl regress`, over the run of `texrtl texread`
//! ([`crate::runs::texture`]).
//!
//! Every result is compared with the integer reference ([`reference_filter`]) and
//! with the `f64` golden model of the decoded texture (bound [`golden::texture::ERROR_BOUND_LSB`]);
//! the golden model of the original (uncompressed) texture measures the compression error,
//! reported separately. Misses are split into cold, capacity and conflict misses by a
//! fully-associative LRU shadow cache ([`crate::runs::texture::Shadow`]) of the same four
//! blocks, fed the same block references (Hakura and Gupta's method).

use crate::runs::texture::{run_texread_checked, TexReadStats, TexRequest, TexRun};
use formats::ccc::Ccc;
use formats::netpbm::Ppm;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use units::texmem::cache_614::Lookahead;
use units::texmem::layout::Layout;
use units::texmem::texture_unit_602::TexParams;
use verif::{About, Coverage, Coverpoint, Ctx, Seed, TbResult, Testbench};
use waves::TraceConfig;

/// Integer reference of unit 622 on the reference decode: clamp-to-edge footprint of raw
/// `uQ12.F` position `(u, v)`, the four-weight sum per channel, round half up. (The hardware
/// does two lerps; the sum is the same exact integer.)
pub fn reference_filter(t: &Ccc, u: u32, v: u32, frac_bits: u32) -> u32 {
    let f = frac_bits;
    let sums = reference_sums(t, u, v, f);
    let mut out = 0;
    for (s, shift) in sums.into_iter().zip([16, 8, 0]) {
        out |= (((s + (1 << (2 * f - 1))) >> (2 * f)) as u32) << shift;
    }
    out
}

/// The reference's exact four-weight sums of R, G, B (each the channel times `2^2F`).
pub fn reference_sums(t: &Ccc, u: u32, v: u32, frac_bits: u32) -> [u64; 3] {
    let f = frac_bits;
    let one = 1u64 << f;
    let (x0, y0) = (u >> f, v >> f);
    let (fu, fv) = (u64::from(u) & (one - 1), u64::from(v) & (one - 1));
    let x1 = (x0 + 1).min(t.width - 1);
    let y1 = (y0 + 1).min(t.height - 1);
    let tex = [
        t.texel(x0, y0),
        t.texel(x1, y0),
        t.texel(x0, y1),
        t.texel(x1, y1),
    ];
    let w = [
        (one - fu) * (one - fv),
        fu * (one - fv),
        (one - fu) * fv,
        fu * fv,
    ];
    [16, 8, 0].map(|shift| {
        (0..4)
            .map(|k| w[k] * u64::from(tex[k] >> shift & 0xff))
            .sum()
    })
}

/// A CCC texture for tests of any size (multiples of 4): a grey-ramp CLUT, block `i` with
/// colours `i` and `255 - i` (mod 256) and a checker of decision bits, so neighbouring blocks
/// and texels differ.
pub fn test_pattern(w: u32, h: u32) -> Ccc {
    Ccc {
        width: w,
        height: h,
        clut: (0..256).map(|i| i * 0x010101).collect(),
        blocks: (0..(w / 4) * (h / 4))
            .map(|i| units::texmem::ccc_decode_608::CccBlock {
                a: i as u8,
                b: 255 - i as u8,
                bits: 0x5a5a,
            })
            .collect(),
    }
}

/// Scanline traces of the hit-rate table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceKind {
    /// Horizontal scanlines of 32 pixels, 0.75 texel per pixel.
    Horizontal,
    /// The same texture rotated by 30 degrees.
    Diagonal,
    /// Uniformly random positions, a `newline` every 32 requests.
    Random,
    /// Horizontal scanlines of 8 pixels (the document's pessimistic example), 2.5 texels
    /// apart in v.
    Short,
    /// Scanlines of 32 pixels drawn right to left (the texture mirrored).
    Leftward,
    /// Scanlines of 32 pixels drawn bottom to top (the texture rotated by 90 degrees).
    Upward,
}

impl TraceKind {
    pub const ALL: [TraceKind; 6] = [
        TraceKind::Horizontal,
        TraceKind::Diagonal,
        TraceKind::Random,
        TraceKind::Short,
        TraceKind::Leftward,
        TraceKind::Upward,
    ];
    pub fn name(self) -> &'static str {
        match self {
            TraceKind::Horizontal => "horizontal",
            TraceKind::Diagonal => "diagonal",
            TraceKind::Random => "random",
            TraceKind::Short => "short (8 px)",
            TraceKind::Leftward => "leftward",
            TraceKind::Upward => "upward",
        }
    }
}

/// About `n` requests of `kind` on a `w x h` texture, coordinates rounded to `uQ12.F`.
pub fn trace(
    kind: TraceKind,
    w: u32,
    h: u32,
    frac_bits: u32,
    n: usize,
    seed: Seed,
) -> Vec<TexRequest> {
    let one = f64::from(1u32 << frac_bits);
    let q = |x: f64, size: u32| {
        let max = f64::from((size << frac_bits) - 1);
        (x * one).round().clamp(0.0, max) as u32
    };
    let mut out = Vec::with_capacity(n);
    match kind {
        TraceKind::Random => {
            let mut st = verif::Stimulus::new(seed);
            let us = st.draw_n(&(0..w << frac_bits), n);
            let vs = st.draw_n(&(0..h << frac_bits), n);
            for (i, (u, v)) in us.into_iter().zip(vs).enumerate() {
                out.push(TexRequest {
                    u,
                    v,
                    newline: i % 32 == 0,
                });
            }
        }
        _ => {
            let (len, s, dv, angle) = match kind {
                TraceKind::Short => (8, 0.75, 2.5, 0.0f64),
                TraceKind::Diagonal => (32, 0.75, 0.75, 30f64.to_radians()),
                TraceKind::Leftward => (32, 0.75, 0.75, 180f64.to_radians()),
                TraceKind::Upward => (32, 0.75, 0.75, -90f64.to_radians()),
                _ => (32, 0.75, 0.75, 0.0),
            };
            // Pixel `i` of scanline `j` is at `s i` along the scanline's direction and `dv j`
            // across it, both in texels; the direction is `angle` from the u axis. A rotated
            // trace starts mid-texture, as the scanlines step left as they go down. Positions
            // wrap around the texture when there are many scanlines.
            let (c, sn) = (angle.cos(), angle.sin());
            let (w_f, h_f) = (f64::from(w), f64::from(h));
            let u0 = if angle == 0.0 { 2.37 } else { w_f / 2.0 + 0.37 };
            let mut j = 0.0;
            while out.len() < n {
                for i in 0..len {
                    let along = s * i as f64;
                    let u = u0 + along * c - j * dv * sn;
                    let v = 1.61 + along * sn + j * dv * c;
                    out.push(TexRequest {
                        u: q(u.rem_euclid(w_f - 1.0), w),
                        v: q(v.rem_euclid(h_f - 1.0), h),
                        newline: i == 0,
                    });
                }
                j += 1.0;
            }
            out.truncate(n);
        }
    }
    out
}

/// A synthetic RGB test texture: smooth gradients, coloured discs and hashed noise, so that
/// blocks with one, two and many colours all occur.
pub fn synthetic_texture(w: u32, h: u32, seed: Seed) -> Ppm {
    let mut pixels = Vec::with_capacity((w * h * 3) as usize);
    let salt = seed.0;
    for y in 0..h {
        for x in 0..w {
            let hash = ((u64::from(x) * 0x9e37_79b9) ^ (u64::from(y) * 0x85eb_ca6b) ^ salt)
                .wrapping_mul(0xc2b2_ae35)
                >> 40;
            let noise = (hash % 24) as i32 - 12;
            let fx = f64::from(x) / f64::from(w);
            let fy = f64::from(y) / f64::from(h);
            let mut c = [
                (255.0 * fx) as i32,
                (255.0 * fy) as i32,
                (128.0 + 100.0 * (6.0 * fx + 4.0 * fy).sin()) as i32,
            ];
            let (dx, dy) = (fx - 0.6, fy - 0.4);
            if dx * dx + dy * dy < 0.04 {
                c = [230, 40, 60];
            }
            if (x / 8 + y / 8) % 5 == 0 {
                c = c.map(|v| v + noise);
            }
            pixels.extend(c.map(|v| v.clamp(0, 255) as u8));
        }
    }
    Ppm {
        width: w,
        height: h,
        maxval: 255,
        pixels,
    }
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let blocks = c.add(
        Coverpoint::new("footprint_blocks")
            .value("one", 1)
            .value("two", 2)
            .value("four", 4),
    );
    c.add(Coverpoint::new("first_lookup").values(&["all_miss", "partial", "all_hit"]));
    let any = c.add(Coverpoint::new("missed").values(&["no", "yes"]));
    c.add(Coverpoint::new("mode").values(&[
        "cache_quadrant",
        "cache_only",
        "no_cache",
        "cache_direction",
    ]));
    c.add(Coverpoint::new("layout").values(&["row_major", "tiled"]));
    c.add(Coverpoint::new("edge").values(&["inside", "clamped"]));
    c.cross("blocks_x_missed", blocks, any);
    c
}

/// What a testbench run's configurations add to: its result, coverage and compression error
/// (the hardware against the golden model of the original texture), over the fixture.
struct Checks {
    res: TbResult,
    cov: Coverage,
    compression: verif::ErrorStats,
    check_schedule: bool,
    orig: &'static Ppm,
    tex: &'static Ccc,
}

impl Checks {
    fn new(ctx: &Ctx) -> Result<Checks, String> {
        let (orig, tex) = fixture()?;
        Ok(Checks {
            res: TbResult::new(NAME, TextureTb.unit()),
            cov: coverage_model(),
            compression: verif::ErrorStats::new(),
            check_schedule: ctx.check_schedule,
            orig,
            tex,
        })
    }

    /// One configuration: every result against the integer reference and the golden model,
    /// the unit's counters against each other, coverage sampled; returns the run.
    fn run(
        &mut self,
        p: TexParams,
        reqs: &[TexRequest],
        interval: u32,
        vcd: Option<(PathBuf, TraceConfig)>,
    ) -> Result<TexRun, String> {
        let run = run_texread_checked(self.tex, p, reqs, interval, vcd, self.check_schedule)?;
        let mode = match (p.cache, p.lookahead) {
            (false, _) => 2,
            (true, Lookahead::Quadrant) => 0,
            (true, Lookahead::Off) => 1,
            (true, Lookahead::Direction) => 3,
        };
        let tag = format!(
            "{} {} interval {interval}",
            p.layout.name(),
            ["cache+quadrant", "cache", "no cache", "cache+direction"][mode]
        );
        self.res.cycles += run.stats.cycles;
        if !run.findings.is_empty() {
            // A hang or a broken handshake: the results and counts stop there; that is the finding.
            let failures = run.findings.iter().map(|f| format!("{tag}: {f}"));
            self.res.failures.extend(failures);
            return Ok(run);
        }
        for (i, r) in reqs.iter().enumerate() {
            self.request(&p, r, run.rgb[i], &tag, i);
            let edge = (r.u >> p.frac_bits) + 1 >= p.width || (r.v >> p.frac_bits) + 1 >= p.height;
            let (nb, hits) = run.lookups[i];
            let outcome = if hits == nb { 2 } else { i64::from(hits > 0) };
            let tiled = i64::from(p.layout == Layout::Tiled);
            let bins = [
                nb.into(),
                outcome,
                (hits < nb).into(),
                mode as i64,
                tiled,
                edge.into(),
            ];
            self.cov.sample(&bins);
        }
        if self.res.stats.max_abs_lsb > golden::texture::ERROR_BOUND_LSB {
            self.res.failures.push(format!(
                "{tag}: error {:.3} LSB against the golden model of the decoded texture, bound 0.5",
                self.res.stats.max_abs_lsb
            ));
        }
        let counts = count_failures(&run.stats, p.cache, reqs.len() as u64);
        (self.res.failures).extend(counts.into_iter().map(|f| format!("{tag}: {f}")));
        Ok(run)
    }

    /// Request `i`'s result `got` against the integer reference (bit for bit), the golden
    /// model of the decoded texture and that of the original.
    fn request(&mut self, p: &TexParams, r: &TexRequest, got: u32, tag: &str, i: usize) {
        let (tex, orig, res) = (self.tex, self.orig, &mut self.res);
        let want = reference_filter(tex, r.u, r.v, p.frac_bits);
        res.transactions += 1;
        if got != want {
            res.mismatches += 1;
            if res.mismatch_log.len() < 10 {
                res.mismatch_log.push(format!(
                    "{tag}: request {i} (u {}, v {}): rgb {got:06x}, integer reference {want:06x}",
                    r.u, r.v
                ));
            }
        }
        let one = f64::from(1u32 << p.frac_bits);
        let (u, v) = (f64::from(r.u) / one, f64::from(r.v) / one);
        let dec = |x: u32, y: u32| {
            let c = tex.texel(x, y);
            [16, 8, 0].map(|s| f64::from(c >> s & 0xff))
        };
        let g = golden::texture::bilinear(dec, p.width, p.height, u, v);
        let org = |x: u32, y: u32| {
            let k = 3 * (y * orig.width + x) as usize;
            [0, 1, 2].map(|c| f64::from(orig.pixels[k + c]))
        };
        let go = golden::texture::bilinear(org, p.width, p.height, u, v);
        for (c, sh) in [16, 8, 0].into_iter().enumerate() {
            let dut = f64::from(got >> sh & 0xff);
            res.stats.record(dut, g[c], 1.0);
            self.compression.record(dut, go[c], 1.0);
        }
    }
}

/// The unit's counters against each other: every request accepted, misses split completely,
/// two DRAM reads per fill, no hit with the cache off, no prefetch without lookahead, every
/// miss served by a fill or a late prefetch, no DRAM timing violation. Returns what fails.
fn count_failures(s: &TexReadStats, cache: bool, requests: u64) -> Vec<String> {
    let (fills, misses) = (s.demand_fills + s.prefetch_fills, s.misses);
    let off = s.lookahead == "off";
    let (demand, prefetch, late) = (s.demand_fills, s.prefetch_fills, s.late_prefetches);
    let split = s.misses_cold + s.misses_capacity + s.misses_conflict;
    [
        (
            s.violations == 0,
            format!("{} DRAM timing violations", s.violations),
        ),
        (
            s.requests == requests,
            format!("{} requests accepted of {requests}", s.requests),
        ),
        (
            misses == split,
            format!("misses {misses} != cold + capacity + conflict"),
        ),
        (
            s.dram_reads == 2 * fills,
            format!("{} DRAM reads for {fills} fills", s.dram_reads),
        ),
        (
            cache || (s.hits == 0 && demand == s.block_refs),
            format!(
                "cache off: {} hits, {demand} fills for {} blocks",
                s.hits, s.block_refs
            ),
        ),
        (
            !off || (prefetch == 0 && demand == misses),
            format!("no lookahead: {prefetch} prefetches, {demand} fills for {misses} misses"),
        ),
        (
            demand + late >= misses,
            format!("{misses} misses but {demand} fills + {late} late prefetches"),
        ),
    ]
    .into_iter()
    .filter_map(|(ok, what)| (!ok).then_some(what))
    .collect()
}

/// Texture size of the testbench.
pub const TB_SIZE: u32 = 256;
/// Requests per trace.
pub const TB_REQUESTS: usize = 2048;

/// The configurations every trace runs in: layout, cache, lookahead, rasterizer interval.
pub const TB_CONFIGS: [(Layout, bool, Lookahead, u32); 11] = [
    (Layout::RowMajor, true, Lookahead::Quadrant, 1),
    (Layout::RowMajor, true, Lookahead::Direction, 1),
    (Layout::RowMajor, true, Lookahead::Off, 1),
    (Layout::RowMajor, false, Lookahead::Off, 1),
    (Layout::Tiled, true, Lookahead::Quadrant, 1),
    (Layout::Tiled, true, Lookahead::Direction, 1),
    (Layout::Tiled, true, Lookahead::Off, 1),
    (Layout::Tiled, false, Lookahead::Off, 1),
    (Layout::RowMajor, true, Lookahead::Quadrant, 4),
    (Layout::RowMajor, true, Lookahead::Direction, 4),
    (Layout::RowMajor, true, Lookahead::Off, 4),
];

/// The texture testbench: a 256x256 synthetic texture (a fixed fixture), CCC-encoded, read
/// through the unit. Configuration 0 is a short horizontal trace in the default mode (the
/// traced one); the others are one scanline trace each ([`TraceKind`]), run in every mode of
/// [`TB_CONFIGS`]: every result checked against the integer reference and the golden model,
/// the modes bit-identical, one record per mode for the hit-rate table and the plots.
pub struct TextureTb;

/// The testbench's name: the unit's.
pub const NAME: &str = "texture_unit_602";

/// The seed of the testbench's texture (the traces are what the run's seed varies).
const TEXTURE_SEED: Seed = Seed(0x602);

/// The fixture: the synthetic texture and its CCC encoding, made once per process.
pub fn fixture() -> Result<&'static (Ppm, Ccc), String> {
    static FIXTURE: std::sync::OnceLock<Result<(Ppm, Ccc), String>> = std::sync::OnceLock::new();
    FIXTURE
        .get_or_init(|| {
            let orig = synthetic_texture(TB_SIZE, TB_SIZE, TEXTURE_SEED);
            formats::ccc::encode(&orig).map(|c| (orig, c))
        })
        .as_ref()
        .map_err(Clone::clone)
}

impl Testbench for TextureTb {
    fn about(&self) -> About {
        About::new(NAME, "texture unit 602: DRAM 604, control 607, CCC 608-612, cache 614, extract 618, bilinear 622 (Figures 4-7)")
            .count(TB_REQUESTS, "requests per trace")
    }
    fn configurations(&self) -> Vec<String> {
        let mut v = vec!["horizontal + edges, 104 requests, default mode (traced)".to_string()];
        v.extend(
            TraceKind::ALL
                .iter()
                .map(|k| format!("{} trace, every mode", k.name())),
        );
        v
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let mut c = Checks::new(ctx)?;
        let (w, h) = (TB_SIZE, TB_SIZE);
        if ctx.index == 0 {
            let (db, worst) = formats::ccc::psnr(&c.orig.pixels, &c.tex.decode());
            c.res.notes.push(format!(
                "CCC of the {w}x{h} test texture: {db:.2} dB PSNR, worst texel error {worst} levels"
            ));
            let mut reqs = trace(TraceKind::Horizontal, w, h, 4, 96, ctx.seed);
            // A scanline along the clamped right edge and one along the bottom edge.
            let edge = |u: u32, v: u32, newline| TexRequest { u, v, newline };
            reqs.extend((0..4).map(|k| edge(((w - 1) << 4) + 4 * k, (40 + k) << 4, k == 0)));
            reqs.extend((0..4).map(|k| edge((40 + 3 * k) << 4, ((h - 1) << 4) + 5, k == 0)));
            let wave = ctx.waves.as_ref().map(|x| (x.vcd.clone(), x.config(5_000)));
            c.run(TexParams::new(w, h), &reqs, 1, wave)?;
            c.res.vcd = ctx.waves.as_ref().map(|x| x.vcd.clone());
        } else {
            let kind = TraceKind::ALL[ctx.index - 1];
            every_mode(&mut c, kind, &trace(kind, w, h, 4, ctx.count, ctx.seed))?;
        }
        c.res.record(&c.compression);
        c.res.coverage = Some(c.cov);
        Ok(c.res)
    }
    fn conclude(&self, merged: &mut TbResult) {
        let mut compression = verif::ErrorStats::new();
        let mut refused = None;
        for c in merged.records_of::<verif::ErrorStats>() {
            if let Err(e) = compression.merge(&c) {
                refused = Some(e);
                break;
            }
        }
        if let Some(e) = refused {
            merged.failures.push(format!("compression statistics: {e}"));
        }
        merged.notes.push(format!(
            "compression error (hardware against the golden model of the original texture): worst {:.2} levels, mean {:.2}",
            compression.max_abs_lsb,
            compression.mean_abs_lsb()
        ));
        let rows = merged.records_of::<TableRow>();
        for r in rows
            .iter()
            .filter(|r| r.stats.layout == "row-major" && r.stats.interval == 1 && r.stats.cache)
        {
            merged.notes.push(format!(
                "{} trace, cache, lookahead {}: hit rate {:.1} %, {:.1} M pixels/s, {:.2} page faults per scanline",
                r.trace,
                r.stats.lookahead,
                100.0 * r.stats.hit_rate,
                r.stats.pixels_per_second / 1e6,
                r.stats.page_faults_per_scanline
            ));
        }
        if !rows.is_empty() {
            merged.tables.push(format!(
                "Hit rate and speed (texture {TB_SIZE}x{TB_SIZE}, {} requests per trace, 512-word pages, 5 ns cycle; interval = cycles between requests the rasterizer offers; misses split by a 4-block fully-associative LRU shadow cache; with the cache off, every reference is a miss and the split says which a 4-block fully-associative cache would have caught):\n\n{}",
                rows[0].stats.requests,
                table(&rows)
            ));
        }
    }
}

/// Runs one trace in every mode of [`TB_CONFIGS`], requiring bit-identical results; records a
/// table row per mode.
fn every_mode(c: &mut Checks, kind: TraceKind, reqs: &[TexRequest]) -> Result<(), String> {
    let mut first: Option<Vec<u32>> = None;
    for (layout, cache, look, interval) in TB_CONFIGS {
        let mut p = TexParams::new(TB_SIZE, TB_SIZE);
        (p.layout, p.cache, p.lookahead) = (layout, cache, look);
        let run = c.run(p, reqs, interval, None)?;
        match &first {
            None => first = Some(run.rgb.clone()),
            Some(r) if *r != run.rgb && run.findings.is_empty() => c.res.failures.push(format!(
                "{}: results differ from the first configuration in {} cache {cache} lookahead {} interval {interval}",
                kind.name(),
                layout.name(),
                look.name()
            )),
            _ => {}
        }
        c.res.record(&TableRow {
            trace: kind.name().into(),
            stats: run.stats,
        });
    }
    Ok(())
}

/// One line of the hit-rate table.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TableRow {
    pub trace: String,
    pub stats: TexReadStats,
}

/// The hit-rate table in markdown.
pub fn table(rows: &[TableRow]) -> String {
    use std::fmt::Write;
    let mut t = String::from(
        "| trace | layout | mode | interval | hit rate | misses cold / capacity / conflict | prefetches (used, late) | page faults / scanline | M pixels/s |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let s = &r.stats;
        let mode = match (s.cache, s.lookahead.as_str()) {
            (false, _) => "no cache".to_string(),
            (true, "off") => "cache".to_string(),
            (true, l) => format!("cache + {l} lookahead"),
        };
        let _ = writeln!(
            t,
            "| {} | {} | {mode} | {} | {:.1} % | {} / {} / {} | {} ({}, {}) | {:.2} | {:.1} |",
            r.trace,
            s.layout,
            s.interval,
            100.0 * s.hit_rate,
            s.misses_cold,
            s.misses_capacity,
            s.misses_conflict,
            s.prefetch_fills,
            s.prefetch_hits,
            s.late_prefetches,
            s.page_faults_per_scanline,
            s.pixels_per_second / 1e6
        );
    }
    t
}
