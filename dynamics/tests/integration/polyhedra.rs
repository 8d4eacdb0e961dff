//! Two convex polyhedra kept apart by all their feature pairs (docs/contacts.md "Edges"), against closed forms: a
//! cube dropped edge-first across another's edge lands on the crossing at `√(2h/g)` and balances there; a cube
//! sliding without friction off a ledge lets go of the ledge's top face with its leading corners as they pass the
//! edge at `(x_e − x₀ − a/2)/v₀`, rides on its bottom edges across the ledge's edge, and lets go with its trailing
//! corners when its centre passes the edge at `(x_e − x₀)/v₀`, then tips and falls off, keeping its energy and
//! never passing into the ledge; cubes dropped tumbling onto a box from seeded random starts never pass into it.

use dynamics::contacts::{Friction, Polyhedron, OUTSIDE_FACE};
use dynamics::limits::LimitChange;
use dynamics::{simulate, Algebra, Body, BodyId, Force, JointMethod, Mechanism, Method, Schedule, Simulation, State};
use nalgebra::{UnitQuaternion, Vector3};

use super::friction::adaptive;

const G: f64 = 9.81;
/// The cube's side (m) and mass (kg); the ledge's mass (kg): it is not moved by the cube.
const SIDE: f64 = 0.2;
const MASS: f64 = 1.0;
const HEAVY: f64 = 1e15;

/// A cube above a heavy box of `sides`, the cube under gravity, every feature pair of the two with `friction` and
/// `restitution`; the cube's and the box's ids.
fn cube_over<A: Algebra>(sides: Vector3<f64>, friction: Friction, restitution: f64) -> (Mechanism<A>, [BodyId; 2]) {
    let mut system = Mechanism::<A>::new();
    let cube = system
        .add_body("cube", Body::cuboid(MASS, Vector3::repeat(SIDE)).unwrap())
        .unwrap();
    let ledge = system.add_body("ledge", Body::cuboid(HEAVY, sides).unwrap()).unwrap();
    system.add_force(cube, Force::gravity()).unwrap();
    let shapes = (
        Polyhedron::cuboid(Vector3::repeat(SIDE)).unwrap(),
        Polyhedron::cuboid(sides).unwrap(),
    );
    system
        .add_polyhedron_contacts(
            "pair",
            (cube, &shapes.0, "cube"),
            (ledge, &shapes.1, "ledge"),
            friction,
            restitution,
        )
        .unwrap();
    (system, [cube, ledge])
}

fn placed<A: Algebra>(
    sides: Vector3<f64>,
    at: Vector3<f64>,
    turn: UnitQuaternion<f64>,
    velocity: Vector3<f64>,
) -> State<A> {
    State::from_world_twist(
        &Body::cuboid(MASS, sides).unwrap(),
        at,
        &turn,
        Vector3::zeros(),
        velocity,
    )
}

/// The transitions of `run` whose constraint names contain `part`, with their times.
fn changes<A: Algebra>(run: &Simulation<A>, part: &str) -> Vec<(f64, LimitChange)> {
    (run.transitions.iter())
        .filter(|t| t.constraint.contains(part))
        .map(|t| (t.t, t.change))
        .collect()
}

/// The deepest any vertex of either box goes inside the other at a sample of `run` (m; negative: apart).
fn deepest_vertex<A: Algebra>(run: &Simulation<A>, sides: [Vector3<f64>; 2]) -> f64 {
    let corners = |s: Vector3<f64>| Polyhedron::cuboid(s).unwrap().vertices().to_vec();
    let mut deepest = f64::NEG_INFINITY;
    for (first, second) in run.body(0).iter().zip(run.body(1)) {
        for (from, into, own, other) in [(first, second, sides[0], sides[1]), (second, first, sides[1], sides[0])] {
            for corner in corners(own) {
                let world = from.position + from.orientation * corner;
                let local = into.orientation.inverse() * (world - into.position);
                let depth = (0..3)
                    .map(|k| other[k] / 2.0 - local[k].abs())
                    .fold(f64::INFINITY, f64::min);
                deepest = deepest.max(depth);
            }
        }
    }
    deepest
}

/// A cube turned 45° about x (its lowest feature an edge along x) dropped from rest 5 cm above a heavy cube turned
/// 45° about y (its highest feature an edge along y), centred above it: the edges cross below the cube's centre. It
/// falls freely for `√(2h/g)`, where the edge contact is held (restitution 0: the impulse through the centre stops it
/// without spin) and the cube balances on the crossing, its centre still.
fn a_cube_lands_edge_on_edge_and_balances<A: Algebra>() {
    let (system, _) = cube_over::<A>(Vector3::repeat(SIDE), Friction::NONE, 0.0);
    let reach = SIDE / 2.0 * 2f64.sqrt();
    let drop = 0.05;
    let rest = Vector3::z() * 2.0 * reach;
    let start = [
        placed::<A>(
            Vector3::repeat(SIDE),
            rest + Vector3::z() * drop,
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_4),
            Vector3::zeros(),
        ),
        placed::<A>(
            Vector3::repeat(SIDE),
            Vector3::zeros(),
            UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_4),
            Vector3::zeros(),
        ),
    ];
    let landing = (2.0 * drop / G).sqrt();
    for run in [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 0.5)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(2e-3, 0.5).unwrap()).unwrap(),
    ] {
        assert_eq!(run.transitions.len(), 1, "{:?}", run.transitions);
        let held = &run.transitions[0];
        assert!(held.constraint.contains("edge"), "{}", held.constraint);
        assert!(matches!(held.change, LimitChange::Held { .. }), "{held:?}");
        assert!(
            (held.t - landing).abs() < 1e-12,
            "held at {} s, {landing} s exact",
            held.t
        );
        for sample in run.body(0).iter().filter(|s| s.t > landing) {
            assert!(
                (sample.position - rest).norm() < 1e-10,
                "t = {}: {}",
                sample.t,
                sample.position
            );
            assert!(sample.angular_velocity.norm() < 1e-9, "t = {}", sample.t);
        }
        assert!(deepest_vertex(&run, [Vector3::repeat(SIDE); 2]) < 1e-12);
    }
}

/// A cube sliding at 1 m/s without friction on a heavy ledge 1 m long, from 0.2 m short of its edge: its leading
/// corners pass the edge at 0.1 s and let go of the top face; its bottom edges along x then ride on the ledge's edge
/// (edge contacts held) until its centre passes the edge at 0.2 s, where the trailing corners' push reaches zero and
/// they let go; it tips over the edge and falls off. No contact is ever passed through, and the energy is kept.
fn a_cube_slides_off_a_ledge_and_tips_over_its_edge<A: Algebra>() {
    let ledge = Vector3::new(1.0, 1.0, 0.2);
    let (system, _) = cube_over::<A>(ledge, Friction::NONE, 0.0);
    let (x0, speed, edge) = (0.3, 1.0, 0.5);
    let start = [
        placed::<A>(
            Vector3::repeat(SIDE),
            Vector3::new(x0, 0.0, SIDE / 2.0),
            UnitQuaternion::identity(),
            Vector3::x() * speed,
        ),
        placed::<A>(ledge, Vector3::z() * -0.1, UnitQuaternion::identity(), Vector3::zeros()),
    ];
    let corners_pass = (edge - x0 - SIDE / 2.0) / speed;
    let centre_passes = (edge - x0) / speed;
    for run in [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-11, 0.6)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(1e-3, 0.6).unwrap()).unwrap(),
    ] {
        let on_top: Vec<(f64, LimitChange)> = changes(&run, "face 6");
        let released: Vec<f64> = (on_top.iter())
            .filter(|(_, c)| matches!(c, LimitChange::Released { .. }))
            .map(|(t, _)| *t)
            .collect();
        assert_eq!(released.len(), 4, "{:?}", run.transitions);
        // A corner lets go of its face OUTSIDE_FACE past the face's edge.
        let leading = corners_pass + OUTSIDE_FACE / speed;
        for t in &released[..2] {
            assert!(
                (t - leading).abs() < 1e-12,
                "{released:?}: leading corners at {leading} s"
            );
        }
        for t in &released[2..] {
            assert!(
                (t - centre_passes).abs() < 1e-12,
                "{released:?}: trailing corners at {centre_passes} s"
            );
        }
        // The bottom edges along x take the cube's front as its leading corners pass the ledge's edge.
        let riding: Vec<f64> = (changes(&run, " edge ").iter())
            .filter(|(_, c)| matches!(c, LimitChange::Held { .. }))
            .map(|(t, _)| *t)
            .collect();
        assert_eq!(riding.len(), 2, "{:?}", run.transitions);
        assert!(riding.iter().all(|t| (t - corners_pass).abs() < 1e-11), "{riding:?}");
        let energies: Vec<f64> = run.energies().collect();
        assert!(
            energies.iter().all(|e| (e - energies[0]).abs() < 1e-10 * energies[0]),
            "{:?}",
            (energies.first(), energies.last())
        );
        let end = run.body(0).last().unwrap();
        assert!(
            end.position.x > edge && end.position.z < SIDE / 2.0 - 0.01,
            "{}",
            end.position
        );
        assert!(deepest_vertex(&run, [Vector3::repeat(SIDE), ledge]) < 1e-9);
    }
}

/// A ball (radius r = 5 cm, no friction) sliding at v₀ = 0.1 m/s across a heavy box's top face, 0.2 m from its edge
/// (docs/contacts.md "Spheres on polyhedra"): at `(x_e − x₀)/v₀` its centre passes over the edge, where the ball's
/// contact with the edge is held and the face lets go (`OUTSIDE_FACE` later); the ball then turns about the edge as a
/// particle on a circle of radius r, without spin, and leaves it where `cos θ = (v₀²/(g r) + 2)/3`, at the time the
/// quadrature `∫ dθ / √((v₀/r)² + 2 (g/r)(1 − cos θ))` gives; the energy is kept throughout.
fn a_ball_rolls_over_a_box_edge_and_leaves_it_at_the_classical_angle<A: Algebra>() {
    let (radius, speed, x0, edge) = (0.05, 0.1, 0.3, 0.5);
    let ledge = Vector3::new(1.0, 1.0, 0.2);
    let ball = Body::sphere(MASS, radius).unwrap();
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("ball", ball).unwrap();
    let heavy = system.add_body("ledge", Body::cuboid(HEAVY, ledge).unwrap()).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    let shape = Polyhedron::cuboid(ledge).unwrap();
    system
        .add_sphere_polyhedron_contacts(
            "pair",
            (id, Vector3::zeros(), radius, "ball"),
            (heavy, &shape, "ledge"),
            Friction::NONE,
            0.0,
        )
        .unwrap();
    let start = [
        State::<A>::from_world_twist(
            &ball,
            Vector3::new(x0, 0.0, radius),
            &UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::x() * speed,
        ),
        placed::<A>(ledge, Vector3::z() * -0.1, UnitQuaternion::identity(), Vector3::zeros()),
    ];
    let over = (edge - x0) / speed;
    let leaving = ((speed * speed / (G * radius) + 2.0) / 3.0).acos();
    // Simpson's rule on the turn from the top to where it leaves (the integrand is smooth: v₀ > 0).
    let rate = |theta: f64| ((speed / radius).powi(2) + 2.0 * G / radius * (1.0 - theta.cos())).sqrt();
    let n = 20_000;
    let h = leaving / n as f64;
    let turning: f64 = (0..=n)
        .map(|k| {
            let weight = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            weight / rate(k as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    for run in [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 2.5)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(2e-3, 2.5).unwrap()).unwrap(),
    ] {
        // The face lets go OUTSIDE_FACE past its edge and hands the ball to the edge.
        let handed = over + OUTSIDE_FACE / speed;
        let on_edge = changes(&run, " edge ");
        assert_eq!(on_edge.len(), 2, "{:?}", run.transitions);
        assert!(
            matches!(on_edge[0].1, LimitChange::Held { .. }) && (on_edge[0].0 - handed).abs() < 1e-11,
            "{on_edge:?}"
        );
        assert!(
            matches!(on_edge[1].1, LimitChange::Released { .. }) && (on_edge[1].0 - over - turning).abs() < 1e-9,
            "{on_edge:?}: leaves {turning} s after {over} s"
        );
        let face: Vec<(f64, LimitChange)> = changes(&run, "face 6");
        assert!(
            face.iter()
                .any(|(t, c)| matches!(c, LimitChange::Released { .. }) && (t - handed).abs() < 1e-11),
            "{face:?}"
        );
        let energies: Vec<f64> = run.energies().collect();
        assert!(energies
            .iter()
            .all(|e| (e - energies[0]).abs() < 1e-10 * energies[0].abs().max(1.0)));
        assert!(run.body(0).iter().all(|s| s.angular_velocity.norm() < 1e-9));
    }
}

/// A number uniform in [0, 1) from `seed`, which it advances (a linear congruential generator).
fn uniform(seed: &mut u64) -> f64 {
    *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

/// A cube dropped tumbling onto a heavy box from 16 seeded starts (random orientation, spin up to 3 rad/s about each
/// axis, drift up to 0.5 m/s, 0.25–0.35 m up; friction 0 or 0.5, restitution 0 or 0.3) for 1.5 s by DOP853-body at
/// 1e-10: every run ends without error, no vertex of either box is ever inside the other by 1e-12 m at a sample, and
/// between samples the energy never rises by more than the integration error (1e-8 J); the cubes that stay on the box
/// end on a face (centre 0.2 m up, to 1e-9 m).
fn cubes_tumbling_onto_a_box_never_pass_into_it<A: Algebra>() {
    let ledge = Vector3::new(0.6, 0.6, 0.2);
    let mut seed: u64 = 12345;
    for trial in 0..16 {
        let (mu, e) = (
            if trial % 2 == 0 { 0.0 } else { 0.5 },
            if trial % 3 == 0 { 0.3 } else { 0.0 },
        );
        let (system, _) = cube_over::<A>(ledge, Friction::coulomb(mu).unwrap(), e);
        let mut draw = || uniform(&mut seed);
        let axis = nalgebra::Unit::new_normalize(Vector3::new(draw() - 0.5, draw() - 0.5, draw() - 0.5));
        let turn = UnitQuaternion::from_axis_angle(&axis, draw() * 6.0);
        let at = Vector3::new(draw() * 0.5 - 0.25, draw() * 0.5 - 0.25, 0.35 + draw() * 0.1);
        let spin = Vector3::new(draw() - 0.5, draw() - 0.5, draw() - 0.5) * 6.0;
        let drift = Vector3::new(draw() - 0.5, draw() - 0.5, 0.0);
        let body = Body::cuboid(MASS, Vector3::repeat(SIDE)).unwrap();
        let start = [
            State::<A>::from_world_twist(&body, at, &turn, spin, drift),
            placed::<A>(ledge, Vector3::zeros(), UnitQuaternion::identity(), Vector3::zeros()),
        ];
        let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-10, 1.5))
            .unwrap_or_else(|error| panic!("trial {trial}: {error}"));
        assert!(
            deepest_vertex(&run, [Vector3::repeat(SIDE), ledge]) < 1e-12,
            "trial {trial}"
        );
        let energies: Vec<f64> = run.energies().collect();
        assert!(
            energies.windows(2).all(|w| w[1] <= w[0] + 1e-8),
            "trial {trial}: the energy rose"
        );
        let end = run.body(0).last().unwrap();
        if end.position.z > 0.0 && end.velocity.norm() < 1e-9 {
            assert!((end.position.z - 0.2).abs() < 1e-9, "trial {trial}: {}", end.position);
        }
    }
}

for_both_algebras!(
    a_ball_rolls_over_a_box_edge_and_leaves_it_at_the_classical_angle,
    cubes_tumbling_onto_a_box_never_pass_into_it,
    a_cube_lands_edge_on_edge_and_balances,
    a_cube_slides_off_a_ledge_and_tips_over_its_edge,
);

/// Careless edges, edge contacts and polyhedra are refused naming the cause: ends NaN, infinite, far away or
/// coincident; face normals zero, NaN, along the edge or parallel to each other; restitution outside [0, 1]; boxes of
/// zero, negative, NaN or huge sides; polyhedra of too few or too many faces, a vertex outside a face, a face through
/// fewer than three vertices, a vertex on fewer than three faces; an edge contact of a body with itself or with an
/// unknown body; a switching face on no contact or on an edge contact; a pair of polyhedra with too many feature pairs;
/// a sphere on a polyhedron of zero, negative, NaN or huge radius, a NaN or far centre, or on its own body.
#[test]
fn careless_edges_and_polyhedra_are_refused() {
    use dynamics::contacts::{Edge, EdgeContact, PlaneContact};
    use dynamics::Pga;
    let (nan, inf) = (f64::NAN, f64::INFINITY);
    let (z, y) = (Vector3::z(), Vector3::y());
    let message = |r: Result<Edge, dynamics::ConstraintError>| r.err().map(|e| e.to_string()).unwrap_or_default();
    for (start, end, faces, part) in [
        (Vector3::new(nan, 0.0, 0.0), Vector3::x(), [z, y], "finite"),
        (Vector3::zeros(), Vector3::new(inf, 0.0, 0.0), [z, y], "finite"),
        (Vector3::zeros(), Vector3::new(2e6, 0.0, 0.0), [z, y], "within 1e6"),
        (Vector3::x(), Vector3::x(), [z, y], "apart"),
        (Vector3::zeros(), Vector3::x(), [Vector3::zeros(), y], "not zero"),
        (
            Vector3::zeros(),
            Vector3::x(),
            [Vector3::new(0.0, nan, 1.0), y],
            "not zero",
        ),
        (Vector3::zeros(), Vector3::x(), [z, Vector3::x()], "normal to the edge"),
        (Vector3::zeros(), Vector3::x(), [z, -z * 1e-300], "parallel"),
    ] {
        let text = message(Edge::new(start, end, faces));
        assert!(
            text.contains("edge") && text.contains(part),
            "{start} {end} {faces:?}: {text}"
        );
    }
    let edge = Edge::new(Vector3::zeros(), Vector3::x(), [z, y]).unwrap();
    for restitution in [-0.1, 1.5, nan] {
        assert!(EdgeContact::new(edge, edge).with_restitution(restitution).is_err());
    }
    for sides in [
        Vector3::new(0.0, 1.0, 1.0),
        Vector3::new(-1.0, 1.0, 1.0),
        Vector3::new(nan, 1.0, 1.0),
        Vector3::new(1.0, 2e6, 1.0),
    ] {
        let text = Polyhedron::cuboid(sides)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(text.contains("sides must be positive"), "{sides}: {text}");
    }
    let tetra = vec![Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::z()];
    let planes = vec![(-Vector3::x(), 0.0), (-y, 0.0), (-z, 0.0), (Vector3::repeat(1.0), 1.0)];
    let mut inside_out = planes.clone();
    inside_out[3] = (Vector3::repeat(1.0), 0.5);
    let mut extra = tetra.clone();
    extra.push(Vector3::repeat(0.2));
    for (vertices, faces, part) in [
        (tetra.clone(), planes[..3].to_vec(), "4 to 512 faces"),
        (tetra.clone(), vec![planes[0]; 600], "4 to 512 faces"),
        (tetra.clone(), inside_out, "outside face 4"),
        (tetra[..3].to_vec(), planes.clone(), "passes through 2 vertices"),
        (extra, planes.clone(), "fewer than three faces"),
        (vec![Vector3::new(nan, 0.0, 0.0); 4], planes.clone(), "not finite"),
        (tetra.clone(), vec![(Vector3::zeros(), 0.0); 4], "non-zero normal"),
        (tetra.clone(), vec![(Vector3::x(), inf); 4], "finite offset"),
    ] {
        let text = Polyhedron::new(vertices, faces)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(text.contains("polyhedron") && text.contains(part), "{part}: {text}");
    }
    let mut system = Mechanism::<Pga>::new();
    let cube = Body::cuboid(1.0, Vector3::repeat(SIDE)).unwrap();
    let (a, b) = (system.add_body("a", cube).unwrap(), system.add_body("b", cube).unwrap());
    let mut other = Mechanism::<Pga>::new();
    other.add_body("x", cube).unwrap();
    other.add_body("y", cube).unwrap();
    let stranger = other.add_body("z", cube).unwrap(); // no third body in `system`
    assert!(system
        .add_edge_contact("self", a, a, EdgeContact::new(edge, edge))
        .is_err());
    assert!(system
        .add_edge_contact("stranger", a, stranger, EdgeContact::new(edge, edge))
        .is_err());
    system
        .add_edge_contact("edges", a, b, EdgeContact::new(edge, edge))
        .unwrap();
    assert!(system
        .add_edge_contact("edges", a, b, EdgeContact::new(edge, edge))
        .is_err()); // the name again
    let side = [(Vector3::x(), 0.1)];
    assert!(system.set_contact_switching_face("nothing", &side).is_err());
    assert!(system.set_contact_switching_face("edges", &side).is_err());
    system
        .add_contact_on("corner", a, b, PlaneContact::new(Vector3::zeros(), z, 0.1).unwrap())
        .unwrap();
    assert!(system
        .set_contact_switching_face("corner", &[(Vector3::new(nan, 0.0, 1.0), 0.1)])
        .is_err());
    assert!(system
        .set_contact_switching_face("corner", &[(Vector3::x(), 2e6)])
        .is_err());
    // A hull of many vertices against another makes more feature pairs than a pair may watch.
    let ring: Vec<Vector3<f64>> = (0..200)
        .flat_map(|k| {
            let angle = k as f64 * std::f64::consts::TAU / 200.0;
            [
                Vector3::new(angle.cos(), angle.sin(), -0.1),
                Vector3::new(angle.cos(), angle.sin(), 0.1),
            ]
        })
        .collect();
    let mut faces: Vec<(Vector3<f64>, f64)> = (0..200)
        .map(|k| {
            let angle = (k as f64 + 0.5) * std::f64::consts::TAU / 200.0;
            let normal = Vector3::new(angle.cos(), angle.sin(), 0.0);
            (normal, normal.dot(&ring[2 * k]))
        })
        .collect();
    faces.extend([(z, 0.1), (-z, 0.1)]);
    let prism = Polyhedron::new(ring, faces).unwrap();
    let text = system
        .add_polyhedron_contacts("many", (a, &prism, "a"), (b, &prism, "b"), Friction::NONE, 0.0)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(text.contains("feature pairs, more than 10000"), "{text}");
    let box_shape = Polyhedron::cuboid(Vector3::repeat(SIDE)).unwrap();
    // A sphere on a polyhedron: radius zero, negative, NaN or huge; centre NaN or far; restitution out of range; the
    // sphere's own body.
    for (centre, radius, restitution, other) in [
        (Vector3::zeros(), 0.0, 0.0, b),
        (Vector3::zeros(), -0.1, 0.0, b),
        (Vector3::zeros(), nan, 0.0, b),
        (Vector3::zeros(), 2e6, 0.0, b),
        (Vector3::new(nan, 0.0, 0.0), 0.1, 0.0, b),
        (Vector3::new(0.0, 0.0, 2e6), 0.1, 0.0, b),
        (Vector3::zeros(), 0.1, 1.5, b),
        (Vector3::zeros(), 0.1, 0.0, a),
    ] {
        assert!(
            system
                .add_sphere_polyhedron_contacts(
                    "ball",
                    (a, centre, radius, "a"),
                    (other, &box_shape, "b"),
                    Friction::NONE,
                    restitution
                )
                .is_err(),
            "{centre} {radius} {restitution}"
        );
    }
    assert!(system
        .add_polyhedron_contacts(
            "bounce",
            (a, &box_shape, "a"),
            (b, &box_shape, "b"),
            Friction::NONE,
            2.0
        )
        .is_err());
}
