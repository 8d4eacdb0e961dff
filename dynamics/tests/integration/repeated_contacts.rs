//! Repeated and dependent contacts (docs/contacts.md "Repeated and dependent contacts"): a tumbling cube whose corners
//! are each listed fifty times moves, bounces, holds, sticks and slides exactly as with each corner once, in the same
//! steps; a cube with points all along its edges (rows that depend on the corners') lands as its corners alone make it
//! land, where the impacts' active sets used to cycle.

use dynamics::contacts::{Friction, PlaneContact};
use dynamics::{
    simulate, Algebra, Body, Force, JointMethod, Mechanism, Method, Schedule, Simulation, State, Tolerance,
};
use nalgebra::{Unit, UnitQuaternion, Vector3};

/// The cube's half side (m): a 0.2 m cube of 1 kg.
const HALF: f64 = 0.1;

fn cube() -> Body {
    Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap()
}

/// The cube under gravity with a contact above the floor z = 0 at each of `points` (body frame), each listed
/// `copies` times: the first of each named as a lone contact would be, so that transitions compare by name.
fn cube_with<A: Algebra>(points: &[Vector3<f64>], copies: usize, friction: f64) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("cube", cube()).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    for (k, point) in points.iter().enumerate() {
        let contact = PlaneContact::new(*point, Vector3::z(), 0.0)
            .unwrap()
            .with_restitution(0.5)
            .unwrap()
            .with_friction(if friction > 0.0 {
                Friction::coulomb(friction).unwrap()
            } else {
                Friction::NONE
            });
        for copy in 0..copies {
            let name = if copy == 0 {
                format!("point {k}")
            } else {
                format!("point {k} copy {copy}")
            };
            system.add_contact(name, id, contact).unwrap();
        }
    }
    system
}

fn corners() -> Vec<Vector3<f64>> {
    (0..8)
        .map(|k| Vector3::new([-HALF, HALF][k & 1], [-HALF, HALF][(k >> 1) & 1], [-HALF, HALF][k >> 2]))
        .collect()
}

/// `count` points along each of the cube's twelve edges, ends included, each point once.
fn edge_points(count: usize) -> Vec<Vector3<f64>> {
    let mut points = corners();
    for a in corners() {
        for b in corners() {
            // An edge joins corners that differ in one coordinate; each edge once (a before b).
            let differing = (0..3).filter(|&i| a[i] != b[i]).count();
            if differing == 1 && (0..3).all(|i| a[i] <= b[i]) {
                points.extend((1..count - 1).map(|s| a.lerp(&b, s as f64 / (count - 1) as f64)));
            }
        }
    }
    points
}

/// The tumbling drop of the shipped bouncing-block scene: 0.5 m up, turned 30° about (1, 0.3, 0), turning at (0, 2, 3)
/// rad/s in the body frame and moving at 0.5 m/s along x.
fn tumbling<A: Algebra>() -> State<A> {
    let turn = UnitQuaternion::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 0.3, 0.0)), 30f64.to_radians());
    let omega = turn * Vector3::new(0.0, 2.0, 3.0);
    State::from_world_twist(
        &cube(),
        Vector3::new(0.0, 0.0, 0.5),
        &turn,
        omega,
        Vector3::new(0.5, 0.0, 0.0),
    )
}

fn adaptive(duration: f64) -> Schedule {
    Schedule::adaptive(Tolerance::new(1e-10, 1e-10).unwrap(), duration, 0.01).unwrap()
}

/// The largest differences between two runs' samples: of the poses (positions in m, turns in rad) and of the
/// velocities (m/s, rad/s).
fn largest_differences<A: Algebra>(one: &Simulation<A>, other: &Simulation<A>) -> (f64, f64) {
    assert_eq!(one.body(0).len(), other.body(0).len());
    (one.body(0).iter().zip(other.body(0))).fold((0.0f64, 0.0f64), |(pose, speed), (a, b)| {
        let turn = (a.orientation.inverse() * b.orientation).angle();
        let rates = (a.velocity - b.velocity)
            .norm()
            .max((a.angular_velocity - b.angular_velocity).norm());
        (pose.max(turn).max((a.position - b.position).norm()), speed.max(rates))
    })
}

/// Fifty copies of each corner: the same samples to round-off, the same transitions (the copies never take one), and
/// the same steps and evaluations, by body-momentum and joint-coordinate steps with a tolerance (DOP853-body,
/// DOP853-joint) and joint-coordinate steps of 1 ms, with friction (the cube sticks and slides) and without.
fn fifty_copies_of_each_corner_change_nothing<A: Algebra>() {
    for friction in [0.0, 0.3] {
        let (once, fifty) = (
            cube_with::<A>(&corners(), 1, friction),
            cube_with::<A>(&corners(), 50, friction),
        );
        let start = [tumbling::<A>()];
        let runs = [
            (
                simulate(&once, &start, Method::Dop853Body, &adaptive(2.0)),
                simulate(&fifty, &start, Method::Dop853Body, &adaptive(2.0)),
            ),
            (
                simulate(&once, &start, JointMethod::Rkmk8, &Schedule::new(1e-3, 2.0).unwrap()),
                simulate(&fifty, &start, JointMethod::Rkmk8, &Schedule::new(1e-3, 2.0).unwrap()),
            ),
            (
                simulate(&once, &start, JointMethod::Dop853, &adaptive(2.0)),
                simulate(&fifty, &start, JointMethod::Dop853, &adaptive(2.0)),
            ),
        ];
        for (one, many) in runs {
            let (one, many) = (one.unwrap(), many.unwrap());
            assert!(one.transitions.len() > 20, "{} transitions", one.transitions.len());
            assert_eq!(one.transitions.len(), many.transitions.len(), "μ = {friction}");
            for (a, b) in one.transitions.iter().zip(&many.transitions) {
                assert_eq!((&a.constraint, a.t), (&b.constraint, b.t), "μ = {friction}");
                assert_eq!(format!("{:?}", a.change), format!("{:?}", b.change), "μ = {friction}");
            }
            let (pose, speed) = largest_differences(&one, &many);
            assert!(
                pose.max(speed) < 1e-12,
                "μ = {friction}: the runs differ by {pose:e}, {speed:e}"
            );
            assert_eq!(one.statistics.evaluations, many.statistics.evaluations);
        }
    }
}

/// Five points along each edge (44 contacts whose rows depend on the corners'): the tumbling cube bounces, lands and
/// slides as its eight corners alone make it (within 1e-10 over 1.5 s; the points' impacts are the corners', and a
/// point within the touching distance of the floor at a corner's impact takes part in it, which the corners alone
/// cannot), never below the floor, and the impacts never add energy.
fn points_along_the_edges_land_the_cube_as_its_corners_do<A: Algebra>() {
    let corners_only = cube_with::<A>(&corners(), 1, 0.0);
    let edges = cube_with::<A>(&edge_points(5), 1, 0.0);
    let start = [tumbling::<A>()];
    let reference = simulate(&corners_only, &start, Method::Dop853Body, &adaptive(1.5)).unwrap();
    let run = simulate(&edges, &start, Method::Dop853Body, &adaptive(1.5)).unwrap();
    let (pose, speed) = largest_differences(&reference, &run);
    assert!(pose < 1e-10 && speed < 1e-7, "the runs differ by {pose:e}, {speed:e}");
    assert!(run.transitions.len() > reference.transitions.len());
    assert!(
        run.transitions.iter().all(|t| t.energy_change <= 1e-12),
        "an impact added energy"
    );
    for sample in run.body(0) {
        let lowest = (edge_points(5).iter())
            .map(|p| (sample.position + sample.orientation * p).z)
            .fold(f64::INFINITY, f64::min);
        assert!(
            lowest > -1e-12,
            "a point {lowest:e} m below the floor at t = {}",
            sample.t
        );
    }
}

for_both_algebras!(
    fifty_copies_of_each_corner_change_nothing,
    points_along_the_edges_land_the_cube_as_its_corners_do,
);
