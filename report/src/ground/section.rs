//! The report's section on bodies on the ground (docs/contacts.md): `scenes/solo12_standing.toml`,
//! `scenes/shapes_on_a_floor.toml`, `scenes/stack_and_billiards.toml`, `scenes/ur5_pushes_a_box.toml` and
//! `scenes/box_off_a_ledge.toml` run as the
//! scene job runs them (written under `ground/`), a figure, and a table of their transitions, the deepest any contact
//! went below its plane or into another shape, the energy balance and the cost.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::figures;
use crate::markdown::{scientific, TransitionCounts};
use crate::plot::PlotError;
use crate::scene_job::{run_scene_file, AlgebraRun};

/// The shipped scene files the section runs.
const SCENES: [&str; 5] = [
    "solo12_standing.toml",
    "shapes_on_a_floor.toml",
    "stack_and_billiards.toml",
    "ur5_pushes_a_box.toml",
    "box_off_a_ledge.toml",
];

/// The repository's `scenes/` folder (the section runs the files shipped there).
fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// The section: both scene files in both algebras, a figure and a table.
pub(crate) fn ground_section(dir: &Path) -> Result<String, PlotError> {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## Bodies on the ground (docs/contacts.md)\n\nCoulomb friction at exact contacts: a sliding contact's \
         push carries μN against its slip, a sticking one holds two more rows while its force stays in the cone, and \
         every stop and slip is located as impacts are. Collision shapes (boxes, capsules, cylinders, convex hulls) stay \
         above `[[plane]]`s through their corners, end spheres, cap rims and vertices, and apart in `[[collision]]` \
         pairs: a capsule end or rim of one body on a face of another, two balls, and a sphere and a polytope or two \
         polytopes by all their vertex, edge and face pairs, each a contact only where its features meet. The shipped scene files below run as \
         `cargo run --release -- --scene-file scenes/<name>` runs them (written under `ground/`).\n"
    );
    let mut runs: Vec<(&str, Vec<AlgebraRun>)> = Vec::new();
    for file in SCENES {
        let stem = file.trim_end_matches(".toml");
        match run_scene_file(&scenes().join(file), &dir.join("ground").join(stem)) {
            Ok(summary) => runs.push((stem, summary.runs)),
            Err(error) => {
                let _ = writeln!(out, "{file}: failed: {error}\n");
            }
        }
    }
    let of = |stem: &str| {
        runs.iter()
            .find(|(s, _)| *s == stem)
            .map_or(&[][..], |(_, r)| r.as_slice())
    };
    let scenes = figures::Scenes {
        robot: of("solo12_standing"),
        shapes: of("shapes_on_a_floor"),
        billiards: of("stack_and_billiards"),
        push: of("ur5_pushes_a_box"),
        ledge: of("box_off_a_ledge"),
    };
    for name in figures::draw(dir, &scenes)? {
        let _ = writeln!(out, "![{name}]({name})\n");
    }
    let _ = writeln!(
        out,
        "| scene | algebra | bounces | holds | releases | sticks | slips | deepest into a plane or shape (m) | E − E₀ − L − W \
         (J) | CPU per simulated second (s) |\n|---|---|---|---|---|---|---|---|---|---|"
    );
    for (stem, algebra_runs) in &runs {
        for run in algebra_runs {
            let counts = TransitionCounts::of(&run.transitions);
            let _ = writeln!(
                out,
                "| {stem} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                run.algebra.name(),
                counts.bounces,
                counts.holds,
                counts.releases,
                counts.sticks,
                counts.slips,
                scientific(run.deepest),
                scientific(run.unexplained_energy()),
                scientific(run.cpu_per_simulated_second),
            );
        }
    }
    if let Some(run) = of("solo12_standing").first() {
        let base = &run.bodies[0];
        let settled = base.iter().find(|s| s.t >= 2.0).map(|s| s.position);
        let moved = settled.map_or(f64::NAN, |p| {
            (base.iter().filter(|s| s.t >= 2.0)).fold(0.0, |m, s| f64::max(m, (s.position - p).norm()))
        });
        let _ = writeln!(
            out,
            "\nSolo-12 stands on its sticking feet: from t = 2 s to the end its base moves {} m ({}).",
            scientific(moved),
            run.algebra.name()
        );
    }
    let _ = writeln!(out);
    Ok(out)
}
