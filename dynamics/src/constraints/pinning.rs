//! Constraints by pinning multivectors (`docs/theory.md` §7), parametric paths (§8) and linear functions of them (§9),
//! all as one [`Pin`]: a world object V(t), mapped into the body frame `V_b = ~R V R`, must satisfy
//! `A[V_b] = U(t)` for a body-fixed linear function A (the identity for plain pins) and a body-frame
//! target U(t).
//!
//! Residuals and rows (theory §8, §9), with `Ḃ×` the commutator product:
//!
//! ```text
//! e = A[V_b] − U
//! ė = A[Ḃ × V_b + V̇_b] − U̇                                   (Jacobian column j: A[Ḃⱼ × V_b])
//! ë = A[B̈ × V_b] + A[Ḃ×(Ḃ×V_b) + 2 Ḃ×V̇_b + V̈_b] − Ü         (bias: everything but the B̈ term)
//! ```
//! which is theory §9's final equation `A[V_b × M⁻¹F] = −Ü + A[M⁻¹[S + Ḃ×Ω_b] × V_b + …]` once
//! `B̈ = M⁻¹[Ḃ×Ω_b + S + F]` is substituted (the solve does that, see [`crate::constraints`]).

use std::marker::PhantomData;
use std::sync::Arc;

use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::cga::{generated as cga_types, Cga};
use crate::constraints::kinematics::Kinematics;
use crate::constraints::objects::{cga_circle, cga_sphere, Coefficients, Pinnable, PinningAlgebra};
use crate::constraints::paths::{CarriedPath, Fixed, MotorPath, Path, TranslatedPath};
use crate::constraints::rows::{ConstraintRow, RowBuffer};
use crate::constraints::virtual_power::unit;
use crate::constraints::{Composite, Constraint, ConstraintError};
use crate::convert::direction_and_length;

/// A linear map from X to Y, fixed in the body frame. Linearity is the caller's promise: the rows apply
/// it to each term of theory §9's equation separately.
pub struct LinearFunction<X, Y>(Arc<dyn Fn(X) -> Y + Send + Sync>);

impl<X, Y> Clone for LinearFunction<X, Y> {
    fn clone(&self) -> Self {
        LinearFunction(self.0.clone())
    }
}

impl<X, Y> LinearFunction<X, Y> {
    /// Wraps `function`, which the caller promises is linear.
    ///
    /// The incidence `P ∧ X` of a fixed point P with a plane X: zero for a plane through P, otherwise P's distance
    /// from a unit-normal plane (up to sign). [`Pin::linear`] pins such a function of a world object to a target.
    ///
    /// ```
    /// use dynamics::constraints::{Coefficients, LinearFunction, PinningAlgebra};
    /// use dynamics::Pga;
    /// use nalgebra::Vector3;
    ///
    /// let point = Pga::point_object(Vector3::new(0.3, -0.2, 0.5)); // m
    /// let incidence = LinearFunction::new(move |plane| Pga::point_plane_incidence(point, plane));
    /// let through = incidence.apply(Pga::plane_object(Vector3::z(), 0.5)).coefficients(); // the plane z = 0.5 m
    /// let below = incidence.apply(Pga::plane_object(Vector3::z(), 0.2)).coefficients();
    /// assert_eq!(through, [0.0]);
    /// assert!((below[0].abs() - 0.3).abs() < 1e-15); // m
    /// ```
    pub fn new(function: impl Fn(X) -> Y + Send + Sync + 'static) -> Self {
        LinearFunction(Arc::new(function))
    }

    /// `A[x]`.
    #[inline]
    pub fn apply(&self, x: X) -> Y {
        (self.0)(x)
    }
}

impl<X: 'static> LinearFunction<X, X> {
    /// The identity map, for plain pins `V_b = U`.
    ///
    /// With the identity, [`Pin::linear`] is the plain pin [`Pin::new`]: the same rows at any state.
    ///
    /// ```
    /// use dynamics::constraints::paths::Fixed;
    /// use dynamics::constraints::{Constraint, Kinematics, LinearFunction, Pin, RowBuffer};
    /// use dynamics::{motor, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let (tip, pivot) = (Pga::point(Vector3::z()), Pga::point(Vector3::new(0.1, 0.0, 0.0)));
    /// let plain = Pin::new("ball", tip, pivot, 3);
    /// let linear = Pin::linear("ball", Fixed(tip), LinearFunction::identity(), Fixed(pivot), 3);
    /// let turn = UnitQuaternion::from_scaled_axis(Vector3::x());
    /// let pose = motor::from_pose::<Pga>(Vector3::new(0.0, 0.3, -1.0), &turn);
    /// let twist = Pga::screw(ScrewCoordinates { l: Vector3::y(), t: Vector3::z() });
    /// let at = Kinematics::<Pga>::new(0.0, pose, twist);
    /// let (mut a, mut b) = (RowBuffer::new(), RowBuffer::new());
    /// plain.rows(&at, &mut a)?;
    /// linear.rows(&at, &mut b)?;
    /// assert_eq!(a.len(), 4); // one per coefficient of the PGA point (its weight's row is identically zero)
    /// assert_eq!(a.rows(), b.rows());
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn identity() -> Self {
        LinearFunction::new(|x| x)
    }
}

/// `A[~R V(t) R] = U(t)`: see the module docs. `X` is the pinned object's type, `Y` the type of `A[X]`.
pub struct Pin<A: Algebra, X: Pinnable<A>, Y: Coefficients = X> {
    name: String,
    world: Arc<dyn Path<X>>,
    function: LinearFunction<X, Y>,
    body: Arc<dyn Path<Y>>,
    rank: usize,
    algebra: PhantomData<fn() -> A>,
}

impl<A: Algebra, X: Pinnable<A>, Y: Coefficients> Clone for Pin<A, X, Y> {
    fn clone(&self) -> Self {
        Pin {
            name: self.name.clone(),
            world: self.world.clone(),
            function: self.function.clone(),
            body: self.body.clone(),
            rank: self.rank,
            algebra: PhantomData,
        }
    }
}

impl<A: Algebra, X: Pinnable<A>, Y: Coefficients> std::fmt::Debug for Pin<A, X, Y> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pin")
            .field("name", &self.name)
            .field("rank", &self.rank)
            .finish_non_exhaustive()
    }
}

impl<A: Algebra, X: Pinnable<A>> Pin<A, X, X> {
    /// The body object `body` (body frame) pinned to the world object `world`: `V = R U ~R` (theory §7).
    /// `rank` is the number of constrained degrees of freedom (theory §7 table).
    ///
    /// A ball joint: the top end of a rod pinned to the world origin. A state swinging about the pivot keeps it;
    /// one moved 1 cm off does not.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, Pin};
    /// use dynamics::{Algebra, Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?; // 1 kg, 1 m along body z
    /// let top = Vector3::new(0.0, 0.0, 0.5); // body point, m
    /// let ball = Pin::new("ball", Pga::point(top), Pga::point(Vector3::zeros()), 3);
    /// assert_eq!(ball.rank(), 3);
    /// let pendulum = Mechanism::single(rod).with_constraint(ball)?;
    ///
    /// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.4, 0.0, 0.0));
    /// let (centre, spin) = (-(tilt * top), Vector3::new(0.0, 1.0, 2.0)); // m, rad/s
    /// let swinging = State::from_world_twist(&rod, centre, &tilt, spin, spin.cross(&centre));
    /// let on = pendulum.violation(0.0, &[swinging])?;
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// let off = State::from_world_twist(&rod, centre + Vector3::x() * 0.01, &tilt, spin, spin.cross(&centre));
    /// assert!((pendulum.violation(0.0, &[off])?.position - 0.01).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(name: impl Into<String>, body: X, world: X, rank: usize) -> Self {
        Pin::with_paths(name, Fixed(body), Fixed(world), rank)
    }

    /// A body path U(t) pinned to a world path V(t) (theory §8).
    ///
    /// A driven pivot: the body's origin pinned to a world point moving along x at 1 m/s (exact derivatives by
    /// [`moving_point`](super::paths::moving_point)). A body carried along with it keeps the pin.
    ///
    /// ```
    /// use dynamics::constraints::paths::{moving_point, Fixed};
    /// use dynamics::constraints::{PathPoint, Pin};
    /// use dynamics::{Algebra, Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let pivot = |t: f64| PathPoint {
    ///     value: Vector3::new(t, 0.0, 0.0),
    ///     rate: Vector3::x(),
    ///     acceleration: Vector3::zeros(),
    /// };
    /// let body = Body::sphere(1.0, 0.1)?;
    /// let centre = Fixed(Pga::point(Vector3::zeros()));
    /// let tow = Pin::with_paths("towed", centre, moving_point::<Pga, _>(pivot), 3);
    /// let towed = Mechanism::single(body).with_constraint(tow)?;
    /// let still = UnitQuaternion::identity();
    /// let at = |x: f64| State::<Pga>::new(&body, Vector3::new(x, 0.0, 0.0), &still, Vector3::z(), Vector3::x());
    /// let on = towed.violation(0.5, &[at(0.5)])?; // at t = 0.5 s the pivot is at x = 0.5 m
    /// assert!(on.position < 1e-15 && on.velocity < 1e-15);
    /// assert!((towed.violation(0.5, &[at(0.0)])?.position - 0.5).abs() < 1e-15); // left behind, m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_paths(
        name: impl Into<String>,
        body: impl Path<X> + 'static,
        world: impl Path<X> + 'static,
        rank: usize,
    ) -> Self {
        Pin::linear(name, body, LinearFunction::identity(), world, rank)
    }
}

impl<A: Algebra, X: Pinnable<A>, Y: Coefficients> Pin<A, X, Y> {
    /// `target(t) = function[~R V(t) R]` (theory §9): the body-side target, then the function of the world
    /// path, in the order of [`Pin::new`]'s (body, world).
    ///
    /// The body point `(0, 0, −0.5)` kept on the world plane z = 0 through the incidence `P ∧ X = 0`: one row, rank
    /// 1, and the point may slide anywhere on the plane.
    ///
    /// ```
    /// use dynamics::constraints::paths::Fixed;
    /// use dynamics::constraints::{Constraint, LinearFunction, Pin, PinningAlgebra};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let foot = Pga::point_object(Vector3::new(0.0, 0.0, -0.5)); // body point, m
    /// let on_floor = LinearFunction::new(move |plane| Pga::point_plane_incidence(foot, plane));
    /// let floor = Fixed(Pga::plane_object(Vector3::z(), 0.0));
    /// let pin = Pin::linear("foot on floor", Fixed(<Pga as PinningAlgebra>::Incidence::ZERO), on_floor, floor, 1);
    /// assert_eq!((pin.rank(), pin.row_count()), (1, 1));
    ///
    /// let leg = Body::rod(1.0, 1.0, 1e-3)?;
    /// let standing = Mechanism::single(leg).with_constraint(pin)?;
    /// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 0.0));
    /// let centre = Vector3::new(2.0, 1.0, 0.0) - tilt * Vector3::new(0.0, 0.0, -0.5); // the foot at (2, 1, 0)
    /// let state = State::new(&leg, centre, &tilt, Vector3::zeros(), Vector3::new(0.5, -0.3, 0.0));
    /// assert!(standing.violation(0.0, &[state])?.position < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn linear(
        name: impl Into<String>,
        target: impl Path<Y> + 'static,
        function: LinearFunction<X, Y>,
        world: impl Path<X> + 'static,
        rank: usize,
    ) -> Self {
        Pin {
            name: name.into(),
            world: Arc::new(world),
            function,
            body: Arc::new(target),
            rank,
            algebra: PhantomData,
        }
    }
}

/// The basis velocity screws `Ḃⱼ` of the coordinates `x = (ω; v)`: `lⱼ` for ωⱼ, `tⱼ` for vⱼ (theory §3).
fn velocity_basis<A: Algebra>() -> [A::Screw; 6] {
    std::array::from_fn(|j| {
        let mut coordinates = ScrewCoordinates::default();
        if j < 3 {
            coordinates.l[j] = 1.0;
        } else {
            coordinates.t[j - 3] = 1.0;
        }
        A::screw(coordinates)
    })
}

impl<A: Algebra, X: Pinnable<A>, Y: Coefficients> Constraint<A> for Pin<A, X, Y> {
    fn name(&self) -> &str {
        &self.name
    }

    fn rank(&self) -> usize {
        self.rank
    }

    fn row_count(&self) -> usize {
        Y::zero().coefficients().as_ref().len()
    }

    fn has_position_residual(&self) -> bool {
        true
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        let commute = X::screw_commutator;
        let apply = |x: X| self.function.apply(x);
        let velocity = kinematics.body_velocity;
        let world = self.world.at(kinematics.t);
        let target = self.body.at(kinematics.t);
        let pinned = world.value.transformed(kinematics.reverse);
        let moved = commute(velocity, pinned);
        let (rate, second) = if self.world.is_fixed() {
            (moved, commute(velocity, moved))
        } else {
            let world_rate = world.rate.transformed(kinematics.reverse);
            let world_acceleration = world.acceleration.transformed(kinematics.reverse);
            (
                moved + world_rate,
                commute(velocity, moved) + commute(velocity, world_rate) * 2.0 + world_acceleration,
            )
        };
        let position = (apply(pinned) - target.value).coefficients();
        let velocity_residual = (apply(rate) - target.rate).coefficients();
        let bias = (apply(second) - target.acceleration).coefficients();
        let columns = velocity_basis::<A>().map(|basis| apply(commute(basis, pinned)).coefficients());
        for (i, ((&e, &de), &b)) in position
            .as_ref()
            .iter()
            .zip(velocity_residual.as_ref())
            .zip(bias.as_ref())
            .enumerate()
        {
            rows.push(ConstraintRow {
                jacobian: std::array::from_fn(|j| columns[j].as_ref()[i]),
                velocity_residual: de,
                bias: b,
                position_residual: Some(e),
            });
        }
        Ok(())
    }
}

/// A body point (body coordinates) pinned to a world point: a ball joint, rank 3 (theory §7 table). The pinned
/// objects are [`PinningAlgebra::PinnedPoint`]s (in CGA flat points).
///
/// The same ball joint in CGA and PGA: a pendulum's top end held at the origin, and its weight carried by the pivot
/// (the reaction on a body hanging at rest is `m g` up).
///
/// ```
/// use dynamics::constraints::pinning;
/// use dynamics::{Algebra, Body, Cga, Force, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let rod = Body::rod(2.0, 1.0, 1e-3)?; // 2 kg, 1 m
/// let top = Vector3::new(0.0, 0.0, 0.5); // body point, m
/// let still = UnitQuaternion::identity();
/// let pga = Mechanism::<Pga>::single(rod).with_force(Force::gravity())?
///     .with_constraint(pinning::point::<Pga>("pivot", top, Vector3::zeros()))?;
/// let cga = Mechanism::<Cga>::single(rod).with_force(Force::gravity())?
///     .with_constraint(pinning::point::<Cga>("pivot", top, Vector3::zeros()))?;
/// let hanging_pga = State::<Pga>::new(&rod, -top, &still, Vector3::zeros(), Vector3::zeros());
/// let hanging_cga = State::<Cga>::new(&rod, -top, &still, Vector3::zeros(), Vector3::zeros());
/// let up = Pga::screw_coordinates(pga.reactions(0.0, &[hanging_pga])?[0]).l;
/// assert!((up - Vector3::new(0.0, 0.0, 2.0 * 9.81)).norm() < 1e-12); // N
/// assert!((Cga::screw_coordinates(cga.reactions(0.0, &[hanging_cga])?[0]).l - up).norm() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn point<A: PinningAlgebra>(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    world_point: Vector3<f64>,
) -> Pin<A, A::PinnedPoint> {
    Pin::new(name, A::pinned_point(body_point), A::pinned_point(world_point), 3)
}

/// A body line pinned to a world line: a **cylindrical** joint, rank 4 — the body may slide along and turn
/// about the line (theory §7 table, E7). Directions need not be unit but must have equal lengths (to 1e-12
/// relative): a line's coefficients scale with its direction, and lines of different weights cannot be pinned
/// together (the pivot then drifts, 0.25–0.30 m in a test); points and directions must be finite, directions
/// nonzero.
///
/// ```
/// use dynamics::constraints::{pinning, Constraint};
/// use dynamics::{Body, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// // The body's z axis on the world line through (1, 0, 0) along z.
/// let slide = pinning::line::<Pga>("sleeve", (Vector3::zeros(), Vector3::z()), (Vector3::x(), Vector3::z()))?;
/// assert_eq!(slide.rank(), 4);
/// let sleeve = Body::cylinder(1.0, 0.05, 0.3)?;
/// let system = Mechanism::single(sleeve).with_constraint(slide)?;
/// // Slid 0.7 m up the line and turned about it, sliding and spinning: on the joint.
/// let turned = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, 1.2));
/// let (centre, spin) = (Vector3::new(1.0, 0.0, 0.7), Vector3::z() * 3.0); // m, rad/s
/// let state = State::from_world_twist(&sleeve, centre, &turned, spin, Vector3::z());
/// let on = system.violation(0.0, &[state])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// // Directions of different lengths would pin lines of different weights.
/// assert!(pinning::line::<Pga>("bad", (Vector3::zeros(), Vector3::z() * 2.0), (Vector3::x(), Vector3::z())).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn line<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_point, body_direction): (Vector3<f64>, Vector3<f64>),
    (world_point, world_direction): (Vector3<f64>, Vector3<f64>),
) -> Result<Pin<A, A::LineObject>, ConstraintError> {
    let name = name.into();
    let invalid = |reason: String| ConstraintError::InvalidParameter {
        name: name.clone(),
        reason,
    };
    let finite = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
    if !(finite(&body_point) && finite(&world_point) && finite(&body_direction) && finite(&world_direction)) {
        return Err(invalid("the line points and directions must be finite".to_owned()));
    }
    let (body_length, world_length) = (body_direction.norm(), world_direction.norm());
    if !(body_length.is_finite() && world_length.is_finite()) {
        return Err(invalid(format!(
            "the line directions' lengths {body_length} and {world_length} must be finite"
        )));
    }
    if body_length == 0.0 || world_length == 0.0 {
        return Err(invalid("a line direction is zero".to_owned()));
    }
    if (body_length - world_length).abs() > 1e-12 * body_length.max(world_length) {
        return Err(invalid(format!(
            "the body direction has length {body_length} and the world direction {world_length}: pinned lines \
             need equal weights (scale one direction, or make both unit)"
        )));
    }
    Ok(Pin::new(
        name,
        A::line_object(body_point, body_direction),
        A::line_object(world_point, world_direction),
        4,
    ))
}

/// A body plane `{x : n·x = δ}` (body frame) pinned to a world plane: a planar joint, rank 3. The normals need not
/// be unit (each plane is scaled to a unit normal, pinned planes needing equal weights) but must be finite and
/// nonzero, the offsets finite: a zero normal is no plane, and would pin nothing.
///
/// A puck on the floor: its bottom face, the body plane z = −0.02 m, pinned to the world plane z = 0; it slides
/// and turns on the floor.
///
/// ```
/// use dynamics::constraints::{pinning, Constraint};
/// use dynamics::{Body, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let face = pinning::plane::<Pga>("on the floor", (Vector3::z(), -0.02), (Vector3::z(), 0.0))?;
/// assert_eq!(face.rank(), 3);
/// assert!(pinning::plane::<Pga>("no plane", (Vector3::zeros(), 0.0), (Vector3::z(), 0.0)).is_err());
/// let puck = Body::cylinder(0.2, 0.04, 0.04)?;
/// let system = Mechanism::single(puck).with_constraint(face)?;
/// let turned = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, 2.0));
/// let (centre, spin) = (Vector3::new(1.0, -2.0, 0.02), Vector3::z() * 5.0); // m, rad/s
/// let state = State::from_world_twist(&puck, centre, &turned, spin, Vector3::x());
/// let on = system.violation(0.0, &[state])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-13); // round-off
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plane<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_normal, body_offset): (Vector3<f64>, f64),
    (world_normal, world_offset): (Vector3<f64>, f64),
) -> Result<Pin<A, A::PlaneObject>, ConstraintError> {
    let name = name.into();
    let unit = |side: &str, normal: Vector3<f64>, offset: f64| match direction_and_length(normal) {
        Some((unit, length)) if offset.is_finite() => Ok((unit, offset / length)),
        _ => Err(ConstraintError::InvalidParameter {
            name: name.clone(),
            reason: format!(
                "the {side} plane needs a finite nonzero normal and a finite offset, got {normal:?} and {offset:?}"
            ),
        }),
    };
    let (body_normal, body_offset) = unit("body", body_normal, body_offset)?;
    let (world_normal, world_offset) = unit("world", world_normal, world_offset)?;
    Ok(Pin::new(
        name,
        A::plane_object(body_normal, body_offset),
        A::plane_object(world_normal, world_offset),
        3,
    ))
}

/// A hinge: the body line through `body_point` along `body_axis` pinned to the world line through
/// `world_point` along `world_axis`, plus the point itself; rank 5 (theory §7 table, E7). Axes are normalised.
///
/// A door hinged about the world z axis at its edge (as [`VirtualPower::hinge`], by pinning): swinging about the axis
/// keeps the hinge; a tilt of 0.1 rad about x tilts the pinned line, whose direction is then off by sin 0.1. Being
/// normalised, the axes need not have equal lengths as [`line()`]'s directions must; a zero axis is an error.
///
/// [`VirtualPower::hinge`]: crate::constraints::VirtualPower::hinge
///
/// ```
/// use dynamics::constraints::{pinning, Constraint};
/// use dynamics::{Body, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let door = Body::cuboid(20.0, Vector3::new(0.8, 0.04, 2.0))?; // kg; m
/// let edge = Vector3::new(-0.4, 0.0, 0.0); // body point on the hinge line, m
/// let hinge = pinning::hinge::<Pga>("hinge", (edge, Vector3::z()), (Vector3::zeros(), Vector3::z() * 2.0))?;
/// assert_eq!(hinge.rank(), 5);
/// let system = Mechanism::single(door).with_constraint(hinge)?;
/// let state = |turn: Vector3<f64>, spin: Vector3<f64>| {
///     let rotation = UnitQuaternion::from_scaled_axis(turn);
///     let centre = -(rotation * edge);
///     State::from_world_twist(&door, centre, &rotation, spin, spin.cross(&centre))
/// };
/// let open = system.violation(0.0, &[state(Vector3::z() * 1.2, Vector3::z() * 0.5)])?; // rad, rad/s
/// assert!(open.position < 1e-15 && open.velocity < 1e-15);
/// let tilted = system.violation(0.0, &[state(Vector3::x() * 0.1, Vector3::zeros())])?;
/// assert!((tilted.position - 0.1f64.sin()).abs() < 1e-15);
/// assert!(pinning::hinge::<Pga>("no axis", (edge, Vector3::zeros()), (Vector3::zeros(), Vector3::z())).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn hinge<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
    (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
) -> Result<Composite<A>, ConstraintError> {
    let name = name.into();
    let (body_axis, world_axis) = (
        unit(&name, "hinge axis", body_axis)?,
        unit(&name, "hinge axis", world_axis)?,
    );
    let parts: Vec<Arc<dyn Constraint<A>>> = vec![
        Arc::new(line::<A>(
            format!("{name}: line"),
            (body_point, body_axis),
            (world_point, world_axis),
        )?),
        Arc::new(point::<A>(format!("{name}: point"), body_point, world_point)),
    ];
    Ok(Composite::new(name, parts, 5))
}

/// A prismatic joint (slider): the body line through `body_point` along `body_axis` pinned to the world line through
/// `world_point` along `world_axis` (a cylindrical joint), plus the body plane through the point with normal
/// `body_normal` pinned to the world plane with normal `world_normal` (each normal's part along its axis is
/// removed, so the plane contains the line and blocks only the turn about it): the body slides along the axis
/// without turning.
/// Rank 5 (4 + 1).
///
/// A carriage on a rail along world x (as [`VirtualPower::prismatic`], by pinning): sliding keeps the joint; a roll
/// of 0.2 rad about the rail keeps the line but turns the plane's normal by 0.2 rad, a violation of sin 0.2. A
/// normal along its axis has no part normal to it and is an error.
///
/// [`VirtualPower::prismatic`]: crate::constraints::VirtualPower::prismatic
///
/// ```
/// use dynamics::constraints::{pinning, Constraint};
/// use dynamics::{Body, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let carriage = Body::cuboid(2.0, Vector3::new(0.3, 0.2, 0.1))?;
/// let (x, z) = (Vector3::x(), Vector3::z());
/// let rail = pinning::prismatic::<Pga>("rail", (Vector3::zeros(), x, z), (Vector3::zeros(), x, z))?;
/// assert_eq!(rail.rank(), 5);
/// let system = Mechanism::single(carriage).with_constraint(rail)?;
/// let still = UnitQuaternion::identity();
/// let sliding = State::new(&carriage, x * 1.5, &still, Vector3::zeros(), x * 2.0); // m, m/s
/// let on = system.violation(0.0, &[sliding])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// let rolled = UnitQuaternion::from_scaled_axis(x * 0.2);
/// let off = State::new(&carriage, x * 1.5, &rolled, Vector3::zeros(), Vector3::zeros());
/// assert!((system.violation(0.0, &[off])?.position - 0.2f64.sin()).abs() < 1e-15);
/// assert!(pinning::prismatic::<Pga>("bad", (Vector3::zeros(), x, x), (Vector3::zeros(), x, z)).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn prismatic<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_point, body_axis, body_normal): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
    (world_point, world_axis, world_normal): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
) -> Result<Composite<A>, ConstraintError> {
    let name = name.into();
    let unit = |what: &str, v: Vector3<f64>| unit(&name, what, v);
    let (body_axis, world_axis) = (unit("body axis", body_axis)?, unit("world axis", world_axis)?);
    let body_normal = unit("body normal", body_normal - body_axis * body_axis.dot(&body_normal))?;
    let world_normal = unit(
        "world normal",
        world_normal - world_axis * world_axis.dot(&world_normal),
    )?;
    let parts: Vec<Arc<dyn Constraint<A>>> = vec![
        Arc::new(line::<A>(
            format!("{name}: line"),
            (body_point, body_axis),
            (world_point, world_axis),
        )?),
        Arc::new(plane::<A>(
            format!("{name}: plane"),
            (body_normal, body_normal.dot(&body_point)),
            (world_normal, world_normal.dot(&world_point)),
        )?),
    ];
    Ok(Composite::new(name, parts, 5))
}

/// A motor joint by pinning: the body's motor relative to the reference follows `path` (U(t), theory §8). The
/// body's x and z axes (lines through its origin) are pinned to their images carried by the path
/// ([`CarriedPath`]): two lines that meet fix all six degrees of freedom. Rank 6.
///
/// A turntable (as [`VirtualPower::motor_joint`], by pinning): the body's motor follows a turn about z at 1 rad/s.
/// A body on the path, turning with it, has zero violation; 0.1 rad behind, its x axis is off by sin 0.1; stopped
/// on the path, the axis falls behind at 1 rad/s.
///
/// [`VirtualPower::motor_joint`]: crate::constraints::VirtualPower::motor_joint
///
/// ```
/// use dynamics::constraints::{pinning, Constraint, PathPoint, ScrewMotion};
/// use dynamics::{motor, Algebra, Body, Mechanism, Pga, ScrewCoordinates, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let about_z = Pga::screw(ScrewCoordinates { l: Vector3::z(), t: Vector3::zeros() });
/// let theta = |t: f64| PathPoint { value: t, rate: 1.0, acceleration: 0.0 }; // rad
/// let path = ScrewMotion::<Pga, _>::new(motor::identity::<Pga>(), about_z, theta);
/// let turntable = pinning::motor_joint("turntable", path);
/// assert_eq!((turntable.rank(), turntable.row_count()), (6, 12)); // two PGA lines of 6 coefficients
/// let disc = Body::cylinder(1.0, 0.3, 0.02)?;
/// let system = Mechanism::single(disc).with_constraint(turntable)?;
/// let at = |angle: f64, rate: f64| {
///     let turned = UnitQuaternion::from_scaled_axis(Vector3::z() * angle);
///     State::from_body_twist(&disc, Vector3::zeros(), &turned, Vector3::z() * rate, Vector3::zeros())
/// };
/// let on = system.violation(0.5, &[at(0.5, 1.0)])?; // t = 0.5 s: turned by 0.5 rad at 1 rad/s
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// assert!((system.violation(0.5, &[at(0.4, 1.0)])?.position - 0.1f64.sin()).abs() < 1e-15);
/// assert!((system.violation(0.5, &[at(0.5, 0.0)])?.velocity - 1.0).abs() < 1e-15); // rad/s
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn motor_joint<A: PinningAlgebra>(name: impl Into<String>, path: impl MotorPath<A> + 'static) -> Composite<A> {
    let name = name.into();
    let path: Arc<dyn MotorPath<A>> = Arc::new(path);
    let axis = |direction: Vector3<f64>| -> Arc<dyn Constraint<A>> {
        let line = A::line_object(Vector3::zeros(), direction);
        Arc::new(Pin::with_paths(
            format!("{name}: line {direction:?}"),
            Fixed(line),
            CarriedPath::shared(line, path.clone()),
            4,
        ))
    };
    let parts = vec![axis(Vector3::x()), axis(Vector3::z())];
    Composite::new(name, parts, 6)
}

/// A body point pinned to a world point moving along `pivot(t)` (value, velocity, acceleration): a driven
/// pivot (theory §8), exact through a [`TranslatedPath`] of the pinned point at the origin.
///
/// The top of a rod held to a pivot that moves along a circle of radius 0.1 m at 2 rad/s; a rod carried along
/// with the pivot keeps the joint.
///
/// ```
/// use dynamics::constraints::{pinning, PathPoint};
/// use dynamics::{Body, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let pivot = |t: f64| PathPoint {
///     value: Vector3::new((2.0 * t).cos(), (2.0 * t).sin(), 0.0) * 0.1,
///     rate: Vector3::new(-(2.0 * t).sin(), (2.0 * t).cos(), 0.0) * 0.2,
///     acceleration: Vector3::new((2.0 * t).cos(), (2.0 * t).sin(), 0.0) * -0.4,
/// };
/// let rod = Body::rod(1.0, 1.0, 1e-3)?;
/// let top = Vector3::new(0.0, 0.0, 0.5);
/// let shaken = Mechanism::single(rod).with_constraint(pinning::driven_point::<Pga>("shaker", top, pivot))?;
/// let t = 0.3; // s
/// let p = pivot(t);
/// let state = State::new(&rod, p.value - top, &UnitQuaternion::identity(), Vector3::zeros(), p.rate);
/// let on = shaken.violation(t, &[state])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn driven_point<A: PinningAlgebra>(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    pivot: impl Path<Vector3<f64>> + 'static,
) -> Pin<A, A::PinnedPoint> {
    let pivot = TranslatedPath::new(A::pinned_point(Vector3::zeros()), pivot);
    Pin::with_paths(name, Fixed(A::pinned_point(body_point)), pivot, 3)
}

/// An attachment point sliding on the body along `attachment(t)` (body coordinates), pinned to a fixed
/// world point (theory §8).
///
/// A bead fixed in the world at the origin, threaded on a rod: the attachment point slides along the rod's axis
/// at 0.2 m/s, so the rod moves the other way at 0.2 m/s.
///
/// ```
/// use dynamics::constraints::{pinning, PathPoint};
/// use dynamics::{Body, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let along = |t: f64| PathPoint {
///     value: Vector3::new(0.0, 0.0, 0.2 * t - 0.5),
///     rate: Vector3::z() * 0.2,
///     acceleration: Vector3::zeros(),
/// };
/// let rod = Body::rod(1.0, 1.0, 1e-3)?;
/// let bead = pinning::sliding_attachment::<Pga>("bead", along, Vector3::zeros());
/// let threaded = Mechanism::single(rod).with_constraint(bead)?;
/// // At t = 1 s the attachment is at body z = −0.3 m: the rod's centre is 0.3 m above the bead.
/// let still = UnitQuaternion::identity();
/// let state = State::new(&rod, Vector3::z() * 0.3, &still, Vector3::zeros(), Vector3::z() * -0.2);
/// let on = threaded.violation(1.0, &[state])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn sliding_attachment<A: PinningAlgebra>(
    name: impl Into<String>,
    attachment: impl Path<Vector3<f64>> + 'static,
    world_point: Vector3<f64>,
) -> Pin<A, A::PinnedPoint> {
    Pin::with_paths(
        name,
        TranslatedPath::new(A::pinned_point(Vector3::zeros()), attachment),
        Fixed(A::pinned_point(world_point)),
        3,
    )
}

/// CGA: a body sphere (centre in body coordinates) pinned to a world sphere of the same radius: the
/// centre is pinned, rank 3 (theory §7 table).
///
/// ```
/// use dynamics::constraints::{pinning, Constraint};
/// use dynamics::{Body, Cga, Mechanism, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// // A ball (radius 0.1 m) about the body point (0, 0, 0.5) held in a world socket about the origin.
/// let socket = pinning::cga_sphere_pin("socket", Vector3::new(0.0, 0.0, 0.5), Vector3::zeros(), 0.1);
/// assert_eq!(socket.rank(), 3);
/// let arm = Body::rod(1.0, 1.0, 1e-3)?;
/// let system = Mechanism::single(arm).with_constraint(socket)?;
/// let turned = UnitQuaternion::from_scaled_axis(Vector3::new(0.5, 0.2, 0.0));
/// let centre = -(turned * Vector3::new(0.0, 0.0, 0.5));
/// let on = system.violation(0.0, &[State::new(&arm, centre, &turned, Vector3::zeros(), Vector3::zeros())])?;
/// assert!(on.position < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cga_sphere_pin(
    name: impl Into<String>,
    body_centre: Vector3<f64>,
    world_centre: Vector3<f64>,
    radius: f64,
) -> Pin<Cga, cga_types::Quadvector> {
    Pin::new(
        name,
        cga_sphere(body_centre, radius),
        cga_sphere(world_centre, radius),
        3,
    )
}

/// CGA: a body circle pinned to a world circle of the same radius: only rotation about the circle's axis
/// remains, rank 5 (theory §7 table).
///
/// A wheel's rim (radius 0.3 m in its body xy plane) pinned to a world circle in the plane y = 0 (normal y): the
/// wheel may only spin about the circle's axis.
///
/// ```
/// use dynamics::constraints::{pinning, Constraint};
/// use dynamics::{Body, Cga, Mechanism, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let rim = pinning::cga_circle_pin("rim", (Vector3::zeros(), Vector3::z()), (Vector3::z(), Vector3::y()), 0.3);
/// assert_eq!(rim.rank(), 5);
/// let wheel = Body::cylinder(2.0, 0.3, 0.05)?;
/// let system = Mechanism::single(wheel).with_constraint(rim)?;
/// // Body z along world y (a quarter turn about x), then any turn about that axis, spinning about it.
/// let upright = UnitQuaternion::from_scaled_axis(Vector3::new(-std::f64::consts::FRAC_PI_2, 0.0, 0.0));
/// let turned = UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.7, 0.0)) * upright;
/// let spinning = State::from_world_twist(&wheel, Vector3::z(), &turned, Vector3::y() * 4.0, Vector3::zeros());
/// let on = system.violation(0.0, &[spinning])?;
/// assert!(on.position < 1e-14 && on.velocity < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cga_circle_pin(
    name: impl Into<String>,
    (body_centre, body_normal): (Vector3<f64>, Vector3<f64>),
    (world_centre, world_normal): (Vector3<f64>, Vector3<f64>),
    radius: f64,
) -> Pin<Cga, cga_types::Trivector> {
    Pin::new(
        name,
        cga_circle(body_centre, radius, body_normal),
        cga_circle(world_centre, radius, world_normal),
        5,
    )
}
