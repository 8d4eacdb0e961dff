//! PNG charts for the report: work-precision diagrams (log–log), quantities over time (log y) and
//! traced paths (equal-aspect x–y views). Text is drawn with an embedded font (see Cargo.toml), so
//! plots render the same on any machine.

use std::ops::Range;
use std::path::Path;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;

/// Why a chart could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw {path}: {message}")]
pub struct PlotError {
    pub path: String,
    pub message: String,
}

/// Width and height of every chart: readable at 800 px.
pub const SIZE: (u32, u32) = (1000, 700);

const FONT: &str = "sans-serif";

fn register_font() {
    static REGISTERED: Once = Once::new();
    REGISTERED.call_once(|| {
        // The bytes are a valid TrueType font shipped by the crate; a failure would leave text blank
        // rather than stop the report.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
    });
}

/// One labelled curve.
#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points as well as the line (for sparse data such as dt sweeps).
    pub markers: bool,
    /// Draw only markers (reference points such as MuJoCo's).
    pub markers_only: bool,
}

impl Series {
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            markers: false,
            markers_only: false,
        }
    }
}

/// Axis titles (with units) and the chart title.
#[derive(Clone, Debug)]
pub struct Labels<'a> {
    pub title: &'a str,
    pub x: &'a str,
    pub y: &'a str,
}

/// A palette that stays distinguishable for up to twelve curves.
fn color(index: usize) -> RGBColor {
    const PALETTE: [RGBColor; 12] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(23, 190, 207),
        RGBColor(188, 189, 34),
        RGBColor(127, 127, 127),
        RGBColor(0, 0, 0),
        RGBColor(255, 187, 120),
    ];
    PALETTE[index % PALETTE.len()]
}

fn error(path: &Path, message: impl ToString) -> PlotError {
    PlotError {
        path: path.display().to_string(),
        message: message.to_string(),
    }
}

/// The range covering every finite point (positive only on a log axis), padded.
fn bounds(series: &[Series], axis: fn(&(f64, f64)) -> f64, log: bool) -> Range<f64> {
    let values = series
        .iter()
        .flat_map(|s| s.points.iter().map(axis))
        .filter(|v| v.is_finite() && (!log || *v > 0.0));
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !low.is_finite() {
        return if log { 1e-16..1.0 } else { 0.0..1.0 };
    }
    if log {
        // Whole decades, so ticks fall on powers of ten.
        let (low, high) = (low.log10().floor(), high.log10().ceil().max(low.log10().floor() + 1.0));
        10f64.powf(low)..10f64.powf(high)
    } else {
        let pad = ((high - low) * 0.05).max(1e-9);
        (low - pad)..(high + pad)
    }
}

fn draw_series<'a, DB: DrawingBackend + 'a, CT: CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'a, DB, CT>,
    series: &[Series],
    keep: impl Fn(&(f64, f64)) -> bool,
    legend: SeriesLabelPosition,
) -> Result<(), String> {
    for (index, s) in series.iter().enumerate() {
        let color = color(index);
        let points: Vec<(f64, f64)> = s.points.iter().copied().filter(|p| keep(p)).collect();
        let style = ShapeStyle::from(&color).stroke_width(2);
        if s.markers_only {
            chart
                .draw_series(points.iter().map(|&p| TriangleMarker::new(p, 9, color.filled())))
                .map_err(|e| e.to_string())?
                .label(s.label.as_str())
                .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 8, color.filled()));
            continue;
        }
        chart
            .draw_series(LineSeries::new(points.clone(), style))
            .map_err(|e| e.to_string())?
            .label(s.label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        if s.markers {
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(|e| e.to_string())?;
        }
    }
    chart
        .configure_series_labels()
        .position(legend)
        .label_font((FONT, 15))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())
}

fn canvas(path: &Path) -> DrawingArea<BitMapBackend<'_>, Shift> {
    register_font();
    BitMapBackend::new(path, SIZE).into_drawing_area()
}

/// A log–log chart (work-precision diagrams: error against CPU time).
pub fn log_log(path: &Path, labels: &Labels, series: &[Series]) -> Result<(), PlotError> {
    let root = canvas(path);
    let draw = || -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(labels.title, (FONT, 26))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(
                bounds(series, |p| p.0, true).log_scale(),
                bounds(series, |p| p.1, true).log_scale(),
            )
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(labels.x)
            .y_desc(labels.y)
            .label_style((FONT, 18))
            .axis_desc_style((FONT, 20))
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| e.to_string())?;
        // Work-precision curves run from cheap-and-coarse to costly-and-accurate: the lower left is empty.
        draw_series(
            &mut chart,
            series,
            |p| p.0 > 0.0 && p.1 > 0.0,
            SeriesLabelPosition::LowerLeft,
        )?;
        root.present().map_err(|e| e.to_string())
    };
    draw().map_err(|message| error(path, message))
}

/// A chart with a linear x axis and a logarithmic y axis (drift and violation over time).
pub fn linear_log(path: &Path, labels: &Labels, series: &[Series]) -> Result<(), PlotError> {
    let root = canvas(path);
    let draw = || -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(labels.title, (FONT, 26))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(
                bounds(series, |p| p.0, false),
                bounds(series, |p| p.1, true).log_scale(),
            )
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(labels.x)
            .y_desc(labels.y)
            .label_style((FONT, 18))
            .axis_desc_style((FONT, 20))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| e.to_string())?;
        // Drift and violation grow with time: the upper left stays clear longest.
        draw_series(&mut chart, series, |p| p.1 > 0.0, SeriesLabelPosition::UpperLeft)?;
        root.present().map_err(|e| e.to_string())
    };
    draw().map_err(|message| error(path, message))
}

/// A linear chart with equal scales on both axes (traced paths, like the paper's figures).
pub fn path_view(path: &Path, labels: &Labels, series: &[Series]) -> Result<(), PlotError> {
    linear(path, labels, series, true)
}

/// A linear chart; with `equal_aspect` one unit has the same length on both axes.
pub fn linear(path: &Path, labels: &Labels, series: &[Series], equal_aspect: bool) -> Result<(), PlotError> {
    let root = canvas(path);
    let draw = || -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (x, y) = (bounds(series, |p| p.0, false), bounds(series, |p| p.1, false));
        // Equal aspect: widen the narrower range to the chart's proportions.
        let aspect = (SIZE.0 - 130) as f64 / (SIZE.1 - 140) as f64;
        let (width, height) = (x.end - x.start, y.end - y.start);
        let (x, y) = if !equal_aspect {
            (x, y)
        } else if width / height < aspect {
            let grow = (height * aspect - width) / 2.0;
            (x.start - grow..x.end + grow, y)
        } else {
            let grow = (width / aspect - height) / 2.0;
            (x, y.start - grow..y.end + grow)
        };
        let mut chart = ChartBuilder::on(&root)
            .caption(labels.title, (FONT, 26))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(70)
            .build_cartesian_2d(x, y)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(labels.x)
            .y_desc(labels.y)
            .label_style((FONT, 18))
            .axis_desc_style((FONT, 20))
            .draw()
            .map_err(|e| e.to_string())?;
        draw_series(&mut chart, series, |_| true, SeriesLabelPosition::UpperRight)?;
        root.present().map_err(|e| e.to_string())
    };
    draw().map_err(|message| error(path, message))
}
