//! The main job: runs a sweep in parallel (rayon) with a progress bar (indicatif) and writes the output
//! folder: `report.md`, the PNG plots and the trajectories as CSV.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use reference::SceneId;

use crate::adaptive::figures::FixedRuns;
use crate::adaptive::section::adaptive_section;
use crate::adaptive::sweep::{run_adaptive, AdaptivePlan, AdaptiveResult};
use crate::contacts::section::contacts_section;
use crate::csv;
use crate::ground::section::ground_section;
use crate::limits::section::limits_section;
use crate::measured_anchors::Anchors;
use crate::mechanisms::section::mechanism_section;
use crate::mechanisms::sweep::{run_mechanism, MechanismPlan, MechanismResult};
use crate::plot::PlotError;
use crate::robots::section::robot_section;
use crate::robots::sweep::{robot_label, run_robot, RobotPlan, RobotResult};
use crate::single_bodies::figures::{self, showcase_step};
use crate::single_bodies::section;
use crate::single_bodies::sweep::{run, Outcome, RunResult, SweepPlan};

/// Why the job could not write its output.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JobError {
    /// An output folder or file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The folder or file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// The plans select no run (no scene, integrator or step), so there is nothing to report.
    #[error("the plan has no configuration to run (check the scenes, integrators and steps)")]
    Empty,
}

/// What the job produced.
#[derive(Debug)]
pub struct JobSummary {
    pub(crate) output: PathBuf,
    /// Each single-body configuration, in the plan's order, with its outcome or why it failed.
    pub results: Vec<RunResult>,
    /// Each mechanism configuration, in the plan's order, with its outcome or why it failed.
    pub mechanisms: Vec<MechanismResult>,
    /// Each robot configuration, in the plan's order, with its outcome or why it failed.
    pub robots: Vec<RobotResult>,
    /// Each adaptive configuration, in the plan's order, with its outcome or why it failed.
    pub adaptive: Vec<AdaptiveResult>,
    /// Failed runs, single bodies and mechanisms: each run's label and why it failed.
    pub failures: Vec<String>,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> JobError + '_ {
    move |source| JobError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Runs every configuration in parallel, the most `work` first, and returns (configuration, result) in the
/// configurations' order.
fn run_all<C: Copy + Send + Sync, R: Send>(
    configs: &[C],
    work: impl Fn(&C) -> f64,
    run: impl Fn(&C) -> R + Sync,
    label: impl Fn(&C) -> String + Sync,
    progress: &ProgressBar,
) -> Vec<(C, R)> {
    let mut order: Vec<usize> = (0..configs.len()).collect();
    order.sort_by(|&a, &b| work(&configs[b]).total_cmp(&work(&configs[a])));
    let mut results: Vec<(usize, (C, R))> = order
        .par_iter()
        .map(|&index| {
            let config = configs[index];
            let result = run(&config);
            progress.set_message(label(&config));
            progress.inc(1);
            (index, (config, result))
        })
        .collect();
    results.sort_by_key(|(index, _)| *index);
    results.into_iter().map(|(_, r)| r).collect()
}

/// Runs every configuration of `plan` and of `mechanisms` and writes the report into `output`.
pub fn run_job(
    plan: &SweepPlan,
    mechanisms: &MechanismPlan,
    output: &Path,
    show_progress: bool,
) -> Result<JobSummary, JobError> {
    run_job_with_robots(
        plan,
        mechanisms,
        &RobotPlan::default(),
        &AdaptivePlan::default(),
        &Anchors::none(),
        output,
        show_progress,
    )
}

/// [`run_job`], and the reference robots of `robots` with the plan's general integrators (each over the
/// reference's 1 s), and the adaptive runs of `adaptive`; MuJoCo's and Pinocchio's times from `anchors` where it
/// measured them.
pub fn run_job_with_robots(
    plan: &SweepPlan,
    mechanisms: &MechanismPlan,
    robots: &RobotPlan,
    adaptive: &AdaptivePlan,
    anchors: &Anchors,
    output: &Path,
    show_progress: bool,
) -> Result<JobSummary, JobError> {
    let configs = plan.configurations();
    let mechanism_configs = mechanisms.configurations(&plan.integrators, plan.duration, plan.stabilisation);
    let robot_configs = robots.configurations(&plan.integrators);
    let adaptive_configs = adaptive.configurations();
    if configs.is_empty() && mechanism_configs.is_empty() && robot_configs.is_empty() && adaptive_configs.is_empty() {
        return Err(JobError::Empty);
    }
    std::fs::create_dir_all(output).map_err(io(output))?;
    let trajectories = output.join("trajectories");
    std::fs::create_dir_all(&trajectories).map_err(io(&trajectories))?;

    let runs = configs.len() + mechanism_configs.len() + robot_configs.len() + adaptive_configs.len();
    let progress = progress_bar(runs, show_progress);
    // The slowest runs first (smallest steps; for mechanisms, most steps times most bodies), so the pool
    // stays busy to the end.
    let results: Vec<RunResult> = run_all(
        &configs,
        |c| c.duration / c.dt,
        run,
        |c| format!("{} {}", c.scene.label(), c.series_label()),
        &progress,
    );
    let mechanism_results: Vec<MechanismResult> = run_all(
        &mechanism_configs,
        |c| c.duration / c.dt * c.id.bodies() as f64,
        run_mechanism,
        |c| format!("{} {}", c.id.label(), c.series_label()),
        &progress,
    );
    let robot_results: Vec<RobotResult> = run_all(
        &robot_configs,
        |c| c.work(),
        run_robot,
        |c| format!("{} {}", robot_label(c.robot), c.series_label()),
        &progress,
    );
    let adaptive_results: Vec<AdaptiveResult> = run_all(
        &adaptive_configs,
        |c| c.work(),
        run_adaptive,
        |c| format!("{} {}", c.case.label(), c.series_label()),
        &progress,
    );
    progress.finish_and_clear();

    let mut summary = JobSummary {
        output: output.to_path_buf(),
        results,
        mechanisms: mechanism_results,
        robots: robot_results,
        adaptive: adaptive_results,
        failures: Vec::new(),
    };
    let figure_files = single_body_figures(output, &trajectories, &summary.results, anchors)?;
    write_report(&summary, &figure_files, anchors)?;
    summary.failures = failures(&summary);
    Ok(summary)
}

/// A progress bar over `runs` runs, drawn if `shown`.
fn progress_bar(runs: usize, shown: bool) -> ProgressBar {
    let progress = if shown {
        ProgressBar::new(runs as u64)
    } else {
        ProgressBar::hidden()
    };
    progress.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed} elapsed, about {eta} left  {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    progress
}

/// Draws each single-body scene's figures into `output` and writes its showcase step's trajectories into
/// `trajectories`, one CSV per configuration; returns each scene's figure files.
fn single_body_figures(
    output: &Path,
    trajectories: &Path,
    results: &[RunResult],
    anchors: &Anchors,
) -> Result<HashMap<SceneId, Vec<String>>, JobError> {
    let mut figure_files: HashMap<SceneId, Vec<String>> = HashMap::new();
    for scene in SceneId::ALL {
        let runs: Vec<&RunResult> = results.iter().filter(|(c, _)| c.scene == scene).collect();
        if runs.is_empty() {
            continue;
        }
        figure_files.insert(scene, figures::scene_figures(output, scene, &runs, anchors)?);
        // The trajectories of the showcase step, one CSV per configuration.
        let outcomes: Vec<&Outcome> = runs.iter().filter_map(|(_, r)| r.as_ref().ok()).collect();
        if let Some(dt) = showcase_step(&outcomes) {
            for outcome in outcomes.iter().filter(|o| o.config.dt == dt) {
                let name = format!(
                    "{}_{}_dt{:.0e}.csv",
                    figures::stem(scene),
                    outcome
                        .config
                        .series_label()
                        .to_lowercase()
                        .replace(", ", "_")
                        .replace(' ', "-"),
                    dt
                );
                let path = trajectories.join(name);
                csv::write(&path, &outcome.samples).map_err(io(&path))?;
            }
        }
    }
    Ok(figure_files)
}

/// Writes `report.md` into the job's output folder: the single bodies' section (their figures `figure_files`), the
/// mechanisms', the robots', the adaptive runs', the limits', the contacts', and the figures `anchors` measured.
fn write_report(
    job: &JobSummary,
    figure_files: &HashMap<SceneId, Vec<String>>,
    anchors: &Anchors,
) -> Result<(), JobError> {
    let output = &job.output;
    let threads = rayon::current_num_threads();
    let report_path = output.join("report.md");
    let mut text = section::report(&job.results, threads, figure_files, anchors);
    text.push_str(&mechanism_section(output, &job.mechanisms, anchors)?);
    text.push_str(&robot_section(output, &job.robots, anchors)?);
    let fixed = FixedRuns {
        single: &job.results,
        mechanisms: &job.mechanisms,
        robots: &job.robots,
    };
    text.push_str(&adaptive_section(output, &job.adaptive, &fixed)?);
    text.push_str(&limits_section(output)?);
    text.push_str(&contacts_section(output)?);
    text.push_str(&ground_section(output)?);
    text.push_str(&anchors.section());
    std::fs::write(&report_path, text).map_err(io(&report_path))
}

/// Every failed run of the job: its label and why it failed.
fn failures(job: &JobSummary) -> Vec<String> {
    let single_failures = job.results.iter().filter_map(|(config, result)| {
        let error = result.as_ref().err()?;
        Some(format!("{} {}: {error}", config.scene.label(), config.series_label()))
    });
    let mechanism_failures = job.mechanisms.iter().filter_map(|(config, result)| {
        let error = result.as_ref().err()?;
        Some(format!("{} {}: {error}", config.id.label(), config.series_label()))
    });
    let robot_failures = job.robots.iter().filter_map(|(config, result)| {
        let error = result.as_ref().err()?;
        Some(format!(
            "{} {}, dt = {:e}: {error}",
            robot_label(config.robot),
            config.series_label(),
            config.dt
        ))
    });
    let adaptive_failures = job.adaptive.iter().filter_map(|(config, result)| {
        let error = result.as_ref().err()?;
        Some(format!("{} {}: {error}", config.case.label(), config.series_label()))
    });
    single_failures
        .chain(mechanism_failures)
        .chain(robot_failures)
        .chain(adaptive_failures)
        .collect()
}
