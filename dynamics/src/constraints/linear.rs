//! Pinning linear functions of multivectors (`docs/theory.md` §9): `A[~R V(t) R] = U(t)` with A linear and fixed in
//! the body frame. The incidence constraints "body point P on a world object X" are `A[X] = P ∧ X = 0`, which
//! constrains fewer degrees of freedom than pinning X itself (theory §9 table).

use nalgebra::Vector3;

use crate::algebra::Algebra;
use crate::cga::{generated as cga_types, Cga};
use crate::constraints::objects::{cga_circle, cga_sphere, PinningAlgebra};
use crate::constraints::paths::{Fixed, Path, TranslatedPath};
use crate::constraints::pinning::{LinearFunction, Pin};
use crate::constraints::Coefficients;

/// `P ∧ X = 0` with the target U = 0 at rest.
fn incidence_target<Y: Coefficients>() -> Fixed<Y> {
    Fixed(Y::zero())
}

/// The body point `body_point` (body coordinates) stays on the world plane `{x : normal·x = offset}`:
/// `P ∧ X = 0`, rank 1 (theory §9 table), in either algebra.
///
/// A rod's foot kept on the floor z = 0.5 m, in both algebras: one row, rank 1. The foot anywhere on the floor, the rod
/// tilted and sliding, keeps it; lifted 0.1 m and rising at 1 m/s, the residual is the height, 0.1 m, and its rate
/// 1 m/s. (That is for a unit normal: `P ∧ X` scales with the normal's length, unlike
/// [`VirtualPower::point_on_plane`]'s residual.)
///
/// [`VirtualPower::point_on_plane`]: crate::constraints::VirtualPower::point_on_plane
///
/// ```
/// use dynamics::constraints::{linear, Constraint};
/// use dynamics::{Body, Cga, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let rod = Body::rod(1.0, 1.0, 1e-3)?;
/// let foot = Vector3::new(0.0, 0.0, -0.5); // body point, m
/// let floor = (Vector3::z(), 0.5); // (unit normal, offset m): z = 0.5 m
/// let in_pga = linear::point_on_plane::<Pga>("foot", foot, floor);
/// assert_eq!((in_pga.rank(), in_pga.row_count()), (1, 1));
/// let pga = Mechanism::single(rod).with_constraint(in_pga)?;
/// let cga = Mechanism::single(rod).with_constraint(linear::point_on_plane::<Cga>("foot", foot, floor))?;
/// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.2, 0.0));
/// let centre = Vector3::new(3.0, -1.0, 0.5) - tilt * foot; // the foot on the floor
/// let (lifted, sliding, rising) = (centre + Vector3::z() * 0.1, Vector3::x(), Vector3::z()); // m, m/s
/// let on = pga.violation(0.0, &[State::new(&rod, centre, &tilt, Vector3::zeros(), sliding)])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// let on = cga.violation(0.0, &[State::new(&rod, centre, &tilt, Vector3::zeros(), sliding)])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-14); // round-off
/// let off = pga.violation(0.0, &[State::new(&rod, lifted, &tilt, Vector3::zeros(), rising)])?;
/// assert!((off.position - 0.1).abs() < 1e-15 && (off.velocity - 1.0).abs() < 1e-15);
/// let off = cga.violation(0.0, &[State::new(&rod, lifted, &tilt, Vector3::zeros(), rising)])?;
/// assert!((off.position - 0.1).abs() < 1e-14 && (off.velocity - 1.0).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn point_on_plane<A: PinningAlgebra>(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    (normal, offset): (Vector3<f64>, f64),
) -> Pin<A, A::PlaneObject, A::Incidence> {
    let point = A::point_object(body_point);
    Pin::linear(
        name,
        incidence_target(),
        LinearFunction::new(move |plane| A::point_plane_incidence(point, plane)),
        Fixed(A::plane_object(normal, offset)),
        1,
    )
}

/// The body point `body_point` stays on the world line through `line_point` along `direction`: the point–line
/// incidence is zero (theory §9 table: CGA `P ∧ L`, PGA `L × P`), rank 2, in either algebra.
///
/// A rod's end kept on the line through (0, 0, 1) along x: rank 2, with one row per coefficient of the incidence (4 of
/// a PGA trivector, 5 of a CGA 4-vector). The end anywhere on the line, the rod tilted and sliding along it, keeps
/// it; the end 0.1 m above the line is off by 0.1 m in both algebras (for a unit direction; the upright rod's body
/// axes are the world's, so the body-frame coefficients are the world's).
///
/// ```
/// use dynamics::constraints::{linear, Constraint};
/// use dynamics::{Body, Cga, Mechanism, Pga, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let rod = Body::rod(1.0, 1.0, 1e-3)?;
/// let end = Vector3::new(0.0, 0.0, 0.5); // body point, m
/// let rail = (Vector3::z(), Vector3::x()); // (point, unit direction)
/// let in_pga = linear::point_on_line::<Pga>("end", end, rail);
/// let in_cga = linear::point_on_line::<Cga>("end", end, rail);
/// assert_eq!((in_pga.rank(), in_pga.row_count(), in_cga.rank(), in_cga.row_count()), (2, 4, 2, 5));
/// let pga = Mechanism::single(rod).with_constraint(in_pga)?;
/// let cga = Mechanism::single(rod).with_constraint(in_cga)?;
/// let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.6, 0.1));
/// let centre = Vector3::new(0.7, 0.0, 1.0) - tilt * end; // the end 0.7 m along the line
/// let on = pga.violation(0.0, &[State::new(&rod, centre, &tilt, Vector3::zeros(), Vector3::x())])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// let on = cga.violation(0.0, &[State::new(&rod, centre, &tilt, Vector3::zeros(), Vector3::x())])?;
/// assert!(on.position < 1e-14 && on.velocity < 1e-14); // round-off
/// let upright = UnitQuaternion::identity();
/// let above = Vector3::new(0.7, 0.0, 1.1) - end; // the end 0.1 m above the line
/// let off = pga.violation(0.0, &[State::new(&rod, above, &upright, Vector3::zeros(), Vector3::zeros())])?;
/// assert!((off.position - 0.1).abs() < 1e-15);
/// let off = cga.violation(0.0, &[State::new(&rod, above, &upright, Vector3::zeros(), Vector3::zeros())])?;
/// assert!((off.position - 0.1).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn point_on_line<A: PinningAlgebra>(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    (line_point, direction): (Vector3<f64>, Vector3<f64>),
) -> Pin<A, A::LineObject, A::LineIncidence> {
    let point = A::point_object(body_point);
    Pin::linear(
        name,
        incidence_target(),
        LinearFunction::new(move |line| A::point_line_incidence(point, line)),
        Fixed(A::line_object(line_point, direction)),
        2,
    )
}

/// CGA: the body point stays on the OPNS sphere (centre, radius): `P ∧ S = 0`, a 5-vector, rank 1 (theory §9).
///
/// A bob on a string of 1.5 m from (0, 0, 2): anywhere on the sphere, moving along it, the residual is zero; 1 m from
/// the centre it is `½(ρ² − |a − c|²)` = 0.625 m², as for [`VirtualPower::point_on_sphere`].
///
/// [`VirtualPower::point_on_sphere`]: crate::constraints::VirtualPower::point_on_sphere
///
/// ```
/// use dynamics::constraints::{linear, Constraint};
/// use dynamics::{Body, Mechanism, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let string = linear::cga_point_on_sphere("string", Vector3::zeros(), Vector3::z() * 2.0, 1.5);
/// assert_eq!((string.rank(), string.row_count()), (1, 1));
/// let bob = Body::sphere(1.0, 0.05)?;
/// let system = Mechanism::single(bob).with_constraint(string)?;
/// let (direction, still) = (Vector3::new(0.3, -0.4, -1.0).normalize(), UnitQuaternion::identity());
/// let at = |distance: f64, velocity: Vector3<f64>| {
///     State::new(&bob, Vector3::z() * 2.0 + direction * distance, &still, Vector3::zeros(), velocity)
/// };
/// let on = system.violation(0.0, &[at(1.5, direction.cross(&Vector3::z()))])?; // tangent, m/s
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// assert!((system.violation(0.0, &[at(1.0, Vector3::zeros())])?.position - 0.625).abs() < 1e-15); // m²
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cga_point_on_sphere(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    centre: Vector3<f64>,
    radius: f64,
) -> Pin<Cga, cga_types::Quadvector, cga_types::Pseudoscalar> {
    let point = Cga::point(body_point);
    Pin::linear(
        name,
        incidence_target(),
        LinearFunction::new(move |sphere| point ^ sphere),
        Fixed(cga_sphere(centre, radius)),
        1,
    )
}

/// CGA: the body point stays on a sphere of `radius` whose centre moves along `centre(t)`:
/// `V(t) = T(c(t)) S₀ ~T(c(t))` with S₀ at the origin (theory §8, §9 table), rank 1.
///
/// A bob on a string of 1.5 m whose top is carried along x at 1 m/s. A bob 0.9 m ahead of the top and 1.2 m below it,
/// moving with it, keeps the constraint; the same bob at rest breaks the velocity condition by the rate of
/// `½(ρ² − |a − c|²)`, `(a − c)·ċ` = 0.9 m²/s.
///
/// ```
/// use dynamics::constraints::{linear, Constraint, PathPoint};
/// use dynamics::{Body, Mechanism, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let carried = |t: f64| PathPoint {
///     value: Vector3::new(t, 0.0, 2.0),
///     rate: Vector3::x(),
///     acceleration: Vector3::zeros(),
/// };
/// let string = linear::cga_point_on_moving_sphere("string", Vector3::zeros(), carried, 1.5);
/// assert_eq!(string.rank(), 1);
/// let bob = Body::sphere(1.0, 0.05)?;
/// let system = Mechanism::single(bob).with_constraint(string)?;
/// let (t, still) = (0.7, UnitQuaternion::identity()); // s
/// let at = carried(t).value + Vector3::new(0.9, 0.0, -1.2); // 1.5 m from the top
/// let moving = system.violation(t, &[State::new(&bob, at, &still, Vector3::zeros(), Vector3::x())])?;
/// assert!(moving.position < 1e-15 && moving.velocity < 1e-15);
/// let left = system.violation(t, &[State::new(&bob, at, &still, Vector3::zeros(), Vector3::zeros())])?;
/// assert!(left.position < 1e-15 && (left.velocity - 0.9).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cga_point_on_moving_sphere(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    centre: impl Path<Vector3<f64>> + 'static,
    radius: f64,
) -> Pin<Cga, cga_types::Quadvector, cga_types::Pseudoscalar> {
    let point = Cga::point(body_point);
    Pin::linear(
        name,
        incidence_target(),
        LinearFunction::new(move |sphere| point ^ sphere),
        TranslatedPath::<Cga, _, _>::new(cga_sphere(Vector3::zeros(), radius), centre),
        1,
    )
}

/// CGA: the body point stays on the OPNS circle: `P ∧ C = 0`, a 4-vector with 5 coefficients and rank 2.
/// Off the circle the map picks up spurious small singular values (theory §7.1, E8), which the fixed-rank
/// solve ignores.
///
/// A bead on a ring of radius 0.5 m about (0, 0, 1) in a horizontal plane: 5 rows, rank 2. A bead going round the
/// ring is on it; at the ring's centre the residual is, up to sign, `½ρ²` times the ring's plane π (unit normal), a
/// violation of ½ρ² = 0.125 m².
///
/// ```
/// use dynamics::constraints::{linear, Constraint};
/// use dynamics::{Body, Mechanism, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let ring = linear::cga_point_on_circle("ring", Vector3::zeros(), (Vector3::z(), 0.5, Vector3::z()));
/// assert_eq!((ring.rank(), ring.row_count()), (2, 5));
/// let bead = Body::sphere(0.1, 0.01)?;
/// let system = Mechanism::single(bead).with_constraint(ring)?;
/// let (phi, still) = (0.8f64, UnitQuaternion::identity());
/// let at = Vector3::z() + Vector3::new(phi.cos(), phi.sin(), 0.0) * 0.5; // m
/// let along = Vector3::new(-phi.sin(), phi.cos(), 0.0) * 2.0; // tangent, m/s
/// let on = system.violation(0.0, &[State::new(&bead, at, &still, Vector3::zeros(), along)])?;
/// assert!(on.position < 1e-15 && on.velocity < 1e-15);
/// let centre = State::new(&bead, Vector3::z(), &still, Vector3::zeros(), Vector3::zeros());
/// assert!((system.violation(0.0, &[centre])?.position - 0.125).abs() < 1e-15); // m²
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cga_point_on_circle(
    name: impl Into<String>,
    body_point: Vector3<f64>,
    (centre, radius, normal): (Vector3<f64>, f64, Vector3<f64>),
) -> Pin<Cga, cga_types::Trivector, cga_types::Quadvector> {
    let point = Cga::point(body_point);
    Pin::linear(
        name,
        incidence_target(),
        LinearFunction::new(move |circle| point ^ circle),
        Fixed(cga_circle(centre, radius, normal)),
        2,
    )
}
