//! The ground figure: Solo-12's base height as it lands on its feet and stands; the crate's, pill's, gem's and can's
//! centres as they bounce and come to rest on the floor; and, on their own axes, how far the billiard balls and the box a UR5
//! pushes travel, and the height of a box thrown off a ledge.

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

/// A body's horizontal distance from where it started, over a run's samples (dashed for CGA).
fn travel(run: &AlgebraRun, body: usize, label: &str) -> Series {
    let start = run.bodies[body][0].position.xy();
    Series {
        dashed: run.algebra == scene_file::AlgebraKind::Cga,
        ..Series::line(
            format!("{label}, {}", run.algebra.name()),
            (run.bodies[body].iter())
                .map(|s| (s.t, (s.position.xy() - start).norm()))
                .collect(),
        )
    }
}

/// The runs the figure draws, each empty if its scene failed.
pub(crate) struct Scenes<'r> {
    pub robot: &'r [AlgebraRun],
    pub shapes: &'r [AlgebraRun],
    pub billiards: &'r [AlgebraRun],
    pub push: &'r [AlgebraRun],
    pub ledge: &'r [AlgebraRun],
}

/// Draws the figures of the scenes' runs into `dir`: heights (the robot and the shapes), and distances travelled (the
/// bodies meeting bodies), each on its own axes; returns the files drawn.
pub(crate) fn draw(dir: &Path, scenes: &Scenes<'_>) -> Result<Vec<&'static str>, PlotError> {
    let Scenes {
        robot,
        shapes,
        billiards,
        push,
        ledge,
    } = *scenes;
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
    // Two bodies to a panel: each drawn in both algebras, within the colours one axis may use.
    let pairs: Vec<Vec<usize>> = shapes.first().map_or_else(Vec::new, |run| {
        (0..run.names.len())
            .collect::<Vec<_>>()
            .chunks(2)
            .map(<[usize]>::to_vec)
            .collect()
    });
    let titles: Vec<String> = (pairs.iter())
        .map(|pair| {
            let names: Vec<&str> = pair.iter().map(|&b| shapes[0].names[b].as_str()).collect();
            format!("The {} dropped onto a floor", names.join(" and the "))
        })
        .collect();
    for (pair, title) in pairs.iter().zip(&titles) {
        let series = (shapes.iter())
            .flat_map(|run| pair.iter().map(move |&body| heights(run, body, &run.names[body])))
            .collect();
        panels.push(Panel::new(Labels::new(title, "time (s)", "centre height (m)"), series));
    }
    let mut drawn = Vec::new();
    if !panels.is_empty() {
        figure_with_caption(
            &dir.join("ground.png"),
            "Bodies on the ground: Coulomb friction and collision shapes",
            &panels,
            "Top: Solo-12's base (foot spheres, friction 0.8, a PD stance) lands 3 cm below its start, its feet stick \
             and it settles and stands still. Below: a box, a capsule, a convex hull and a cylinder dropped onto a \
             floor with friction 0.5 bounce on their corners, ends, vertices and cap rims and come to rest on a face, \
             on a side, on a face of the hull and on a side.",
        )?;
        drawn.push("ground.png");
    }
    let mut series = Vec::new();
    for run in billiards {
        for (body, name) in run.names.iter().enumerate().filter(|(_, n)| *n == "cue" || *n == "red") {
            series.push(travel(run, body, &format!("{name} ball")));
        }
    }
    for run in push {
        if let Some(body) = run.names.iter().position(|n| n == "box") {
            series.push(travel(run, body, "box pushed by the UR5"));
        }
    }
    if !series.is_empty() {
        let mut panels = vec![Panel::new(
            Labels::new("Bodies meeting bodies", "time (s)", "distance travelled (m)"),
            series,
        )];
        let tumbling: Vec<Series> = (ledge.iter())
            .filter_map(|run| Some(heights(run, run.names.iter().position(|n| n == "box")?, "box")))
            .collect();
        if !tumbling.is_empty() {
            panels.push(Panel::new(
                Labels::new("A box thrown off a ledge", "time (s)", "centre height (m)"),
                tumbling,
            ));
        }
        figure_with_caption(
            &dir.join("bodies_meeting.png"),
            "Bodies meeting bodies: [[collision]] pairs",
            &panels,
            "A cue ball slides, rolls and meets a red ball off centre, and the red ball rolls off \
             (scenes/stack_and_billiards.toml, where a stack of three boxes rests beside them); a ball welded to a \
             UR5's flange sweeps into a box on a table, which slides on and stops (scenes/ur5_pushes_a_box.toml). \
             Below: a box slides across a ledge, tips over its edge on its bottom edges, falls, lands on an edge and \
             tumbles to rest on the floor, kept off the ledge by all the two boxes' vertex-face and edge-edge pairs \
             (scenes/box_off_a_ledge.toml).",
        )?;
        drawn.push("bodies_meeting.png");
    }
    Ok(drawn)
}
