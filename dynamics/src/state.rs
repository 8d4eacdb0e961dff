//! The state of one rigid body: the motor R (body → world) and the momentum about the centre of mass in world axes
//! (`docs/theory.md` §0, §5; docs/dynamics.md, "Momentum about the centre of mass").

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::body::Body;
use crate::motor;

/// `[R, Ω_c]`: objects move as `V = R U ~R`; Ω_c is the momentum bivector in world axes about the body's centre of
/// mass, the world momentum Ω of theory §3 translated to the centre (`Ω = T Ω_c ~T`, T the motor's translation).
///
/// Holding the momentum about the origin, `I ω + c × m v`, would round it to ε |c| m |v| every step, an error in the
/// spin that grows with the distance from the origin; about the centre of mass it is `I ω`, whose round-off does
/// not depend on where the body is (docs/dynamics.md, "Momentum about the centre of mass").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<A: Algebra> {
    /// R (body → world).
    pub motor: A::Motor,
    /// Ω_c: `l` the linear momentum `m v`, `t` the angular momentum about the centre of mass `I ω`, both in world
    /// axes ([`State::momentum_about_origin`] gives Ω).
    pub central_momentum: A::Screw,
}

/// Momenta in world terms ([`State::world_momentum`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldMomentum {
    /// `m v` (kg m/s).
    pub linear: Vector3<f64>,
    /// `I ω` about the centre of mass, world axes (kg m²/s).
    pub angular_about_centre_of_mass: Vector3<f64>,
    /// About the world origin: `I ω + c × m v`.
    pub angular_about_origin: Vector3<f64>,
}

/// Velocities in world terms, for reports and comparisons with classical references.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldVelocity {
    /// Angular velocity, world axes.
    pub angular: Vector3<f64>,
    /// Velocity of the centre of mass, world axes.
    pub linear: Vector3<f64>,
}

/// The largest magnitude of a state coordinate (motor or momentum) that the dynamics accepts. The equations form
/// products of a few coordinates with masses and moments (sandwiches multiply by the motor twice), which stay
/// finite far below this but overflow near `f64::MAX` (a body placed at 1e308 m used to fail inside its first
/// joint as a "non-finite residual").
pub const MAX_COORDINATE: f64 = 1e50;

/// Body points, plane normals and offsets and surface parameters beyond this magnitude (m) are refused: the heights
/// and incidences the simulation watches would lose every digit below a micrometre.
pub const LARGEST_COORDINATE: f64 = 1e6;

/// How far from the world origin a body's centre of mass may be at the start of a step, in its smallest radius of
/// gyration r = √(I_min / m) ([`crate::Body::smallest_gyration_radius`]). Positions there are resolved to ε |c|
/// (ε = 2.2e-16): 1e-9 of the body's size at this distance, so the points its joints, contacts and forces act at,
/// and its place relative to other bodies, keep nine digits fewer than at the origin. (Its spin keeps its digits:
/// the state holds the momentum about the centre of mass. While it held the momentum about the origin, a 2 kg
/// cuboid of 0.1 × 0.2 × 0.3 m, r = 0.065 m, moving at 2.3 m/s 1e6 m out lost 3e-7 rad/s of its spin in 1 s.) A
/// scene that far out belongs nearer the origin.
pub const MAX_DISTANCE_IN_GYRATION_RADII: f64 = 1e-9 / f64::EPSILON;

impl<A: Algebra> State<A> {
    /// Whether every coordinate of the motor and the momentum is finite and at most [`MAX_COORDINATE`] in
    /// magnitude.
    pub fn is_representable(&self) -> bool {
        let motor = A::motor_coordinates(self.motor);
        let momentum = A::screw_coordinates(self.central_momentum);
        let within = |x: &f64| x.abs() <= MAX_COORDINATE;
        within(&motor.scalar)
            && within(&motor.pseudoscalar)
            && motor.l.iter().chain(motor.t.iter()).all(within)
            && momentum.l.iter().chain(momentum.t.iter()).all(within)
    }

    /// The squared norm of the motor's rotor part, `s² + |a|²` (scalar and rotation bivectors): 1 for a rigid
    /// motion; a zero or scaled motor (a state written field by field) is none.
    pub fn rotor_norm_squared(&self) -> f64 {
        let motor = A::motor_coordinates(self.motor);
        motor.scalar * motor.scalar + motor.l.norm_squared()
    }

    /// The state of a body at `position` (its centre of mass) with orientation `rotation`, moving
    /// with body-frame angular velocity `angular_body` and centre-of-mass velocity `linear_world`: the mixed
    /// frames of the reference scenes' files. [`State::from_body_twist`] and [`State::from_world_twist`] take
    /// both velocities in one frame.
    ///
    /// ```
    /// use dynamics::{Body, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::cuboid(1.0, Vector3::new(0.1, 0.2, 0.3))?;
    /// let quarter = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
    /// // Spinning at 2 rad/s about its body x axis, which the quarter turn points along world y; moving along
    /// // world x at 3 m/s.
    /// let state = State::<Pga>::new(&body, Vector3::zeros(), &quarter, 2.0 * Vector3::x(), 3.0 * Vector3::x());
    /// let velocity = state.world_velocity(&body);
    /// assert!((velocity.angular - Vector3::y() * 2.0).norm() < 1e-15); // rad/s, world axes
    /// assert!((velocity.linear - Vector3::x() * 3.0).norm() < 1e-15); // m/s, world axes
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn new(
        body: &Body,
        position: Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angular_body: Vector3<f64>,
        linear_world: Vector3<f64>,
    ) -> Self {
        State::from_body_twist(
            body,
            position,
            rotation,
            angular_body,
            rotation.inverse() * linear_world,
        )
    }

    /// The state of a body whose centre of mass is at `position` (world), oriented by `rotation` (body → world),
    /// moving with angular velocity `angular_world` and centre-of-mass velocity `linear_world`, both in world
    /// axes.
    ///
    /// ```
    /// use dynamics::{Body, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::cylinder(2.0, 0.1, 0.5)?;
    /// let turned = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.3, 0.0));
    /// let state = State::<Pga>::from_world_twist(&body, Vector3::z(), &turned, Vector3::z(), Vector3::x());
    /// let velocity = state.world_velocity(&body);
    /// assert!((velocity.angular - Vector3::z()).norm() < 1e-15);
    /// assert!((velocity.linear - Vector3::x()).norm() < 1e-15);
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn from_world_twist(
        body: &Body,
        position: Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angular_world: Vector3<f64>,
        linear_world: Vector3<f64>,
    ) -> Self {
        let to_body = rotation.inverse();
        State::from_body_twist(
            body,
            position,
            rotation,
            to_body * angular_world,
            to_body * linear_world,
        )
    }

    /// The state of a body whose centre of mass is at `position` (world), oriented by `rotation` (body → world),
    /// moving with angular velocity `angular_body` and centre-of-mass velocity `linear_body`, both in body axes:
    /// `R₀ = T(c₀)R_rot`, `Ω₀ = R₀ M(Ḃ₀) ~R₀` (theory §11).
    ///
    /// ```
    /// use dynamics::{Body, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::sphere(2.0, 0.1)?; // 2 kg
    /// let quarter = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
    /// // 1.5 m/s along its body x axis, which points along world y.
    /// let state = State::<Pga>::from_body_twist(&body, Vector3::z(), &quarter, Vector3::zeros(), 1.5 * Vector3::x());
    /// assert!((state.world_velocity(&body).linear - Vector3::y() * 1.5).norm() < 1e-15); // m/s
    /// assert!((state.world_momentum().linear - Vector3::y() * 3.0).norm() < 1e-15); // m v (kg m/s)
    /// assert!((state.kinetic_energy(&body) - 0.5 * 2.0 * 1.5 * 1.5).abs() < 1e-15); // J
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn from_body_twist(
        body: &Body,
        position: Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angular_body: Vector3<f64>,
        linear_body: Vector3<f64>,
    ) -> Self {
        let motor = motor::from_pose::<A>(position, rotation);
        let velocity = A::screw(ScrewCoordinates {
            l: angular_body,
            t: linear_body,
        });
        State {
            motor,
            central_momentum: crate::motor::central_from_body::<A>(motor, body.momentum::<A>(velocity)),
        }
    }

    /// `Ω_b = ~R Ω R`, the body momentum: the central momentum turned to body axes.
    #[inline]
    pub fn body_momentum(&self) -> A::Screw {
        crate::motor::body_from_central::<A>(self.motor, self.central_momentum)
    }

    /// Ω, the momentum about the world origin in world axes (theory §3): `(m v, I ω + c × m v)`. Far from the origin
    /// its angular part is a large `c × m v` plus the spin's small `I ω`; the state keeps the two apart.
    pub fn momentum_about_origin(&self) -> A::Screw {
        let centre = self.pose().0;
        let central = A::screw_coordinates(self.central_momentum);
        A::screw(ScrewCoordinates {
            l: central.l,
            t: central.t + centre.cross(&central.l),
        })
    }

    /// `Ḃ = M⁻¹[Ω_b]`: angular velocity and centre-of-mass velocity, both in body axes (theory §3).
    #[inline]
    pub fn body_velocity(&self, body: &Body) -> A::Screw {
        body.velocity::<A>(self.body_momentum())
    }

    /// Position of the centre of mass and orientation (body → world).
    pub fn pose(&self) -> (Vector3<f64>, UnitQuaternion<f64>) {
        motor::pose::<A>(self.motor)
    }

    /// World angular velocity and centre-of-mass velocity.
    pub fn world_velocity(&self, body: &Body) -> WorldVelocity {
        let (_, rotation) = self.pose();
        let v = A::screw_coordinates(self.body_velocity(body));
        WorldVelocity {
            angular: rotation * v.l,
            linear: rotation * v.t,
        }
    }

    /// Linear momentum and angular momentum (about the centre of mass and about the world origin), in world
    /// axes: the body momentum's parts `(p_b, L_b)` (the l and t coordinates of `Ω_b`, see [`Body::momentum`])
    /// turned to the world, and `L_O = L + c × p`.
    pub fn world_momentum(&self) -> WorldMomentum {
        let (position, rotation) = self.pose();
        let body = A::screw_coordinates(self.body_momentum());
        let (linear, angular) = (rotation * body.l, rotation * body.t);
        WorldMomentum {
            linear,
            angular_about_centre_of_mass: angular,
            angular_about_origin: angular + position.cross(&linear),
        }
    }

    /// Kinetic energy `½⟨Ḃ ∧ Ω_b⟩_Π` (theory §4).
    pub fn kinetic_energy(&self, body: &Body) -> f64 {
        body.kinetic_energy::<A>(self.body_velocity(body))
    }

    /// World position of a body-fixed point given in body coordinates.
    pub fn world_point(&self, body_point: Vector3<f64>) -> Vector3<f64> {
        A::position(A::transform_point(self.motor, A::point(body_point)))
    }
}
