//! The command line of the main job (`cargo run --release -- --help`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, ValueEnum};
use dynamics::constraints::Stabilisation;
use dynamics::integrate::{Integrator, Method, SplittingMethod};
use reference::SceneId;

use crate::job::run_job;
use crate::sweep::SweepPlan;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SceneName {
    Cuboid,
    Pendulum,
    TopCusp,
    TopSteady,
    RodOnSphere,
    RodOnCircle,
}

impl From<SceneName> for SceneId {
    fn from(name: SceneName) -> SceneId {
        match name {
            SceneName::Cuboid => SceneId::Cuboid,
            SceneName::Pendulum => SceneId::Pendulum,
            SceneName::TopCusp => SceneId::TopCusp,
            SceneName::TopSteady => SceneId::TopSteady,
            SceneName::RodOnSphere => SceneId::RodOnSphere,
            SceneName::RodOnCircle => SceneId::RodOnCircle,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorName {
    Rk4,
    Rkmk4,
    Rkmk4Body,
    Strang,
    Yoshida4,
}

impl From<IntegratorName> for Integrator {
    fn from(name: IntegratorName) -> Integrator {
        match name {
            IntegratorName::Rk4 => Integrator::General(Method::Rk4),
            IntegratorName::Rkmk4 => Integrator::General(Method::Rkmk4),
            IntegratorName::Rkmk4Body => Integrator::General(Method::Rkmk4Body),
            IntegratorName::Strang => Integrator::Splitting(SplittingMethod::Strang),
            IntegratorName::Yoshida4 => Integrator::Splitting(SplittingMethod::Yoshida4),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StabilisationName {
    /// Post-step projection onto the constraint manifold (SPEC §10).
    Projection,
    /// Baumgarte feedback, α = β = 10 (SPEC §10).
    Baumgarte,
    /// None: bare acceleration-level constraints (they drift).
    None,
}

impl From<StabilisationName> for Stabilisation {
    fn from(name: StabilisationName) -> Stabilisation {
        match name {
            StabilisationName::Projection => Stabilisation::PROJECTION,
            StabilisationName::Baumgarte => Stabilisation::Baumgarte {
                alpha: 10.0,
                beta: 10.0,
            },
            StabilisationName::None => Stabilisation::None,
        }
    }
}

/// Runs every reference scene in CGA and PGA with each integrator over a sweep of step sizes, and writes a
/// work-precision report (report.md), PNG plots and the trajectories as CSV.
#[derive(Debug, Parser)]
#[command(version, about)]
pub struct Options {
    /// Scenes to run (default: all).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub scenes: Vec<SceneName>,
    /// Integrators (default: all; splittings run on the free body only).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub integrators: Vec<IntegratorName>,
    /// Step sizes in seconds; each must divide the 0.01 s sample interval.
    #[arg(long, value_delimiter = ',', default_values_t = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4])]
    pub steps: Vec<f64>,
    /// Simulated time in seconds for every scene (default: each scene's T from SCENES.md).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Output folder.
    #[arg(long, default_value = "out")]
    pub output: PathBuf,
    /// Worker threads (default: one per core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// How constrained scenes are kept on their constraint manifold.
    #[arg(long, value_enum, default_value_t = StabilisationName::Projection)]
    pub stabilisation: StabilisationName,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

impl Options {
    /// The sweep these options describe.
    pub fn plan(&self) -> SweepPlan {
        let scenes = if self.scenes.is_empty() {
            SceneId::ALL.to_vec()
        } else {
            self.scenes.iter().map(|&s| s.into()).collect()
        };
        let integrators = if self.integrators.is_empty() {
            crate::sweep::default_integrators()
        } else {
            self.integrators.iter().map(|&i| i.into()).collect()
        };
        SweepPlan {
            scenes,
            integrators,
            steps: self.steps.clone(),
            duration: self.duration,
            stabilisation: self.stabilisation.into(),
        }
    }
}

/// Parses the command line, runs the job and prints where the output went.
pub fn main() -> ExitCode {
    let options = Options::parse();
    if let Some(threads) = options.threads {
        if let Err(error) = rayon::ThreadPoolBuilder::new().num_threads(threads).build_global() {
            eprintln!("cannot start {threads} threads: {error}");
            return ExitCode::FAILURE;
        }
    }
    let started = std::time::Instant::now();
    match run_job(&options.plan(), &options.output, !options.quiet) {
        Ok(summary) => {
            println!(
                "{} runs in {:.1} s ({} failed); report, plots and trajectories in {}",
                summary.results.len(),
                started.elapsed().as_secs_f64(),
                summary.failures,
                summary.output.join("report.md").display()
            );
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
