//! The report's contact section (docs/contacts.md): the scenes of `scenarios::contacts` in PGA and CGA with
//! DOP853-body at a tolerance of 1e-12, the cube's lowest corner and centre over time, and a table of the
//! transitions, the first impact against free fall, the deepest a corner went below the floor and the energy drift
//! net of the impacts.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::{Cga, Pga};
use scenarios::contacts::ContactScene;
use scene_file::AlgebraKind;

use super::sweep::{run_in, ContactRun, TOLERANCE};
use crate::markdown::{scientific, transition_cells};
use crate::plot::{figure_with_caption, Labels, Panel, PlotError, Series};
use crate::runs::in_both_algebras;

/// The section: every contact scene in both algebras, a figure and a table.
pub(crate) fn contacts_section(dir: &Path) -> Result<String, PlotError> {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## Contacts (docs/contacts.md)\n\nA contact keeps a body point above a world plane, exactly and without \
         friction: its impact is located to round-off, corners touching together take their impulses together (none \
         pulling: complementarity), and a corner that stops is held by a row of the articulated solve while the floor \
         pushes. A 0.2 m cube's eight corners are kept above the floor, restitution 0.5; the scenes of \
         `scenarios::contacts` run with DOP853-body at a tolerance of {TOLERANCE:e}, PGA and CGA.\n"
    );
    let run = |scene, algebra| match algebra {
        AlgebraKind::Pga => run_in::<Pga>(scene, algebra),
        AlgebraKind::Cga => run_in::<Cga>(scene, algebra),
    };
    let runs = in_both_algebras(&ContactScene::ALL, ContactScene::label, run, &mut out);
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
    if !panels.is_empty() {
        figure_with_caption(
            &dir.join("contacts.png"),
            "Contacts: a cube bouncing on a floor",
            &panels,
            "The cube's lowest corner and its centre above the floor (black). Dropped flat, its four bottom corners \
             land together at the free-fall time (the marker) and it bounces straight up at half the speed; dropped \
             tumbling, its corners bounce until it rests on a face, 0.1 m up.",
        )?;
        let _ = writeln!(out, "![contacts.png](contacts.png)\n");
    }
    let _ = writeln!(
        out,
        "| scene | algebra | bounces | holds | releases | first impact (s) | free fall (s) | deepest below the floor \
         (m) | energy drift net of impacts (J) | steps | CPU (s) |\n|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for run in &runs {
        let exact = (run.scene.exact_first_impact()).map_or("–".to_owned(), |t| format!("{t:.15}"));
        let _ = writeln!(
            out,
            "| {} | {} | {} | {exact} | {} | {} | {} | {} |",
            run.scene.label(),
            run.algebra.name(),
            transition_cells(&run.transitions),
            scientific(run.deepest()),
            scientific(run.drift()),
            run.steps,
            scientific(run.stepping_time.as_secs_f64()),
        );
    }
    let _ = writeln!(out);
    Ok(out)
}
