//! Rigid transforms built from the algebra's products (SPEC §2): rotors, translators, poses and
//! normalisation, written once for both algebras.

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::{Algebra, MotorCoordinates};

/// The identity motor `1`.
pub fn identity<A: Algebra>() -> A::Motor {
    A::motor(MotorCoordinates {
        scalar: 1.0,
        ..MotorCoordinates::default()
    })
}

/// The rotor `cos(θ/2) − sin(θ/2) n̂I₃` rotating by +θ about the unit axis n̂ (SPEC §2; `n̂I₃ = Σ nᵢlᵢ`).
/// A zero axis gives the identity.
pub fn rotor<A: Algebra>(axis: Vector3<f64>, angle: f64) -> A::Motor {
    let axis = axis.try_normalize(0.0).unwrap_or_else(Vector3::zeros);
    let (sin, cos) = (0.5 * angle).sin_cos();
    A::motor(MotorCoordinates {
        scalar: cos,
        l: -sin * axis,
        ..MotorCoordinates::default()
    })
}

/// The translator `T(c) = 1 − ½ Σ cᵢ tᵢ` (SPEC §2).
pub fn translator<A: Algebra>(offset: Vector3<f64>) -> A::Motor {
    A::motor(MotorCoordinates {
        scalar: 1.0,
        t: -0.5 * offset,
        ..MotorCoordinates::default()
    })
}

/// The rotor of a unit quaternion (w, x, y, z) (body → world): `w − (x, y, z)·l`.
pub fn rotor_from_quaternion<A: Algebra>(rotation: &UnitQuaternion<f64>) -> A::Motor {
    let q = rotation.quaternion();
    A::motor(MotorCoordinates {
        scalar: q.w,
        l: -q.imag(),
        ..MotorCoordinates::default()
    })
}

/// The motor `T(position) R(rotation)` of a body at `position` with orientation `rotation`.
pub fn from_pose<A: Algebra>(position: Vector3<f64>, rotation: &UnitQuaternion<f64>) -> A::Motor {
    A::compose(translator::<A>(position), rotor_from_quaternion::<A>(rotation))
}

/// The position and orientation of a motor: the image of the origin (SPEC §2), and the rotor part
/// (its scalar and lᵢ coefficients; the N-terms never touch them) as a unit quaternion.
pub fn pose<A: Algebra>(motor: A::Motor) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let origin = A::transform_point(motor, A::point(Vector3::zeros()));
    let c = A::motor_coordinates(motor);
    let rotation = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(c.scalar, -c.l.x, -c.l.y, -c.l.z));
    (A::position(origin), rotation)
}

/// Projects onto the motor subalgebra and normalises: with `K = R~R = a + bΠ`,
/// `R ← (1 − ½(b/a)Π) R / √a` (SPEC §2). Valid for drift inside the subalgebra, which the
/// projection guarantees.
pub fn normalise<A: Algebra>(motor: A::Motor) -> A::Motor {
    let projected = A::motor(A::motor_coordinates(motor));
    let norm = A::motor_coordinates(A::compose(projected, A::reverse(projected)));
    let (a, b) = (norm.scalar, norm.pseudoscalar);
    let correction = A::motor(MotorCoordinates {
        scalar: 1.0,
        pseudoscalar: -0.5 * b / a,
        ..MotorCoordinates::default()
    });
    A::compose(correction, projected) * (1.0 / a.sqrt())
}

/// How far a motor is from unit norm: `|R~R − 1|` over the scalar and Π parts.
pub fn norm_error<A: Algebra>(motor: A::Motor) -> f64 {
    let norm = A::motor_coordinates(A::compose(motor, A::reverse(motor)));
    (norm.scalar - 1.0).abs().max(norm.pseudoscalar.abs())
}
