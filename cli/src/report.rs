//! Results of testbenches, the summary table and `summary.json`.

use formats::output::write_output;
use std::fmt::Write;
use std::path::Path;
use tb::regress::{RegressConfig, Summary};
use verif::{Seed, TbResult};

/// The summary table printed by `texrtl regress`.
pub fn table(results: &[TbResult]) -> String {
    let mut s = String::new();
    // The name column fits the longest name (co-simulation rows are long).
    let w = results
        .iter()
        .map(|r| r.name.len())
        .max()
        .unwrap_or(0)
        .max(32);
    let _ = writeln!(
        s,
        "{:<w$} {:>9} {:>9} {:>6} {:>7} {:>9} {:>10} {:>7}  result",
        "testbench", "txns", "cycles", "mism", "cover", "max LSB", "mean LSB", "latency"
    );
    for r in results {
        let _ = writeln!(
            s,
            "{:<w$} {:>9} {:>9} {:>6} {:>6.1}% {:>9.3} {:>10.4} {:>7}  {}",
            r.name,
            r.transactions,
            r.cycles,
            r.mismatches,
            r.coverage_percent,
            r.stats.max_abs_lsb,
            r.stats.mean_abs_lsb(),
            r.latency_text(),
            r.verdict()
        );
    }
    for r in results {
        for n in &r.notes {
            let _ = writeln!(s, "  {}: {n}", r.name);
        }
    }
    for r in results.iter().filter(|r| !r.passed) {
        for m in r.mismatch_log.iter().chain(&r.failures) {
            let _ = writeln!(s, "  {}: {m}", r.name);
        }
    }
    s
}

/// `report.md`: the summary, each testbench's figures, error histogram and coverage, and
/// links to its waveform and pictures.
pub fn markdown(s: &Summary, pictures: &[(&str, &str)]) -> String {
    let mut m = String::new();
    let _ = writeln!(m, "# texrtl regression report\n");
    let _ = writeln!(
        m,
        "texrtl {}, seed `{}`{}: **{}**.\n",
        s.texrtl,
        s.seed,
        s.shard
            .as_ref()
            .map(|x| format!(", shard {x}"))
            .unwrap_or_default(),
        if s.passed { "all passed" } else { "FAILED" }
    );
    let _ = writeln!(m, "| testbench | unit | transactions | cycles | mismatches | coverage | max error (LSB) | mean error (LSB) | latency | result |");
    let _ = writeln!(m, "|---|---|---:|---:|---:|---:|---:|---:|---:|---|");
    for r in &s.testbenches {
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {} | {:.1} % | {:.3} | {:.4} | {} | {} |",
            r.name,
            r.unit,
            r.transactions,
            r.cycles,
            r.mismatches,
            r.coverage_percent,
            r.stats.max_abs_lsb,
            r.stats.mean_abs_lsb(),
            r.latency_text(),
            r.verdict()
        );
    }
    let _ = writeln!(
        m,
        "\nHow to read it: *mismatches* are transactions whose bits differ from the golden model \
         beyond the testbench's stated tolerance (zero for exact units); *coverage* is the share of \
         functional-coverage bins hit (a hole fails the testbench); errors are in LSBs of each \
         unit's output format against the f64 golden model. Each waveform opens with \
         `gtkwave <name>.gtkw`.\n"
    );
    if !pictures.is_empty() {
        let _ = writeln!(m, "## Pictures\n");
        for (file, caption) in pictures {
            let _ = writeln!(m, "![{caption}]({file})\n\n*{caption}*\n");
        }
    }
    for r in &s.testbenches {
        let _ = writeln!(m, "## {}\n\n{}\n", r.name, r.unit);
        let st = &r.stats;
        if st.count > 0 {
            let _ = writeln!(
                m,
                "Error against golden: {} results, max {:.3} LSB, mean {:.4} LSB, {} exact, {} within ±1 LSB{}.\n",
                st.count,
                st.max_abs_lsb,
                st.mean_abs_lsb(),
                st.exact,
                st.within_1_lsb,
                st.sqnr_db().map(|x| format!(", SQNR {x:.1} dB")).unwrap_or_default()
            );
            let _ = writeln!(m, "| error (LSB, rounded) | count |\n|---:|---:|");
            for (k, v) in &st.histogram {
                let _ = writeln!(m, "| {k} | {v} |");
            }
            m.push('\n');
        }
        for n in &r.notes {
            let _ = writeln!(m, "- {n}");
        }
        for t in &r.tables {
            let _ = writeln!(m, "\n{t}");
        }
        if let Some(v) = &r.vcd {
            let name = v
                .file_name()
                .map(|x| x.to_string_lossy().into_owned())
                .unwrap_or_default();
            let g = v.with_extension("gtkw");
            let gname = g
                .file_name()
                .map(|x| x.to_string_lossy().into_owned())
                .unwrap_or_default();
            let _ = writeln!(m, "\nWaveform: [{name}]({name}), view: [{gname}]({gname})");
        }
        if !r.unhit.is_empty() {
            let _ = writeln!(m, "\nCoverage holes: {}", r.unhit.join(", "));
        }
        for f in r.mismatch_log.iter().chain(&r.failures) {
            let _ = writeln!(m, "- **{f}**");
        }
        m.push('\n');
    }
    m
}

/// The pictures and `report.md` of a regression's summary.
pub fn write_report(out: &Path, summary: &Summary) -> Result<(), String> {
    let write = |f: &str, b: &[u8]| write_output(&out.join(f), b).map_err(|e| e.to_string());
    let results = &summary.testbenches;
    let mut pictures = Vec::new();
    if results.iter().any(|r| r.name == tb::normals::NAME) {
        pictures.push(normals_picture(out)?);
    }
    if results.iter().any(|r| r.name == tb::mipmap::NAME) {
        pictures.push(mipmap_picture(out)?);
    }
    if let Some(t) = results.iter().find(|r| r.name == tb::texture::NAME) {
        let rows = t.records_of::<tb::texture::TableRow>();
        if !rows.is_empty() {
            pictures.extend(crate::plots::memory_plots(out, &rows)?);
        }
    }
    if results.iter().any(|r| r.name == tb::texram::NAME) {
        pictures.push(crate::plots::texram_plot(out)?);
    }
    if results.iter().any(|r| r.name == tb::footprint::NAME) {
        pictures.push(footprint_picture(out)?);
    }
    if results.iter().any(|r| r.name == tb::volume::NAME) {
        pictures.push(volume_picture(out)?);
    }
    if results.iter().any(|r| r.name == tb::mapchain::NAME) {
        pictures.push(mapchain_picture(out)?);
    }
    if results.iter().any(|r| r.name == tb::ptm::FITTER) {
        pictures.push(ptm_picture(out)?);
    }
    if results.iter().any(|r| r.name == tb::derivative::NAME) {
        pictures.push(derivative_picture(out)?);
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
    write("report.md", markdown(summary, &refs).as_bytes())
}

/// The bump-map comparison of the report (FIG. 8a against 8b). Returns `(file, caption)`.
fn normals_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use units::bump::params::BumpParams;
    let p = BumpParams::default();
    let map = tb::maps::builtin("bumps", 48, 48, p.texel_fmt())?;
    let (png, worst) = crate::cmd::render::render_png(&map, &p, [1.0, 1.0, 2.0], 0.5, 4)?;
    let f = "normals_render.png";
    write_output(&out.join(f), &png).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!(
            "Dot3 lighting of the built-in bumps map, scale 0.5: Blinn | B-spline (bit-exact) | golden | log heat map of the B-spline's intensity error (worst {worst:.2e})"
        ),
    ))
}

/// The mipmap levels of a synthetic video frame, for the report. Returns `(file, caption)`.
fn mipmap_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let mp = units::mipmap::MipmapParams {
        width: 64,
        height: 32,
        scan: units::mipmap::Scan::InterlacedTop,
        rounding: units::mipmap::Rounding::Round,
    };
    let frame = tb::mipmap::synthetic_video(64, 32, 1, Seed(3));
    let o = tb::mipmap::run_mipmap(mp, &frame, None)?;
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
    write_output(&out.join(f), &formats::png::encode(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        "Mipmap levels 0-6 of a 64x32 interlaced synthetic frame from the cycle-accurate generator, each scaled to the size of level 0".to_string(),
    ))
}

/// The quality map on a plane at 85 degrees: the exact footprint's mean, isotropic
/// trilinear and footprint assembly, side by side, four times enlarged; pixels whose
/// footprint is longer than 128 texels (not measured) dark red. Returns `(file, caption)`.
fn footprint_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use tb::footprint::VIEW;
    use units::footprint::setup_fig12::SetupParams;
    let v = tb::footprint::view(85.0, &SetupParams::default())?;
    let (s, gap) = (4u32, 8u32);
    let side = VIEW as u32 * s;
    let mut img = image::RgbImage::new(3 * side + 2 * gap, side);
    for (k, px) in v.iter().enumerate() {
        // The view's first rows are the nearest: drawn at the bottom, the horizon up.
        let (x, y) = ((k % VIEW) as u32, (VIEW - 1 - k / VIEW) as u32);
        let vals = match px {
            Some(p) => [p.reference.round() as u8, p.trilinear, p.footprint].map(|t| [t, t, t]),
            None => [[90, 0, 0]; 3],
        };
        for (panel, c) in vals.iter().enumerate() {
            for dy in 0..s {
                for dx in 0..s {
                    let px = panel as u32 * (side + gap) + x * s + dx;
                    img.put_pixel(px, y * s + dy, image::Rgb(*c));
                }
            }
        }
    }
    let f = "footprint_quality.png";
    write_output(&out.join(f), &formats::png::encode(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        "A checker with text on a plane at 85 degrees, 64x64 pixels: the mean over each pixel's exact footprint | isotropic trilinear (blurred along the plane) | footprint assembly, N accesses along the longer edge (section 10); dark red: footprints longer than 128 texels, not measured".to_string(),
    ))
}

/// The built-in volume (24^3, classified to RGBA on the host) cast on four chips in
/// lock-step, 48x48 rays, composited by the golden model; four times enlarged. Returns
/// `(file, caption)`.
fn volume_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let side = 48u32;
    let (px, samples) = tb::volume::render(24, side)?;
    let img = enlarged(&px, side, 4);
    let f = "volume_render.png";
    write_output(&out.join(f), &formats::png::encode(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!("The built-in volume (two shells and a bar, 24^3 voxels, classified to RGBA by the host) ray-cast on four TEXRAM chips in lock-step (section 13): {side}x{side} rays, {samples} samples, each checked against the reference; compositing front to back by the golden model, as the document leaves it to the host"),
    ))
}

/// The bumped, detailed, environment-mapped quad of the map chain, twice enlarged. Returns
/// `(file, caption)`.
fn mapchain_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let side = 160u32;
    let px = tb::mapchain::render_quad(side as usize)?;
    let img = enlarged(&px, side, 2);
    let f = "mapchain_quad.png";
    write_output(&out.join(f), &formats::png::encode(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!("A brick wall tilted 60 degrees away, {side}x{side} pixels through the chain walker of 812 (section 14), one chip a colour component: texture (eq. 5 with Lambert I_d) -> u,v offsets -> detail (multiply, lambda < 0 in the foreground) -> environment (eq. 4 on the normal perturbed by the mortar grooves, eq. 6 with k_s 130): sky and a checkered ground reflected"),
    ))
}

/// The PTM swatch lit from four directions: marched truth over the PTM's visibility, three
/// times enlarged. Returns `(file, caption)`.
fn ptm_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let (px, side, q) = tb::ptm::swatch_picture()?;
    let grey: Vec<[u8; 3]> = px.iter().map(|&c| [c; 3]).collect();
    let img = enlarged(&grey, 4 * side as u32, 3);
    let f = "ptm_swatch.png";
    write_output(&out.join(f), &formats::png::encode(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!("A {side}x{side} woven cloth (001's micro-occlusion) lit at 30 degrees from four azimuths not among the {} fitted lights: top, occlusion marched toward the light (white lit); bottom, visibility 1 - K from the 8-bit PTM through the fitter 604 and the shader 608. Fit RMSE a texel {:.3} mean, {:.3} worst", q.lights, q.rmse_mean, q.rmse_max),
    ))
}

/// FIG. 8 extended: Dot3 lighting of the bumps map by the FIG. 7 pipeline's B-spline and
/// Blinn surfaces and by para. 0086's four derivative filters. Returns `(file, caption)`.
fn derivative_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use units::bump::params::{BumpParams, Filter};
    let p = BumpParams::default();
    let map = tb::maps::builtin("bumps", 32, 32, p.texel_fmt())?;
    let (zoom, scale, light) = (4u32, 0.5, [1.0, 1.0, 2.0]);
    let l = {
        let n = (1.0f64 + 1.0 + 4.0).sqrt();
        light.map(|x: f64| x / n)
    };
    let side = 32 * zoom;
    let mut panels = Vec::new();
    for filter in [Filter::BSpline, Filter::Blinn] {
        panels.push(crate::cmd::render::dot3_panel(
            &map,
            &BumpParams { filter, ..p },
            l,
            scale,
            zoom,
        )?);
    }
    for f in tb::derivative::filters() {
        panels.push(tb::derivative::render(&map, f, scale, zoom, l));
    }
    let gap = 4;
    let mut img = image::RgbImage::new(panels.len() as u32 * (side + gap) - gap, side);
    for (k, panel) in panels.iter().enumerate() {
        for (i, &g) in panel.iter().enumerate() {
            let (x, y) = (i as u32 % side, i as u32 / side);
            img.put_pixel(k as u32 * (side + gap) + x, y, image::Rgb([g, g, g]));
        }
    }
    let f = "derivative_filters.png";
    write_output(&out.join(f), &formats::png::encode(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        "FIG. 8 extended: Dot3 lighting of the built-in bumps map (scale 0.5, 4 samples a texel): FIG. 7's B-spline (9 texels a sample) | Blinn (8) | para. 0086's central differences (12) | Sobel (16) | Prewitt (16) | the 5-point table (20), the filters at four texel centres then bilinear".to_string(),
    ))
}

/// `px` (row by row, `w` wide) enlarged `s` times.
fn enlarged(px: &[[u8; 3]], w: u32, s: u32) -> image::RgbImage {
    let h = px.len() as u32 / w;
    let mut img = image::RgbImage::new(w * s, h * s);
    for (k, c) in px.iter().enumerate() {
        let (x, y) = (k as u32 % w, k as u32 / w);
        for dy in 0..s {
            for dx in 0..s {
                img.put_pixel(x * s + dx, y * s + dy, image::Rgb(*c));
            }
        }
    }
    img
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
