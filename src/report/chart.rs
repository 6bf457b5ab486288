//! Charts as PNG bytes: error (log) against run time (log) or view angle (linear).
//!
//! Text is drawn with the Hack font that `epaint_default_fonts` bundles (through plotters'
//! `ab_glyph` backend), so no system font is needed.

use image::ImageEncoder;
use image::codecs::png::PngEncoder;
use plotters::coord::combinators::IntoLogRange;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
#[cfg(not(target_arch = "wasm32"))]
use plotters::style::{FontStyle, register_font};

use super::measure::{Row, Study, Vector};
use super::surfaces::Region;

/// The x axis of the tangent and kernel charts.
const SECONDS_PER_SURFACE: &str = "median run time per surface (s)";
/// Chart size in pixels.
const SIZE: (u32, u32) = (1100, 760);
/// Errors below this many degrees (the analytic frame's ≈ 0) are drawn at it.
pub const ERROR_FLOOR_DEGREES: f64 = 1e-6;
/// One colour per method, in the order methods first appear.
pub(super) const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(227, 119, 194),
];

/// How a series's points are marked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Marker {
    Circle,
    Triangle,
    /// No marker: a line alone (a floor, a front), drawn thicker.
    Line,
    /// Circles alone, not joined (a scatter).
    Dots,
}

/// One line of points, in the order they are joined.
pub(super) struct Series {
    pub(super) label: String,
    pub(super) colour: RGBColor,
    pub(super) marker: Marker,
    /// `(x, y)`; y positive (a log axis), x positive where the x axis is logarithmic.
    pub(super) points: Vec<(f64, f64)>,
}

/// The x axis: logarithmic (run times) or linear (angles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum XAxis {
    Log,
    Linear,
}

/// Why a chart could not be made.
#[derive(Debug, Clone, thiserror::Error)]
pub enum ChartError {
    #[error("the bundled Hack font did not load")]
    Font,
    #[error("drawing the chart {title:?}: {reason}")]
    Draw { title: String, reason: String },
    #[error("encoding the chart {title:?}: {reason}")]
    Encode { title: String, reason: String },
}

#[cfg(not(target_arch = "wasm32"))]
fn register_hack_font() -> Result<(), ChartError> {
    use std::sync::OnceLock;
    static REGISTERED: OnceLock<Result<(), ChartError>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            register_font("sans-serif", FontStyle::Normal, epaint_default_fonts::HACK_REGULAR)
                .map_err(|_| ChartError::Font)
        })
        .clone()
}

/// The web build cannot register fonts with plotters (it has no `register_font` on wasm32):
/// no charts there.
#[cfg(target_arch = "wasm32")]
fn register_hack_font() -> Result<(), ChartError> {
    Err(ChartError::Font)
}

/// Series of `study`'s rows over `surfaces` and region `All`: one per (method, surface),
/// the mean error of `vector` against the median run time.
fn series(rows: &[Row], study: Study, surfaces: &[&str], vector: Vector) -> Vec<Series> {
    let mut methods: Vec<&str> = vec![];
    for row in rows.iter().filter(|r| r.study == study) {
        if !methods.contains(&row.method) {
            methods.push(row.method);
        }
    }
    let mut result = vec![];
    for (index, method) in methods.iter().enumerate() {
        for surface in surfaces {
            let mut points: Vec<(u32, f64, f64)> = rows
                .iter()
                .filter(|r| r.study == study && r.method == *method && r.surface == *surface && r.region == Region::All)
                .filter_map(|r| r.error(vector).map(|e| (r.resolution, r.seconds, e.mean as f64)))
                .collect();
            points.sort_by_key(|p| p.0);
            result.push(Series {
                label: if surfaces.len() > 1 { format!("{method} · {surface}") } else { method.to_string() },
                colour: COLOURS[index % COLOURS.len()],
                marker: if *surface == "torus" { Marker::Triangle } else { Marker::Circle },
                points: points.into_iter().map(|(_, s, e)| (s.max(1e-9), e.max(ERROR_FLOOR_DEGREES))).collect(),
            });
        }
    }
    result
}

/// `(low, high)` of positive `values`, widened to whole decades and a little beyond, so that
/// the outermost decade labels are drawn.
fn decades(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if low > high {
        return (1e-6, 1.0);
    }
    (10f64.powf(low.log10().floor()) / 1.5, 10f64.powf((high.log10() + 1e-9).ceil()) * 1.5)
}

fn draw(buffer: &mut [u8], title: &str, axes: [&str; 2], series: &[Series], x_axis: XAxis) -> Result<(), ChartError> {
    let failed = |e: &dyn std::fmt::Display| ChartError::Draw { title: title.to_owned(), reason: e.to_string() };
    // The buffer comes white: filling it through the backend, pixel by pixel, is most of an
    // unoptimised build's time per chart.
    let root = BitMapBackend::with_buffer(buffer, SIZE).into_drawing_area();
    let xs = || series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let (y0, y1) = decades(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    let mut builder = ChartBuilder::on(&root);
    builder.caption(title, ("sans-serif", 22)).margin(16).x_label_area_size(50).y_label_area_size(80);
    match x_axis {
        XAxis::Log => {
            let (x0, x1) = decades(xs());
            let chart =
                builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale()).map_err(|e| failed(&e))?;
            finish(chart, axes, series, &|v| format!("{v:.0e}"), &failed)?;
        }
        XAxis::Linear => {
            let (x0, x1) = xs().fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
            let (x0, x1) = if x0 < x1 { (x0, x1) } else { (0.0, 1.0) };
            let pad = 0.03 * (x1 - x0);
            let chart = builder.build_cartesian_2d(x0 - pad..x1 + pad, (y0..y1).log_scale()).map_err(|e| failed(&e))?;
            finish(chart, axes, series, &|v| format!("{v:.0}"), &failed)?;
        }
    }
    root.present().map_err(|e| failed(&e))
}

/// The mesh, the series and the legend of a chart whose axes are built.
fn finish<'a, X, Y>(
    mut chart: ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    axes: [&str; 2],
    series: &[Series],
    x_labels: &dyn Fn(&f64) -> String,
    failed: &dyn Fn(&dyn std::fmt::Display) -> ChartError,
) -> Result<(), ChartError>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(axes[0])
        .y_desc(axes[1])
        .x_label_formatter(x_labels)
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| failed(&e))?;
    for s in series {
        let colour = s.colour;
        if s.marker == Marker::Dots {
            let dots = s.points.iter().map(|&p| Circle::new(p, 5, colour.filled()));
            let legend = chart.draw_series(dots).map_err(|e| failed(&e))?.label(&s.label);
            legend.legend(move |(x, y)| Circle::new((x + 9, y), 5, colour.filled()));
            continue;
        }
        let width = if s.marker == Marker::Line { 4 } else { 2 };
        let line = LineSeries::new(s.points.iter().copied(), colour.stroke_width(width));
        let legend = chart.draw_series(line).map_err(|e| failed(&e))?.label(&s.label);
        let stroke =
            move |at| EmptyElement::at(at) + PathElement::new(vec![(0, 0), (18, 0)], colour.stroke_width(width));
        match s.marker {
            Marker::Triangle => {
                legend.legend(move |at| stroke(at) + TriangleMarker::new((9, 0), 6, colour.filled()));
                let markers = s.points.iter().map(|&p| TriangleMarker::new(p, 6, colour.filled()));
                chart.draw_series(markers).map_err(|e| failed(&e))?;
            }
            Marker::Circle => {
                legend.legend(move |at| stroke(at) + Circle::new((9, 0), 4, colour.filled()));
                let markers = s.points.iter().map(|&p| Circle::new(p, 4, colour.filled()));
                chart.draw_series(markers).map_err(|e| failed(&e))?;
            }
            // Dots are drawn above, alone.
            Marker::Line | Marker::Dots => {
                legend.legend(stroke);
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()
        .map_err(|e| failed(&e))
}

/// A chart of `series` as PNG bytes, y logarithmic; `axes`: the x and y axis labels.
pub(super) fn png(title: &str, axes: [&str; 2], series: &[Series], x_axis: XAxis) -> Result<Vec<u8>, ChartError> {
    register_hack_font()?;
    let mut rgb = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    draw(&mut rgb, title, axes, series, x_axis)?;
    let mut bytes = vec![];
    PngEncoder::new(&mut bytes)
        .write_image(&rgb, SIZE.0, SIZE.1, image::ExtendedColorType::Rgb8)
        .map_err(|e| ChartError::Encode { title: title.to_owned(), reason: e.to_string() })?;
    Ok(bytes)
}

/// Tangent methods on the sphere (circles) and torus (triangles): mean T error over all
/// vertices against run time, one point per resolution.
pub fn tangent_chart(rows: &[Row]) -> Result<Vec<u8>, ChartError> {
    let series = series(rows, Study::Tangents, &["sphere", "torus"], Vector::Tangent);
    let title = "Tangent methods: mean T error vs run time (one point per resolution)";
    png(title, [SECONDS_PER_SURFACE, "mean angular error of T, all vertices (°)"], &series, XAxis::Log)
}

/// Height kernels on the sine-bump plane (float heights, wrapped): mean normal error against
/// run time, one point per texels-per-period.
pub fn kernel_chart(rows: &[Row]) -> Result<Vec<u8>, ChartError> {
    let series = series(rows, Study::Kernels, &["plane"], Vector::Normal);
    let title = "Height kernels: mean normal error vs run time (one point per texels/period)";
    png(title, [SECONDS_PER_SURFACE, "mean angular error of N (°)"], &series, XAxis::Log)
}
