//! Contacts (docs/contacts.md): body points kept above world planes. A block dropped flat lands on four corners at
//! once at the free-fall time, bounces at `e` times its speed without turning, and rests where it lands; a block
//! dropped on a corner takes the impulse of the classical impact formula; elastic corners keep the energy; a block
//! held on an inclined plane slides down it at `g sin α`; a pendulum whose tip meets a plane behaves as the joint
//! limit at the same angle (the elliptic integral's impact time); careless contacts are refused by name.

use dynamics::contacts::PlaneContact;
use dynamics::limits::{Bound, LimitChange};
use dynamics::{
    simulate, Algebra, Body, Dynamics, Force, JointKind, JointMethod, JointModel, Mechanism, Method, Reference,
    Schedule, Simulation, SimulationError, State, Tolerance,
};
use nalgebra::{Isometry3, Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};

const G: f64 = 9.81;
/// The block's half side (m): a 0.2 m cube of 1 kg.
const HALF: f64 = 0.1;

fn block() -> Body {
    Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap()
}

/// The cube's corners (body frame), the four bottom ones first.
fn corners() -> Vec<Vector3<f64>> {
    let mut all = Vec::new();
    for z in [-HALF, HALF] {
        for (x, y) in [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)] {
            all.push(Vector3::new(x, y, z));
        }
    }
    all
}

/// The cube under gravity, free, with `count` of its corners kept above the plane `normal · x = offset`.
fn block_above<A: Algebra>(count: usize, normal: Vector3<f64>, restitution: f64) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("block", block()).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    for (k, corner) in corners().into_iter().take(count).enumerate() {
        let contact = PlaneContact::new(corner, normal, 0.0)
            .unwrap()
            .with_restitution(restitution)
            .unwrap();
        system.add_contact(format!("corner {k}"), id, contact).unwrap();
    }
    system
}

fn at_rest<A: Algebra>(position: Vector3<f64>, rotation: UnitQuaternion<f64>) -> State<A> {
    State::from_world_twist(&block(), position, &rotation, Vector3::zeros(), Vector3::zeros())
}

fn adaptive(tolerance: f64, duration: f64) -> Schedule {
    Schedule::adaptive(Tolerance::new(tolerance, tolerance).unwrap(), duration, 0.01).unwrap()
}

/// The lowest height of the cube's eight corners above the plane through the origin with unit normal `normal`,
/// over every sample of `run`.
fn lowest_corner<A: Algebra>(run: &Simulation<A>, normal: Vector3<f64>) -> f64 {
    (run.body(0).iter())
        .flat_map(|sample| {
            corners()
                .into_iter()
                .map(move |c| normal.dot(&(sample.position + sample.orientation * c)))
        })
        .fold(f64::INFINITY, f64::min)
}

fn a_block_dropped_flat_lands_on_four_corners_at_once<A: Algebra>() {
    let drop = 0.5; // m, the bottom face above the floor
    let first = (2.0 * drop / G).sqrt();
    let system = block_above::<A>(4, Vector3::z(), 0.5);
    let start = [at_rest::<A>(
        Vector3::new(0.3, -0.2, drop + HALF),
        UnitQuaternion::identity(),
    )];
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 2.2 * first)).unwrap();
    // Bounces at half the speed: the flights are first·(1, 2·½) long, so the impacts fall at first and 2·first.
    assert_eq!(run.transitions.len(), 8, "{:?}", run.transitions);
    for (n, impact) in run.transitions.chunks(4).enumerate() {
        let exact = first * (n + 1) as f64;
        let speed = G * first * 0.5f64.powi(n as i32);
        for (k, transition) in impact.iter().enumerate() {
            assert_eq!(transition.constraint, format!("corner {k}"));
            assert!(
                (transition.t - exact).abs() < 1e-12,
                "impact {n} at {} s, free fall gives {exact} s",
                transition.t
            );
            let LimitChange::Bounced {
                speed_before,
                speed_after,
                ..
            } = transition.change
            else {
                panic!("{:?}", transition.change)
            };
            assert!(
                (speed_before - speed).abs() < 1e-11,
                "{speed_before} m/s, {speed} exact"
            );
            assert!((speed_after - 0.5 * speed_before).abs() < 1e-12 * speed);
        }
        assert_eq!(impact[0].t, impact[3].t);
    }
    // Landing flat it does not turn, and it keeps its place on the floor.
    for sample in run.body(0) {
        assert!(
            sample.angular_velocity.norm() < 1e-12,
            "{:e} rad/s",
            sample.angular_velocity.norm()
        );
        assert!((sample.position.xy() - Vector3::new(0.3, -0.2, 0.0).xy()).norm() < 1e-13);
    }
    assert!(lowest_corner(&run, Vector3::z()) > -1e-12);
}

fn an_inelastic_block_rests_where_it_lands<A: Algebra>() {
    let system = block_above::<A>(4, Vector3::z(), 0.0);
    let start = [at_rest::<A>(
        Vector3::new(0.0, 0.0, 0.3 + HALF),
        UnitQuaternion::identity(),
    )];
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 1.0)).unwrap();
    assert_eq!(
        run.transitions.len(),
        4,
        "held on four corners, never released: {:?}",
        run.transitions
    );
    assert!(run.transitions.iter().all(|t| matches!(
        t.change,
        LimitChange::Held {
            bound: Bound::Lower,
            ..
        }
    )));
    let landed = run.transitions[0].t;
    let resting = HALF * G; // J: its potential energy on the floor
    for sample in run.body(0).iter().filter(|s| s.t > landed) {
        assert!(
            (sample.position.z - HALF).abs() < 1e-12,
            "{:e} m off the floor",
            sample.position.z - HALF
        );
        assert!(sample.velocity.norm() < 1e-12 && sample.angular_velocity.norm() < 1e-12);
        assert!((sample.energy - resting).abs() < 1e-12);
    }
}

/// A cube turned so that one corner is lowest, that corner touching the floor and moving down at 2 m/s while the
/// cube turns at (1, −2, 0.5) rad/s: one contact's impact changes the velocities as the classical formula says,
/// `j = −(1 + e) u / (1/m + n · (I⁻¹(r × n) × r))` along n at the corner (r from the centre of mass, I in world axes).
fn a_corner_impact_is_the_classical_impulse<A: Algebra>() {
    let e = 0.7;
    let system = block_above::<A>(8, Vector3::z(), e);
    let rotation = UnitQuaternion::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 1.0, 0.0)), 0.6);
    let lowest = (0..8)
        .min_by(|&a, &b| (rotation * corners()[a]).z.total_cmp(&(rotation * corners()[b]).z))
        .unwrap();
    let r = rotation * corners()[lowest];
    let (omega, velocity) = (Vector3::new(1.0, -2.0, 0.5), Vector3::new(0.4, 0.1, -2.0));
    let body = block();
    let mut states = [State::<A>::from_world_twist(
        &body,
        Vector3::new(1.0, 2.0, -r.z),
        &rotation,
        omega,
        velocity,
    )];
    let mut workspace = system.workspace();
    let changes = system
        .limit_transition(lowest, 0.0, &mut states, &mut workspace)
        .unwrap();
    assert_eq!(changes.len(), 1, "{changes:?}");

    let n = Vector3::z();
    let rotation_matrix: Matrix3<f64> = *rotation.to_rotation_matrix().matrix();
    let inverse_inertia =
        rotation_matrix * Matrix3::from_diagonal(&body.moments().map(|i| 1.0 / i)) * rotation_matrix.transpose();
    let u = n.dot(&(velocity + omega.cross(&r)));
    let j = -(1.0 + e) * u / (1.0 / body.mass() + n.dot(&(inverse_inertia * r.cross(&n)).cross(&r)));
    let expected_velocity = velocity + n * (j / body.mass());
    let expected_omega = omega + inverse_inertia * r.cross(&(n * j));
    let after = states[0].world_velocity(&body);
    assert!(
        (after.linear - expected_velocity).norm() < 1e-13,
        "{} vs {}",
        after.linear,
        expected_velocity
    );
    assert!(
        (after.angular - expected_omega).norm() < 1e-13,
        "{} vs {}",
        after.angular,
        expected_omega
    );
    let LimitChange::Bounced {
        speed_before,
        speed_after,
        ..
    } = changes[0].1
    else {
        panic!("{changes:?}")
    };
    assert!((speed_before + u).abs() < 1e-14 && (speed_after - e * speed_before).abs() < 1e-13);
}

fn elastic_corners_keep_the_energy<A: Algebra>() -> Simulation<A> {
    let system = block_above::<A>(8, Vector3::z(), 1.0);
    let rotation = UnitQuaternion::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 0.3, 0.0)), 0.5);
    let start = [State::<A>::from_world_twist(
        &block(),
        Vector3::new(0.0, 0.0, 0.4),
        &rotation,
        Vector3::new(0.0, 0.0, 3.0),
        Vector3::zeros(),
    )];
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 2.0)).unwrap();
    assert!(run.transitions.len() >= 4, "{:?}", run.transitions);
    for transition in &run.transitions {
        assert!(
            matches!(transition.change, LimitChange::Bounced { .. }),
            "{transition:?}"
        );
        assert!(transition.energy_change.abs() < 1e-13, "{transition:?}");
    }
    let energy = run.body(0)[0].energy;
    let drift = (run.body(0).last().unwrap().energy - energy).abs();
    assert!(drift < 1e-11, "{drift:e} J over 2 s");
    assert!(lowest_corner(&run, Vector3::z()) > -1e-12);
    run
}

fn a_held_block_slides_down_an_incline<A: Algebra>() {
    let slope = 0.2f64; // rad
    let normal = Vector3::new(0.0, slope.sin(), slope.cos());
    let system = block_above::<A>(4, normal, 0.0);
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -slope);
    let centre = normal * HALF;
    let start = [at_rest::<A>(centre, rotation)];
    let runs = [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 1.0)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(1e-2, 1.0).unwrap()).unwrap(),
    ];
    for run in &runs {
        assert_eq!(
            run.transitions.len(),
            4,
            "held at the start, never released: {:?}",
            run.transitions
        );
        // Frictionless: down the slope at g sin α, its height above the plane fixed.
        let down = Vector3::new(0.0, slope.cos(), -slope.sin());
        for sample in run.body(0) {
            let travelled = (sample.position - centre).dot(&down);
            let exact = 0.5 * G * slope.sin() * sample.t * sample.t;
            assert!(
                (travelled - exact).abs() < 1e-11,
                "t = {}: {travelled} m, {exact} m exact",
                sample.t
            );
            assert!((normal.dot(&sample.position) - HALF).abs() < 1e-12);
            assert!(sample.angular_velocity.norm() < 1e-12);
        }
    }
}

/// The rod hinged at its top (the origin) about world x, its tip kept above the plane through the hinge axis that
/// the tip meets at angle −0.3 rad: the joint limit of `limits.rs` made by a contact.
fn pendulum_with_tip_contact<A: Algebra>(restitution: f64) -> Mechanism<A> {
    let rod = Body::rod(1.0, 1.0, 1e-3).unwrap();
    let mut system = Mechanism::<A>::new();
    let body = system.add_body("rod", rod).unwrap();
    system.add_force(body, Force::gravity()).unwrap();
    let hinge = JointModel::new(
        "pivot",
        JointKind::Revolute { axis: Vector3::x() },
        Isometry3::identity(),
        Isometry3::translation(0.0, 0.0, 0.5),
    )
    .unwrap();
    system.connect(body, Reference::World, hinge).unwrap();
    // The tip's direction at −0.3 rad, turned a quarter turn about x toward the start's side, is the normal.
    let tip_at_bound = Rotation3::from_axis_angle(&Vector3::x_axis(), -0.3) * Vector3::new(0.0, 0.0, -1.0);
    let normal = Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2) * tip_at_bound;
    let contact = PlaneContact::new(Vector3::new(0.0, 0.0, -0.5), normal, 0.0)
        .unwrap()
        .with_restitution(restitution)
        .unwrap();
    system.add_contact("tip", body, contact).unwrap();
    system
}

fn a_pendulum_tip_meets_a_plane_as_a_joint_limit<A: Algebra>() {
    let (start, reach) = (1.0, 0.3);
    let system = pendulum_with_tip_contact::<A>(0.0);
    let states = system.states_from_joints(&[start], &[0.0]).unwrap();
    let mut workspace = system.workspace();
    let mut values = [0.0];
    system.limit_values(0.0, &states, &mut workspace, &mut values).unwrap();
    assert!(
        (values[0] - (start + reach).sin()).abs() < 1e-15,
        "the tip's height {}",
        values[0]
    );
    let run = simulate(&system, &states, Method::Dop853Body, &adaptive(1e-12, 1.5)).unwrap();
    // The exact pendulum (as limits.rs): a quarter period and then F(φ, k), over ω.
    let body = Body::rod(1.0, 1.0, 1e-3).unwrap();
    let frequency = (body.mass() * G * 0.5 / (body.moments().x + body.mass() * 0.25)).sqrt();
    let k = (start / 2.0).sin();
    let f =
        |phi: f64| reference::incomplete_elliptic_f(phi, reference::EllipticParameter::new(k * k).unwrap()).unwrap();
    let exact = (f(std::f64::consts::FRAC_PI_2) + f(((reach / 2.0).sin() / k).asin())) / frequency;
    let held = &run.transitions[0];
    assert!(
        (held.t - exact).abs() < 1e-12,
        "impact at {} s, {exact} s exact",
        held.t
    );
    assert!(matches!(held.change, LimitChange::Held { .. }));
    // Gravity pulls it off the plane: released at once, it swings back up to +0.3 rad.
    assert!(matches!(run.transitions[1].change, LimitChange::Released { .. }));
    assert_eq!(run.transitions[1].t, held.t);
    let angles: Vec<f64> = (run.body(0).iter())
        .map(|s| system.joint_positions(&[s.state(&body)], None).unwrap()[0])
        .collect();
    let lowest = angles.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(
        lowest >= -reach - 1e-12,
        "passed the plane by {:e} rad",
        -reach - lowest
    );
    let highest = (angles.iter().zip(run.body(0)))
        .filter(|(_, s)| s.t > held.t + 0.01)
        .map(|(q, _)| *q)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!((highest - reach).abs() < 1e-3, "swings back up to {highest} rad");
}

/// A double pendulum (two 1 m rods hinged about x, the upper at the origin) whose tip is kept above the floor
/// z = −1.7 with restitution 0.5, released with the upper rod at 1.2 rad: the tip strikes the floor, bounces and
/// comes to rest sliding on it (frictionless), and the body-momentum pairs and the joint-coordinate RKMK8 find the
/// same transitions; the tip never goes below the floor.
fn a_chain_tip_strikes_the_floor_alike_by_every_method<A: Algebra>() {
    let rod = Body::rod(1.0, 1.0, 1e-3).unwrap();
    let hinge = |name: &str, at: f64| {
        JointModel::new(
            name,
            JointKind::Revolute { axis: Vector3::x() },
            Isometry3::translation(0.0, 0.0, at),
            Isometry3::translation(0.0, 0.0, 0.5),
        )
        .unwrap()
    };
    let mut system = Mechanism::<A>::new();
    let upper = system.add_body("upper", rod).unwrap();
    let lower = system.add_body("lower", rod).unwrap();
    for body in [upper, lower] {
        system.add_force(body, Force::gravity()).unwrap();
    }
    system.connect(upper, Reference::World, hinge("shoulder", 0.0)).unwrap();
    system.connect(lower, upper, hinge("elbow", -0.5)).unwrap();
    let floor = PlaneContact::new(Vector3::new(0.0, 0.0, -0.5), Vector3::z(), -1.7)
        .unwrap()
        .with_restitution(0.5)
        .unwrap();
    system.add_contact("tip", lower, floor).unwrap();
    let start = system.states_from_joints(&[1.2, 0.0], &[0.0, 0.0]).unwrap();
    let runs = [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 2.0)).unwrap(),
        simulate(&system, &start, Method::Dopri5Body, &adaptive(1e-12, 2.0)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(1e-3, 2.0).unwrap()).unwrap(),
    ];
    let first = &runs[0].transitions;
    assert!(first.len() >= 3, "{first:?}");
    assert!(matches!(first[0].change, LimitChange::Bounced { .. }), "{first:?}");
    for run in &runs {
        assert_eq!(run.transitions.len(), first.len(), "{:?} vs {first:?}", run.transitions);
        for (a, b) in run.transitions.iter().zip(first) {
            assert_eq!(std::mem::discriminant(&a.change), std::mem::discriminant(&b.change));
            assert!((a.t - b.t).abs() < 1e-9, "{} vs {} s", a.t, b.t);
        }
        let tip = (run.body(1).iter())
            .map(|s| (s.position + s.orientation * Vector3::new(0.0, 0.0, -0.5)).z + 1.7)
            .fold(f64::INFINITY, f64::min);
        assert!(tip > -1e-12, "the tip went {:e} m below the floor", -tip);
    }
}

for_both_algebras!(
    a_block_dropped_flat_lands_on_four_corners_at_once,
    an_inelastic_block_rests_where_it_lands,
    a_corner_impact_is_the_classical_impulse,
    a_held_block_slides_down_an_incline,
    a_pendulum_tip_meets_a_plane_as_a_joint_limit,
    a_chain_tip_strikes_the_floor_alike_by_every_method,
);

/// The tumbling elastic cube bounces at the same times in both algebras.
#[test]
fn elastic_corners_bounce_alike_in_both_algebras() {
    let (pga, cga) = (
        elastic_corners_keep_the_energy::<dynamics::Pga>(),
        elastic_corners_keep_the_energy::<dynamics::Cga>(),
    );
    assert_eq!(pga.transitions.len(), cga.transitions.len());
    for (p, c) in pga.transitions.iter().zip(&cga.transitions) {
        assert_eq!(p.constraint, c.constraint);
        assert!((p.t - c.t).abs() < 1e-10, "{} vs {} s", p.t, c.t);
    }
}

/// Careless spheres and disks of plane contacts, each refused naming what is wrong: radii zero, negative, NaN,
/// infinite or huge; disks' axes zero, NaN or infinite; centres NaN or far away. An axis of huge or tiny numbers is a
/// direction like any other.
#[test]
fn careless_spheres_and_disks_are_refused() {
    let (nan, inf) = (f64::NAN, f64::INFINITY);
    let point = Vector3::new(0.0, 0.0, -0.1);
    // Spheres: radii zero, negative, NaN, infinite or huge; centres NaN or far away.
    for radius in [0.0, -0.1, nan, inf, 2e6] {
        let error = PlaneContact::sphere(point, radius, Vector3::z(), 0.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("radius"), "{radius}: {error}");
    }
    for centre in [Vector3::new(nan, 0.0, 0.0), Vector3::new(0.0, 0.0, -2e6)] {
        let error = PlaneContact::sphere(centre, 0.1, Vector3::z(), 0.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("must be finite and within"), "{centre:?}: {error}");
    }
    // Disks: radii zero, negative, NaN, infinite or huge; axes zero, NaN or infinite; centres NaN or far away. An axis
    // of huge or tiny numbers is a direction like any other.
    for radius in [0.0, -0.1, nan, inf, 2e6] {
        let error = PlaneContact::disk(point, Vector3::z(), radius, Vector3::z(), 0.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("disk's radius"), "{radius}: {error}");
    }
    for axis in [
        Vector3::zeros(),
        Vector3::new(nan, 0.0, 1.0),
        Vector3::new(0.0, -inf, 1.0),
    ] {
        let error = PlaneContact::disk(point, axis, 0.1, Vector3::z(), 0.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("disk's axis"), "{axis:?}: {error}");
    }
    for centre in [Vector3::new(nan, 0.0, 0.0), Vector3::new(0.0, 0.0, -2e6)] {
        let error = PlaneContact::disk(centre, Vector3::z(), 0.1, Vector3::z(), 0.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("must be finite and within"), "{centre:?}: {error}");
    }
    for (axis, unit) in [
        (Vector3::new(1e300, 1e300, 0.0), Vector3::new(1.0, 1.0, 0.0)),
        (Vector3::new(0.0, 0.0, -1e-320), -Vector3::z()),
    ] {
        let disk = PlaneContact::disk(point, axis, 0.1, Vector3::z(), 0.0).unwrap();
        assert!((disk.rim().unwrap().0 - unit.normalize()).norm() < 1e-15, "{axis:?}");
    }
}

/// Careless contacts, each refused naming what is wrong: points, normals and offsets NaN, infinite or beyond 1e6 m,
/// a zero normal, restitutions outside [0, 1]; a contact with no name, a repeated name or one of a joint, on a body
/// that is not there, on a mechanism without the articulated solve (or a change that would take it away); a start
/// below the plane. A plane far from the origin and a non-unit normal are contacts like any other.
#[test]
fn careless_contacts_are_refused() {
    use dynamics::constraints::{Stabilisation, VirtualPower};
    use dynamics::{MechanismError, Pga};
    let (nan, inf) = (f64::NAN, f64::INFINITY);
    let point = Vector3::new(0.0, 0.0, -0.1);
    for (p, n, d) in [
        (Vector3::new(nan, 0.0, 0.0), Vector3::z(), 0.0),
        (Vector3::new(0.0, inf, 0.0), Vector3::z(), 0.0),
        (Vector3::new(0.0, 0.0, 2e6), Vector3::z(), 0.0),
        (point, Vector3::z(), nan),
        (point, Vector3::z(), -inf),
        (point, Vector3::z(), 1e7),
    ] {
        let error = PlaneContact::new(p, n, d).unwrap_err().to_string();
        assert!(error.contains("must be finite and within"), "{p:?} {d}: {error}");
    }
    for n in [
        Vector3::zeros(),
        Vector3::new(nan, 0.0, 1.0),
        Vector3::new(0.0, inf, 1.0),
    ] {
        let error = PlaneContact::new(point, n, 0.0).unwrap_err().to_string();
        assert!(error.contains("the normal"), "{n:?}: {error}");
    }
    // A normal of huge or tiny numbers is a direction like any other (as a surface's is); the plane's distance from
    // the origin, the offset over the normal's length, stays within 1e6 m.
    for (n, d, unit, distance) in [
        (Vector3::new(1e300, 0.0, 0.0), 5e299, Vector3::x(), 0.5),
        (Vector3::new(0.0, -1e-320, 0.0), 1e-320, -Vector3::y(), 1.0),
        (
            Vector3::new(3e-300, 4e-300, 0.0),
            5e-300,
            Vector3::new(0.6, 0.8, 0.0),
            1.0,
        ),
    ] {
        let contact = PlaneContact::new(point, n, d).unwrap();
        assert!(
            (contact.normal() - unit).norm() < 1e-15 && (contact.offset() - distance).abs() < 1e-15,
            "{n:?}"
        );
    }
    let error = PlaneContact::new(point, Vector3::z() * 1e-300, 1.0)
        .unwrap_err()
        .to_string();
    assert!(error.contains("distance from the origin"), "{error}");
    for e in [nan, -0.1, 1.0 + 1e-12, inf] {
        let error = PlaneContact::new(point, Vector3::z(), 0.0)
            .unwrap()
            .with_restitution(e)
            .unwrap_err()
            .to_string();
        assert!(error.contains("restitution"), "{e}: {error}");
    }
    // Friction: coefficients negative, NaN, infinite or beyond 1e6, static below kinetic.
    use dynamics::contacts::{Friction, MAX_FRICTION};
    for (kinetic, stiction) in [
        (-0.1, 0.5),
        (nan, 0.5),
        (0.3, nan),
        (inf, inf),
        (0.3, 2.0 * MAX_FRICTION),
        (0.5, 0.4),
    ] {
        let error = Friction::new(kinetic, stiction).unwrap_err().to_string();
        assert!(
            error.contains("friction") && error.contains("coefficient"),
            "{kinetic} {stiction}: {error}"
        );
    }
    assert!(Friction::coulomb(-1e-300).is_err() && Friction::coulomb(MAX_FRICTION).is_ok());
    // A plane given by a non-unit normal is scaled to a unit one: 2z = 1 is z = 0.5.
    let scaled = PlaneContact::new(point, Vector3::z() * 2.0, 1.0).unwrap();
    assert_eq!((scaled.normal(), scaled.offset()), (Vector3::z(), 0.5));

    let contact = PlaneContact::new(point, Vector3::z(), 0.0).unwrap();
    let mut system = Mechanism::<Pga>::new();
    let id = system.add_body("block", block()).unwrap();
    assert_eq!(
        system.add_contact("", id, contact),
        Err(MechanismError::EmptyName("contact"))
    );
    let other = Mechanism::<Pga>::new().add_body("x", block()).map(|_| ());
    assert!(other.is_ok());
    let stranger = {
        let mut m = Mechanism::<Pga>::new();
        m.add_body("a", block()).unwrap();
        m.add_body("b", block()).unwrap()
    };
    assert!(matches!(
        system.add_contact("c", stranger, contact),
        Err(MechanismError::UnknownBody(1))
    ));
    system.add_contact("c", id, contact).unwrap();
    assert_eq!(
        system.add_contact("c", id, contact),
        Err(MechanismError::DuplicateContact("c".to_owned()))
    );
    // A joint that is not a joint model would take the articulated solve away.
    let error = system
        .add_joint(
            id,
            Reference::World,
            VirtualPower::<Pga>::ball_joint("ball", Vector3::z(), Vector3::zeros()),
        )
        .unwrap_err()
        .to_string();
    assert!(error.contains("has contacts"), "{error}");
    let error = system
        .set_stabilisation(Stabilisation::Baumgarte { alpha: 1.0, beta: 1.0 })
        .unwrap_err()
        .to_string();
    assert!(error.contains("has contacts"), "{error}");
    let mut baumgarte = Mechanism::<Pga>::new().with_stabilisation(Stabilisation::Baumgarte { alpha: 1.0, beta: 1.0 });
    let held = baumgarte.as_mut().unwrap().add_body("block", block()).unwrap();
    let error = baumgarte
        .unwrap()
        .add_contact("c", held, contact)
        .unwrap_err()
        .to_string();
    assert!(error.contains("need the articulated solve"), "{error}");

    // A start below the plane, by more than round-off, names the contact.
    let schedule = Schedule::new(1e-3, 0.01).unwrap();
    for depth in [1e-11, 1e-3, 5.0] {
        let start = [at_rest::<Pga>(
            Vector3::new(0.0, 0.0, 0.1 - depth),
            UnitQuaternion::identity(),
        )];
        let error = simulate(&system, &start, Method::Rkmk4Body, &schedule).unwrap_err();
        assert!(
            matches!(&error, SimulationError::BeyondLimit { constraint, depth: d } if constraint == "c" && (d - depth).abs() < 1e-12),
            "{depth}: {error}"
        );
    }
    // Far from the origin, on a plane far from it, the block lands at the free-fall time.
    let far = Vector3::new(3e4, -2e4, 1e3);
    let mut distant = Mechanism::<Pga>::new();
    let id = distant.add_body("block", block()).unwrap();
    distant.add_force(id, Force::gravity()).unwrap();
    let floor = PlaneContact::new(point, Vector3::z(), far.z).unwrap();
    distant.add_contact("c", id, floor).unwrap();
    let start = [at_rest::<Pga>(
        far + Vector3::new(0.0, 0.0, 0.6),
        UnitQuaternion::identity(),
    )];
    let run = simulate(&distant, &start, Method::Dop853Body, &adaptive(1e-10, 0.5)).unwrap();
    assert!(
        (run.transitions[0].t - (2.0 * 0.5 / G).sqrt()).abs() < 1e-9,
        "{:?}",
        run.transitions
    );

    // The one-sided interface with careless calls: a constraint that is not there, wrong counts.
    let mut workspace = system.workspace();
    let start = [at_rest::<Pga>(Vector3::new(0.0, 0.0, 1.0), UnitQuaternion::identity())];
    assert_eq!(
        (system.limit_count(), system.limit_name(0), system.limit_name(1)),
        (1, Some("c"), None)
    );
    let error = system
        .limit_transition(1, 0.0, &mut start.clone(), &mut workspace)
        .unwrap_err()
        .to_string();
    assert!(error.contains("no one-sided constraint 1"), "{error}");
    let error = system
        .limit_values(0.0, &start, &mut workspace, &mut [0.0; 2])
        .unwrap_err()
        .to_string();
    assert!(error.contains("limit values"), "{error}");
    let error = system
        .limit_values(0.0, &[], &mut workspace, &mut [0.0])
        .unwrap_err()
        .to_string();
    assert!(error.contains("states"), "{error}");
}
