//! The configurations of the sweep (scene × algebra × formulation × integrator × step) and running one.

use dynamics::constraints::Stabilisation;
use dynamics::integrate::{Integrator, Method};
use dynamics::simulate::{simulate, Sample, Schedule};
use dynamics::{Algebra, Body, Cga, Force, FreeBody, Pga};
use nalgebra::Vector3;
use reference::{SceneConstraint, SceneId, SceneParameters};
use scenarios::{Formulation, SceneAlgebra};
use scene_file::AlgebraKind;

use super::measure::{measure, Measurements};
use crate::runs::{metrics_error, simulation_error, RunError};

/// One run of the sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    /// The reference scene.
    pub scene: SceneId,
    /// The algebra it runs in.
    pub algebra: AlgebraKind,
    /// `None` for the free body, which has no constraint to formulate.
    pub(crate) formulation: Option<Formulation>,
    pub(crate) integrator: Integrator,
    pub(crate) dt: f64,
    /// Simulated time (the scene's T unless shortened).
    pub(crate) duration: f64,
    pub(crate) stabilisation: Stabilisation,
}

impl Config {
    /// A label for tables and legends: "PGA, pinning, RK4".
    pub fn series_label(&self) -> String {
        match self.formulation {
            Some(formulation) => format!(
                "{}, {}, {}",
                self.algebra.name(),
                formulation.name(),
                self.integrator.name()
            ),
            None => format!("{}, {}", self.algebra.name(), self.integrator.name()),
        }
    }

    /// The same run in the other algebra.
    pub fn same_but(&self, algebra: AlgebraKind) -> Config {
        Config { algebra, ..*self }
    }
}

/// The single-body scenes' steps without `--steps`.
pub(crate) const DEFAULT_STEPS: [f64; 7] = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4];

/// What the sweep covers.
#[derive(Clone, Debug)]
pub struct SweepPlan {
    /// The reference scenes to run.
    pub scenes: Vec<SceneId>,
    /// The integrators; splittings run the free body only.
    pub integrators: Vec<Integrator>,
    /// Step sizes (s); each must divide the 0.01 s sample interval.
    pub steps: Vec<f64>,
    /// Overrides every scene's duration (for quick runs); must be a multiple of 0.01 s.
    pub duration: Option<f64>,
    /// How the constrained scenes are held on their constraints.
    pub stabilisation: Stabilisation,
}

/// Whether a scene can be written by a formulation in an algebra (PGA has no spheres or circles, so scene 4
/// pins only in CGA; theory §13).
fn expressible(scene: SceneId, algebra: AlgebraKind, formulation: Formulation) -> bool {
    let needs_round_objects = matches!(
        scene.parameters().constraint,
        SceneConstraint::PointOnSphere { .. } | SceneConstraint::PointOnCircle { .. }
    );
    !(needs_round_objects && formulation == Formulation::Pinning && algebra == AlgebraKind::Pga)
}

impl SweepPlan {
    /// Every configuration of the plan that can run: splitting integrators only on the free body, and
    /// formulations only where the algebra has the geometry.
    pub(crate) fn configurations(&self) -> Vec<Config> {
        let mut configs = Vec::new();
        for &scene in &self.scenes {
            let parameters = scene.parameters();
            let free = matches!(parameters.constraint, SceneConstraint::Free);
            let formulations: Vec<Option<Formulation>> = if free {
                vec![None]
            } else {
                Formulation::ALL.iter().copied().map(Some).collect()
            };
            for algebra in AlgebraKind::ALL {
                for &formulation in &formulations {
                    if formulation.is_some_and(|f| !expressible(scene, algebra, f)) {
                        continue;
                    }
                    for &integrator in &self.integrators {
                        // Splittings take free bodies only; the joint-coordinate methods, robots only (the reference
                        // scenes hold their bodies by constraints, which have no joint coordinates).
                        if (!free && matches!(integrator, Integrator::Splitting(_)))
                            || matches!(integrator, Integrator::Joint(_))
                        {
                            continue;
                        }
                        for &dt in &self.steps {
                            configs.push(Config {
                                scene,
                                algebra,
                                formulation,
                                integrator,
                                dt,
                                duration: self.duration.unwrap_or(parameters.duration),
                                stabilisation: self.stabilisation,
                            });
                        }
                    }
                }
            }
        }
        configs
    }
}

/// A finished run.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub(crate) config: Config,
    /// The samples every 0.01 s.
    pub samples: Vec<Sample>,
    /// Stepping time of the run divided by the simulated time (s/s).
    pub(crate) cpu_per_simulated_second: f64,
    /// Stepping time per step (s).
    pub(crate) time_per_step: f64,
    /// The errors against the reference, energy drift and constraint violation.
    pub measurements: Measurements,
}

/// A run's result as the report sees it.
pub(crate) type RunResult = (Config, Result<Outcome, RunError>);

/// Runs one configuration.
pub(crate) fn run(config: &Config) -> Result<Outcome, RunError> {
    match config.algebra {
        AlgebraKind::Cga => run_in::<Cga>(config),
        AlgebraKind::Pga => run_in::<Pga>(config),
    }
}

/// A free scene's body as a [`FreeBody`] with its gravity, where every integrator (splittings included) applies.
pub(crate) fn free_body<A: Algebra>(parameters: &SceneParameters) -> Result<FreeBody<A>, RunError> {
    let body = Body::new(parameters.mass, parameters.principal_moments).map_err(simulation_error)?;
    let system = FreeBody::<A>::new(body);
    Ok(if parameters.gravity != 0.0 {
        system.with_force(Force::Gravity {
            acceleration: Vector3::new(0.0, 0.0, -parameters.gravity),
        })
    } else {
        system
    })
}

fn run_in<A: SceneAlgebra>(config: &Config) -> Result<Outcome, RunError> {
    let schedule = Schedule::new(config.dt, config.duration).map_err(simulation_error)?;
    let mut simulation = match config.formulation {
        None => {
            // The free body runs as a `FreeBody`, where every integrator (splittings included) applies.
            let scene = scenarios::build::<A>(config.scene, Formulation::Pinning, config.stabilisation)?;
            let system = free_body(&scene.parameters)?;
            simulate(&system, &[scene.initial], config.integrator, &schedule).map_err(simulation_error)?
        }
        Some(formulation) => {
            let scene = scenarios::build::<A>(config.scene, formulation, config.stabilisation)?;
            simulate(&scene.system, &[scene.initial], config.integrator, &schedule).map_err(simulation_error)?
        }
    };
    let stepping = simulation.stepping_time.as_secs_f64();
    let trajectory = scenarios::trajectory(simulation.body(0)).map_err(metrics_error)?;
    let measurements = measure(config.scene, &trajectory).map_err(metrics_error)?;
    Ok(Outcome {
        config: *config,
        cpu_per_simulated_second: stepping / schedule.duration(),
        time_per_step: stepping / simulation.statistics.accepted.max(1) as f64,
        measurements,
        samples: simulation.bodies.swap_remove(0),
    })
}

/// The default integrators: every general method but the embedded pairs, and the splittings for the free body. The
/// pairs' place is a sweep over tolerances on an adaptive schedule, which the report does not draw yet; at fixed
/// steps they would add curves beside RKMK6-body's and RKMK8-body's.
pub(crate) fn default_integrators() -> Vec<Integrator> {
    let mut integrators: Vec<Integrator> = (Method::ALL.iter().copied())
        .filter(|method| method.estimate_order().is_none())
        .map(Integrator::General)
        .collect();
    integrators.extend(
        Integrator::ALL
            .iter()
            .copied()
            .filter(|i| matches!(i, Integrator::Splitting(_))),
    );
    integrators
}
