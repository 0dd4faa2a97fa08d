//! `texrtl regress`: every registered testbench on built-in stimulus, with waveforms and a
//! summary.

use crate::report::{table, write_atomic, Summary, TbResult};
use std::path::PathBuf;
use verif::{Registry, RunOptions, Seed};
use waves::check::{check_gtkw, read_vcd};
use waves::TraceConfig;

/// Every testbench of the project, in the order `texrtl regress` runs and reports them.
pub fn registry() -> Registry {
    let mut r = Registry::new();
    r.register(Box::new(crate::blend_adjust::BlendAdjustTb::default()))
        .register(Box::new(crate::normals::NormalsTb))
        .register(Box::new(crate::mipmap::MipmapTb))
        .register(Box::new(crate::dram::DramTb))
        .register(Box::new(crate::texture::TextureTb));
    r
}

/// The name of the bit-accuracy vectors row (a check of fixed stimuli, not a testbench).
pub const VECTORS: &str = "vectors";

/// What `texrtl regress` runs with.
#[derive(Clone, Debug)]
pub struct RegressConfig {
    pub out: PathBuf,
    pub seed: Seed,
    /// Write a VCD and `.gtkw` per testbench.
    pub vcd: bool,
    pub trace: TraceConfig,
    /// The clock period of every waveform; `None`: each testbench's own clock.
    pub period_ps: Option<u64>,
    /// This run's share of the configurations.
    pub shard: verif::Shard,
    /// Random transactions per configuration (`None`: each testbench's default).
    pub count: Option<usize>,
    /// Also write each waveform as FST (made from the VCD, checked against it).
    pub fst: bool,
    /// Run only these testbenches (empty: all, and the vectors check).
    pub only: Vec<String>,
    /// Run the kernel's schedule check on every cycle.
    pub check_schedule: bool,
}

impl RegressConfig {
    /// Checks the names in `only` against the registry.
    pub fn validate(&self, reg: &Registry) -> Result<(), String> {
        for o in &self.only {
            if reg.get(o).is_none() && o != VECTORS {
                return Err(format!(
                    "--only: no testbench '{o}' (there are: {}, {VECTORS})",
                    reg.names().join(", ")
                ));
            }
        }
        Ok(())
    }

    fn selected(&self, name: &str) -> bool {
        self.only.is_empty() || self.only.iter().any(|o| o == name)
    }
}

/// Runs every selected testbench, checks every waveform it wrote (read back with wellen,
/// `.gtkw` checked against it), writes `summary.json`, the pictures and `report.md`. `Err`
/// is for bad options and I/O failures; mismatches are in the results.
pub fn regress(cfg: &RegressConfig) -> Result<Vec<TbResult>, String> {
    let reg = registry();
    cfg.validate(&reg)?;
    std::fs::create_dir_all(&cfg.out).map_err(|e| format!("{}: {e}", cfg.out.display()))?;
    let opts = RunOptions {
        seed: cfg.seed,
        count: cfg.count,
        shard: cfg.shard,
        waves: cfg
            .vcd
            .then(|| (cfg.out.clone(), cfg.trace.clone(), cfg.period_ps)),
        check_schedule: cfg.check_schedule,
    };
    // A progress bar on stderr, one step per configuration (hidden when stderr is not a
    // terminal).
    let bar = indicatif::ProgressBar::new(reg.owned_configurations(cfg.shard, &cfg.only));
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let mut results = Vec::new();
    for tb in reg.iter().filter(|t| cfg.selected(t.name())) {
        let name = tb.name();
        let r = verif::run_testbench(tb, &opts, &mut |label| {
            bar.set_message(format!("{name}: {label}"));
            bar.inc(1);
        })?;
        results.push(r);
    }
    bar.set_message("vectors, waveforms, report");
    // Bit-accuracy vectors of this source tree, when it is there (not for an installed binary);
    // checked by the first shard.
    let dir = crate::vectors::vectors_dir();
    if dir.is_dir() && cfg.shard.index == 1 && cfg.selected(VECTORS) {
        results.push(vectors_row(&dir));
    }
    for r in &mut results {
        check_waveform(r, cfg.fst);
    }
    let summary = Summary {
        texrtl: env!("CARGO_PKG_VERSION").to_string(),
        seed: cfg.seed.to_string(),
        shard: (!cfg.shard.is_all()).then(|| cfg.shard.to_string()),
        passed: results.iter().all(|r| r.passed),
        testbenches: results.clone(),
    };
    write_report(&cfg.out, &summary)?;
    bar.finish_and_clear();
    Ok(results)
}

/// The vectors check as a row of the table.
fn vectors_row(dir: &std::path::Path) -> TbResult {
    let mut r = TbResult::new(VECTORS, "bit-accuracy regression vectors (golden/vectors/)");
    r.coverage_percent = 100.0;
    match crate::vectors::check(dir) {
        Ok(d) => {
            r.transactions = crate::vectors::UNITS.len() as u64;
            r.mismatches = d.len() as u64;
            r.mismatch_log = d;
        }
        Err(e) => r.failures.push(e),
    }
    r.finish_with(false);
    r
}

/// Reads a result's waveform back with wellen and checks its `.gtkw` against it; with `fst`,
/// also writes the FST and compares it value by value. A problem fails the testbench.
fn check_waveform(r: &mut TbResult, fst: bool) {
    let Some(vcd) = &r.vcd else { return };
    let rb = match read_vcd(vcd).and_then(|rb| check_gtkw(vcd, &rb).map(|_| rb)) {
        Ok(rb) => rb,
        Err(e) => return fail_waveform(r, e),
    };
    if fst {
        let f = vcd.with_extension("fst");
        let checked = waves::fst::vcd_to_fst(vcd, &f).and_then(|_| {
            let back = waves::check::read_fst(&f)?;
            waves::fst::same_values(&rb, &back)
                .map_err(|e| format!("{}: differs from {}: {e}", f.display(), vcd.display()))
        });
        if let Err(e) = checked {
            fail_waveform(r, e);
        }
    }
}

fn fail_waveform(r: &mut TbResult, e: String) {
    r.failures.push(format!("waveform: {e}"));
    r.passed = false;
}

/// `summary.json`, the pictures and `report.md`.
fn write_report(out: &std::path::Path, summary: &Summary) -> Result<(), String> {
    let write = |f: &str, b: &[u8]| {
        write_atomic(&out.join(f), b).map_err(|e| format!("{}: {e}", out.join(f).display()))
    };
    write(
        "summary.json",
        &serde_json::to_vec_pretty(summary).map_err(|e| e.to_string())?,
    )?;
    let results = &summary.testbenches;
    let mut pictures = Vec::new();
    if results.iter().any(|r| r.name == "normals") {
        pictures.push(normals_picture(out)?);
    }
    if results.iter().any(|r| r.name == "mipmap") {
        pictures.push(mipmap_picture(out)?);
    }
    if let Some(t) = results.iter().find(|r| r.name == "texture") {
        let rows = t.records_of::<crate::texture::TableRow>();
        if !rows.is_empty() {
            pictures.extend(crate::texture::memory_plots(out, &rows)?);
        }
    }
    for r in results.iter().filter(|r| r.stats.count > 0) {
        let f = format!("{}_error_histogram.png", r.name);
        let title = format!("{}: error against golden", r.name);
        write(
            &f,
            &crate::plots::histogram_png(&title, &r.stats.histogram)?,
        )?;
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
    write(
        "report.md",
        crate::report::markdown(summary, &refs).as_bytes(),
    )
}

/// The bump-map comparison of the report (FIG. 8a against 8b). Returns `(file, caption)`.
fn normals_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use hdl::bump_params::BumpParams;
    let p = BumpParams::default();
    let map = crate::maps::builtin("bumps", 48, 48, p.texel_fmt())?;
    let (png, worst) = crate::commands::render_png(&map, &p, [1.0, 1.0, 2.0], 0.5, 4)?;
    let f = "normals_render.png";
    write_atomic(&out.join(f), &png).map_err(|e| format!("{}: {e}", out.join(f).display()))?;
    Ok((
        f.to_string(),
        format!(
            "Dot3 lighting of the built-in bumps map, scale 0.5: Blinn | B-spline (bit-exact) | golden | log heat map of the B-spline's intensity error (worst {worst:.2e})"
        ),
    ))
}

/// The mipmap levels of a synthetic video frame, for the report. Returns `(file, caption)`.
fn mipmap_picture(out: &std::path::Path) -> Result<(String, String), String> {
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
    Ok((
        f.to_string(),
        "Mipmap levels 0-6 of a 64x32 interlaced synthetic frame from the cycle-accurate generator, each scaled to the size of level 0".to_string(),
    ))
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
    let reg = registry();
    let mut merged: Vec<TbResult> = Vec::new();
    for (p, s) in &shards {
        for r in &s.testbenches {
            let mut r = r.clone();
            r.strip_conclusions();
            match merged.iter_mut().find(|m| m.name == r.name) {
                Some(m) => m
                    .absorb(&r, None)
                    .map_err(|e| format!("{}: {}: {e}", p.display(), r.name))?,
                None => merged.push(r),
            }
        }
    }
    // The order of an unsharded run (shards see different subsets).
    merged.sort_by_key(|m| reg.position(&m.name).unwrap_or(usize::MAX));
    for m in &mut merged {
        match reg.get(&m.name) {
            Some(tb) => verif::conclude(tb, m, true),
            None => m.finish_with(true),
        }
    }
    Ok(Summary {
        texrtl: first.texrtl.clone(),
        seed: first.seed.clone(),
        shard: None,
        passed: merged.iter().all(|m| m.passed),
        testbenches: merged,
    })
}
