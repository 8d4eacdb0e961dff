//! What the tests and the main job measure of a mechanism run, against the GA-independent references of
//! [`reference::multibody`]: end-state errors (M1, M2), energy drift, joint violation from the sampled poses
//! alone (not from the solver's residuals), and the four-bar's crank revolutions and end angles.

use std::f64::consts::TAU;

use dynamics::simulate::Sample;
use reference::multibody::{revolution_times, MechanismSample, Pose, CHAIN, DOUBLE_PENDULUM, FOUR_BAR};
use reference::TrajectoryError;

use crate::MechanismId;

/// Why a run could not be measured.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeasureError {
    /// The embedded reference trajectory of the mechanism could not be parsed.
    #[error("the reference trajectory: {0}")]
    Reference(#[from] TrajectoryError),
    /// The run has no samples to measure.
    #[error("the run has no samples")]
    Empty,
    /// The run's last sample time (s, the field) is not on the reference's 0.01 s grid.
    #[error("the reference has no sample at t = {0} s (it is sampled every 0.01 s)")]
    NoReferenceAt(f64),
    /// The run's number of bodies differs from the mechanism's.
    #[error("the run has {found} bodies, the mechanism {expected}")]
    BodyCount {
        /// Bodies in the run.
        found: usize,
        /// Bodies the mechanism has ([`MechanismId::bodies`]).
        expected: usize,
    },
}

/// The measures of one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MechanismMeasures {
    /// End orientation error (rad), the largest over the bodies, against the reference at the run's last sample;
    /// `None` without a reference (M3 is chaotic and has none).
    pub orientation_end: Option<f64>,
    /// End centre-of-mass error (m), the largest over the bodies.
    pub position_end: Option<f64>,
    /// The largest |E(t) − E(0)| over the samples (J).
    pub energy_drift: f64,
    /// The largest joint violation over the samples (m; `reference::multibody`'s measure per mechanism).
    pub violation: f64,
    /// The four-bar's features (M2 only).
    pub four_bar: Option<FourBarMeasures>,
}

/// The four-bar's features: the crank's revolutions against the period in `docs/scenes.md` (M2), the link angles at
/// the end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarMeasures {
    /// Completed crank revolutions.
    pub revolutions: usize,
    /// The largest relative error of the k-th revolution time against k × the period.
    pub period_error: f64,
    /// The largest error of the three link angles at the end against the reference (rad).
    pub angle_error: f64,
    /// The coupler's centre of mass at the end against the reference (m): MuJoCo's measure of this scene.
    pub coupler_error: f64,
}

/// Every body's pose at sample `k`.
pub fn poses(bodies: &[Vec<Sample>], k: usize) -> Vec<Pose> {
    bodies
        .iter()
        .map(|samples| Pose {
            position: samples[k].position,
            orientation: samples[k].orientation,
        })
        .collect()
}

/// The angle of a four-bar link in the x–z plane: its body z is `(cos α, 0, sin α)`.
fn link_angle(sample: &Sample) -> f64 {
    let axis = sample.orientation * nalgebra::Vector3::z();
    axis.z.atan2(axis.x)
}

/// The crank angle (unwrapped) and its rate at every sample: the crank's angular velocity is `(0, −φ̇, 0)`.
pub fn crank_angles(crank: &[Sample]) -> Vec<(f64, f64, f64)> {
    let mut previous: Option<f64> = None;
    crank
        .iter()
        .map(|s| {
            let mut angle = link_angle(s);
            if let Some(p) = previous {
                angle += TAU * ((p - angle) / TAU).round();
            }
            previous = Some(angle);
            (s.t, angle, -s.angular_velocity.y)
        })
        .collect()
}

/// The reference sample at time `t` (the references are sampled every 0.01 s).
fn reference_at(reference: &[MechanismSample], t: f64) -> Result<usize, MeasureError> {
    reference
        .iter()
        .position(|s| (s.t - t).abs() < 1e-9)
        .ok_or(MeasureError::NoReferenceAt(t))
}

/// The largest orientation (rad) and position (m) differences between two sets of poses.
fn pose_errors(poses: &[Pose], expected: &[Pose]) -> (f64, f64) {
    poses.iter().zip(expected).fold((0.0f64, 0.0f64), |(o, p), (pose, e)| {
        (
            o.max(pose.orientation.angle_to(&e.orientation)),
            p.max((pose.position - e.position).norm()),
        )
    })
}

/// Measures a run of mechanism `id` (`bodies[i][k]`: body i at sample k, as in `Simulation::bodies`).
pub fn measure(id: MechanismId, bodies: &[Vec<Sample>]) -> Result<MechanismMeasures, MeasureError> {
    let expected = id.bodies();
    if bodies.len() != expected {
        return Err(MeasureError::BodyCount {
            found: bodies.len(),
            expected,
        });
    }
    let samples = bodies.first().map_or(0, Vec::len);
    let last = samples.checked_sub(1).ok_or(MeasureError::Empty)?;
    let violation_at = |k: usize| {
        let poses = poses(bodies, k);
        match id {
            MechanismId::DoublePendulum => DOUBLE_PENDULUM.violation(&poses),
            MechanismId::FourBar => FOUR_BAR.violation(&poses),
            MechanismId::Chain(_) => CHAIN.violation(&poses),
        }
    };
    let violation = (0..samples).map(violation_at).fold(0.0, f64::max);
    let initial_energy = bodies[0][0].energy;
    let energy_drift = bodies[0]
        .iter()
        .map(|s| (s.energy - initial_energy).abs())
        .fold(0.0, f64::max);
    let end_time = bodies[0][last].t;
    let mut measures = MechanismMeasures {
        orientation_end: None,
        position_end: None,
        energy_drift,
        violation,
        four_bar: None,
    };
    let reference = match id {
        MechanismId::DoublePendulum => DOUBLE_PENDULUM.reference()?,
        MechanismId::FourBar => FOUR_BAR.reference()?,
        MechanismId::Chain(_) => return Ok(measures),
    };
    let index = reference_at(&reference, end_time)?;
    let (orientation, position) = pose_errors(&poses(bodies, last), &reference[index].bodies);
    measures.orientation_end = Some(orientation);
    measures.position_end = Some(position);
    if id == MechanismId::FourBar {
        let angles = crank_angles(&bodies[0]);
        let times = revolution_times(&angles, FOUR_BAR.initial_angle);
        let period = FOUR_BAR.revolution_period;
        let period_error = times
            .iter()
            .enumerate()
            .map(|(k, t)| (t - (k + 1) as f64 * period).abs() / ((k + 1) as f64 * period))
            .fold(0.0, f64::max);
        let [phi, alpha_2, alpha_3] = FOUR_BAR.reference_angles()?[index];
        let angle_error = (angles[last].1 - phi)
            .abs()
            .max((link_angle(&bodies[1][last]) - alpha_2).abs())
            .max((link_angle(&bodies[2][last]) - alpha_3).abs());
        measures.four_bar = Some(FourBarMeasures {
            revolutions: times.len(),
            period_error,
            angle_error,
            coupler_error: (bodies[1][last].position - reference[index].bodies[1].position).norm(),
        });
    }
    Ok(measures)
}
