//! The bodies checked: their mass properties, orientations and forces.

use dynamics::{Algebra, Body, BodyError, Force};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use super::values::{direction, finite, rescaled};
use crate::error::{invalid, SceneFileError};
use crate::syntax::bodies::{BodySpec, ForceSpec, OrientationSpec, Shape};

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
    pub(crate) fn force<A: Algebra>(&self, index: usize) -> Result<Force<A>, SceneFileError> {
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
