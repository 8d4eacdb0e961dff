//! Forces as screws (`docs/theory.md` §3): a force f acting along the line through a is the wrench
//! `W = f I₃ − (a∧f) I₃ N = Σ fᵢlᵢ + (a⨯f)ᵢtᵢ` (the same in both algebras); a couple b is `b∧N = Σ bᵢtᵢ`.

use std::fmt;
use std::sync::Arc;

use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::body::Body;
use crate::state::State;

/// The wrench of force `force` acting along the line through `point` (world frame).
#[inline]
pub fn force_line<A: Algebra>(force: Vector3<f64>, point: Vector3<f64>) -> A::Screw {
    A::screw(ScrewCoordinates {
        l: force,
        t: point.cross(&force),
    })
}

/// The wrench of a pure moment (couple): a free vector, unchanged by translations.
#[inline]
pub fn couple<A: Algebra>(moment: Vector3<f64>) -> A::Screw {
    A::screw(ScrewCoordinates {
        l: Vector3::zeros(),
        t: moment,
    })
}

/// A user force: world wrench as a function of time and state.
pub type WrenchFunction<A> = Arc<dyn Fn(f64, &State<A>) -> <A as Algebra>::Screw + Send + Sync>;

/// An external force on a body; its wrench is expressed in the world frame.
#[derive(Clone)]
pub enum Force<A: Algebra> {
    /// Uniform gravity `m g` acting at the centre of mass (g = 9.81 along −e₃ in the scenes).
    Gravity {
        /// The gravitational acceleration g (m/s²), world axes.
        acceleration: Vector3<f64>,
    },
    /// A constant force along a fixed world line.
    Line {
        /// The force f (N), world axes.
        force: Vector3<f64>,
        /// A point of its line of action (m), world frame.
        point: Vector3<f64>,
    },
    /// A constant couple.
    Couple {
        /// The moment b (N m), world axes.
        moment: Vector3<f64>,
    },
    /// Any wrench depending on time and state.
    Custom(WrenchFunction<A>),
}

impl<A: Algebra> fmt::Debug for Force<A> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Force::Gravity { acceleration } => write!(f, "Gravity({acceleration:?})"),
            Force::Line { force, point } => write!(f, "Line({force:?} through {point:?})"),
            Force::Couple { moment } => write!(f, "Couple({moment:?})"),
            Force::Custom(_) => write!(f, "Custom(..)"),
        }
    }
}

/// Standard gravity of the scenes (m/s²).
pub const STANDARD_GRAVITY: f64 = 9.81;

impl<A: Algebra> Force<A> {
    /// Gravity of 9.81 m/s² along −e₃.
    ///
    /// The weight of a 2 kg body whose centre of mass is at `(1, 0, 0.5)` m: 19.62 N down through it, a moment
    /// `c × f` about the origin, and the potential energy `m g z`.
    ///
    /// ```
    /// use dynamics::{Algebra, Body, Force, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::sphere(2.0, 0.1)?;
    /// let centre = Vector3::new(1.0, 0.0, 0.5);
    /// let state = State::<Pga>::new(&body, centre, &UnitQuaternion::identity(), Vector3::zeros(), Vector3::zeros());
    /// let gravity = Force::gravity();
    /// let weight = Pga::screw_coordinates(gravity.wrench(&body, 0.0, &state));
    /// assert_eq!(weight.l, Vector3::new(0.0, 0.0, -2.0 * 9.81)); // N
    /// assert_eq!(weight.t, centre.cross(&weight.l)); // N m
    /// assert!((gravity.potential_energy(&body, &state) - 2.0 * 9.81 * 0.5).abs() < 1e-15); // J
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn gravity() -> Self {
        Force::Gravity {
            acceleration: Vector3::new(0.0, 0.0, -STANDARD_GRAVITY),
        }
    }

    /// The world wrench on `body` in `state` at time `t`.
    pub fn wrench(&self, body: &Body, t: f64, state: &State<A>) -> A::Screw {
        self.wrench_at(body, t, state.motor, || state.central_momentum)
    }

    /// [`Force::wrench`] for a body at `motor` whose central momentum ([`State::central_momentum`]) is computed only
    /// if a custom force asks for it (a caller holding the body momentum saves a rotation).
    pub fn wrench_at(&self, body: &Body, t: f64, motor: A::Motor, momentum: impl FnOnce() -> A::Screw) -> A::Screw {
        match self {
            Force::Gravity { acceleration } => {
                let centre = A::position(A::transform_point(motor, A::point(Vector3::zeros())));
                force_line::<A>(body.mass() * acceleration, centre)
            }
            Force::Line { force, point } => force_line::<A>(*force, *point),
            Force::Couple { moment } => couple::<A>(*moment),
            Force::Custom(function) => function(
                t,
                &State {
                    motor,
                    central_momentum: momentum(),
                },
            ),
        }
    }

    /// [`Force::wrench_at`] about the body's centre of mass c, world axes: the weight with no moment, a force f
    /// through p with the moment `(p − c) × f`, a couple as it is. Formed from the centre rather than as the moment
    /// about the origin less `c × f`, whose round-off grows with the distance from the origin; only a custom force,
    /// which gives its wrench about the origin, is moved (docs/dynamics.md, "Momentum about the centre of mass").
    pub(crate) fn central_wrench_at(
        &self,
        body: &Body,
        t: f64,
        motor: A::Motor,
        momentum: impl FnOnce() -> A::Screw,
    ) -> A::Screw {
        let centre = || A::position(A::transform_point(motor, A::point(Vector3::zeros())));
        match self {
            Force::Gravity { acceleration } => force_line::<A>(body.mass() * acceleration, Vector3::zeros()),
            Force::Line { force, point } => force_line::<A>(*force, point - centre()),
            Force::Couple { moment } => couple::<A>(*moment),
            Force::Custom(_) => crate::motor::central_wrench::<A>(motor, self.wrench_at(body, t, motor, momentum)),
        }
    }

    /// The potential energy of a conservative force (zero for the others): `−m g·c` for gravity.
    pub fn potential_energy(&self, body: &Body, state: &State<A>) -> f64 {
        match self {
            Force::Gravity { acceleration } => -body.mass() * acceleration.dot(&state.pose().0),
            _ => 0.0,
        }
    }
}
