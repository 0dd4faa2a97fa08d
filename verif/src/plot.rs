//! Charts for a report, drawn with `plotters` as SVG (a browser, a Markdown viewer and GTKWave's
//! neighbours all show it; the text is the viewer's sans-serif, so no font is compiled in): an
//! error histogram and grouped bars. [`png()`] encodes a picture of the design's own.

use plotters::prelude::*;
use std::collections::BTreeMap;

const FONT: FontFamily = FontFamily::SansSerif;

/// A bar chart of an error histogram (error in LSBs -> count, log-scaled counts), as SVG.
pub fn histogram_svg(title: &str, hist: &BTreeMap<i64, u64>) -> Result<String, String> {
    let (w, h) = (640u32, 360u32);
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let lo = hist.keys().next().copied().unwrap_or(0).min(-1);
        let hi = hist.keys().last().copied().unwrap_or(0).max(1);
        let top = hist.values().copied().max().unwrap_or(1).max(1) as f64;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FONT, 22))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(64)
            .build_cartesian_2d(
                (lo as f64 - 1.0)..(hi as f64 + 1.0),
                (0.5f64..top * 2.0).log_scale(),
            )
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("error (output LSBs, rounded)")
            .y_desc("results")
            .x_labels((hi - lo + 3) as usize)
            .label_style((FONT, 16))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .axis_desc_style((FONT, 17))
            .draw()
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(hist.iter().map(|(&k, &v)| {
                let k = k as f64;
                Rectangle::new(
                    [(k - 0.4, 0.5), (k + 0.4, v as f64)],
                    RGBColor(40, 90, 170).filled(),
                )
            }))
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(buf)
}

/// A grouped bar chart as SVG: one group per label on the x axis, one bar per series in each
/// group (series named in the legend), values on a linear y axis starting at 0.
pub fn grouped_bars_svg(
    title: &str,
    y_desc: &str,
    groups: &[String],
    series: &[(String, Vec<f64>)],
) -> Result<String, String> {
    let (w, h) = (720u32, 380u32);
    let mut buf = String::new();
    let colours = [
        RGBColor(40, 90, 170),
        RGBColor(220, 120, 30),
        RGBColor(60, 150, 80),
        RGBColor(150, 60, 150),
        RGBColor(120, 170, 220),
        RGBColor(240, 190, 120),
    ];
    {
        let root = SVGBackend::with_string(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let top = series
            .iter()
            .flat_map(|s| s.1.iter().copied())
            .fold(0.0f64, f64::max)
            .max(1e-9)
            // Headroom for the legend above the bars.
            * (1.25 + 0.06 * series.len() as f64);
        let n = groups.len().max(1);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FONT, 22))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(64)
            .build_cartesian_2d(-0.5f64..(n as f64 - 0.5), 0.0..top)
            .map_err(|e| e.to_string())?;
        let names = groups.to_vec();
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(n)
            .x_label_formatter(&|v| {
                let k = v.round();
                if (v - k).abs() < 1e-6 && k >= 0.0 {
                    names.get(k as usize).cloned().unwrap_or_default()
                } else {
                    String::new()
                }
            })
            .y_desc(y_desc)
            .label_style((FONT, 16))
            .axis_desc_style((FONT, 17))
            .draw()
            .map_err(|e| e.to_string())?;
        let m = series.len().max(1) as f64;
        let bw = 0.8 / m;
        for (si, (name, vals)) in series.iter().enumerate() {
            let c = colours[si % colours.len()];
            chart
                .draw_series(vals.iter().enumerate().map(|(g, &v)| {
                    let x0 = g as f64 - 0.4 + si as f64 * bw;
                    Rectangle::new([(x0, 0.0), (x0 + bw * 0.9, v)], c.filled())
                }))
                .map_err(|e| e.to_string())?
                .label(name.as_str())
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 10, y + 5)], c.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font((FONT, 16))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(buf)
}

/// One row of a bit chart ([`bit_spans_svg`]): bit positions are binary weights, `k` for
/// `2^k` (negative: fraction bits).
#[derive(Clone, Debug, PartialEq)]
pub struct BitSpan {
    /// The row's name.
    pub label: String,
    /// The lowest and highest bit the format declares.
    pub declared: (i32, i32),
    /// The lowest and highest bit the values needed (`None`: no value came).
    pub used: Option<(i32, i32)>,
    /// Values needed more than the declared bits (they saturated or wrapped).
    pub overflowed: bool,
}

/// A chart of bit spans as SVG, a row each: the declared bits as a wide grey bar, the bits the
/// values used as a narrow bar over it (blue; red where values overflowed the declaration).
pub fn bit_spans_svg(title: &str, rows: &[BitSpan]) -> Result<String, String> {
    let n = rows.len().max(1);
    let label_px = rows.iter().map(|r| r.label.len()).max().unwrap_or(8) as u32 * 8 + 16;
    // Wide enough for the title (about 11 pixels a character at its size).
    let w = (420 + label_px.min(520)).max(title.len() as u32 * 11 + 40);
    let h = 190 + 26 * n as u32;
    let lo = rows.iter().map(|r| r.declared.0).min().unwrap_or(0);
    let hi = rows.iter().map(|r| r.declared.1).max().unwrap_or(0);
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(label_px.min(520))
            .build_cartesian_2d(
                (lo as f64 - 0.75)..(hi as f64 + 0.75),
                // Three rows' room below the bars for the legend.
                -3.6f64..(n as f64 - 0.4),
            )
            .map_err(|e| e.to_string())?;
        let labels: Vec<String> = rows.iter().map(|r| r.label.clone()).collect();
        chart
            .configure_mesh()
            .disable_y_mesh()
            .y_labels(n + 4)
            .y_label_formatter(&|v| {
                let k = v.round();
                let i = n as f64 - 1.0 - k;
                let whole = (v - k).abs() < 1e-6 && i >= 0.0;
                whole
                    .then(|| labels.get(i as usize).cloned())
                    .flatten()
                    .unwrap_or_default()
            })
            .x_desc("bit: weight 2^k (k < 0: fraction bits)")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 15))
            .draw()
            .map_err(|e| e.to_string())?;
        let grey = RGBColor(205, 205, 205);
        let (blue, red) = (RGBColor(40, 90, 170), RGBColor(200, 40, 40));
        let bar = |(a, b): (i32, i32), y: f64, half: f64, c: RGBColor| {
            Rectangle::new(
                [(a as f64 - 0.5, y - half), (b as f64 + 0.5, y + half)],
                c.filled(),
            )
        };
        let y = |i: usize| (n - 1 - i) as f64;
        let declared = rows.iter().enumerate();
        chart
            .draw_series(declared.map(|(i, r)| bar(r.declared, y(i), 0.38, grey)))
            .map_err(|e| e.to_string())?
            .label("declared")
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 10, y + 5)], grey.filled()));
        for (overflowed, c, name) in [(false, blue, "used"), (true, red, "overflowed")] {
            let used = rows
                .iter()
                .enumerate()
                .filter(|(_, r)| r.overflowed == overflowed);
            let used = used.filter_map(|(i, r)| Some(bar(r.used?, y(i), 0.18, c)));
            chart
                .draw_series(used)
                .map_err(|e| e.to_string())?
                .label(name)
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 10, y + 5)], c.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FONT, 14))
            .position(SeriesLabelPosition::LowerLeft)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(buf)
}

/// PNG bytes of an 8-bit RGB image of `width` x `height` pixels, row by row (`rgb` holds
/// 3 bytes a pixel).
pub fn png(width: u32, height: u32, rgb: &[u8]) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let mut e = ::png::Encoder::new(&mut out, width, height);
    e.set_color(::png::ColorType::Rgb);
    e.set_depth(::png::BitDepth::Eight);
    let mut w = e.write_header().map_err(|e| e.to_string())?;
    w.write_image_data(rgb).map_err(|e| e.to_string())?;
    w.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_histogram_is_an_svg_with_its_title_and_a_bar_per_bin() {
        let hist = BTreeMap::from([(-1, 3), (0, 1000), (2, 7)]);
        let svg = histogram_svg("unit: error", &hist).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("unit: error"));
        // The background and the plotting area are rectangles too; each bin adds one.
        let bars = svg.matches("<rect").count();
        let empty = histogram_svg("unit: error", &BTreeMap::new()).unwrap();
        assert_eq!(bars - empty.matches("<rect").count(), hist.len());
    }

    #[test]
    fn bit_spans_draw_a_declared_bar_a_row_and_a_used_bar_where_values_came() {
        let row = |label: &str, used: Option<(i32, i32)>, overflowed| BitSpan {
            label: label.into(),
            declared: (-4, 5),
            used,
            overflowed,
        };
        let rows = [
            row("unit.a", Some((-4, 1)), false),
            row("unit.b", None, false),
            row("unit.c", Some((-4, 5)), true),
        ];
        let svg = bit_spans_svg("unit: bits", &rows).unwrap();
        let none = bit_spans_svg("unit: bits", &[]).unwrap();
        // Three declared bars, two used ones (one red), and the legend's three swatches.
        let bars = svg.matches("<rect").count() - none.matches("<rect").count();
        assert_eq!(bars, 5);
        assert_eq!(svg.matches("fill=\"#C82828\"").count(), 2, "{svg}");
        for word in [
            "unit: bits",
            "unit.a",
            "unit.b",
            "unit.c",
            "declared",
            "overflowed",
        ] {
            assert!(svg.lines().any(|l| l.trim() == word), "{word} missing");
        }
    }

    #[test]
    fn grouped_bars_name_every_group_and_series() {
        let groups = vec!["a".to_string(), "b".to_string()];
        let series = vec![
            ("hits".to_string(), vec![1.0, 2.0]),
            ("misses".to_string(), vec![0.5, 0.0]),
        ];
        let svg = grouped_bars_svg("t", "per pixel", &groups, &series).unwrap();
        // plotters writes each text element's content on a line of its own.
        for word in ["t", "per pixel", "hits", "misses", "a", "b"] {
            assert!(svg.lines().any(|l| l.trim() == word), "{word} missing");
        }
    }
}
