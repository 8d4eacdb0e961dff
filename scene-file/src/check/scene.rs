//! The scene's schedule (within [`MAX_STEPS`] and [`MAX_SAMPLES`]), stabilisation, whether it is one free body and
//! whether its forces conserve the energy.

use dynamics::constraints::Stabilisation;
use dynamics::simulate::Schedule;
use dynamics::step_control::Tolerance;

use super::layout::Layout;
use super::robot::LoadedRobot;
use crate::error::{invalid, SceneFileError};
use crate::names::StabilisationName;
use crate::syntax::bodies::ForceSpec;
use crate::syntax::file::{BaumgarteGains, SceneFile};
use crate::syntax::robot::{JointDynamicsName, RobotSpec};

/// The most steps a scene file's run takes (per algebra): about a minute for a single body, several for a
/// chain; a longer run is more likely a typo (`duration = 99990`, `dt = 1e-15`) than a plan.
pub const MAX_STEPS: usize = 100_000_000;

/// The most body samples (samples × bodies) a scene file's run records (per algebra), about 120 bytes each:
/// every sample is kept for the CSV and the plots.
pub const MAX_SAMPLES: usize = 1_000_000;

impl SceneFile {
    /// Whether the scene is one body alone, without joints, a robot or force elements: a free body.
    pub(crate) fn free_body(&self, layout: &Layout) -> bool {
        layout.joints.is_empty()
            && layout.bodies.len() == 1
            && self.robot.is_none()
            && self.spring.is_empty()
            && self.couple.is_empty()
            && self.joint_torque.is_empty()
            && self.joint_damping.is_empty()
            && self.pd.is_empty()
            && self.contact.is_empty()
    }

    /// The robot's URDF as read, with its `[robot]` table; an error if the table was not read by
    /// [`SceneFile::parse`].
    pub fn robot(&self) -> Result<Option<(&RobotSpec, &LoadedRobot)>, SceneFileError> {
        match (&self.robot, &self.loaded_robot) {
            (Some(spec), Some(loaded)) => Ok(Some((spec, loaded))),
            (Some(_), None) => Err(invalid(
                "robot",
                "the URDF was not read: make the scene with SceneFile::parse or SceneFile::load",
            )),
            (None, _) => Ok(None),
        }
    }

    /// The run's steps and samples, within [`MAX_STEPS`] and [`MAX_SAMPLES`].
    pub fn schedule(&self) -> Result<Schedule, SceneFileError> {
        let schedule = match (self.dt, self.tolerance) {
            (Some(dt), None) => Schedule::with_sample_interval(dt, self.duration, self.sample_interval),
            (None, Some(tolerance)) => {
                let tolerance =
                    Tolerance::new(tolerance, tolerance).map_err(|error| invalid("tolerance", error.to_string()))?;
                Schedule::adaptive(tolerance, self.duration, self.sample_interval)
            }
            (Some(_), Some(_)) => {
                return Err(invalid(
                    "dt, tolerance",
                    "give one: dt for fixed steps, or tolerance for steps chosen by the error",
                ))
            }
            (None, None) => {
                return Err(invalid(
                    "dt",
                    "missing: give dt (s) for fixed steps, or tolerance for steps chosen by the error",
                ))
            }
        }
        .map_err(SceneFileError::Schedule)?;
        if schedule.step_count() > MAX_STEPS {
            return Err(invalid(
                "dt, duration",
                format!(
                    "{} steps ({} s at dt = {:e} s) is more than a scene file runs (at most {MAX_STEPS:e})",
                    schedule.step_count(),
                    self.duration,
                    schedule.dt()
                ),
            ));
        }
        let robot_bodies = self.robot()?.map_or(0, |(spec, loaded)| loaded.body_count(spec));
        let bodies = self.layout()?.bodies.len() + robot_bodies;
        if schedule.sample_count().saturating_mul(bodies) > MAX_SAMPLES {
            return Err(invalid(
                "duration, sample_interval",
                format!(
                    "{} samples ({} s every {} s) of {bodies} bodies is more than a scene file records (at most \
                     {MAX_SAMPLES:e} body samples): lengthen sample_interval",
                    schedule.sample_count(),
                    self.duration,
                    self.sample_interval
                ),
            ));
        }
        Ok(schedule)
    }

    /// How the joints are held: `stabilisation`, with the `baumgarte` gains if given; an error if gains are
    /// given for another stabilisation.
    pub fn stabilisation(&self) -> Result<Stabilisation, SceneFileError> {
        match (self.stabilisation, self.baumgarte) {
            (StabilisationName::Baumgarte, Some(BaumgarteGains { alpha, beta })) => {
                Ok(Stabilisation::Baumgarte { alpha, beta })
            }
            (_, Some(_)) => Err(invalid(
                "baumgarte",
                "gains apply only with stabilisation = \"baumgarte\"",
            )),
            (name, None) => Ok(name.into()),
        }
    }

    /// Whether every force has a potential, so the energy is conserved and its change is drift: only gravity and
    /// undamped springs, no drive.
    pub fn conservative(&self) -> Result<bool, SceneFileError> {
        let layout = self.layout()?;
        let robot_damped = self.robot()?.is_some_and(|(spec, loaded)| {
            !spec.torque.is_empty()
                || (spec.joint_dynamics == JointDynamicsName::Urdf
                    && loaded.model.joints.iter().any(|j| j.damping > 0.0))
        });
        Ok(layout
            .bodies
            .iter()
            .all(|b| b.forces.iter().all(ForceSpec::conservative))
            && layout.joints.iter().all(|j| j.drive.is_none())
            && self.spring.iter().all(|s| s.damping == 0.0)
            && self.couple.is_empty()
            && self.joint_torque.is_empty()
            && self.joint_damping.is_empty()
            && self.pd.is_empty()
            && !robot_damped)
    }
}
