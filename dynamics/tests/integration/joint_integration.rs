//! Stepping in joint coordinates (docs/mechanisms.md §M9): each method converges at its order on a mechanism
//! that exercises every kind of coordinate — a free root (a rotation and a translation), a spherical joint (a
//! rotation), revolute and prismatic joints (vectors) — by self-convergence; it agrees with the body-momentum
//! methods; it keeps the energy and accounts the work of the force elements; and it is refused, with the reason,
//! for systems without joint coordinates.

use std::sync::Arc;

use dynamics::constraints::{Stabilisation, VirtualPower};
use dynamics::mechanism::force_elements::{ForceElement, OfTime};
use dynamics::{
    simulate, Algebra, Body, Dynamics, Force, FreeBody, JointKind, JointMethod, JointModel, Mechanism, Method,
    Reference, Schedule, State, StepError, Stepper, Tolerance,
};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// A floating torso with an arm (spherical shoulder, revolute elbow) and a slider, under gravity, thrown tumbling.
fn mechanism<A: Algebra>() -> (Mechanism<A>, Vec<State<A>>) {
    let torso = Body::cuboid(3.0, Vector3::new(0.4, 0.3, 0.6)).unwrap();
    let arm = Body::cuboid(0.8, Vector3::new(0.06, 0.08, 0.5)).unwrap();
    let hand = Body::cuboid(0.3, Vector3::new(0.05, 0.05, 0.3)).unwrap();
    let slider = Body::cuboid(0.5, Vector3::new(0.1, 0.1, 0.1)).unwrap();
    let mut system = Mechanism::<A>::new();
    let ids: Vec<_> = [("torso", torso), ("arm", arm), ("hand", hand), ("slider", slider)]
        .into_iter()
        .map(|(name, body)| system.add_body(name, body).unwrap())
        .collect();
    for &id in &ids {
        system.add_force(id, Force::gravity()).unwrap();
    }
    let frame = |x: f64, y: f64, z: f64, turn: Vector3<f64>| {
        Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::from_scaled_axis(turn))
    };
    let joints = [
        (
            1,
            0,
            "shoulder",
            JointKind::Spherical,
            frame(0.2, 0.0, 0.3, Vector3::new(0.2, 0.0, 0.0)),
            frame(0.0, 0.0, 0.25, Vector3::zeros()),
        ),
        (
            2,
            1,
            "elbow",
            JointKind::Revolute {
                axis: Vector3::new(0.0, 1.0, 0.2),
            },
            frame(0.0, 0.0, -0.25, Vector3::zeros()),
            frame(0.0, 0.0, 0.15, Vector3::new(0.0, 0.3, 0.0)),
        ),
        (
            3,
            0,
            "rail",
            JointKind::Prismatic {
                axis: Vector3::new(1.0, 0.5, 0.0),
            },
            frame(-0.2, 0.1, -0.3, Vector3::zeros()),
            frame(0.0, 0.0, 0.05, Vector3::zeros()),
        ),
    ];
    for (child, parent, name, kind, parent_frame, child_frame) in joints {
        let model = JointModel::new(name, kind, parent_frame, child_frame).unwrap();
        system.connect(ids[child], ids[parent], model).unwrap();
    }
    system.set_stabilisation(Stabilisation::PROJECTION).unwrap();
    let shoulder = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.4, 0.2)).into_inner();
    let q = [
        0.1, -0.2, 1.0, 0.9, 0.1, 0.2, 0.3, // torso: position, orientation (normalised by the reader)
        shoulder.w, shoulder.i, shoulder.j, shoulder.k, // shoulder
        0.7,        // elbow
        0.05,       // rail
    ];
    let norm = (0.9f64 * 0.9 + 0.01 + 0.04 + 0.09).sqrt();
    let mut q = q.to_vec();
    q[3..7].iter_mut().for_each(|x| *x /= norm);
    let v = [0.5, -0.3, 2.0, 1.0, -2.0, 0.5, 0.8, 1.5, -0.6, -1.2, 0.4];
    let states = system.states_from_joints(&q, &v).unwrap();
    (system, states)
}

/// The end joint coordinates (positions, with the torso's quaternion as a rotation) after 1 s with steps of `dt`.
fn end<A: Algebra>(method: JointMethod, dt: f64) -> Vec<f64> {
    let (system, states) = mechanism::<A>();
    let run = simulate(
        &system,
        &states,
        method,
        &Schedule::with_sample_interval(dt, 1.0, 1.0).unwrap(),
    )
    .unwrap();
    system.joint_positions(&run.final_state, None).unwrap()
}

/// The largest difference of two end coordinate vectors (rotations compared by angle).
fn difference(a: &[f64], b: &[f64]) -> f64 {
    let rotation = |q: &[f64], at: usize| {
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[at], q[at + 1], q[at + 2], q[at + 3]))
    };
    let angle = rotation(a, 3)
        .angle_to(&rotation(b, 3))
        .max(rotation(a, 7).angle_to(&rotation(b, 7)));
    let vectors = [0, 1, 2, 11, 12]
        .iter()
        .map(|&k| (a[k] - b[k]).abs())
        .fold(0.0, f64::max);
    angle.max(vectors)
}

/// Self-convergence at steps h, h/2, h/4: the observed order `log₂(d₁/d₂)` is the method's within 0.3.
/// Measured (printed with `--nocapture`), PGA and CGA alike: RKMK4-joint 3.96 (h = 1e-2), RKMK6-joint 5.92
/// (h = 2.5e-2), RKMK8-joint 7.74 (h = 5e-2; differences 1.2e-8 and 5.7e-11, near the round-off of this 1 s run),
/// DOP853-joint at fixed steps 7.98 (h = 5e-2; 3.0e-10 and 1.2e-12).
fn joint_methods_converge_at_their_order<A: Algebra>() {
    for (method, h) in [
        (JointMethod::Rkmk4, 1e-2),
        (JointMethod::Rkmk6, 2.5e-2),
        (JointMethod::Rkmk8, 5e-2),
        (JointMethod::Dop853, 5e-2),
    ] {
        let [coarse, middle, fine] = [h, h / 2.0, h / 4.0].map(|dt| end::<A>(method, dt));
        let (first, second) = (difference(&coarse, &middle), difference(&middle, &fine));
        let order = (first / second).log2();
        println!(
            "{} {}: differences {first:.2e}, {second:.2e}, order {order:.2}",
            A::NAME,
            method.name()
        );
        assert!(
            (order - method.order() as f64).abs() < 0.3,
            "{}: order {order:.2}",
            method.name()
        );
    }
}

/// The joint-coordinate and body-momentum eighth-order methods reach the same end state (1e-9 at dt = 5e-3, where
/// each is within ~1e-12 of the exact motion), and the energy holds to 1e-10 J relative.
fn joint_and_body_methods_agree<A: Algebra>() {
    let (system, states) = mechanism::<A>();
    let schedule = Schedule::new(5e-3, 1.0).unwrap();
    let joint = simulate(&system, &states, JointMethod::Rkmk8, &schedule).unwrap();
    let body = simulate(&system, &states, Method::Rkmk8Body, &schedule).unwrap();
    let (a, b) = (
        system.joint_positions(&joint.final_state, None).unwrap(),
        system.joint_positions(&body.final_state, None).unwrap(),
    );
    assert!(difference(&a, &b) < 1e-9, "{}", difference(&a, &b));
    let energies: Vec<f64> = joint.energies().collect();
    let drift = energies.iter().map(|e| (e - energies[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-10 * energies[0].abs().max(1.0), "energy drift {drift:e} J");
    // The joints hold exactly: the states are written by forward kinematics. The velocity residual is read back
    // through the states' world momenta about the origin, whose round-off after a 5 m fall at 10 m/s is
    // ε·|c × p| ≈ 1e-14 of momenta ~1e-3 kg m²/s: 5e-12 m/s measured.
    let violation = system.violation(1.0, &joint.final_state).unwrap();
    assert!(
        violation.position < 1e-14 && violation.velocity < 2e-11,
        "{violation:?}"
    );
}

/// The work of a joint damper and a motor is accounted by the joint methods as by the others.
fn joint_methods_account_the_work<A: Algebra>() {
    let (mut system, states) = mechanism::<A>();
    let elbow = system.joint_space().unwrap().group("elbow").unwrap().joint().unwrap();
    let rail = system.joint_space().unwrap().group("rail").unwrap().joint().unwrap();
    system
        .add_force_element(ForceElement::joint_damping("elbow damper", elbow, 0.05).unwrap())
        .unwrap();
    let push = OfTime::Function(Arc::new(|t: f64| 2.0 * (4.0 * t).cos()));
    system
        .add_force_element(ForceElement::joint_force("rail motor", rail, push))
        .unwrap();
    let run = simulate(&system, &states, JointMethod::Rkmk8, &Schedule::new(5e-3, 1.0).unwrap()).unwrap();
    let first = run.body(0)[0].energy;
    let worst = run
        .body(0)
        .iter()
        .map(|s| (s.energy - first - s.work).abs())
        .fold(0.0, f64::max);
    let largest = run.body(0).iter().map(|s| s.work.abs()).fold(0.0, f64::max);
    assert!(largest > 0.01, "work done: {largest}");
    assert!(worst < 1e-10, "energy change against work: {worst:e} J");
}

/// DOP853-joint with a tolerance follows it: on the tumbling mechanism (a free root, a spherical, a revolute and a
/// prismatic joint) the largest error of any joint coordinate over every sample (from the continuous extension),
/// against RKMK8-joint at 1 ms (within ~1e-14 of the exact motion), lies within [0.1, 10] times the tolerance asked,
/// from 1e-6 to 1e-12; the samples are on the 0.01 s grid, the end on the joints, and the energy less the work of an
/// elbow damper stays within ten times the tolerance. Measured, PGA and CGA alike: 0.11, 0.24, 0.22 and 0.15 times the
/// tolerance at 1e-6, 1e-8, 1e-10 and 1e-12, in 18, 27, 43 and 70 steps.
fn dop853_joint_follows_its_tolerance<A: Algebra>() {
    let (mut system, states) = mechanism::<A>();
    let elbow = system.joint_space().unwrap().group("elbow").unwrap().joint().unwrap();
    system
        .add_force_element(ForceElement::joint_damping("elbow damper", elbow, 0.05).unwrap())
        .unwrap();
    let reference = simulate(&system, &states, JointMethod::Rkmk8, &Schedule::new(1e-3, 1.0).unwrap()).unwrap();
    let coordinates = |run: &dynamics::Simulation<A>, k: usize| {
        let sample: Vec<State<A>> = (0..4)
            .map(|b| {
                let s = &run.body(b)[k];
                State::from_world_twist(
                    system.body(b),
                    s.position,
                    &s.orientation,
                    s.angular_velocity,
                    s.velocity,
                )
            })
            .collect();
        system.joint_positions(&sample, None).unwrap()
    };
    for asked in [1e-6, 1e-8, 1e-10, 1e-12] {
        let schedule = Schedule::adaptive(Tolerance::new(asked, asked).unwrap(), 1.0, 0.01).unwrap();
        let run = simulate(&system, &states, JointMethod::Dop853, &schedule).unwrap();
        assert_eq!(run.body(0).len(), reference.body(0).len());
        let mut error = 0.0f64;
        for k in 0..run.body(0).len() {
            assert!((run.body(0)[k].t - reference.body(0)[k].t).abs() < 1e-12);
            error = error.max(difference(&coordinates(&run, k), &coordinates(&reference, k)));
        }
        let balance = (run.body(0).iter())
            .map(|s| (s.energy - run.body(0)[0].energy - s.work).abs())
            .fold(0.0, f64::max);
        println!(
            "{} DOP853-joint at {asked:e}: error {error:.2e} ({:.2}x), energy less work {balance:.1e} J, {} steps",
            A::NAME,
            error / asked,
            run.statistics.accepted
        );
        assert!((0.1 * asked..10.0 * asked).contains(&error), "at {asked:e}: {error:e}");
        assert!(
            balance < 10.0 * asked.max(1e-11),
            "at {asked:e}: energy less work {balance:e}"
        );
        let violation = system.violation(1.0, &run.final_state).unwrap();
        assert!(violation.position < 1e-13, "{violation:?}");
    }
}

/// Systems without joint coordinates refuse the joint methods when the stepper is made, with the reason.
fn systems_without_joint_coordinates_refuse_them<A: Algebra>() {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let free = FreeBody::<A>::new(ball);
    let refused = Stepper::new(&free, JointMethod::Rkmk8).err().unwrap();
    assert!(matches!(refused, StepError::NoJointCoordinates { .. }), "{refused}");
    let constrained = Mechanism::<A>::single(ball)
        .with_constraint(VirtualPower::point_on_sphere("string", Vector3::zeros(), Vector3::z(), 1.0).unwrap())
        .unwrap();
    for method in [JointMethod::Rkmk4, JointMethod::Dop853] {
        let refused = Stepper::new(&constrained, method).err().unwrap();
        assert!(refused.to_string().contains("joint models"), "{refused}");
    }
    // With a tolerance too, before any step; and the fixed-step joint methods have no error estimate.
    let adaptive = Schedule::adaptive(Tolerance::new(1e-8, 1e-8).unwrap(), 1.0, 0.1).unwrap();
    let start = [State::new(
        &ball,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
    )];
    assert!(simulate(&constrained, &start, JointMethod::Dop853, &adaptive).is_err());
    let single = Mechanism::<A>::single(ball);
    let refused = simulate(&single, &start, JointMethod::Rkmk8, &adaptive).unwrap_err();
    assert!(refused.to_string().contains("RKMK8-joint"), "{refused}");
    assert_eq!(
        JointMethod::ALL.map(JointMethod::estimate_order),
        [None, None, None, Some(8)]
    );
    // A free body in a mechanism is a free root: it has joint coordinates.
    assert!(Stepper::new(&single, JointMethod::Rkmk8).is_ok());
    let _ = Reference::World;
}

for_both_algebras!(
    joint_methods_converge_at_their_order,
    joint_and_body_methods_agree,
    joint_methods_account_the_work,
    dop853_joint_follows_its_tolerance,
    systems_without_joint_coordinates_refuse_them,
);
