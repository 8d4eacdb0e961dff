//! Adaptive steps against fixed steps at equal error: for scene 1 (the free Dzhanibekov cuboid), M1 (the double
//! pendulum), M3 (the 64-link chain released from horizontal, whose tip whips) and the four-bar carried through
//! near-toggle configurations ([`crate::toggle_four_bar`]), a tolerance for
//! [`Method::Dop853Body`] and the fixed step at which the best fixed-step method ([`Method::Rkmk8Body`], the
//! cheapest per simulated second at these accuracies) makes an error at least as large and less than 10× as large.
//! The tests assert both; the `adaptive` benchmark times both runs, so the ratio of their CPU times, measured in
//! one run, is a ratio at equal error that favours the fixed step.
//!
//! The error is each scene's own: scene 1's largest orientation error against its reference trajectory (rad),
//! M1's end orientation error against its reference (rad), and, for M3 (chaotic, without a reference) and the
//! near-toggle four-bar, the largest energy drift (J; the energy is a constant of the motion).

use dynamics::constraints::{PinningAlgebra, Stabilisation};
use dynamics::{simulate, Body, FreeBody, Mechanism, Method, Schedule, Simulation, SimulationError, State, Tolerance};
use reference::SceneId;

use crate::mechanism_measures::{measure, MeasureError};
use crate::{build_mechanism, trajectory, Formulation, MechanismId, SceneError};

/// The scenes compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ComparedScene {
    /// Scene 1, the free cuboid flipping about its middle axis, sampled every 0.01 s (its reference's grid).
    Cuboid,
    /// M1, the double pendulum, by virtual power with projection, sampled every 0.1 s.
    DoublePendulum,
    /// M3 with 64 links, by virtual power with projection, sampled every 0.1 s.
    Chain64,
    /// The near-toggle four-bar, sampled every 0.1 s.
    NearToggleFourBar,
}

/// A tolerance and the fixed step that matches its error on one scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EqualError {
    /// The scene.
    pub scene: ComparedScene,
    /// The tolerance of the adaptive run (relative and absolute alike).
    pub tolerance: f64,
    /// The fixed-step method.
    pub fixed: Method,
    /// Its step (s): the longest of the steps tried (see [`EQUAL_ERROR`]) whose error is at least the adaptive run's
    /// and less than 10× it.
    pub dt: f64,
}

/// The pairs, measured on PGA (`cargo test --release -p scenarios --test integration adaptive:: -- --nocapture`),
/// each fixed step the longest of those tried (dt dividing the sample interval: 1e-2, 5e-3, … for scene 1; 5e-2,
/// 2.5e-2, 2e-2, 1e-2 for M1, where 5e-2 is 470× less accurate; 2e-3, 1e-3, 5e-4, 2.5e-4 for M3, where 5e-4 is
/// 3400× less accurate; 2e-3, 1/600, 1.25e-3, 1/900, 1e-3 for the near-toggle four-bar, where 1.25e-3 is 20× less
/// accurate and 1e-3 more accurate) whose error is at least the adaptive run's and less than 10× it.
pub const EQUAL_ERROR: [EqualError; 4] = [
    EqualError {
        scene: ComparedScene::Cuboid,
        tolerance: 1e-10,
        fixed: Method::Rkmk8Body,
        dt: 1e-2,
    },
    EqualError {
        scene: ComparedScene::DoublePendulum,
        tolerance: 3e-10,
        fixed: Method::Rkmk8Body,
        dt: 2.5e-2,
    },
    EqualError {
        scene: ComparedScene::Chain64,
        tolerance: 1e-10,
        fixed: Method::Rkmk8Body,
        dt: 2.5e-4,
    },
    EqualError {
        scene: ComparedScene::NearToggleFourBar,
        tolerance: 1e-12,
        fixed: Method::Rkmk8Body,
        dt: 1.0 / 900.0,
    },
];

/// Why a compared run could not be made or measured.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CompareError {
    /// The scene could not be built.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The run failed.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// The run could not be measured against its reference.
    #[error(transparent)]
    Measure(#[from] MeasureError),
    /// Scene 1's run could not be compared with its reference trajectory.
    #[error("scene 1's reference: {0}")]
    Reference(#[from] reference::TrajectoryError),
    /// Scene 1's run is not on its reference's grid.
    #[error("scene 1's errors: {0}")]
    Metric(#[from] reference::MetricError),
    /// The tolerance was refused.
    #[error(transparent)]
    Tolerance(#[from] dynamics::integrate::step_control::ToleranceError),
}

/// A scene's system and initial state, built once.
pub enum Prepared<A: PinningAlgebra> {
    /// Scene 1, a free body.
    FreeBody(FreeBody<A>, State<A>),
    /// A mechanism (boxed: it is far larger than a free body).
    Mechanism(Box<crate::MechanismScene<A>>),
    /// The near-toggle four-bar and its start.
    FourBar(Box<(Mechanism<A>, Vec<State<A>>)>),
}

impl ComparedScene {
    /// Every compared scene.
    pub const ALL: [ComparedScene; 4] = [
        ComparedScene::Cuboid,
        ComparedScene::DoublePendulum,
        ComparedScene::Chain64,
        ComparedScene::NearToggleFourBar,
    ];

    /// The scene's name in tables and benchmark ids.
    pub fn label(self) -> &'static str {
        match self {
            ComparedScene::Cuboid => "scene 1",
            ComparedScene::DoublePendulum => "M1",
            ComparedScene::Chain64 => "M3 (64 links)",
            ComparedScene::NearToggleFourBar => "near-toggle four-bar",
        }
    }

    /// The unit of the scene's error.
    pub fn error_unit(self) -> &'static str {
        match self {
            ComparedScene::Cuboid | ComparedScene::DoublePendulum => "rad",
            ComparedScene::Chain64 | ComparedScene::NearToggleFourBar => "J",
        }
    }

    fn duration(self) -> f64 {
        match self {
            ComparedScene::Cuboid => SceneId::Cuboid.parameters().duration,
            ComparedScene::DoublePendulum => MechanismId::DoublePendulum.duration(),
            ComparedScene::Chain64 => MechanismId::Chain(64).duration(),
            ComparedScene::NearToggleFourBar => crate::toggle_four_bar::NEAR_TOGGLE.duration,
        }
    }

    fn sample_interval(self) -> f64 {
        match self {
            ComparedScene::Cuboid => 0.01,
            ComparedScene::DoublePendulum | ComparedScene::Chain64 | ComparedScene::NearToggleFourBar => 0.1,
        }
    }

    /// The scene's adaptive schedule at `tolerance`.
    pub fn adaptive(self, tolerance: f64) -> Result<Schedule, CompareError> {
        let tolerance = Tolerance::new(tolerance, tolerance)?;
        Ok(Schedule::adaptive(tolerance, self.duration(), self.sample_interval())?)
    }

    /// The scene's schedule at the fixed step `dt`, which must divide its sample interval.
    pub fn fixed(self, dt: f64) -> Result<Schedule, CompareError> {
        Ok(Schedule::with_sample_interval(
            dt,
            self.duration(),
            self.sample_interval(),
        )?)
    }

    /// The scene built in algebra `A`.
    pub fn prepare<A: PinningAlgebra>(self) -> Result<Prepared<A>, CompareError> {
        let mechanism = |id| build_mechanism::<A>(id, Formulation::VirtualPower, Stabilisation::PROJECTION);
        Ok(match self {
            ComparedScene::Cuboid => {
                let scene = SceneId::Cuboid.parameters();
                let body = Body::new(scene.mass, scene.principal_moments).map_err(SceneError::from)?;
                let initial = State::new(
                    &body,
                    scene.initial_com,
                    &scene.initial_orientation,
                    scene.initial_body_angular_velocity,
                    scene.initial_com_velocity,
                );
                Prepared::FreeBody(FreeBody::new(body), initial)
            }
            ComparedScene::DoublePendulum => Prepared::Mechanism(Box::new(mechanism(MechanismId::DoublePendulum)?)),
            ComparedScene::Chain64 => Prepared::Mechanism(Box::new(mechanism(MechanismId::Chain(64))?)),
            ComparedScene::NearToggleFourBar => Prepared::FourBar(Box::new(crate::toggle_four_bar::build()?)),
        })
    }
}

impl<A: PinningAlgebra> Prepared<A> {
    /// A run of `method` on `schedule`.
    pub fn run(&self, method: Method, schedule: &Schedule) -> Result<Simulation<A>, SimulationError> {
        match self {
            Prepared::FreeBody(system, initial) => simulate(system, &[*initial], method, schedule),
            Prepared::Mechanism(scene) => simulate(&scene.system, &scene.initial, method, schedule),
            Prepared::FourBar(scene) => simulate(&scene.0, &scene.1, method, schedule),
        }
    }

    /// The scene's error of a run (see the module docs).
    pub fn error(&self, run: &Simulation<A>) -> Result<f64, CompareError> {
        match self {
            Prepared::FreeBody(..) => {
                let reference = SceneId::Cuboid.reference_trajectory()?;
                Ok(reference::trajectory_errors(&reference, &trajectory(run.body(0))?)?.max_orientation)
            }
            Prepared::Mechanism(scene) => {
                let measures = measure(scene.id, &run.bodies)?;
                Ok(measures.orientation_end.unwrap_or(measures.energy_drift))
            }
            Prepared::FourBar(_) => {
                let energies: Vec<f64> = run.energies().collect();
                Ok(energies.iter().map(|e| (e - energies[0]).abs()).fold(0.0, f64::max))
            }
        }
    }
}
