//! The adaptive runs of the main job: every selected scene (single bodies, M1–M3, the robots) in PGA with each
//! embedded pair (DP5(4)-body, DOP853-body, and on the robots DOP853-joint) over a sweep of tolerances, measured as the fixed-step runs of the same
//! scene are, so the report draws both on the same work-precision axes (`figures`, `section`).
//!
//! Single bodies run by virtual power (scene 1 as a free body), M1 and M2 by virtual power with projection, M3 as
//! its 64-link long run; each over the scene's duration (or the job's), sampled every 0.01 s. The error is the one
//! the fixed-step figures plot: the orientation at T (the position at T for scene 4), M1's end orientation, M2's
//! coupler position, M3's energy drift (it is chaotic and has no reference), the robots' largest joint error
//! against Pinocchio. Every run also records the length of each step it kept.

use std::ops::ControlFlow;

use dynamics::constraints::Stabilisation;
use dynamics::integrate::step_control::Tolerance;
use dynamics::integrate::Integrator;
use dynamics::simulate::{simulate, Plan, Schedule, Simulation};
use dynamics::{Algebra, Dynamics, Pga, State, StepStatistics};
use reference::robots::RobotId;
use reference::{SceneConstraint, SceneId};
use scenarios::mechanism_measures::{measure as measure_mechanism, MechanismMeasures};
use scenarios::{build_mechanism, Formulation, MechanismId};

use crate::robots::measure::measure_robot;
use crate::robots::sweep::robot_label;
use crate::runs::{fastest_of_repeats, metrics_error, simulation_error, RunError};
use crate::single_bodies::measure::{headline_error, measure};
use crate::single_bodies::sweep::free_body;

/// The tolerances without `--tolerances`: 1e-3 to 1e-13, a decade apart.
pub const DEFAULT_TOLERANCES: [f64; 11] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13];

/// The interval the adaptive runs are sampled at (s): the references' grid.
const SAMPLE_INTERVAL: f64 = 0.01;

/// A scene of the adaptive sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AdaptiveCase {
    /// A single-body scene of the reference set.
    SingleBody(SceneId),
    /// M1, M2, or M3 as its 64-link long run.
    Mechanism(MechanismId),
    /// A reference robot, over its reference's 1 s.
    Robot(RobotId),
}

impl AdaptiveCase {
    /// The scene's name in the report.
    pub fn label(self) -> String {
        match self {
            AdaptiveCase::SingleBody(scene) => format!("scene {}", scene.label()),
            AdaptiveCase::Mechanism(id) => id.label(),
            AdaptiveCase::Robot(robot) => robot_label(robot).to_owned(),
        }
    }

    /// What the scene's error measures, with its unit.
    pub fn error_label(self) -> &'static str {
        match self {
            AdaptiveCase::SingleBody(SceneId::RodOnSphere | SceneId::RodOnCircle) => "position error at T (m)",
            AdaptiveCase::SingleBody(_) | AdaptiveCase::Mechanism(MechanismId::DoublePendulum) => {
                "orientation error at T (rad)"
            }
            AdaptiveCase::Mechanism(MechanismId::FourBar) => "coupler error at T (m)",
            AdaptiveCase::Mechanism(MechanismId::Chain(_)) => "largest energy drift (J)",
            AdaptiveCase::Robot(_) => "largest joint error (rad)",
        }
    }

    /// Whether the scene's error is in the tolerance's units (rad, m), so that their ratio says how well the tolerance
    /// is followed: all but M3's energy drift.
    pub fn error_in_tolerance_units(self) -> bool {
        !matches!(self, AdaptiveCase::Mechanism(MechanismId::Chain(_)))
    }

    /// The formulation the scene's constraints are written in (`None` for the free body and the robots, whose
    /// joints are joint models).
    pub(crate) fn formulation(self) -> Option<Formulation> {
        match self {
            AdaptiveCase::SingleBody(scene) => {
                (!matches!(scene.parameters().constraint, SceneConstraint::Free)).then_some(Formulation::VirtualPower)
            }
            AdaptiveCase::Mechanism(_) => Some(Formulation::VirtualPower),
            AdaptiveCase::Robot(_) => None,
        }
    }
}

/// What the adaptive part of the job covers.
#[derive(Clone, Debug, Default)]
pub struct AdaptivePlan {
    /// The scenes; none if empty.
    pub cases: Vec<AdaptiveCase>,
    /// The embedded pairs (those in joint coordinates run on the robots only).
    pub methods: Vec<Integrator>,
    /// The tolerances (relative and absolute alike).
    pub tolerances: Vec<f64>,
    /// Overrides the duration of every scene but the robots (for quick runs).
    pub duration: Option<f64>,
}

/// One adaptive run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveConfig {
    /// The scene.
    pub case: AdaptiveCase,
    /// The embedded pair.
    pub method: Integrator,
    /// The tolerance.
    pub tolerance: f64,
    pub(crate) duration: Option<f64>,
}

impl AdaptivePlan {
    /// Every run: scene × method × tolerance (methods without an error estimate are left out, and those stepping in
    /// joint coordinates but on the robots).
    pub(crate) fn configurations(&self) -> Vec<AdaptiveConfig> {
        let mut configs = Vec::new();
        for &case in &self.cases {
            let applies = |m: &&Integrator| {
                m.estimate_order().is_some()
                    && (matches!(case, AdaptiveCase::Robot(_)) || !matches!(m, Integrator::Joint(_)))
            };
            for &method in self.methods.iter().filter(applies) {
                for &tolerance in &self.tolerances {
                    configs.push(AdaptiveConfig {
                        case,
                        method,
                        tolerance,
                        duration: self.duration,
                    });
                }
            }
        }
        configs
    }
}

impl AdaptiveConfig {
    /// "DOP853-body, tol 1e-8".
    pub fn series_label(&self) -> String {
        format!("{}, tol {:.0e}", self.method.name(), self.tolerance)
    }

    /// How much stepping the run does, roughly (for the scheduling: the slowest first).
    pub(crate) fn work(&self) -> f64 {
        let bodies = match self.case {
            AdaptiveCase::SingleBody(_) => 1.0,
            AdaptiveCase::Mechanism(id) => id.bodies() as f64,
            AdaptiveCase::Robot(RobotId::Ur5) => 6.0,
            AdaptiveCase::Robot(RobotId::Solo12) => 13.0,
        };
        let order = f64::from(self.method.order());
        bodies * self.tolerance.powf(-1.0 / order)
    }
}

/// A finished adaptive run.
#[derive(Clone, Debug)]
pub struct AdaptiveOutcome {
    pub(crate) config: AdaptiveConfig,
    /// The scene's error (see the module docs).
    pub error: f64,
    /// Stepping time divided by the simulated time (s/s): the fastest of the repeats.
    pub cpu_per_simulated_second: f64,
    /// The steps kept and refused, the evaluations, the shortest and longest step.
    pub statistics: StepStatistics,
    /// Each kept step: (the time it ended at, its length) (s).
    pub steps: Vec<(f64, f64)>,
}

/// An adaptive run and its outcome, or why it failed.
pub type AdaptiveResult = (AdaptiveConfig, Result<AdaptiveOutcome, RunError>);

/// A timed run and the steps it kept.
struct TimedRun<A: Algebra> {
    run: Simulation<A>,
    /// The fastest repeat's stepping time divided by the simulated time (s/s).
    cpu_per_simulated_second: f64,
    /// Each kept step: (the time it ended at, its length) (s).
    steps: Vec<(f64, f64)>,
}

/// Runs `system` from `initial` on the adaptive schedule, timed over repeats (the fastest counts), with an observer
/// that records the steps (outside the timed stepping).
fn timed_run<A: Algebra, D: Dynamics<A> + ?Sized>(
    system: &D,
    initial: &[State<A>],
    config: &AdaptiveConfig,
    duration: f64,
) -> Result<TimedRun<A>, RunError> {
    let tolerance = Tolerance::new(config.tolerance, config.tolerance).map_err(simulation_error)?;
    let schedule = Schedule::adaptive(tolerance, duration, SAMPLE_INTERVAL).map_err(simulation_error)?;
    let mut steps = Vec::new();
    let (run, fastest, _) = fastest_of_repeats(|| {
        steps.clear();
        let mut last = schedule.start();
        let record = |t: f64, _: &[State<A>]| {
            steps.push((t, t - last));
            last = t;
            ControlFlow::Continue(())
        };
        simulate(system, initial, config.method, Plan::new(&schedule).observer(record)).map_err(simulation_error)
    })?;
    Ok(TimedRun {
        run,
        cpu_per_simulated_second: fastest / duration,
        steps,
    })
}

/// A mechanism's error (see the module docs): `None` for a run too short for M2's measure.
pub(crate) fn mechanism_error(id: MechanismId, measures: &MechanismMeasures) -> Option<f64> {
    match id {
        MechanismId::DoublePendulum => measures.orientation_end,
        MechanismId::FourBar => measures.four_bar.map(|f| f.coupler_error),
        MechanismId::Chain(_) => Some(measures.energy_drift),
    }
}

/// Runs one configuration.
pub(crate) fn run_adaptive(config: &AdaptiveConfig) -> Result<AdaptiveOutcome, RunError> {
    let (error, cpu_per_simulated_second, statistics, steps) = match config.case {
        AdaptiveCase::SingleBody(scene) => {
            let built = scenarios::build::<Pga>(scene, Formulation::VirtualPower, Stabilisation::PROJECTION)?;
            let duration = config.duration.unwrap_or(built.duration);
            let TimedRun {
                run,
                cpu_per_simulated_second: cpu,
                steps,
            } = match config.case.formulation() {
                // The free body runs as a `FreeBody`, as in the fixed-step sweep.
                None => timed_run(
                    &free_body::<Pga>(&built.parameters)?,
                    &[built.initial],
                    config,
                    duration,
                )?,
                Some(_) => timed_run(&built.system, &[built.initial], config, duration)?,
            };
            let trajectory = scenarios::trajectory(run.body(0)).map_err(metrics_error)?;
            let measurements = measure(scene, &trajectory).map_err(metrics_error)?;
            (headline_error(scene, &measurements), cpu, run.statistics, steps)
        }
        AdaptiveCase::Mechanism(id) => {
            let scene = build_mechanism::<Pga>(id, Formulation::VirtualPower, Stabilisation::PROJECTION)?;
            let duration = config.duration.unwrap_or(id.duration());
            let TimedRun {
                run,
                cpu_per_simulated_second: cpu,
                steps,
            } = timed_run(&scene.system, &scene.initial, config, duration)?;
            let measures = measure_mechanism(id, &run.bodies).map_err(metrics_error)?;
            let error = mechanism_error(id, &measures)
                .ok_or_else(|| RunError::Metrics("the run ends before the measure applies".into()))?;
            (error, cpu, run.statistics, steps)
        }
        AdaptiveCase::Robot(robot) => {
            let scene = scenarios::build_robot::<Pga>(robot)
                .map_err(|e| RunError::Simulation(format!("building the robot: {e}")))?;
            let samples = &scene.reference.samples;
            let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
                return Err(RunError::Metrics("the reference has no samples".into()));
            };
            let TimedRun {
                run,
                cpu_per_simulated_second: cpu,
                steps,
            } = timed_run(scene.robot.mechanism(), &scene.initial, config, last.t - first.t)?;
            let measured = measure_robot(&scene, &run)?;
            (measured.joint_error, cpu, run.statistics, steps)
        }
    };
    Ok(AdaptiveOutcome {
        config: *config,
        error,
        cpu_per_simulated_second,
        statistics,
        steps,
    })
}
