//! The bodies checked: their mass properties, initial states ([`InitialState`]) and forces ([`BodyForce`]), and any
//! orientation a file gives.

use dynamics::{Algebra, Body, BodyError, Force, State};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use super::values::{bounded_vector, direction, finite, rescaled};
use crate::error::{invalid, SceneFileError};
use crate::syntax::bodies::{BodySpec, ForceSpec, InitialSpec, OrientationSpec, Shape};

/// A body's pose: its centre of mass (world) and its orientation body → world.
pub type Pose = (Vector3<f64>, UnitQuaternion<f64>);

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
    /// The body's mass properties, from its shape or its principal moments.
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
    /// The rotation, or an error under `what` (the key) naming what is wrong: keys given in another combination, a
    /// non-finite angle, a zero axis or quaternion.
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
    /// The force checked finite (and within 1e50), messages naming it `force {index}` (1-based).
    pub(crate) fn checked(&self, index: usize) -> Result<BodyForce, SceneFileError> {
        let what = |field: &str| format!("force {index}: {field}");
        Ok(match *self {
            ForceSpec::Gravity { acceleration } => BodyForce::Gravity {
                acceleration: bounded_vector(&what("acceleration"), acceleration)?,
            },
            ForceSpec::Force { force, point } => BodyForce::Line {
                force: bounded_vector(&what("force"), force)?,
                point: finite(&what("point"), point)?,
            },
            ForceSpec::Couple { moment } => BodyForce::Couple {
                moment: bounded_vector(&what("moment"), moment)?,
            },
        })
    }
}

/// An external force on a body, checked finite (world frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BodyForce {
    /// Uniform gravity at the centre of mass.
    Gravity {
        /// m/s².
        acceleration: Vector3<f64>,
    },
    /// A constant force along a fixed world line.
    Line {
        /// N.
        force: Vector3<f64>,
        /// A point of its line (m).
        point: Vector3<f64>,
    },
    /// A constant couple.
    Couple {
        /// N m.
        moment: Vector3<f64>,
    },
}

impl BodyForce {
    /// The force in algebra `A`.
    pub fn force<A: Algebra>(self) -> Force<A> {
        match self {
            BodyForce::Gravity { acceleration } => Force::Gravity { acceleration },
            BodyForce::Line { force, point } => Force::Line { force, point },
            BodyForce::Couple { moment } => Force::Couple { moment },
        }
    }

    /// What it is, for the summary: "gravity", "constant force" or "couple".
    pub fn kind(self) -> &'static str {
        match self {
            BodyForce::Gravity { .. } => "gravity",
            BodyForce::Line { .. } => "constant force",
            BodyForce::Couple { .. } => "couple",
        }
    }

    /// Whether the force has a potential, so that the energy is conserved under it.
    pub fn conservative(self) -> bool {
        matches!(self, BodyForce::Gravity { .. })
    }
}

/// A body's state at t = 0, checked: every value finite, the orientation a rotation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialState {
    /// Centre of mass, world (m).
    pub position: Vector3<f64>,
    /// Body → world.
    pub orientation: UnitQuaternion<f64>,
    /// Angular velocity in body axes (rad/s).
    pub body_angular_velocity: Vector3<f64>,
    /// Centre-of-mass velocity, world (m/s).
    pub velocity: Vector3<f64>,
}

impl InitialState {
    /// The state of `body` in algebra `A`.
    pub fn state<A: Algebra>(&self, body: &Body) -> State<A> {
        State::new(
            body,
            self.position,
            &self.orientation,
            self.body_angular_velocity,
            self.velocity,
        )
    }

    /// The body's pose.
    pub fn pose(&self) -> Pose {
        (self.position, self.orientation)
    }
}

impl InitialSpec {
    /// The state checked, messages naming its keys after `prefix` (the body's, "body NAME: ", or none).
    pub(crate) fn checked(&self, prefix: &str) -> Result<InitialState, SceneFileError> {
        let at = |key: &str| format!("{prefix}initial.{key}");
        Ok(InitialState {
            position: finite(&at("position"), self.position)?,
            orientation: self.orientation.rotation_of(&at("orientation"))?,
            body_angular_velocity: bounded_vector(&at("body_angular_velocity"), self.body_angular_velocity)?,
            velocity: bounded_vector(&at("velocity"), self.velocity)?,
        })
    }
}
