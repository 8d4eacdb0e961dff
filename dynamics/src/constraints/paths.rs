//! Parametric paths (`docs/theory.md` §8): a body-frame U(t) or world-frame V(t) with exact first and second time
//! derivatives, given by the user (any closure `Fn(f64) -> PathPoint<X>` is a [`Path`]) or generated exactly
//! by a translator ([`TranslatedPath`]: a driven pivot, an attachment sliding on the body).
//!
//! Every constructor that takes a path takes it the same way, as `impl Path<X> + 'static` (or
//! `impl MotorPath<A>`, `impl WrenchPath<A>`): a closure, one of the paths here, or an `Arc` of any of them
//! when one path is shared.

use std::marker::PhantomData;
use std::sync::Arc;

use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::objects::{Coefficients, Pinnable, PinningAlgebra};

/// A path's value and its first and second time derivatives at one time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint<X> {
    /// The value at that time.
    pub value: X,
    /// Its first time derivative.
    pub rate: X,
    /// Its second time derivative.
    pub acceleration: X,
}

impl<X: Coefficients> PathPoint<X> {
    /// A value at rest.
    ///
    /// A pivot path that stays put: a pendulum hanging still from it is on its joint, and the pivot carries
    /// its weight.
    ///
    /// ```
    /// use dynamics::constraints::{PathPoint, VirtualPower};
    /// use dynamics::{Algebra, Body, Force, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let pivot = |_t: f64| PathPoint::at_rest(Vector3::new(0.0, 0.0, 2.0)); // m
    /// assert_eq!((pivot(1.0).rate, pivot(1.0).acceleration), (Vector3::zeros(), Vector3::zeros()));
    /// let rod = Body::rod(1.5, 1.0, 1e-3)?; // 1.5 kg, 1 m
    /// let top = Vector3::new(0.0, 0.0, 0.5);
    /// let pendulum = Mechanism::single(rod).with_force(Force::gravity())?
    ///     .with_constraint(VirtualPower::driven_ball_joint("pivot", top, pivot))?;
    /// let still = UnitQuaternion::identity();
    /// let hanging = State::<Pga>::new(&rod, Vector3::z() * 1.5, &still, Vector3::zeros(), Vector3::zeros());
    /// assert_eq!(pendulum.violation(0.0, &[hanging])?.velocity, 0.0);
    /// let reaction = Pga::screw_coordinates(pendulum.reactions(0.0, &[hanging])?[0]);
    /// assert!((reaction.l - Vector3::new(0.0, 0.0, 1.5 * 9.81)).norm() < 1e-12); // N
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn at_rest(value: X) -> Self {
        PathPoint {
            value,
            rate: X::zero(),
            acceleration: X::zero(),
        }
    }
}

/// A prescribed path with exact derivatives.
pub trait Path<X>: Send + Sync {
    /// The value and its exact first and second derivatives at time `t` (s).
    fn at(&self, t: f64) -> PathPoint<X>;
    /// A fixed path lets a pin skip the derivative terms of theory §8 (they are zero).
    fn is_fixed(&self) -> bool {
        false
    }
}

/// A constant value (theory §7: static U and V).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fixed<X>(pub X);

impl<X: Coefficients> Path<X> for Fixed<X> {
    fn at(&self, _t: f64) -> PathPoint<X> {
        PathPoint::at_rest(self.0)
    }

    fn is_fixed(&self) -> bool {
        true
    }
}

/// A closure returning the value and its exact derivatives.
impl<X, F: Fn(f64) -> PathPoint<X> + Send + Sync> Path<X> for F {
    fn at(&self, t: f64) -> PathPoint<X> {
        self(t)
    }
}

/// A shared path.
impl<X, P: Path<X> + ?Sized> Path<X> for Arc<P> {
    fn at(&self, t: f64) -> PathPoint<X> {
        (**self).at(t)
    }

    fn is_fixed(&self) -> bool {
        (**self).is_fixed()
    }
}

/// `V(t) = T(c(t)) V₀ ~T(c(t))` for an offset path c(t) with exact derivatives (theory §8).
///
/// Theory §8 also writes it as `V₀ + L(c) + Q(c,c)` with `L(c) = ½(N c V₀ − V₀ N c)` and `Q(c₁,c₂) = −¼ N c₁ V₀ N c₂`.
/// With the translation screw `τ(c) = N c = −Σ cᵢtᵢ` (so `T(c) = 1 + ½τ`), `L(c) = τ × V₀`, and since
/// translation screws annihilate each other (`τ₁τ₂ = 0`), `Q(c₁,c₂) + Q(c₂,c₁) = τ₁ × (τ₂ × V₀)`. Hence,
/// exactly and with the commutator alone:
///
/// ```text
/// V = V₀ + τ×V₀ + ½ τ×(τ×V₀)
/// V̇ = τ̇×V₀ + τ̇×(τ×V₀)
/// V̈ = τ̈×V₀ + τ̈×(τ×V₀) + τ̇×(τ̇×V₀)
/// ```
/// (`τ̇ × (τ × V₀) = τ × (τ̇ × V₀)` by the Jacobi identity, translations commuting.)
pub struct TranslatedPath<A, X, P> {
    base: X,
    offset: P,
    algebra: PhantomData<fn() -> A>,
}

impl<A, X, P> TranslatedPath<A, X, P>
where
    A: Algebra,
    X: Pinnable<A>,
    P: Path<Vector3<f64>>,
{
    /// `base` moved along the offset path `offset(t)` (value, velocity, acceleration).
    ///
    /// The plane z = 0 lifted along `c(t) = (0, 0, t²)`: at t = 1.5 s it is the plane z = 2.25 m, moving up
    /// at 3 m/s.
    ///
    /// ```
    /// use dynamics::constraints::paths::TranslatedPath;
    /// use dynamics::constraints::{Coefficients, Path, PathPoint, PinningAlgebra};
    /// use dynamics::Pga;
    /// use nalgebra::Vector3;
    ///
    /// let lift = |t: f64| PathPoint {
    ///     value: Vector3::z() * (t * t),
    ///     rate: Vector3::z() * (2.0 * t),
    ///     acceleration: Vector3::z() * 2.0,
    /// };
    /// let floor = TranslatedPath::<Pga, _, _>::new(Pga::plane_object(Vector3::z(), 0.0), lift);
    /// let at = floor.at(1.5);
    /// let expected = Pga::plane_object(Vector3::z(), 2.25).coefficients();
    /// let expected_rate = Pga::plane_object(Vector3::zeros(), 3.0).coefficients();
    /// let (value, rate) = (at.value.coefficients(), at.rate.coefficients());
    /// assert!(value.iter().zip(expected).all(|(ours, exact)| (ours - exact).abs() < 1e-15));
    /// assert!(rate.iter().zip(expected_rate).all(|(ours, exact)| (ours - exact).abs() < 1e-15));
    /// ```
    pub fn new(base: X, offset: P) -> Self {
        TranslatedPath {
            base,
            offset,
            algebra: PhantomData,
        }
    }
}

/// `τ(c) = N c = −Σ cᵢtᵢ`.
fn translation_screw<A: Algebra>(offset: Vector3<f64>) -> A::Screw {
    A::screw(ScrewCoordinates {
        l: Vector3::zeros(),
        t: -offset,
    })
}

impl<A, X, P> Path<X> for TranslatedPath<A, X, P>
where
    A: Algebra,
    X: Pinnable<A>,
    P: Path<Vector3<f64>>,
{
    fn at(&self, t: f64) -> PathPoint<X> {
        let c = self.offset.at(t);
        let (tau, tau_rate, tau_acceleration) = (
            translation_screw::<A>(c.value),
            translation_screw::<A>(c.rate),
            translation_screw::<A>(c.acceleration),
        );
        let commute = X::screw_commutator;
        let first = commute(tau, self.base);
        PathPoint {
            value: self.base + first + commute(tau, first) * 0.5,
            rate: commute(tau_rate, self.base) + commute(tau_rate, first),
            acceleration: commute(tau_acceleration, self.base)
                + commute(tau_acceleration, first)
                + commute(tau_rate, commute(tau_rate, self.base)),
        }
    }
}

/// The point at `position(t)`: the origin point translated along the path, so its derivatives are exact
/// (theory §8 gives them per algebra: `ṗ + (p·ṗ)n∞` in CGA, `e₀ṗI₃` in PGA).
///
/// ```
/// use dynamics::constraints::paths::moving_point;
/// use dynamics::constraints::{Path, PathPoint};
/// use dynamics::{Algebra, Cga};
/// use nalgebra::Vector3;
///
/// // A point going round the unit circle at 1 rad/s.
/// let circle = |t: f64| PathPoint {
///     value: Vector3::new(t.cos(), t.sin(), 0.0),
///     rate: Vector3::new(-t.sin(), t.cos(), 0.0),
///     acceleration: Vector3::new(-t.cos(), -t.sin(), 0.0),
/// };
/// let point = moving_point::<Cga, _>(circle);
/// assert!((Cga::position(point.at(0.7).value) - circle(0.7).value).norm() < 1e-15); // m
/// ```
pub fn moving_point<A, P>(position: P) -> TranslatedPath<A, A::PointObject, P>
where
    A: PinningAlgebra,
    P: Path<Vector3<f64>>,
{
    TranslatedPath::new(A::point_object(Vector3::zeros()), position)
}

/// A prescribed rigid motion at one time: the motor U (body → reference), its body-frame velocity ξ
/// (`dU/dt = −½Uξ`, theory §3) and ξ̇.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotorPoint<A: Algebra> {
    /// The motor U (body → reference).
    pub motor: A::Motor,
    /// The body-frame velocity ξ, with `dU/dt = −½Uξ`.
    pub velocity: A::Screw,
    /// Its time derivative ξ̇.
    pub acceleration: A::Screw,
}

/// A prescribed rigid motion U(t), for motor joints (a body's motor relative to its reference follows it).
pub trait MotorPath<A: Algebra>: Send + Sync {
    /// The motor, its body-frame velocity and that velocity's derivative at time `t` (s).
    fn at(&self, t: f64) -> MotorPoint<A>;
}

/// A closure returning the motor and its velocity and acceleration.
impl<A: Algebra, F: Fn(f64) -> MotorPoint<A> + Send + Sync> MotorPath<A> for F {
    fn at(&self, t: f64) -> MotorPoint<A> {
        self(t)
    }
}

/// A shared motor path.
impl<A: Algebra, P: MotorPath<A> + ?Sized> MotorPath<A> for Arc<P> {
    fn at(&self, t: f64) -> MotorPoint<A> {
        (**self).at(t)
    }
}

/// `U(t) = U₀ exp(−½ θ(t) S)`: a screw motion by the parameter θ(t) (value, rate, acceleration) along the screw S
/// (a body velocity: with S = l₃, θ turns the body about its z axis; with S = t₁, θ slides it along x), from the
/// motor U₀. Its body velocity is `ξ = θ̇ S` (S commutes with exp(θS)), so `ξ̇ = θ̈ S`.
pub struct ScrewMotion<A: Algebra, P> {
    start: A::Motor,
    screw: A::Screw,
    parameter: P,
}

impl<A: Algebra, P: Path<f64>> ScrewMotion<A, P> {
    /// The motion from `start` along `screw` by the parameter path `parameter` (θ with its exact derivatives).
    ///
    /// A turn about the body z axis at 1 rad/s: after π/2 s the motor is a quarter turn, and the velocity is the
    /// screw times θ̇.
    ///
    /// ```
    /// use dynamics::constraints::{MotorPath, PathPoint, ScrewMotion};
    /// use dynamics::{motor, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let about_z = Pga::screw(ScrewCoordinates { l: Vector3::z(), t: Vector3::zeros() });
    /// let theta = |t: f64| PathPoint { value: t, rate: 1.0, acceleration: 0.0 }; // rad
    /// let turning = ScrewMotion::<Pga, _>::new(motor::identity::<Pga>(), about_z, theta);
    /// let quarter = turning.at(std::f64::consts::FRAC_PI_2);
    /// let (position, rotation) = motor::pose::<Pga>(quarter.motor);
    /// let expected = UnitQuaternion::from_scaled_axis(Vector3::z() * std::f64::consts::FRAC_PI_2);
    /// assert!(position.norm() < 1e-15 && rotation.angle_to(&expected) < 1e-15);
    /// assert_eq!(quarter.velocity, about_z); // rad/s about z
    /// ```
    pub fn new(start: A::Motor, screw: A::Screw, parameter: P) -> Self {
        ScrewMotion {
            start,
            screw,
            parameter,
        }
    }
}

impl<A: Algebra, P: Path<f64>> MotorPath<A> for ScrewMotion<A, P> {
    fn at(&self, t: f64) -> MotorPoint<A> {
        let theta = self.parameter.at(t);
        MotorPoint {
            motor: A::compose(
                self.start,
                crate::exponential::exp::<A>(self.screw * (-0.5 * theta.value)),
            ),
            velocity: self.screw * theta.rate,
            acceleration: self.screw * theta.acceleration,
        }
    }
}

/// An object X of the body frame carried by a motor path: `V(t) = U X ~U`, and from
/// `d/dt(R Y ~R) = R(Y × Ḃ + Ẏ)~R` (theory §5) applied twice, `V̇ = U(X × ξ)~U`,
/// `V̈ = U((X × ξ) × ξ + X × ξ̇)~U`: the reference-frame path a motor joint pins the body's X to.
pub struct CarriedPath<A: Algebra, X> {
    object: X,
    path: Arc<dyn MotorPath<A>>,
}

impl<A: Algebra, X: Pinnable<A>> CarriedPath<A, X> {
    /// The body-frame object `object` carried by the motor path `path`.
    ///
    /// The body x axis carried by a quarter turn about z is the world y axis:
    ///
    /// ```
    /// use dynamics::constraints::{CarriedPath, Coefficients, Path, PathPoint, PinningAlgebra, ScrewMotion};
    /// use dynamics::{motor, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::Vector3;
    ///
    /// let about_z = Pga::screw(ScrewCoordinates { l: Vector3::z(), t: Vector3::zeros() });
    /// let theta = |t: f64| PathPoint { value: t, rate: 1.0, acceleration: 0.0 }; // rad
    /// let turning = ScrewMotion::<Pga, _>::new(motor::identity::<Pga>(), about_z, theta);
    /// let x_axis = CarriedPath::new(Pga::line_object(Vector3::zeros(), Vector3::x()), turning);
    /// let carried = x_axis.at(std::f64::consts::FRAC_PI_2).value.coefficients();
    /// let y_axis = Pga::line_object(Vector3::zeros(), Vector3::y()).coefficients();
    /// assert!(carried.iter().zip(y_axis).all(|(a, b)| (a - b).abs() < 1e-15));
    /// ```
    pub fn new(object: X, path: impl MotorPath<A> + 'static) -> Self {
        CarriedPath::shared(object, Arc::new(path))
    }

    /// One motor path carrying several objects (a motor joint's two lines) without a second indirection.
    pub(crate) fn shared(object: X, path: Arc<dyn MotorPath<A>>) -> Self {
        CarriedPath { object, path }
    }
}

impl<A: Algebra, X: Pinnable<A>> Path<X> for CarriedPath<A, X> {
    fn at(&self, t: f64) -> PathPoint<X> {
        let MotorPoint {
            motor,
            velocity,
            acceleration,
        } = self.path.at(t);
        // X × ξ = −ξ × X.
        let moved = X::screw_commutator(velocity, self.object) * -1.0;
        let second = X::screw_commutator(velocity, moved) * -1.0 - X::screw_commutator(acceleration, self.object);
        PathPoint {
            value: self.object.transformed(motor),
            rate: moved.transformed(motor),
            acceleration: second.transformed(motor),
        }
    }
}
