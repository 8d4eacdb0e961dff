//! The scene job's plots: the energy change over time and, where there are joints to measure, the largest
//! constraint violation up to each time; PGA dark and solid, CGA light and dashed, as in the main job's plots.

use std::path::{Path, PathBuf};

use scene_file::CheckedScene;

use super::describe::stepping;
use super::run::AlgebraRun;
use crate::panels::{running_max, styled, LOG_FLOOR};
use crate::plot::{chart, Labels, Panel, PlotError, Series};

/// Draws the plots of `runs` into `output`, named after `stem` and titled `title`, the energy change `relative` to
/// |E₀| or in J; returns their paths.
pub(crate) fn draw(
    output: &Path,
    (stem, title): (&str, &str),
    scene: &CheckedScene,
    runs: &[AlgebraRun],
    relative: bool,
) -> Result<Vec<PathBuf>, PlotError> {
    let over_time = |values: fn(&AlgebraRun) -> Vec<f64>| -> Vec<Series> {
        runs.iter()
            .map(|run| {
                let points = run.bodies[0].iter().zip(values(run)).map(|(s, v)| (s.t, v)).collect();
                // PGA dark and solid, CGA light and dashed, as in the main job's plots.
                styled(Series::line(run.algebra.name(), points), run.algebra, 0)
            })
            .collect()
    };
    let mut files = Vec::new();
    let energy_title = format!("{title}: energy change, {}", stepping(scene));
    let energy_axis = if relative {
        "|E(t) − E₀| / |E₀|"
    } else {
        "|E(t) − E₀| (J)"
    };
    let energy_path = output.join(format!("{stem}_energy.png"));
    let labels = Labels::new(&energy_title, "time (s)", energy_axis);
    chart(
        &energy_path,
        &Panel::new(labels, over_time(|r| r.energy_change.clone())).log_y_with_floor(LOG_FLOOR),
    )?;
    files.push(energy_path);
    if !scene.layout.joints.is_empty() || scene.robot.is_some() {
        let violation_title = format!("{title}: constraint violation, {}", stepping(scene));
        let violation_path = output.join(format!("{stem}_violation.png"));
        // The running maximum: per-sample violations at round-off are noise that hides the curves.
        let labels = Labels::new(&violation_title, "time (s)", "largest constraint violation up to t (m)");
        let panel = Panel::new(labels, over_time(|r| running_max(&r.violation)))
            .log_y_with_floor(LOG_FLOOR)
            .note("The largest violation over all joints from the start up to each sample (running maximum).");
        chart(&violation_path, &panel)?;
        files.push(violation_path);
    }
    Ok(files)
}
