//! The state of the body at one evaluation, in the forms the constraints need: the motor and its reverse
//! (to move objects between frames, SPEC §2), the body velocity Ḃ (SPEC §3) and, for the force-line
//! constraints of virtual power (SPEC §6), world positions and velocities of body points.

use nalgebra::{Rotation3, Vector3, Vector6};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::motor;

/// The body's configuration and velocity at time `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kinematics<A: Algebra> {
    pub t: f64,
    /// R (body → world).
    pub motor: A::Motor,
    /// ~R (world → body).
    pub reverse: A::Motor,
    /// Ḃ = M⁻¹[~R Ω R], body frame.
    pub body_velocity: A::Screw,
    /// The coordinates `x = (ω; v)` of Ḃ (body axes).
    pub velocity: Vector6<f64>,
    /// Ḃ_w = R Ḃ ~R, world frame (SPEC §3).
    pub world_velocity: A::Screw,
    /// World position of the centre of mass.
    pub position: Vector3<f64>,
    /// Rotation body → world.
    pub rotation: Rotation3<f64>,
    /// Angular velocity, world axes.
    pub angular_velocity: Vector3<f64>,
    /// Centre-of-mass velocity, world axes.
    pub linear_velocity: Vector3<f64>,
}

impl<A: Algebra> Kinematics<A> {
    /// The kinematics of a body with motor `motor` moving with body velocity `body_velocity`.
    pub fn new(t: f64, motor: A::Motor, body_velocity: A::Screw) -> Self {
        let (position, orientation) = motor::pose::<A>(motor);
        let rotation = orientation.to_rotation_matrix();
        let ScrewCoordinates { l: omega, t: v } = A::screw_coordinates(body_velocity);
        Kinematics {
            t,
            motor,
            reverse: A::reverse(motor),
            body_velocity,
            velocity: Vector6::new(omega.x, omega.y, omega.z, v.x, v.y, v.z),
            world_velocity: A::transform_screw(motor, body_velocity),
            position,
            rotation,
            angular_velocity: rotation * omega,
            linear_velocity: rotation * v,
        }
    }

    /// `~R X R`: the body view of a world screw.
    #[inline]
    pub fn to_body(&self, world: A::Screw) -> A::Screw {
        A::transform_screw(self.reverse, world)
    }

    /// `R X ~R`: the world view of a body screw.
    #[inline]
    pub fn to_world(&self, body: A::Screw) -> A::Screw {
        A::transform_screw(self.motor, body)
    }

    /// World position of the body point at `body_point` (body coordinates, from the centre of mass).
    #[inline]
    pub fn world_point(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.rotation * body_point
    }

    /// World direction of a body direction.
    #[inline]
    pub fn world_direction(&self, body_direction: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * body_direction
    }

    /// World velocity of the body point at `body_point`: `v + ω ⨯ (a − c)`.
    #[inline]
    pub fn world_point_velocity(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.linear_velocity + self.angular_velocity.cross(&(self.rotation * body_point))
    }
}
