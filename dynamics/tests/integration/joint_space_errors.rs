//! Careless inputs to the joint models, joint coordinates and couplings (NaN, zero, negative, huge, wrong lengths
//! and counts, far from the origin): each row is an input and the words its error must contain — never a panic, a
//! NaN or a quiet answer.

use dynamics::constraints::{PathPoint, Stabilisation, VirtualPower};
use dynamics::{Body, Force, JointKind, JointMethod, JointModel, Mechanism, Method, Pga, Reference, State, Stepper};
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

type Outcome = Result<(), String>;

fn err<T, E: std::fmt::Display>(result: Result<T, E>) -> Outcome {
    match result {
        Ok(_) => Ok(()),
        Err(e) => Err(e.to_string()),
    }
}

fn identity() -> Isometry3<f64> {
    Isometry3::identity()
}

fn revolute(axis: Vector3<f64>) -> Result<JointModel, dynamics::ConstraintError> {
    JointModel::new(
        "hinge",
        JointKind::Revolute { axis },
        identity(),
        Isometry3::translation(0.0, 0.0, 0.5),
    )
}

/// A two-link arm on revolute joints (the second about a tilted axis), with gravity.
fn arm() -> Mechanism<Pga> {
    let link = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 1.0)).unwrap();
    let mut arm = Mechanism::<Pga>::new();
    let upper = arm.add_body("upper", link).unwrap();
    let lower = arm.add_body("lower", link).unwrap();
    for body in [upper, lower] {
        arm.add_force(body, Force::gravity()).unwrap();
    }
    let joint = |name: &str, above: f64, axis: Vector3<f64>| {
        JointModel::new(
            name,
            JointKind::Revolute { axis },
            Isometry3::translation(0.0, 0.0, above),
            Isometry3::translation(0.0, 0.0, 0.5),
        )
        .unwrap()
    };
    arm.connect(upper, Reference::World, joint("shoulder", 0.0, Vector3::x()))
        .unwrap();
    arm.connect(lower, upper, joint("elbow", -0.5, Vector3::new(0.0, 1.0, 1.0)))
        .unwrap();
    arm
}

fn states() -> Vec<State<Pga>> {
    arm().states_from_joints(&[0.3, -0.2], &[0.1, 0.4]).unwrap()
}

#[test]
fn careless_joint_models_are_refused_naming_the_joint() {
    let non_unit = Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::new_unchecked(Quaternion::new(2.0, 0.0, 0.0, 0.0)),
    );
    let cases: Vec<(&str, Outcome, &[&str])> = vec![
        (
            "zero axis",
            err(revolute(Vector3::zeros())),
            &["hinge", "axis", "no direction"],
        ),
        (
            "NaN axis",
            err(revolute(Vector3::new(f64::NAN, 0.0, 1.0))),
            &["hinge", "no direction"],
        ),
        (
            "infinite axis",
            err(revolute(Vector3::new(f64::INFINITY, 0.0, 0.0))),
            &["hinge", "no direction"],
        ),
        // An axis of 1e300 is a direction like any other (errors.rs, `axes_of_any_finite_length_are_directions`).
        (
            "empty name",
            err(JointModel::new("", JointKind::Spherical, identity(), identity())),
            &["non-empty name"],
        ),
        (
            "NaN frame",
            err(JointModel::new(
                "ball",
                JointKind::Spherical,
                Isometry3::translation(f64::NAN, 0.0, 0.0),
                identity(),
            )),
            &["ball", "parent's joint frame", "finite"],
        ),
        (
            "frame far out",
            err(JointModel::new(
                "ball",
                JointKind::Spherical,
                identity(),
                Isometry3::translation(1e60, 0.0, 0.0),
            )),
            &["ball", "child's joint frame"],
        ),
        (
            "non-unit rotation",
            err(JointModel::new("ball", JointKind::Spherical, non_unit, identity())),
            &["ball", "unit rotation"],
        ),
        (
            "universal axes not normal",
            err(JointModel::new(
                "cardan",
                JointKind::Universal {
                    first: Vector3::x(),
                    second: Vector3::new(1.0, 1.0, 0.0),
                },
                identity(),
                identity(),
            )),
            &["cardan", "normal", "cosine"],
        ),
        (
            "planar zero normal",
            err(JointModel::new(
                "slide",
                JointKind::Planar {
                    normal: Vector3::zeros(),
                },
                identity(),
                identity(),
            )),
            &["slide", "normal"],
        ),
        (
            "driven spherical joint",
            err(JointModel::new("ball", JointKind::Spherical, identity(), identity())
                .unwrap()
                .driven(|t: f64| PathPoint {
                    value: t,
                    rate: 1.0,
                    acceleration: 0.0,
                })),
            &["ball", "only revolute and prismatic"],
        ),
        (
            "joint pose, wrong count",
            err(revolute(Vector3::x()).unwrap().joint_pose(&[0.1, 0.2])),
            &["hinge", "takes 1", "got 2"],
        ),
        (
            "joint pose, NaN",
            err(revolute(Vector3::x()).unwrap().joint_pose(&[f64::NAN])),
            &["hinge", "finite"],
        ),
        (
            "joint pose, huge",
            err(revolute(Vector3::x()).unwrap().joint_pose(&[1e60])),
            &["hinge", "1e50"],
        ),
        (
            "joint pose, zero quaternion",
            err(JointModel::new("ball", JointKind::Spherical, identity(), identity())
                .unwrap()
                .joint_pose(&[0.0; 4])),
            &["ball", "no direction"],
        ),
    ];
    check(cases);
}

#[test]
fn careless_connections_and_couplings_are_refused() {
    let link = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 1.0)).unwrap();
    let mut other = Mechanism::<Pga>::new();
    let ids: Vec<_> = (0..4).map(|k| other.add_body(format!("b{k}"), link).unwrap()).collect();
    let mut arm = arm();
    let upper = arm.body_id("upper").unwrap();
    let lower = arm.body_id("lower").unwrap();
    let joints: Vec<_> = (0..2)
        .map(|k| arm.joint_space().unwrap().groups()[k].joint().unwrap())
        .collect();
    let ball = || JointModel::new("ball", JointKind::Spherical, identity(), identity()).unwrap();
    let mut cases: Vec<(&str, Outcome, &[&str])> = vec![
        (
            "unknown body",
            err(arm.clone().connect(ids[3], Reference::World, ball())),
            &["body index 3"],
        ),
        (
            "to itself",
            err(arm.clone().connect(upper, upper, ball())),
            &["ball", "itself"],
        ),
        (
            "second parent model",
            err(arm.clone().connect(lower, Reference::World, ball())),
            &["ball", "already has a parent joint model"],
        ),
        (
            "follows itself",
            err(arm.clone().couple(joints[0], joints[0], 1.0, 0.0)),
            &["shoulder", "itself"],
        ),
        (
            "NaN multiplier",
            err(arm.clone().couple(joints[1], joints[0], f64::NAN, 0.0)),
            &["elbow", "finite"],
        ),
        (
            "infinite offset",
            err(arm.clone().couple(joints[1], joints[0], 1.0, f64::INFINITY)),
            &["elbow", "finite"],
        ),
    ];
    // A coupling needs the articulated solve: refused with Baumgarte, and Baumgarte refused once coupled.
    let mut baumgarte = arm.clone();
    baumgarte
        .set_stabilisation(Stabilisation::Baumgarte {
            alpha: 10.0,
            beta: 10.0,
        })
        .unwrap();
    cases.push((
        "coupling under Baumgarte",
        err(baumgarte.couple(joints[1], joints[0], 1.0, 0.0)),
        &["articulated solve"],
    ));
    let mut coupled = arm.clone();
    coupled.couple(joints[1], joints[0], 2.0, 0.1).unwrap();
    cases.push((
        "a second leader",
        err(coupled.clone().couple(joints[1], joints[0], 1.0, 0.0)),
        &["elbow", "already follows"],
    ));
    cases.push((
        "Baumgarte after coupling",
        err(coupled
            .clone()
            .set_stabilisation(Stabilisation::Baumgarte { alpha: 1.0, beta: 1.0 })),
        &["Baumgarte", "couples joint coordinates"],
    ));
    let pin = VirtualPower::ball_joint("pin", Vector3::z(), Vector3::zeros());
    cases.push((
        "a loop after coupling",
        err(coupled.add_joint(lower, Reference::World, pin)),
        &["pin", "couples joint coordinates"],
    ));
    check(cases);
    arm.connect(ids[0], Reference::World, ball()).unwrap_err();
}

#[test]
fn careless_joint_coordinates_are_refused() {
    let arm = arm();
    let good = states();
    let mut nan = good.clone();
    nan[1].central_momentum *= f64::NAN;
    let cases: Vec<(&str, Outcome, &[&str])> = vec![
        (
            "positions, short",
            err(arm.states_from_joints(&[0.1], &[0.0, 0.0])),
            &["joint positions", "expected 2", "got 1"],
        ),
        (
            "velocities, long",
            err(arm.states_from_joints(&[0.1, 0.2], &[0.0; 3])),
            &["joint velocities", "expected 2", "got 3"],
        ),
        (
            "position NaN",
            err(arm.states_from_joints(&[f64::NAN, 0.0], &[0.0, 0.0])),
            &["shoulder", "finite"],
        ),
        (
            "position huge",
            err(arm.states_from_joints(&[0.0, 1e300], &[0.0, 0.0])),
            &["elbow", "1e50"],
        ),
        (
            "velocity NaN",
            err(arm.states_from_joints(&[0.0, 0.0], &[0.0, f64::NAN])),
            &["elbow", "finite"],
        ),
        (
            "velocity huge",
            err(arm.states_from_joints(&[0.0, 0.0], &[1e200, 0.0])),
            &["shoulder", "1e50"],
        ),
        (
            "read, too few states",
            err(arm.joint_positions(&good[..1], None)),
            &["states", "expected 2", "got 1"],
        ),
        (
            "read, too many states",
            err(arm.joint_velocities(&[good[0], good[1], good[0]])),
            &["states", "expected 2", "got 3"],
        ),
        (
            "read, previous wrong length",
            err(arm.joint_positions(&good, Some(&[0.0]))),
            &["previous joint positions", "got 1"],
        ),
        (
            "read, NaN state",
            err(arm.joint_positions(&nan, None)),
            &["state 1", "not finite"],
        ),
        (
            "mass matrix, no states",
            err(arm.mass_matrix(&[])),
            &["states", "expected 2", "got 0"],
        ),
        ("mass matrix, NaN state", err(arm.mass_matrix(&nan)), &["state 1"]),
        ("bias forces, NaN state", err(arm.bias_forces(0.0, &nan)), &["state 1"]),
        (
            "inverse dynamics, short",
            err(arm.inverse_dynamics(0.0, &good, &[1.0])),
            &["joint accelerations", "expected 2"],
        ),
        (
            "inverse dynamics, NaN",
            err(arm.inverse_dynamics(0.0, &good, &[1.0, f64::NAN])),
            &["joint acceleration 1"],
        ),
        (
            "inverse dynamics, huge",
            err(arm.inverse_dynamics(0.0, &good, &[1e300, 0.0])),
            &["joint acceleration 0"],
        ),
        (
            "accelerations, NaN state",
            err(arm.joint_accelerations(0.0, &nan)),
            &["state 1"],
        ),
    ];
    check(cases);
}

/// Far from the origin the coordinates still read back and the mass matrix stays the one at the origin: the
/// arm carried 1e6 m out on a slide.
#[test]
fn joint_coordinates_far_from_the_origin() {
    let link = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 1.0)).unwrap();
    let build = |offset: f64| {
        let mut arm = Mechanism::<Pga>::new();
        let upper = arm.add_body("upper", link).unwrap();
        let lower = arm.add_body("lower", link).unwrap();
        let shoulder = Isometry3::translation(offset, 0.0, 0.0);
        arm.connect(
            upper,
            Reference::World,
            JointModel::new(
                "shoulder",
                JointKind::Revolute { axis: Vector3::x() },
                shoulder,
                Isometry3::translation(0.0, 0.0, 0.5),
            )
            .unwrap(),
        )
        .unwrap();
        arm.connect(
            lower,
            upper,
            JointModel::new(
                "elbow",
                JointKind::Revolute { axis: Vector3::y() },
                Isometry3::translation(0.0, 0.0, -0.5),
                Isometry3::translation(0.0, 0.0, 0.5),
            )
            .unwrap(),
        )
        .unwrap();
        arm
    };
    let (near, far) = (build(0.0), build(1e6));
    let q = [0.4, -0.7];
    let (a, b) = (
        near.states_from_joints(&q, &[0.2, 0.1]).unwrap(),
        far.states_from_joints(&q, &[0.2, 0.1]).unwrap(),
    );
    let read = far.joint_positions(&b, None).unwrap();
    // Poses 1e6 m out carry ~1e-10 m of round-off, over lever arms of 0.5 m.
    assert!(
        (read[0] - q[0]).abs() < 1e-9 && (read[1] - q[1]).abs() < 1e-9,
        "{read:?}"
    );
    let (m_near, m_far) = (near.mass_matrix(&a).unwrap(), far.mass_matrix(&b).unwrap());
    assert!(
        (m_near - m_far).amax() < 1e-9,
        "mass matrices differ by {:e}",
        (near.mass_matrix(&a).unwrap() - far.mass_matrix(&b).unwrap()).amax()
    );
}

#[test]
fn joint_methods_refuse_systems_without_joint_coordinates() {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let string = VirtualPower::point_on_sphere("string", Vector3::zeros(), Vector3::z(), 1.0).unwrap();
    let held = Mechanism::<Pga>::single(ball).with_constraint(string).unwrap();
    let refused = Stepper::new(&held, JointMethod::Rkmk8).err().unwrap().to_string();
    assert!(
        refused.contains("RKMK8-joint") && refused.contains("joint models"),
        "{refused}"
    );
    // The body methods still take it.
    assert!(Stepper::new(&held, Method::Rkmk8Body).is_ok());
}

fn check(cases: Vec<(&str, Outcome, &[&str])>) {
    for (label, outcome, words) in cases {
        match outcome {
            Ok(()) => panic!("{label}: accepted"),
            Err(message) => {
                for word in words {
                    assert!(message.contains(word), "{label}: {message:?} lacks {word:?}");
                }
            }
        }
    }
}

/// Every method of a system that takes one entry per body (or per joint coordinate) refuses another count, naming
/// both counts: never an index out of bounds, and never an answer about some of the bodies (the energy of the first
/// of two links read as the system's).
#[test]
fn wrong_counts_are_refused_with_both_counts() {
    use dynamics::motion::{BodyRates, Dynamics, Rates};
    use dynamics::{simulate, FreeBody, Schedule, SimulationError};

    let arm = arm();
    let good = states();
    let three = [good[0], good[1], good[1]];
    let mut workspace = arm.workspace();
    let zero = good[0].central_momentum * 0.0;
    let mut rates = vec![
        Rates {
            body_velocity: zero,
            momentum_rate: zero
        };
        2
    ];
    let mut body_rates = vec![
        BodyRates {
            body_velocity: zero,
            body_wrench: zero
        };
        2
    ];
    let motors: Vec<_> = good.iter().map(|s| s.motor).collect();
    let momenta: Vec<_> = good.iter().map(|s| s.body_momentum()).collect();
    let (mut q, mut v) = (vec![0.0; 2], vec![0.0; 2]);
    let mut written = good.clone();
    let mut more = three.to_vec();
    let mut fewer = good[..1].to_vec();
    let cases: Vec<(&str, Outcome, &[&str])> = vec![
        (
            "energy, one of two",
            err(arm.energy(&good[..1])),
            &["states", "1 given", "has 2"],
        ),
        ("energy, none", err(arm.energy(&[])), &["states", "0 given", "has 2"]),
        (
            "momentum, three",
            err(arm.momentum(&three)),
            &["states", "3 given", "has 2"],
        ),
        (
            "violation, three",
            err(arm.violation(0.0, &three)),
            &["states", "3 given", "has 2"],
        ),
        (
            "violation, one",
            err(arm.violation(0.0, &good[..1])),
            &["1 given", "has 2"],
        ),
        (
            "rates_at, none",
            err(arm.rates_at(0.0, &[])),
            &["states", "0 given", "has 2"],
        ),
        ("rates_at, three", err(arm.rates_at(0.0, &three)), &["3 given", "has 2"]),
        (
            "reactions, three",
            err(arm.reactions(0.0, &three)),
            &["states", "3 given"],
        ),
        ("reactions, one", err(arm.reactions(0.0, &good[..1])), &["1 given"]),
        (
            "project, three",
            err(arm.project(0.0, &mut more)),
            &["states", "3 given"],
        ),
        ("project, one", err(arm.project(0.0, &mut fewer)), &["1 given"]),
        (
            "rates, three states",
            err(arm.rates(0.0, &three, &mut rates, &mut workspace)),
            &["states", "3 given"],
        ),
        (
            "rates, one rate",
            err(arm.rates(0.0, &good, &mut rates[..1], &mut workspace)),
            &["rates", "1 given"],
        ),
        (
            "body rates, one motor",
            err(arm.body_rates(0.0, &motors[..1], &momenta, &mut body_rates, &mut workspace)),
            &["motors", "1 given"],
        ),
        (
            "body rates, no momenta",
            err(arm.body_rates(0.0, &motors, &[], &mut body_rates, &mut workspace)),
            &["body momenta", "0 given"],
        ),
        (
            "after step, three",
            err(arm.after_step(0.0, &mut more, &mut workspace)),
            &["states", "3 given"],
        ),
        (
            "read joints, one state",
            err(arm.read_joints(&good[..1], &mut q, &mut v, &mut workspace)),
            &["states", "1 given"],
        ),
        (
            "read joints, three positions",
            err(arm.read_joints(&good, &mut [0.0; 3], &mut v, &mut workspace)),
            &["joint positions", "3 given", "has 2"],
        ),
        (
            "write joints, one velocity",
            err(arm.write_joints(0.0, &[0.0; 2], &[0.0], &mut written, &mut workspace)),
            &["joint velocities", "1 given"],
        ),
        (
            "joint rates, three accelerations",
            err(arm.joint_rates(0.0, &[0.0; 2], &[0.0; 2], &mut [0.0; 3], &mut workspace)),
            &["joint accelerations", "3 given", "has 2"],
        ),
        (
            "joint rates, one position",
            err(arm.joint_rates(0.0, &[0.0], &[0.0; 2], &mut [0.0; 2], &mut workspace)),
            &["joint positions", "1 given"],
        ),
    ];
    check(cases);

    // A free body takes exactly one of each.
    let ball = FreeBody::<Pga>::new(Body::sphere(1.0, 0.1).unwrap());
    let mut free_workspace = ball.workspace();
    let two = [good[0], good[0]];
    check(vec![
        (
            "free body, two states",
            err(ball.rates(0.0, &two, &mut rates, &mut free_workspace)),
            &["states", "2 given", "has 1"],
        ),
        (
            "free body, no rates",
            err(ball.body_rates(0.0, &motors[..1], &momenta[..1], &mut [], &mut free_workspace)),
            &["rates", "0 given", "has 1"],
        ),
    ]);

    // The right counts still answer, and the energy is the whole system's.
    let whole = arm.energy(&good).unwrap();
    assert!(whole.is_finite());
    assert!(arm.violation(0.0, &good).is_ok() && arm.rates_at(0.0, &good).is_ok());

    // A mechanism without bodies has nothing to simulate.
    let empty = Mechanism::<Pga>::new();
    let run = simulate(&empty, &[], Method::Rk4, &Schedule::new(1e-3, 0.1).unwrap());
    assert!(matches!(run, Err(SimulationError::NoBodies)), "{run:?}");
}
