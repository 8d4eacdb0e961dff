//! Force elements (docs/mechanisms.md §M8): forces between two bodies obey Newton's third law (a free pair keeps
//! its total momentum), conservative ones report their potential and the others their power, so that the
//! recorded energy change equals the recorded work; a joint actuator gives the textbook pendulum equation; a
//! controller sees the joint-space state and can cancel the dynamics (computed torque); careless inputs are errors
//! naming the element.

use std::sync::Arc;

use dynamics::constraints::PathPoint;
use dynamics::mechanism::force_elements::{ForceElement, JointState, OfTime};
use dynamics::{
    simulate, Algebra, Body, Force, FreeBody, Integrator, JointKind, JointMethod, JointModel, Mechanism,
    MechanismError, Method, Reference, Schedule, Stabilisation, State,
};
use nalgebra::{DVector, Isometry3, UnitQuaternion, Vector3};

/// Two free bodies joined by a damped spring between off-centre points, no gravity: the element's wrenches are
/// equal and opposite along one line, so the total momentum (linear and angular about the origin) stays what it
/// was to round-off while the spring rings down, and the energy lost equals the damper's work.
fn a_spring_between_two_free_bodies_keeps_the_total_momentum<A: Algebra>() {
    let (a, b) = (
        Body::cuboid(1.0, Vector3::new(0.2, 0.3, 0.4)).unwrap(),
        Body::cuboid(0.5, Vector3::new(0.1, 0.5, 0.2)).unwrap(),
    );
    let mut pair = Mechanism::<A>::new();
    let (ia, ib) = (pair.add_body("a", a).unwrap(), pair.add_body("b", b).unwrap());
    let spring = ForceElement::spring_damper(
        "spring",
        (ia, Vector3::new(0.1, 0.0, 0.2)),
        (Reference::Body(ib), Vector3::new(0.0, -0.2, 0.0)),
        40.0,
        0.8,
        0.3,
    )
    .unwrap();
    pair.add_force_element(spring).unwrap();
    let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.2, -0.4, 0.1));
    let states = [
        State::new(
            &a,
            Vector3::zeros(),
            &turn,
            Vector3::new(0.5, -1.0, 2.0),
            Vector3::new(0.1, 0.0, 0.0),
        ),
        State::new(
            &b,
            Vector3::new(0.6, 0.2, -0.1),
            &turn,
            Vector3::new(-1.0, 0.3, 0.0),
            Vector3::zeros(),
        ),
    ];
    let before = A::screw_coordinates(pair.momentum(&states).unwrap());
    let run = simulate(&pair, &states, Method::Rkmk8Body, &Schedule::new(1e-3, 2.0).unwrap()).unwrap();
    let after = A::screw_coordinates(pair.momentum(&run.final_state).unwrap());
    assert!(
        (after.l - before.l).norm() < 1e-13,
        "linear momentum moved by {:e}",
        (after.l - before.l).norm()
    );
    assert!(
        (after.t - before.t).norm() < 1e-13,
        "angular momentum moved by {:e}",
        (after.t - before.t).norm()
    );
    let (first, last) = (run.body(0)[0], *run.body(0).last().unwrap());
    let lost = last.energy - first.energy;
    assert!(lost < -0.01, "the damper dissipates: {lost}");
    // RKMK8 at 1 ms integrates both the motion and the power to ~1e-14 over 2 s.
    assert!(
        (lost - last.work).abs() < 1e-11,
        "energy change {lost} against work {}",
        last.work
    );
}

/// A pendulum on a revolute joint driven by a joint torque τ: `I_p θ̈ = τ − m g d sin θ` (I_p about the pivot).
fn a_joint_torque_gives_the_pendulum_equation<A: Algebra>() {
    let (mass, length) = (1.5, 0.8);
    let rod = Body::rod(mass, length, 1e-3).unwrap();
    let mut pendulum = Mechanism::<A>::new();
    let link = pendulum.add_body("rod", rod).unwrap();
    pendulum.add_force(link, Force::gravity()).unwrap();
    let hinge = JointModel::new(
        "pivot",
        JointKind::Revolute { axis: Vector3::x() },
        Isometry3::identity(),
        Isometry3::translation(0.0, 0.0, 0.5 * length),
    )
    .unwrap();
    let pivot = pendulum.connect(link, Reference::World, hinge).unwrap();
    let tau = 2.5; // N m
    pendulum
        .add_force_element(ForceElement::joint_force("motor", pivot, OfTime::Constant(tau)))
        .unwrap();
    for theta in [0.0, 0.4, -1.2, 2.5] {
        let states = pendulum.states_from_joints(&[theta], &[0.7]).unwrap();
        let q_ddot = pendulum.joint_accelerations(0.0, &states).unwrap()[0];
        let about_pivot = mass * length * length / 3.0;
        // θ about +x: the centre at (0, d sin θ, −d cos θ), gravity's torque about x is −m g d sin θ.
        let expected = (tau - mass * 9.81 * 0.5 * length * theta.sin()) / about_pivot;
        assert!(
            (q_ddot - expected).abs() < 1e-12 * expected.abs().max(1.0),
            "θ = {theta}: {q_ddot} vs {expected}"
        );
    }
}

/// A damped, driven double pendulum with a spring to the world: the energy change equals the work of the joint
/// dampers and the motor at every sample, to the integration error (RKMK8 at 2 ms over 3 s: ~1e-12 J).
fn energy_change_equals_the_work_done<A: Algebra>() {
    let link = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 1.0)).unwrap();
    let mut pendulum = Mechanism::<A>::new();
    let upper = pendulum.add_body("upper", link).unwrap();
    let lower = pendulum.add_body("lower", link).unwrap();
    for body in [upper, lower] {
        pendulum.add_force(body, Force::gravity()).unwrap();
    }
    let hinge = |name: &str, above: f64, axis: Vector3<f64>| {
        let (parent, child) = (
            Isometry3::translation(0.0, 0.0, above),
            Isometry3::translation(0.0, 0.0, 0.5),
        );
        JointModel::new(name, JointKind::Revolute { axis }, parent, child).unwrap()
    };
    let shoulder = pendulum
        .connect(upper, Reference::World, hinge("shoulder", 0.0, Vector3::x()))
        .unwrap();
    let elbow = pendulum
        .connect(lower, upper, hinge("elbow", -0.5, Vector3::new(0.0, 1.0, 0.5)))
        .unwrap();
    let drive = OfTime::Function(Arc::new(|t: f64| 0.8 * (3.0 * t).sin()));
    let elements = [
        ForceElement::joint_damping("shoulder damping", shoulder, 0.05).unwrap(),
        ForceElement::joint_damping("elbow damping", elbow, 0.02).unwrap(),
        ForceElement::joint_force("motor", elbow, drive),
        ForceElement::spring_damper(
            "tether",
            (lower, Vector3::new(0.0, 0.0, -0.5)),
            (Reference::World, Vector3::new(0.5, 0.5, -1.5)),
            5.0,
            0.1,
            0.4,
        )
        .unwrap(),
    ];
    for element in elements {
        pendulum.add_force_element(element).unwrap();
    }
    pendulum
        .set_stabilisation(dynamics::constraints::Stabilisation::PROJECTION)
        .unwrap();
    let states = pendulum.states_from_joints(&[1.0, 0.6], &[1.0, -0.5]).unwrap();
    let run = simulate(
        &pendulum,
        &states,
        Method::Rkmk8Body,
        &Schedule::new(2e-3, 3.0).unwrap(),
    )
    .unwrap();
    let start = run.body(0)[0].energy;
    let mut worst: f64 = 0.0;
    let mut largest_work: f64 = 0.0;
    for sample in run.body(0) {
        worst = worst.max((sample.energy - start - sample.work).abs());
        largest_work = largest_work.max(sample.work.abs());
    }
    assert!(
        largest_work > 0.1,
        "the dampers and the motor do work: {largest_work} J"
    );
    assert!(worst < 1e-9, "energy change against work: {worst:e} J");
}

/// A double pendulum whose shoulder is driven along `q(t) = 0.6 sin 2t` and whose lower link carries a constant
/// couple (a body force that is not gravity): the drive's torque and the couple do work, and the energy change
/// equals it at every sample on all three paths — the articulated solve, joint coordinates, and the general solve
/// (Baumgarte, whose stabilising reactions do work too) — to the integration error. A coarse step leaves the driven
/// joint exactly on its drive: its coordinate is the drive's, not an integrated copy.
fn drives_and_body_forces_do_the_work<A: Algebra>() {
    let link = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 1.0)).unwrap();
    let drive = |t: f64| PathPoint {
        value: 0.6 * (2.0 * t).sin(),
        rate: 1.2 * (2.0 * t).cos(),
        acceleration: -2.4 * (2.0 * t).sin(),
    };
    let build = |stabilisation: Stabilisation| {
        let mut pendulum = Mechanism::<A>::new();
        let upper = pendulum.add_body("upper", link).unwrap();
        let lower = pendulum.add_body("lower", link).unwrap();
        for body in [upper, lower] {
            pendulum.add_force(body, Force::gravity()).unwrap();
        }
        pendulum
            .add_force(
                lower,
                Force::Couple {
                    moment: Vector3::new(0.3, 0.1, 0.0),
                },
            )
            .unwrap();
        let hinge = |name: &str, above: f64| {
            let (parent, child) = (
                Isometry3::translation(0.0, 0.0, above),
                Isometry3::translation(0.0, 0.0, 0.5),
            );
            JointModel::new(name, JointKind::Revolute { axis: Vector3::x() }, parent, child).unwrap()
        };
        pendulum
            .connect(upper, Reference::World, hinge("shoulder", 0.0).driven(drive).unwrap())
            .unwrap();
        pendulum.connect(lower, upper, hinge("elbow", -0.5)).unwrap();
        pendulum.set_stabilisation(stabilisation).unwrap();
        pendulum
    };
    let baumgarte = Stabilisation::Baumgarte {
        alpha: 10.0,
        beta: 10.0,
    };
    let paths: [(&str, Integrator, Stabilisation); 3] = [
        ("articulated", Method::Rkmk8Body.into(), Stabilisation::PROJECTION),
        (
            "joint coordinates",
            JointMethod::Rkmk8.into(),
            Stabilisation::PROJECTION,
        ),
        ("general", Method::Rkmk8Body.into(), baumgarte),
    ];
    for (path, integrator, stabilisation) in paths {
        let pendulum = build(stabilisation);
        let states = pendulum.states_from_joints(&[0.0, 0.4], &[1.2, -0.5]).unwrap();
        let run = simulate(&pendulum, &states, integrator, &Schedule::new(2e-3, 3.0).unwrap()).unwrap();
        let start = run.body(0)[0].energy;
        let mut worst: f64 = 0.0;
        let mut largest_work: f64 = 0.0;
        for sample in run.body(0) {
            worst = worst.max((sample.energy - start - sample.work).abs());
            largest_work = largest_work.max(sample.work.abs());
        }
        assert!(
            largest_work > 0.1,
            "{path}: the drive and the couple do work: {largest_work} J"
        );
        assert!(worst < 1e-9, "{path}: energy change against work: {worst:e} J");
    }
    for integrator in [Integrator::from(Method::Rkmk4Body), JointMethod::Rkmk4.into()] {
        let pendulum = build(Stabilisation::PROJECTION);
        let states = pendulum.states_from_joints(&[0.0, 0.4], &[1.2, -0.5]).unwrap();
        let run = simulate(
            &pendulum,
            &states,
            integrator,
            &Schedule::with_sample_interval(0.05, 1.0, 0.5).unwrap(),
        )
        .unwrap();
        let (q, v) = (
            pendulum.joint_positions(&run.final_state, None).unwrap(),
            pendulum.joint_velocities(&run.final_state).unwrap(),
        );
        let end = drive(1.0);
        assert!(
            (q[0] - end.value).abs() < 1e-14 && (v[0] - end.rate).abs() < 1e-13,
            "{integrator:?}: the shoulder at {} rad, {} rad/s; its drive at {} rad, {} rad/s",
            q[0],
            v[0],
            end.value,
            end.rate
        );
    }
}

/// A free body under gravity, a constant couple, a force along a fixed world line and a custom drag on its angular
/// momentum about its centre of mass: the body reports the power of every force but gravity (whose potential is in the
/// energy), so the energy change equals the recorded work, on the world-state and the body-momentum paths.
fn a_free_body_reports_the_work_of_its_forces<A: Algebra>() {
    let brick = Body::cuboid(2.0, Vector3::new(0.1, 0.2, 0.3)).unwrap();
    let drag = Force::Custom(Arc::new(|_t: f64, state: &State<A>| {
        let momentum = A::screw_coordinates(state.central_momentum);
        A::screw(dynamics::ScrewCoordinates {
            l: Vector3::zeros(),
            t: -0.05 * momentum.t,
        })
    }));
    let system = FreeBody::<A>::new(brick)
        .with_force(Force::gravity())
        .with_force(Force::Couple {
            moment: Vector3::new(0.2, -0.1, 0.3),
        })
        .with_force(Force::Line {
            force: Vector3::new(1.0, 0.0, 0.5),
            point: Vector3::new(0.3, -0.1, 1.2),
        })
        .with_force(drag);
    let start = State::new(
        &brick,
        Vector3::new(0.3, -0.2, 1.0),
        &UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.2, -0.1)),
        Vector3::new(1.0, 4.0, -2.0),
        Vector3::new(0.5, 0.0, 1.0),
    );
    // The world-state path (RK4 on the motor and momentum as vectors, whose error in the energy dominates: 3e-8 J at
    // 0.1 ms, fourth order) and the body-momentum path (RKMK8: 3e-12 J at 1 ms).
    for (method, step, tolerance) in [(Method::Rk4, 1e-4, 1e-7), (Method::Rkmk8Body, 1e-3, 1e-10)] {
        let run = simulate(&system, &[start], method, &Schedule::new(step, 1.0).unwrap()).unwrap();
        let first = run.body(0)[0].energy;
        let worst = run
            .body(0)
            .iter()
            .map(|s| (s.energy - first - s.work).abs())
            .fold(0.0, f64::max);
        let work = run.body(0).last().unwrap().work;
        assert!(work.abs() > 1.0, "{method:?}: the forces do work: {work} J");
        assert!(worst < tolerance, "{method:?}: energy change against work: {worst:e} J");
    }
}

/// Computed torque: a controller that asks for `τ = M q̈* + h` makes the joint accelerations `q̈*`, whatever the
/// state (the controller sees the joint-space state and the mechanism's M and h, which leave it out).
fn computed_torque_gives_the_asked_accelerations<A: Algebra>() {
    let link = Body::cuboid(0.8, Vector3::new(0.06, 0.08, 0.6)).unwrap();
    let mut arm = Mechanism::<A>::new();
    let bodies: Vec<_> = (0..3)
        .map(|k| arm.add_body(format!("link {k}"), link).unwrap())
        .collect();
    let axes = [Vector3::z(), Vector3::y(), Vector3::new(1.0, 0.0, 1.0)];
    for (k, &body) in bodies.iter().enumerate() {
        arm.add_force(body, Force::gravity()).unwrap();
        let parent = if k == 0 {
            Reference::World
        } else {
            Reference::Body(bodies[k - 1])
        };
        let above = if k == 0 { 0.0 } else { -0.3 };
        let model = JointModel::new(
            format!("joint {k}"),
            JointKind::Revolute { axis: axes[k] },
            Isometry3::translation(0.0, 0.0, above),
            Isometry3::translation(0.0, 0.0, 0.3),
        )
        .unwrap();
        arm.connect(body, parent, model).unwrap();
    }
    let asked = DVector::from_vec(vec![0.3, -1.2, 2.0]);
    let wanted = asked.clone();
    let law = move |state: &JointState<'_, A>| {
        let mass = state.mass_matrix().expect("mass matrix");
        let bias = state.bias_forces().expect("bias forces");
        &mass * &wanted + bias
    };
    arm.add_force_element(ForceElement::controller("computed torque", Arc::new(law)))
        .unwrap();
    let states = arm.states_from_joints(&[0.4, -0.7, 1.1], &[1.0, 0.2, -0.6]).unwrap();
    let q_ddot = arm.joint_accelerations(0.0, &states).unwrap();
    for (ours, asked) in q_ddot.iter().zip(asked.iter()) {
        assert!((ours - asked).abs() < 1e-11, "{q_ddot:?} vs {asked}");
    }
}

/// Careless inputs are errors naming the element (when built, when added, or at the evaluation that meets them).
fn careless_elements_are_errors_naming_them<A: Algebra>() {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let mut system = Mechanism::<A>::new();
    let body = system.add_body("ball", ball).unwrap();
    let spring = |k: f64, c: f64, l: f64, point: Vector3<f64>| {
        ForceElement::<A>::spring_damper("spring", (body, point), (Reference::World, Vector3::zeros()), k, c, l)
    };
    for (k, c, l) in [
        (f64::NAN, 0.0, 0.0),
        (-1.0, 0.0, 0.0),
        (1.0, -0.1, 0.0),
        (1.0, 0.0, -0.2),
        (1e300, 0.0, 0.0),
    ] {
        let error = spring(k, c, l, Vector3::zeros()).unwrap_err().to_string();
        assert!(error.contains("spring"), "{error}");
    }
    assert!(spring(1.0, 0.0, 0.0, Vector3::new(f64::INFINITY, 0.0, 0.0)).is_err());
    let to_itself = ForceElement::<A>::spring_damper(
        "loop",
        (body, Vector3::zeros()),
        (Reference::Body(body), Vector3::x()),
        1.0,
        0.0,
        0.0,
    )
    .unwrap();
    assert!(system
        .add_force_element(to_itself)
        .unwrap_err()
        .to_string()
        .contains("loop"));
    // Bodies and joints of another mechanism.
    let mut other = Mechanism::<A>::new();
    let ids: Vec<_> = (0..3).map(|k| other.add_body(format!("b{k}"), ball).unwrap()).collect();
    let pins: Vec<_> = ids
        .iter()
        .map(|&b| {
            let pin = dynamics::constraints::VirtualPower::ball_joint("pin", Vector3::z(), Vector3::zeros());
            other.add_joint(b, Reference::World, pin).unwrap()
        })
        .collect();
    let stray = ForceElement::<A>::couple("stray", ids[2], Reference::World, OfTime::Constant(Vector3::x()));
    assert!(matches!(
        system.add_force_element(stray),
        Err(MechanismError::UnknownBody(2))
    ));
    // A spring of rest length 0.5 whose two points meet has no line of action: an error at that evaluation.
    system
        .add_force_element(spring(10.0, 0.0, 0.5, Vector3::zeros()).unwrap())
        .unwrap();
    let at_anchor = State::new(
        &ball,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let error = system.rates_at(0.0, &[at_anchor]).unwrap_err().to_string();
    assert!(error.contains("spring") && error.contains("meet"), "{error}");
    // A controller on a mechanism without joint coordinates' joints still sees the free root; a wrong count is an
    // error naming it.
    let law = |_: &JointState<'_, A>| DVector::from_element(2, 0.0);
    let mut free = Mechanism::<A>::new();
    free.add_body("ball", ball).unwrap();
    free.add_force_element(ForceElement::controller("short", Arc::new(law)))
        .unwrap();
    let error = free.rates_at(0.0, &[at_anchor]).unwrap_err().to_string();
    assert!(
        error.contains("short") && error.contains("returned 2 forces"),
        "{error}"
    );
    let not_finite = |_: &JointState<'_, A>| DVector::from_element(6, f64::NAN);
    let mut free = Mechanism::<A>::new();
    free.add_body("ball", ball).unwrap();
    free.add_force_element(ForceElement::controller("nan", Arc::new(not_finite)))
        .unwrap();
    assert!(free
        .rates_at(0.0, &[at_anchor])
        .unwrap_err()
        .to_string()
        .contains("nan"));
    // A joint force on a joint that is not a joint model, or on an unknown joint.
    let mut constrained = Mechanism::<A>::new();
    let b = constrained.add_body("ball", ball).unwrap();
    let joint = constrained
        .add_joint(
            b,
            Reference::World,
            dynamics::constraints::VirtualPower::ball_joint("pin", Vector3::z(), Vector3::zeros()),
        )
        .unwrap();
    let force = ForceElement::<A>::joint_force("push", joint, OfTime::Constant(1.0));
    assert!(constrained
        .add_force_element(force)
        .unwrap_err()
        .to_string()
        .contains("not a joint model"));
    let damping = ForceElement::<A>::joint_damping("damp", joint, f64::NAN);
    assert!(damping.is_err());
    let unknown = ForceElement::<A>::joint_force("push", pins[2], OfTime::Constant(1.0));
    assert!(matches!(
        constrained.add_force_element(unknown),
        Err(MechanismError::UnknownJoint(_))
    ));
}

for_both_algebras!(
    a_spring_between_two_free_bodies_keeps_the_total_momentum,
    a_joint_torque_gives_the_pendulum_equation,
    energy_change_equals_the_work_done,
    drives_and_body_forces_do_the_work,
    a_free_body_reports_the_work_of_its_forces,
    computed_torque_gives_the_asked_accelerations,
    careless_elements_are_errors_naming_them,
);
