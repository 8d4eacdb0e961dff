//! The joint limits' figures: the limited joint's angle over time against its bounds (the first impact's closed form
//! marked), and the energy dropping at the impacts.

use std::path::Path;

use scenarios::limits::LimitScene;
use scene_file::AlgebraKind;

use super::sweep::LimitRun;
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};

/// Draws the figures of `runs` into `dir`; returns their file names.
pub(crate) fn draw(dir: &Path, runs: &[LimitRun]) -> Result<Vec<&'static str>, PlotError> {
    let mut drawn = Vec::new();
    let (mut angles, mut energies) = (Vec::new(), Vec::new());
    for scene in LimitScene::ALL {
        let of_scene: Vec<&LimitRun> = runs.iter().filter(|run| run.scene == scene).collect();
        let Some(first) = of_scene.first() else {
            continue;
        };
        let end = scene.duration();
        let limit = scene.limit();
        let mut series: Vec<Series> = (of_scene.iter())
            .map(|run| Series {
                dashed: run.algebra == AlgebraKind::Cga,
                ..Series::line(
                    run.algebra.name(),
                    run.samples.iter().map(|&(t, q, _)| (t, q)).collect(),
                )
            })
            .collect();
        // The bounds within the swing, as one path (a box from the start to the end when both are).
        let bounds: Vec<f64> = [limit.lower(), limit.upper()]
            .into_iter()
            .filter(|b| b.abs() <= 1.0)
            .collect();
        let mut path = Vec::new();
        for (k, bound) in bounds.iter().enumerate() {
            let (from, to) = if k % 2 == 0 { (0.0, end) } else { (end, 0.0) };
            path.extend([(from, *bound), (to, *bound)]);
        }
        series.push(Series::reference_line("bounds", path));
        if let Some(Ok(exact)) = scene.exact_first_impact() {
            series.push(Series {
                markers_only: true,
                ..Series::line("closed-form impact", vec![(exact, limit.upper())])
            });
        }
        let title = match scene {
            LimitScene::StoppingPendulum => "Pendulum stopping at a limit: its angle",
            LimitScene::BouncingDoublePendulum => "Double pendulum bouncing off a limit: the elbow",
        };
        angles.push(Panel::new(Labels::new(title, "time (s)", "joint angle (rad)"), series));
        let start = first.samples.first().map_or(0.0, |s| s.2);
        let change = first.samples.iter().map(|&(t, _, e)| (t, e - start)).collect();
        let title = match scene {
            LimitScene::StoppingPendulum => "Pendulum stopping at a limit: energy change",
            LimitScene::BouncingDoublePendulum => "Double pendulum bouncing off a limit: energy change",
        };
        energies.push(Panel::new(
            Labels::new(title, "time (s)", "E(t) − E₀ (J)"),
            vec![Series::line(first.algebra.name(), change)],
        ));
    }
    for (name, title, panels, caption) in [
        (
            "limits.png",
            "Joint limits: the limited joint's angle",
            angles,
            "The limited joint's angle and its bounds within the swing (dashed black): the pendulum meets its bound at \
             the time the incomplete elliptic integral gives (the marker) and stays there; the elbow bounces off \
             ±0.3 rad at restitution 0.5.",
        ),
        (
            "limits_energy.png",
            "Joint limits: the energy",
            energies,
            "The energy drops at each impact (restitution 0 for the pendulum, 0.5 for the elbow) by what the impact \
             takes, and holds between them.",
        ),
    ] {
        if panels.is_empty() {
            continue;
        }
        figure_with_caption(&dir.join(name), title, &panels, caption)?;
        drawn.push(name);
    }
    Ok(drawn)
}
