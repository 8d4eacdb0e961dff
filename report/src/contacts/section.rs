//! The report's contact section (docs/contacts.md): the scenes of `scenarios::contacts` in PGA and CGA with
//! DOP853-body at a tolerance of 1e-12, the cube's lowest corner and centre over time, and a table of the
//! transitions, the first impact against free fall, the deepest a corner went below the floor and the energy drift
//! net of the impacts.

use std::fmt::Write as _;
use std::path::Path;

use scenarios::contacts::ContactScene;

use super::figures;
use super::sweep::{run, TOLERANCE};
use crate::markdown::{scientific, transition_cells};
use crate::plot::PlotError;
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
    let runs = in_both_algebras(&ContactScene::ALL, ContactScene::label, run, &mut out);
    if let Some(name) = figures::draw(dir, &runs)? {
        let _ = writeln!(out, "![{name}]({name})\n");
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
