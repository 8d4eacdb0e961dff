//! Interop with nalgebra, for either algebra: motors ↔ [`Isometry3`], points ↔ [`Point3`], screws ↔ pairs of
//! [`Vector3`].
//!
//! Conventions (`docs/theory.md` §2–§3): a motor `T(c) R_rot` is the isometry `x ↦ q x + c` with the quaternion
//! `q = (w, x, y, z)` of `R_rot = w − (x, y, z)·l`; a screw `Σ aᵢlᵢ + bᵢtᵢ` is the pair `(a, b)`, which is
//! `(ω, v)` for a velocity, `(p, L)` for a momentum and `(f, τ)` for a wrench.

use nalgebra::{Isometry3, Point3, Translation3, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::motor;

/// Why a multivector has no nalgebra counterpart.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConversionError {
    /// The motor's rotor part (scalar and lᵢ) is zero or not finite, so it does not normalise to a rigid motion.
    #[error("the motor's rotor part has squared norm {0}, so it is not a rigid motion")]
    NotARigidMotion(f64),
    /// The point has zero or non-finite weight (a direction or a degenerate element, not a Euclidean point).
    #[error("the point has no finite position (weight zero or not finite)")]
    NotAPoint,
}

/// The isometry of a motor, after normalising it onto the unit motors (theory §2).
pub fn motor_to_isometry<A: Algebra>(motor: A::Motor) -> Result<Isometry3<f64>, ConversionError> {
    let c = A::motor_coordinates(motor);
    let rotor_norm_squared = c.scalar * c.scalar + c.l.norm_squared();
    let finite = [c.scalar, c.pseudoscalar]
        .iter()
        .chain(c.l.iter())
        .chain(c.t.iter())
        .all(|x| x.is_finite());
    if !(finite && rotor_norm_squared > 0.0) {
        return Err(ConversionError::NotARigidMotion(rotor_norm_squared));
    }
    let (position, rotation) = motor::pose::<A>(motor::normalise::<A>(motor));
    Ok(Isometry3::from_parts(Translation3::from(position), rotation))
}

/// The motor `T(c) R_rot` of an isometry.
pub fn isometry_to_motor<A: Algebra>(isometry: &Isometry3<f64>) -> A::Motor {
    motor::from_pose::<A>(isometry.translation.vector, &isometry.rotation)
}

/// The position of a point.
pub fn point_to_point3<A: Algebra>(point: A::Point) -> Result<Point3<f64>, ConversionError> {
    let position = A::position(point);
    if position.iter().all(|x| x.is_finite()) {
        Ok(Point3::from(position))
    } else {
        Err(ConversionError::NotAPoint)
    }
}

/// The point at a position.
pub fn point3_to_point<A: Algebra>(point: &Point3<f64>) -> A::Point {
    A::point(point.coords)
}

/// The coordinates `(a, b)` of a screw `Σ aᵢlᵢ + bᵢtᵢ`.
pub fn screw_to_vectors<A: Algebra>(screw: A::Screw) -> (Vector3<f64>, Vector3<f64>) {
    let c = A::screw_coordinates(screw);
    (c.l, c.t)
}

/// The screw `Σ aᵢlᵢ + bᵢtᵢ` from `(a, b)`.
pub fn vectors_to_screw<A: Algebra>(l: Vector3<f64>, t: Vector3<f64>) -> A::Screw {
    A::screw(ScrewCoordinates { l, t })
}

/// `v`'s direction and length, `None` for a zero or non-finite `v`. The length is taken through the largest
/// coordinate, so that an axis or normal of 1e200 (whose squared norm overflows) still has its direction.
pub(crate) fn direction_and_length(v: Vector3<f64>) -> Option<(Vector3<f64>, f64)> {
    let largest = v.amax(); // which skips a NaN coordinate
    if !(largest > 0.0 && v.iter().all(|x| x.is_finite())) {
        return None;
    }
    let scaled = v / largest;
    let scaled_length = scaled.norm();
    Some((scaled / scaled_length, largest * scaled_length))
}
