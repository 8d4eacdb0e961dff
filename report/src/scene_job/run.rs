//! A scene file run in one algebra and measured ([`AlgebraRun`]): the energy change net of the limits' and contacts'
//! impacts, the largest joint violation and the deepest contact per sample, a robot's joint coordinates, and the work
//! of the forces without a potential.

use dynamics::limits::{energy_changed_by, LimitTransition};
use dynamics::simulate::Sample;
use dynamics::{Correction, Dynamics, State, StepStatistics};
use scene_file::{AlgebraKind, FileAlgebra, Pose, Scene, SceneFileError};

/// The run in one algebra, with what the summary states about it.
#[derive(Clone, Debug)]
pub struct AlgebraRun {
    pub(crate) algebra: AlgebraKind,
    /// Every body's samples, `bodies[i][k]`; the energy in each sample is the whole system's.
    pub bodies: Vec<Vec<Sample>>,
    /// Stepping time divided by the simulated time (s/s).
    pub(crate) cpu_per_simulated_second: f64,
    /// Stepping time per step (s).
    pub(crate) time_per_step: f64,
    /// The energy change per sample, |E(t) − E₀ − L(t)| relative to |E₀| (absolute, in J, if |E₀| is below
    /// [`ABSOLUTE_ENERGY_BELOW`]), L(t) what the joint limits' impacts changed it by up to t (zero without limits).
    pub energy_change: Vec<f64>,
    /// The joint limits' impacts, holds and releases.
    pub transitions: Vec<LimitTransition>,
    /// The deepest any contact point went below its plane over the samples (m); 0 without contacts.
    pub deepest: f64,
    /// The `[[collision]]` shapes that went deepest into each other at a sample, by parry3d's query rather than the
    /// contacts (`SceneSystem::deepest_overlap`): the time, the shapes and the depth (m); `None` if none overlapped.
    pub overlap: Option<(f64, String, f64)>,
    /// The largest joint violation per sample (m).
    pub(crate) violation: Vec<f64>,
    /// The work done by the force elements from the start to each sample (J; `Sample::work`).
    pub work: Vec<f64>,
    /// Every body's name, in the order of [`AlgebraRun::bodies`].
    pub names: Vec<String>,
    /// With a robot: the joints CSV's headers between `t` and `energy`, and per sample its values between them.
    pub joints: Option<(Vec<String>, Vec<Vec<f64>>)>,
    /// How far putting the file's start on the joints moved each body.
    pub start_correction: Correction,
    /// The steps kept and refused, the evaluations, the shortest and longest step.
    pub statistics: StepStatistics,
}

/// Energy changes are relative to |E₀| unless it is below this (J): a chain released from z = 0 starts at
/// E₀ = round-off.
pub const ABSOLUTE_ENERGY_BELOW: f64 = 1e-6;

impl AlgebraRun {
    /// The largest of [`AlgebraRun::energy_change`].
    pub fn max_energy_change(&self) -> f64 {
        self.energy_change.iter().copied().fold(0.0, f64::max)
    }

    /// E(T) − E₀ over the run (J; 0 without samples).
    pub fn total_energy_change(&self) -> f64 {
        match (self.bodies[0].first(), self.bodies[0].last()) {
            (Some(first), Some(last)) => last.energy - first.energy,
            _ => 0.0,
        }
    }

    /// L(T): what the impacts at limits and contacts changed the energy by over the run (J).
    pub fn impact_energy(&self) -> f64 {
        self.transitions.iter().map(|t| t.energy_change).sum()
    }

    /// E(T) − E₀ − L(T) − W(T) (J): the energy change the impacts and the work of the forces without a potential
    /// (sliding friction's included) do not explain, the integration error.
    pub fn unexplained_energy(&self) -> f64 {
        self.total_energy_change() - self.impact_energy() - self.work.last().copied().unwrap_or(0.0)
    }

    /// The largest joint violation over the run (m); 0 without joints.
    pub fn max_violation(&self) -> f64 {
        self.violation.iter().copied().fold(0.0, f64::max)
    }
}

/// The largest energy change (relative, or in J, as [`AlgebraRun::energy_change`]) a scene whose forces all have
/// a potential may show before its run is flagged: well above what the integrators drift at sensible steps
/// (1e-12 … 1e-8 on the reference scenes at dt = 1e-3), well below a step too large for the motion (a cuboid
/// spinning at 300 rad/s with RK4 at dt = 1e-2 doubles its energy in a second).
pub const ENERGY_WARNING: f64 = 1e-6;

pub(crate) fn run_in<A: FileAlgebra>(algebra: AlgebraKind, scene: &Scene) -> Result<AlgebraRun, SceneFileError> {
    let system = scene.system::<A>()?;
    let simulation = scene.simulate::<A>()?;
    let contacts = !(scene.checked().contacts.is_empty() && scene.checked().pairs.is_empty());
    let bodies = simulation.bodies;
    let samples = &bodies[0];
    let duration = scene.checked().schedule.duration();
    let stepping = simulation.stepping_time.as_secs_f64();
    let initial_energy = samples.first().map_or(0.0, |s| s.energy);
    let scale = if initial_energy.abs() < ABSOLUTE_ENERGY_BELOW {
        1.0
    } else {
        initial_energy.abs()
    };
    let transitions = simulation.transitions;
    let energy_change = samples
        .iter()
        .map(|s| (s.energy - initial_energy - energy_changed_by(&transitions, s.t)).abs() / scale)
        .collect();
    let mechanism = system.mechanism();
    let robot = system.joint_columns().is_some();
    let mut violation = Vec::with_capacity(samples.len());
    let mut deepest = 0.0f64;
    let mut overlap = None;
    let mut rows = Vec::new();
    let mut previous: Option<Vec<f64>> = None;
    for k in 0..samples.len() {
        let poses: Vec<Pose> = bodies.iter().map(|b| (b[k].position, b[k].orientation)).collect();
        // The sampled states, for the joint positions of a robot and the heights of contacts.
        let states: Vec<State<A>> = if robot || contacts {
            (bodies.iter().enumerate())
                .map(|(i, b)| b[k].state(mechanism.body(i)))
                .collect()
        } else {
            Vec::new()
        };
        let failed = |what: &str, e: &dyn std::fmt::Display| SceneFileError::Run {
            algebra: A::NAME,
            message: format!("{what} at t = {}: {e}", samples[k].t),
        };
        let q = if robot {
            // The joint positions from the sampled poses, angles nearest the previous sample's.
            Some(
                mechanism
                    .joint_positions(&states, previous.as_deref())
                    .map_err(|e| failed("the joint positions", &e))?,
            )
        } else {
            None
        };
        violation.push(system.joint_violation(&poses, q.as_deref()));
        if contacts {
            let heights = mechanism
                .contact_heights(&states)
                .map_err(|e| failed("the contact heights", &e))?;
            deepest = heights.into_iter().fold(deepest, |d, h| d.max(-h));
            if let Some((shapes, depth)) = system.deepest_overlap(&states) {
                if overlap.as_ref().is_none_or(|(_, _, deepest)| depth > *deepest) {
                    overlap = Some((samples[k].t, shapes, depth));
                }
            }
        }
        if let Some(q) = q {
            rows.extend(system.joint_row(&q));
            previous = Some(q);
        }
    }
    let work = samples.iter().map(|s| s.work).collect();
    let joints = system.joint_columns().map(|headers| (headers.to_vec(), rows));
    Ok(AlgebraRun {
        algebra,
        cpu_per_simulated_second: stepping / duration,
        time_per_step: stepping / simulation.statistics.accepted.max(1) as f64,
        energy_change,
        violation,
        work,
        names: system.body_names().to_vec(),
        joints,
        bodies,
        start_correction: system.start_correction().clone(),
        statistics: simulation.statistics,
        transitions,
        deepest,
        overlap,
    })
}
