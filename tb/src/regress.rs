//! `texrtl regress`: every testbench on built-in stimulus, with waveforms and a summary.

use crate::blend_adjust::{self, BaConfig};
use crate::report::{table, write_atomic, Summary, TbResult};
use std::path::PathBuf;
use verif::Seed;
use waves::check::{check_gtkw, read_vcd};
use waves::TraceConfig;

/// The testbenches in the order `texrtl regress` runs and reports them.
pub const ORDER: [&str; 6] = [
    "blend_adjust",
    "normals",
    "mipmap",
    "dram",
    "texture",
    "vectors",
];

/// What `texrtl regress` runs with.
#[derive(Clone, Debug)]
pub struct RegressConfig {
    pub out: PathBuf,
    pub seed: Seed,
    /// Write a VCD and `.gtkw` per testbench.
    pub vcd: bool,
    pub trace: TraceConfig,
    /// This run's share of the configurations.
    pub shard: verif::Shard,
    /// Random transactions per configuration (`None`: each testbench's default).
    pub count: Option<usize>,
    /// Also write each waveform as FST (made from the VCD, checked against it).
    pub fst: bool,
}

/// Runs every testbench, checks every waveform it wrote (read back with wellen, `.gtkw`
/// checked against it), writes `summary.json`. `Err` is for I/O failures only; mismatches are
/// in the results.
pub fn regress(cfg: &RegressConfig) -> Result<Vec<TbResult>, String> {
    std::fs::create_dir_all(&cfg.out).map_err(|e| format!("{}: {e}", cfg.out.display()))?;
    let mut results = Vec::new();
    // A progress bar on stderr (hidden when stderr is not a terminal).
    let bar = indicatif::ProgressBar::new(7);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar.set_message("blend_adjust");

    let ba = BaConfig {
        seed: cfg.seed.derive(153),
        vcd: cfg.vcd.then(|| cfg.out.join("blend_adjust.vcd")),
        trace: cfg.trace.clone(),
        shard: cfg.shard,
        random_per_width: cfg.count.unwrap_or(BaConfig::default().random_per_width),
        ..BaConfig::default()
    };
    results.push(blend_adjust::run_tb(&ba)?);
    bar.inc(1);
    bar.set_message("normals");
    results.push(crate::normals::regress_suite(
        cfg.seed.derive(7),
        cfg.vcd.then(|| cfg.out.join("normals.vcd")),
        cfg.trace.clone(),
        cfg.shard,
        cfg.count,
    )?);
    bar.inc(1);
    bar.set_message("mipmap");
    results.push(crate::mipmap::regress_suite(
        cfg.seed.derive(816),
        cfg.vcd.then(|| cfg.out.join("mipmap.vcd")),
        cfg.trace.clone(),
        cfg.shard,
    )?);

    bar.inc(1);
    bar.set_message("dram");
    if cfg.shard.owns(0) {
        results.push(crate::dram::regress_suite(
            cfg.seed.derive(604),
            cfg.vcd.then(|| cfg.out.join("dram.vcd")),
        )?);
    }
    bar.set_message("texture");
    let mut memory_rows = Vec::new();
    if cfg.shard.owns(1) {
        let (r, rows) = crate::texture::regress_suite(
            cfg.seed.derive(602),
            cfg.vcd.then(|| cfg.out.join("texture.vcd")),
            cfg.trace.clone(),
        )?;
        results.push(r);
        memory_rows = rows;
    }
    bar.inc(1);
    bar.set_message("vectors, waveforms, report");
    // Bit-accuracy vectors of this source tree, when it is there (not for an installed binary);
    // checked by the first shard.
    let dir = crate::vectors::vectors_dir();
    if dir.is_dir() && cfg.shard.index == 1 {
        let mut r = TbResult::new(
            "vectors",
            "bit-accuracy regression vectors (golden/vectors/)",
        );
        r.coverage_percent = 100.0;
        match crate::vectors::check(&dir) {
            Ok(d) => {
                r.transactions = crate::vectors::UNITS.len() as u64;
                r.mismatches = d.len() as u64;
                r.mismatch_log = d;
            }
            Err(e) => r.failures.push(e),
        }
        r.finish_with(false);
        results.push(r);
    }

    for r in &mut results {
        if let Some(vcd) = &r.vcd {
            let checked = read_vcd(vcd).and_then(|rb| check_gtkw(vcd, &rb).map(|_| rb));
            let checked = match (checked, cfg.fst) {
                (Ok(rb), true) => {
                    let fst = vcd.with_extension("fst");
                    waves::fst::vcd_to_fst(vcd, &fst).and_then(|_| {
                        let f = waves::check::read_fst(&fst)?;
                        waves::fst::same_values(&rb, &f).map_err(|e| {
                            format!("{}: differs from {}: {e}", fst.display(), vcd.display())
                        })
                    })
                }
                (r, _) => r.map(|_| ()),
            };
            match checked {
                Ok(_) => {}
                Err(e) => {
                    r.failures.push(format!("waveform: {e}"));
                    r.passed = false;
                }
            }
        }
    }
    let passed = results.iter().all(|r| r.passed);
    let summary = Summary {
        texrtl: env!("CARGO_PKG_VERSION").to_string(),
        seed: cfg.seed.to_string(),
        shard: (!cfg.shard.is_all()).then(|| cfg.shard.to_string()),
        passed,
        testbenches: results.clone(),
    };
    let json = serde_json::to_vec_pretty(&summary).map_err(|e| e.to_string())?;
    let path = cfg.out.join("summary.json");
    write_atomic(&path, &json).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut pictures = pictures(&cfg.out)?;
    if !memory_rows.is_empty() {
        pictures.extend(crate::texture::memory_plots(&cfg.out, &memory_rows)?);
    }
    for r in results.iter().filter(|r| r.stats.count > 0) {
        let f = format!("{}_error_histogram.png", r.name);
        let png = crate::plots::histogram_png(
            &format!("{}: error against golden", r.name),
            &r.stats.histogram,
        )?;
        write_atomic(&cfg.out.join(&f), &png)
            .map_err(|e| format!("{}: {e}", cfg.out.join(&f).display()))?;
        pictures.push((
            f,
            format!(
                "{}: histogram of the error against the golden model, in output LSBs (log scale)",
                r.name
            ),
        ));
    }
    let refs: Vec<(&str, &str)> = pictures
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    let report = cfg.out.join("report.md");
    write_atomic(&report, crate::report::markdown(&summary, &refs).as_bytes())
        .map_err(|e| format!("{}: {e}", report.display()))?;
    bar.finish_and_clear();
    Ok(results)
}

/// The pictures of the report: the bump-map comparison (FIG. 8a against 8b) and the mipmap
/// levels of a synthetic video frame. Returns `(file, caption)`.
fn pictures(out: &std::path::Path) -> Result<Vec<(String, String)>, String> {
    use hdl::bump_params::BumpParams;
    let mut v = Vec::new();
    let p = BumpParams::default();
    let map = crate::maps::builtin("bumps", 48, 48, p.texel_fmt())?;
    let (png, worst) = crate::commands::render_png(&map, &p, [1.0, 1.0, 2.0], 0.5, 4)?;
    let f = "normals_render.png";
    write_atomic(&out.join(f), &png).map_err(|e| format!("{}: {e}", out.join(f).display()))?;
    v.push((
        f.to_string(),
        format!(
            "Dot3 lighting of the built-in bumps map, scale 0.5: Blinn | B-spline (bit-exact) | golden | log heat map of the B-spline's intensity error (worst {worst:.2e})"
        ),
    ));
    let mp = hdl::mipmap::MipmapParams {
        width: 64,
        height: 32,
        scan: hdl::mipmap::Scan::InterlacedTop,
        rounding: hdl::mipmap::Rounding::Round,
    };
    let frame = crate::mipmap::synthetic_video(64, 32, 1, Seed(3));
    let o = crate::mipmap::run_mipmap(mp, &frame, None)?;
    let dims = mp.levels();
    let mut img = image::RgbImage::new(dims.len() as u32 * 68, 32);
    for (k, level) in o.frames[0].iter().enumerate() {
        let (lw, _) = dims[k];
        let s = 1u32 << k;
        for y in 0..32u32 {
            for x in 0..64u32 {
                let t = level[((y / s.min(32)) * lw + (x / s).min(lw - 1)) as usize];
                img.put_pixel(k as u32 * 68 + x, y, image::Rgb([t, t, t]));
            }
        }
    }
    let f = "mipmap_levels.png";
    write_atomic(&out.join(f), &crate::commands::encode_png(&img)?)
        .map_err(|e| format!("{}: {e}", out.join(f).display()))?;
    v.push((
        f.to_string(),
        "Mipmap levels 0-6 of a 64x32 interlaced synthetic frame from the cycle-accurate generator, each scaled to the size of level 0".to_string(),
    ));
    Ok(v)
}

/// The table and a closing line, as `texrtl regress` prints them.
pub fn render(results: &[TbResult], cfg: &RegressConfig) -> String {
    let mut s = table(results);
    let failed = results.iter().filter(|r| !r.passed).count();
    s.push_str(&format!(
        "{} testbenches: {} passed, {} failed (seed {}; outputs in {})\n",
        results.len(),
        results.len() - failed,
        failed,
        cfg.seed,
        cfg.out.display()
    ));
    s
}

/// `texrtl merge`: combines the `summary.json` of every shard of one run into one: counts and
/// error statistics add up, coverage is merged bin by bin (a hole fails only if no shard hit
/// it). Errors name the file and the problem.
pub fn merge(paths: &[PathBuf]) -> Result<Summary, String> {
    let mut shards: Vec<(PathBuf, Summary)> = Vec::new();
    for p in paths {
        let b = std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()))?;
        let s: Summary = serde_json::from_slice(&b)
            .map_err(|e| format!("{}: not a texrtl summary.json: {e}", p.display()))?;
        shards.push((p.clone(), s));
    }
    let (first_path, first) = shards.first().ok_or("merge: no summary.json given")?;
    let parse = |p: &PathBuf, s: &Summary| -> Result<verif::Shard, String> {
        match &s.shard {
            Some(x) => verif::Shard::parse(x).map_err(|e| format!("{}: {e}", p.display())),
            None => Err(format!(
                "{}: not a shard (run with --shard I/N)",
                p.display()
            )),
        }
    };
    let n = parse(first_path, first)?.count;
    let mut seen = vec![false; n as usize];
    for (p, s) in &shards {
        let sh = parse(p, s)?;
        if s.seed != first.seed || sh.count != n {
            return Err(format!(
                "{}: shard {sh} of seed {} does not belong with {}/{n} of seed {}",
                p.display(),
                s.seed,
                1,
                first.seed
            ));
        }
        if std::mem::replace(&mut seen[sh.index as usize - 1], true) {
            return Err(format!("{}: shard {sh} given twice", p.display()));
        }
    }
    if let Some(i) = seen.iter().position(|s| !s) {
        return Err(format!("merge: shard {}/{n} is missing", i + 1));
    }
    let mut merged: Vec<TbResult> = Vec::new();
    for (_, s) in &shards {
        for r in &s.testbenches {
            match merged.iter_mut().find(|m| m.name == r.name) {
                Some(m) => m.absorb(r),
                None => {
                    let mut m = r.clone();
                    m.failures.retain(|f| !f.starts_with("coverage holes"));
                    merged.push(m);
                }
            }
        }
    }
    // The order of an unsharded run (shards see different subsets).
    merged.sort_by_key(|m| {
        ORDER
            .iter()
            .position(|n| *n == m.name)
            .unwrap_or(ORDER.len())
    });
    for m in &mut merged {
        if let Some(c) = m.coverage.take() {
            m.set_coverage(c);
        }
        m.failures.retain(|f| !f.starts_with("coverage holes"));
        let holes = m.coverage.is_some();
        m.finish_with(holes);
    }
    Ok(Summary {
        texrtl: first.texrtl.clone(),
        seed: first.seed.clone(),
        shard: None,
        passed: merged.iter().all(|m| m.passed),
        testbenches: merged,
    })
}
