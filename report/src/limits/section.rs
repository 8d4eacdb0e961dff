//! The report's joint-limit section (docs/limits.md): the scenes of `scenarios::limits` in PGA and CGA with
//! DOP853-body at a tolerance of 1e-12, the limited coordinate over time against its bounds, the energy, and a table
//! of the transitions, the first impact against its closed form, how far a bound was passed and the energy drift net
//! of the impacts.

use std::fmt::Write as _;
use std::path::Path;

use scenarios::limits::LimitScene;

use super::figures;
use super::sweep::{run, TOLERANCE};
use crate::markdown::{scientific, transition_cells};
use crate::plot::PlotError;
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
    let runs = in_both_algebras(&LimitScene::ALL, LimitScene::label, run, &mut out);
    for name in figures::draw(dir, &runs)? {
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
