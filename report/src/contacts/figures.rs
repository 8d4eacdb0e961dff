//! The contacts' figure: the cube's lowest corner and its centre above the floor over time, the free-fall impact
//! marked.

use std::path::Path;

use scenarios::contacts::ContactScene;
use scene_file::AlgebraKind;

use super::sweep::ContactRun;
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};

/// Draws the figure of `runs` into `dir`; returns its file name, or `None` without runs.
pub(crate) fn draw(dir: &Path, runs: &[ContactRun]) -> Result<Option<&'static str>, PlotError> {
    let mut panels = Vec::new();
    for scene in ContactScene::ALL {
        let of_scene: Vec<&ContactRun> = runs.iter().filter(|run| run.scene == scene).collect();
        if of_scene.is_empty() {
            continue;
        }
        let mut series = Vec::new();
        for run in &of_scene {
            let dashed = run.algebra == AlgebraKind::Cga;
            series.push(Series {
                dashed,
                ..Series::line(
                    format!("lowest corner, {}", run.algebra.name()),
                    run.samples.iter().map(|&(t, lowest, _, _)| (t, lowest)).collect(),
                )
            });
            series.push(Series {
                dashed,
                ..Series::line(
                    format!("centre, {}", run.algebra.name()),
                    run.samples.iter().map(|&(t, _, centre, _)| (t, centre)).collect(),
                )
            });
        }
        series.push(Series::reference_line(
            "floor",
            vec![(0.0, 0.0), (scene.duration(), 0.0)],
        ));
        if let Some(exact) = scene.exact_first_impact() {
            series.push(Series {
                markers_only: true,
                ..Series::line("free-fall impact", vec![(exact, 0.0)])
            });
        }
        let title = match scene {
            ContactScene::FlatDrop => "Cube dropped flat: heights",
            ContactScene::TumblingCube => "Cube dropped tumbling: heights",
        };
        panels.push(Panel::new(
            Labels::new(title, "time (s)", "height above the floor (m)"),
            series,
        ));
    }
    if panels.is_empty() {
        return Ok(None);
    }
    figure_with_caption(
        &dir.join("contacts.png"),
        "Contacts: a cube bouncing on a floor",
        &panels,
        "The cube's lowest corner and its centre above the floor (black). Dropped flat, its four bottom corners \
         land together at the free-fall time (the marker) and it bounces straight up at half the speed; dropped \
         tumbling, its corners bounce until it rests on a face, 0.1 m up.",
    )?;
    Ok(Some("contacts.png"))
}
