//! PNG charts: one chart, or a figure of several panels (small multiples) stacked under a common title, with
//! shared axes so the panels compare at a glance. Each panel has a linear or logarithmic scale per axis and
//! optionally equal scales on both (traced paths).
//!
//! Every panel's legend stands to the right of its plotting area, never over the data. Colours come from the
//! Okabe–Ito palette (distinguishable with the common colour-vision deficiencies); a panel uses at most
//! [`MAX_COLOURS_PER_AXIS`] colours and never repeats one ([`series_colours`]). Reference series (a reference
//! path, MuJoCo's points) are black and drawn over the others: a path as a thick dashed line, so the simulated
//! curve under it shows through the gaps.
//!
//! Text is drawn with an embedded font (see Cargo.toml), so plots render the same on any machine. Sizes
//! are chosen for an image shown [`READING_WIDTH`] pixels wide.

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
    pub(crate) path: String,
    pub(crate) message: String,
}

/// Width and height of a single chart; a figure's panels are as wide and [`FIGURE_PANEL_HEIGHT`] high.
pub const SIZE: (u32, u32) = (1000, 700);
/// The height of each panel of a figure of several panels.
pub const FIGURE_PANEL_HEIGHT: u32 = 560;

/// The width at which the images are meant to be read; the text sizes below are pixels at that width.
pub const READING_WIDTH: u32 = 800;
pub(crate) const FIGURE_TITLE_SIZE: f64 = 22.0;
const CAPTION_SIZE: f64 = 19.0;
pub(crate) const AXIS_TITLE_SIZE: f64 = 16.0;
pub(crate) const TICK_LABEL_SIZE: f64 = 14.0;
pub(crate) const LEGEND_SIZE: f64 = 14.0;
pub(crate) const NOTE_SIZE: f64 = 13.0;

/// The legend's line samples, the room kept for them before the text, the gap between the plotting area and
/// the legend, and the widest a legend may be (longer labels wrap), all at the reading width.
const LEGEND_SAMPLE: f64 = 24.0;
const LEGEND_SAMPLE_ROOM: f64 = 32.0;
const LEGEND_GAP: f64 = 14.0;
const LEGEND_MAX_WIDTH: f64 = 210.0;

pub(crate) const FONT: &str = "sans-serif";

/// The Okabe–Ito colours, in pairs of a dark and a light shade of one hue (blue, vermilion, green/purple), so a
/// caller can give two variants of one thing (e.g. PGA and CGA runs of one integrator) one hue.
pub const PALETTE: [RGBColor; 6] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(213, 94, 0),    // vermilion
    RGBColor(230, 159, 0),   // orange
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
];
/// The colour of reference series.
pub(crate) const REFERENCE_COLOUR: RGBColor = RGBColor(0, 0, 0);
/// The colour of notes and captions.
pub(crate) const NOTE_COLOUR: RGBColor = RGBColor(60, 60, 60);
/// The most colours (reference black included) one panel may use.
pub const MAX_COLOURS_PER_AXIS: usize = 6;

/// Image pixels for a length in pixels at the reading width.
pub(crate) fn px(reading_pixels: f64) -> u32 {
    (reading_pixels * f64::from(SIZE.0) / f64::from(READING_WIDTH)).round() as u32
}

pub(crate) fn register_font() {
    static REGISTERED: Once = Once::new();
    REGISTERED.call_once(|| {
        // The bytes are a valid TrueType font shipped by the crate; a failure would leave text blank
        // rather than stop the report.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
    });
}

/// The marker drawn at a series' points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shape {
    /// ●, the default.
    #[default]
    Circle,
    /// ■
    Square,
    /// ▲, as reference points.
    Triangle,
    /// ◆
    Diamond,
}

/// One labelled curve.
#[derive(Clone, Debug)]
pub struct Series {
    /// The legend entry.
    pub label: String,
    /// (x, y) in the axes' units, joined in this order.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points as well as the line (for sparse data such as dt sweeps).
    pub markers: bool,
    /// Draw only markers (reference points such as MuJoCo's).
    pub markers_only: bool,
    /// The markers' shape.
    pub shape: Shape,
    /// Draw the line dashed (so an identical curve drawn before it shows through the gaps).
    pub dashed: bool,
    /// A reference: black, drawn over every other series; a line is thick and dashed.
    pub reference: bool,
    /// A line twice the usual width (a run drawn under a reference path, so it shows on both sides of the dashes).
    pub thick: bool,
    /// A fixed entry of [`PALETTE`], so a series keeps its colour from panel to panel; `None`: the first entry no
    /// other series of the panel takes.
    pub slot: Option<usize>,
}

impl Series {
    /// A plain line in the panel's next free colour; set the other fields with struct update syntax.
    ///
    /// ```
    /// use report::plot::Series;
    ///
    /// let sweep = Series {
    ///     markers: true, // sparse points: mark each one
    ///     ..Series::line("RK4, PGA", vec![(1e-3, 1e-6), (1e-2, 1e-10)])
    /// };
    /// assert_eq!((sweep.label.as_str(), sweep.points.len()), ("RK4, PGA", 2));
    /// assert!(!sweep.dashed && !sweep.reference && sweep.slot.is_none());
    /// ```
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            markers: false,
            markers_only: false,
            shape: Shape::Circle,
            dashed: false,
            reference: false,
            thick: false,
            slot: None,
        }
    }

    /// A reference path: a thick dashed black line drawn over the other series.
    pub(crate) fn reference_line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            reference: true,
            ..Series::line(label, points)
        }
    }

    /// Reference points (such as MuJoCo's): black triangles drawn over the other series.
    pub(crate) fn reference_points(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            reference: true,
            markers_only: true,
            shape: Shape::Triangle,
            ..Series::line(label, points)
        }
    }
}

/// Axis titles (with units) and the chart title.
#[derive(Clone, Debug)]
pub struct Labels<'a> {
    /// Above the plotting area.
    pub title: &'a str,
    /// The x axis title, with its unit: "time (s)".
    pub x: &'a str,
    /// The y axis title, with its unit.
    pub y: &'a str,
}

impl<'a> Labels<'a> {
    /// The labels in reading order: title, x axis, y axis.
    ///
    /// ```
    /// use report::plot::Labels;
    ///
    /// let labels = Labels::new("Energy drift", "time (s)", "|E(t) − E₀| / |E₀|");
    /// assert_eq!((labels.title, labels.x), ("Energy drift", "time (s)"));
    /// ```
    pub const fn new(title: &'a str, x: &'a str, y: &'a str) -> Self {
        Labels { title, x, y }
    }
}

/// How an axis maps values to lengths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scale {
    Linear,
    /// Decades; only positive values are drawn (or, with a floor, values from zero up).
    Log,
}

/// One chart: its labels, curves and axes.
#[derive(Clone, Debug)]
pub struct Panel<'a> {
    pub(crate) labels: Labels<'a>,
    pub(crate) series: Vec<Series>,
    pub(crate) x_scale: Scale,
    pub(crate) y_scale: Scale,
    /// One unit has the same length on both axes (paths seen from one side, as in the paper's figures).
    pub(crate) equal_aspect: bool,
    /// On a log y axis: values from zero up to this floor (exact zeros included) are drawn at the floor, which the
    /// panel's note states.
    pub(crate) floor: Option<f64>,
    /// A line or two under the panel.
    pub(crate) note: Option<String>,
}

impl<'a> Panel<'a> {
    /// A chart with linear axes; the methods below change them.
    ///
    /// ```
    /// use report::plot::{chart, Labels, Panel, Series};
    ///
    /// let drift = Series::line("RK4", vec![(0.0, 1e-16), (5.0, 1e-12), (10.0, 1e-10)]);
    /// let panel = Panel::new(Labels::new("Energy drift", "time (s)", "|E(t) − E₀| / |E₀|"), vec![drift]).log_y();
    /// let path = std::env::temp_dir().join("report-doc-panel.png");
    /// chart(&path, &panel)?;
    /// assert!(std::fs::metadata(&path)?.len() > 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(labels: Labels<'a>, series: Vec<Series>) -> Self {
        Panel {
            labels,
            series,
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            equal_aspect: false,
            floor: None,
            note: None,
        }
    }

    /// A logarithmic x axis: decades, only positive values drawn.
    pub fn log_x(self) -> Self {
        Panel {
            x_scale: Scale::Log,
            ..self
        }
    }

    /// A logarithmic y axis: decades, only positive values drawn.
    pub fn log_y(self) -> Self {
        Panel {
            y_scale: Scale::Log,
            ..self
        }
    }

    /// A log y axis on which values below `floor`, zeros included, are drawn at `floor`.
    pub(crate) fn log_y_with_floor(self, floor: f64) -> Self {
        Panel {
            y_scale: Scale::Log,
            floor: Some(floor),
            ..self
        }
    }

    /// One unit as long on both axes, for paths seen from one side.
    pub fn equal_aspect(self) -> Self {
        Panel {
            equal_aspect: true,
            ..self
        }
    }

    pub(crate) fn note(self, note: impl Into<String>) -> Self {
        Panel {
            note: Some(note.into()),
            ..self
        }
    }

    /// The note drawn under the panel: its own, and what the floor does.
    fn full_note(&self) -> Option<String> {
        let floor = self
            .floor
            .filter(|_| self.y_scale == Scale::Log)
            .map(|f| format!("Values below {f:.0e}, exact zeros included, are drawn at {f:.0e}."));
        match (&self.note, floor) {
            (Some(note), Some(floor)) => Some(format!("{note} {floor}")),
            (Some(note), None) => Some(note.clone()),
            (None, floor) => floor,
        }
    }
}

/// The colour of each series of one panel: black for references; [`PALETTE`]`[slot]` for a series with a slot;
/// the first free palette entries, in order, for the others. An error if a slot is out of the palette, two
/// series would share a colour, or the panel would use more than [`MAX_COLOURS_PER_AXIS`] colours.
pub fn series_colours(series: &[Series]) -> Result<Vec<RGBColor>, String> {
    let mut taken = [false; PALETTE.len()];
    for s in series.iter().filter(|s| !s.reference) {
        if let Some(slot) = s.slot {
            if slot >= PALETTE.len() {
                return Err(format!("series {:?}: palette slot {slot} out of range", s.label));
            }
            if std::mem::replace(&mut taken[slot], true) {
                return Err(format!("series {:?}: palette slot {slot} is taken twice", s.label));
            }
        }
    }
    let references = series.iter().filter(|s| s.reference).count();
    if references > 1 {
        return Err(format!("{references} reference series would share black on one axis"));
    }
    if series.len() > MAX_COLOURS_PER_AXIS {
        return Err(format!(
            "{} series on one axis: at most {MAX_COLOURS_PER_AXIS} distinct colours",
            series.len()
        ));
    }
    series
        .iter()
        .map(|s| {
            if s.reference {
                return Ok(REFERENCE_COLOUR);
            }
            let slot = match s.slot {
                Some(slot) => slot,
                None => {
                    let free = taken
                        .iter()
                        .position(|t| !t)
                        .ok_or_else(|| format!("series {:?}: no palette colour left", s.label))?;
                    taken[free] = true;
                    free
                }
            };
            Ok(PALETTE[slot])
        })
        .collect()
}

/// Draws one chart of [`SIZE`].
pub fn chart(path: &Path, panel: &Panel) -> Result<(), PlotError> {
    render(path, None, std::slice::from_ref(panel), None)
}

/// Draws the panels one under the other, [`FIGURE_PANEL_HEIGHT`] high each (one panel: [`SIZE`]), under a
/// common title, with shared axes where the panels' scales agree.
pub fn figure(path: &Path, title: &str, panels: &[Panel]) -> Result<(), PlotError> {
    render(path, Some(title), panels, None)
}

/// [`figure`] with a caption under the panels (where the figure's data come from).
pub(crate) fn figure_with_caption(path: &Path, title: &str, panels: &[Panel], caption: &str) -> Result<(), PlotError> {
    render(path, Some(title), panels, Some(caption))
}

/// Lines of at most `width` pixels, broken at spaces (a word longer than that gets a line of its own; a
/// no-break space, U+00A0, does not break).
pub(crate) fn wrap(text: &str, font: &FontDesc, width: u32) -> Vec<String> {
    let fits = |line: &str| font.box_size(line).map_or(true, |(w, _)| w <= width);
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in text.split([' ', '\n', '\t']).filter(|w| !w.is_empty()) {
        let candidate = if current.is_empty() {
            word.to_owned()
        } else {
            format!("{current} {word}")
        };
        if current.is_empty() || fits(&candidate) {
            current = candidate;
        } else {
            lines.push(std::mem::replace(&mut current, word.to_owned()));
        }
    }
    if !current.is_empty() {
        lines.push(current);
    }
    lines
}

fn line_height(size: f64) -> i32 {
    (f64::from(px(size)) * 1.3).round() as i32
}

fn render(path: &Path, title: Option<&str>, panels: &[Panel], caption: Option<&str>) -> Result<(), PlotError> {
    let error = |message: String| PlotError {
        path: path.display().to_string(),
        message,
    };
    if panels.is_empty() {
        return Err(error("no panel to draw".into()));
    }
    let colours = panels
        .iter()
        .map(|p| series_colours(&p.series).map_err(|m| format!("panel {:?}: {m}", p.labels.title)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(error)?;
    register_font();
    // A note every panel of a figure shares is said once, in the caption.
    let mut notes: Vec<Option<String>> = panels.iter().map(Panel::full_note).collect();
    let mut caption = caption.map(str::to_owned);
    if panels.len() > 1 && notes[0].is_some() && notes.iter().all(|n| *n == notes[0]) {
        let shared = notes[0].take().unwrap_or_default();
        caption = Some(caption.map_or(shared.clone(), |c| format!("{shared} {c}")));
        notes.iter_mut().for_each(|n| *n = None);
    }
    let caption_font = FontDesc::from((FONT, f64::from(px(NOTE_SIZE))));
    let caption_lines = caption.map_or_else(Vec::new, |c| wrap(&c, &caption_font, SIZE.0 - 2 * px(14.0)));
    let caption_band = if caption_lines.is_empty() {
        0
    } else {
        caption_lines.len() as u32 * line_height(NOTE_SIZE) as u32 + px(16.0)
    };
    let title_band = title.map_or(0, |_| px(2.0 * FIGURE_TITLE_SIZE));
    let panel_height = if panels.len() == 1 { SIZE.1 } else { FIGURE_PANEL_HEIGHT };
    let height = title_band + panel_height * panels.len() as u32 + caption_band;
    let root = BitMapBackend::new(path, (SIZE.0, height)).into_drawing_area();
    let shared = shared_spans(panels);
    // One legend width for every panel, so shared axes line up.
    let legend_width = panels.iter().map(|p| legend_layout(p).1).max().unwrap_or(0);
    let draw = || -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (band, rest) = root.split_vertically(title_band);
        if let Some(title) = title {
            let style = TextStyle::from((FONT, px(FIGURE_TITLE_SIZE))).pos(Pos::new(HPos::Center, VPos::Center));
            band.draw_text(title, &style, (SIZE.0 as i32 / 2, title_band as i32 / 2))
                .map_err(|e| e.to_string())?;
        }
        let (body, caption_area) = rest.split_vertically(panel_height * panels.len() as u32);
        let areas = body.split_evenly((panels.len(), 1));
        for (((area, panel), colours), note) in areas.iter().zip(panels).zip(&colours).zip(&notes) {
            draw_panel(area, panel, colours, note.as_deref(), (shared, legend_width))?;
        }
        let style = TextStyle::from(caption_font.clone()).color(&NOTE_COLOUR);
        for (k, line) in caption_lines.iter().enumerate() {
            caption_area
                .draw_text(
                    line,
                    &style,
                    (px(14.0) as i32, px(4.0) as i32 + k as i32 * line_height(NOTE_SIZE)),
                )
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())
    };
    draw().map_err(error)
}

/// A value's position along an axis: itself on a linear axis, its decimal logarithm on a log axis (`None`
/// where the axis cannot show it); on a log axis with a floor, values from zero to the floor sit at the floor.
fn axis_position(scale: Scale, value: f64, floor: Option<f64>) -> Option<f64> {
    match (scale, floor) {
        (Scale::Linear, _) => value.is_finite().then_some(value),
        (Scale::Log, Some(floor)) if value.is_finite() && value >= 0.0 => Some(value.max(floor).log10()),
        (Scale::Log, _) => (value.is_finite() && value > 0.0).then(|| value.log10()),
    }
}

/// A range of axis positions.
#[derive(Clone, Copy, Debug, PartialEq)]
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

    fn union(&self, other: &Span) -> Span {
        Span {
            low: self.low.min(other.low),
            high: self.high.max(other.high),
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
                .filter_map(|&(x, y)| {
                    Some((
                        axis_position(panel.x_scale, x, None)?,
                        axis_position(panel.y_scale, y, panel.floor)?,
                    ))
                })
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

/// A panel's own spans (before any equal-aspect widening).
fn panel_spans(panel: &Panel) -> (Span, Span) {
    let curves = positions(panel);
    let points = || curves.iter().flatten();
    (
        data_span(points().map(|p| p.0), panel.x_scale),
        data_span(points().map(|p| p.1), panel.y_scale),
    )
}

/// The spans every panel of a figure shares: the union of theirs, when they have more than one panel, the same
/// scales and no equal aspect.
fn shared_spans(panels: &[Panel]) -> Option<(Span, Span)> {
    let first = panels.first()?;
    let alike = panels.len() > 1
        && panels
            .iter()
            .all(|p| p.x_scale == first.x_scale && p.y_scale == first.y_scale && !p.equal_aspect);
    alike.then(|| {
        panels
            .iter()
            .map(panel_spans)
            .reduce(|(x, y), (u, v)| (x.union(&u), y.union(&v)))
            .expect("at least one panel")
    })
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

/// A legend entry: the series' index and its label in lines.
struct Entry {
    series: usize,
    lines: Vec<String>,
}

/// The legend's entries and its width in pixels (0 without labels).
fn legend_layout(panel: &Panel) -> (Vec<Entry>, u32) {
    let font = FontDesc::from((FONT, f64::from(px(LEGEND_SIZE))));
    let text_width = px(LEGEND_MAX_WIDTH - LEGEND_SAMPLE_ROOM);
    let entries: Vec<Entry> = panel
        .series
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.label.is_empty())
        .map(|(series, s)| Entry {
            series,
            lines: wrap(&s.label, &font, text_width),
        })
        .collect();
    let widest = entries
        .iter()
        .flat_map(|e| &e.lines)
        .filter_map(|line| font.box_size(line).ok())
        .map(|(w, _)| w)
        .max();
    let width = widest.map_or(0, |w| w + px(LEGEND_SAMPLE_ROOM) + px(LEGEND_GAP));
    (entries, width)
}

/// The style a series' line and markers are drawn with.
fn stroke(series: &Series, colour: RGBColor) -> ShapeStyle {
    let width = if series.thick {
        px(3.6)
    } else if series.reference {
        px(2.0)
    } else {
        px(1.6)
    };
    ShapeStyle::from(&colour).stroke_width(width)
}

/// Dash and gap lengths (pixels) of a dashed line.
fn dash_pattern(series: &Series) -> Option<(f64, f64)> {
    if series.reference {
        Some((f64::from(px(8.0)), f64::from(px(7.0))))
    } else if series.dashed {
        Some((f64::from(px(7.0)), f64::from(px(4.0))))
    } else {
        None
    }
}

/// The pieces of a polyline (pixels) that are drawn: every segment, or with a dash pattern the dashes along the
/// whole line. Drawn one straight piece at a time: plotters draws a wide polyline as one polygon with unlimited
/// mitre joins, which shoots spikes far out of the chart at sharp turns (round-off noise) and leaves holes where a
/// long path crosses itself (a precession circle traced twice).
fn line_pieces(pixels: &[(f64, f64)], dash: Option<(f64, f64)>) -> Vec<[(f64, f64); 2]> {
    let Some((on, off)) = dash.filter(|&(on, off)| on > 0.0 && off > 0.0) else {
        return pixels.windows(2).map(|pair| [pair[0], pair[1]]).collect();
    };
    let mut pieces = Vec::new();
    // What is left of the current dash or gap (pixels), and whether it is a dash.
    let (mut left, mut drawing) = (on, true);
    for pair in pixels.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.0 - a.0).hypot(b.1 - a.1);
        if !(length > 0.0 && length.is_finite()) {
            continue;
        }
        let at = |s: f64| (a.0 + (b.0 - a.0) * s / length, a.1 + (b.1 - a.1) * s / length);
        let mut start = 0.0;
        // Each pass ends a dash or gap, or the segment: at most length / min(on, off) + 1 passes.
        while length - start > 1e-9 {
            let end = (start + left).min(length);
            if drawing {
                pieces.push([at(start), at(end)]);
            }
            left -= end - start;
            if left <= 1e-9 {
                drawing = !drawing;
                left = if drawing { on } else { off };
            }
            start = end;
        }
    }
    pieces
}

/// Draws a marker of `shape` at the pixel `at` of `area`.
fn draw_marker(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    (x, y): (i32, i32),
    shape: Shape,
    size: i32,
    style: ShapeStyle,
) -> Result<(), String> {
    let s = size;
    match shape {
        Shape::Circle => area.draw(&Circle::new((x, y), s, style)),
        Shape::Square => area.draw(&Rectangle::new([(x - s, y - s), (x + s, y + s)], style)),
        Shape::Triangle => area.draw(&TriangleMarker::new((x, y), s + 2, style)),
        Shape::Diamond => {
            let d = s + 1;
            area.draw(&Polygon::new(
                vec![(x, y - d), (x + d, y), (x, y + d), (x - d, y)],
                style,
            ))
        }
    }
    .map_err(|e| e.to_string())
}

fn draw_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    panel: &Panel,
    colours: &[RGBColor],
    note: Option<&str>,
    (shared, legend_width): (Option<(Span, Span)>, u32),
) -> Result<(), String> {
    let margin = px(14.0) as i32;
    let area = area
        .margin(margin, margin / 2, margin, margin)
        .titled(panel.labels.title, (FONT, px(CAPTION_SIZE)))
        .map_err(|e| e.to_string())?;
    let (width, height) = area.dim_in_pixel();

    // The note under the panel, the legend to the right of the plotting area.
    let note_font = FontDesc::from((FONT, f64::from(px(NOTE_SIZE))));
    let note_lines = note.map_or_else(Vec::new, |n| wrap(n, &note_font, width));
    let note_height = if note_lines.is_empty() {
        0
    } else {
        note_lines.len() as u32 * line_height(NOTE_SIZE) as u32 + px(6.0)
    };
    let (main, note_area) = area.split_vertically(height - note_height);
    let (entries, _) = legend_layout(panel);
    let (plot_part, legend_area) = main.split_horizontally(width - legend_width);

    let builder = || {
        let mut builder = ChartBuilder::on(&plot_part);
        builder.x_label_area_size(px(46.0)).y_label_area_size(px(70.0));
        builder
    };
    // The plotting area's size does not depend on the ranges: measure it on a provisional chart.
    let plot = builder()
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(|e| e.to_string())?
        .plotting_area()
        .dim_in_pixel();
    let (mut x, mut y) = shared.unwrap_or_else(|| panel_spans(panel));
    if panel.equal_aspect {
        (x, y) = equal_aspect(x, y, plot);
    }
    let chart = builder()
        .build_cartesian_2d(x.low..x.high, y.low..y.high)
        .map_err(|e| e.to_string())?;
    let plot_top = chart.plotting_area().get_base_pixel().1;
    draw_chart(chart, panel, colours, (x, y))?;

    // The legend, its first entry level with the top of the plotting area.
    let legend_origin = legend_area.get_base_pixel();
    let (left, mut top) = (px(LEGEND_GAP) as i32, plot_top - legend_origin.1);
    let text_style = TextStyle::from((FONT, px(LEGEND_SIZE))).pos(Pos::new(HPos::Left, VPos::Center));
    let step = line_height(LEGEND_SIZE);
    for entry in &entries {
        let series = &panel.series[entry.series];
        let colour = colours[entry.series];
        let style = stroke(series, colour);
        let middle = top + step / 2;
        let sample = px(LEGEND_SAMPLE) as i32;
        if !series.markers_only {
            let from = (f64::from(left), f64::from(middle));
            let to = (f64::from(left + sample), f64::from(middle));
            for [a, b] in line_pieces(&[from, to], dash_pattern(series)) {
                let piece = [
                    (a.0.round() as i32, a.1.round() as i32),
                    (b.0.round() as i32, b.1.round() as i32),
                ];
                legend_area
                    .draw(&PathElement::new(piece.to_vec(), style))
                    .map_err(|e| e.to_string())?;
            }
        }
        if series.markers || series.markers_only {
            let size = px(4.0) as i32;
            draw_marker(
                &legend_area,
                (left + sample / 2, middle),
                series.shape,
                size,
                colour.filled(),
            )?;
        }
        for (k, line) in entry.lines.iter().enumerate() {
            legend_area
                .draw_text(
                    line,
                    &text_style,
                    (left + px(LEGEND_SAMPLE_ROOM) as i32, middle + k as i32 * step),
                )
                .map_err(|e| e.to_string())?;
        }
        top += step * entry.lines.len() as i32 + step / 3;
    }

    let style = TextStyle::from(note_font).color(&NOTE_COLOUR);
    for (k, line) in note_lines.iter().enumerate() {
        note_area
            .draw_text(line, &style, (0, px(2.0) as i32 + k as i32 * line_height(NOTE_SIZE)))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
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

/// Draws the panel's curves, given at axis positions, on a chart over those positions: the other series first,
/// then the references over them.
fn draw_chart<'a>(
    mut chart: ChartContext<'a, BitMapBackend<'a>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    panel: &Panel,
    colours: &[RGBColor],
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

    let curves = positions(panel);
    let plotting = chart.plotting_area().strip_coord_spec();
    let base = plotting.get_base_pixel();
    let marker_size = px(4.0) as i32;
    let order = (0..panel.series.len())
        .filter(|&i| !panel.series[i].reference)
        .chain((0..panel.series.len()).filter(|&i| panel.series[i].reference));
    for index in order {
        let (series, points, colour) = (&panel.series[index], &curves[index], colours[index]);
        let style = stroke(series, colour);
        let pixels: Vec<(f64, f64)> = points
            .iter()
            .map(|p| {
                let (u, v) = chart.backend_coord(p);
                (f64::from(u - base.0), f64::from(v - base.1))
            })
            .collect();
        if !series.markers_only {
            for [a, b] in line_pieces(&pixels, dash_pattern(series)) {
                let piece = vec![
                    (a.0.round() as i32, a.1.round() as i32),
                    (b.0.round() as i32, b.1.round() as i32),
                ];
                plotting
                    .draw(&PathElement::new(piece, style))
                    .map_err(|e| e.to_string())?;
            }
        }
        if series.markers || series.markers_only {
            let size = if series.markers_only {
                marker_size + 1
            } else {
                marker_size
            };
            for &(u, v) in &pixels {
                draw_marker(&plotting, (u as i32, v as i32), series.shape, size, colour.filled())?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(slot: Option<usize>) -> Series {
        Series {
            slot,
            ..Series::line("s", vec![(0.0, 1.0)])
        }
    }

    fn distinct(colours: &[RGBColor]) -> bool {
        colours
            .iter()
            .enumerate()
            .all(|(i, c)| colours[..i].iter().all(|d| d != c))
    }

    #[test]
    fn palette_never_repeats_a_colour_within_a_panel() {
        // Every number of plain series up to the limit, with and without a reference.
        for n in 0..=MAX_COLOURS_PER_AXIS {
            let plain: Vec<Series> = (0..n).map(|_| series(None)).collect();
            let colours = series_colours(&plain).unwrap();
            assert!(distinct(&colours), "{n} series: {colours:?}");
            if n < MAX_COLOURS_PER_AXIS {
                let mut with_reference = plain.clone();
                with_reference.insert(0, Series::reference_points("MuJoCo", vec![]));
                let colours = series_colours(&with_reference).unwrap();
                assert!(distinct(&colours), "{n} series and a reference: {colours:?}");
                assert_eq!(colours[0], REFERENCE_COLOUR);
            }
        }
        // Fixed slots are kept, and the free series take the entries left over, not a fixed one's.
        let mixed = [series(Some(3)), series(None), series(Some(0)), series(None)];
        let colours = series_colours(&mixed).unwrap();
        assert_eq!(colours[0], PALETTE[3]);
        assert_eq!(colours[2], PALETTE[0]);
        assert!(distinct(&colours), "{colours:?}");
        // Overloaded or clashing panels are refused rather than drawn with repeated colours.
        let seven: Vec<Series> = (0..7).map(|_| series(None)).collect();
        assert!(series_colours(&seven).is_err());
        let mut six_and_reference: Vec<Series> = (0..6).map(|_| series(None)).collect();
        six_and_reference.push(Series::reference_line("reference", vec![]));
        assert!(series_colours(&six_and_reference).is_err());
        assert!(series_colours(&[series(Some(1)), series(Some(1))]).is_err());
        assert!(series_colours(&[series(Some(PALETTE.len()))]).is_err());
        let two_references = [
            Series::reference_line("a", vec![]),
            Series::reference_points("b", vec![]),
        ];
        assert!(series_colours(&two_references).is_err());
    }

    #[test]
    fn palette_is_okabe_ito_without_black() {
        assert_eq!(PALETTE.len(), MAX_COLOURS_PER_AXIS);
        assert!(PALETTE.iter().all(|c| *c != REFERENCE_COLOUR));
        assert!(distinct(&PALETTE));
    }

    #[test]
    fn zeros_sit_on_the_floor_of_a_log_axis() {
        assert_eq!(axis_position(Scale::Log, 0.0, None), None);
        assert_eq!(axis_position(Scale::Log, 0.0, Some(1e-17)), Some(-17.0));
        assert_eq!(axis_position(Scale::Log, 1e-20, Some(1e-17)), Some(-17.0));
        assert_eq!(axis_position(Scale::Log, 1e-3, Some(1e-17)), Some(-3.0));
        assert_eq!(axis_position(Scale::Log, -1.0, Some(1e-17)), None);
        let panel = Panel::new(Labels::new("t", "x", "y"), vec![]).log_y_with_floor(1e-17);
        assert!(panel.full_note().unwrap().contains("exact zeros included"));
    }

    #[test]
    fn dashes_follow_the_pattern_along_the_line() {
        // A 20-pixel line in three segments, dashes of 4 and gaps of 2: dashes at 0–4, 6–10, 12–16, 18–20.
        let line = [(0.0, 0.0), (5.0, 0.0), (11.0, 0.0), (20.0, 0.0)];
        let mut covered: Vec<(f64, f64)> = line_pieces(&line, Some((4.0, 2.0)))
            .into_iter()
            .map(|[a, b]| (a.0, b.0))
            .collect();
        // Merge the pieces split at the segment ends.
        covered.dedup_by(|b, a| {
            let joined = (a.1 - b.0).abs() < 1e-12;
            if joined {
                a.1 = b.1;
            }
            joined
        });
        assert_eq!(covered, vec![(0.0, 4.0), (6.0, 10.0), (12.0, 16.0), (18.0, 20.0)]);
        assert_eq!(line_pieces(&line, None).len(), 3);
    }

    #[test]
    fn panels_of_a_figure_share_their_axes() {
        let panel = |points: Vec<(f64, f64)>| {
            Panel::new(Labels::new("t", "x", "y"), vec![Series::line("s", points)])
                .log_x()
                .log_y()
        };
        let panels = [panel(vec![(1e-3, 1e-6), (1e-2, 1e-9)]), panel(vec![(1e-1, 1e-12)])];
        let (x, y) = shared_spans(&panels).unwrap();
        // The second panel's single point spans its own unit decade, [-1, 0].
        assert_eq!((x.low, x.high), (-3.0, 0.0));
        assert_eq!((y.low, y.high), (-12.0, -6.0));
        assert!(shared_spans(&panels[..1]).is_none());
    }
}
