//! The texture units' pictures in the regression report, each unit's named by its descriptor
//! ([`crate::project`]): FIG. 8's lighting, the mipmap levels, the memory path's charts, the
//! TEXRAM's slots, the footprint quality map, the ray-cast volume, the map chain's quad, the
//! PTM swatch and the derivative filters.

pub mod derivative;
pub mod lighting;
pub mod ptm;
pub mod quad;
pub mod texram;
pub mod volume;

use std::path::Path;
use verif::plot::grouped_bars_svg;
use verif::project::Picture;
use verif::Seed;
use waves::output::write_output;

/// PNG bytes of a picture.
pub fn png(img: &image::RgbImage) -> Result<Vec<u8>, String> {
    verif::plot::png(img.width(), img.height(), img.as_raw())
}

/// `(file, caption)` as a report picture.
fn picture((file, caption): (String, String)) -> Picture {
    Picture { file, caption }
}

/// One picture of a unit's testbench results, as the descriptor takes it.
pub fn one(
    f: fn(&Path) -> Result<(String, String), String>,
) -> impl Fn(&Path, &[verif::TbResult]) -> Result<Vec<Picture>, String> + Send + Sync {
    move |out, _| Ok(vec![picture(f(out)?)])
}

/// The memory path's charts, from the texture testbench's rows.
pub fn memory(out: &Path, results: &[verif::TbResult]) -> Result<Vec<Picture>, String> {
    let Some(t) = results.iter().find(|r| r.name == crate::texture::NAME) else {
        return Ok(Vec::new());
    };
    let rows = t.records_of::<crate::texture::TableRow>();
    if rows.is_empty() {
        return Ok(Vec::new());
    }
    Ok(memory_plots(out, &rows)?.into_iter().map(picture).collect())
}

/// The bump-map comparison of the report (FIG. 8a against 8b). Returns `(file, caption)`.
pub fn normals_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use units::bump::params::BumpParams;
    let p = BumpParams::default();
    let map = crate::maps::builtin("bumps", 48, 48, p.texel_fmt())?;
    let (png, worst) = lighting::render_png(&map, &p, [1.0, 1.0, 2.0], 0.5, 4)?;
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
pub fn mipmap_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let mp = units::mipmap::MipmapParams {
        width: 64,
        height: 32,
        scan: units::mipmap::Scan::InterlacedTop,
        rounding: units::mipmap::Rounding::Round,
    };
    let frame = crate::mipmap::synthetic_video(64, 32, 1, Seed(3));
    let o = crate::runs::mipmap::run_mipmap(mp, &frame, None)?;
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
    write_output(&out.join(f), &png(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        "Mipmap levels 0-6 of a 64x32 interlaced synthetic frame from the cycle-accurate generator, each scaled to the size of level 0".to_string(),
    ))
}

/// The quality map on a plane at 85 degrees: the exact footprint's mean, isotropic
/// trilinear and footprint assembly, side by side, four times enlarged; pixels whose
/// footprint is longer than 128 texels (not measured) dark red. Returns `(file, caption)`.
pub fn footprint_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use crate::runs::footprint::VIEW;
    use units::footprint::setup_fig12::SetupParams;
    let v = crate::runs::footprint::view(85.0, &SetupParams::default())?;
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
    write_output(&out.join(f), &png(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        "A checker with text on a plane at 85 degrees, 64x64 pixels: the mean over each pixel's exact footprint | isotropic trilinear (blurred along the plane) | footprint assembly, N accesses along the longer edge (section 10); dark red: footprints longer than 128 texels, not measured".to_string(),
    ))
}

/// The built-in volume (24^3, classified to RGBA on the host) cast on four chips in
/// lock-step, 48x48 rays, composited by the golden model; four times enlarged. Returns
/// `(file, caption)`.
pub fn volume_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let side = 48u32;
    let (px, samples) = volume::render(24, side)?;
    let img = enlarged(&px, side, 4);
    let f = "volume_render.png";
    write_output(&out.join(f), &png(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!("The built-in volume (two shells and a bar, 24^3 voxels, classified to RGBA by the host) ray-cast on four TEXRAM chips in lock-step (section 13): {side}x{side} rays, {samples} samples, each checked against the reference; compositing front to back by the golden model, as the document leaves it to the host"),
    ))
}

/// The bumped, detailed, environment-mapped quad of the map chain, twice enlarged. Returns
/// `(file, caption)`.
pub fn mapchain_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let side = 160u32;
    let px = quad::render_quad(side as usize)?;
    let img = enlarged(&px, side, 2);
    let f = "mapchain_quad.png";
    write_output(&out.join(f), &png(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!("A brick wall tilted 60 degrees away, {side}x{side} pixels through the chain walker of 812 (section 14), one chip a colour component: texture (eq. 5 with Lambert I_d) -> u,v offsets -> detail (multiply, lambda < 0 in the foreground) -> environment (eq. 4 on the normal perturbed by the mortar grooves, eq. 6 with k_s 130): sky and a checkered ground reflected"),
    ))
}

/// The PTM swatch lit from four directions: marched truth over the PTM's visibility, three
/// times enlarged. Returns `(file, caption)`.
pub fn ptm_picture(out: &std::path::Path) -> Result<(String, String), String> {
    let (px, side, q) = ptm::swatch_picture()?;
    let grey: Vec<[u8; 3]> = px.iter().map(|&c| [c; 3]).collect();
    let img = enlarged(&grey, 4 * side as u32, 3);
    let f = "ptm_swatch.png";
    write_output(&out.join(f), &png(&img)?).map_err(|e| e.to_string())?;
    Ok((
        f.to_string(),
        format!("A {side}x{side} woven cloth (001's micro-occlusion) lit at 30 degrees from four azimuths not among the {} fitted lights: top, occlusion marched toward the light (white lit); bottom, visibility 1 - K from the 8-bit PTM through the fitter 604 and the shader 608. Fit RMSE a texel {:.3} mean, {:.3} worst", q.lights, q.rmse_mean, q.rmse_max),
    ))
}

/// FIG. 8 extended: Dot3 lighting of the bumps map by the FIG. 7 pipeline's B-spline and
/// Blinn surfaces and by para. 0086's four derivative filters. Returns `(file, caption)`.
pub fn derivative_picture(out: &std::path::Path) -> Result<(String, String), String> {
    use units::bump::params::{BumpParams, Filter};
    let p = BumpParams::default();
    let map = crate::maps::builtin("bumps", 32, 32, p.texel_fmt())?;
    let (zoom, scale, light) = (4u32, 0.5, [1.0, 1.0, 2.0]);
    let l = {
        let n = (1.0f64 + 1.0 + 4.0).sqrt();
        light.map(|x: f64| x / n)
    };
    let side = 32 * zoom;
    let mut panels = Vec::new();
    for filter in [Filter::BSpline, Filter::Blinn] {
        panels.push(lighting::dot3_panel(
            &map,
            &BumpParams { filter, ..p },
            l,
            scale,
            zoom,
        )?);
    }
    for f in crate::derivative::filters() {
        panels.push(derivative::render(&map, f, scale, zoom, l));
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
    write_output(&out.join(f), &png(&img)?).map_err(|e| e.to_string())?;
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

/// The memory-path pictures of the report (hit rate, pixels per second with and without
/// lookahead, page faults per scanline by layout), from the testbench's rows. Returns
/// `(file, caption)`.
fn memory_plots(
    out: &std::path::Path,
    rows: &[crate::texture::TableRow],
) -> Result<Vec<(String, String)>, String> {
    let traces: Vec<String> = crate::texture::TraceKind::ALL
        .iter()
        .map(|k| k.name().to_string())
        .collect();
    let pick = |layout: &str,
                cache: bool,
                look: &str,
                interval: u32,
                f: &dyn Fn(&crate::runs::texture::TexReadStats) -> f64| {
        traces
            .iter()
            .map(|t| {
                rows.iter()
                    .find(|r| {
                        r.trace == *t
                            && r.stats.layout == layout
                            && r.stats.cache == cache
                            && r.stats.lookahead == look
                            && r.stats.interval == interval
                    })
                    .map_or(0.0, |r| f(&r.stats))
            })
            .collect::<Vec<f64>>()
    };
    let hit = |s: &crate::runs::texture::TexReadStats| 100.0 * s.hit_rate;
    let mpx = |s: &crate::runs::texture::TexReadStats| s.pixels_per_second / 1e6;
    let pf = |s: &crate::runs::texture::TexReadStats| s.page_faults_per_scanline;
    let plots = [
        (
            "texture_hit_rate.svg",
            "Cache 614: block hit rate (row-major, 256x256 texture)",
            "hit rate (%)",
            vec![
                ("quadrant, 1 req/cycle".to_string(), pick("row-major", true, "quadrant", 1, &hit)),
                ("direction, 1 req/cycle".to_string(), pick("row-major", true, "direction", 1, &hit)),
                ("no lookahead, 1 req/cycle".to_string(), pick("row-major", true, "off", 1, &hit)),
                ("quadrant, 1 req/4 cycles".to_string(), pick("row-major", true, "quadrant", 4, &hit)),
                ("direction, 1 req/4 cycles".to_string(), pick("row-major", true, "direction", 4, &hit)),
                ("no lookahead, 1 req/4 cycles".to_string(), pick("row-major", true, "off", 4, &hit)),
            ],
            "block hit rate of cache 614 per trace, quadrant lookahead, direction lookahead and none, rasterizer offering a request every cycle or every 4 cycles",
        ),
        (
            "texture_pixels_per_second.svg",
            "Texture unit 602: pixels per second (5 ns cycle, row-major)",
            "M pixels/s",
            vec![
                ("cache + quadrant lookahead".to_string(), pick("row-major", true, "quadrant", 1, &mpx)),
                ("cache + direction lookahead".to_string(), pick("row-major", true, "direction", 1, &mpx)),
                ("cache".to_string(), pick("row-major", true, "off", 1, &mpx)),
                ("no cache".to_string(), pick("row-major", false, "off", 1, &mpx)),
            ],
            "textured pixels per second per trace with quadrant or direction lookahead, without it, and without the cache (rasterizer offering one request per cycle)",
        ),
        (
            "texture_page_faults.svg",
            "DRAM 604: page faults per scanline (512-word pages)",
            "page faults / scanline",
            vec![
                ("row-major, cache".to_string(), pick("row-major", true, "off", 1, &pf)),
                ("tiled, cache".to_string(), pick("tiled", true, "off", 1, &pf)),
                ("row-major, no cache".to_string(), pick("row-major", false, "off", 1, &pf)),
                ("tiled, no cache".to_string(), pick("tiled", false, "off", 1, &pf)),
            ],
            "DRAM page faults per scanline per trace, row-major against tiled layout, 512-word pages",
        ),
    ];
    let mut v = Vec::new();
    for (file, title, ydesc, series, caption) in plots {
        let svg = grouped_bars_svg(title, ydesc, &traces, &series)?;
        let path = out.join(file);
        write_output(&path, svg.as_bytes()).map_err(|e| e.to_string())?;
        v.push((file.to_string(), caption.to_string()));
    }
    Ok(v)
}

/// The TEXRAM picture of the report: slots per pixel and page faults per scanline of each
/// configuration (`texram::layout_rows`). Returns `(file, caption)`.
pub fn texram_plot(out: &std::path::Path) -> Result<(String, String), String> {
    let rows = texram::layout_rows();
    let groups: Vec<String> = rows.iter().map(|r| r.0.clone()).collect();
    let series = vec![
        (
            "slots per pixel".to_string(),
            rows.iter().map(|r| r.1).collect(),
        ),
        (
            "accesses with a page fault per scanline".to_string(),
            rows.iter().map(|r| r.2).collect(),
        ),
    ];
    let file = "texram_slots.svg";
    let svg = grouped_bars_svg(
        "TEXRAM 802: slots and page faults by configuration",
        "per pixel / per scanline",
        &groups,
        &series,
    )?;
    write_output(&out.join(file), svg.as_bytes()).map_err(|e| e.to_string())?;
    Ok((
        file.to_string(),
        "TEXRAM chip 802, a 64x64-pixel view scanline by scanline at lambda 2.5: slots per pixel (1 at best; four component accesses in the colour layouts, whose quadrant rows the planar one switches twice a pixel, and conflict rounds in the literal one) and the slots lost per 64-pixel scanline to page faults and bank conflicts".to_string(),
    ))
}
