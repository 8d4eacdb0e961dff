//! The state of the body at one evaluation, in the forms the constraints need: the motor and its reverse
//! (to move objects between frames, `docs/theory.md` §2), the body velocity Ḃ (theory §3) and, for the force-line
//! constraints of virtual power (theory §6), world positions and velocities of body points.
//!
//! "World" is the constraint's reference frame: the world for a body held by the world, or another body's
//! frame for a joint between two bodies, whose kinematics are then the relative ones (docs/mechanisms.md §M2).

use nalgebra::{Vector3, Vector6};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::motor::ScrewFrame;

/// The body's configuration and velocity at time `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kinematics<A: Algebra> {
    /// The time of the evaluation (s).
    pub t: f64,
    /// R (body → world).
    pub motor: A::Motor,
    /// ~R (world → body).
    pub reverse: A::Motor,
    /// Ḃ = M⁻¹[~R Ω R], body frame.
    pub body_velocity: A::Screw,
    /// The coordinates `x = (ω; v)` of Ḃ (body axes).
    pub velocity: Vector6<f64>,
    /// Ḃ_w = R Ḃ ~R, world frame (theory §3).
    pub world_velocity: A::Screw,
    /// Position of the centre of mass and rotation body → world, with the motor's map on screw coordinates.
    pub frame: ScrewFrame,
    /// Angular velocity, world axes.
    pub angular_velocity: Vector3<f64>,
    /// Centre-of-mass velocity, world axes.
    pub linear_velocity: Vector3<f64>,
}

impl<A: Algebra> Kinematics<A> {
    /// The kinematics of a body with motor `motor` moving with body velocity `body_velocity`.
    ///
    /// What a constraint sees of its body: here a body at the origin spinning at 2 rad/s about world z, whose body
    /// point one metre out along its x axis (turned to world y) moves at 2 m/s along −x.
    ///
    /// ```
    /// use dynamics::constraints::Kinematics;
    /// use dynamics::{motor, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let quarter = UnitQuaternion::from_scaled_axis(Vector3::z() * std::f64::consts::FRAC_PI_2);
    /// let spin = Pga::screw(ScrewCoordinates { l: Vector3::z() * 2.0, t: Vector3::zeros() }); // body frame, rad/s
    /// let at = Kinematics::<Pga>::new(0.0, motor::from_pose::<Pga>(Vector3::zeros(), &quarter), spin);
    /// assert!((at.world_point(&Vector3::x()) - Vector3::y()).norm() < 1e-15); // m
    /// assert!((at.world_point_velocity(&Vector3::x()) + Vector3::x() * 2.0).norm() < 1e-15); // m/s
    /// ```
    #[inline]
    pub fn new(t: f64, motor: A::Motor, body_velocity: A::Screw) -> Self {
        Self::with_frame(t, motor, ScrewFrame::of::<A>(motor), body_velocity)
    }

    /// [`Kinematics::new`] with the motor's frame already computed.
    ///
    /// The kinematics a constraint's rows are evaluated at: a ball joint holding the body point `(0, 0, 1)` at the
    /// world origin, for a body hanging below it and turning about the pivot, has zero residuals.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, Kinematics, RowBuffer, VirtualPower};
    /// use dynamics::motor::{from_pose, ScrewFrame};
    /// use dynamics::{Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let motor = from_pose::<Pga>(-Vector3::z(), &UnitQuaternion::identity());
    /// // 1 rad/s about body x, the centre moving at ω × (c − pivot) = 1 m/s along y (body frame).
    /// let swing = Pga::screw(ScrewCoordinates { l: Vector3::x(), t: Vector3::y() });
    /// let at = Kinematics::<Pga>::with_frame(0.0, motor, ScrewFrame::of::<Pga>(motor), swing);
    /// let mut rows = RowBuffer::new();
    /// VirtualPower::<Pga>::ball_joint("pivot", Vector3::z(), Vector3::zeros()).rows(&at, &mut rows)?;
    /// assert_eq!(rows.len(), 3);
    /// assert!(rows.rows().iter().all(|row| row.position_residual == Some(0.0) && row.velocity_residual == 0.0));
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    #[inline]
    pub fn with_frame(t: f64, motor: A::Motor, frame: ScrewFrame, body_velocity: A::Screw) -> Self {
        let ScrewCoordinates { l: omega, t: v } = A::screw_coordinates(body_velocity);
        let angular_velocity = frame.rotation * omega;
        let linear_velocity = frame.rotation * v;
        Kinematics {
            t,
            motor,
            reverse: A::reverse(motor),
            body_velocity,
            velocity: Vector6::new(omega.x, omega.y, omega.z, v.x, v.y, v.z),
            // The world coordinates of Ḃ (see `ScrewFrame::to_world`), without a second rotation.
            world_velocity: A::screw(ScrewCoordinates {
                l: angular_velocity,
                t: linear_velocity + frame.position.cross(&angular_velocity),
            }),
            frame,
            angular_velocity,
            linear_velocity,
        }
    }

    /// The coordinates of `~R X R` from those of a world screw X ([`ScrewFrame::to_body`]: 24 multiplies
    /// instead of a motor sandwich).
    #[inline]
    pub fn to_body_coordinates(&self, world: &ScrewCoordinates) -> ScrewCoordinates {
        self.frame.to_body(world)
    }

    /// The coordinates of `R X ~R` from those of a body screw.
    #[inline]
    pub fn to_world_coordinates(&self, body: &ScrewCoordinates) -> ScrewCoordinates {
        self.frame.to_world(body)
    }

    /// `~R X R`: the body view of a world screw.
    #[inline]
    pub fn to_body(&self, world: A::Screw) -> A::Screw {
        A::screw(self.to_body_coordinates(&A::screw_coordinates(world)))
    }

    /// `R X ~R`: the world view of a body screw.
    #[inline]
    pub fn to_world(&self, body: A::Screw) -> A::Screw {
        A::screw(self.to_world_coordinates(&A::screw_coordinates(body)))
    }

    /// World position of the body point at `body_point` (body coordinates, from the centre of mass).
    #[inline]
    pub fn world_point(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.frame.position + self.frame.rotation * body_point
    }

    /// World direction of a body direction.
    #[inline]
    pub fn world_direction(&self, body_direction: &Vector3<f64>) -> Vector3<f64> {
        self.frame.rotation * body_direction
    }

    /// World velocity of the body point at `body_point`: `v + ω ⨯ (a − c)`.
    #[inline]
    pub fn world_point_velocity(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.linear_velocity + self.angular_velocity.cross(&(self.frame.rotation * body_point))
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::UnitQuaternion;

    use super::*;
    use crate::{motor, Cga, Pga};

    /// The coordinate maps ([`ScrewFrame`]) equal the sandwiches `~RXR` and `RX~R` on screws, in both algebras.
    fn coordinate_maps_are_the_sandwich<A: Algebra>(tolerance: f64) {
        let mut uniform = crate::test_random::uniform(0x9e37_79b9_7f4a_7c15_u64);
        let mut next = || uniform() * 4.0 - 2.0;
        for _ in 0..100 {
            let mut vector = || Vector3::new(next(), next(), next());
            let rotation = UnitQuaternion::from_scaled_axis(vector());
            let motor = motor::from_pose::<A>(vector(), &rotation);
            let screw = A::screw(ScrewCoordinates {
                l: vector(),
                t: vector(),
            });
            let kinematics = Kinematics::<A>::new(0.0, motor, screw);
            let sandwich_body = A::screw_coordinates(A::transform_screw(A::reverse(motor), screw));
            let sandwich_world = A::screw_coordinates(A::transform_screw(motor, screw));
            let body = kinematics.to_body_coordinates(&A::screw_coordinates(screw));
            let world = kinematics.to_world_coordinates(&A::screw_coordinates(screw));
            for (ours, sandwich) in [(body, sandwich_body), (world, sandwich_world)] {
                assert!((ours.l - sandwich.l).norm() + (ours.t - sandwich.t).norm() < tolerance);
            }
            let world_velocity = A::screw_coordinates(kinematics.world_velocity);
            assert!(
                (world_velocity.l - sandwich_world.l).norm() + (world_velocity.t - sandwich_world.t).norm() < tolerance
            );
        }
    }

    #[test]
    fn coordinate_maps_are_the_sandwich_in_pga() {
        coordinate_maps_are_the_sandwich::<Pga>(1e-13);
    }

    #[test]
    fn coordinate_maps_are_the_sandwich_in_cga() {
        coordinate_maps_are_the_sandwich::<Cga>(1e-13);
    }
}
