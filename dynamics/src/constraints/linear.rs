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
