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
