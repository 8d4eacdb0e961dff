//! Running a scene file (`--scene-file`) and writing its output folder: its trajectories (CSV), energy and
//! constraint-violation plots and `summary.md`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use dynamics::{Cga, Pga};
use scene_file::{AlgebraKind, CheckedScene, Scene, SceneFileError};

use super::describe::stepping;
use super::figures;
use super::run::{run_in, AlgebraRun, ABSOLUTE_ENERGY_BELOW, ENERGY_WARNING};
use super::summary::{summary, Setup};
use crate::csv;
use crate::markdown::scientific;
use crate::plot::PlotError;

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

/// Loads the scene file at `path`, runs it and writes the output into `output`.
pub fn run_scene_file(path: &Path, output: &Path) -> Result<SceneJobSummary, SceneJobError> {
    let scene = Scene::load(path)?;
    let checked = scene.checked();
    let runs = checked
        .algebra
        .algebras()
        .into_iter()
        .map(|algebra| match algebra {
            AlgebraKind::Pga => run_in::<Pga>(algebra, &scene),
            AlgebraKind::Cga => run_in::<Cga>(algebra, &scene),
        })
        .collect::<Result<Vec<_>, _>>()?;
    std::fs::create_dir_all(output).map_err(write_error(output))?;
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    let title = checked.title.clone().unwrap_or_else(|| stem.to_owned());
    // Relative to E₀ unless it is (nearly) zero (every run starts from the same state, so the same E₀).
    let relative = runs
        .first()
        .and_then(|r| r.bodies[0].first())
        .is_some_and(|s| s.energy.abs() >= ABSOLUTE_ENERGY_BELOW);
    let mut files = write_trajectories(output, stem, checked, &runs)?;
    files.extend(figures::draw(output, (stem, &title), checked, &runs, relative)?);
    let file_names: Vec<String> = files
        .iter()
        .filter_map(|f| f.file_name().and_then(|n| n.to_str()).map(str::to_owned))
        .collect();
    let warnings = energy_warnings(checked, &runs, relative);
    let setup = Setup {
        scene: checked,
        path,
        title: &title,
        relative_energy: relative,
    };
    let mut text = summary(&setup, &runs, &file_names);
    for warning in &warnings {
        let _ = writeln!(text, "\n**Warning**: {warning}.");
    }
    let summary_path = output.join("summary.md");
    std::fs::write(&summary_path, text).map_err(write_error(&summary_path))?;
    Ok(SceneJobSummary { runs, warnings })
}

/// The error of writing `path`.
fn write_error(path: &Path) -> impl FnOnce(std::io::Error) -> SceneJobError {
    let path = path.to_path_buf();
    move |source| SceneJobError::Write { path, source }
}

/// Writes each run's trajectory CSV into `output`, named after `stem` and its algebra, and with a robot its joints CSV;
/// returns their paths.
fn write_trajectories(
    output: &Path,
    stem: &str,
    scene: &CheckedScene,
    runs: &[AlgebraRun],
) -> Result<Vec<PathBuf>, SceneJobError> {
    let mut files = Vec::new();
    for run in runs {
        let csv_path = output.join(format!("{stem}_{}.csv", run.algebra.name().to_lowercase()));
        let written = if scene.layout.named {
            let names: Vec<&str> = run.names.iter().map(String::as_str).collect();
            csv::write_bodies(&csv_path, &names, &run.bodies)
        } else {
            csv::write(&csv_path, &run.bodies[0])
        };
        written.map_err(write_error(&csv_path))?;
        files.push(csv_path);
        if let Some((headers, rows)) = &run.joints {
            let joints_path = output.join(format!("{stem}_joints_{}.csv", run.algebra.name().to_lowercase()));
            csv::write_joints(&joints_path, headers, rows, &run.bodies[0]).map_err(write_error(&joints_path))?;
            files.push(joints_path);
        }
    }
    Ok(files)
}

/// The runs whose result is suspect, in words: a conservative scene whose energy changed by more than
/// [`ENERGY_WARNING`], or another whose energy change less what its impacts and its forces without a potential did,
/// `E − E₀ − L − W`, is more than that (`relative` to |E₀|, or in J). A run on fixed steps is told that a tolerance
/// chooses the steps by the error.
fn energy_warnings(scene: &CheckedScene, runs: &[AlgebraRun], relative: bool) -> Vec<String> {
    let unit = if relative { "" } else { " J" };
    let advice = if scene.schedule.tolerance().is_none() {
        "; a `tolerance` in place of `dt` would choose them by the error"
    } else {
        ""
    };
    runs.iter()
        .filter_map(|run| {
            let scale = match run.bodies[0].first() {
                Some(first) if relative => first.energy.abs(),
                _ => 1.0,
            };
            let unexplained = run.unexplained_energy().abs() / scale;
            if scene.conservative && run.max_energy_change() > ENERGY_WARNING {
                Some(format!(
                    "{}: the energy of this conservative scene changed by {}{unit} (more than {ENERGY_WARNING:e}): the \
                     steps ({}) are probably too coarse for its motion{advice}",
                    run.algebra.name(),
                    scientific(run.max_energy_change()),
                    stepping(scene)
                ))
            } else if !scene.conservative && unexplained > ENERGY_WARNING {
                Some(format!(
                    "{}: the energy change less what the impacts and the forces without a potential did, E − E₀ − L − \
                     W, is {}{unit} at the end (more than {ENERGY_WARNING:e}): the steps ({}) are probably too coarse \
                     for its motion{advice}",
                    run.algebra.name(),
                    scientific(unexplained),
                    stepping(scene)
                ))
            } else {
                None
            }
        })
        .collect()
}
