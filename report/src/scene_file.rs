//! Scenes described in a TOML file (README, "Scene files"): bodies with their shape or inertia, initial pose
//! and velocities and forces, joints to the world or between bodies, algebra, integrator, step and duration,
//! run without writing Rust (`--scene-file`; the run and its output are in [`crate::scene_job`]).
//!
//! Two layouts, one system: a single `[body]` with its `[initial]` state, `[[forces]]` and `[[constraints]]`
//! to the world; or named `[[body]]` entries, each with its `initial` state and `forces`, and `[[joint]]`
//! entries `between = ["body", "other body" or "world"]`. Both become the same list of bodies and joints
//! ([`SceneFile::layout`]) and one [`Mechanism`]. A joint is any constraint kind (`Geometry`: ball, hinge,
//! cylindrical, prismatic, planar, point on plane, line, sphere or circle) in either formulation, its body's
//! side in body coordinates and the rest in its reference's frame. The run's output, its CSV columns included,
//! is described in [`crate::scene_job`].
//!
//! [`SceneFile::parse`] checks everything a run needs, down to building the system in each requested
//! algebra, so a bad file fails before anything runs, with a message that names the offending entry. The
//! format is derived from the structs below (serde), so toml reports unknown keys, missing fields and wrong
//! types with their line and column.

use std::path::Path;
use std::sync::Arc;

use dynamics::constraints::{
    linear, pinning, Constraint, ConstraintError, PinningAlgebra, Stabilisation, VirtualPower,
};
use dynamics::integrate::Integrator;
use dynamics::simulate::{simulate, Schedule, SimulationError, SAMPLE_INTERVAL};
use dynamics::{
    Algebra, Body, BodyError, Cga, Force, FreeBody, Mechanism, MechanismError, Pga, Reference, Simulation, State,
};
use nalgebra::{Quaternion, SVector, Unit, UnitQuaternion, Vector3};
use scenarios::Formulation;
use serde::Deserialize;

use crate::names::{IntegratorName, StabilisationName};
use crate::sweep::AlgebraKind;

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
    /// `dt`, `duration` and `sample_interval` make no schedule.
    #[error("dt, duration, sample_interval: {0}")]
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
    pub(crate) title: Option<String>,
    /// Which algebras run the scene.
    #[serde(default)]
    pub algebra: AlgebraChoice,
    /// Default `"rk4"`; the splittings run a single body without constraints only.
    #[serde(default = "default_integrator")]
    pub integrator: IntegratorName,
    /// The step (s); it must divide the sample interval.
    pub dt: f64,
    /// Simulated time (s), a whole number of sample intervals.
    pub duration: f64,
    /// Time between recorded samples (s).
    #[serde(default = "default_sample_interval")]
    pub sample_interval: f64,
    #[serde(default = "default_stabilisation")]
    pub(crate) stabilisation: StabilisationName,
    /// Gains for `stabilisation = "baumgarte"` (default α = β = 10, as on the command line).
    #[serde(default)]
    pub(crate) baumgarte: Option<BaumgarteGains>,
    /// `[body]`, one body, or `[[body]]`, named bodies.
    pub(crate) body: Bodies,
    /// The single body's initial state.
    #[serde(default)]
    pub(crate) initial: Option<InitialSpec>,
    /// The single body's forces.
    #[serde(default)]
    pub(crate) forces: Vec<ForceSpec>,
    /// The single body's constraints to the world.
    #[serde(default)]
    pub constraints: Vec<ConstraintSpec>,
    /// Joints between named bodies, or a named body and the world.
    #[serde(default)]
    pub(crate) joint: Vec<JointSpec>,
}

/// The `body` key: a table (`[body]`, one body) or an array of tables (`[[body]]`, named bodies). Deserialized
/// by peeking at which it is, so that toml's messages keep their line and column.
#[derive(Clone, Debug)]
pub(crate) enum Bodies {
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
pub(crate) struct NamedBody {
    /// Letters, digits, `_` and `-` (it heads CSV columns and names the body in messages).
    pub(crate) name: String,
    pub(crate) mass: f64,
    #[serde(default)]
    pub(crate) shape: Option<Shape>,
    #[serde(default)]
    pub(crate) principal_moments: Option<[f64; 3]>,
    #[serde(default)]
    pub(crate) initial: InitialSpec,
    #[serde(default)]
    pub(crate) forces: Vec<ForceSpec>,
}

/// A `[[joint]]`: `between = [body, reference]`, the reference another body or `"world"`. The geometry is that
/// of a constraint, with the held body's points and axes in its body coordinates and the rest (`world_point`,
/// `world_axis`, also written `reference_point`, `reference_axis`; normals, offsets, centres) in the
/// reference's: its body coordinates, or the world's.
#[derive(Clone, Debug, Deserialize)]
pub(crate) struct JointSpec {
    pub(crate) name: String,
    pub(crate) between: [String; 2],
    #[serde(default)]
    pub(crate) formulation: FormulationName,
    #[serde(flatten)]
    pub(crate) geometry: Geometry,
}

/// A body of the scene, whichever layout it came from.
#[derive(Clone, Debug)]
pub struct LayoutBody {
    pub(crate) name: String,
    pub(crate) spec: BodySpec,
    /// Its state at t = 0, as the file gives it.
    pub initial: InitialSpec,
    pub(crate) forces: Vec<ForceSpec>,
}

/// A joint of the scene: its name in messages, its body and reference (`None`: the world) by index.
#[derive(Clone, Debug)]
pub(crate) struct LayoutJoint {
    pub(crate) name: String,
    pub(crate) body: usize,
    pub(crate) reference: Option<usize>,
    pub(crate) formulation: FormulationName,
    pub(crate) geometry: Geometry,
}

/// The scene's bodies and joints.
#[derive(Clone, Debug)]
pub struct Layout {
    /// In file order.
    pub bodies: Vec<LayoutBody>,
    pub(crate) joints: Vec<LayoutJoint>,
    /// Whether the bodies are named `[[body]]` entries (else the single `[body]`, named "body").
    pub(crate) named: bool,
}

impl Layout {
    /// Per joint: its checked geometry (reference-side values in the reference's frame), its body and its
    /// reference, to measure violations with.
    pub fn joint_geometries(&self) -> Result<Vec<JointGeometry>, SceneFileError> {
        self.joints
            .iter()
            .map(|j| Ok((j.geometry.checked(&j.name)?, j.body, j.reference)))
            .collect()
    }
}

fn default_integrator() -> IntegratorName {
    IntegratorName::Rk4
}

fn default_sample_interval() -> f64 {
    SAMPLE_INTERVAL
}

fn default_stabilisation() -> StabilisationName {
    StabilisationName::Projection
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BaumgarteGains {
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
}

/// The body: its mass (kg) and either a shape or its principal moments of inertia (kg m², about the centre
/// of mass along the body axes).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BodySpec {
    pub(crate) mass: f64,
    #[serde(default)]
    pub(crate) shape: Option<Shape>,
    #[serde(default)]
    pub(crate) principal_moments: Option<[f64; 3]>,
}

/// A solid of uniform density, centred on its centre of mass; lengths in metres.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(crate) enum Shape {
    /// Side lengths along body x, y, z.
    Cuboid {
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
    pub(crate) position: [f64; 3],
    /// Body → world; the identity if absent.
    #[serde(default)]
    pub orientation: OrientationSpec,
    /// Angular velocity in body axes (rad/s).
    #[serde(default)]
    pub(crate) body_angular_velocity: [f64; 3],
    /// Centre-of-mass velocity, world (m/s).
    #[serde(default)]
    pub(crate) velocity: [f64; 3],
}

/// Body → world rotation: `axis` with `angle` (rad) or `degrees`, or a `quaternion` [w, x, y, z]
/// (normalised here); none of them is the identity.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientationSpec {
    pub(crate) axis: Option<[f64; 3]>,
    pub(crate) angle: Option<f64>,
    pub(crate) degrees: Option<f64>,
    pub(crate) quaternion: Option<[f64; 4]>,
}

/// An external force on the body (world frame).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(crate) enum ForceSpec {
    /// Uniform gravity at the centre of mass (m/s²; default 9.81 along −z).
    Gravity {
        #[serde(default = "standard_gravity")]
        acceleration: [f64; 3],
    },
    /// A constant force (N) along the fixed world line through `point` (m).
    Force { force: [f64; 3], point: [f64; 3] },
    /// A constant couple (N m).
    Couple { moment: [f64; 3] },
}

fn standard_gravity() -> [f64; 3] {
    [0.0, 0.0, -dynamics::forces::STANDARD_GRAVITY]
}

/// How a constraint is written (theory §6 and §7–§9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum FormulationName {
    #[default]
    VirtualPower,
    Pinning,
}

impl From<FormulationName> for Formulation {
    fn from(name: FormulationName) -> Formulation {
        match name {
            FormulationName::VirtualPower => Formulation::VirtualPower,
            FormulationName::Pinning => Formulation::Pinning,
        }
    }
}

/// One constraint: its geometry and formulation.
#[derive(Clone, Debug, Deserialize)]
pub struct ConstraintSpec {
    #[serde(default)]
    pub(crate) formulation: FormulationName,
    #[serde(flatten)]
    pub(crate) geometry: Geometry,
}

/// What a constraint holds. Body points and axes are in body coordinates, the rest in world coordinates;
/// lengths in metres. Axes and normals need not be unit.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(crate) enum Geometry {
    /// The body point stays at the world point (rank 3).
    BallJoint {
        body_point: [f64; 3],
        #[serde(alias = "reference_point")]
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
        body_point: [f64; 3],
        body_axis: [f64; 3],
        body_normal: [f64; 3],
        #[serde(alias = "reference_point")]
        world_point: [f64; 3],
        #[serde(alias = "reference_axis")]
        world_axis: [f64; 3],
        #[serde(alias = "reference_normal")]
        world_normal: [f64; 3],
    },
    /// The body plane through the body point normal to the body normal stays on the world plane through the
    /// world point normal to the world normal (rank 3).
    Planar {
        body_point: [f64; 3],
        body_normal: [f64; 3],
        #[serde(alias = "reference_point")]
        world_point: [f64; 3],
        #[serde(alias = "reference_normal")]
        world_normal: [f64; 3],
    },
    /// The body point stays on the world plane `normal · x = offset` (rank 1).
    PointOnPlane {
        body_point: [f64; 3],
        normal: [f64; 3],
        offset: f64,
    },
    /// The body point stays on the world line through the world point along the world axis (rank 2).
    PointOnLine {
        body_point: [f64; 3],
        #[serde(alias = "reference_point")]
        world_point: [f64; 3],
        #[serde(alias = "reference_axis")]
        world_axis: [f64; 3],
    },
    /// The body point stays on the sphere (rank 1).
    PointOnSphere {
        body_point: [f64; 3],
        centre: [f64; 3],
        radius: f64,
    },
    /// The body point stays on the circle of the sphere in the plane through its centre normal to
    /// `normal` (rank 2).
    PointOnCircle {
        body_point: [f64; 3],
        centre: [f64; 3],
        radius: f64,
        normal: [f64; 3],
    },
}

/// A body axis through a body point, held on a world axis through a world point.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AxisJoint {
    pub(crate) body_point: [f64; 3],
    pub(crate) body_axis: [f64; 3],
    #[serde(alias = "reference_point")]
    pub(crate) world_point: [f64; 3],
    #[serde(alias = "reference_axis")]
    pub(crate) world_axis: [f64; 3],
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
    pub(crate) fn body(&self) -> Result<Body, SceneFileError> {
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
        const WHAT: &str = "initial.orientation";
        let axis_angle = |axis: [f64; 3], angle: f64| {
            if !angle.is_finite() {
                return Err(invalid(WHAT, format!("angle {angle} is not finite")));
            }
            Ok(UnitQuaternion::from_axis_angle(
                &direction("initial.orientation.axis", axis)?,
                angle,
            ))
        };
        match (self.axis, self.angle, self.degrees, self.quaternion) {
            (None, None, None, None) => Ok(UnitQuaternion::identity()),
            (Some(axis), Some(angle), None, None) => axis_angle(axis, angle),
            (Some(axis), None, Some(degrees), None) => axis_angle(axis, degrees.to_radians()),
            (None, None, None, Some(quaternion)) => match rescaled(WHAT, quaternion) {
                Ok((_, q)) => Ok(UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))),
                Err(_) => Err(invalid(
                    WHAT,
                    format!("quaternion {quaternion:?} is zero or not finite"),
                )),
            },
            _ => Err(invalid(
                WHAT,
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

    pub(crate) fn kind(&self) -> &'static str {
        match self {
            ForceSpec::Gravity { .. } => "gravity",
            ForceSpec::Force { .. } => "constant force",
            ForceSpec::Couple { .. } => "couple",
        }
    }

    /// Whether the force has a potential, so that the energy is conserved under it.
    pub(crate) fn conservative(&self) -> bool {
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
    pub(crate) fn kind(&self) -> &'static str {
        match self {
            Geometry::BallJoint { .. } => "ball joint",
            Geometry::Hinge(_) => "hinge",
            Geometry::Cylindrical(_) => "cylindrical joint",
            Geometry::Prismatic { .. } => "prismatic joint",
            Geometry::Planar { .. } => "planar joint",
            Geometry::PointOnLine { .. } => "point on line",
            Geometry::PointOnPlane { .. } => "point on plane",
            Geometry::PointOnSphere { .. } => "point on sphere",
            Geometry::PointOnCircle { .. } => "point on circle",
        }
    }

    fn checked(&self, name: &str) -> Result<CheckedGeometry, SceneFileError> {
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
        })
    }
}

impl ConstraintSpec {
    /// The constraint in algebra `A`, called `name` in messages.
    fn constraint<A: FileAlgebra>(&self, name: String) -> Result<Arc<dyn Constraint<A>>, SceneFileError> {
        let pinned = self.formulation == FormulationName::Pinning;
        let not_expressible = |name, object| SceneFileError::NotExpressible {
            name,
            object,
            algebra: A::NAME,
        };
        Ok(match self.geometry.checked(&name)? {
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
                    Arc::new(pinning::plane::<A>(name, plane(body), plane(world)))
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
}

impl CheckedGeometry {
    /// The geometry with its reference-side points, axes and planes moved from the reference body's frame (at
    /// its pose) into the world.
    pub fn in_world(&self, (position, orientation): &Pose) -> CheckedGeometry {
        let point = |p: Vector3<f64>| position + orientation * p;
        let axis = |a: Vector3<f64>| orientation * a;
        match *self {
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
        }
    }

    /// How far a body at `pose` is from satisfying the constraint (m): the body point's distance from where it
    /// must be; for axis joints also that of the point 1 m further along the body axis, for prismatic and
    /// planar joints that of the point 1 m along the body normal. World geometry (see
    /// [`CheckedGeometry::in_world`] for a body reference).
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
        Some(r) => geometry.in_world(&poses[*r]).violation(&poses[*body]),
    })
}

/// A system ready to run in one algebra, and its initial state (one per body) on the joints.
pub struct SceneSystem<A: Algebra> {
    pub(crate) system: Mechanism<A>,
    pub(crate) initial: Vec<State<A>>,
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
    /// Reads and checks a scene file (at most [`MAX_FILE_BYTES`]).
    ///
    /// ```
    /// use std::path::Path;
    /// use report::scene_file::SceneFile;
    ///
    /// // The heavy top shipped in the workspace's `scenes` folder: a cone on a ball joint at its tip.
    /// let scene = SceneFile::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/heavy_top.toml"))?;
    /// assert_eq!((scene.dt, scene.duration), (1e-3, 10.0));
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
        SceneFile::parse(&text)
    }

    /// Parses a scene file and checks that it can run: the bodies, the timing, the integrator and, in every
    /// requested algebra, the forces, joints, stabilisation, the projection of the initial state onto the
    /// joints and the reaction solve there.
    ///
    /// ```
    /// use report::scene_file::SceneFile;
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
        let scene: SceneFile = toml::from_str(text)?;
        scene.schedule()?;
        let layout = scene.layout()?;
        let splitting = matches!(Integrator::from(scene.integrator), Integrator::Splitting(_));
        if splitting && !(layout.joints.is_empty() && layout.bodies.len() == 1) {
            return Err(invalid(
                "integrator",
                format!(
                    "{} is a splitting method, which runs one body without constraints only",
                    Integrator::from(scene.integrator).name()
                ),
            ));
        }
        for algebra in scene.algebra.algebras() {
            match algebra {
                AlgebraKind::Pga => scene.system::<Pga>().map(drop)?,
                AlgebraKind::Cga => scene.system::<Cga>().map(drop)?,
            }
        }
        Ok(scene)
    }

    /// The run's steps and samples, within [`MAX_STEPS`] and [`MAX_SAMPLES`].
    pub fn schedule(&self) -> Result<Schedule, SceneFileError> {
        let schedule = Schedule::with_sample_interval(self.dt, self.duration, self.sample_interval)
            .map_err(SceneFileError::Schedule)?;
        if schedule.step_count() > MAX_STEPS {
            return Err(invalid(
                "dt, duration",
                format!(
                    "{} steps ({} s at dt = {:e} s) is more than a scene file runs (at most {MAX_STEPS:e})",
                    schedule.step_count(),
                    self.duration,
                    self.dt
                ),
            ));
        }
        let bodies = self.layout()?.bodies.len();
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
        match &self.body {
            Bodies::One(spec) => {
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
                        reference: None,
                        formulation: c.formulation,
                        geometry: c.geometry.clone(),
                    })
                    .collect();
                Ok(Layout {
                    bodies: vec![LayoutBody {
                        name: "body".to_owned(),
                        spec: spec.clone(),
                        initial: self.initial.clone().unwrap_or_default(),
                        forces: self.forces.clone(),
                    }],
                    joints,
                    named: false,
                })
            }
            Bodies::Named(entries) => {
                if self.initial.is_some() || !self.forces.is_empty() || !self.constraints.is_empty() {
                    return Err(invalid(
                        "initial, forces, constraints",
                        "with [[body]] entries, give each body its `initial` state and `forces` in its entry, and \
                         the joints as [[joint]] entries",
                    ));
                }
                if entries.is_empty() {
                    return Err(invalid("body", "needs at least one entry"));
                }
                let mut bodies: Vec<LayoutBody> = Vec::with_capacity(entries.len());
                for entry in entries {
                    let name = &entry.name;
                    let valid =
                        !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
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
                    bodies.push(LayoutBody {
                        name: name.clone(),
                        spec: BodySpec {
                            mass: entry.mass,
                            shape: entry.shape.clone(),
                            principal_moments: entry.principal_moments,
                        },
                        initial: entry.initial.clone(),
                        forces: entry.forces.clone(),
                    });
                }
                let index_of = |joint: &str, name: &str| {
                    bodies.iter().position(|b| b.name == name).ok_or_else(|| {
                        let known: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
                        invalid(
                            format!("joint {joint}: between"),
                            format!(
                                "no body named {name:?} (the bodies: {}; or \"world\")",
                                known.join(", ")
                            ),
                        )
                    })
                };
                let mut joints: Vec<LayoutJoint> = Vec::with_capacity(self.joint.len());
                for spec in &self.joint {
                    let name = &spec.name;
                    if joints.iter().any(|j| &j.name == name) {
                        return Err(invalid(format!("joint {name}"), "two joints have this name"));
                    }
                    let [held, reference] = &spec.between;
                    if held == WORLD {
                        return Err(invalid(
                            format!("joint {name}: between"),
                            "the first is the held body, not the world (write [\"body\", \"world\"])",
                        ));
                    }
                    let body = index_of(name, held)?;
                    let reference = if reference == WORLD {
                        None
                    } else {
                        Some(index_of(name, reference)?)
                    };
                    if reference == Some(body) {
                        return Err(invalid(
                            format!("joint {name}: between"),
                            format!("joins {held} to itself"),
                        ));
                    }
                    joints.push(LayoutJoint {
                        name: name.clone(),
                        body,
                        reference,
                        formulation: spec.formulation,
                        geometry: spec.geometry.clone(),
                    });
                }
                Ok(Layout {
                    bodies,
                    joints,
                    named: true,
                })
            }
        }
    }

    /// The system in algebra `A` and its initial state, projected onto the joints; an error if the joints
    /// cannot all hold there or their reactions cannot be solved for.
    pub fn system<A: FileAlgebra>(&self) -> Result<SceneSystem<A>, SceneFileError> {
        let layout = self.layout()?;
        let mut system = Mechanism::<A>::new();
        let mut states = Vec::with_capacity(layout.bodies.len());
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
        for joint in &layout.joints {
            let constraint = ConstraintSpec {
                formulation: joint.formulation,
                geometry: joint.geometry.clone(),
            }
            .constraint::<A>(joint.name.clone())?;
            let reference = joint.reference.map_or(Reference::World, |r| Reference::Body(ids[r]));
            system.add_joint(ids[joint.body], reference, constraint)?;
        }
        system.set_stabilisation(self.stabilisation()?)?;
        // Onto the joints (theory §10); joints that cannot hold together are an error naming them.
        let mut initial = states;
        system.project(0.0, &mut initial)?;
        // A rank-deficient or inconsistent reaction solve fails here, with the joints' names.
        system.rates_at(0.0, &initial)?;
        Ok(SceneSystem { initial, system })
    }

    /// Runs the scene in algebra `A`: one body without joints as a free body (where every integrator,
    /// splittings included, applies), otherwise as the mechanism.
    pub fn simulate<A: FileAlgebra>(&self) -> Result<Simulation<A>, SceneFileError> {
        let SceneSystem { system, initial } = self.system::<A>()?;
        let schedule = self.schedule()?;
        let failed = |message: String| SceneFileError::Run {
            algebra: A::NAME,
            message,
        };
        let integrator = Integrator::from(self.integrator);
        let layout = self.layout()?;
        match (&layout.bodies[..], layout.joints.is_empty()) {
            ([only], true) => {
                let mut free = FreeBody::<A>::new(only.spec.body()?);
                for (index, force) in only.forces.iter().enumerate() {
                    free = free.with_force(force.force(index + 1)?);
                }
                simulate(&free, &initial, integrator, &schedule).map_err(|e| failed(e.to_string()))
            }
            _ => simulate(&system, &initial, integrator, &schedule).map_err(|e| failed(e.to_string())),
        }
    }

    /// Whether every force has a potential, so the energy is conserved and its change is drift.
    pub fn conservative(&self) -> Result<bool, SceneFileError> {
        Ok(self
            .layout()?
            .bodies
            .iter()
            .all(|b| b.forces.iter().all(ForceSpec::conservative)))
    }
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
