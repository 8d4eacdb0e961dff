//! Rigid transforms built from the algebra's products (`docs/theory.md` §2): rotors, translators, poses and
//! normalisation, written once for both algebras.

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use crate::algebra::{Algebra, MotorCoordinates, ScrewCoordinates};

/// The identity motor `1`.
pub fn identity<A: Algebra>() -> A::Motor {
    A::motor(MotorCoordinates {
        scalar: 1.0,
        ..MotorCoordinates::default()
    })
}

/// The rotor `cos(θ/2) − sin(θ/2) n̂I₃` rotating by +θ about the unit axis n̂ (theory §2; `n̂I₃ = Σ nᵢlᵢ`).
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

/// The translator `T(c) = 1 − ½ Σ cᵢ tᵢ` (theory §2).
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

/// The position and orientation of a motor: the image of the origin (theory §2), and the rotor part
/// (its scalar and lᵢ coefficients; the N-terms never touch them) as a unit quaternion.
///
/// The image of the origin comes from the motor's coordinates, `c = −2(s t + p l − l⨯t) / (s² + |l|²)`
/// (the translation of `T(c) R`, divided by the sandwich's scale `⟨R~R⟩₀`), not from a sandwich of a point:
/// one formula for both algebras, 15 multiplies against a motor sandwich of a point and a division.
/// `tests::pose_is_the_image_of_the_origin` checks it against the sandwich.
pub fn pose<A: Algebra>(motor: A::Motor) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let c = A::motor_coordinates(motor);
    let rotation = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(c.scalar, -c.l.x, -c.l.y, -c.l.z));
    (origin_image(&c), rotation)
}

/// The position alone (the first part of [`pose`]), without building the rotation: what the step's check of the
/// distance from the origin reads for every body at every step.
pub(crate) fn position_of<A: Algebra>(motor: A::Motor) -> Vector3<f64> {
    origin_image(&A::motor_coordinates(motor))
}

/// `c = −2(s t + p l − l⨯t) / (s² + |l|²)`, see [`pose`].
fn origin_image(c: &MotorCoordinates) -> Vector3<f64> {
    let scale = c.scalar * c.scalar + c.l.norm_squared();
    (c.scalar * c.t + c.pseudoscalar * c.l - c.l.cross(&c.t)) * (-2.0 / scale)
}

/// The rigid map of a motor on screw coordinates (theory §1.4): a screw `(l, t)` of the body frame is
/// `(Ql, Qt + c⨯Ql)` in the world frame, with Q the rotation and c the position of the motor ([`pose`]); a
/// force f through a has `l = f`, `t = a⨯f` and moves with its line. This is the sandwich `RX~R` on
/// span{lᵢ, tᵢ}, divided by the sandwich's scale `⟨R~R⟩₀` (so a motor normalised to round-off does not scale
/// screws), at 24 multiplies once the 3×3 rotation is built. It is hand-written because the kinematics need Q
/// and c themselves (points, directions and velocities of body points, `constraints::kinematics`), which the
/// generated 6×6 map of the sandwich (`moved_line_map`, 27 multiplies per screw) does not expose. Moving screws
/// alone, the generated kernels are as fast or faster (`cargo bench -p dynamics --bench screw_frames`,
/// 2026-11-26, PGA: one screw 34 ns through a frame, 22 ns fused, 22 ns through the map; eight screws 96, 165
/// and 88 ns). `constraints::kinematics::tests` checks it against the sandwich.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScrewFrame {
    /// Q, the rotation from body axes to world axes (see [`ScrewFrame::of`]).
    pub rotation: Rotation3<f64>,
    /// c: the image of the body origin (the centre of mass), world frame (m).
    pub position: Vector3<f64>,
}

impl ScrewFrame {
    /// The frame of a motor. Q is the rotation matrix of the quaternion `(s, −l)` divided by its squared norm
    /// `⟨R~R⟩₀`, as the sandwich's linear part is (no square root, and no normalisation error that a round
    /// trip body ↔ world would accumulate step after step).
    ///
    /// ```
    /// use dynamics::motor::{from_pose, ScrewFrame};
    /// use dynamics::{Pga, ScrewCoordinates};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let (centre, turn) = (Vector3::new(1.0, 2.0, 0.0), UnitQuaternion::from_scaled_axis(Vector3::z() * 0.5));
    /// let frame = ScrewFrame::of::<Pga>(from_pose::<Pga>(centre, &turn));
    /// assert!((frame.position - centre).norm() < 1e-15); // m
    /// assert!((frame.rotation.matrix() - turn.to_rotation_matrix().matrix()).norm() < 1e-15);
    /// // A 1 N force along body x through the centre of mass, in the world: along turn·x, through the centre.
    /// let world = frame.to_world(&ScrewCoordinates { l: Vector3::x(), t: Vector3::zeros() });
    /// assert!((world.l - turn * Vector3::x()).norm() < 1e-15); // N
    /// assert!((world.t - centre.cross(&world.l)).norm() < 1e-15); // its moment about the origin, N m
    /// ```
    pub fn of<A: Algebra>(motor: A::Motor) -> Self {
        let c = A::motor_coordinates(motor);
        let (w, x, y, z) = (c.scalar, -c.l.x, -c.l.y, -c.l.z);
        let scale = w * w + x * x + y * y + z * z;
        let (ww, xx, yy, zz) = (w * w, x * x, y * y, z * z);
        let (xy, xz, yz, wx, wy, wz) = (x * y, x * z, y * z, w * x, w * y, w * z);
        // One division, then products (nine divisions cost more than the rest of the frame).
        let inverse = 1.0 / scale;
        let twice = 2.0 * inverse;
        let matrix = Matrix3::new(
            (ww + xx - yy - zz) * inverse,
            (xy - wz) * twice,
            (xz + wy) * twice,
            (xy + wz) * twice,
            (ww - xx + yy - zz) * inverse,
            (yz - wx) * twice,
            (xz - wy) * twice,
            (yz + wx) * twice,
            (ww - xx - yy + zz) * inverse,
        );
        ScrewFrame {
            rotation: Rotation3::from_matrix_unchecked(matrix),
            position: origin_image(&c),
        }
    }

    /// The frame of body b seen from body a (`~R_a R_b`, b → a), from the two frames: rotation `Q_aᵀQ_b`, position
    /// `Q_aᵀ(c_b − c_a)` (36 multiplies, against a motor product and a frame extraction).
    ///
    /// The same as the frame of the relative motor `~R_a R_b`:
    ///
    /// ```
    /// use dynamics::motor::{from_pose, ScrewFrame};
    /// use dynamics::{Algebra, Pga};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let turn = |x: f64, y: f64, z: f64| UnitQuaternion::from_scaled_axis(Vector3::new(x, y, z));
    /// let a = from_pose::<Pga>(Vector3::new(1.0, 0.0, 0.0), &turn(0.0, 0.0, 1.0));
    /// let b = from_pose::<Pga>(Vector3::new(0.0, 2.0, 1.0), &turn(0.3, -0.2, 0.1));
    /// let seen_from_a = ScrewFrame::relative(&ScrewFrame::of::<Pga>(a), &ScrewFrame::of::<Pga>(b));
    /// let direct = ScrewFrame::of::<Pga>(Pga::compose(Pga::reverse(a), b));
    /// assert!((seen_from_a.position - direct.position).norm() < 1e-15); // b's centre in a's frame, m
    /// assert!((seen_from_a.rotation.matrix() - direct.rotation.matrix()).norm() < 1e-15);
    /// ```
    pub fn relative(reference: &ScrewFrame, body: &ScrewFrame) -> Self {
        let to_reference = reference.rotation.matrix();
        ScrewFrame {
            rotation: Rotation3::from_matrix_unchecked(to_reference.tr_mul(body.rotation.matrix())),
            position: to_reference.tr_mul(&(body.position - reference.position)),
        }
    }

    /// `(l, t) ↦ (Qᵀl, Qᵀ(t − c⨯l))`: the body coordinates of a world screw.
    #[inline]
    pub fn to_body(&self, world: &ScrewCoordinates) -> ScrewCoordinates {
        ScrewCoordinates {
            l: self.rotation.inverse_transform_vector(&world.l),
            t: self
                .rotation
                .inverse_transform_vector(&(world.t - self.position.cross(&world.l))),
        }
    }

    /// `(l, t) ↦ (Qᵀl, Qᵀt)`: a screw about the centre of mass in world axes seen in body axes (no translation).
    #[inline]
    pub(crate) fn turn_to_body(&self, central: &ScrewCoordinates) -> ScrewCoordinates {
        ScrewCoordinates {
            l: self.rotation.inverse_transform_vector(&central.l),
            t: self.rotation.inverse_transform_vector(&central.t),
        }
    }

    /// `(l, t) ↦ (Ql, Qt)`: a body screw in world axes, its moment still about the centre of mass.
    #[inline]
    pub(crate) fn turn_to_world(&self, body: &ScrewCoordinates) -> ScrewCoordinates {
        ScrewCoordinates {
            l: self.rotation * body.l,
            t: self.rotation * body.t,
        }
    }

    /// `(l, t) ↦ (Ql, Qt + c⨯Ql)`: the world coordinates of a body screw.
    #[inline]
    pub fn to_world(&self, body: &ScrewCoordinates) -> ScrewCoordinates {
        let l = self.rotation * body.l;
        ScrewCoordinates {
            l,
            t: self.rotation * body.t + self.position.cross(&l),
        }
    }
}

/// The central view of a body screw: its parts turned to world axes, the moment kept about the centre of mass,
/// `(l, t) ↦ (Ql, Qt)` (docs/dynamics.md, "Momentum about the centre of mass").
pub(crate) fn central_from_body<A: Algebra>(motor: A::Motor, body: A::Screw) -> A::Screw {
    A::screw(ScrewFrame::of::<A>(motor).turn_to_world(&A::screw_coordinates(body)))
}

/// The body view of a central screw, `(l, t) ↦ (Qᵀl, Qᵀt)`.
pub(crate) fn body_from_central<A: Algebra>(motor: A::Motor, central: A::Screw) -> A::Screw {
    A::screw(ScrewFrame::of::<A>(motor).turn_to_body(&A::screw_coordinates(central)))
}

/// A world wrench (moment about the world origin) as a central one, `(f, m_O) ↦ (f, m_O − c × f)`: the rate of
/// the momentum about the centre of mass (docs/dynamics.md, "Momentum about the centre of mass").
pub(crate) fn central_wrench<A: Algebra>(motor: A::Motor, world: A::Screw) -> A::Screw {
    let centre = ScrewFrame::of::<A>(motor).position;
    let w = A::screw_coordinates(world);
    A::screw(ScrewCoordinates {
        l: w.l,
        t: w.t - centre.cross(&w.l),
    })
}

/// Normalises: with `K = R~R = a + bΠ`, `R ← (1 − ½(b/a)Π) R / √a` (theory §2). Both algebras store motors in
/// the motor subalgebra (theory §1.4), so drift never leaves it.
pub fn normalise<A: Algebra>(motor: A::Motor) -> A::Motor {
    let norm = A::motor_coordinates(A::compose(motor, A::reverse(motor)));
    let (a, b) = (norm.scalar, norm.pseudoscalar);
    let correction = A::motor(MotorCoordinates {
        scalar: 1.0,
        pseudoscalar: -0.5 * b / a,
        ..MotorCoordinates::default()
    });
    A::compose(correction, motor) * (1.0 / a.sqrt())
}

/// How far a motor is from unit norm: `|R~R − 1|` over the scalar and Π parts.
pub fn norm_error<A: Algebra>(motor: A::Motor) -> f64 {
    let norm = A::motor_coordinates(A::compose(motor, A::reverse(motor)));
    (norm.scalar - 1.0).abs().max(norm.pseudoscalar.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cga, Pga};

    /// The coordinate formula of [`pose`] is the image of the origin under the sandwich, for unit and for
    /// scaled motors, in both algebras.
    fn pose_is_the_image_of_the_origin<A: Algebra>() {
        for (k, scale) in [1.0, 1.0 + 1e-9, 0.5].into_iter().enumerate() {
            let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -1.1, 0.7) * (k as f64 + 1.0));
            let position = Vector3::new(1.5, -2.0, 0.25) * (k as f64 + 0.5);
            let motor = from_pose::<A>(position, &rotation) * scale;
            let sandwich = A::position(A::transform_point(motor, A::point(Vector3::zeros())));
            let (ours, orientation) = pose::<A>(motor);
            assert!((ours - sandwich).norm() < 1e-13, "{} {ours} vs {sandwich}", A::NAME);
            assert!((ours - position).norm() < 1e-13);
            assert!(orientation.angle_to(&rotation) < 1e-15);
            assert_eq!(position_of::<A>(motor), ours);
        }
    }

    #[test]
    fn pose_is_the_image_of_the_origin_in_both_algebras() {
        pose_is_the_image_of_the_origin::<Pga>();
        pose_is_the_image_of_the_origin::<Cga>();
    }
}
