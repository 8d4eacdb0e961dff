//! A robot's motion as stick figures: the robot at a few instants drawn over each other, the earliest palest, in a
//! side view (x–z) and a front view (y–z) side by side at one scale (a metre is as long on every axis). Each joint
//! origin is joined to its parent's, the end bodies to their last link frame; circles mark the bodies' centres of
//! mass.
//!
//! Drawn with plotters directly (the charts of [`crate::plot`] are curves in a palette; these are figures in one
//! fading hue), with the same embedded font and text sizes.

use std::path::Path;

use nalgebra::Vector3;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::plot::{
    px, register_font, wrap, PlotError, AXIS_TITLE_SIZE, FIGURE_TITLE_SIZE, FONT, LEGEND_SIZE, NOTE_COLOUR, NOTE_SIZE,
    TICK_LABEL_SIZE,
};
use crate::robot_sweep::StickFigure;

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

        // The legend: a sample line per instant, then the marks.
        let (legend, caption_area) = rest.split_vertically(legend_band);
        let text = TextStyle::from((FONT, px(LEGEND_SIZE))).pos(Pos::new(HPos::Left, VPos::Center));
        let middle = legend_band as i32 / 2;
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
