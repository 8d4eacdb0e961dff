//! The command line of the main job (`cargo run --release -- --help`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{CommandFactory, Parser, ValueEnum};
use dynamics::simulate::SAMPLE_INTERVAL;
use dynamics::Schedule;
use reference::SceneId;
use scenarios::MechanismId;

use crate::adaptive::sweep::{AdaptiveCase, AdaptivePlan, DEFAULT_TOLERANCES};
use crate::job::run_job_with_robots;
use crate::measured_anchors::Anchors;
use crate::mechanisms::sweep::{MechanismKind, MechanismPlan};
use crate::robots::sweep::RobotPlan;
use crate::scene_job::run_scene_file;
use crate::single_bodies::sweep::{SweepPlan, DEFAULT_STEPS};
use crate::{mechanisms, robots};
use scene_file::names::{IntegratorName, StabilisationName};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SceneName {
    Cuboid,
    Pendulum,
    TopCusp,
    TopSteady,
    RodOnSphere,
    RodOnCircle,
    /// M1 of docs/scenes.md.
    DoublePendulum,
    /// M2 of docs/scenes.md.
    FourBar,
    /// M3 of docs/scenes.md: cost against N, and 64 links over 10 s.
    Chain,
    /// The UR5 arm and the Solo-12 quadruped from their URDFs, against Pinocchio's motion over 1 s.
    Robots,
}

/// A scene name is a single-body scene of the reference set or a mechanism.
enum Named {
    SingleBody(SceneId),
    Mechanism(MechanismKind),
    Robots,
}

impl SceneName {
    fn named(self) -> Named {
        match self {
            SceneName::Cuboid => Named::SingleBody(SceneId::Cuboid),
            SceneName::Pendulum => Named::SingleBody(SceneId::Pendulum),
            SceneName::TopCusp => Named::SingleBody(SceneId::TopCusp),
            SceneName::TopSteady => Named::SingleBody(SceneId::TopSteady),
            SceneName::RodOnSphere => Named::SingleBody(SceneId::RodOnSphere),
            SceneName::RodOnCircle => Named::SingleBody(SceneId::RodOnCircle),
            SceneName::DoublePendulum => Named::Mechanism(MechanismKind::DoublePendulum),
            SceneName::FourBar => Named::Mechanism(MechanismKind::FourBar),
            SceneName::Chain => Named::Mechanism(MechanismKind::Chain),
            SceneName::Robots => Named::Robots,
        }
    }
}

/// Runs every reference scene in CGA and PGA with each integrator over a sweep of step sizes, and writes a
/// work-precision report (report.md), PNG plots and the trajectories as CSV.
#[derive(Debug, Parser)]
#[command(name = "ga-dynamics", version, about)]
pub(crate) struct Options {
    /// Scenes to run (default: all): the single-body scenes and the mechanisms.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub(crate) scenes: Vec<SceneName>,
    /// Integrators (default: all; splittings run on the free body only).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub(crate) integrators: Vec<IntegratorName>,
    /// Step sizes in seconds; each must divide the 0.01 s sample interval (default: 1e-2, 5e-3, 2e-3, 1e-3,
    /// 5e-4, 2e-4, 1e-4; for the double pendulum and the four-bar, down to 2e-4; for the robots 4e-2 to 2.5e-4).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) steps: Vec<f64>,
    /// Tolerances of the adaptive runs, relative and absolute alike (default: 1e-3 to 1e-13 by decades): every scene
    /// also runs with the selected embedded pairs (dp5-body, dop853-body; both by default) at each, in PGA.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) tolerances: Vec<f64>,
    /// Simulated time in seconds for every scene (default: each scene's T from docs/scenes.md; the robots always run
    /// their reference's 1 s).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) duration: Option<f64>,
    /// Output folder (default: out; with --scene-file, out/STEM for a scene file STEM.toml).
    #[arg(long)]
    pub(crate) output: Option<PathBuf>,
    /// Run the scene described in this TOML file (docs/scene-files.md) instead of the sweep: writes its
    /// trajectories (CSV), energy and constraint-violation plots and summary.md.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["scenes", "integrators", "steps", "tolerances", "duration", "stabilisation"])]
    pub(crate) scene_file: Option<PathBuf>,
    /// Worker threads (default: one per core; at most four per core).
    #[arg(long)]
    pub(crate) threads: Option<usize>,
    /// How constrained scenes are kept on their constraint manifold.
    #[arg(long, value_enum, default_value_t = StabilisationName::Projection)]
    pub(crate) stabilisation: StabilisationName,
    /// No progress bar.
    #[arg(long)]
    pub(crate) quiet: bool,
    /// MuJoCo's and Pinocchio's times measured on this machine beside the run by `tools/anchors/measure`
    /// (docs/benchmarks.md); the report compares with them instead of the recorded constants and says which is which.
    #[arg(long, value_name = "FILE", conflicts_with = "scene_file")]
    pub(crate) anchors: Option<PathBuf>,
}

/// The longest `--duration` accepted (s): a sweep runs every configuration for it, down to dt = 1e-4.
pub(crate) const MAX_DURATION: f64 = 1000.0;

/// The most steps one run of the sweep may take, as a scene file's ([`scene_file::MAX_STEPS`]): a step of
/// 1e-12 s would otherwise run for days.
const MAX_STEPS_PER_RUN: f64 = scene_file::MAX_STEPS as f64;

impl Options {
    /// Why these options cannot make a job, if they cannot: every step must give a schedule (positive, finite,
    /// dividing the 0.01 s sample interval, and `--duration` a whole number of them), the duration
    /// must be positive and at most [`MAX_DURATION`], the thread count between one and four per core.
    pub(crate) fn validate(&self) -> Result<(), String> {
        if let Some(duration) = self.duration {
            if !(duration > 0.0 && duration <= MAX_DURATION) {
                return Err(format!(
                    "--duration must be a positive number of seconds, at most {MAX_DURATION}, got {duration}"
                ));
            }
        }
        // Every run is compared with its reference trajectory, so none may run past the shortest selected one, and
        // every sample must fall on the reference's 0.01 s grid.
        if let Some(duration) = self.duration {
            let samples = duration / SAMPLE_INTERVAL;
            if (samples - samples.round()).abs() > 1e-9 * samples {
                return Err(format!(
                    "--duration {duration}: the runs are compared with their references every {SAMPLE_INTERVAL} s, so \
                     the duration must be a whole number of {SAMPLE_INTERVAL} s"
                ));
            }
            if let Some((label, own)) = self
                .references()
                .into_iter()
                .find(|&(_, own)| duration > own * (1.0 + 1e-12))
            {
                return Err(format!(
                    "--duration {duration}: longer than the reference trajectory of {label} ({own} s), which its runs \
                     are compared with"
                ));
            }
        }
        let duration = self.duration.unwrap_or(1.0);
        let longest = self
            .duration
            .into_iter()
            .chain(self.references().into_iter().map(|(_, own)| own))
            .fold(duration, f64::max);
        for &dt in &self.steps {
            Schedule::new(dt, duration).map_err(|error| format!("--steps {dt}: {error}"))?;
            if longest / dt > MAX_STEPS_PER_RUN {
                return Err(format!(
                    "--steps {dt}: {:.0e} steps for {longest} s, more than a run takes (at most {MAX_STEPS_PER_RUN:e})",
                    longest / dt
                ));
            }
        }
        if self.duration.is_some() && self.steps.is_empty() {
            for dt in DEFAULT_STEPS {
                Schedule::new(dt, duration).map_err(|error| format!("--duration {duration}: {error}"))?;
            }
        }
        for &tolerance in &self.tolerances {
            dynamics::Tolerance::new(tolerance, tolerance)
                .map_err(|error| format!("--tolerances {tolerance}: {error}"))?;
        }
        let (plan, mechanisms, robots, adaptive) = self.plan();
        if plan.configurations().is_empty()
            && mechanisms
                .configurations(&plan.integrators, plan.duration, plan.stabilisation)
                .is_empty()
            && robots.configurations(&plan.integrators).is_empty()
            && adaptive.configurations().is_empty()
        {
            return Err(
                "--scenes and --integrators make no run: the splittings (strang, yoshida4) run only scene 1, the free \
                 cuboid, and the joint-coordinate methods (rkmk4-joint, rkmk6-joint, rkmk8-joint) only the robots"
                    .to_owned(),
            );
        }
        if let Some(threads) = self.threads {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            if threads == 0 || threads > 4 * cores {
                return Err(format!(
                    "--threads must be between 1 and {} (four per core on this machine), got {threads}",
                    4 * cores
                ));
            }
        }
        Ok(())
    }

    /// The selected scenes that are compared with a reference trajectory, with its length (s): the single bodies and
    /// M1, M2 (the robots always run their reference's 1 s; M3's chain has no reference trajectory).
    fn references(&self) -> Vec<(String, f64)> {
        let (plan, mechanisms, _, _) = self.plan();
        let single = plan
            .scenes
            .iter()
            .map(|scene| (format!("scene {}", scene.label()), scene.parameters().duration));
        let multi = mechanisms.mechanisms.iter().filter_map(|kind| match kind {
            MechanismKind::DoublePendulum => Some(MechanismId::DoublePendulum),
            MechanismKind::FourBar => Some(MechanismId::FourBar),
            MechanismKind::Chain => None,
        });
        single.chain(multi.map(|id| (id.label(), id.duration()))).collect()
    }

    /// The sweep these options describe: the single-body scenes, the mechanisms, the robots and the adaptive runs.
    pub(crate) fn plan(&self) -> (SweepPlan, MechanismPlan, RobotPlan, AdaptivePlan) {
        let (mut scenes, mut mechanisms, mut robots) = (Vec::new(), Vec::new(), false);
        for name in &self.scenes {
            match name.named() {
                Named::SingleBody(scene) => scenes.push(scene),
                Named::Mechanism(kind) => mechanisms.push(kind),
                Named::Robots => robots = true,
            }
        }
        if self.scenes.is_empty() {
            scenes = SceneId::ALL.to_vec();
            mechanisms = MechanismKind::ALL.to_vec();
            robots = true;
        }
        let steps = |default: &[f64]| {
            if self.steps.is_empty() {
                default.to_vec()
            } else {
                self.steps.clone()
            }
        };
        let integrators = if self.integrators.is_empty() {
            crate::single_bodies::sweep::default_integrators()
        } else {
            self.integrators.iter().map(|&i| i.into()).collect()
        };
        let plan = SweepPlan {
            scenes,
            integrators,
            steps: steps(&DEFAULT_STEPS),
            duration: self.duration,
            stabilisation: self.stabilisation.into(),
        };
        let mechanisms = MechanismPlan {
            mechanisms,
            steps: steps(&mechanisms::sweep::DEFAULT_STEPS),
        };
        let robots = RobotPlan {
            robots: if robots {
                reference::robots::RobotId::ALL.to_vec()
            } else {
                Vec::new()
            },
            steps: steps(&robots::sweep::DEFAULT_STEPS),
            // With the default integrators, the robots also run in joint coordinates.
            joint_methods: if self.integrators.is_empty() {
                dynamics::JointMethod::ALL.to_vec()
            } else {
                Vec::new()
            },
        };
        let cases = (plan.scenes.iter().map(|&scene| AdaptiveCase::SingleBody(scene)))
            .chain(mechanisms.mechanisms.iter().map(|kind| {
                AdaptiveCase::Mechanism(match kind {
                    MechanismKind::DoublePendulum => MechanismId::DoublePendulum,
                    MechanismKind::FourBar => MechanismId::FourBar,
                    MechanismKind::Chain => MechanismId::Chain(mechanisms::sweep::CHAIN_LONG_RUN.0),
                })
            }))
            .chain(robots.robots.iter().map(|&robot| AdaptiveCase::Robot(robot)))
            .collect();
        let methods = (plan.integrators.iter())
            .filter(|integrator| integrator.estimate_order().is_some())
            .copied()
            .chain(
                self.integrators
                    .is_empty()
                    .then_some([
                        dynamics::Method::Dopri5Body.into(),
                        dynamics::Method::Dop853Body.into(),
                        dynamics::JointMethod::Dop853.into(),
                    ])
                    .into_iter()
                    .flatten(),
            )
            .collect();
        let adaptive = AdaptivePlan {
            cases,
            methods,
            tolerances: if self.tolerances.is_empty() {
                DEFAULT_TOLERANCES.to_vec()
            } else {
                self.tolerances.clone()
            },
            duration: self.duration,
        };
        (plan, mechanisms, robots, adaptive)
    }
}

/// Parses the command line, runs the job (or the scene file) and prints where the output went.
pub fn main() -> ExitCode {
    let options = Options::parse();
    if let Err(message) = options.validate() {
        Options::command().error(ErrorKind::ValueValidation, message).exit();
    }
    if let Some(path) = &options.scene_file {
        return scene_file_main(path, options.output.as_deref());
    }
    if let Some(threads) = options.threads {
        if let Err(error) = rayon::ThreadPoolBuilder::new().num_threads(threads).build_global() {
            eprintln!("cannot start {threads} threads: {error}");
            return ExitCode::FAILURE;
        }
    }
    // Read before the sweep: a bad file should not cost a whole run.
    let anchors = match &options.anchors {
        Some(path) => match Anchors::read(path) {
            Ok(anchors) => anchors,
            Err(error) => {
                eprintln!("error: --anchors {}: {error}", path.display());
                return ExitCode::FAILURE;
            }
        },
        None => Anchors::none(),
    };
    let started = std::time::Instant::now();
    let output = options.output.clone().unwrap_or_else(|| PathBuf::from("out"));
    let (plan, mechanisms, robots, adaptive) = options.plan();
    match run_job_with_robots(
        &plan,
        &mechanisms,
        &robots,
        &adaptive,
        &anchors,
        &output,
        !options.quiet,
    ) {
        Ok(summary) => {
            println!(
                "{} runs in {:.1} s ({} failed); report, plots and trajectories in {}",
                summary.results.len() + summary.mechanisms.len() + summary.robots.len() + summary.adaptive.len(),
                started.elapsed().as_secs_f64(),
                summary.failures.len(),
                summary.output.join("report.md").display()
            );
            if summary.failures.is_empty() {
                return ExitCode::SUCCESS;
            }
            for failure in &summary.failures {
                eprintln!("failed: {failure}");
            }
            ExitCode::FAILURE
        }
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// Runs one scene file into `output` (default `out/<file name>`) and prints its summary's numbers.
fn scene_file_main(path: &Path, output: Option<&Path>) -> ExitCode {
    let stem = path.file_stem().unwrap_or(path.as_os_str());
    let output = output.map_or_else(|| Path::new("out").join(stem), Path::to_path_buf);
    match run_scene_file(path, &output) {
        Ok(summary) => {
            for run in &summary.runs {
                println!(
                    "{}: largest energy change {:.1e}, largest constraint violation {:.1e} m, CPU {:.2e} s per \
                     simulated second",
                    run.algebra.name(),
                    run.max_energy_change(),
                    run.max_violation(),
                    run.cpu_per_simulated_second
                );
            }
            println!(
                "summary, plots and trajectories in {}",
                output.join("summary.md").display()
            );
            for warning in &summary.warnings {
                eprintln!("warning: {warning}");
            }
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("error: {}: {error}", path.display());
            ExitCode::FAILURE
        }
    }
}
