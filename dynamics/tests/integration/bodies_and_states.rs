//! Bodies and states in the user's terms: a body from a full inertia tensor about any point, from a
//! cylinder; states from a twist in world or in body axes; world momenta. Checked against classical formulas in
//! plain nalgebra, in both algebras.

use dynamics::{Algebra, Body, BodyError, Cga, Pga, State};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

fn tensor_of(body: &Body, rotation: &UnitQuaternion<f64>) -> Matrix3<f64> {
    let q = rotation.to_rotation_matrix();
    q.matrix() * Matrix3::from_diagonal(&body.moments()) * q.matrix().transpose()
}

/// A cuboid turned and moved in a part frame, its tensor given about a point that is not its centre: the
/// principal moments, axes and centre come back.
#[test]
fn a_full_inertia_tensor_about_any_point_is_diagonalised() {
    let cuboid = Body::cuboid(3.0, Vector3::new(0.2, 0.5, 1.1)).unwrap();
    let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(0.4, -0.9, 0.3));
    let centre = Vector3::new(0.3, -0.2, 0.8);
    let about = Vector3::new(-0.5, 0.1, 0.2);
    let d = centre - about;
    let given = tensor_of(&cuboid, &rotation) + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * 3.0;
    let (body, frame) = Body::from_inertia_tensor(3.0, given, about, centre).unwrap();
    assert_eq!(body.mass(), 3.0);
    assert_eq!(frame.centre_of_mass, centre);
    let mut found: Vec<f64> = body.moments().iter().copied().collect();
    let mut expected: Vec<f64> = cuboid.moments().iter().copied().collect();
    found.sort_by(f64::total_cmp);
    expected.sort_by(f64::total_cmp);
    for (f, e) in found.iter().zip(&expected) {
        assert!((f - e).abs() < 1e-14, "{found:?} vs {expected:?}");
    }
    // The principal frame reproduces the central tensor, and is a proper rotation.
    let difference = tensor_of(&body, &frame.rotation) - tensor_of(&cuboid, &rotation);
    assert!(difference.amax() < 1e-14, "{difference}");
    assert!((frame.rotation.to_rotation_matrix().matrix().determinant() - 1.0).abs() < 1e-14);
    // Placing the part places its body frame.
    let (position, orientation) = frame.body_pose(Vector3::new(1.0, 2.0, 3.0), &UnitQuaternion::identity());
    assert_eq!(position, Vector3::new(1.0, 2.0, 3.0) + centre);
    assert_eq!(orientation, frame.rotation);
}

#[test]
fn tensors_that_are_not_physical_are_refused() {
    let mut lopsided = Matrix3::identity();
    lopsided[(0, 1)] = 0.5;
    assert!(matches!(
        Body::from_inertia_tensor(1.0, lopsided, Vector3::zeros(), Vector3::zeros()),
        Err(BodyError::Tensor(_))
    ));
    assert!(matches!(
        Body::from_inertia_tensor(1.0, Matrix3::identity() * f64::NAN, Vector3::zeros(), Vector3::zeros()),
        Err(BodyError::Tensor(_))
    ));
    assert!(matches!(
        Body::from_inertia_tensor(
            1.0,
            Matrix3::identity(),
            Vector3::zeros(),
            Vector3::repeat(f64::INFINITY)
        ),
        Err(BodyError::Point(_))
    ));
    // About a point 2 m away, a unit tensor is less than the parallel-axis term: negative central moments.
    assert!(matches!(
        Body::from_inertia_tensor(1.0, Matrix3::identity(), Vector3::zeros(), Vector3::new(2.0, 0.0, 0.0)),
        Err(BodyError::Moments(_))
    ));
    assert_eq!(
        Body::from_inertia_tensor(-1.0, Matrix3::identity(), Vector3::zeros(), Vector3::zeros()),
        Err(BodyError::Mass(-1.0))
    );
}

/// The cylinder's moments at its limits: a thin rod (m h²/12 across) and a thin disc (m r²/4 across, m r²/2
/// along).
#[test]
fn a_cylinder_has_the_rod_and_disc_limits() {
    let rod = Body::cylinder(2.0, 1e-6, 3.0).unwrap();
    assert!((rod.moments().x - 2.0 * 9.0 / 12.0).abs() < 1e-11);
    let disc = Body::cylinder(2.0, 0.5, 1e-9).unwrap();
    assert!((disc.moments().x - 2.0 * 0.25 / 4.0).abs() < 1e-15);
    assert!((disc.moments().z - 2.0 * 0.25 / 2.0).abs() < 1e-15);
    assert!(matches!(Body::cylinder(1.0, 0.0, 1.0), Err(BodyError::Dimensions(_))));
}

fn twists_and_momenta<A: Algebra>() {
    let (body, _) = Body::from_inertia_tensor(
        1.5,
        Matrix3::new(0.3, 0.02, -0.01, 0.02, 0.4, 0.03, -0.01, 0.03, 0.5),
        Vector3::zeros(),
        Vector3::zeros(),
    )
    .unwrap();
    let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(-0.7, 0.2, 1.3));
    let position = Vector3::new(0.5, -1.0, 2.0);
    let (omega, v) = (Vector3::new(0.3, -2.0, 1.1), Vector3::new(-0.4, 0.6, 0.25));
    let world = State::<A>::from_world_twist(&body, position, &rotation, omega, v);
    let seen = world.world_velocity(&body);
    assert!((seen.angular - omega).norm() < 1e-14 && (seen.linear - v).norm() < 1e-14);
    let in_body = State::<A>::from_body_twist(
        &body,
        position,
        &rotation,
        rotation.inverse() * omega,
        rotation.inverse() * v,
    );
    let difference = A::screw_coordinates(in_body.central_momentum - world.central_momentum);
    assert!(difference.l.norm().max(difference.t.norm()) < 1e-14);
    let mixed = State::<A>::new(&body, position, &rotation, rotation.inverse() * omega, v);
    let difference = A::screw_coordinates(mixed.central_momentum - in_body.central_momentum);
    assert!(difference.l.norm().max(difference.t.norm()) < 1e-15);

    // Momenta against the classical formulas: p = m v, L = Q I Qᵀ ω about the centre, plus c × p about O.
    let momentum = world.world_momentum();
    let inertia = tensor_of(&body, &rotation);
    assert!((momentum.linear - 1.5 * v).norm() < 1e-14);
    assert!((momentum.angular_about_centre_of_mass - inertia * omega).norm() < 1e-14);
    let about_origin = inertia * omega + position.cross(&(1.5 * v));
    assert!((momentum.angular_about_origin - about_origin).norm() < 1e-13);
    let energy = 0.5 * (1.5 * v.norm_squared() + omega.dot(&(inertia * omega)));
    assert!((world.kinetic_energy(&body) - energy).abs() < 1e-14);
}

#[test]
fn twists_in_either_frame_and_world_momenta_in_pga() {
    twists_and_momenta::<Pga>();
}

#[test]
fn twists_in_either_frame_and_world_momenta_in_cga() {
    twists_and_momenta::<Cga>();
}

/// `State::momentum_about_origin` is theory §3's Ω: `(m v, I ω + c × m v)`, the same as `world_momentum`'s parts,
/// at the origin and 1e5 m out, while the state's own `central_momentum` does not depend on where the body is.
/// Careless states pass through without a panic: a NaN momentum gives NaN, a zero one zero, coordinates at the
/// largest the dynamics accepts stay finite.
fn momentum_about_origin<A: Algebra>() {
    let body = Body::cuboid(2.0, Vector3::new(0.1, 0.2, 0.3)).unwrap();
    let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 0.5));
    let (spin, velocity) = (Vector3::new(0.2, 1.0, 0.3), Vector3::new(1.0, -2.0, 0.5));
    let at = |position: Vector3<f64>| State::<A>::new(&body, position, &rotation, spin, velocity);
    for position in [Vector3::zeros(), Vector3::new(1e5, -3e4, 2e4)] {
        let state = at(position);
        let omega = A::screw_coordinates(state.momentum_about_origin());
        let classical = state.world_momentum();
        assert!((omega.l - classical.linear).norm() < 1e-15 * classical.linear.norm());
        assert!(
            (omega.t - classical.angular_about_origin).norm() <= 1e-15 * classical.angular_about_origin.norm(),
            "{position:?}"
        );
        let central = A::screw_coordinates(state.central_momentum);
        assert!((central.t - classical.angular_about_centre_of_mass).norm() < 1e-15);
    }
    let mut nan = at(Vector3::zeros());
    nan.central_momentum = nan.central_momentum * f64::NAN;
    assert!(A::screw_coordinates(nan.momentum_about_origin())
        .t
        .iter()
        .all(|x| x.is_nan()));
    let mut zero = at(Vector3::new(1.0, 2.0, 3.0));
    zero.central_momentum = zero.central_momentum * 0.0;
    assert_eq!(A::screw_coordinates(zero.momentum_about_origin()).t, Vector3::zeros());
    let largest = at(Vector3::new(1e24, -1e24, 1e24));
    let omega = A::screw_coordinates(largest.momentum_about_origin());
    assert!(omega.l.iter().chain(omega.t.iter()).all(|x| x.is_finite()), "{omega:?}");
}

#[test]
fn momentum_about_origin_in_pga() {
    momentum_about_origin::<Pga>();
}

#[test]
fn momentum_about_origin_in_cga() {
    momentum_about_origin::<Cga>();
}
