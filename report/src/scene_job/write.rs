//! Running a scene file (`--scene-file`) and writing its output folder: its trajectories (CSV), energy and
//! constraint-violation plots and `summary.md`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use dynamics::integrate::Integrator;
use dynamics::simulate::Sample;
use dynamics::{Cga, Pga};
use scene_file::{AlgebraKind, Scene, SceneFileError};

use super::describe::{element_list, robot_summary, stepping};
use super::run::{run_in, AlgebraRun, ABSOLUTE_ENERGY_BELOW, ENERGY_WARNING};
use super::summary::{summary, Setup};
use crate::csv;
use crate::markdown::scientific;
use crate::panels::{running_max, styled, LOG_FLOOR};
use crate::plot::{chart, Labels, Panel, PlotError, Series};

/// Why a scene file's run or output failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneJobError {
    /// The file cannot run, or its run failed.
    #[error(transparent)]
    Scene(#[from] SceneFileError),
    /// An output folder or file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The folder or file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

/// What the job wrote.
#[derive(Clone, Debug)]
pub struct SceneJobSummary {
    /// One per requested algebra, PGA first.
    pub runs: Vec<AlgebraRun>,
    /// Runs whose result is suspect (a conservative scene whose energy changed by more than
    /// [`ENERGY_WARNING`]), said in words; also in `summary.md`.
    pub warnings: Vec<String>,
}

/// Writes a robot's joints CSV: `t`, the columns, `energy`.
fn write_joints(path: &Path, headers: &[String], rows: &[Vec<f64>], samples: &[Sample]) -> std::io::Result<()> {
    let mut text = String::from("t");
    for header in headers {
        let _ = write!(text, ",{header}");
    }
    text.push_str(",energy\n");
    for (row, sample) in rows.iter().zip(samples) {
        let _ = write!(text, "{:e}", sample.t);
        for value in row {
            let _ = write!(text, ",{value:e}");
        }
        let _ = writeln!(text, ",{:e}", sample.energy);
    }
    std::fs::write(path, text)
}

/// Loads the scene file at `path`, runs it and writes the output into `output`.
pub fn run_scene_file(path: &Path, output: &Path) -> Result<SceneJobSummary, SceneJobError> {
    let scene = Scene::load(path)?;
    let checked = scene.checked();
    let layout = &checked.layout;
    let runs = checked
        .algebra
        .algebras()
        .into_iter()
        .map(|algebra| match algebra {
            AlgebraKind::Pga => run_in::<Pga>(algebra, &scene),
            AlgebraKind::Cga => run_in::<Cga>(algebra, &scene),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let robot = checked.robot.as_ref().map(|robot| robot_summary(&robot.loaded));

    let write_error = |path: &Path| {
        let path = path.to_path_buf();
        move |source| SceneJobError::Write { path, source }
    };
    std::fs::create_dir_all(output).map_err(write_error(output))?;
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    let title = checked.title.clone().unwrap_or_else(|| stem.to_owned());
    let mut files = Vec::new();
    for run in &runs {
        let csv_path = output.join(format!("{stem}_{}.csv", run.algebra.name().to_lowercase()));
        let written = if layout.named {
            let names: Vec<&str> = run.names.iter().map(String::as_str).collect();
            csv::write_bodies(&csv_path, &names, &run.bodies)
        } else {
            csv::write(&csv_path, &run.bodies[0])
        };
        written.map_err(write_error(&csv_path))?;
        files.push(csv_path);
        if let Some((headers, rows)) = &run.joints {
            let joints_path = output.join(format!("{stem}_joints_{}.csv", run.algebra.name().to_lowercase()));
            write_joints(&joints_path, headers, rows, &run.bodies[0]).map_err(write_error(&joints_path))?;
            files.push(joints_path);
        }
    }

    let over_time = |values: fn(&AlgebraRun) -> Vec<f64>| -> Vec<Series> {
        runs.iter()
            .map(|run| {
                let points = run.bodies[0].iter().zip(values(run)).map(|(s, v)| (s.t, v)).collect();
                // PGA dark and solid, CGA light and dashed, as in the main job's plots.
                styled(Series::line(run.algebra.name(), points), run.algebra, 0)
            })
            .collect()
    };
    // Relative to E₀ unless it is (nearly) zero (every run starts from the same state, so the same E₀).
    let relative = runs
        .first()
        .and_then(|r| r.bodies[0].first())
        .is_some_and(|s| s.energy.abs() >= ABSOLUTE_ENERGY_BELOW);
    let energy_title = format!("{title}: energy change, {}", stepping(checked));
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
    if !layout.joints.is_empty() || robot.is_some() {
        let violation_title = format!("{title}: constraint violation, {}", stepping(checked));
        let violation_path = output.join(format!("{stem}_violation.png"));
        // The running maximum: per-sample violations at round-off are noise that hides the curves.
        let labels = Labels::new(&violation_title, "time (s)", "largest constraint violation up to t (m)");
        let panel = Panel::new(labels, over_time(|r| running_max(&r.violation)))
            .log_y_with_floor(LOG_FLOOR)
            .note("The largest violation over all joints from the start up to each sample (running maximum).");
        chart(&violation_path, &panel)?;
        files.push(violation_path);
    }

    let summary_path = output.join("summary.md");
    let file_names: Vec<String> = files
        .iter()
        .filter_map(|f| f.file_name().and_then(|n| n.to_str()).map(str::to_owned))
        .collect();
    let conservative = checked.conservative;
    let warnings: Vec<String> = runs
        .iter()
        .filter(|run| conservative && run.max_energy_change() > ENERGY_WARNING)
        .map(|run| {
            format!(
                "{}: the energy of this conservative scene changed by {}{} (more than {ENERGY_WARNING:e}): the \
                 steps ({}) are probably too coarse for its motion",
                run.algebra.name(),
                scientific(run.max_energy_change()),
                if relative { "" } else { " J" },
                stepping(checked)
            )
        })
        .collect();
    let setup = Setup {
        scene: checked,
        layout,
        conservative,
        path,
        title: &title,
        stabilisation: checked.stabilisation,
        relative_energy: relative,
        robot: robot.as_deref(),
        elements: element_list(checked),
        splitting: matches!(Integrator::from(checked.integrator), Integrator::Splitting(_)),
    };
    let mut text = summary(&setup, &runs, &file_names);
    for warning in &warnings {
        let _ = writeln!(text, "\n**Warning**: {warning}.");
    }
    std::fs::write(&summary_path, text).map_err(write_error(&summary_path))?;
    Ok(SceneJobSummary { runs, warnings })
}
