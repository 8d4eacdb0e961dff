//! What the scene examples write: the output folder (first command-line argument, default `out/examples/`),
//! CSV trajectories and PNG plots of traced paths.
//!
//! Text needs a font: plotters' `ab_glyph` backend renders a TrueType file read at run time, from
//! `$GA_DYNAMICS_FONT` or a usual system location (DejaVu Sans or Liberation Sans).

// Each example compiles this module on its own and uses a subset of it.
#![allow(dead_code)]

use std::error::Error;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use dynamics::constraints::{simulate_constrained, ConstrainedBody, ConstrainedSimulationError};
use dynamics::{Algebra, Method, Schedule, Simulation, State};
use nalgebra::Vector3;
use plotters::prelude::*;

pub type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// The folder from the command line (default `out/examples/`), created if missing.
pub fn output_folder() -> Result<PathBuf> {
    let folder = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "out/examples".to_owned()));
    fs::create_dir_all(&folder)?;
    Ok(folder)
}

const FONT_CANDIDATES: [&str; 4] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/Library/Fonts/Arial.ttf",
];

/// Registers a TrueType font as plotters' "sans-serif" (once per process; the bytes live for the program).
fn register_font() -> Result<()> {
    let candidates = std::env::var("GA_DYNAMICS_FONT")
        .into_iter()
        .chain(FONT_CANDIDATES.map(String::from));
    for candidate in candidates {
        if let Ok(bytes) = fs::read(&candidate) {
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            return plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
                .map_err(|_| format!("{candidate} is not a usable TrueType font").into());
        }
    }
    Err("no font found: set GA_DYNAMICS_FONT to a .ttf file (e.g. DejaVuSans.ttf)".into())
}

/// One named curve of a panel.
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

impl Curve {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Curve {
            label: label.into(),
            points,
        }
    }
}

/// One chart: title, axis labels and curves.
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
    /// Equal scales on both axes (for paths traced in a plane).
    pub equal_axes: bool,
    /// A vertical range to use instead of the curves' (e.g. to leave room for the legend).
    pub y_range: Option<(f64, f64)>,
}

const COLOURS: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

/// The range of the curves' coordinates with a 5% margin, or a unit range if empty.
fn ranges(panel: &Panel) -> ((f64, f64), (f64, f64)) {
    let points = panel.curves.iter().flat_map(|c| c.points.iter());
    let (mut x, mut y) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    for &(px, py) in points {
        x = (x.0.min(px), x.1.max(px));
        y = (y.0.min(py), y.1.max(py));
    }
    let pad = |(low, high): (f64, f64)| {
        if !low.is_finite() {
            return (0.0, 1.0);
        }
        let span = (high - low).max(1e-9);
        (low - 0.05 * span, high + 0.05 * span)
    };
    let (mut x, mut y) = (pad(x), panel.y_range.unwrap_or_else(|| pad(y)));
    if panel.equal_axes {
        let half = 0.5 * (x.1 - x.0).max(y.1 - y.0);
        let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
        x = (cx - half, cx + half);
        y = (cy - half, cy + half);
    }
    (x, y)
}

/// Draws the panels side by side into a PNG of 800 px height per row, with fonts sized to stay readable
/// when the image is shown 800 px wide.
pub fn plot(path: &Path, title: &str, panels: &[Panel]) -> Result<()> {
    static FONT: std::sync::OnceLock<std::result::Result<(), String>> = std::sync::OnceLock::new();
    FONT.get_or_init(|| register_font().map_err(|error| error.to_string()))
        .clone()?;
    let width = 800 * panels.len() as u32;
    let root = BitMapBackend::new(path, (width, 860)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 36))?;
    let areas = root.split_evenly((1, panels.len()));
    for (area, panel) in areas.iter().zip(panels) {
        let ((x0, x1), (y0, y1)) = ranges(panel);
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 30))
            .margin(20)
            .x_label_area_size(70)
            .y_label_area_size(110)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(panel.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .axis_desc_style(("sans-serif", 28))
            .label_style(("sans-serif", 24))
            .x_labels(6)
            .y_labels(6)
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        for (curve, colour) in panel.curves.iter().zip(COLOURS.iter().cycle()) {
            chart
                .draw_series(LineSeries::new(curve.points.iter().copied(), colour.stroke_width(3)))?
                .label(curve.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 30, y)], colour.stroke_width(4)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 24))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// Writes `header` and one line per row.
pub fn write_csv(path: &Path, header: &str, rows: impl IntoIterator<Item = Vec<f64>>) -> Result<()> {
    let mut file = std::io::BufWriter::new(fs::File::create(path)?);
    writeln!(file, "{header}")?;
    for row in rows {
        let fields: Vec<String> = row.iter().map(|v| format!("{v:.15e}")).collect();
        writeln!(file, "{}", fields.join(","))?;
    }
    Ok(())
}

/// Runs a system with RK4, sampled every 0.01 s.
pub fn run<A: Algebra>(
    system: &ConstrainedBody<A>,
    initial: State<A>,
    dt: f64,
    duration: f64,
) -> std::result::Result<Simulation<A>, ConstrainedSimulationError> {
    let schedule = Schedule::new(dt, duration).map_err(ConstrainedSimulationError::from)?;
    simulate_constrained(system, initial, Method::Rk4, &schedule)
}

/// The world positions of a body point (body coordinates) over a run.
pub fn traced(simulation: &Simulation<impl Algebra>, body_point: Vector3<f64>) -> Vec<Vector3<f64>> {
    simulation
        .samples
        .iter()
        .map(|s| s.position + s.orientation * body_point)
        .collect()
}

/// The standard trajectory CSV (the reference files' columns) plus energy, for one run.
pub fn write_trajectory(path: &Path, simulation: &Simulation<impl Algebra>) -> Result<()> {
    write_csv(
        path,
        "t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,energy",
        simulation.samples.iter().map(|s| {
            let q = s.orientation.quaternion();
            vec![
                s.t,
                s.position.x,
                s.position.y,
                s.position.z,
                q.w,
                q.i,
                q.j,
                q.k,
                s.velocity.x,
                s.velocity.y,
                s.velocity.z,
                s.angular_velocity.x,
                s.angular_velocity.y,
                s.angular_velocity.z,
                s.energy,
            ]
        }),
    )
}
