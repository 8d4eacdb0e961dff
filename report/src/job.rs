//! The main job: runs a sweep in parallel (rayon) with a progress bar (indicatif) and writes the output
//! folder: `report.md`, the PNG plots and the trajectories as CSV.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use reference::SceneId;

use crate::csv;
use crate::figures::{self, showcase_step};
use crate::markdown::{self, RunResult};
use crate::mechanism_report::mechanism_section;
use crate::mechanism_sweep::{run_mechanism, MechanismPlan, MechanismResult};
use crate::plot::PlotError;
use crate::sweep::{run, Outcome, SweepPlan};

/// Why the job could not write its output.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error("cannot write {path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    #[error(transparent)]
    Plot(#[from] PlotError),
    #[error("the plan has no configuration to run (check the scenes, integrators and steps)")]
    Empty,
}

/// What the job produced.
#[derive(Debug)]
pub struct JobSummary {
    pub output: PathBuf,
    pub results: Vec<RunResult>,
    pub mechanisms: Vec<MechanismResult>,
    /// Failed runs, single bodies and mechanisms.
    pub failures: usize,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> JobError + '_ {
    move |source| JobError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Runs every configuration of `plan` and of `mechanisms` and writes the report into `output`.
pub fn run_job(
    plan: &SweepPlan,
    mechanisms: &MechanismPlan,
    output: &Path,
    show_progress: bool,
) -> Result<JobSummary, JobError> {
    let configs = plan.configurations();
    let mechanism_configs = mechanisms.configurations(&plan.integrators, plan.duration, plan.stabilisation);
    if configs.is_empty() && mechanism_configs.is_empty() {
        return Err(JobError::Empty);
    }
    std::fs::create_dir_all(output).map_err(io(output))?;
    let trajectories = output.join("trajectories");
    std::fs::create_dir_all(&trajectories).map_err(io(&trajectories))?;

    let progress = if show_progress {
        ProgressBar::new((configs.len() + mechanism_configs.len()) as u64)
    } else {
        ProgressBar::hidden()
    };
    progress.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed} elapsed, about {eta} left  {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    // The slowest runs (smallest steps) first, so the pool stays busy to the end.
    let mut order: Vec<usize> = (0..configs.len()).collect();
    order.sort_by(|&a, &b| (configs[a].dt / configs[a].duration).total_cmp(&(configs[b].dt / configs[b].duration)));
    let mut results: Vec<(usize, RunResult)> = order
        .par_iter()
        .map(|&index| {
            let config = configs[index];
            let result = run(&config);
            progress.set_message(format!("{} {}", config.scene.label(), config.series_label()));
            progress.inc(1);
            (index, (config, result))
        })
        .collect();
    // The mechanisms after the single bodies, the longest runs (most steps times most bodies) first.
    let mut mechanism_order: Vec<usize> = (0..mechanism_configs.len()).collect();
    let work = |i: usize| {
        let c = &mechanism_configs[i];
        c.duration / c.dt * c.id.bodies() as f64
    };
    mechanism_order.sort_by(|&a, &b| work(b).total_cmp(&work(a)));
    let mut mechanism_results: Vec<(usize, MechanismResult)> = mechanism_order
        .par_iter()
        .map(|&index| {
            let config = mechanism_configs[index];
            let result = run_mechanism(&config);
            progress.set_message(format!("{} {}", config.id.label(), config.series_label()));
            progress.inc(1);
            (index, (config, result))
        })
        .collect();
    progress.finish_and_clear();
    mechanism_results.sort_by_key(|(index, _)| *index);
    let mechanism_results: Vec<MechanismResult> = mechanism_results.into_iter().map(|(_, r)| r).collect();
    results.sort_by_key(|(index, _)| *index);
    let results: Vec<RunResult> = results.into_iter().map(|(_, r)| r).collect();

    let mut figure_files: HashMap<SceneId, Vec<String>> = HashMap::new();
    for scene in SceneId::ALL {
        let runs: Vec<&RunResult> = results.iter().filter(|(c, _)| c.scene == scene).collect();
        if runs.is_empty() {
            continue;
        }
        figure_files.insert(scene, figures::scene_figures(output, scene, &runs)?);
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
    let threads = rayon::current_num_threads();
    let report_path = output.join("report.md");
    let mut text = markdown::report(&results, threads, &figure_files);
    text.push_str(&mechanism_section(output, &mechanism_results)?);
    std::fs::write(&report_path, text).map_err(io(&report_path))?;
    let failures = results.iter().filter(|(_, r)| r.is_err()).count()
        + mechanism_results.iter().filter(|(_, r)| r.is_err()).count();
    Ok(JobSummary {
        output: output.to_path_buf(),
        results,
        mechanisms: mechanism_results,
        failures,
    })
}
