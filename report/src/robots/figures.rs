//! The robots' figures: work-precision (a panel per integrator family, MuJoCo's points in each) and the motion of the
//! most accurate run as stick figures, seen from the front, the side and above.
//! A robot's motion as stick figures: the robot at a few instants drawn over each other, the earliest palest, in a
//! side view (x–z) and a front view (y–z) side by side at one scale (a metre is as long on every axis). Each joint
//! origin is joined to its parent's, the end bodies to their last link frame; circles mark the bodies' centres of
//! mass.
//!
//! Drawn with plotters directly (the charts of [`crate::plot`] are curves in a palette; these are figures in one
//! fading hue), with the same embedded font and text sizes.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use dynamics::integrate::Integrator;
use dynamics::JointMethod;
use nalgebra::Vector3;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use reference::robots::{RobotId, RobotReference};
use scene_file::AlgebraKind;

use super::measure::{StickFigure, SNAPSHOT_TIMES};
use super::sweep::{robot_label, series_of, RobotResult};
use crate::measured_anchors::{mujoco_time, sources_short, Anchors, Time};
use crate::panels::{panel_title, slot, styled, Family};
use crate::plot::{
    figure_with_caption, px, register_font, wrap, Labels, Panel, PlotError, Series, AXIS_TITLE_SIZE, FIGURE_TITLE_SIZE,
    FONT, LEGEND_SIZE, NOTE_COLOUR, NOTE_SIZE, TICK_LABEL_SIZE,
};
use crate::recorded_anchors::{MUJOCO, PINOCCHIO, RECORDED_WHEN};

/// The work-precision panel of an integrator (its place) and its place in the panel (0 or 1): the general methods
/// by [`Family`], with the eighth-order joint-coordinate method beside the eighth-order body method, the other two
/// fixed-step joint-coordinate methods in a panel of their own, and DOP853-joint (at fixed steps) in another.
fn panel(integrator: Integrator) -> (usize, usize) {
    match integrator {
        Integrator::Joint(JointMethod::Rkmk8) => (Family::EighthOrder as usize, 1),
        Integrator::Joint(JointMethod::Dop853) => (11, 0),
        Integrator::Joint(method) => (10, usize::from(method == JointMethod::Rkmk6)),
        general => {
            let (family, member) = Family::of(general);
            (family as usize, member)
        }
    }
}

/// A panel's title, from the integrators it shows.
fn panel_heading(panel: usize, integrators: &[Integrator]) -> String {
    let joint_eighth = integrators.contains(&Integrator::Joint(JointMethod::Rkmk8));
    let body_eighth = integrators.contains(&Integrator::General(dynamics::Method::Rkmk8Body));
    match panel {
        10 => "RKMK4-joint and RKMK6-joint (stepping in joint coordinates)".to_owned(),
        11 => "DOP853-joint at fixed steps (joint coordinates)".to_owned(),
        p if p == Family::EighthOrder as usize && joint_eighth && body_eighth => {
            "RKMK8-body and RKMK8-joint (order 8: body momentum, joint coordinates)".to_owned()
        }
        p if p == Family::EighthOrder as usize && joint_eighth => "RKMK8-joint (order 8, joint coordinates)".to_owned(),
        _ => integrators
            .first()
            .map_or(String::new(), |&i| panel_title(None, Family::of(i).0)),
    }
}

/// Work-precision: a panel per integrator family, PGA and CGA per method, MuJoCo's two points in each.
pub(crate) fn work_precision_figure(
    dir: &Path,
    results: &[RobotResult],
    id: RobotId,
    reference: &RobotReference,
    name: &str,
    anchors: &Anchors,
) -> Result<bool, PlotError> {
    let groups = series_of(results, id);
    if groups.is_empty() {
        return Ok(false);
    }
    let times: Vec<Time> = reference.mujoco.iter().map(|r| mujoco_time(anchors, id, r)).collect();
    let mujoco_source = sources_short(&times.iter().map(|t| t.source).collect::<Vec<_>>());
    let mut mujoco: Vec<(f64, f64)> = reference
        .mujoco
        .iter()
        .zip(&times)
        .map(|(r, time)| (time.seconds / r.dt, r.max_joint_error))
        .collect();
    mujoco.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut steps: Vec<f64> = reference.mujoco.iter().map(|r| r.dt).collect();
    steps.sort_by(|a, b| b.total_cmp(a));
    let steps: Vec<String> = steps.iter().map(|dt| format!("{dt:.0e}")).collect();
    let mut panels_runs: BTreeMap<usize, BTreeMap<usize, Series>> = BTreeMap::new();
    let mut shown: BTreeMap<usize, Vec<Integrator>> = BTreeMap::new();
    for runs in groups.values() {
        let config = runs[0].config;
        let (key, member) = panel(config.integrator);
        shown.entry(key).or_default().push(config.integrator);
        let points = runs
            .iter()
            .map(|o| (o.cpu_per_simulated_second, o.joint_error))
            .collect();
        let line = Series {
            markers: true,
            ..Series::line(config.series_label(), points)
        };
        panels_runs
            .entry(key)
            .or_default()
            .insert(slot(config.algebra, member), styled(line, config.algebra, member));
    }
    let titles: Vec<String> = panels_runs.keys().map(|key| panel_heading(*key, &shown[key])).collect();
    let panels: Vec<Panel> = panels_runs
        .into_values()
        .zip(&titles)
        .map(|(series, title)| {
            let mut series: Vec<Series> = series.into_values().collect();
            series.push(Series::reference_points(
                format!("{MUJOCO}, dt\u{a0}=\u{a0}{}, {mujoco_source}", steps.join(" and ")),
                mujoco.clone(),
            ));
            Panel::new(
                Labels::new(
                    title,
                    "CPU per simulated second (s)",
                    "largest joint-position error over 1 s (rad)",
                ),
                series,
            )
            .log_x()
            .log_y()
        })
        .collect();
    let caption = format!(
        "Black triangles: {MUJOCO} on the same URDF at dt = {}, its errors recorded {RECORDED_WHEN}, its times \
         {mujoco_source}; {PINOCCHIO}'s C++ ABA takes {:.2} µs per evaluation, recorded {RECORDED_WHEN}. Ours: this job's, the fastest of repeated timings. Error: the largest joint-position error against Pinocchio's reference over the 101 samples every \
         0.01 s. Dark, solid: PGA; light, dashed: CGA.",
        steps.join(" and "),
        reference.pinocchio_aba_microseconds
    );
    figure_with_caption(
        &dir.join(name),
        &format!("{}: joint error against CPU time", robot_label(id)),
        &panels,
        &caption,
    )?;
    Ok(true)
}

/// The motion of the most accurate run (PGA if any), as stick figures; for a floating base relative to the whole
/// robot's centre of mass. Returns the run's label, or None without a run.
pub(crate) fn motion_picture(
    dir: &Path,
    results: &[RobotResult],
    id: RobotId,
    name: &str,
) -> Result<Option<String>, PlotError> {
    let candidates = || {
        results
            .iter()
            .filter(|(c, _)| c.robot == id)
            .filter_map(|(_, r)| r.as_ref().ok())
            .filter(|o| o.figures.len() == SNAPSHOT_TIMES.len())
    };
    let most_accurate = |algebra: AlgebraKind| {
        candidates()
            .filter(|o| o.config.algebra == algebra)
            .min_by(|a, b| a.joint_error.total_cmp(&b.joint_error))
    };
    let Some(run) = most_accurate(AlgebraKind::Pga).or_else(|| most_accurate(AlgebraKind::Cga)) else {
        return Ok(None);
    };
    let free = run.base_position_error.is_some();
    let figures: Vec<StickFigure> = if free {
        run.figures
            .iter()
            .map(|f| {
                let shift = |p: &nalgebra::Vector3<f64>| p - f.centre;
                StickFigure {
                    t: f.t,
                    segments: f.segments.iter().map(|[a, b]| [shift(a), shift(b)]).collect(),
                    centres: f.centres.iter().map(shift).collect(),
                    centre: nalgebra::Vector3::zeros(),
                }
            })
            .collect()
    } else {
        run.figures.clone()
    };
    let label = format!("{}, dt = {:e} s", run.config.series_label(), run.config.dt);
    let mut caption = format!(
        "{label}, passive under gravity from the reference's start (no torques, no contacts), at t = 0, 0.25, 0.5, 0.75 \
         and 1 s, palest first. Each joint origin is joined to its parent's (the base frame's origin for the joints on \
         the root), each end body's joint origin to its farthest link frame (the tool flange, a foot); circles: the \
         bodies' centres of mass. One scale on every axis."
    );
    if free {
        let (first, last) = (&run.figures[0], &run.figures[run.figures.len() - 1]);
        let _ = write!(
            caption,
            " Positions relative to the whole robot's centre of mass at each instant, which falls {:.2} m along its \
             parabola in the second.",
            first.centre.z - last.centre.z
        );
    }
    motion_figure(
        &dir.join(name),
        &format!("{}: the motion over 1 s", robot_label(id)),
        &figures,
        &caption,
    )?;
    Ok(Some(label))
}

/// The image's width (px), the other plots' ([`crate::plot::SIZE`]), so text sizes and [`px`] are theirs.
const WIDTH: u32 = crate::plot::SIZE.0;

/// The views' height (px): as the data need at the views' scale, within these bounds.
const PANEL_HEIGHT: (u32, u32) = (380, 760);

const PANEL_TITLE_SIZE: f64 = 18.0;

/// The instants' colours, earliest first: a sequential scale from pale green to dark blue (ColorBrewer's YlGnBu),
/// which changes in hue as well as in lightness so that neighbouring instants stay apart.
const SHADES: [RGBColor; 5] = [
    RGBColor(161, 218, 180),
    RGBColor(65, 182, 196),
    RGBColor(44, 127, 184),
    RGBColor(37, 52, 148),
    RGBColor(8, 29, 88),
];

/// The colour of instant `k` of `n`: from the palest shade (the first) to the darkest (the last), interpolated
/// along [`SHADES`].
fn fading(k: usize, n: usize) -> RGBColor {
    let at = if n <= 1 { 1.0 } else { k as f64 / (n - 1) as f64 } * (SHADES.len() - 1) as f64;
    let (low, fraction) = (at.floor() as usize, at.fract());
    let (a, b) = (SHADES[low], SHADES[(low + 1).min(SHADES.len() - 1)]);
    let mix = |x: u8, y: u8| (f64::from(x) + fraction * (f64::from(y) - f64::from(x))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A tick label: two decimals for short spans, one otherwise, never "-0.0".
fn tick(value: f64, span: f64) -> String {
    let text = if span < 1.0 {
        format!("{value:.2}")
    } else {
        format!("{value:.1}")
    };
    match text.strip_prefix('-') {
        Some(zero) if zero.chars().all(|c| c == '0' || c == '.') => zero.to_owned(),
        _ => text,
    }
}

/// The range `[low, high]` of one coordinate over every point of the figures.
fn extent(figures: &[StickFigure], coordinate: impl Fn(&Vector3<f64>) -> f64) -> (f64, f64) {
    figures
        .iter()
        .flat_map(|f| f.segments.iter().flatten().chain(&f.centres))
        .map(coordinate)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
}

/// One view: the figures projected on (horizontal, z).
fn draw_view(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    figures: &[StickFigure],
    (title, horizontal): (&str, &str),
    project: &dyn Fn(&Vector3<f64>) -> (f64, f64),
    (x_range, z_range): ((f64, f64), (f64, f64)),
) -> Result<(), String> {
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FONT, px(PANEL_TITLE_SIZE)))
        .margin(px(10.0))
        .x_label_area_size(px(40.0))
        .y_label_area_size(px(56.0))
        .build_cartesian_2d(x_range.0..x_range.1, z_range.0..z_range.1)
        .map_err(|e| e.to_string())?;
    let (x_span, z_span) = (x_range.1 - x_range.0, z_range.1 - z_range.0);
    let x_label = |v: &f64| tick(*v, x_span);
    let z_label = |v: &f64| tick(*v, z_span);
    chart
        .configure_mesh()
        .x_desc(horizontal)
        .y_desc("z (m)")
        .label_style((FONT, px(TICK_LABEL_SIZE)))
        .axis_desc_style((FONT, px(AXIS_TITLE_SIZE)))
        .bold_line_style(BLACK.mix(0.12))
        .light_line_style(BLACK.mix(0.0))
        .x_labels(7)
        .y_labels(7)
        .x_label_formatter(&x_label)
        .y_label_formatter(&z_label)
        .draw()
        .map_err(|e| e.to_string())?;
    let width = px(2.8);
    for (k, figure) in figures.iter().enumerate() {
        let colour = fading(k, figures.len());
        for [a, b] in &figure.segments {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![project(a), project(b)],
                    colour.stroke_width(width),
                )))
                .map_err(|e| e.to_string())?;
        }
        let joints = figure.segments.iter().flatten().map(project);
        chart
            .draw_series(joints.map(|p| Circle::new(p, px(2.6) as i32, colour.filled())))
            .map_err(|e| e.to_string())?;
        let centres = figure.centres.iter().map(project);
        chart
            .draw_series(centres.map(|p| Circle::new(p, px(5.0) as i32, WHITE.filled())))
            .map_err(|e| e.to_string())?;
        let centres = figure.centres.iter().map(project);
        chart
            .draw_series(centres.map(|p| Circle::new(p, px(5.0) as i32, colour.stroke_width(px(2.0)))))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Draws `figures` (earliest first) into `path`: the title, the two views, a legend of the instants and the marks,
/// and `caption` under it.
pub(crate) fn motion_figure(path: &Path, title: &str, figures: &[StickFigure], caption: &str) -> Result<(), PlotError> {
    let error = |message: String| PlotError {
        path: path.display().to_string(),
        message,
    };
    if figures.is_empty() {
        return Err(error("no instant to draw".into()));
    }
    register_font();
    let caption_font = FontDesc::from((FONT, f64::from(px(NOTE_SIZE))));
    let caption_lines = wrap(caption, &caption_font, WIDTH - 2 * px(14.0));
    let caption_line = (f64::from(px(NOTE_SIZE)) * 1.3).round() as u32;
    let title_band = px(2.0 * FIGURE_TITLE_SIZE);
    let legend_band = px(34.0);
    let caption_band = caption_lines.len() as u32 * caption_line + px(14.0);

    // One scale for both views: the larger of the horizontal spans per pixel, the height as the vertical span needs
    // at that scale (within bounds; past them the scale grows), each range centred on its data.
    let (x, y, z) = (
        extent(figures, |p| p.x),
        extent(figures, |p| p.y),
        extent(figures, |p| p.z),
    );
    let panel_width = f64::from(WIDTH / 2) - f64::from(px(10.0) * 2 + px(56.0));
    let chrome = f64::from(px(10.0) * 2 + px(40.0) + px(PANEL_TITLE_SIZE) * 2);
    let span = |(lo, hi): (f64, f64)| (hi - lo) * 1.1;
    let horizontal = (span(x).max(span(y)) / panel_width).max(1e-6);
    let panel_pixels = (span(z) / horizontal + chrome).clamp(f64::from(PANEL_HEIGHT.0), f64::from(PANEL_HEIGHT.1));
    let panel_height = panel_pixels - chrome;
    let per_pixel = horizontal.max(span(z) / panel_height);
    let panel_pixels = panel_pixels.round() as u32;
    let height = title_band + panel_pixels + legend_band + caption_band;
    let centred = |(lo, hi): (f64, f64), pixels: f64| {
        let middle = 0.5 * (lo + hi);
        let half = 0.5 * per_pixel * pixels;
        (middle - half, middle + half)
    };
    let (x_range, y_range, z_range) = (
        centred(x, panel_width),
        centred(y, panel_width),
        centred(z, panel_height),
    );

    let root = BitMapBackend::new(path, (WIDTH, height)).into_drawing_area();
    let draw = || -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (band, rest) = root.split_vertically(title_band);
        let centre = Pos::new(HPos::Center, VPos::Center);
        band.draw_text(
            title,
            &TextStyle::from((FONT, px(FIGURE_TITLE_SIZE))).pos(centre),
            (WIDTH as i32 / 2, title_band as i32 / 2),
        )
        .map_err(|e| e.to_string())?;
        let (panels, rest) = rest.split_vertically(panel_pixels);
        let (side, front) = panels.split_horizontally(WIDTH / 2);
        draw_view(
            &side,
            figures,
            ("side view (x–z)", "x (m)"),
            &|p| (p.x, p.z),
            (x_range, z_range),
        )?;
        draw_view(
            &front,
            figures,
            ("front view (y–z)", "y (m)"),
            &|p| (p.y, p.z),
            (y_range, z_range),
        )?;

        let (legend, caption_area) = rest.split_vertically(legend_band);
        draw_legend(&legend, figures, legend_band)?;

        let style = TextStyle::from(caption_font.clone()).color(&NOTE_COLOUR);
        for (k, line) in caption_lines.iter().enumerate() {
            caption_area
                .draw_text(
                    line,
                    &style,
                    (px(14.0) as i32, px(6.0) as i32 + k as i32 * caption_line as i32),
                )
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())
    };
    draw().map_err(error)
}

/// The legend below the views, `band` high: a sample line per instant of `figures`, then the marks.
fn draw_legend(legend: &DrawingArea<BitMapBackend, Shift>, figures: &[StickFigure], band: u32) -> Result<(), String> {
    let text = TextStyle::from((FONT, px(LEGEND_SIZE))).pos(Pos::new(HPos::Left, VPos::Center));
    let middle = band as i32 / 2;
    let mut left = px(20.0) as i32;
    for (k, figure) in figures.iter().enumerate() {
        let colour = fading(k, figures.len());
        let sample = px(26.0) as i32;
        legend
            .draw(&PathElement::new(
                vec![(left, middle), (left + sample, middle)],
                colour.stroke_width(px(2.8)),
            ))
            .map_err(|e| e.to_string())?;
        let label = format!("t = {} s", figure.t);
        legend
            .draw_text(&label, &text, (left + sample + px(6.0) as i32, middle))
            .map_err(|e| e.to_string())?;
        left += sample + px(6.0) as i32 + px(78.0) as i32;
    }
    let dark = fading(figures.len() - 1, figures.len());
    legend
        .draw(&Circle::new(
            (left + px(6.0) as i32, middle),
            px(2.6) as i32,
            dark.filled(),
        ))
        .map_err(|e| e.to_string())?;
    legend
        .draw_text("joint origin", &text, (left + px(16.0) as i32, middle))
        .map_err(|e| e.to_string())?;
    left += px(106.0) as i32;
    legend
        .draw(&Circle::new(
            (left + px(6.0) as i32, middle),
            px(5.0) as i32,
            dark.stroke_width(px(2.0)),
        ))
        .map_err(|e| e.to_string())?;
    legend
        .draw_text("centre of mass", &text, (left + px(18.0) as i32, middle))
        .map_err(|e| e.to_string())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instants_fade_from_pale_to_the_full_hue() {
        assert_eq!(fading(0, 5), SHADES[0]);
        assert_eq!(fading(4, 5), SHADES[4]);
        assert_eq!(fading(2, 3), SHADES[4]);
        assert_eq!(fading(1, 3), SHADES[2]);
        assert_eq!(tick(-0.0001, 0.5), "0.00");
        assert_eq!(tick(-0.0001, 2.0), "0.0");
    }
}
