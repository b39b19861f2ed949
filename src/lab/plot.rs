//! Log–log line plots with error bars (plotters), written as SVG and PNG. The PNG's text
//! uses DejaVu Sans Mono (Bitstream Vera licence, free to redistribute) compiled in, so
//! plots look the same on every machine.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use crate::image::io::write_rgb8_png;
use crate::lab::LabError;
use crate::lab::report::write_text;

/// One curve: a label and points (x, y, y_low, y_high); the bar spans [y_low, y_high].
#[derive(Clone, Debug)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// Points with their spread.
    pub points: Vec<(f64, f64, f64, f64)>,
}

/// A log–log plot.
#[derive(Clone, Debug)]
pub struct LogLogPlot {
    /// Title above the plot.
    pub title: String,
    /// x-axis description.
    pub x_label: String,
    /// y-axis description.
    pub y_label: String,
    /// The curves.
    pub curves: Vec<Curve>,
}

const SIZE: (u32, u32) = (820, 540);
pub(crate) const FONT: &str = "sans-serif";

pub(crate) fn register() -> bool {
    static DONE: OnceLock<bool> = OnceLock::new();
    *DONE.get_or_init(|| {
        register_font(
            FONT,
            FontStyle::Normal,
            include_bytes!("report/assets/DejaVuSansMono.ttf"),
        )
        .is_ok()
    })
}

/// Writes `stem.svg` and `stem.png`.
pub fn write_plot(plot: &LogLogPlot, stem: &Path) -> Result<(), LabError> {
    let fail = |e: String| LabError::Input(format!("plot {}: {e}", stem.display()));
    if !register() {
        return Err(fail("the built-in font did not load".into()));
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        draw(plot, &root).map_err(fail)?;
    }
    write_text(&stem.with_extension("svg"), &svg)?;
    let mut buffer = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        draw(plot, &root).map_err(fail)?;
    }
    write_rgb8_png(SIZE.0, SIZE.1, buffer, &stem.with_extension("png"))?;
    Ok(())
}

/// A distinct colour per curve (Tableau 10).
fn colour(i: usize) -> RGBColor {
    const C: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = C[i % C.len()];
    RGBColor(r, g, b)
}

/// The range of positive finite values, widened a little, as (low, high).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return (0.1, 10.0);
    }
    let (lo, hi) = if lo == hi {
        (lo * 0.5, hi * 2.0)
    } else {
        (lo, hi)
    };
    (lo / 1.3, hi * 1.3)
}

fn draw<DB: DrawingBackend>(
    plot: &LogLogPlot,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let xs = range(
        plot.curves
            .iter()
            .flat_map(|c| c.points.iter().map(|p| p.0)),
    );
    let ys = range(
        plot.curves
            .iter()
            .flat_map(|c| c.points.iter().flat_map(|p| [p.1, p.2, p.3])),
    );
    let mut chart = ChartBuilder::on(root)
        .caption(&plot.title, (FONT, 20))
        .margin(14)
        .x_label_area_size(44)
        .y_label_area_size(80)
        .build_cartesian_2d((xs.0..xs.1).log_scale(), (ys.0..ys.1).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(&plot.x_label)
        .y_desc(&plot.y_label)
        .label_style((FONT, 13))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v}"))
        .draw()
        .map_err(e)?;
    for (i, curve) in plot.curves.iter().enumerate() {
        let c = colour(i);
        let pts: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter(|p| p.0 > 0.0 && p.1 > 0.0 && p.1.is_finite())
            .map(|p| (p.0, p.1))
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
            .map_err(e)?
            .label(curve.label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
            .map_err(e)?;
        let bars = curve
            .points
            .iter()
            .filter(|p| p.0 > 0.0 && p.2 > 0.0 && p.3 >= p.2 && p.3.is_finite())
            .map(|p| PathElement::new(vec![(p.0, p.2), (p.0, p.3)], c.stroke_width(1)));
        chart.draw_series(bars).map_err(e)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    root.present().map_err(e)
}
