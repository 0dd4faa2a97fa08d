//! PNG plots for the report, drawn with `plotters`. Text uses a font shipped inside a crate
//! (Hack, from `epaint_default_fonts`), so no system font is needed.

use plotters::prelude::*;
use std::collections::BTreeMap;
use std::sync::Once;

const FONT: &str = "texrtl-sans";

fn register() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font(
            FONT,
            FontStyle::Normal,
            epaint_default_fonts::HACK_REGULAR,
        );
    });
}

/// A bar chart of an error histogram (error in LSBs -> count, log-scaled counts), as PNG.
pub fn histogram_png(title: &str, hist: &BTreeMap<i64, u64>) -> Result<Vec<u8>, String> {
    register();
    let (w, h) = (640u32, 360u32);
    let mut buf = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let lo = hist.keys().next().copied().unwrap_or(0).min(-1);
        let hi = hist.keys().last().copied().unwrap_or(0).max(1);
        let top = hist.values().copied().max().unwrap_or(1).max(1) as f64;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FONT, 18))
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
            .label_style((FONT, 13))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .axis_desc_style((FONT, 14))
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
    let img = image::RgbImage::from_raw(w, h, buf).ok_or("plot buffer")?;
    crate::commands::encode_png(&img)
}
