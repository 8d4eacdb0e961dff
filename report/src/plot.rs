//! PNG charts: one chart, or a figure of several panels stacked under a common title. Each panel has a
//! linear or logarithmic scale per axis and optionally equal scales on both (traced paths).
//!
//! Text is drawn with an embedded font (see Cargo.toml), so plots render the same on any machine. Sizes
//! are chosen for an image shown [`READING_WIDTH`] pixels wide. The legend goes into the first corner no
//! curve passes through; when every corner is crossed, room is added above the data for it.

use std::path::Path;
use std::sync::Once;

use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Why a chart could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw {path}: {message}")]
pub struct PlotError {
    pub path: String,
    pub message: String,
}

/// Width and height of a chart, and of each panel of a figure (panels are stacked, so every image is
/// this wide).
pub const SIZE: (u32, u32) = (1000, 700);

/// The width at which the images are meant to be read; the text sizes below are pixels at that width.
pub const READING_WIDTH: u32 = 800;
const FIGURE_TITLE_SIZE: f64 = 22.0;
const CAPTION_SIZE: f64 = 20.0;
const AXIS_TITLE_SIZE: f64 = 16.0;
const TICK_LABEL_SIZE: f64 = 14.0;
const LEGEND_SIZE: f64 = 14.0;

/// The legend's padding inside its box, the length of its line samples and the room kept for them.
const LEGEND_PADDING: f64 = 7.0;
const LEGEND_SAMPLE: f64 = 18.0;
const LEGEND_SAMPLE_ROOM: f64 = 26.0;
/// plotters puts a corner legend this many (image) pixels from the plotting area's edges.
const LEGEND_OFFSET: i32 = 5;

const FONT: &str = "sans-serif";

/// Image pixels for a length in pixels at the reading width.
fn px(reading_pixels: f64) -> u32 {
    (reading_pixels * f64::from(SIZE.0) / f64::from(READING_WIDTH)).round() as u32
}

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

impl<'a> Labels<'a> {
    pub const fn new(title: &'a str, x: &'a str, y: &'a str) -> Self {
        Labels { title, x, y }
    }
}

/// How an axis maps values to lengths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Linear,
    /// Decades; only positive values are drawn.
    Log,
}

/// One chart: its labels, curves and axes.
#[derive(Clone, Debug)]
pub struct Panel<'a> {
    pub labels: Labels<'a>,
    pub series: Vec<Series>,
    pub x_scale: Scale,
    pub y_scale: Scale,
    /// One unit has the same length on both axes (paths seen from one side, as in the paper's figures).
    pub equal_aspect: bool,
}

impl<'a> Panel<'a> {
    /// A chart with linear axes.
    pub fn new(labels: Labels<'a>, series: Vec<Series>) -> Self {
        Panel {
            labels,
            series,
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            equal_aspect: false,
        }
    }

    pub fn log_x(self) -> Self {
        Panel {
            x_scale: Scale::Log,
            ..self
        }
    }

    pub fn log_y(self) -> Self {
        Panel {
            y_scale: Scale::Log,
            ..self
        }
    }

    pub fn equal_aspect(self) -> Self {
        Panel {
            equal_aspect: true,
            ..self
        }
    }
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

/// Draws one chart of [`SIZE`].
pub fn chart(path: &Path, panel: &Panel) -> Result<(), PlotError> {
    render(path, None, std::slice::from_ref(panel))
}

/// Draws the panels one under the other, each of [`SIZE`], under a common title.
pub fn figure(path: &Path, title: &str, panels: &[Panel]) -> Result<(), PlotError> {
    render(path, Some(title), panels)
}

fn render(path: &Path, title: Option<&str>, panels: &[Panel]) -> Result<(), PlotError> {
    let error = |message: String| PlotError {
        path: path.display().to_string(),
        message,
    };
    if panels.is_empty() {
        return Err(error("no panel to draw".into()));
    }
    register_font();
    let title_band = title.map_or(0, |_| px(2.0 * FIGURE_TITLE_SIZE));
    let height = title_band + SIZE.1 * panels.len() as u32;
    let root = BitMapBackend::new(path, (SIZE.0, height)).into_drawing_area();
    let draw = || -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (band, body) = root.split_vertically(title_band);
        if let Some(title) = title {
            let style = TextStyle::from((FONT, px(FIGURE_TITLE_SIZE))).pos(Pos::new(HPos::Center, VPos::Center));
            band.draw_text(title, &style, (SIZE.0 as i32 / 2, title_band as i32 / 2))
                .map_err(|e| e.to_string())?;
        }
        for (area, panel) in body.split_evenly((panels.len(), 1)).iter().zip(panels) {
            draw_panel(area, panel)?;
        }
        root.present().map_err(|e| e.to_string())
    };
    draw().map_err(error)
}

/// A value's position along an axis: itself on a linear axis, its decimal logarithm on a log axis
/// (`None` where the axis cannot show it).
fn axis_position(scale: Scale, value: f64) -> Option<f64> {
    match scale {
        Scale::Linear => value.is_finite().then_some(value),
        Scale::Log => (value.is_finite() && value > 0.0).then(|| value.log10()),
    }
}

/// A range of axis positions.
#[derive(Clone, Copy, Debug)]
struct Span {
    low: f64,
    high: f64,
}

impl Span {
    fn length(&self) -> f64 {
        self.high - self.low
    }

    /// Grown about its centre to `length`.
    fn widened_to(&self, length: f64) -> Span {
        let grow = 0.5 * (length - self.length());
        Span {
            low: self.low - grow,
            high: self.high + grow,
        }
    }
}

/// The positions of every point a panel draws, per series. Log axes are drawn as linear axes over the
/// exponents, since plotters' own log axis drops every tick below 2.2e-16 (round-off-level plots).
fn positions(panel: &Panel) -> Vec<Vec<(f64, f64)>> {
    panel
        .series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .filter_map(|&(x, y)| Some((axis_position(panel.x_scale, x)?, axis_position(panel.y_scale, y)?)))
                .collect()
        })
        .collect()
}

/// The span covering the positions, padded by 5 % on a linear axis and widened to whole decades on a
/// log axis (so ticks fall on powers of ten).
fn data_span(positions: impl Iterator<Item = f64>, scale: Scale) -> Span {
    let (low, high) = positions.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !low.is_finite() {
        // Nothing to show: a unit range, or 1e-16 to 1 (round-off to order one) on a log axis.
        return match scale {
            Scale::Linear => Span { low: 0.0, high: 1.0 },
            Scale::Log => Span { low: -16.0, high: 0.0 },
        };
    }
    match scale {
        Scale::Linear => {
            let pad = (0.05 * (high - low)).max(1e-9);
            Span {
                low: low - pad,
                high: high + pad,
            }
        }
        Scale::Log => Span {
            low: low.floor(),
            high: high.ceil().max(low.floor() + 1.0),
        },
    }
}

/// Widens the narrower span so one unit has the same length on both axes of a plotting area of
/// `width` × `height` pixels.
fn equal_aspect(x: Span, y: Span, (width, height): (u32, u32)) -> (Span, Span) {
    let aspect = f64::from(width) / f64::from(height);
    if x.length() / y.length() < aspect {
        (x.widened_to(y.length() * aspect), y)
    } else {
        (x, y.widened_to(x.length() / aspect))
    }
}

/// Whether any drawn line or marker passes through the rectangle `[left, right] × [top, bottom]` (pixels
/// of a plotting area of `size`, y downwards).
fn crosses(curves: &[Vec<(f64, f64)>], x: Span, y: Span, size: (u32, u32), rect: [f64; 4]) -> bool {
    let [left, top, right, bottom] = rect;
    let to_pixels = |&(px, py): &(f64, f64)| {
        (
            (px - x.low) / x.length() * f64::from(size.0),
            (y.high - py) / y.length() * f64::from(size.1),
        )
    };
    let inside = |(u, v): (f64, f64)| (left..=right).contains(&u) && (top..=bottom).contains(&v);
    curves.iter().any(|curve| {
        let pixels: Vec<(f64, f64)> = curve.iter().map(to_pixels).collect();
        pixels.iter().any(|&p| inside(p))
            || pixels.windows(2).any(|pair| {
                // Test points along the segment every 2 pixels or so.
                let (a, b) = (pair[0], pair[1]);
                let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) / 2.0).ceil().min(2000.0) as usize;
                (1..steps).any(|k| {
                    let s = k as f64 / steps as f64;
                    inside((a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1)))
                })
            })
    })
}

/// The legend's corner, adding room above the data (so growing `y`) when every corner is crossed.
fn place_legend(
    curves: &[Vec<(f64, f64)>],
    (x, y): (Span, &mut Span),
    plot: (u32, u32),
    legend: (u32, u32),
) -> SeriesLabelPosition {
    let (width, height) = (f64::from(plot.0), f64::from(plot.1));
    let (w, h) = (f64::from(legend.0), f64::from(legend.1));
    // The box with a few pixels of clearance around it.
    let (margin, clearance) = (f64::from(LEGEND_OFFSET), 4.0);
    let (left, right) = (margin - clearance, margin + w + clearance);
    let (top, bottom) = (margin - clearance, margin + h + clearance);
    let corners = [
        (
            SeriesLabelPosition::UpperRight,
            [width - right, top, width - left, bottom],
        ),
        (SeriesLabelPosition::UpperLeft, [left, top, right, bottom]),
        (
            SeriesLabelPosition::LowerRight,
            [width - right, height - bottom, width - left, height - top],
        ),
        (
            SeriesLabelPosition::LowerLeft,
            [left, height - bottom, right, height - top],
        ),
    ];
    if let Some((corner, _)) = corners.iter().find(|(_, rect)| !crosses(curves, x, *y, plot, *rect)) {
        return corner.clone();
    }
    // Raise the top so the data stay below the band the legend takes: the band is the fraction f of the
    // new span, (high' − high) = f (high' − low).
    let band = bottom / height;
    if band < 0.5 {
        y.high = (y.high - band * y.low) / (1.0 - band);
    }
    SeriesLabelPosition::UpperRight
}

/// The legend's size in pixels, as plotters lays it out (text block plus sample room and padding).
fn legend_size(panel: &Panel) -> Result<(u32, u32), String> {
    let style: TextStyle = (FONT, px(LEGEND_SIZE)).into();
    let mut text = plotters::element::MultiLineText::<(i32, i32), &str>::new((0, 0), &style);
    for series in panel.series.iter().filter(|s| !s.label.is_empty()) {
        text.push_line(series.label.as_str());
    }
    let (w, h) = text.estimate_dimension().map_err(|e| e.to_string())?;
    let padding = 2 * px(LEGEND_PADDING);
    Ok((w as u32 + px(LEGEND_SAMPLE_ROOM) + padding, h as u32 + padding))
}

fn draw_panel(area: &DrawingArea<BitMapBackend<'_>, Shift>, panel: &Panel) -> Result<(), String> {
    let margin = px(14.0) as i32;
    let area = area
        .margin(margin, margin, margin, margin)
        .titled(panel.labels.title, (FONT, px(CAPTION_SIZE)))
        .map_err(|e| e.to_string())?;
    let builder = || {
        let mut builder = ChartBuilder::on(&area);
        builder.x_label_area_size(px(46.0)).y_label_area_size(px(70.0));
        builder
    };
    // The plotting area's size does not depend on the ranges: measure it on a provisional chart.
    let plot = builder()
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(|e| e.to_string())?
        .plotting_area()
        .dim_in_pixel();

    let curves = positions(panel);
    let points = || curves.iter().flatten();
    let (mut x, mut y) = (
        data_span(points().map(|p| p.0), panel.x_scale),
        data_span(points().map(|p| p.1), panel.y_scale),
    );
    if panel.equal_aspect {
        (x, y) = equal_aspect(x, y, plot);
    }
    let labelled = panel.series.iter().any(|s| !s.label.is_empty());
    let legend = if labelled {
        let position = place_legend(&curves, (x, &mut y), plot, legend_size(panel)?);
        if panel.equal_aspect {
            (x, y) = equal_aspect(x, y, plot);
        }
        Some(position)
    } else {
        None
    };
    if panel.y_scale == Scale::Log {
        // Whole decades again after any room added for the legend.
        y.high = y.high.ceil();
    }

    let chart = builder()
        .build_cartesian_2d(x.low..x.high, y.low..y.high)
        .map_err(|e| e.to_string())?;
    draw_chart(chart, panel, &curves, legend, (x, y))
}

/// Tick labels at axis positions: powers of ten on a log axis; plotters' own on a linear axis, but without
/// the sign of a negative zero (a range centred on zero puts a tick at about −1e-17).
fn tick_labels(scale: Scale, span: Span) -> impl Fn(&f64) -> String {
    let axis = RangedCoordf64::from(span.low..span.high);
    move |position| match scale {
        Scale::Log => format!("{:.0e}", 10f64.powf(*position)),
        Scale::Linear => {
            let text = axis.format_ext(position);
            match text.strip_prefix('-') {
                Some(zero) if zero.chars().all(|c| c == '0' || c == '.') => zero.to_string(),
                _ => text,
            }
        }
    }
}

/// How many tick labels an axis gets: on a log axis at most one per decade, so plotters' linear steps
/// (1, 2, 5 × 10ᵏ) fall on whole decades.
fn tick_count(scale: Scale, span: Span) -> usize {
    const LINEAR_TICKS: usize = 10;
    match scale {
        Scale::Linear => LINEAR_TICKS,
        Scale::Log => (span.length().round() as usize + 1).min(LINEAR_TICKS),
    }
}

/// Draws the panel's curves, given at axis positions (`positions`), on a chart over those positions.
fn draw_chart<'a>(
    mut chart: ChartContext<'a, BitMapBackend<'a>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    panel: &Panel,
    curves: &[Vec<(f64, f64)>],
    legend: Option<SeriesLabelPosition>,
    (x, y): (Span, Span),
) -> Result<(), String> {
    let (x_label, y_label) = (tick_labels(panel.x_scale, x), tick_labels(panel.y_scale, y));
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(panel.labels.x)
        .y_desc(panel.labels.y)
        .label_style((FONT, px(TICK_LABEL_SIZE)))
        .axis_desc_style((FONT, px(AXIS_TITLE_SIZE)))
        .bold_line_style(BLACK.mix(0.15))
        .light_line_style(BLACK.mix(0.04))
        .x_labels(tick_count(panel.x_scale, x))
        .y_labels(tick_count(panel.y_scale, y))
        .x_label_formatter(&x_label)
        .y_label_formatter(&y_label);
    // Light lines between decades would be evenly spaced in the exponent, unlike a log scale's.
    if panel.x_scale == Scale::Log {
        mesh.x_max_light_lines(0);
    }
    if panel.y_scale == Scale::Log {
        mesh.y_max_light_lines(0);
    }
    mesh.draw().map_err(|e| e.to_string())?;

    let (line_width, marker_size) = (px(1.6), px(4.0) as i32);
    for (index, (series, points)) in panel.series.iter().zip(curves).enumerate() {
        let color = color(index);
        let style = ShapeStyle::from(&color).stroke_width(line_width);
        let sample_length = px(LEGEND_SAMPLE) as i32;
        let labelled = !series.label.is_empty();
        if series.markers_only {
            let annotation = chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| TriangleMarker::new(p, marker_size + 2, color.filled())),
                )
                .map_err(|e| e.to_string())?;
            if labelled {
                annotation.label(series.label.as_str()).legend(move |(x, y)| {
                    TriangleMarker::new((x + sample_length / 2, y), marker_size + 2, color.filled())
                });
            }
            continue;
        }
        if series.markers {
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, marker_size, color.filled())))
                .map_err(|e| e.to_string())?;
        }
        // One element per segment: plotters draws a wide polyline as one polygon with unlimited mitre joins,
        // which shoots spikes far out of the chart at sharp turns (round-off noise) and leaves holes where a
        // long path crosses itself (a precession circle traced twice).
        let segments = points.windows(2).map(|pair| PathElement::new(pair.to_vec(), style));
        let annotation = chart.draw_series(segments).map_err(|e| e.to_string())?;
        if labelled {
            annotation
                .label(series.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + sample_length, y)], style));
        }
    }
    if let Some(position) = legend {
        chart
            .configure_series_labels()
            .position(position)
            .label_font((FONT, px(LEGEND_SIZE)))
            .legend_area_size(px(LEGEND_SAMPLE_ROOM))
            .margin(px(LEGEND_PADDING))
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}
