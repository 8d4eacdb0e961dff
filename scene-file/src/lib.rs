//! Scenes described in a TOML file (docs/scene-files.md): bodies with their shape or inertia, initial pose
//! and velocities and forces, joints to the world or between bodies, a URDF robot, force elements between bodies,
//! algebra, integrator, step and duration, run without writing Rust (`--scene-file`; the run and its output are in
//! the report crate's `scene_job`).
//!
//! Two layouts, one system: a single `[body]` with its `[initial]` state, `[[forces]]` and `[[constraints]]`
//! to the world; or named `[[body]]` entries, each with its `initial` state and `forces`, and `[[joint]]`
//! entries `between = ["body", "other body", "world" or a robot link]`, with or without a `[robot]`. Both become the
//! same list of bodies and joints ([`SceneFile::layout`]) and one [`Mechanism`]: the robot's bodies and joints
//! first (`urdf_import`), then the file's. A joint is any constraint kind (`Geometry`: ball, hinge, cylindrical,
//! prismatic, planar, universal, fixed, point on plane, line, sphere or circle) in either formulation, its body's
//! side in body coordinates and the rest in its reference's frame; a `[[joint]]` of the first seven kinds is a joint
//! model (`joint_models`), with coordinates, a `drive` if it is a hinge or prismatic joint, and the articulated solve.
//! Force elements (`[[spring]]`, `[[couple]]`, `[[joint_torque]]`, `[[joint_damping]]`, `[[pd]]`) are in `elements`,
//! the robot in `robot`. The run's output, its CSV columns included, is described in the report crate's `scene_job`.
//!
//! [`SceneFile::parse`] checks everything a run needs, down to building the system in each requested
//! algebra, so a bad file fails before anything runs, with a message that names the offending entry. The
//! format is derived from the structs below (serde), so toml reports unknown keys, missing fields and wrong
//! types with their line and column.

mod contacts;
mod elements;
mod joint_models;
pub mod names;
pub mod robot;
mod surfaces;

use std::path::Path;
use std::sync::Arc;

use dynamics::constraints::{
    linear, pinning, Constraint, ConstraintError, MotorPoint, PinningAlgebra, Stabilisation, SurfacePin, VirtualPower,
};
use dynamics::force_elements::{ForceElement, JointState, OfTime};
use dynamics::integrate::Integrator;
use dynamics::limits::JointLimit;
use dynamics::simulate::{simulate, Schedule, SimulationError, SAMPLE_INTERVAL};
use dynamics::step_control::Tolerance;
use dynamics::surfaces::{Surface, SurfaceError};
use dynamics::{
    motor, Algebra, Body, BodyError, Cga, Correction, Dynamics, Force, FreeBody, JointId, JointKind, Mechanism,
    MechanismError, Pga, Reference, ScrewCoordinates, Simulation, State,
};
use nalgebra::{DVector, Isometry3, Quaternion, SVector, Translation3, Unit, UnitQuaternion, Vector3};
use serde::Deserialize;

use crate::names::{AlgebraKind, IntegratorName, StabilisationName};
use elements::{
    bounded, element_name, non_negative, CoupleSpec, DriveSpec, JointDampingSpec, JointTorqueSpec, PdSpec, SpringSpec,
    TimeValue,
};
use joint_models::LimitSpec;
use robot::{JointDynamicsName, LoadedRobot, RobotColumns, RobotJoint, RobotSpec};
use surfaces::SurfaceSpec;

/// Where an end of a joint or force element is: the mechanism's reference (a body or the world) and the end's frame in
/// that reference's frame (a robot link's frame, else the identity).
type Place<'a> = dyn Fn(&End) -> Result<(Reference, Isometry3<f64>), SceneFileError> + 'a;

/// Why a scene file cannot run, or its run failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneFileError {
    /// The file could not be read.
    #[error("cannot read the file: {0}")]
    Read(std::io::Error),
    /// Not TOML, or not this format (unknown key or kind, missing field, wrong type); the message gives
    /// the line and column.
    #[error("{0}")]
    Format(#[from] toml::de::Error),
    /// An unknown key in a table that the TOML reader can only point at as a whole (a joint or constraint, whose
    /// kind decides its keys): the key's own line.
    #[error("TOML parse error at line {line}: {message} (in the table from line {table_line})")]
    UnknownKey {
        /// The line of the unknown key (1-based).
        line: usize,
        /// The line the table starts at (1-based).
        table_line: usize,
        /// The reader's message: the key and the keys expected.
        message: String,
    },
    /// A value the format allows but a run cannot use.
    #[error("{what}: {reason}")]
    Invalid {
        /// The entry and key, as the file names them: "body arm: initial.position".
        what: String,
        /// What is wrong with the value.
        reason: String,
    },
    /// The body's mass or moments of inertia are not physical.
    #[error("body: {0}")]
    Body(#[from] BodyError),
    /// `dt` (or `tolerance`), `duration` and `sample_interval` make no schedule.
    #[error("dt or tolerance, duration, sample_interval: {0}")]
    Schedule(SimulationError),
    /// A joint's geometry was refused, or the joints cannot hold at the initial state or their reactions cannot
    /// be solved for; the message names the joints.
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    /// A body, force, joint or the stabilisation was refused while building the system.
    #[error(transparent)]
    Mechanism(#[from] MechanismError),
    /// A pinned joint needs a sphere or a circle, which only CGA has.
    #[error(
        "constraint {name}: pinning needs a {object}, which {algebra} does not have; write \
         formulation = \"virtual_power\", or algebra = \"cga\""
    )]
    NotExpressible {
        /// The joint's name in messages.
        name: String,
        /// "sphere" or "circle".
        object: &'static str,
        /// The algebra that lacks it.
        algebra: &'static str,
    },
    /// The run itself failed.
    #[error("the {algebra} run failed: {message}")]
    Run {
        /// The algebra it ran in.
        algebra: &'static str,
        /// The simulator's message.
        message: String,
    },
}

fn invalid(what: impl Into<String>, reason: impl Into<String>) -> SceneFileError {
    SceneFileError::Invalid {
        what: what.into(),
        reason: reason.into(),
    }
}

/// The reader's error, or, for an unknown key it can only place at its table's header (tables read through a `kind`
/// tag), the same message at the key's own line: the first `key =` between the header and the next one.
fn at_unknown_key(text: &str, error: toml::de::Error) -> SceneFileError {
    let message = error.message().trim().to_owned();
    let key = message
        .strip_prefix("unknown field `")
        .and_then(|rest| rest.split('`').next());
    let (Some(key), Some(span)) = (key, error.span()) else {
        return error.into();
    };
    let line_of = |offset: usize| text[..offset].matches('\n').count() + 1;
    // The span is the table's header; its keys run to the next header.
    let after_header = text[span.end..].find('\n').map_or(text.len(), |end| span.end + end);
    let end = text[after_header..]
        .match_indices("\n[")
        .next()
        .map_or(text.len(), |(at, _)| after_header + at);
    let table = &text[span.start..end];
    let assigned = table.match_indices(key).find(|&(at, _)| {
        let before = table[..at].chars().next_back();
        let after = table[at + key.len()..].trim_start();
        before.is_none_or(|c| c.is_whitespace() || c == '{' || c == ',') && after.starts_with('=')
    });
    match assigned {
        Some((at, _)) if line_of(span.start + at) != line_of(span.start) => SceneFileError::UnknownKey {
            line: line_of(span.start + at),
            table_line: line_of(span.start),
            message,
        },
        _ => error.into(),
    }
}

/// Which algebras run the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AlgebraChoice {
    /// `"pga"`
    Pga,
    /// `"cga"`
    Cga,
    /// `"both"`, to compare them (the default).
    #[default]
    Both,
}

impl AlgebraChoice {
    /// The algebras, in the order they run.
    pub fn algebras(self) -> Vec<AlgebraKind> {
        match self {
            AlgebraChoice::Pga => vec![AlgebraKind::Pga],
            AlgebraChoice::Cga => vec![AlgebraKind::Cga],
            AlgebraChoice::Both => vec![AlgebraKind::Pga, AlgebraKind::Cga],
        }
    }
}

/// A whole scene file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// A title for the summary and the plots.
    #[serde(default)]
    pub title: Option<String>,
    /// Which algebras run the scene.
    #[serde(default)]
    pub algebra: AlgebraChoice,
    /// The integrator as written, if it is.
    #[serde(default, rename = "integrator")]
    integrator_written: Option<IntegratorName>,
    /// The integrator: as written, else `"rkmk8-body"` with a `[robot]` and `"rk4"` without (set by
    /// [`SceneFile::parse`]); the splittings run a single body without constraints only.
    #[serde(skip, default = "default_integrator")]
    pub integrator: IntegratorName,
    /// The fixed step (s); it must divide the sample interval. A file gives this or `tolerance`.
    #[serde(default)]
    pub dt: Option<f64>,
    /// The accuracy an adaptive run chooses its steps by, in place of `dt` (relative and absolute alike, in rad,
    /// m, rad/s and m/s: `dynamics::step_control`); the integrator then defaults to `"dop853-body"`, the pair of
    /// order 8 (`"dp5-body"`, of order 5, is the other integrator with an error estimate).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Simulated time (s); the last sample interval may be shorter.
    pub duration: f64,
    /// Time between recorded samples (s).
    #[serde(default = "default_sample_interval")]
    pub sample_interval: f64,
    #[serde(default = "default_stabilisation")]
    pub stabilisation: StabilisationName,
    /// How far the start may be moved onto its joints (m and rad) before it is refused as breaking them: its
    /// rounding passes, a body placed off its joint does not.
    #[serde(default = "default_max_start_correction")]
    pub max_start_correction: f64,
    /// Gains for `stabilisation = "baumgarte"` (default α = β = 10, as on the command line).
    #[serde(default)]
    pub baumgarte: Option<BaumgarteGains>,
    /// `[body]`, one body, or `[[body]]`, named bodies; none with a `[robot]` alone.
    #[serde(default)]
    pub body: Option<Bodies>,
    /// The single body's initial state.
    #[serde(default)]
    pub initial: Option<InitialSpec>,
    /// The single body's forces.
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
    /// The single body's constraints to the world.
    #[serde(default)]
    pub constraints: Vec<ConstraintSpec>,
    /// Joints between named bodies, or a named body and the world or a robot link.
    #[serde(default)]
    pub joint: Vec<JointSpec>,
    /// A URDF robot.
    #[serde(default)]
    pub robot: Option<RobotSpec>,
    /// Spring-dampers between two bodies.
    #[serde(default)]
    pub spring: Vec<SpringSpec>,
    /// Constant couples between two bodies.
    #[serde(default)]
    pub couple: Vec<CoupleSpec>,
    /// Torques on joints by name.
    #[serde(default)]
    pub joint_torque: Vec<JointTorqueSpec>,
    /// Viscous damping on joints by name.
    #[serde(default)]
    pub joint_damping: Vec<JointDampingSpec>,
    /// PD controllers on joints by name.
    #[serde(default)]
    pub pd: Vec<PdSpec>,
    /// Body points kept above world planes.
    #[serde(default)]
    pub contact: Vec<contacts::ContactSpec>,
    /// The robot's URDF, read by [`SceneFile::parse`].
    #[serde(skip)]
    pub loaded_robot: Option<Arc<LoadedRobot>>,
}

/// The `body` key: a table (`[body]`, one body) or an array of tables (`[[body]]`, named bodies). Deserialized
/// by peeking at which it is, so that toml's messages keep their line and column.
#[derive(Clone, Debug)]
pub enum Bodies {
    One(BodySpec),
    Named(Vec<NamedBody>),
}

impl<'de> Deserialize<'de> for Bodies {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Bodies;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a [body] table or [[body]] entries")
            }

            fn visit_map<M: serde::de::MapAccess<'de>>(self, map: M) -> Result<Bodies, M::Error> {
                BodySpec::deserialize(serde::de::value::MapAccessDeserializer::new(map)).map(Bodies::One)
            }

            fn visit_seq<S: serde::de::SeqAccess<'de>>(self, seq: S) -> Result<Bodies, S::Error> {
                Vec::<NamedBody>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq)).map(Bodies::Named)
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// A `[[body]]` entry: a name, the body as in `[body]`, its initial state and its forces.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NamedBody {
    /// Letters, digits, `_` and `-` (it heads CSV columns and names the body in messages).
    pub name: String,
    pub mass: f64,
    #[serde(default)]
    pub shape: Option<Shape>,
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub principal_moments: Option<[f64; 3]>,
    #[serde(default)]
    pub initial: Option<InitialSpec>,
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
}

/// A `[[joint]]`: `between = [body, reference]`, the reference another body or `"world"`. The geometry is that
/// of a constraint, with the held body's points and axes in its body coordinates and the rest (`world_point`,
/// `world_axis`, also written `reference_point`, `reference_axis`; normals, offsets, centres) in the
/// reference's: its body coordinates, or the world's.
#[derive(Clone, Debug, Deserialize)]
pub struct JointSpec {
    pub name: String,
    #[serde(deserialize_with = "exactly")]
    pub between: [String; 2],
    #[serde(default)]
    pub formulation: FormulationName,
    /// The prescribed coordinate of a hinge or prismatic joint.
    #[serde(default)]
    pub drive: Option<DriveSpec>,
    /// The range of a hinge's or prismatic joint's coordinate, enforced exactly.
    #[serde(default)]
    pub limit: Option<LimitSpec>,
    #[serde(flatten)]
    pub geometry: Geometry,
}

/// A body of the scene, whichever layout it came from.
#[derive(Clone, Debug)]
pub struct LayoutBody {
    pub name: String,
    pub spec: BodySpec,
    /// Its state at t = 0, as the file gives it.
    pub initial: InitialSpec,
    /// Whether the file gives it (an `initial` table); otherwise its joint places it.
    pub initial_given: bool,
    pub forces: Vec<ForceSpec>,
}

/// What a joint holds its body to, or where a force element's end is.
#[derive(Clone, Debug, PartialEq)]
pub enum End {
    World,
    /// A body of the file, by its index in [`Layout::bodies`].
    Body(usize),
    /// A link of the robot, by name.
    Link(String),
}

/// A joint of the scene: its name in messages, its body (by index) and reference.
#[derive(Clone, Debug)]
pub struct LayoutJoint {
    pub name: String,
    pub body: usize,
    pub reference: End,
    pub formulation: FormulationName,
    pub geometry: Geometry,
    /// A `[[joint]]` entry (a joint model where it can be), not a `[[constraints]]` one.
    pub entry: bool,
    pub drive: Option<DriveSpec>,
    pub limit: Option<LimitSpec>,
}

/// The scene's bodies and joints.
#[derive(Clone, Debug)]
pub struct Layout {
    /// In file order.
    pub bodies: Vec<LayoutBody>,
    pub joints: Vec<LayoutJoint>,
    /// Whether the bodies are named `[[body]]` entries (else the single `[body]`, named "body").
    pub named: bool,
}

impl Layout {
    /// Per joint: its checked geometry (reference-side values in the reference's frame), its body and its
    /// reference, to measure violations with.
    ///
    /// A fixed joint without a given pose holds its body where the file starts it (before the projection onto the
    /// joints). Joints to a robot link are placed by the system ([`SceneSystem::joint_violation`]), not here: they are
    /// an error.
    pub fn joint_geometries(&self) -> Result<Vec<JointGeometry>, SceneFileError> {
        self.joints
            .iter()
            .map(|j| {
                let reference = match &j.reference {
                    End::World => None,
                    End::Body(index) => Some(*index),
                    End::Link(link) => {
                        return Err(invalid(
                            format!("joint {}: between", j.name),
                            format!(
                                "its reference is the robot link {link}, which only the built system places (see \
                                 SceneSystem::joint_violation)"
                            ),
                        ))
                    }
                };
                let start = if j.geometry.needs_start() {
                    let body = self.initial_pose(j.body)?;
                    let reference = reference.map(|r| self.initial_pose(r)).transpose()?;
                    Some(relative_pose(&body, reference.as_ref()))
                } else {
                    None
                };
                Ok((j.geometry.checked(&j.name, start)?, j.body, reference))
            })
            .collect()
    }

    /// Body `index`'s pose as the file starts it.
    fn initial_pose(&self, index: usize) -> Result<Pose, SceneFileError> {
        let body = &self.bodies[index];
        let prefix = prefix(self, &body.name);
        let position = finite(&format!("{prefix}initial.position"), body.initial.position)?;
        let orientation = body
            .initial
            .orientation
            .rotation()
            .map_err(|e| named(self, &body.name, e))?;
        Ok((position, orientation))
    }
}

/// The pose of a body at `body` (world) in the frame of a reference at `reference` (the world if `None`).
fn relative_pose(body: &Pose, reference: Option<&Pose>) -> Pose {
    match reference {
        None => *body,
        Some((position, orientation)) => (
            orientation.inverse() * (body.0 - position),
            orientation.inverse() * body.1,
        ),
    }
}

fn default_integrator() -> IntegratorName {
    IntegratorName::Rk4
}

fn default_sample_interval() -> f64 {
    SAMPLE_INTERVAL
}

/// A millimetre or a milliradian: far above a start written to six digits, far below a body off its joint.
fn default_max_start_correction() -> f64 {
    1e-3
}

fn default_stabilisation() -> StabilisationName {
    StabilisationName::Projection
}

/// `baumgarte = { alpha = …, beta = … }` (1/s). Read as a table only: serde's derived struct would also take an
/// array and drop any numbers past the second (`baumgarte = [1, 2, 3]`).
#[derive(Clone, Copy, Debug)]
pub struct BaumgarteGains {
    pub alpha: f64,
    pub beta: f64,
}

impl<'de> Deserialize<'de> for BaumgarteGains {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Gains;
        const FIELDS: &[&str] = &["alpha", "beta"];
        impl<'de> serde::de::Visitor<'de> for Gains {
            type Value = BaumgarteGains;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table { alpha = …, beta = … }")
            }
            fn visit_map<M: serde::de::MapAccess<'de>>(self, mut map: M) -> Result<BaumgarteGains, M::Error> {
                let (mut alpha, mut beta) = (None, None);
                while let Some(key) = map.next_key::<String>()? {
                    let slot = match key.as_str() {
                        "alpha" => &mut alpha,
                        "beta" => &mut beta,
                        other => return Err(serde::de::Error::unknown_field(other, FIELDS)),
                    };
                    if slot.replace(map.next_value::<f64>()?).is_some() {
                        return Err(serde::de::Error::custom(format!("duplicate field `{key}`")));
                    }
                }
                Ok(BaumgarteGains {
                    alpha: alpha.ok_or_else(|| serde::de::Error::missing_field("alpha"))?,
                    beta: beta.ok_or_else(|| serde::de::Error::missing_field("beta"))?,
                })
            }
        }
        deserializer.deserialize_struct("BaumgarteGains", FIELDS, Gains)
    }
}

/// The body: its mass (kg) and either a shape or its principal moments of inertia (kg m², about the centre
/// of mass along the body axes).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub mass: f64,
    #[serde(default)]
    pub shape: Option<Shape>,
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub principal_moments: Option<[f64; 3]>,
}

/// A solid of uniform density, centred on its centre of mass; lengths in metres.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// Side lengths along body x, y, z.
    Cuboid {
        #[serde(deserialize_with = "exactly")]
        size: [f64; 3],
    },
    /// A thin rod along body z; its small axial moment (kg m²) keeps the inertia invertible.
    Rod {
        length: f64,
        axial_moment: f64,
    },
    /// Axis along body z, tip at body (0, 0, −3 height / 4).
    Cone {
        height: f64,
        radius: f64,
    },
    Sphere {
        radius: f64,
    },
}

/// The state at t = 0. Constrained scenes are projected onto their constraints first (theory §10), so the
/// values need to satisfy them only approximately.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Centre of mass, world (m).
    #[serde(default)]
    #[serde(deserialize_with = "exactly")]
    pub position: [f64; 3],
    /// Body → world; the identity if absent.
    #[serde(default)]
    pub orientation: OrientationSpec,
    /// Angular velocity in body axes (rad/s).
    #[serde(default)]
    #[serde(deserialize_with = "exactly")]
    pub body_angular_velocity: [f64; 3],
    /// Centre-of-mass velocity, world (m/s).
    #[serde(default)]
    #[serde(deserialize_with = "exactly")]
    pub velocity: [f64; 3],
}

/// Body → world rotation: `axis` with `angle` (rad) or `degrees`, or a `quaternion` [w, x, y, z]
/// (normalised here); none of them is the identity.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientationSpec {
    #[serde(default, deserialize_with = "maybe_exactly")]
    pub axis: Option<[f64; 3]>,
    pub angle: Option<f64>,
    pub degrees: Option<f64>,
    #[serde(default, deserialize_with = "maybe_exactly")]
    pub quaternion: Option<[f64; 4]>,
}

/// An external force on the body (world frame).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ForceSpec {
    /// Uniform gravity at the centre of mass (m/s²; default 9.81 along −z).
    Gravity {
        #[serde(default = "standard_gravity")]
        #[serde(deserialize_with = "exactly")]
        acceleration: [f64; 3],
    },
    /// A constant force (N) along the fixed world line through `point` (m).
    Force {
        #[serde(deserialize_with = "exactly")]
        force: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        point: [f64; 3],
    },
    /// A constant couple (N m).
    Couple {
        #[serde(deserialize_with = "exactly")]
        moment: [f64; 3],
    },
}

fn standard_gravity() -> [f64; 3] {
    [0.0, 0.0, -dynamics::forces::STANDARD_GRAVITY]
}

/// How a constraint is written (theory §6 and §7–§9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FormulationName {
    #[default]
    VirtualPower,
    Pinning,
}

impl FormulationName {
    /// The name in summaries: "virtual power" or "pinning".
    pub fn name(self) -> &'static str {
        match self {
            FormulationName::VirtualPower => "virtual power",
            FormulationName::Pinning => "pinning",
        }
    }
}

/// One constraint: its geometry and formulation.
#[derive(Clone, Debug, Deserialize)]
pub struct ConstraintSpec {
    #[serde(default)]
    pub formulation: FormulationName,
    #[serde(flatten)]
    pub geometry: Geometry,
}

/// What a constraint holds. Body points and axes are in body coordinates, the rest in world coordinates;
/// lengths in metres. Axes and normals need not be unit.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Geometry {
    /// The body point stays at the world point (rank 3).
    BallJoint {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
    },
    /// The body turns only about the world axis through the world point, where the body point stays
    /// (rank 5).
    Hinge(AxisJoint),
    /// The body point slides along and turns about the world axis (rank 4).
    Cylindrical(AxisJoint),
    /// The body slides along the world axis without turning: a cylindrical joint that also keeps the body
    /// normal (normal to the body axis) along the world normal (normal to the world axis) (rank 5).
    Prismatic {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        body_axis: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        body_normal: [f64; 3],
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
        #[serde(alias = "reference_axis")]
        #[serde(deserialize_with = "exactly")]
        world_axis: [f64; 3],
        #[serde(alias = "reference_normal")]
        #[serde(deserialize_with = "exactly")]
        world_normal: [f64; 3],
    },
    /// The body plane through the body point normal to the body normal stays on the world plane through the
    /// world point normal to the world normal (rank 3).
    Planar {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        body_normal: [f64; 3],
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
        #[serde(alias = "reference_normal")]
        #[serde(deserialize_with = "exactly")]
        world_normal: [f64; 3],
    },
    /// A Cardan joint: the body point stays at the world point, the body axis normal to the world axis; the body
    /// turns about the world axis and about its own (rank 4).
    Universal(AxisJoint),
    /// A weld: the body keeps its pose in the reference's frame, `position` (its centre of mass, m) and
    /// `orientation` (body → reference, as `[initial] orientation`), each the pose at the start if not given
    /// (rank 6).
    Fixed {
        #[serde(default)]
        #[serde(deserialize_with = "maybe_exactly")]
        position: Option<[f64; 3]>,
        #[serde(default)]
        orientation: Option<OrientationSpec>,
    },
    /// The body point stays on the world plane `normal · x = offset` (rank 1).
    PointOnPlane {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        normal: [f64; 3],
        offset: f64,
    },
    /// The body point stays on the world line through the world point along the world axis (rank 2).
    PointOnLine {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(alias = "reference_point")]
        #[serde(deserialize_with = "exactly")]
        world_point: [f64; 3],
        #[serde(alias = "reference_axis")]
        #[serde(deserialize_with = "exactly")]
        world_axis: [f64; 3],
    },
    /// The body point stays on the sphere (rank 1).
    PointOnSphere {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        centre: [f64; 3],
        radius: f64,
    },
    /// The body point stays on a surface (rank 1).
    PointOnSurface {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        surface: SurfaceSpec,
    },
    /// The body point stays on the curve where two surfaces meet (rank 2).
    PointOnCurve {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        surfaces: Vec<SurfaceSpec>,
    },
    /// The body point stays on the circle of the sphere in the plane through its centre normal to
    /// `normal` (rank 2).
    PointOnCircle {
        #[serde(deserialize_with = "exactly")]
        body_point: [f64; 3],
        #[serde(deserialize_with = "exactly")]
        centre: [f64; 3],
        radius: f64,
        #[serde(deserialize_with = "exactly")]
        normal: [f64; 3],
    },
}

/// A body axis through a body point, held on a world axis through a world point.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisJoint {
    #[serde(deserialize_with = "exactly")]
    pub body_point: [f64; 3],
    #[serde(deserialize_with = "exactly")]
    pub body_axis: [f64; 3],
    #[serde(alias = "reference_point")]
    #[serde(deserialize_with = "exactly")]
    pub world_point: [f64; 3],
    #[serde(alias = "reference_axis")]
    #[serde(deserialize_with = "exactly")]
    pub world_axis: [f64; 3],
}

/// `[T; N]` from an array of exactly `N` values: serde's own arrays read the first `N` and let toml drop the rest
/// without a word (`body_point = [0.0, 0.0, 0.5, 9.0]` once meant `[0.0, 0.0, 0.5]`).
fn exactly<'de, D, T, const N: usize>(deserializer: D) -> Result<[T; N], D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    let values = Vec::<T>::deserialize(deserializer)?;
    let count = values.len();
    values
        .try_into()
        .map_err(|_| serde::de::Error::invalid_length(count, &format!("an array of {N}").as_str()))
}

/// [`exactly`] for an optional key.
fn maybe_exactly<'de, D, T, const N: usize>(deserializer: D) -> Result<Option<[T; N]>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    exactly(deserializer).map(Some)
}

/// `[[f64; 3]; N]`: `N` points of exactly three numbers each.
fn points<'de, D, const N: usize>(deserializer: D) -> Result<[[f64; 3]; N], D::Error>
where
    D: serde::Deserializer<'de>,
{
    let rows = Vec::<Vec<f64>>::deserialize(deserializer)?;
    let count = rows.len();
    let rows: Vec<[f64; 3]> = rows
        .into_iter()
        .map(|row| {
            let length = row.len();
            row.try_into()
                .map_err(|_| serde::de::Error::invalid_length(length, &"a point of 3 numbers"))
        })
        .collect::<Result<_, D::Error>>()?;
    rows.try_into()
        .map_err(|_| serde::de::Error::invalid_length(count, &format!("an array of {N} points").as_str()))
}

/// The values as a vector, if all are finite.
fn finite<const D: usize>(what: &str, values: [f64; D]) -> Result<SVector<f64, D>, SceneFileError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(SVector::from(values))
    } else {
        Err(invalid(what, format!("{values:?} is not finite")))
    }
}

/// Finite, non-zero values as `(scale, vector)`, the values = scale × vector, with a squared length that neither
/// overflows nor underflows: the values themselves (scale 1), unless their squared length does (lengths above
/// about 1e154 or below about 1e-154; a normal of 1e300 once became the zero vector), then divided by their
/// largest magnitude. So every finite, non-zero vector has its length and direction, and the usual ones are
/// computed exactly as before.
fn rescaled<const D: usize>(what: &str, values: [f64; D]) -> Result<(f64, SVector<f64, D>), SceneFileError> {
    let vector = finite(what, values)?;
    let largest = vector.amax();
    if largest == 0.0 {
        Err(invalid(what, "has no direction (zero vector)"))
    } else if vector.norm_squared().is_normal() {
        Ok((1.0, vector))
    } else {
        Ok((largest, vector / largest))
    }
}

/// The unit vector along finite, non-zero values (of any magnitude).
fn direction(what: &str, values: [f64; 3]) -> Result<Unit<Vector3<f64>>, SceneFileError> {
    Ok(Unit::new_normalize(rescaled(what, values)?.1))
}

fn positive(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(what, format!("must be positive and finite, got {value}")))
    }
}

impl Shape {
    fn body(&self, mass: f64) -> Result<Body, BodyError> {
        match *self {
            Shape::Cuboid { size } => Body::cuboid(mass, Vector3::from(size)),
            Shape::Rod { length, axial_moment } => Body::rod(mass, length, axial_moment),
            Shape::Cone { height, radius } => Body::solid_cone(mass, height, radius),
            Shape::Sphere { radius } => Body::sphere(mass, radius),
        }
    }
}

impl BodySpec {
    pub fn body(&self) -> Result<Body, SceneFileError> {
        let body = match (&self.shape, self.principal_moments) {
            (Some(shape), None) => shape.body(self.mass),
            (None, Some(moments)) => Body::new(self.mass, Vector3::from(moments)),
            (Some(_), Some(_)) => return Err(invalid("body", "give `shape` or `principal_moments`, not both")),
            (None, None) => return Err(invalid("body", "needs a `shape` or `principal_moments`")),
        };
        Ok(body?)
    }
}

impl OrientationSpec {
    /// The rotation, or an error naming what is wrong: keys given in another combination, a non-finite
    /// angle, a zero axis or quaternion.
    pub fn rotation(&self) -> Result<UnitQuaternion<f64>, SceneFileError> {
        self.rotation_of("initial.orientation")
    }

    /// [`OrientationSpec::rotation`], with messages naming the key `what`.
    pub fn rotation_of(&self, what: &str) -> Result<UnitQuaternion<f64>, SceneFileError> {
        let axis_angle = |axis: [f64; 3], angle: f64| {
            if !angle.is_finite() {
                return Err(invalid(what, format!("angle {angle} is not finite")));
            }
            Ok(UnitQuaternion::from_axis_angle(
                &direction(&format!("{what}.axis"), axis)?,
                angle,
            ))
        };
        match (self.axis, self.angle, self.degrees, self.quaternion) {
            (None, None, None, None) => Ok(UnitQuaternion::identity()),
            (Some(axis), Some(angle), None, None) => axis_angle(axis, angle),
            (Some(axis), None, Some(degrees), None) => axis_angle(axis, degrees.to_radians()),
            (None, None, None, Some(quaternion)) => match rescaled(what, quaternion) {
                Ok((_, q)) => Ok(UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))),
                Err(_) => Err(invalid(
                    what,
                    format!("quaternion {quaternion:?} is zero or not finite"),
                )),
            },
            _ => Err(invalid(
                what,
                "give `axis` with either `angle` (rad) or `degrees`, or a `quaternion` [w, x, y, z]",
            )),
        }
    }
}

impl ForceSpec {
    fn force<A: Algebra>(&self, index: usize) -> Result<Force<A>, SceneFileError> {
        let what = |field: &str| format!("force {index}: {field}");
        Ok(match *self {
            ForceSpec::Gravity { acceleration } => Force::Gravity {
                acceleration: finite(&what("acceleration"), acceleration)?,
            },
            ForceSpec::Force { force, point } => Force::Line {
                force: finite(&what("force"), force)?,
                point: finite(&what("point"), point)?,
            },
            ForceSpec::Couple { moment } => Force::Couple {
                moment: finite(&what("moment"), moment)?,
            },
        })
    }

    pub fn kind(&self) -> &'static str {
        match self {
            ForceSpec::Gravity { .. } => "gravity",
            ForceSpec::Force { .. } => "constant force",
            ForceSpec::Couple { .. } => "couple",
        }
    }

    /// Whether the force has a potential, so that the energy is conserved under it.
    pub fn conservative(&self) -> bool {
        matches!(self, ForceSpec::Gravity { .. })
    }
}

/// An algebra in which scene files run. Only CGA has the spheres and circles that pinning a point to one
/// needs (theory §9, §13).
pub trait FileAlgebra: PinningAlgebra {
    /// The pin holding the body point (body coordinates) on the sphere (world, m); `None` without spheres.
    fn point_on_sphere_pin(
        name: String,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>>;
    /// The pin holding the body point on the circle (centre, radius, unit normal of its plane; world, m);
    /// `None` without circles.
    fn point_on_circle_pin(
        name: String,
        body_point: Vector3<f64>,
        circle: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>>;
}

impl FileAlgebra for Pga {
    fn point_on_sphere_pin(_: String, _: Vector3<f64>, _: Vector3<f64>, _: f64) -> Option<Arc<dyn Constraint<Self>>> {
        None
    }

    fn point_on_circle_pin(
        _: String,
        _: Vector3<f64>,
        _: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>> {
        None
    }
}

impl FileAlgebra for Cga {
    fn point_on_sphere_pin(
        name: String,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>> {
        Some(Arc::new(linear::cga_point_on_sphere(name, body_point, centre, radius)))
    }

    fn point_on_circle_pin(
        name: String,
        body_point: Vector3<f64>,
        circle: (Vector3<f64>, f64, Vector3<f64>),
    ) -> Option<Arc<dyn Constraint<Self>>> {
        Some(Arc::new(linear::cga_point_on_circle(name, body_point, circle)))
    }
}

/// What an axis joint leaves free.
#[derive(Clone, Copy, Debug)]
pub enum AxisFreedom {
    /// Turning about the axis: a hinge.
    Turn,
    /// Turning about and sliding along it: a cylindrical joint.
    TurnAndSlide,
    /// Sliding along it: a prismatic joint, whose body normal stays along the world normal (unit, normal to
    /// their axes).
    Slide {
        /// Body coordinates.
        body_normal: Vector3<f64>,
        /// The reference's coordinates.
        world_normal: Vector3<f64>,
    },
}

/// A constraint's geometry with every value checked: finite points, unit axes and normals, positive radii.
/// `body` values are in body coordinates, `world` values and the rest in the reference's (the world's, or a
/// reference body's until [`CheckedGeometry::in_world`]); points and lengths in metres.
// A surface holds its multivector and pose (about 200 bytes); a geometry is checked once per joint and read per
// sample for the violation, where a box would cost an indirection and the type its `Copy`.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug)]
pub enum CheckedGeometry {
    /// A body point held at a world point.
    Ball {
        /// The held point.
        body_point: Vector3<f64>,
        /// Where it is held.
        world_point: Vector3<f64>,
    },
    /// A body axis (point, unit direction) held on a world axis.
    Axis {
        /// Turning, sliding or both.
        freedom: AxisFreedom,
        /// The body axis.
        body: (Vector3<f64>, Vector3<f64>),
        /// The axis it is held on.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// A body plane (point, unit normal) held on a world plane.
    Planar {
        /// The body plane.
        body: (Vector3<f64>, Vector3<f64>),
        /// The plane it is held on.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// A body point held at a world point, the body axis (point, unit direction) kept normal to the world axis: a
    /// universal joint.
    Universal {
        /// The body point and axis.
        body: (Vector3<f64>, Vector3<f64>),
        /// The world point and axis.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// The body held at a pose: its centre of mass at `position`, turned by `orientation` (body → world).
    Weld {
        /// m.
        position: Vector3<f64>,
        /// Body → world.
        orientation: UnitQuaternion<f64>,
    },
    /// A body point held on a world line (point, unit direction).
    Line {
        /// The held point.
        body_point: Vector3<f64>,
        /// The line.
        world: (Vector3<f64>, Vector3<f64>),
    },
    /// A body point held on the plane `normal · x = offset`.
    Plane {
        /// The held point.
        body_point: Vector3<f64>,
        /// Unit.
        normal: Vector3<f64>,
        /// The plane's signed distance from the origin along `normal`.
        offset: f64,
    },
    /// A body point held on a surface, or on the curve where two meet.
    Surfaces {
        /// The held point.
        body_point: Vector3<f64>,
        /// The (first) surface.
        first: Surface,
        /// The second surface of a curve.
        second: Option<Surface>,
    },
    /// A body point held on a sphere, or on a circle of it.
    Round {
        /// The held point.
        body_point: Vector3<f64>,
        /// The sphere's and the circle's centre.
        centre: Vector3<f64>,
        /// Positive.
        radius: f64,
        /// The circle's plane normal; `None` for a sphere.
        normal: Option<Vector3<f64>>,
    },
}

impl Geometry {
    pub fn kind(&self) -> &'static str {
        match self {
            Geometry::BallJoint { .. } => "ball joint",
            Geometry::Hinge(_) => "hinge",
            Geometry::Cylindrical(_) => "cylindrical joint",
            Geometry::Prismatic { .. } => "prismatic joint",
            Geometry::Planar { .. } => "planar joint",
            Geometry::Universal(_) => "universal joint",
            Geometry::Fixed { .. } => "fixed joint",
            Geometry::PointOnLine { .. } => "point on line",
            Geometry::PointOnPlane { .. } => "point on plane",
            Geometry::PointOnSphere { .. } => "point on sphere",
            Geometry::PointOnCircle { .. } => "point on circle",
            Geometry::PointOnSurface { .. } => "point on surface",
            Geometry::PointOnCurve { .. } => "point on curve",
        }
    }

    /// Whether the checked geometry needs the pose the body starts in (a fixed joint without a given pose).
    pub fn needs_start(&self) -> bool {
        matches!(self, Geometry::Fixed { position, orientation } if position.is_none() || orientation.is_none())
    }

    /// Every value checked; `start` is the body's pose in the reference's frame at the start, which a fixed joint
    /// without a given pose keeps ([`Geometry::needs_start`]).
    fn checked(&self, name: &str, start: Option<Pose>) -> Result<CheckedGeometry, SceneFileError> {
        let what = |field: &str| format!("constraint {name}: {field}");
        let point = |field: &str, values| finite(&what(field), values);
        let unit = |field: &str, values| direction(&what(field), values).map(Unit::into_inner);
        // Normal to a unit axis: its component across the axis, which must not vanish (its length does not matter,
        // so it is rescaled, lest the component overflow).
        let across = |field: &str, axis: Vector3<f64>, values| {
            let (_, normal) = rescaled(&what(field), values)?;
            let across = normal - axis * axis.dot(&normal);
            if across.norm() > 1e-9 * normal.norm() {
                Ok(across.normalize())
            } else {
                Err(invalid(what(field), "is zero or along the axis"))
            }
        };
        let round = |body_point, centre, radius, normal| {
            Ok::<_, SceneFileError>(CheckedGeometry::Round {
                body_point: point("body_point", body_point)?,
                centre: point("centre", centre)?,
                radius: positive(&what("radius"), radius)?,
                normal,
            })
        };
        Ok(match self {
            Geometry::BallJoint {
                body_point,
                world_point,
            } => CheckedGeometry::Ball {
                body_point: point("body_point", *body_point)?,
                world_point: point("world_point", *world_point)?,
            },
            Geometry::Universal(joint) => CheckedGeometry::Universal {
                body: (
                    point("body_point", joint.body_point)?,
                    unit("body_axis", joint.body_axis)?,
                ),
                world: (
                    point("world_point", joint.world_point)?,
                    unit("world_axis", joint.world_axis)?,
                ),
            },
            Geometry::Fixed { position, orientation } => {
                let start = || {
                    start.ok_or_else(|| {
                        invalid(
                            what("position, orientation"),
                            "the pose the body starts in is not known here",
                        )
                    })
                };
                CheckedGeometry::Weld {
                    position: match position {
                        Some(p) => point("position", *p)?,
                        None => start()?.0,
                    },
                    orientation: match orientation {
                        Some(o) => o.rotation_of(&what("orientation"))?,
                        None => start()?.1,
                    },
                }
            }
            Geometry::Hinge(joint) | Geometry::Cylindrical(joint) => CheckedGeometry::Axis {
                freedom: if matches!(self, Geometry::Hinge(_)) {
                    AxisFreedom::Turn
                } else {
                    AxisFreedom::TurnAndSlide
                },
                body: (
                    point("body_point", joint.body_point)?,
                    unit("body_axis", joint.body_axis)?,
                ),
                world: (
                    point("world_point", joint.world_point)?,
                    unit("world_axis", joint.world_axis)?,
                ),
            },
            Geometry::Prismatic {
                body_point,
                body_axis,
                body_normal,
                world_point,
                world_axis,
                world_normal,
            } => {
                let (body_axis, world_axis) = (unit("body_axis", *body_axis)?, unit("world_axis", *world_axis)?);
                CheckedGeometry::Axis {
                    freedom: AxisFreedom::Slide {
                        body_normal: across("body_normal", body_axis, *body_normal)?,
                        world_normal: across("world_normal", world_axis, *world_normal)?,
                    },
                    body: (point("body_point", *body_point)?, body_axis),
                    world: (point("world_point", *world_point)?, world_axis),
                }
            }
            Geometry::Planar {
                body_point,
                body_normal,
                world_point,
                world_normal,
            } => CheckedGeometry::Planar {
                body: (point("body_point", *body_point)?, unit("body_normal", *body_normal)?),
                world: (
                    point("world_point", *world_point)?,
                    unit("world_normal", *world_normal)?,
                ),
            },
            Geometry::PointOnLine {
                body_point,
                world_point,
                world_axis,
            } => CheckedGeometry::Line {
                body_point: point("body_point", *body_point)?,
                world: (point("world_point", *world_point)?, unit("world_axis", *world_axis)?),
            },
            Geometry::PointOnPlane {
                body_point,
                normal,
                offset,
            } => {
                let (scale, scaled_normal) = rescaled(&what("normal"), *normal)?;
                if !offset.is_finite() {
                    return Err(invalid(what("offset"), format!("{offset} is not finite")));
                }
                // n·x = d is the unit normal's n/|n| · x = d/|n|.
                let unit_offset = offset / scale / scaled_normal.norm();
                if !unit_offset.is_finite() {
                    return Err(invalid(
                        what("offset"),
                        format!("{offset} over the normal's length {normal:?} is not finite"),
                    ));
                }
                CheckedGeometry::Plane {
                    body_point: point("body_point", *body_point)?,
                    normal: scaled_normal.normalize(),
                    offset: unit_offset,
                }
            }
            Geometry::PointOnSphere {
                body_point,
                centre,
                radius,
            } => round(*body_point, *centre, *radius, None)?,
            Geometry::PointOnCircle {
                body_point,
                centre,
                radius,
                normal,
            } => round(*body_point, *centre, *radius, Some(unit("normal", *normal)?))?,
            Geometry::PointOnSurface { body_point, surface } => CheckedGeometry::Surfaces {
                body_point: point("body_point", *body_point)?,
                first: surface.surface(&what("surface"))?,
                second: None,
            },
            Geometry::PointOnCurve { body_point, surfaces } => match surfaces.as_slice() {
                [first, second] => CheckedGeometry::Surfaces {
                    body_point: point("body_point", *body_point)?,
                    first: first.surface(&what("surfaces[0]"))?,
                    second: Some(second.surface(&what("surfaces[1]"))?),
                },
                _ => {
                    return Err(invalid(
                        what("surfaces"),
                        format!("{} given: a curve is where exactly two surfaces meet", surfaces.len()),
                    ))
                }
            },
        })
    }
}

/// The constraint of `geometry` (checked, its reference side in the reference body's frame, or the world's) in
/// algebra `A`, by pinning or by virtual power, called `name` in messages.
fn constraint_of<A: FileAlgebra>(
    name: String,
    geometry: CheckedGeometry,
    pinned: bool,
) -> Result<Arc<dyn Constraint<A>>, SceneFileError> {
    let not_expressible = |name, object| SceneFileError::NotExpressible {
        name,
        object,
        algebra: A::NAME,
    };
    Ok(match geometry {
        CheckedGeometry::Universal { body, world } => {
            if pinned {
                return Err(invalid(
                    format!("constraint {name}"),
                    "a universal joint has no pinned form (its two axes staying normal is not an incidence of \
                     pinned objects); write formulation = \"virtual_power\"",
                ));
            }
            Arc::new(VirtualPower::universal(name, body, world)?)
        }
        CheckedGeometry::Weld { position, orientation } => {
            let held = motor::from_pose::<A>(position, &orientation);
            if pinned {
                let zero = A::screw(ScrewCoordinates::default());
                let point = MotorPoint {
                    motor: held,
                    velocity: zero,
                    acceleration: zero,
                };
                Arc::new(pinning::motor_joint::<A>(name, move |_t: f64| point))
            } else {
                Arc::new(VirtualPower::weld(name, held))
            }
        }
        CheckedGeometry::Ball {
            body_point,
            world_point,
        } => {
            if pinned {
                Arc::new(pinning::point::<A>(name, body_point, world_point))
            } else {
                Arc::new(VirtualPower::ball_joint(name, body_point, world_point))
            }
        }
        CheckedGeometry::Axis { freedom, body, world } => match (freedom, pinned) {
            (AxisFreedom::Turn, true) => Arc::new(pinning::hinge::<A>(name, body, world)?),
            (AxisFreedom::Turn, false) => Arc::new(VirtualPower::hinge(name, body, world)?),
            (AxisFreedom::TurnAndSlide, true) => Arc::new(pinning::line::<A>(name, body, world)?),
            (AxisFreedom::TurnAndSlide, false) => Arc::new(VirtualPower::cylindrical(name, body, world)?),
            (
                AxisFreedom::Slide {
                    body_normal,
                    world_normal,
                },
                _,
            ) => {
                let body = (body.0, body.1, body_normal);
                let world = (world.0, world.1, world_normal);
                if pinned {
                    Arc::new(pinning::prismatic::<A>(name, body, world)?)
                } else {
                    Arc::new(VirtualPower::prismatic(name, body, world)?)
                }
            }
        },
        CheckedGeometry::Planar { body, world } => {
            if pinned {
                // The planes {x : n·x = n·p} of the unit normals (pinned planes need normals of one length).
                let plane = |(point, normal): (Vector3<f64>, Vector3<f64>)| (normal, normal.dot(&point));
                Arc::new(pinning::plane::<A>(name, plane(body), plane(world))?)
            } else {
                Arc::new(VirtualPower::planar(name, body, world)?)
            }
        }
        CheckedGeometry::Line { body_point, world } => {
            if pinned {
                Arc::new(linear::point_on_line::<A>(name, body_point, world))
            } else {
                Arc::new(VirtualPower::point_on_line(name, body_point, world)?)
            }
        }
        CheckedGeometry::Plane {
            body_point,
            normal,
            offset,
        } => {
            if pinned {
                Arc::new(linear::point_on_plane::<A>(name, body_point, (normal, offset)))
            } else {
                Arc::new(VirtualPower::point_on_plane(name, body_point, (normal, offset))?)
            }
        }
        CheckedGeometry::Surfaces {
            body_point,
            first,
            second,
        } => match (second, pinned) {
            (None, true) => Arc::new(SurfacePin::point_on_surface(name, body_point, first)?),
            (None, false) => Arc::new(VirtualPower::point_on_surface(name, body_point, first)?),
            (Some(second), true) => Arc::new(SurfacePin::point_on_curve(name, body_point, [first, second])?),
            (Some(second), false) => Arc::new(VirtualPower::point_on_curve(name, body_point, [first, second])?),
        },
        CheckedGeometry::Round {
            body_point,
            centre,
            radius,
            normal: None,
        } => {
            if pinned {
                A::point_on_sphere_pin(name.clone(), body_point, centre, radius)
                    .ok_or_else(|| not_expressible(name, "sphere"))?
            } else {
                Arc::new(VirtualPower::point_on_sphere(name, body_point, centre, radius)?)
            }
        }
        CheckedGeometry::Round {
            body_point,
            centre,
            radius,
            normal: Some(normal),
        } => {
            let circle = (centre, radius, normal);
            if pinned {
                A::point_on_circle_pin(name.clone(), body_point, circle)
                    .ok_or_else(|| not_expressible(name, "circle"))?
            } else {
                Arc::new(VirtualPower::point_on_circle(name, body_point, circle)?)
            }
        }
    })
}

impl CheckedGeometry {
    /// The geometry with its reference-side points, axes and planes moved from the reference body's frame (at
    /// its pose) into the world.
    pub fn in_world(&self, (position, orientation): &Pose) -> Result<CheckedGeometry, SceneFileError> {
        let point = |p: Vector3<f64>| position + orientation * p;
        let axis = |a: Vector3<f64>| orientation * a;
        Ok(match *self {
            CheckedGeometry::Ball {
                body_point,
                world_point,
            } => CheckedGeometry::Ball {
                body_point,
                world_point: point(world_point),
            },
            CheckedGeometry::Axis { freedom, body, world } => CheckedGeometry::Axis {
                freedom: match freedom {
                    AxisFreedom::Slide {
                        body_normal,
                        world_normal,
                    } => AxisFreedom::Slide {
                        body_normal,
                        world_normal: axis(world_normal),
                    },
                    other => other,
                },
                body,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Planar { body, world } => CheckedGeometry::Planar {
                body,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Universal { body, world } => CheckedGeometry::Universal {
                body,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Weld {
                position: at,
                orientation: turn,
            } => CheckedGeometry::Weld {
                position: point(at),
                orientation: orientation * turn,
            },
            CheckedGeometry::Line { body_point, world } => CheckedGeometry::Line {
                body_point,
                world: (point(world.0), axis(world.1)),
            },
            CheckedGeometry::Plane {
                body_point,
                normal,
                offset,
            } => {
                // n·x = d in the reference frame is (Rn)·x_w = d + (Rn)·c in the world.
                let normal = axis(normal);
                CheckedGeometry::Plane {
                    body_point,
                    normal,
                    offset: offset + normal.dot(position),
                }
            }
            CheckedGeometry::Surfaces {
                body_point,
                first,
                second,
            } => {
                let carried = motor::from_pose::<Pga>(*position, orientation);
                let carried_away = |error: SurfaceError| invalid(format!("surface {}", error.parameter), error.reason);
                CheckedGeometry::Surfaces {
                    body_point,
                    first: first.moved::<Pga>(carried).map_err(carried_away)?,
                    second: second
                        .map(|surface| surface.moved::<Pga>(carried))
                        .transpose()
                        .map_err(carried_away)?,
                }
            }
            CheckedGeometry::Round {
                body_point,
                centre,
                radius,
                normal,
            } => CheckedGeometry::Round {
                body_point,
                centre: point(centre),
                radius,
                normal: normal.map(axis),
            },
        })
    }

    /// How far a body at `pose` is from satisfying the constraint (m): the body point's distance from where it
    /// must be; for axis joints also that of the point 1 m further along the body axis, for prismatic and
    /// planar joints that of the point 1 m along the body normal, for universal joints how far the point 1 m along
    /// the body axis is off the plane normal to the world axis, for welds the centre of mass's distance and the
    /// angle (rad) of the turn between the pose and the one held. World geometry (see [`CheckedGeometry::in_world`]
    /// for a body reference).
    pub fn violation(&self, (position, orientation): &Pose) -> f64 {
        let world = |body_point: Vector3<f64>| position + orientation * body_point;
        // Distance of a world point from a world line (point, unit direction).
        let off_line = |(on_line, direction): (Vector3<f64>, Vector3<f64>), p: Vector3<f64>| {
            (p - on_line).cross(&direction).norm()
        };
        match *self {
            CheckedGeometry::Ball {
                body_point,
                world_point,
            } => (world(body_point) - world_point).norm(),
            CheckedGeometry::Axis {
                freedom,
                body,
                world: line,
            } => {
                let along_axis = off_line(line, world(body.0 + body.1));
                let at_point = match freedom {
                    AxisFreedom::Turn => (world(body.0) - line.0).norm(),
                    AxisFreedom::TurnAndSlide => off_line(line, world(body.0)),
                    AxisFreedom::Slide {
                        body_normal,
                        world_normal,
                    } => {
                        // The point 1 m along the body normal stays in the plane of the axis and the world normal.
                        let off_plane = (world(body.0 + body_normal) - line.0).dot(&line.1.cross(&world_normal));
                        off_line(line, world(body.0)).max(off_plane.abs())
                    }
                };
                at_point.max(along_axis)
            }
            CheckedGeometry::Universal { body, world: line } => {
                // The point 1 m along the body axis off the plane normal to the world axis.
                let off_normal = (orientation * body.1).dot(&line.1).abs();
                (world(body.0) - line.0).norm().max(off_normal)
            }
            CheckedGeometry::Weld {
                position: at,
                orientation: turn,
            } => (position - at).norm().max(orientation.angle_to(&turn)),
            CheckedGeometry::Planar { body, world: plane } => {
                let off_plane = plane.1.dot(&(world(body.0) - plane.0)).abs();
                // The point 1 m along the body normal from the world normal through the body point.
                let tilt = (orientation * body.1).cross(&plane.1).norm();
                off_plane.max(tilt)
            }
            CheckedGeometry::Line {
                body_point,
                world: line,
            } => off_line(line, world(body_point)),
            CheckedGeometry::Plane {
                body_point,
                normal,
                offset,
            } => (normal.dot(&world(body_point)) - offset).abs(),
            CheckedGeometry::Surfaces {
                body_point,
                first,
                second,
            } => {
                // |F| / |∇F|: the distance from the surface to first order (exact for a plane).
                let at = world(body_point);
                let distance = |surface: &Surface| surface.value(&at).abs() / surface.gradient(&at).norm();
                distance(&first).max(second.as_ref().map_or(0.0, distance))
            }
            CheckedGeometry::Round {
                body_point,
                centre,
                radius,
                normal,
            } => {
                let offset = world(body_point) - centre;
                let off_plane = normal.map_or(0.0, |n| n.dot(&offset).abs());
                (offset.norm() - radius).abs().max(off_plane)
            }
        }
    }
}

/// A body's pose: its centre of mass (world) and its orientation body → world.
pub type Pose = (Vector3<f64>, UnitQuaternion<f64>);

/// A joint's checked geometry, its body and its reference body (`None`: the world), by index.
pub type JointGeometry = (CheckedGeometry, usize, Option<usize>);

/// Each joint's violation (m) with the bodies at `poses` (by body index).
pub fn joint_violations<'a>(joints: &'a [JointGeometry], poses: &'a [Pose]) -> impl Iterator<Item = f64> + 'a {
    joints.iter().map(|(geometry, body, reference)| match reference {
        None => geometry.violation(&poses[*body]),
        // A reference pose that is not a rigid motion (never one from a run) has no violation to measure.
        Some(r) => geometry
            .in_world(&poses[*r])
            .map_or(f64::NAN, |g| g.violation(&poses[*body])),
    })
}

/// A system ready to run in one algebra: the mechanism (the robot's bodies and joints first, then the file's), its
/// initial state (one per body) on the joints, and what the run measures.
pub struct SceneSystem<A: Algebra> {
    pub system: Mechanism<A>,
    pub initial: Vec<State<A>>,
    /// Every body's name, in the mechanism's order.
    pub names: Vec<String>,
    /// The file's joints: their geometry (reference side in the reference body's frame, or the world's), body and
    /// reference, by mechanism index.
    pub geometries: Vec<JointGeometry>,
    /// The robot's moving joints: model, child, parent (mechanism indices) and where the coordinates start.
    pub robot_joints: Vec<RobotJoint>,
    /// The joints CSV's columns, with a robot.
    pub robot_columns: Option<RobotColumns>,
    /// How far putting the file's start on the joints moved each body.
    pub start_correction: Correction,
}

impl<A: Algebra> SceneSystem<A> {
    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism<A> {
        &self.system
    }

    /// The initial state, one per body, on the joints.
    pub fn initial(&self) -> &[State<A>] {
        &self.initial
    }

    /// Every body's name, in the mechanism's order (the robot's bodies, named after their links, first).
    pub fn body_names(&self) -> &[String] {
        &self.names
    }

    /// The headers of the joints CSV between `t` and `energy`, with a robot.
    pub fn joint_columns(&self) -> Option<&[String]> {
        self.robot_columns.as_ref().map(|c| c.headers.as_slice())
    }

    /// The joints CSV's values between `t` and `energy` at the mechanism's joint positions `q`.
    pub fn joint_row(&self, q: &[f64]) -> Option<Vec<f64>> {
        self.robot_columns.as_ref().map(|c| c.row(q))
    }

    /// The largest joint violation with the bodies at `poses` (mechanism order): the file's joints measured as
    /// [`CheckedGeometry::violation`] (m), the robot's by how far each child is from where its joint's coordinates
    /// put it relative to its parent (the joint origin's distance, m, and the turn's angle, rad). `q`: the joint
    /// positions at these poses, if known.
    pub fn joint_violation(&self, poses: &[Pose], q: Option<&[f64]>) -> f64 {
        let files = joint_violations(&self.geometries, poses).fold(0.0, f64::max);
        if self.robot_joints.is_empty() {
            return files;
        }
        let read;
        let q = match q {
            Some(q) => q,
            None => {
                let states: Vec<State<A>> = poses
                    .iter()
                    .enumerate()
                    .map(|(i, (position, orientation))| {
                        State::new(
                            self.system.body(i),
                            *position,
                            orientation,
                            Vector3::zeros(),
                            Vector3::zeros(),
                        )
                    })
                    .collect();
                match self.system.joint_positions(&states, None) {
                    Ok(q) => {
                        read = q;
                        &read
                    }
                    Err(_) => return f64::NAN,
                }
            }
        };
        let isometry =
            |(position, orientation): &Pose| Isometry3::from_parts(Translation3::from(*position), *orientation);
        let robot = self
            .robot_joints
            .iter()
            .map(|(model, child, parent, offset)| {
                let parent = parent.map_or(Isometry3::identity(), |p| isometry(&poses[p]));
                let relative = parent.inverse() * isometry(&poses[*child]);
                let actual = model.parent_frame().inverse() * relative * model.child_frame();
                let count = model.kind().position_count();
                match model.joint_pose(&q[*offset..*offset + count]) {
                    Ok(placed) => (actual.translation.vector - placed.translation.vector)
                        .norm()
                        .max(actual.rotation.angle_to(&placed.rotation)),
                    Err(_) => f64::NAN,
                }
            })
            .fold(0.0, f64::max);
        files.max(robot)
    }
}

/// Scene files larger than this are refused before they are read to the end (the largest shipped one is 5 KiB).
pub const MAX_FILE_BYTES: u64 = 4 << 20;

/// The most steps a scene file's run takes (per algebra): about a minute for a single body, several for a
/// chain; a longer run is more likely a typo (`duration = 99990`, `dt = 1e-15`) than a plan.
pub const MAX_STEPS: usize = 100_000_000;

/// The most body samples (samples × bodies) a scene file's run records (per algebra), about 120 bytes each:
/// every sample is kept for the CSV and the plots.
pub const MAX_SAMPLES: usize = 1_000_000;

/// The name of the world in `between`.
const WORLD: &str = "world";

impl SceneFile {
    /// Reads and checks a scene file (at most [`MAX_FILE_BYTES`]); a robot's URDF path is relative to the file's
    /// folder.
    ///
    /// ```
    /// use std::path::Path;
    /// use scene_file::SceneFile;
    ///
    /// // The heavy top shipped in the workspace's `scenes` folder: a cone on a ball joint at its tip.
    /// let scene = SceneFile::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/heavy_top.toml"))?;
    /// assert_eq!((scene.dt, scene.duration), (Some(1e-3), 10.0));
    /// assert_eq!(scene.constraints.len(), 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn load(path: &Path) -> Result<SceneFile, SceneFileError> {
        use std::io::Read as _;
        let file = std::fs::File::open(path).map_err(SceneFileError::Read)?;
        let mut bytes = Vec::new();
        file.take(MAX_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(SceneFileError::Read)?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(invalid("the file", format!("is larger than {MAX_FILE_BYTES} bytes")));
        }
        let text = String::from_utf8(bytes).map_err(|e| invalid("the file", format!("is not UTF-8: {e}")))?;
        SceneFile::parse_in(&text, path.parent().unwrap_or(Path::new("")))
    }

    /// Parses a scene file and checks that it can run: the bodies, the timing, the integrator and, in every
    /// requested algebra, the forces, joints, stabilisation, the projection of the initial state onto the
    /// joints and the reaction solve there. A robot's URDF path is relative to the current folder
    /// ([`SceneFile::parse_in`] takes another).
    ///
    /// ```
    /// use scene_file::SceneFile;
    ///
    /// // A pendulum: a 1 m rod hung from the world by a ball joint at its top end.
    /// let pendulum = r#"
    ///     dt = 1e-3
    ///     duration = 0.5
    ///
    ///     [body]
    ///     mass = 1.0
    ///     shape = { kind = "rod", length = 1.0, axial_moment = 1e-3 }
    ///
    ///     [[forces]]
    ///     kind = "gravity"
    ///
    ///     [[constraints]]
    ///     kind = "ball_joint"
    ///     body_point = [0.0, 0.0, 0.5]
    ///     world_point = [0.0, 0.0, 0.0]
    /// "#;
    /// let scene = SceneFile::parse(pendulum)?;
    /// assert_eq!(scene.layout()?.bodies.len(), 1);
    /// assert_eq!(scene.schedule()?.step_count(), 500);
    ///
    /// // A bad value fails here, naming it, before anything runs.
    /// let error = SceneFile::parse(&pendulum.replace("mass = 1.0", "mass = -1.0")).unwrap_err();
    /// assert!(error.to_string().contains("mass"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse(text: &str) -> Result<SceneFile, SceneFileError> {
        SceneFile::parse_in(text, Path::new(""))
    }

    /// [`SceneFile::parse`], with a robot's URDF path relative to `folder` (the scene file's).
    ///
    /// ```
    /// use scene_file::SceneFile;
    ///
    /// let folder = std::env::temp_dir().join(format!("parse-in-{}", std::process::id()));
    /// std::fs::create_dir_all(&folder)?;
    /// std::fs::write(folder.join("wheel.urdf"), r#"<robot name="wheel">
    ///   <link name="base"/>
    ///   <link name="wheel"><inertial><mass value="1"/>
    ///     <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.2"/></inertial></link>
    ///   <joint name="axle" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 0 1"/></joint>
    /// </robot>"#)?;
    /// let text = "dt = 1e-3\nduration = 0.1\n[robot]\nurdf = \"wheel.urdf\"\nroot = \"fixed\"\n";
    /// let scene = SceneFile::parse_in(text, &folder)?;
    /// assert_eq!(scene.schedule()?.step_count(), 100);
    /// // Elsewhere the URDF is not found, and the error names it.
    /// let error = SceneFile::parse_in(text, &folder.join("elsewhere")).unwrap_err();
    /// assert!(error.to_string().contains("wheel.urdf"), "{error}");
    /// std::fs::remove_dir_all(&folder)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse_in(text: &str, folder: &Path) -> Result<SceneFile, SceneFileError> {
        let mut scene: SceneFile = toml::from_str(text).map_err(|error| at_unknown_key(text, error))?;
        if let Some(robot) = &scene.robot {
            scene.loaded_robot = Some(Arc::new(robot.load(folder)?));
        }
        scene.integrator = scene.integrator_written.unwrap_or(if scene.tolerance.is_some() {
            IntegratorName::Dop853Body
        } else if scene.robot.is_some() {
            IntegratorName::Rkmk8Body
        } else {
            IntegratorName::Rk4
        });
        scene.schedule()?;
        if scene.tolerance.is_some() && Integrator::from(scene.integrator).estimate_order().is_none() {
            return Err(invalid(
                "integrator",
                format!(
                    "{} has no error estimate to choose its steps by: with a tolerance, name \"dop853-body\" or \
                     \"dp5-body\" (or leave the integrator out), or give dt in place of the tolerance",
                    Integrator::from(scene.integrator).name()
                ),
            ));
        }
        let layout = scene.layout()?;
        let splitting = matches!(Integrator::from(scene.integrator), Integrator::Splitting(_));
        if splitting && !scene.free_body(&layout) {
            return Err(invalid(
                "integrator",
                format!(
                    "{} is a splitting method, which runs one body without constraints, a robot or force elements only",
                    Integrator::from(scene.integrator).name()
                ),
            ));
        }
        for algebra in scene.algebra.algebras() {
            match algebra {
                AlgebraKind::Pga => scene.check_integrator(&scene.system::<Pga>()?)?,
                AlgebraKind::Cga => scene.check_integrator(&scene.system::<Cga>()?)?,
            }
        }
        Ok(scene)
    }

    /// An integrator stepping in joint coordinates needs every joint a joint model, in a tree: refused here, naming
    /// the integrator, rather than when the run starts.
    fn check_integrator<A: FileAlgebra>(&self, system: &SceneSystem<A>) -> Result<(), SceneFileError> {
        let integrator = Integrator::from(self.integrator);
        if matches!(integrator, Integrator::Joint(_)) {
            dynamics::Stepper::new(&system.system, integrator).map_err(|e| invalid("integrator", e.to_string()))?;
        }
        Ok(())
    }

    /// Whether the scene is one body alone, without joints, a robot or force elements: a free body.
    fn free_body(&self, layout: &Layout) -> bool {
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

    /// How the run steps, for titles and summaries: "dt = 0.001 s", or "tolerance = 1e-8 (adaptive steps)".
    pub fn stepping(&self) -> String {
        match (self.dt, self.tolerance) {
            (_, Some(tolerance)) => format!("tolerance = {tolerance:e} (adaptive steps)"),
            (dt, None) => format!("dt = {:e} s", dt.unwrap_or(f64::NAN)),
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

    /// The bodies and joints, from either layout, with every name resolved.
    pub fn layout(&self) -> Result<Layout, SceneFileError> {
        let robot = self.robot()?;
        match &self.body {
            Some(Bodies::One(spec)) => {
                if robot.is_some() {
                    return Err(invalid(
                        "body",
                        "with a [robot], write the scene's other bodies as [[body]] entries with a `name`",
                    ));
                }
                if !self.joint.is_empty() {
                    return Err(invalid(
                        "joint",
                        "[[joint]] entries join named bodies: write the bodies as [[body]] entries with a `name`",
                    ));
                }
                let joints = self
                    .constraints
                    .iter()
                    .enumerate()
                    .map(|(index, c)| LayoutJoint {
                        name: format!("{} ({})", index + 1, c.geometry.kind()),
                        body: 0,
                        reference: End::World,
                        formulation: c.formulation,
                        geometry: c.geometry.clone(),
                        entry: false,
                        drive: None,
                        limit: None,
                    })
                    .collect();
                Ok(Layout {
                    bodies: vec![LayoutBody {
                        name: "body".to_owned(),
                        spec: spec.clone(),
                        initial: self.initial.clone().unwrap_or_default(),
                        initial_given: self.initial.is_some(),
                        forces: self.forces.clone(),
                    }],
                    joints,
                    named: false,
                })
            }
            Some(Bodies::Named(entries)) => self.named_layout(entries, robot.map(|(_, loaded)| loaded)),
            None => match robot {
                Some((_, loaded)) => self.named_layout(&[], Some(loaded)),
                None => Err(invalid(
                    "body",
                    "a scene needs a [body] table, [[body]] entries or a [robot]",
                )),
            },
        }
    }

    /// The layout of named `[[body]]` entries (none with a robot alone), their joints and the robot's links.
    fn named_layout(&self, entries: &[NamedBody], robot: Option<&LoadedRobot>) -> Result<Layout, SceneFileError> {
        if self.initial.is_some() || !self.forces.is_empty() || !self.constraints.is_empty() {
            return Err(invalid(
                "initial, forces, constraints",
                "with [[body]] entries or a [robot], give each body its `initial` state and `forces` in its entry, \
                 and the joints as [[joint]] entries",
            ));
        }
        if entries.is_empty() && robot.is_none() {
            return Err(invalid("body", "needs at least one entry"));
        }
        let mut bodies: Vec<LayoutBody> = Vec::with_capacity(entries.len());
        for entry in entries {
            let name = &entry.name;
            let valid = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            if !valid {
                return Err(invalid(
                    format!("body {name:?}"),
                    "a name is letters, digits, `_` and `-` (it heads the CSV columns)",
                ));
            }
            if name == WORLD || bodies.iter().any(|b| &b.name == name) {
                return Err(invalid(
                    format!("body {name}"),
                    if name == WORLD {
                        "\"world\" is the name of the world".to_owned()
                    } else {
                        "two bodies have this name".to_owned()
                    },
                ));
            }
            if robot.is_some_and(|r| r.links().any(|link| link == name)) {
                return Err(invalid(
                    format!("body {name}"),
                    "the robot has a link of this name (its bodies are named after their links)",
                ));
            }
            bodies.push(LayoutBody {
                name: name.clone(),
                spec: BodySpec {
                    mass: entry.mass,
                    shape: entry.shape.clone(),
                    principal_moments: entry.principal_moments,
                },
                initial: entry.initial.clone().unwrap_or_default(),
                initial_given: entry.initial.is_some(),
                forces: entry.forces.clone(),
            });
        }
        let mut joints: Vec<LayoutJoint> = Vec::with_capacity(self.joint.len());
        for spec in &self.joint {
            let name = &spec.name;
            if name.is_empty() {
                return Err(invalid("joint \"\"", "a joint needs a non-empty name"));
            }
            if joints.iter().any(|j| &j.name == name) {
                return Err(invalid(format!("joint {name}"), "two joints have this name"));
            }
            if robot.is_some_and(|r| r.has_joint(name)) {
                return Err(invalid(format!("joint {name}"), "the robot has a joint of this name"));
            }
            let [held, reference] = &spec.between;
            let what = format!("joint {name}: between");
            if held == WORLD {
                return Err(invalid(
                    what,
                    "the first is the held body, not the world (write [\"body\", \"world\"])",
                ));
            }
            let body = match end_of(&bodies, robot, &what, held)? {
                End::Body(index) => index,
                _ => {
                    return Err(invalid(
                        what,
                        format!(
                            "the first is the held body, a [[body]] entry; the robot link {held} can be the \
                             reference (the second) only"
                        ),
                    ))
                }
            };
            let reference = end_of(&bodies, robot, &what, reference)?;
            if reference == End::Body(body) {
                return Err(invalid(what, format!("joins {held} to itself")));
            }
            joints.push(LayoutJoint {
                name: name.clone(),
                body,
                reference,
                formulation: spec.formulation,
                geometry: spec.geometry.clone(),
                entry: true,
                drive: spec.drive,
                limit: spec.limit,
            });
        }
        Ok(Layout {
            bodies,
            joints,
            named: true,
        })
    }

    /// The system in algebra `A` and its initial state, projected onto the joints; an error if the joints
    /// cannot all hold there or their reactions cannot be solved for.
    pub fn system<A: FileAlgebra>(&self) -> Result<SceneSystem<A>, SceneFileError> {
        let layout = self.layout()?;
        let robot = self.robot()?;
        let built = robot.map(|(spec, loaded)| loaded.build::<A>(spec)).transpose()?;
        let (mut system, mut states) = match &built {
            Some((robot, states)) => (robot.mechanism().clone(), states.clone()),
            None => (Mechanism::<A>::new(), Vec::new()),
        };
        let offset = states.len();
        let mut ids = Vec::with_capacity(layout.bodies.len());
        for entry in &layout.bodies {
            let body = entry.spec.body().map_err(|e| named(&layout, &entry.name, e))?;
            let id = system.add_body(entry.name.clone(), body)?;
            ids.push(id);
            for (index, force) in entry.forces.iter().enumerate() {
                let force = force.force(index + 1).map_err(|e| named(&layout, &entry.name, e))?;
                system.add_force(id, force)?;
            }
            let initial = &entry.initial;
            let at = |what: &str| format!("{}initial.{what}", prefix(&layout, &entry.name));
            states.push(State::new(
                &body,
                finite(&at("position"), initial.position)?,
                &initial
                    .orientation
                    .rotation()
                    .map_err(|e| named(&layout, &entry.name, e))?,
                finite(&at("body_angular_velocity"), initial.body_angular_velocity)?,
                finite(&at("velocity"), initial.velocity)?,
            ));
        }
        if states.is_empty() {
            return Err(invalid(
                "robot",
                "nothing moves: the robot's root is fixed and it has no moving body, and the file has no [[body]]",
            ));
        }
        // Where an end is: the mechanism's reference and the end's frame in that reference's frame.
        let place = |end: &End| -> Result<(Reference, Isometry3<f64>), SceneFileError> {
            match end {
                End::World => Ok((Reference::World, Isometry3::identity())),
                End::Body(index) => Ok((Reference::Body(ids[*index]), Isometry3::identity())),
                End::Link(link) => built
                    .as_ref()
                    .and_then(|(robot, _)| robot.link_frame(link))
                    .ok_or_else(|| invalid(format!("link {link}"), "is not a link of the robot")),
            }
        };
        let index_of = |reference: Reference| match reference {
            Reference::World => None,
            Reference::Body(body) => Some(body.index()),
        };
        let pose_of = |reference: Reference, frame: &Isometry3<f64>, states: &[State<A>]| {
            let body = match reference {
                Reference::World => Isometry3::identity(),
                Reference::Body(body) => {
                    let (position, orientation) = states[body.index()].pose();
                    Isometry3::from_parts(Translation3::from(position), orientation)
                }
            };
            let world = body * frame;
            (world.translation.vector, world.rotation)
        };
        // Per mechanism body: the parent of its joint model, if it has one (the robot's bodies have theirs).
        let mut parent_of: Vec<Option<Option<usize>>> = vec![Some(None); offset];
        parent_of.resize(offset + layout.bodies.len(), None);
        let mut geometries = Vec::with_capacity(layout.joints.len());
        let mut file_joints: Vec<(String, JointId, Option<JointKind>, bool)> = Vec::new();
        let mut driven: Vec<(JointId, DriveSpec)> = Vec::new();
        let mut limited: Vec<(String, JointLimit)> = Vec::new();
        for joint in &layout.joints {
            let name = &joint.name;
            let child = offset + joint.body;
            let (reference, frame) = place(&joint.reference)?;
            let start = joint.geometry.needs_start().then(|| {
                let reference = pose_of(reference, &frame, &states);
                relative_pose(&states[child].pose(), Some(&reference))
            });
            let checked = joint.geometry.checked(name, start)?;
            let drive = joint
                .drive
                .map(|d| d.checked(&format!("joint {name}: drive"), self.duration))
                .transpose()?;
            let limit = joint
                .limit
                .map(|l| l.limit(&format!("joint {name}: limit")))
                .transpose()?;
            let pinned = joint.formulation == FormulationName::Pinning;
            let parent = index_of(reference);
            // A chain of joint models from the reference up that reaches the body would close a loop.
            let mut above = parent;
            let mut cycle = false;
            while let Some(b) = above {
                if b == child {
                    cycle = true;
                    break;
                }
                above = parent_of[b].flatten();
            }
            let model = (joint.entry && parent_of[child].is_none() && !cycle)
                .then(|| joint_models::joint_model(name, &checked, &frame, drive))
                .transpose()?
                .flatten();
            let frame_pose = (frame.translation.vector, frame.rotation);
            let in_body = checked.in_world(&frame_pose)?;
            match model {
                Some(mut model) => {
                    if let Some(limit) = limit {
                        model = model.with_limit(limit).map_err(|error| match error {
                            ConstraintError::InvalidParameter { reason, .. } => {
                                invalid(format!("joint {name}: limit"), reason)
                            }
                            other => other.into(),
                        })?;
                        limited.push((name.clone(), limit));
                    }
                    let kind = *model.kind();
                    let rows = joint_models::rows::<A>(&model, pinned, drive)?;
                    let id = system.connect_with_rows(ids[joint.body], reference, model, rows)?;
                    parent_of[child] = Some(parent);
                    file_joints.push((name.clone(), id, Some(kind), drive.is_some()));
                    if let Some(drive) = drive {
                        driven.push((id, drive));
                    }
                }
                None => {
                    for (key, given, verb) in [
                        ("limit", limit.is_some(), "limited"),
                        ("drive", drive.is_some(), "driven"),
                    ] {
                        if given {
                            return Err(invalid(
                                format!("joint {name}: {key}"),
                                if joint_models::has_model(&checked) {
                                    format!(
                                        "only a body's first joint, its joint model, is {verb}; this one closes a loop"
                                    )
                                } else {
                                    format!("only hinge and prismatic joints are {verb}")
                                },
                            ));
                        }
                    }
                    let constraint = constraint_of::<A>(name.clone(), in_body, pinned)?;
                    let id = system.add_joint(ids[joint.body], reference, constraint)?;
                    file_joints.push((name.clone(), id, None, false));
                }
            }
            geometries.push((in_body, child, parent));
        }
        system.set_stabilisation(self.stabilisation()?)?;
        self.add_elements(
            &layout,
            &mut system,
            &place,
            built.as_ref().map(|(r, _)| r),
            &file_joints,
        )?;
        self.add_contacts(&layout, &mut system, &place)?;
        // Onto the joints (theory §10); joints that cannot hold together are an error naming them, and a start that
        // breaks them by more than the file allows is refused.
        let mut initial = states;
        let start_correction = system.project(0.0, &mut initial)?;
        // Bodies on a joint model are placed by their joint, from the coordinates their state gives; the others' states
        // are where the file puts them.
        let held_as_given: Vec<bool> = (parent_of.iter().enumerate())
            .map(|(index, parent)| {
                let given = |name: &str| layout.bodies.iter().any(|body| body.initial_given && body.name == name);
                parent.is_none() && system.body_names().nth(index).is_some_and(given)
            })
            .collect();
        self.check_start_correction(&start_correction, &system, &held_as_given)?;
        if !driven.is_empty() {
            // The driven joints start on their paths (the projection by joint coordinates leaves them where they are).
            let mut q = system.joint_positions(&initial, None)?;
            let mut v = system.joint_velocities(&initial)?;
            let space = system.joint_space()?;
            for (id, drive) in &driven {
                if let Some(group) = space.groups().iter().find(|g| g.joint() == Some(*id)) {
                    let at = drive.at(0.0);
                    q[group.position_offset()] = at.value;
                    v[group.velocity_offset()] = at.rate;
                }
            }
            initial = system.states_from_joints(&q, &v)?;
            system.project(0.0, &mut initial)?;
        }
        if !limited.is_empty() {
            // A start outside a limit, by the joint's coordinate as the start gives it.
            let q = system.joint_positions(&initial, None)?;
            let space = system.joint_space()?;
            for (name, limit) in &limited {
                let group = space.group(name).expect("a limited joint is a joint model");
                let at = q[group.position_offset()];
                if limit.gap(at) < -dynamics::simulate::AT_BOUND {
                    return Err(invalid(
                        format!("joint {name}: limit"),
                        format!(
                            "the start puts the joint at {at:?}, outside [{:?}, {:?}]",
                            limit.lower(),
                            limit.upper()
                        ),
                    ));
                }
            }
        }
        self.check_contact_start(&system, &initial)?;
        // A rank-deficient or inconsistent reaction solve fails here, with the joints' names.
        system.rates_at(0.0, &initial)?;
        let (robot_columns, robot_joints) = match (&built, robot) {
            (Some((robot, _)), Some((_, loaded))) => (
                Some(loaded.columns(robot, &system)?),
                loaded.joint_models(robot, &system)?,
            ),
            _ => (None, Vec::new()),
        };
        Ok(SceneSystem {
            names: system.body_names().map(str::to_owned).collect(),
            system,
            initial,
            start_correction,
            geometries,
            robot_joints,
            robot_columns,
        })
    }

    /// Refuses a start that the projection onto the joints moved by more than `max_start_correction`, naming the body:
    /// of the bodies `checked` by index, those whose initial state the file gives and no joint model places.
    fn check_start_correction<A: Algebra>(
        &self,
        correction: &Correction,
        system: &Mechanism<A>,
        checked: &[bool],
    ) -> Result<(), SceneFileError> {
        let limit = self.max_start_correction;
        if !(limit.is_finite() && limit > 0.0) {
            return Err(invalid(
                "max_start_correction",
                format!("must be positive and finite (m and rad), got {limit}"),
            ));
        }
        let names: Vec<&str> = system.body_names().collect();
        let largest = (correction.moved.iter().zip(&correction.turned).enumerate())
            .filter(|(body, _)| checked.get(*body).copied().unwrap_or(false))
            .map(|(body, (moved, turned))| (body, moved.max(*turned)))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match largest {
            Some((body, largest)) if largest > limit => Err(invalid(
                "max_start_correction",
                format!(
                    "the start breaks the joints: putting it on them moves body `{}` by {:.3e} m and turns it by \
                     {:.3e} rad, more than max_start_correction = {limit} (m and rad); correct its initial state or \
                     raise max_start_correction",
                    names[body], correction.moved[body], correction.turned[body],
                ),
            )),
            _ => Ok(()),
        }
    }

    /// Adds the force elements: the robot's URDF damping and torques, then the file's springs, couples, joint torques,
    /// joint damping and PD controllers.
    fn add_elements<A: FileAlgebra>(
        &self,
        layout: &Layout,
        system: &mut Mechanism<A>,
        place: &Place<'_>,
        robot: Option<&urdf_import::Robot<A>>,
        file_joints: &[(String, JointId, Option<JointKind>, bool)],
    ) -> Result<(), SceneFileError> {
        let mut taken: Vec<String> = Vec::new();
        let loaded = self.robot()?;
        // A joint by name: its id; `single`: one coordinate (a torque, a PD target).
        let joint = |what: &str, name: &str, single: bool| -> Result<JointId, SceneFileError> {
            if let (Some((_, loaded)), Some(robot)) = (loaded, robot) {
                if loaded.has_joint(name) {
                    if single {
                        loaded.single_coordinate_joint(what, name)?;
                    } else {
                        loaded.joint_index(what, name)?;
                    }
                    return robot
                        .joint(name)
                        .ok_or_else(|| invalid(what, format!("joint `{name}` has no coordinate")));
                }
            }
            match file_joints.iter().find(|(n, ..)| n == name) {
                Some((_, _, Some(JointKind::Weld), _)) => Err(invalid(
                    what,
                    format!("joint `{name}` is a fixed joint: it has no coordinates"),
                )),
                Some((_, id, Some(kind), false)) => {
                    if single && kind.velocity_count() != 1 {
                        return Err(invalid(
                            what,
                            format!(
                                "joint `{name}` is a {} joint, with {} coordinates; a torque or a PD target needs a \
                                 hinge or prismatic joint",
                                kind.name(),
                                kind.velocity_count()
                            ),
                        ));
                    }
                    Ok(*id)
                }
                Some((_, _, Some(_), true)) => Err(invalid(
                    what,
                    format!("joint `{name}` is driven: its motion is prescribed, so a force on it does nothing"),
                )),
                Some((_, _, None, _)) => Err(invalid(
                    what,
                    format!(
                        "joint `{name}` is a constraint without coordinates (it is not a body's first joint of a \
                         kind with coordinates)"
                    ),
                )),
                None => {
                    let mut known: Vec<&str> = loaded
                        .map(|(_, l)| l.model.joints.iter().map(|j| j.name.as_str()).collect())
                        .unwrap_or_default();
                    known.extend(file_joints.iter().map(|(n, ..)| n.as_str()));
                    Err(invalid(
                        what,
                        format!(
                            "no joint named `{name}` (the joints: {})",
                            if known.is_empty() {
                                "none".to_owned()
                            } else {
                                known.join(", ")
                            }
                        ),
                    ))
                }
            }
        };
        if let (Some((spec, loaded)), Some(robot)) = (loaded, robot) {
            if spec.joint_dynamics == JointDynamicsName::Urdf {
                for urdf_joint in loaded.model.joints.iter().filter(|j| j.damping > 0.0) {
                    let id = robot.joint(&urdf_joint.name).expect("a moving joint");
                    let name = element_name(&None, || format!("{} damping (URDF)", urdf_joint.name), &mut taken)?;
                    system.add_force_element(ForceElement::joint_damping(name, id, urdf_joint.damping)?)?;
                }
            }
            for (name, value) in &spec.torque {
                let what = format!("robot.torque.{name}");
                let id = joint("robot.torque", name, true)?;
                let value = bounded(&what, *value)?;
                let element = element_name(&None, || format!("torque on {name}"), &mut taken)?;
                system.add_force_element(ForceElement::joint_force(element, id, OfTime::Constant(value)))?;
            }
        }
        // Two ends of an element: the first a body (swapped if it is the world), and whether they were swapped.
        let ends = |what: &str, between: &[String; 2]| -> Result<_, SceneFileError> {
            let first = self.end(layout, what, &between[0])?;
            let second = self.end(layout, what, &between[1])?;
            let (first, second) = (place(&first)?, place(&second)?);
            let same = match (first.0, second.0) {
                (Reference::World, Reference::World) => true,
                (Reference::Body(a), Reference::Body(b)) => a == b,
                _ => false,
            };
            if same {
                return Err(invalid(
                    format!("{what}: between"),
                    format!(
                        "{} and {} are on the same body (or both on the world): the element would act on nothing",
                        between[0], between[1]
                    ),
                ));
            }
            Ok(match first.0 {
                Reference::World => (second, first, true),
                Reference::Body(_) => (first, second, false),
            })
        };
        let body_of = |reference: Reference| match reference {
            Reference::Body(body) => body,
            Reference::World => unreachable!("the first end is a body"),
        };
        for (k, spring) in self.spring.iter().enumerate() {
            let name = element_name(&spring.name, || format!("spring {}", k + 1), &mut taken)?;
            let what = format!("spring {name}");
            let ((first, first_frame), (second, second_frame), swapped) = ends(&what, &spring.between)?;
            let [mut a, mut b] = spring.points;
            if swapped {
                std::mem::swap(&mut a, &mut b);
            }
            let (a, b) = (
                finite(&format!("{what}: points"), a)?,
                finite(&format!("{what}: points"), b)?,
            );
            let stiffness = non_negative(&format!("{what}: stiffness"), spring.stiffness)?;
            let damping = non_negative(&format!("{what}: damping"), spring.damping)?;
            let rest = non_negative(&format!("{what}: rest_length"), spring.rest_length)?;
            let element = ForceElement::spring_damper(
                name,
                (body_of(first), first_frame.transform_point(&a.into()).coords),
                (second, second_frame.transform_point(&b.into()).coords),
                stiffness,
                damping,
                rest,
            )?;
            system.add_force_element(element)?;
        }
        for (k, couple) in self.couple.iter().enumerate() {
            let name = element_name(&couple.name, || format!("couple {}", k + 1), &mut taken)?;
            let what = format!("couple {name}");
            let ((first, _), (second, _), swapped) = ends(&what, &couple.between)?;
            let moment = finite(&format!("{what}: moment"), couple.moment)?;
            let moment = if swapped { -moment } else { moment };
            system.add_force_element(ForceElement::couple(
                name,
                body_of(first),
                second,
                OfTime::Constant(moment),
            ))?;
        }
        for torque in &self.joint_torque {
            let name = element_name(&torque.name, || format!("torque on {}", torque.joint), &mut taken)?;
            let what = format!("joint_torque {name}");
            let id = joint(&format!("{what}: joint"), &torque.joint, true)?;
            let value = torque.torque.checked(&format!("{what}: torque"))?;
            let force = match value {
                TimeValue::Constant(value) => OfTime::Constant(value),
                sine => OfTime::Function(Arc::new(move |t| sine.at(t))),
            };
            system.add_force_element(ForceElement::joint_force(name, id, force))?;
        }
        for damping in &self.joint_damping {
            let name = element_name(&damping.name, || format!("damping on {}", damping.joint), &mut taken)?;
            let what = format!("joint_damping {name}");
            let id = joint(&format!("{what}: joint"), &damping.joint, false)?;
            let coefficient = non_negative(&format!("{what}: damping"), damping.damping)?;
            system.add_force_element(ForceElement::joint_damping(name, id, coefficient)?)?;
        }
        for (k, pd) in self.pd.iter().enumerate() {
            let name = element_name(&pd.name, || format!("pd {}", k + 1), &mut taken)?;
            let what = format!("pd {name}");
            let kp = non_negative(&format!("{what}: kp"), pd.kp)?;
            let kd = non_negative(&format!("{what}: kd"), pd.kd)?;
            if pd.target.is_empty() {
                return Err(invalid(
                    format!("{what}: target"),
                    "names no joint: write target = { joint = value, … }",
                ));
            }
            let space = system.joint_space()?;
            let mut targets = Vec::with_capacity(pd.target.len());
            for (joint_name, value) in &pd.target {
                let id = joint(&format!("{what}: target"), joint_name, true)?;
                let value = bounded(&format!("{what}: target.{joint_name}"), *value)?;
                let group = space.groups().iter().find(|g| g.joint() == Some(id)).ok_or_else(|| {
                    invalid(
                        format!("{what}: target"),
                        format!("joint `{joint_name}` has no coordinate"),
                    )
                })?;
                let turns = matches!(group.model().kind(), JointKind::Revolute { .. });
                targets.push((group.position_offset(), group.velocity_offset(), value, turns));
            }
            let compensate = pd.gravity_compensation;
            let law = move |state: &JointState<'_, A>| {
                let n = state.velocities.len();
                let bias = if compensate {
                    match state.bias_forces() {
                        Ok(h) => Some(h),
                        Err(_) => return DVector::from_element(n, f64::NAN),
                    }
                } else {
                    None
                };
                let mut tau = DVector::zeros(n);
                for &(p, v, target, turns) in &targets {
                    let mut error = target - state.positions[p];
                    if turns {
                        // Angles are read in (−π, π]: the error is taken the short way round.
                        error -= std::f64::consts::TAU * (error / std::f64::consts::TAU).round();
                    }
                    tau[v] = kp * error - kd * state.velocities[v] + bias.as_ref().map_or(0.0, |h| h[v]);
                }
                tau
            };
            system.add_force_element(ForceElement::controller(name, Arc::new(law)))?;
        }
        Ok(())
    }

    /// Where the end `name` of a force element is: a body of the file, a robot link, or the world.
    fn end(&self, layout: &Layout, what: &str, name: &str) -> Result<End, SceneFileError> {
        end_of(
            &layout.bodies,
            self.robot()?.map(|(_, loaded)| loaded),
            &format!("{what}: between"),
            name,
        )
    }

    /// Runs the scene in algebra `A`: one body without joints as a free body (where every integrator,
    /// splittings included, applies), otherwise as the mechanism.
    pub fn simulate<A: FileAlgebra>(&self) -> Result<Simulation<A>, SceneFileError> {
        let system = self.system::<A>()?;
        self.run(&system)
    }

    /// Runs `system` (this scene's, [`SceneFile::system`]).
    pub fn run<A: FileAlgebra>(&self, system: &SceneSystem<A>) -> Result<Simulation<A>, SceneFileError> {
        let schedule = self.schedule()?;
        let failed = |message: String| SceneFileError::Run {
            algebra: A::NAME,
            message,
        };
        let integrator = Integrator::from(self.integrator);
        let layout = self.layout()?;
        if self.free_body(&layout) {
            let only = &layout.bodies[0];
            let mut free = FreeBody::<A>::new(only.spec.body()?);
            for (index, force) in only.forces.iter().enumerate() {
                free = free.with_force(force.force(index + 1)?);
            }
            return simulate(&free, &system.initial, integrator, &schedule).map_err(|e| failed(e.to_string()));
        }
        simulate(&system.system, &system.initial, integrator, &schedule).map_err(|e| failed(e.to_string()))
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

    /// The force elements, for the summary: "spring 1 (spring-damper, k = 100 N/m, …)".
    pub fn element_list(&self) -> Result<Vec<String>, SceneFileError> {
        let mut out = Vec::new();
        if let Some((spec, loaded)) = self.robot()? {
            if spec.joint_dynamics == JointDynamicsName::Urdf {
                for j in loaded.model.joints.iter().filter(|j| j.damping > 0.0) {
                    out.push(format!("{} damping (URDF): {} on {}", j.name, j.damping, j.name));
                }
            }
            for (name, value) in &spec.torque {
                out.push(format!("torque on {name}: {value} (constant)"));
            }
        }
        for (k, s) in self.spring.iter().enumerate() {
            out.push(format!(
                "{} (spring-damper {} – {}: k = {} N/m, c = {} N s/m, rest length {} m)",
                s.name.clone().unwrap_or_else(|| format!("spring {}", k + 1)),
                s.between[0],
                s.between[1],
                s.stiffness,
                s.damping,
                s.rest_length
            ));
        }
        for (k, c) in self.couple.iter().enumerate() {
            out.push(format!(
                "{} (couple {:?} N m on {}, its opposite on {})",
                c.name.clone().unwrap_or_else(|| format!("couple {}", k + 1)),
                c.moment,
                c.between[0],
                c.between[1]
            ));
        }
        for t in &self.joint_torque {
            out.push(format!(
                "{} (joint torque {} on {})",
                t.name.clone().unwrap_or_else(|| format!("torque on {}", t.joint)),
                t.torque.describe(),
                t.joint
            ));
        }
        for d in &self.joint_damping {
            out.push(format!(
                "{} (joint damping {} on {})",
                d.name.clone().unwrap_or_else(|| format!("damping on {}", d.joint)),
                d.damping,
                d.joint
            ));
        }
        for (k, pd) in self.pd.iter().enumerate() {
            let targets: Vec<String> = pd.target.iter().map(|(j, v)| format!("{j} → {v}")).collect();
            out.push(format!(
                "{} (PD, kp = {}, kd = {}{}: {})",
                pd.name.clone().unwrap_or_else(|| format!("pd {}", k + 1)),
                pd.kp,
                pd.kd,
                if pd.gravity_compensation {
                    ", with the bias forces h(q, v) added"
                } else {
                    ""
                },
                targets.join(", ")
            ));
        }
        for j in self.joint.iter().filter(|j| j.drive.is_some()) {
            if let Some(drive) = j.drive {
                out.push(format!("drive of {}: q(t) = {}", j.name, drive.describe()));
            }
        }
        Ok(out)
    }
}

/// The end `name`: a body of `bodies`, a link of `robot`, or the world; an error under `what` listing them.
fn end_of(bodies: &[LayoutBody], robot: Option<&LoadedRobot>, what: &str, name: &str) -> Result<End, SceneFileError> {
    if name == WORLD {
        return Ok(End::World);
    }
    if let Some(index) = bodies.iter().position(|b| b.name == name) {
        return Ok(End::Body(index));
    }
    if robot.is_some_and(|r| r.links().any(|link| link == name)) {
        return Ok(End::Link(name.to_owned()));
    }
    let known: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    let links = robot.map_or(String::new(), |r| {
        format!("; or a link of the robot: {}", r.links().collect::<Vec<_>>().join(", "))
    });
    Err(invalid(
        what,
        format!(
            "no body named {name:?} (the bodies: {}; or \"world\"{links})",
            if known.is_empty() {
                "none".to_owned()
            } else {
                known.join(", ")
            }
        ),
    ))
}

/// How a body is named in messages: nothing for the single-body layout (its fields are top-level), else
/// "body NAME: ".
fn prefix(layout: &Layout, name: &str) -> String {
    if !layout.named {
        String::new()
    } else {
        format!("body {name}: ")
    }
}

/// An error about a body's entry, with the body's name in front.
fn named(layout: &Layout, name: &str, error: SceneFileError) -> SceneFileError {
    let prefix = prefix(layout, name);
    if prefix.is_empty() {
        return error;
    }
    match error {
        SceneFileError::Invalid { what, reason } => SceneFileError::Invalid {
            what: format!("{prefix}{what}"),
            reason,
        },
        SceneFileError::Body(e) => SceneFileError::Invalid {
            what: format!("body {name}"),
            reason: e.to_string(),
        },
        other => other,
    }
}
