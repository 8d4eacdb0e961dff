//! A scene file checked once ([`CheckedScene`]): its robot read, its integrator, its schedule (within [`MAX_STEPS`] and
//! [`MAX_SAMPLES`]), its stabilisation, its bodies and joints ([`Layout`]), whether it is one free body and whether
//! its forces conserve the energy. What depends on the algebra is checked when the system is built.

use std::path::Path;

use dynamics::constraints::Stabilisation;
use dynamics::integrate::step_control::Tolerance;
use dynamics::integrate::Integrator;
use dynamics::simulate::Schedule;

use super::collisions::{plane_contacts, urdf_shapes, ShapedBody};
use super::layout::{Layout, Names};
use super::pairs::{collision_pairs, CheckedPair};
use super::robot::{CheckedRobot, LoadedRobot};
use crate::error::{invalid, SceneFileError};
use crate::names::{AlgebraChoice, IntegratorName, StabilisationName};
use crate::syntax::bodies::Bodies;
use crate::syntax::contacts::ContactSpec;
use crate::syntax::elements::{CoupleSpec, JointDampingSpec, JointTorqueSpec, PdSpec, SpringSpec};
use crate::syntax::file::{BaumgarteGains, SceneFile};
use crate::syntax::robot::{CollisionsName, JointDynamicsName};

/// The most steps a scene file's run takes (per algebra): about a minute for a single body, several for a
/// chain; a longer run is more likely a typo (`duration = 99990`, `dt = 1e-15`) than a plan.
pub const MAX_STEPS: usize = 100_000_000;

/// The most body samples (samples × bodies) a scene file's run records (per algebra), about 120 bytes each:
/// every sample is kept for the CSV and the plots.
pub const MAX_SAMPLES: usize = 1_000_000;

/// How the run steps: a fixed step, or steps chosen by a tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepping {
    /// `dt` (s).
    Fixed {
        /// s.
        dt: f64,
    },
    /// `tolerance`, relative and absolute alike.
    Adaptive {
        /// In rad, m, rad/s and m/s.
        tolerance: f64,
    },
}

/// A scene file with every value checked that does not depend on the algebra, each once.
#[derive(Clone, Debug)]
pub struct CheckedScene {
    /// A title for the summary and the plots.
    pub title: Option<String>,
    /// Which algebras run the scene.
    pub algebra: AlgebraChoice,
    /// As written, else `"dop853-body"` with a tolerance, `"rkmk8-body"` with a `[robot]` and `"rk4"` otherwise.
    pub integrator: IntegratorName,
    /// A fixed step or a tolerance.
    pub stepping: Stepping,
    /// The steps and samples.
    pub schedule: Schedule,
    /// Simulated time (s).
    pub duration: f64,
    /// Time between recorded samples (s).
    pub sample_interval: f64,
    /// How the joints are held.
    pub stabilisation: Stabilisation,
    /// How far the start may be moved onto its joints (m and rad), positive.
    pub max_start_correction: f64,
    /// The bodies and joints.
    pub layout: Layout,
    /// The robot.
    pub robot: Option<CheckedRobot>,
    /// Spring-dampers between two bodies, as written.
    pub springs: Vec<SpringSpec>,
    /// Constant couples between two bodies, as written.
    pub couples: Vec<CoupleSpec>,
    /// Torques on joints by name, as written.
    pub joint_torques: Vec<JointTorqueSpec>,
    /// Viscous damping on joints by name, as written.
    pub joint_dampings: Vec<JointDampingSpec>,
    /// PD controllers on joints by name, as written.
    pub pds: Vec<PdSpec>,
    /// Body points kept above world planes, as written, and the `[[plane]]`s' contacts with the collision shapes.
    pub contacts: Vec<ContactSpec>,
    /// Pairs of bodies whose collision shapes stay apart.
    pub pairs: Vec<CheckedPair>,
    /// One body alone, without joints, a robot, force elements or contacts: a free body, which every integrator
    /// (splittings included) runs.
    pub free_body: bool,
    /// Whether every force has a potential, so the energy is conserved and its change is drift: only gravity and
    /// undamped springs, no drive, no friction at contacts.
    pub conservative: bool,
}

impl CheckedScene {
    /// Checks `file`, reading its robot's URDF relative to `folder` (the scene file's).
    pub fn new(file: SceneFile, folder: &Path) -> Result<CheckedScene, SceneFileError> {
        let mut robot = (file.robot.as_ref())
            .map(|spec| LoadedRobot::load(spec, folder))
            .transpose()?;
        // A robot with a tolerance steps in joint coordinates (every joint of its file a joint model: the robot's and
        // the free roots of other bodies), where its error is measured coordinate by coordinate; a [[joint]] may
        // be a constraint no joint coordinate describes, and Baumgarte's feedback acts on the bodies, so a file
        // with either steps its bodies.
        let joint_models_only = file.joint.is_empty() && file.stabilisation != StabilisationName::Baumgarte;
        let integrator = file
            .integrator
            .unwrap_or(match (file.tolerance.is_some(), file.robot.is_some()) {
                (true, true) if joint_models_only => IntegratorName::Dop853Joint,
                (true, _) => IntegratorName::Dop853Body,
                (false, true) => IntegratorName::Rkmk8Body,
                (false, false) => IntegratorName::Rk4,
            });
        let (stepping, schedule) = schedule(&file)?;
        let names = Names::resolve(&file, robot.as_ref())?;
        let bodies = names.body_count() + robot.as_ref().map_or(0, LoadedRobot::body_count);
        check_samples(&schedule, bodies, &file)?;
        check_error_estimate(integrator, stepping)?;
        let (contacts, pairs) = contacts_with_planes(&file, folder, robot.as_mut())?;
        let free_body = names.joint_count() == 0
            && names.body_count() == 1
            && robot.is_none()
            && file.spring.is_empty()
            && file.couple.is_empty()
            && file.joint_torque.is_empty()
            && file.joint_damping.is_empty()
            && file.pd.is_empty()
            && contacts.is_empty()
            && pairs.is_empty();
        let method = Integrator::from(integrator);
        if matches!(method, Integrator::Splitting(_)) && !free_body {
            return Err(invalid(
                "integrator",
                format!(
                    "{} is a splitting method, which runs one body without constraints, a robot or force elements only",
                    method.name()
                ),
            ));
        }
        let robot = robot.map(LoadedRobot::checked).transpose()?;
        if bodies == 0 {
            return Err(invalid(
                "robot",
                "nothing moves: the robot's root is fixed and it has no moving body, and the file has no [[body]]",
            ));
        }
        let layout = names.checked(file.duration)?;
        let stabilisation = stabilisation(file.stabilisation, file.baumgarte)?;
        let max_start_correction = file.max_start_correction;
        if !(max_start_correction.is_finite() && max_start_correction > 0.0) {
            return Err(invalid(
                "max_start_correction",
                format!("must be positive and finite (m and rad), got {max_start_correction}"),
            ));
        }
        let robot_damped = robot.as_ref().is_some_and(|CheckedRobot { loaded, .. }| {
            !loaded.spec.torque.is_empty()
                || (loaded.spec.joint_dynamics == JointDynamicsName::Urdf
                    && loaded.model.joints.iter().any(|j| j.damping > 0.0))
        });
        let conservative = (layout.bodies.iter()).all(|b| b.forces.iter().all(|f| f.conservative()))
            && layout.joints.iter().all(|j| j.drive.is_none())
            && file.spring.iter().all(|s| s.damping == 0.0)
            && file.couple.is_empty()
            && file.joint_torque.is_empty()
            && file.joint_damping.is_empty()
            && file.pd.is_empty()
            && (contacts.iter()).all(|c| c.friction == 0.0 && c.static_friction.unwrap_or(0.0) == 0.0)
            && pairs.iter().all(|p| !p.friction.is_some())
            && !robot_damped;
        Ok(CheckedScene {
            title: file.title,
            algebra: file.algebra,
            integrator,
            stepping,
            schedule,
            duration: file.duration,
            sample_interval: file.sample_interval,
            stabilisation,
            max_start_correction,
            layout,
            robot,
            springs: file.spring,
            couples: file.couple,
            joint_torques: file.joint_torque,
            joint_dampings: file.joint_damping,
            pds: file.pd,
            pairs,
            contacts,
            free_body,
            conservative,
        })
    }
}

/// How the run steps and its schedule, at most [`MAX_STEPS`] steps.
fn schedule(file: &SceneFile) -> Result<(Stepping, Schedule), SceneFileError> {
    let (stepping, schedule) = match (file.dt, file.tolerance) {
        (Some(dt), None) => (
            Stepping::Fixed { dt },
            Schedule::with_sample_interval(dt, file.duration, file.sample_interval),
        ),
        (None, Some(tolerance)) => {
            let checked =
                Tolerance::new(tolerance, tolerance).map_err(|error| invalid("tolerance", error.to_string()))?;
            (
                Stepping::Adaptive { tolerance },
                Schedule::adaptive(checked, file.duration, file.sample_interval),
            )
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
    };
    let schedule = schedule.map_err(SceneFileError::Schedule)?;
    if schedule.step_count() > MAX_STEPS {
        return Err(invalid(
            "dt, duration",
            format!(
                "{} steps ({} s at dt = {:e} s) is more than a scene file runs (at most {MAX_STEPS:e})",
                schedule.step_count(),
                file.duration,
                schedule.dt()
            ),
        ));
    }
    Ok((stepping, schedule))
}

/// Refuses more than [`MAX_SAMPLES`] samples of `bodies` bodies.
fn check_samples(schedule: &Schedule, bodies: usize, file: &SceneFile) -> Result<(), SceneFileError> {
    if schedule.sample_count().saturating_mul(bodies) > MAX_SAMPLES {
        return Err(invalid(
            "duration, sample_interval",
            format!(
                "{} samples ({} s every {} s) of {bodies} bodies is more than a scene file records (at most \
                 {MAX_SAMPLES:e} body samples): lengthen sample_interval",
                schedule.sample_count(),
                file.duration,
                file.sample_interval
            ),
        ));
    }
    Ok(())
}

/// Refuses an integrator without an error estimate for adaptive steps.
fn check_error_estimate(integrator: IntegratorName, stepping: Stepping) -> Result<(), SceneFileError> {
    let method = Integrator::from(integrator);
    if matches!(stepping, Stepping::Adaptive { .. }) && method.estimate_order().is_none() {
        return Err(invalid(
            "integrator",
            format!(
                "{} has no error estimate to choose its steps by: with a tolerance, name \"dop853-body\" or \
                 \"dp5-body\" (or leave the integrator out), or give dt in place of the tolerance",
                method.name()
            ),
        ));
    }
    Ok(())
}

/// How the joints are held: `name`, with the `baumgarte` gains if given; an error if gains are given for another
/// stabilisation.
fn stabilisation(name: StabilisationName, gains: Option<BaumgarteGains>) -> Result<Stabilisation, SceneFileError> {
    match (name, gains) {
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

/// The file's `[[contact]]`s, then every `[[plane]]`'s contacts with the bodies' collision shapes, and the
/// `[[collision]]` pairs; a `[[plane]]` with no shape to keep above it is refused (it would do nothing), as is a shape
/// with neither a plane nor a pair.
fn contacts_with_planes(
    file: &SceneFile,
    folder: &Path,
    robot: Option<&mut LoadedRobot>,
) -> Result<(Vec<ContactSpec>, Vec<CheckedPair>), SceneFileError> {
    let mut bodies: Vec<ShapedBody> = match &file.body {
        None => Vec::new(),
        Some(Bodies::One(spec)) => vec![ShapedBody {
            name: None,
            shapes: spec.collision.clone(),
        }],
        Some(Bodies::Named(entries)) => (entries.iter())
            .map(|entry| ShapedBody {
                name: Some(entry.name.clone()),
                shapes: entry.collision.clone(),
            })
            .collect(),
    };
    // The robot's links' shapes, with a warning in the model for each URDF shape that cannot be one.
    let mut skipped = Vec::new();
    let urdf = robot.filter(|robot| robot.spec.collisions == CollisionsName::Urdf);
    let asked = urdf.is_some();
    if let Some(robot) = urdf {
        bodies.extend(urdf_shapes(&robot.model.collisions, &robot.path, &mut skipped));
        robot.model.warnings.extend(skipped.iter().cloned());
    }
    let shaped = bodies.iter().any(|b| !b.shapes.is_empty());
    match (file.plane.is_empty(), shaped) {
        (false, false) => {
            let why = if asked {
                format!("; the robot's URDF shapes could not be used: {}", skipped.join("; "))
            } else {
                String::new()
            };
            return Err(invalid(
                "plane 1",
                format!(
                    "no body has a collision shape to keep above it: give a body `collision = [{{ kind = \"sphere\", \
                     radius = 0.1 }}]` (or a box, capsule or convex hull){why}"
                ),
            ));
        }
        (true, _) if asked && file.collision.is_empty() => {
            return Err(invalid(
                "robot.collisions",
                "\"urdf\" keeps the links' shapes above the [[plane]]s and apart in [[collision]] pairs, and the file \
                 has no [[plane]] and no [[collision]]: add one",
            ))
        }
        (true, true) if file.collision.is_empty() => {
            return Err(invalid(
                "collision",
                "no [[plane]] for the collision shapes to stay above and no [[collision]] pair: add one (`[[plane]]` \
                 with `normal` and `offset`, or `[[collision]]` with `bodies = [\"a\", \"b\"]`)",
            ))
        }
        _ => {}
    }
    let mut contacts = file.contact.clone();
    contacts.extend(plane_contacts(&file.plane, &bodies, folder)?);
    Ok((contacts, collision_pairs(&file.collision, &bodies, folder)?))
}
