//! The error metrics of docs/scenes.md for one run, against the reference trajectories and analytic values of
//! the `reference` crate (independent of any GA code).

use reference::metrics::{self, MetricError};
use reference::scenes::{CUBOID_VALUES, HEAVY_TOP_VALUES, PENDULUM_VALUES, TOP_INITIAL_TILT};
use reference::{Sample, SceneConstraint, SceneId, SceneParameters, Trajectory, TrajectoryError};

/// Why a run could not be measured.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub(crate) enum MeasureError {
    #[error(transparent)]
    Metric(#[from] MetricError),
    #[error("reference trajectory: {0}")]
    Reference(#[from] TrajectoryError),
}

/// A scene's physical feature (flip time, period, precession rate…) measured on the run and on the
/// reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feature {
    /// As the report names it: "period", "nutation period"….
    pub name: &'static str,
    pub(crate) unit: &'static str,
    pub(crate) simulated: f64,
    pub(crate) reference: f64,
}

impl Feature {
    /// |simulated − reference|, in the feature's unit.
    pub fn error(&self) -> f64 {
        (self.simulated - self.reference).abs()
    }
}

/// Everything the report states about one run.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurements {
    /// Geodesic angle between simulated and reference orientation at T (rad).
    pub orientation_end: f64,
    /// The largest such angle over the run (rad).
    pub orientation_max: f64,
    /// Centre-of-mass distance from the reference (m), at T.
    pub(crate) position_end: f64,
    /// The largest such distance over the run (m).
    pub position_max: f64,
    /// |E(T) − E₀| / E_scale.
    pub(crate) energy_drift_end: f64,
    /// The largest |E(t) − E₀| / E_scale over the run.
    pub energy_drift_max: f64,
    /// The largest constraint violation over the run (m); `None` for the free body.
    pub violation_max: Option<f64>,
    /// The scene's features of docs/scenes.md (none for scene 4, nor for a cuboid run that ends before its
    /// first flip).
    pub features: Vec<Feature>,
    /// Energy drift per sample (for the drift-over-time plot).
    pub(crate) energy_drift: Vec<f64>,
    /// Constraint violation per sample (empty for the free body).
    pub(crate) violation: Vec<f64>,
}

/// The constraint violation of one sample (m): how far the constrained body point is from where it must be.
pub(crate) fn violation(constraint: &SceneConstraint, sample: &Sample) -> Option<f64> {
    match *constraint {
        SceneConstraint::Free => None,
        SceneConstraint::Hinge { pivot, body_anchor, .. } | SceneConstraint::BallJoint { pivot, body_anchor } => {
            Some((sample.world_point(&body_anchor) - pivot).norm())
        }
        SceneConstraint::PointOnSphere {
            body_anchor,
            centre,
            radius,
        } => Some(((sample.world_point(&body_anchor) - centre).norm() - radius).abs()),
        SceneConstraint::PointOnCircle {
            body_anchor,
            centre,
            radius,
            normal,
        } => {
            let offset = sample.world_point(&body_anchor) - centre;
            Some(((offset.norm() - radius).abs()).max(offset.dot(&normal.normalize()).abs()))
        }
    }
}

/// The first `count` samples of a trajectory (the reference is cut to a shortened run's length).
fn truncated(trajectory: &Trajectory, count: usize) -> Result<Trajectory, TrajectoryError> {
    Trajectory::new(trajectory.samples()[..count.min(trajectory.samples().len())].to_vec())
}

fn features(
    scene: SceneId,
    parameters: &SceneParameters,
    simulated: &Trajectory,
    reference: &Trajectory,
) -> Result<Vec<Feature>, MetricError> {
    let duration = simulated.last().t;
    Ok(match scene {
        SceneId::Cuboid => {
            let analytic: Vec<f64> = CUBOID_VALUES
                .flip_instants
                .iter()
                .copied()
                .filter(|&t| t < duration - 0.05)
                .collect();
            if analytic.is_empty() {
                vec![]
            } else {
                let measured = metrics::flip_times(simulated, &parameters.principal_moments);
                vec![Feature {
                    name: "flip time (worst flip)",
                    unit: "s",
                    simulated: metrics::flip_time_error(&measured, &analytic)?,
                    reference: 0.0,
                }]
            }
        }
        SceneId::Pendulum => vec![Feature {
            name: "period",
            unit: "s",
            simulated: metrics::pendulum_period(simulated)?,
            reference: PENDULUM_VALUES.exact_period,
        }],
        SceneId::TopCusp => {
            let (ours, theirs) = (
                metrics::nutation_features(simulated)?,
                metrics::nutation_features(reference)?,
            );
            vec![
                Feature {
                    name: "largest nutation angle θ",
                    unit: "rad",
                    simulated: ours.theta_max,
                    reference: theirs.theta_max,
                },
                Feature {
                    name: "nutation period",
                    unit: "s",
                    simulated: ours.nutation_period,
                    reference: theirs.nutation_period,
                },
                Feature {
                    name: "mean precession rate",
                    unit: "rad/s",
                    simulated: ours.mean_precession_rate,
                    reference: theirs.mean_precession_rate,
                },
            ]
        }
        SceneId::TopSteady => {
            let steady = metrics::steady_precession_features(simulated, TOP_INITIAL_TILT)?;
            vec![
                Feature {
                    name: "spurious nutation",
                    unit: "rad",
                    simulated: steady.max_nutation,
                    reference: 0.0,
                },
                Feature {
                    name: "precession rate",
                    unit: "rad/s",
                    simulated: steady.precession_rate,
                    reference: HEAVY_TOP_VALUES.slow_precession_rate,
                },
            ]
        }
        SceneId::RodOnSphere | SceneId::RodOnCircle => vec![],
    })
}

/// All metrics of one run of `scene`.
pub(crate) fn measure(scene: SceneId, simulated: &Trajectory) -> Result<Measurements, MeasureError> {
    let parameters = scene.parameters();
    let full_reference = scene.reference_trajectory()?;
    let reference = truncated(&full_reference, simulated.samples().len())?;
    let errors = metrics::trajectory_errors(&reference, simulated)?;
    let energy_drift: Vec<f64> = simulated
        .samples()
        .iter()
        .map(|s| (parameters.mechanical_energy(s) - parameters.initial_energy).abs() / parameters.energy_scale)
        .collect();
    let violation: Vec<f64> = simulated
        .samples()
        .iter()
        .filter_map(|s| self::violation(&parameters.constraint, s))
        .collect();
    Ok(Measurements {
        orientation_end: errors.end_orientation,
        orientation_max: errors.max_orientation,
        position_end: errors.end_position,
        position_max: errors.max_position,
        energy_drift_end: *energy_drift.last().unwrap_or(&0.0),
        energy_drift_max: energy_drift.iter().copied().fold(0.0, f64::max),
        violation_max: (!violation.is_empty()).then(|| violation.iter().copied().fold(0.0, f64::max)),
        features: features(scene, &parameters, simulated, &reference)?,
        energy_drift,
        violation,
    })
}

/// The work-precision error of a scene: orientation at T, except scene 4, whose anchor is a position.
pub(crate) fn headline_error(scene: SceneId, measurements: &Measurements) -> f64 {
    match scene {
        SceneId::RodOnSphere | SceneId::RodOnCircle => measurements.position_end,
        _ => measurements.orientation_end,
    }
}
