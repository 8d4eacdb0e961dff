//! Joints between two moving bodies (docs/mechanisms.md §M2): body A hangs from the world by a ball joint, body
//! B hangs from A by the joint under test, under gravity. For each joint of the catalogue, written by pinning
//! and by virtual power: the joint holds to round-off (measured from the poses with the joint's own geometry,
//! not from the solver's residuals), the motions it allows happen, the two formulations give the same motion,
//! and the energy is conserved. Then driven joints: a motor joint (the relative motor follows U(t)) by both
//! formulations, and a pivot moved by user wrenches with their prescribed power.

use std::sync::Arc;

use dynamics::constraints::{
    linear, pinning, Constraint, MotorPath, PathPoint, PinningAlgebra, ScrewMotion, Stabilisation, VirtualPower,
    WrenchPoint,
};
use dynamics::forces::force_line;
use dynamics::{
    motor, simulate, Algebra, Body, Cga, Force, Mechanism, Method, Pga, Reference, Schedule, ScrewCoordinates,
    Simulation, State,
};
use nalgebra::{UnitQuaternion, Vector3};

/// A's joint point (body A, its bottom) and B's (body B, its top).
const ON_A: Vector3<f64> = Vector3::new(0.0, 0.0, -0.5);
const ON_B: Vector3<f64> = Vector3::new(0.0, 0.0, 0.4);

fn body_a() -> Body {
    Body::cuboid(1.0, Vector3::new(0.1, 0.2, 1.0)).unwrap()
}

fn body_b() -> Body {
    Body::cuboid(0.6, Vector3::new(0.3, 0.1, 0.8)).unwrap()
}

/// A joint of the catalogue: both formulations, the relative pose it starts from (B relative to A: rotation
/// and offset of B's joint point from A's), and what stays fixed (measured from the poses).
struct Case<A: Algebra> {
    name: &'static str,
    pinned: Arc<dyn Constraint<A>>,
    by_power: Arc<dyn Constraint<A>>,
    start: (UnitQuaternion<f64>, Vector3<f64>),
    /// The joint's violation (m) at the two bodies' poses.
    violation: fn(&Pose, &Pose) -> f64,
    /// How far B moved relative to A in the joint's free directions over the run (must be well above zero).
    freedom: fn(&Pose, &Pose, &Pose, &Pose) -> f64,
    /// How closely the two formulations' runs agree (m).
    agreement: f64,
}

#[derive(Clone, Copy, Debug)]
struct Pose {
    position: Vector3<f64>,
    rotation: UnitQuaternion<f64>,
}

impl Pose {
    fn point(&self, body: Vector3<f64>) -> Vector3<f64> {
        self.position + self.rotation * body
    }

    fn direction(&self, body: Vector3<f64>) -> Vector3<f64> {
        self.rotation * body
    }
}

/// B's joint point relative to A's, in A's frame.
fn offset(a: &Pose, b: &Pose) -> Vector3<f64> {
    a.rotation.inverse() * (b.point(ON_B) - a.point(ON_A))
}

/// B's rotation relative to A.
fn relative(a: &Pose, b: &Pose) -> UnitQuaternion<f64> {
    a.rotation.inverse() * b.rotation
}

fn cases<A: PinningAlgebra>() -> Vec<Case<A>> {
    let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
    let turn = |axis: Vector3<f64>, angle: f64| UnitQuaternion::from_scaled_axis(axis * angle);
    vec![
        Case {
            name: "ball",
            pinned: Arc::new(pinning::point::<A>("ball", ON_B, ON_A)),
            by_power: Arc::new(VirtualPower::ball_joint("ball", ON_B, ON_A)),
            start: (turn(Vector3::new(0.3, -0.5, 0.2), 1.0), Vector3::zeros()),
            violation: |a, b| offset(a, b).norm(),
            freedom: |a0, b0, a1, b1| relative(a0, b0).angle_to(&relative(a1, b1)),
            agreement: 1e-10,
        },
        Case {
            name: "hinge",
            pinned: Arc::new(pinning::hinge::<A>("hinge", (ON_B, y), (ON_A, y)).unwrap()),
            by_power: Arc::new(VirtualPower::hinge("hinge", (ON_B, y), (ON_A, y)).unwrap()),
            start: (turn(y, 0.8), Vector3::zeros()),
            // The point and the axis: B's y stays A's y.
            violation: |a, b| {
                let y = Vector3::y();
                offset(a, b).norm().max((a.direction(y) - b.direction(y)).norm())
            },
            freedom: |a0, b0, a1, b1| relative(a0, b0).angle_to(&relative(a1, b1)),
            agreement: 1e-10,
        },
        Case {
            name: "cylindrical",
            pinned: Arc::new(pinning::line::<A>("cylindrical", (ON_B, y), (ON_A, y)).unwrap()),
            by_power: Arc::new(VirtualPower::cylindrical("cylindrical", (ON_B, y), (ON_A, y)).unwrap()),
            start: (turn(y, 0.8), 0.2 * y),
            // B's point stays on A's axis, and the axes stay parallel.
            violation: |a, b| {
                let y = Vector3::y();
                offset(a, b)
                    .cross(&y)
                    .norm()
                    .max((a.direction(y) - b.direction(y)).norm())
            },
            freedom: |a0, b0, a1, b1| (offset(a0, b0).y - offset(a1, b1).y).abs(),
            agreement: 1e-10,
        },
        Case {
            name: "prismatic",
            pinned: Arc::new(pinning::prismatic::<A>("prismatic", (ON_B, x, z), (ON_A, x, z)).unwrap()),
            by_power: Arc::new(VirtualPower::prismatic("prismatic", (ON_B, x, z), (ON_A, x, z)).unwrap()),
            start: (UnitQuaternion::identity(), 0.15 * x),
            // B's point stays on A's x axis and B does not turn relative to A.
            violation: |a, b| offset(a, b).cross(&Vector3::x()).norm().max(relative(a, b).angle()),
            freedom: |a0, b0, a1, b1| (offset(a0, b0).x - offset(a1, b1).x).abs(),
            agreement: 1e-10,
        },
        Case {
            name: "planar",
            pinned: Arc::new(pinning::plane::<A>("planar", (z, ON_B.z), (z, ON_A.z)).unwrap()),
            by_power: Arc::new(VirtualPower::planar("planar", (ON_B, z), (ON_A, z)).unwrap()),
            start: (turn(z, 0.5), Vector3::new(0.1, -0.05, 0.0)),
            // B's plane z = 0.4 stays on A's plane z = −0.5 with the normals aligned.
            violation: |a, b| {
                let z = Vector3::z();
                offset(a, b).z.abs().max((a.direction(z) - b.direction(z)).norm())
            },
            freedom: |a0, b0, a1, b1| {
                (offset(a0, b0) - offset(a1, b1)).norm() + relative(a0, b0).angle_to(&relative(a1, b1))
            },
            agreement: 1e-10,
        },
        Case {
            name: "point on plane",
            pinned: Arc::new(linear::point_on_plane::<A>("point on plane", ON_B, (z, ON_A.z))),
            by_power: Arc::new(VirtualPower::point_on_plane("point on plane", ON_B, (z, ON_A.z)).unwrap()),
            start: (turn(Vector3::new(1.0, 2.0, 0.5), 0.7), Vector3::new(0.1, 0.05, 0.0)),
            violation: |a, b| offset(a, b).z.abs(),
            freedom: |a0, b0, a1, b1| (offset(a0, b0) - offset(a1, b1)).norm(),
            agreement: 1e-10,
        },
        Case {
            name: "point on line",
            pinned: Arc::new(linear::point_on_line::<A>("point on line", ON_B, (ON_A, x))),
            by_power: Arc::new(VirtualPower::point_on_line("point on line", ON_B, (ON_A, x)).unwrap()),
            start: (turn(Vector3::new(1.0, 2.0, 0.5), 0.7), 0.1 * x),
            violation: |a, b| offset(a, b).cross(&Vector3::x()).norm(),
            freedom: |a0, b0, a1, b1| (offset(a0, b0).x - offset(a1, b1).x).abs(),
            // The incidence `P ∧ L` (`L × P`) picks up spurious singular values off the manifold (theory §12, E8), where
            // the integrator's stages are, so its truncation error differs from the virtual-power rows': the runs
            // differ by 7.6e-8 m at dt = 1e-3, 4.8e-9 at 5e-4, 3.0e-10 at 2.5e-4 (order 4: the same motion).
            agreement: 3e-7,
        },
    ]
}

/// The two bodies with B joined to A by `joint`, started at the case's relative pose with a spin, projected.
fn two_bodies<A: Algebra>(
    joint: Arc<dyn Constraint<A>>,
    start: (UnitQuaternion<f64>, Vector3<f64>),
) -> (Mechanism<A>, Vec<State<A>>) {
    let mut system = Mechanism::<A>::new();
    let a = system.add_body("A", body_a()).unwrap();
    let b = system.add_body("B", body_b()).unwrap();
    system.add_force(a, Force::gravity()).unwrap();
    system.add_force(b, Force::gravity()).unwrap();
    let top = Vector3::new(0.0, 0.0, 0.5);
    system
        .add_joint(
            a,
            Reference::World,
            VirtualPower::ball_joint("pivot", top, Vector3::zeros()),
        )
        .unwrap();
    system.add_joint(b, a, joint).unwrap();
    system.set_stabilisation(Stabilisation::PROJECTION).unwrap();
    let rotation_a = UnitQuaternion::from_scaled_axis(Vector3::new(0.6, 0.2, -0.1));
    let centre_a = -(rotation_a * top);
    let (relative_rotation, shift) = start;
    let rotation_b = rotation_a * relative_rotation;
    let centre_b = centre_a + rotation_a * (ON_A + shift) - rotation_b * ON_B;
    let mut states = vec![
        State::new(
            &body_a(),
            centre_a,
            &rotation_a,
            Vector3::new(0.5, -1.0, 0.8),
            Vector3::zeros(),
        ),
        State::new(
            &body_b(),
            centre_b,
            &rotation_b,
            Vector3::new(-1.2, 0.7, 1.5),
            Vector3::new(0.3, 0.5, -0.2),
        ),
    ];
    system.project(0.0, &mut states).unwrap();
    (system, states)
}

fn poses<A: Algebra>(run: &Simulation<A>, k: usize) -> (Pose, Pose) {
    let pose = |i: usize| Pose {
        position: run.body(i)[k].position,
        rotation: run.body(i)[k].orientation,
    };
    (pose(0), pose(1))
}

/// Every joint, both formulations, 2 s of RKMK4-body at dt = 1e-3 with projection. Measured (both algebras): the
/// joints hold to ≤ 1.8e-14 m (and rad); the formulations agree to ≤ 1.3e-11 m (point on line: see its case);
/// the energy moves by ≤ 6.1e-9 J (truncation); every free motion is at least 1.1 (m or rad).
fn joints_hold_and_agree<A: PinningAlgebra>() {
    let schedule = Schedule::new(1e-3, 2.0).unwrap();
    for case in cases::<A>() {
        let runs: Vec<Simulation<A>> = [case.pinned.clone(), case.by_power.clone()]
            .into_iter()
            .map(|joint| {
                let (system, initial) = two_bodies::<A>(joint, case.start);
                simulate(&system, &initial, Method::Rkmk4Body, &schedule).unwrap()
            })
            .collect();
        let samples = runs[0].body(0).len();
        let (mut violation, mut difference, mut energy) = (0.0f64, 0.0f64, 0.0f64);
        for run in &runs {
            let e0 = run.body(0)[0].energy;
            for k in 0..samples {
                let (a, b) = poses(run, k);
                violation = violation.max((case.violation)(&a, &b));
                energy = energy.max((run.body(0)[k].energy - e0).abs());
            }
        }
        for k in 0..samples {
            let ((a0, b0), (a1, b1)) = (poses(&runs[0], k), poses(&runs[1], k));
            difference = difference
                .max((a0.position - a1.position).norm())
                .max((b0.position - b1.position).norm());
        }
        let ((a0, b0), (a1, b1)) = (poses(&runs[1], 0), poses(&runs[1], samples - 1));
        let freedom = (case.freedom)(&a0, &b0, &a1, &b1);
        println!(
            "{} {}: joint {violation:.1e}, formulations differ by {difference:.1e} m, energy {energy:.1e} J, free \
             motion {freedom:.2}",
            A::NAME,
            case.name
        );
        assert!(violation < 1e-13, "{}: {violation:e}", case.name);
        assert!(difference < case.agreement, "{}: {difference:e}", case.name);
        assert!(energy < 1e-8, "{}: {energy:e}", case.name);
        assert!(freedom > 0.05, "{}: {freedom}", case.name);
    }
}

#[test]
fn pga_joints_hold_and_agree() {
    joints_hold_and_agree::<Pga>();
}

#[test]
fn cga_joints_hold_and_agree() {
    joints_hold_and_agree::<Cga>();
}

/// A linear function of pinned multivectors between bodies (CGA): B's point stays on a sphere carried by A,
/// `P ∧ S = 0` with S fixed in A's frame, against the same constraint by virtual power. Measured: both hold the
/// sphere to 2.5e-14 m and agree to 1.6e-14 m over 2 s.
#[test]
fn point_on_a_sphere_carried_by_another_body() {
    let (centre, radius) = (Vector3::new(0.0, 0.0, -0.9), 0.4);
    let schedule = Schedule::new(1e-3, 2.0).unwrap();
    let constraints: [Arc<dyn Constraint<Cga>>; 2] = [
        Arc::new(linear::cga_point_on_sphere("on sphere", ON_B, centre, radius)),
        Arc::new(VirtualPower::point_on_sphere("on sphere", ON_B, centre, radius).unwrap()),
    ];
    let runs: Vec<Simulation<Cga>> = constraints
        .into_iter()
        .map(|joint| {
            // B's point starts on the sphere, straight below its centre.
            let (system, initial) =
                two_bodies::<Cga>(joint, (UnitQuaternion::identity(), Vector3::new(0.0, 0.0, -0.8)));
            simulate(&system, &initial, Method::Rkmk4Body, &schedule).unwrap()
        })
        .collect();
    let (mut violation, mut difference) = (0.0f64, 0.0f64);
    for k in 0..runs[0].body(0).len() {
        for run in &runs {
            let (a, b) = poses(run, k);
            violation = violation.max(((b.point(ON_B) - a.point(centre)).norm() - radius).abs());
        }
        let ((_, b0), (_, b1)) = (poses(&runs[0], k), poses(&runs[1], k));
        difference = difference.max((b0.position - b1.position).norm());
    }
    println!("CGA point on a carried sphere: {violation:.1e} m, formulations differ by {difference:.1e} m");
    assert!(violation < 1e-13 && difference < 1e-10, "{violation:e} {difference:e}");
}

/// A motor joint: A swings from the world by a hinge; B's motor relative to A follows U(t), a turn about A's z by
/// θ(t) = 0.8 sin 3t about B's joint point, by pinning and by virtual power. Measured: the relative pose follows
/// U(t) to 1.4e-14 (m and rad) in both, and the formulations agree on A's swing to 2.8e-13 rad over 2 s.
fn motor_joint_follows_its_path<A: PinningAlgebra>() {
    let theta = |t: f64| PathPoint {
        value: 0.8 * (3.0 * t).sin(),
        rate: 2.4 * (3.0 * t).cos(),
        acceleration: -7.2 * (3.0 * t).sin(),
    };
    // U(t) = U₀ exp(−½θ l₃): B's frame turned about its z axis, its joint point at A's; U₀ places B's joint point
    // ON_B at A's ON_A.
    let start = motor::translator::<A>(ON_A - ON_B);
    let z = A::screw(ScrewCoordinates {
        l: Vector3::z(),
        t: Vector3::zeros(),
    });
    // The turn about B's joint point rather than its centre: the screw l₃ moved to ON_B.
    let about_point =
        A::screw(motor::ScrewFrame::of::<A>(motor::translator::<A>(ON_B)).to_world(&A::screw_coordinates(z)));
    let path = Arc::new(ScrewMotion::<A, _>::new(start, about_point, theta));
    let schedule = Schedule::new(1e-3, 2.0).unwrap();
    let joints: [Arc<dyn Constraint<A>>; 2] = [
        Arc::new(pinning::motor_joint::<A>("motor", path.clone())),
        Arc::new(VirtualPower::motor_joint("motor", path.clone())),
    ];
    let mut swings = Vec::new();
    for joint in joints {
        let mut system = Mechanism::<A>::new();
        let a = system.add_body("A", body_a()).unwrap();
        let b = system.add_body("B", body_b()).unwrap();
        system.add_force(a, Force::gravity()).unwrap();
        system.add_force(b, Force::gravity()).unwrap();
        let top = Vector3::new(0.0, 0.0, 0.5);
        system
            .add_joint(
                a,
                Reference::World,
                VirtualPower::hinge("hinge", (top, Vector3::x()), (Vector3::zeros(), Vector3::x())).unwrap(),
            )
            .unwrap();
        system.add_joint(b, a, joint).unwrap();
        system.set_stabilisation(Stabilisation::PROJECTION).unwrap();
        let rotation_a = UnitQuaternion::from_scaled_axis(Vector3::x() * 0.5);
        let centre_a = -(rotation_a * top);
        let mut states = vec![
            State::new(&body_a(), centre_a, &rotation_a, Vector3::zeros(), Vector3::zeros()),
            State::new(
                &body_b(),
                centre_a + rotation_a * (ON_A - ON_B),
                &rotation_a,
                Vector3::zeros(),
                Vector3::zeros(),
            ),
        ];
        system.project(0.0, &mut states).unwrap();
        let run = simulate(&system, &states, Method::Rkmk4Body, &schedule).unwrap();
        let mut worst = 0.0f64;
        for k in 0..run.body(0).len() {
            let (pa, pb) = poses(&run, k);
            let expected = path.at(run.body(0)[k].t).motor;
            let (position, rotation) = motor::pose::<A>(expected);
            let actual_rotation = relative(&pa, &pb);
            let actual_position = pa.rotation.inverse() * (pb.position - pa.position);
            worst = worst
                .max(actual_rotation.angle_to(&rotation))
                .max((actual_position - position).norm());
        }
        println!("{} motor joint: relative pose off the path by {worst:.1e}", A::NAME);
        assert!(worst < 1e-12, "{worst:e}");
        swings.push(run.body(0).iter().map(|s| s.orientation).collect::<Vec<_>>());
    }
    let difference = swings[0]
        .iter()
        .zip(&swings[1])
        .map(|(p, q)| p.angle_to(q))
        .fold(0.0, f64::max);
    println!("{} motor joint: formulations differ by {difference:.1e} rad", A::NAME);
    assert!(difference < 1e-10, "{difference:e}");
}

#[test]
fn pga_motor_joint_follows_its_path() {
    motor_joint_follows_its_path::<Pga>();
}

#[test]
fn cga_motor_joint_follows_its_path() {
    motor_joint_follows_its_path::<Cga>();
}

/// A pivot moved along p(t) = (0.2 sin 2t, 0, 0.1 t²) by user wrenches — three force lines through p(t), each with
/// the prescribed power `f·ṗ` of the driven motion — against the driven ball joint of the catalogue and the pinned
/// moving point. Without a position residual the user form runs unstabilised; measured over 1 s: the three agree
/// to 3.7e-13 m, and the pivot is followed to 1.4e-13 m.
#[test]
fn a_moving_pivot_by_prescribed_power() {
    let pivot = |t: f64| PathPoint {
        value: Vector3::new(0.2 * (2.0 * t).sin(), 0.0, 0.1 * t * t),
        rate: Vector3::new(0.4 * (2.0 * t).cos(), 0.0, 0.2 * t),
        acceleration: Vector3::new(-0.8 * (2.0 * t).sin(), 0.0, 0.2),
    };
    let tip = Vector3::new(0.0, 0.0, 0.5);
    let wrenches = (0..3)
        .map(|k| {
            let direction = Vector3::ith(k, 1.0);
            move |t: f64| {
                let p = pivot(t);
                WrenchPoint {
                    wrench: force_line::<Pga>(direction, p.value),
                    // d/dt (f, p⨯f) = (0, ṗ⨯f).
                    rate: dynamics::forces::couple::<Pga>(p.rate.cross(&direction)),
                    power: direction.dot(&p.rate),
                    power_rate: direction.dot(&p.acceleration),
                }
            }
        })
        .collect::<Vec<_>>();
    let constraints: [Arc<dyn Constraint<Pga>>; 3] = [
        Arc::new(VirtualPower::from_wrenches("user wrenches", wrenches)),
        Arc::new(VirtualPower::driven_ball_joint("driven ball", tip, pivot)),
        Arc::new(pinning::driven_point::<Pga>("driven point", tip, pivot)),
    ];
    let body = body_a();
    let schedule = Schedule::new(1e-3, 1.0).unwrap();
    let runs: Vec<Simulation<Pga>> = constraints
        .into_iter()
        .map(|constraint| {
            // Unstabilised, as user wrenches have no position residual to project.
            let system = Mechanism::<Pga>::single(body)
                .with_stabilisation(Stabilisation::None)
                .unwrap()
                .with_force(Force::gravity())
                .unwrap()
                .with_constraint(constraint)
                .unwrap();
            let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(0.4, 0.0, 0.0));
            let initial = State::new(
                &body,
                -(rotation * tip),
                &rotation,
                Vector3::zeros(),
                Vector3::new(0.4, 0.0, 0.0),
            );
            simulate(&system, &[initial], Method::Rkmk4Body, &schedule).unwrap()
        })
        .collect();
    let (mut difference, mut off) = (0.0f64, 0.0f64);
    for k in 0..runs[0].body(0).len() {
        let t = runs[0].body(0)[k].t;
        for run in &runs {
            let s = &run.body(0)[k];
            off = off.max((s.position + s.orientation * tip - pivot(t).value).norm());
            difference = difference.max((s.position - runs[0].body(0)[k].position).norm());
        }
    }
    println!("moving pivot: the forms differ by {difference:.1e} m, the pivot is followed to {off:.1e} m");
    assert!(difference < 3e-12 && off < 1e-12, "{difference:e} {off:e}");
}
