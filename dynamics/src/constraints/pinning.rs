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
use crate::constraints::paths::{moving_point, CarriedPath, Fixed, MotorPath, Path};
use crate::constraints::rows::{ConstraintRow, RowBuffer};
use crate::constraints::{Composite, Constraint, ConstraintError};

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
    pub fn new(name: impl Into<String>, body: X, world: X, rank: usize) -> Self {
        Pin::with_paths(name, Fixed(body), Fixed(world), rank)
    }

    /// A body path U(t) pinned to a world path V(t) (theory §8).
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

/// A body point (body coordinates) pinned to a world point: a ball joint, rank 3 (theory §7 table).
pub fn point<A: PinningAlgebra>(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    world_point: Vector3<f64>,
) -> Pin<A, A::PointObject> {
    Pin::new(name, A::point_object(body_point), A::point_object(world_point), 3)
}

/// A body line pinned to a world line: a **cylindrical** joint, rank 4 — the body may slide along and turn
/// about the line (theory §7 table, E7). Directions need not be unit but must have equal lengths (to 1e-12
/// relative): a line's coefficients scale with its direction, and lines of different weights cannot be pinned
/// together (the pivot then drifts, 0.25–0.30 m in a test); points and directions must be finite, directions
/// nonzero.
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

/// A body plane `{x : n·x = δ}` (body frame) pinned to a world plane: a planar joint, rank 3.
pub fn plane<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_normal, body_offset): (Vector3<f64>, f64),
    (world_normal, world_offset): (Vector3<f64>, f64),
) -> Pin<A, A::PlaneObject> {
    Pin::new(
        name,
        A::plane_object(body_normal, body_offset),
        A::plane_object(world_normal, world_offset),
        3,
    )
}

/// A hinge: the body line through `body_point` along `body_axis` pinned to the world line through
/// `world_point` along `world_axis`, plus the point itself; rank 5 (theory §7 table, E7). Axes are normalised.
pub fn hinge<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_point, body_axis): (Vector3<f64>, Vector3<f64>),
    (world_point, world_axis): (Vector3<f64>, Vector3<f64>),
) -> Result<Composite<A>, ConstraintError> {
    let name = name.into();
    let unit = |axis: Vector3<f64>| {
        axis.try_normalize(0.0)
            .ok_or_else(|| ConstraintError::InvalidParameter {
                name: name.clone(),
                reason: format!("hinge axis {axis:?} has no direction"),
            })
    };
    let (body_axis, world_axis) = (unit(body_axis)?, unit(world_axis)?);
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
/// `body_normal` pinned to the world plane with normal `world_normal` (both normal to their axes, so the plane
/// contains the line and blocks only the turn about it): the body slides along the axis without turning.
/// Rank 5 (4 + 1).
pub fn prismatic<A: PinningAlgebra>(
    name: impl Into<String>,
    (body_point, body_axis, body_normal): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
    (world_point, world_axis, world_normal): (Vector3<f64>, Vector3<f64>, Vector3<f64>),
) -> Result<Composite<A>, ConstraintError> {
    let name = name.into();
    let unit = |what: &str, v: Vector3<f64>| {
        v.try_normalize(0.0)
            .filter(|u| u.iter().all(|c| c.is_finite()))
            .ok_or_else(|| ConstraintError::InvalidParameter {
                name: name.clone(),
                reason: format!("{what} {v:?} has no direction"),
            })
    };
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
        )),
    ];
    Ok(Composite::new(name, parts, 5))
}

/// A motor joint by pinning: the body's motor relative to the reference follows `path` (U(t), theory §8). The
/// body's x and z axes (lines through its origin) are pinned to their images carried by the path
/// ([`CarriedPath`]): two lines that meet fix all six degrees of freedom. Rank 6.
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
/// pivot (theory §8), exact through [`moving_point`].
pub fn driven_point<A: PinningAlgebra>(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    pivot: impl Path<Vector3<f64>> + 'static,
) -> Pin<A, A::PointObject> {
    Pin::with_paths(name, Fixed(A::point_object(body_point)), moving_point::<A, _>(pivot), 3)
}

/// An attachment point sliding on the body along `attachment(t)` (body coordinates), pinned to a fixed
/// world point (theory §8).
pub fn sliding_attachment<A: PinningAlgebra>(
    name: impl Into<String>,
    attachment: impl Path<Vector3<f64>> + 'static,
    world_point: Vector3<f64>,
) -> Pin<A, A::PointObject> {
    Pin::with_paths(
        name,
        moving_point::<A, _>(attachment),
        Fixed(A::point_object(world_point)),
        3,
    )
}

/// CGA: a body sphere (centre in body coordinates) pinned to a world sphere of the same radius: the
/// centre is pinned, rank 3 (theory §7 table).
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
