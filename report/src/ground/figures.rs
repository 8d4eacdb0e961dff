//! The ground figure: Solo-12's base height as it lands on its feet and stands, and the crate's, pill's and gem's
//! centres as they bounce and come to rest on the floor.

use std::path::Path;

use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};
use crate::scene_job::AlgebraRun;

/// A body's centre height over a run's samples, as a line (dashed for CGA, drawn over PGA).
fn heights(run: &AlgebraRun, body: usize, label: &str) -> Series {
    Series {
        dashed: run.algebra == scene_file::AlgebraKind::Cga,
        ..Series::line(
            format!("{label}, {}", run.algebra.name()),
            run.bodies[body].iter().map(|s| (s.t, s.position.z)).collect(),
        )
    }
}

/// Draws the figure of the standing robot's runs and the shapes' runs into `dir`; returns its file name, or `None`
/// without runs.
pub(crate) fn draw(dir: &Path, robot: &[AlgebraRun], shapes: &[AlgebraRun]) -> Result<Option<&'static str>, PlotError> {
    let mut panels = Vec::new();
    if !robot.is_empty() {
        let series = robot.iter().map(|run| heights(run, 0, "base")).collect();
        panels.push(Panel::new(
            Labels::new(
                "Solo-12 dropped onto a floor with friction",
                "time (s)",
                "base height (m)",
            ),
            series,
        ));
    }
    if !shapes.is_empty() {
        let mut series = Vec::new();
        for run in shapes {
            for (body, name) in run.names.iter().enumerate() {
                series.push(heights(run, body, name));
            }
        }
        panels.push(Panel::new(
            Labels::new("A crate, a pill and a gem on a floor", "time (s)", "centre height (m)"),
            series,
        ));
    }
    if panels.is_empty() {
        return Ok(None);
    }
    figure_with_caption(
        &dir.join("ground.png"),
        "Bodies on the ground: Coulomb friction and collision shapes",
        &panels,
        "Top: Solo-12's base (foot spheres, friction 0.8, a PD stance) lands 3 cm below its start, its feet stick and \
         it settles and stands still. Bottom: a box, a capsule and a convex hull dropped onto a floor with friction 0.5 \
         bounce on their corners, ends and vertices and come to rest on a face, on a side and on a face of the hull.",
    )?;
    Ok(Some("ground.png"))
}
