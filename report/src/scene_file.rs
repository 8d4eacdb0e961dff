//! Scenes described in a TOML file (README, "Scene files"): one body with its shape or inertia, initial pose
//! and velocities, forces, constraints, algebra, integrator, step and duration, run without writing Rust
//! (`--scene-file`; the run and its output are in [`crate::scene_job`]).
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
use dynamics::simulate::{simulate, Sample, Schedule, SimulationError, SAMPLE_INTERVAL};
use dynamics::{Algebra, Body, BodyError, Cga, Force, FreeBody, Mechanism, MechanismError, Pga, Simulation, State};
use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};
use scenarios::Formulation;
use serde::Deserialize;

use crate::cli::{IntegratorName, StabilisationName};
use crate::sweep::AlgebraKind;

/// Why a scene file cannot run, or its run failed.
#[derive(Debug, thiserror::Error)]
pub enum SceneFileError {
    #[error("cannot read the file: {0}")]
    Read(std::io::Error),
    /// Not TOML, or not this format (unknown key or kind, missing field, wrong type); the message gives
    /// the line and column.
    #[error("{0}")]
    Format(#[from] toml::de::Error),
    #[error("{what}: {reason}")]
    Invalid { what: String, reason: String },
    #[error("body: {0}")]
    Body(#[from] BodyError),
    #[error("dt, duration, sample_interval: {0}")]
    Schedule(SimulationError),
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    #[error(transparent)]
    Mechanism(#[from] MechanismError),
    #[error(
        "constraint {name}: pinning needs a {object}, which {algebra} does not have; write \
         formulation = \"virtual_power\", or algebra = \"cga\""
    )]
    NotExpressible {
        name: String,
        object: &'static str,
        algebra: &'static str,
    },
    #[error("the {algebra} run failed: {message}")]
    Run { algebra: &'static str, message: String },
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
    Pga,
    Cga,
    /// Both, to compare them.
    #[default]
    Both,
}

impl AlgebraChoice {
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
    #[serde(default)]
    pub algebra: AlgebraChoice,
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
    pub stabilisation: StabilisationName,
    /// Gains for `stabilisation = "baumgarte"` (default α = β = 10, as on the command line).
    #[serde(default)]
    pub baumgarte: Option<BaumgarteGains>,
    pub body: BodySpec,
    #[serde(default)]
    pub initial: InitialSpec,
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
    #[serde(default)]
    pub constraints: Vec<ConstraintSpec>,
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
pub struct BaumgarteGains {
    pub alpha: f64,
    pub beta: f64,
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
    pub principal_moments: Option<[f64; 3]>,
}

/// A solid of uniform density, centred on its centre of mass; lengths in metres.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
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

/// The state at t = 0. Constrained scenes are projected onto their constraints first (SPEC §10), so the
/// values need to satisfy them only approximately.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Centre of mass, world (m).
    #[serde(default)]
    pub position: [f64; 3],
    #[serde(default)]
    pub orientation: OrientationSpec,
    /// Angular velocity in body axes (rad/s).
    #[serde(default)]
    pub body_angular_velocity: [f64; 3],
    /// Centre-of-mass velocity, world (m/s).
    #[serde(default)]
    pub velocity: [f64; 3],
}

/// Body → world rotation: `axis` with `angle` (rad) or `degrees`, or a `quaternion` [w, x, y, z]
/// (normalised here); none of them is the identity.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientationSpec {
    pub axis: Option<[f64; 3]>,
    pub angle: Option<f64>,
    pub degrees: Option<f64>,
    pub quaternion: Option<[f64; 4]>,
}

/// An external force on the body (world frame).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ForceSpec {
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

/// How a constraint is written (SPEC §6 and §7–§9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FormulationName {
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
        body_point: [f64; 3],
        world_point: [f64; 3],
    },
    /// The body turns only about the world axis through the world point, where the body point stays
    /// (rank 5).
    Hinge(AxisJoint),
    /// The body point slides along and turns about the world axis (rank 4).
    Cylindrical(AxisJoint),
    /// The body point stays on the world plane `normal · x = offset` (rank 1).
    PointOnPlane {
        body_point: [f64; 3],
        normal: [f64; 3],
        offset: f64,
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
pub struct AxisJoint {
    pub body_point: [f64; 3],
    pub body_axis: [f64; 3],
    pub world_point: [f64; 3],
    pub world_axis: [f64; 3],
}

/// The values as a vector, if all are finite.
fn finite(what: &str, values: [f64; 3]) -> Result<Vector3<f64>, SceneFileError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(Vector3::from(values))
    } else {
        Err(invalid(what, format!("{values:?} is not finite")))
    }
}

/// The unit vector along finite, non-zero values.
fn direction(what: &str, values: [f64; 3]) -> Result<Unit<Vector3<f64>>, SceneFileError> {
    Unit::try_new(finite(what, values)?, 0.0).ok_or_else(|| invalid(what, "has no direction (zero vector)"))
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
            (None, None, None, Some([w, x, y, z])) => {
                let q = Quaternion::new(w, x, y, z);
                if q.coords.iter().all(|c| c.is_finite()) && q.norm() > 0.0 {
                    Ok(UnitQuaternion::from_quaternion(q))
                } else {
                    Err(invalid(
                        WHAT,
                        format!("quaternion {:?} is zero or not finite", [w, x, y, z]),
                    ))
                }
            }
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
/// needs (SPEC §9, §13).
pub trait FileAlgebra: PinningAlgebra {
    fn point_on_sphere_pin(
        name: String,
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
        radius: f64,
    ) -> Option<Arc<dyn Constraint<Self>>>;
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

/// A constraint's geometry with every value checked: finite points, unit axes and normals, positive radii.
#[derive(Clone, Copy, Debug)]
pub enum CheckedGeometry {
    Ball {
        body_point: Vector3<f64>,
        world_point: Vector3<f64>,
    },
    Axis {
        hinge: bool,
        body: (Vector3<f64>, Vector3<f64>),
        world: (Vector3<f64>, Vector3<f64>),
    },
    Plane {
        body_point: Vector3<f64>,
        normal: Vector3<f64>,
        offset: f64,
    },
    Round {
        body_point: Vector3<f64>,
        centre: Vector3<f64>,
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
            Geometry::PointOnPlane { .. } => "point on plane",
            Geometry::PointOnSphere { .. } => "point on sphere",
            Geometry::PointOnCircle { .. } => "point on circle",
        }
    }

    fn checked(&self, name: &str) -> Result<CheckedGeometry, SceneFileError> {
        let what = |field: &str| format!("constraint {name}: {field}");
        let point = |field: &str, values| finite(&what(field), values);
        let unit = |field: &str, values| direction(&what(field), values).map(Unit::into_inner);
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
                hinge: matches!(self, Geometry::Hinge(_)),
                body: (
                    point("body_point", joint.body_point)?,
                    unit("body_axis", joint.body_axis)?,
                ),
                world: (
                    point("world_point", joint.world_point)?,
                    unit("world_axis", joint.world_axis)?,
                ),
            },
            Geometry::PointOnPlane {
                body_point,
                normal,
                offset,
            } => {
                let length = finite(&what("normal"), *normal)?.norm();
                if !offset.is_finite() {
                    return Err(invalid(what("offset"), format!("{offset} is not finite")));
                }
                CheckedGeometry::Plane {
                    body_point: point("body_point", *body_point)?,
                    normal: unit("normal", *normal)?,
                    offset: offset / length,
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
            CheckedGeometry::Axis { hinge, body, world } => match (hinge, pinned) {
                (true, true) => Arc::new(pinning::hinge::<A>(name, body, world)?),
                (true, false) => Arc::new(VirtualPower::hinge(name, body, world)?),
                (false, true) => Arc::new(pinning::line::<A>(name, body, world)),
                (false, false) => Arc::new(VirtualPower::cylindrical(name, body, world)?),
            },
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
    /// How far a sample is from satisfying the constraint (m): the body point's distance from where it
    /// must be; for axis joints also that of the point 1 m further along the body axis.
    pub fn violation(&self, sample: &Sample) -> f64 {
        let world = |body_point: Vector3<f64>| sample.position + sample.orientation * body_point;
        match *self {
            CheckedGeometry::Ball {
                body_point,
                world_point,
            } => (world(body_point) - world_point).norm(),
            CheckedGeometry::Axis {
                hinge,
                body,
                world: line,
            } => {
                // Distance of a world point from the world axis.
                let off_axis = |p: Vector3<f64>| (p - line.0).cross(&line.1).norm();
                let along_axis = off_axis(world(body.0 + body.1));
                let at_point = if hinge {
                    (world(body.0) - line.0).norm()
                } else {
                    off_axis(world(body.0))
                };
                at_point.max(along_axis)
            }
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

/// A system ready to run in one algebra, and its initial state on the constraints.
pub struct SceneSystem<A: Algebra> {
    pub system: Mechanism<A>,
    pub initial: State<A>,
}

/// At most this many projections of a scene file's initial state (each of at most two Gauss–Newton steps).
const INITIAL_PROJECTIONS: usize = 20;

/// The initial state on the constraints (SPEC §10). A file's state may start centimetres off them, further
/// than one projection's two Gauss–Newton steps reach, so it is projected again while that still helps.
fn project_initial<A: Algebra>(system: &Mechanism<A>, state: &State<A>) -> Result<State<A>, SceneFileError> {
    let mut state = [*state];
    system.project(0.0, &mut state)?;
    let mut residual = system.violation(0.0, &state)?.position;
    for _ in 1..INITIAL_PROJECTIONS {
        let mut next = state;
        system.project(0.0, &mut next)?;
        let next_residual = system.violation(0.0, &next)?.position;
        if next_residual >= residual {
            break;
        }
        (state, residual) = (next, next_residual);
    }
    Ok(state[0])
}

impl SceneFile {
    /// Reads and checks a scene file.
    pub fn load(path: &Path) -> Result<SceneFile, SceneFileError> {
        let text = std::fs::read_to_string(path).map_err(SceneFileError::Read)?;
        SceneFile::parse(&text)
    }

    /// Parses a scene file and checks that it can run: the body, the timing, the integrator and, in every
    /// requested algebra, the forces, constraints, stabilisation and the projection of the initial state.
    pub fn parse(text: &str) -> Result<SceneFile, SceneFileError> {
        let scene: SceneFile = toml::from_str(text)?;
        scene.schedule()?;
        if !scene.constraints.is_empty() && matches!(Integrator::from(scene.integrator), Integrator::Splitting(_)) {
            return Err(invalid(
                "integrator",
                format!(
                    "{} is a splitting method, which runs bodies without constraints only",
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

    pub fn schedule(&self) -> Result<Schedule, SceneFileError> {
        Schedule::with_sample_interval(self.dt, self.duration, self.sample_interval).map_err(SceneFileError::Schedule)
    }

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

    /// The name of constraint `index` (from 1) in messages: "1 (hinge)".
    fn constraint_name(index: usize, constraint: &ConstraintSpec) -> String {
        format!("{index} ({})", constraint.geometry.kind())
    }

    /// The system in algebra `A` and its initial state, projected onto the constraints.
    pub fn system<A: FileAlgebra>(&self) -> Result<SceneSystem<A>, SceneFileError> {
        let body = self.body.body()?;
        let mut system = Mechanism::<A>::single(body);
        for (index, force) in self.forces.iter().enumerate() {
            system = system.with_force(force.force(index + 1)?);
        }
        for (index, constraint) in self.constraints.iter().enumerate() {
            system =
                system.with_constraint(constraint.constraint::<A>(Self::constraint_name(index + 1, constraint))?)?;
        }
        let system = system.with_stabilisation(self.stabilisation()?)?;
        let initial = &self.initial;
        let state = State::new(
            &body,
            finite("initial.position", initial.position)?,
            &initial.orientation.rotation()?,
            finite("initial.body_angular_velocity", initial.body_angular_velocity)?,
            finite("initial.velocity", initial.velocity)?,
        );
        Ok(SceneSystem {
            initial: project_initial(&system, &state)?,
            system,
        })
    }

    /// Runs the scene in algebra `A`: a body without constraints as a free body (where every integrator,
    /// splittings included, applies), otherwise with the constraints.
    pub fn simulate<A: FileAlgebra>(&self) -> Result<Simulation<A>, SceneFileError> {
        let SceneSystem { system, initial } = self.system::<A>()?;
        let schedule = self.schedule()?;
        let failed = |message: String| SceneFileError::Run {
            algebra: A::NAME,
            message,
        };
        let integrator = Integrator::from(self.integrator);
        if self.constraints.is_empty() {
            let mut free = FreeBody::<A>::new(self.body.body()?);
            for (index, force) in self.forces.iter().enumerate() {
                free = free.with_force(force.force(index + 1)?);
            }
            simulate(&free, &[initial], integrator, &schedule).map_err(|e| failed(e.to_string()))
        } else {
            simulate(&system, &[initial], integrator, &schedule).map_err(|e| failed(e.to_string()))
        }
    }

    /// The checked geometry of every constraint, to measure violations with.
    pub fn constraint_geometries(&self) -> Result<Vec<CheckedGeometry>, SceneFileError> {
        self.constraints
            .iter()
            .enumerate()
            .map(|(index, c)| c.geometry.checked(&Self::constraint_name(index + 1, c)))
            .collect()
    }

    /// Whether every force has a potential, so the energy is conserved and its change is drift.
    pub fn conservative(&self) -> bool {
        self.forces.iter().all(ForceSpec::conservative)
    }
}
