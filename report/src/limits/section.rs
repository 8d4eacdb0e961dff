//! The report's joint-limit section (docs/limits.md): the scenes of `scenarios::limits` in PGA and CGA with
//! DOP853-body at a tolerance of 1e-12, the limited coordinate over time against its bounds, the energy, and a table
//! of the transitions, the first impact against its closed form, how far a bound was passed and the energy drift net
//! of the impacts.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::{Cga, Pga};
use scenarios::limits::LimitScene;
use scene_file::AlgebraKind;

use super::sweep::{run_in, LimitRun, TOLERANCE};
use crate::markdown::{scientific, transition_cells};
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};
use crate::runs::in_both_algebras;

/// The section: every limit scene in both algebras, a figure and a table.
pub(crate) fn limits_section(dir: &Path) -> Result<String, PlotError> {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## Joint limits (docs/limits.md)\n\nJoint limits are one-sided constraints, enforced exactly: a bound is met \
         in an impact located to round-off (Newton's restitution, an impulse through the joint-space mass matrix); \
         the joint is held on it by a joint-space row while the bound pushes, and released where the bound would \
         pull. The scenes of `scenarios::limits` run with DOP853-body at a tolerance of {TOLERANCE:e}, PGA and CGA.\n"
    );
    let run = |scene, algebra| match algebra {
        AlgebraKind::Pga => run_in::<Pga>(scene, algebra),
        AlgebraKind::Cga => run_in::<Cga>(scene, algebra),
    };
    let runs = in_both_algebras(&LimitScene::ALL, LimitScene::label, run, &mut out);
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
        let _ = writeln!(out, "![{name}]({name})\n");
    }
    let _ = writeln!(
        out,
        "| scene | algebra | bounces | holds | releases | first impact (s) | closed form (s) | past a bound (rad) | \
         energy drift net of impacts (J) | steps | CPU (s) |\n|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for run in &runs {
        let exact = match run.scene.exact_first_impact() {
            Some(Ok(exact)) => format!("{exact:.15}"),
            Some(Err(error)) => error.to_string(),
            None => "–".to_owned(),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {exact} | {} | {} | {} | {} |",
            run.scene.label(),
            run.algebra.name(),
            transition_cells(&run.transitions),
            scientific(run.passed()),
            scientific(run.drift()),
            run.steps,
            scientific(run.stepping_time.as_secs_f64()),
        );
    }
    let _ = writeln!(out);
    Ok(out)
}
