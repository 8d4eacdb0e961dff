//! CPU time of the reference robots (UR5, Solo-12; `reference::robots`), per algebra: one evaluation of the equations
//! of motion — the body rates the body-momentum methods take, and the joint accelerations the joint-coordinate
//! methods take (forward kinematics and the articulated solve) — and one simulated second at MuJoCo's RK4 accuracy at
//! dt = 1e-3 (largest joint error over the reference's 1 s, at all 100 samples): UR5 by RKMK8-joint at dt = 1/60 s,
//! 6.5e-10 rad against MuJoCo's 6.8e-10; Solo-12 by RKMK6-joint at dt = 0.01 s, 7.2e-14 rad against MuJoCo's 3.7e-14,
//! both at the reference's own accuracy (3.4e-14 rad), where neither error means more than round-off. Pinocchio's ABA
//! and MuJoCo's RK4 are measured beside these with the scripts in `shared/robots/tools` (see docs/robots.md).
//!
//! `cargo bench -p scenarios --bench robots [-- FILTER]`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::motion::{BodyRates, Dynamics};
use dynamics::simulate::{simulate, Schedule};
use dynamics::{Algebra, Cga, JointMethod, Pga};
use reference::robots::RobotId;
use scenarios::build_robot;

/// The cheapest joint-coordinate method and step found to meet MuJoCo's RK4 accuracy at dt = 1e-3 on the robot.
fn matching_configuration(id: RobotId) -> (JointMethod, f64) {
    match id {
        RobotId::Ur5 => (JointMethod::Rkmk8, 1.0 / 60.0),
        RobotId::Solo12 => (JointMethod::Rkmk6, 0.01),
    }
}

fn robots<A: Algebra>(c: &mut Criterion) {
    for id in RobotId::ALL {
        let scene = build_robot::<A>(id).expect("the robot builds");
        let mechanism = scene.robot.mechanism();
        let mut group = c.benchmark_group(format!("{}/{}", A::NAME, id.name()));
        // One evaluation, as the body-momentum methods take it.
        let motors: Vec<A::Motor> = scene.initial.iter().map(|s| s.motor).collect();
        let momenta: Vec<A::Screw> = scene.initial.iter().map(|s| s.body_momentum()).collect();
        let zero = momenta[0] * 0.0;
        let mut rates = vec![
            BodyRates {
                body_velocity: zero,
                body_wrench: zero,
            };
            motors.len()
        ];
        let mut workspace = mechanism.workspace();
        group.bench_function("evaluation, body rates", |b| {
            b.iter(|| {
                mechanism
                    .body_rates(0.0, black_box(&motors), black_box(&momenta), &mut rates, &mut workspace)
                    .unwrap()
            })
        });
        // One evaluation in joint coordinates.
        let space = mechanism.joint_space().expect("a tree of joint models");
        let q = mechanism.joint_positions(&scene.initial, None).unwrap();
        let v = mechanism.joint_velocities(&scene.initial).unwrap();
        let mut accelerations = vec![0.0; space.velocity_count()];
        group.bench_function("evaluation, joint accelerations", |b| {
            b.iter(|| {
                mechanism
                    .joint_rates(0.0, black_box(&q), black_box(&v), &mut accelerations, &mut workspace)
                    .unwrap()
            })
        });
        // One simulated second at MuJoCo's accuracy.
        let (method, dt) = matching_configuration(id);
        let schedule = Schedule::with_sample_interval(dt, 1.0, 1.0).expect("a schedule");
        group.bench_function(format!("1 s, {}, dt = {dt:.4}", method.name()), |b| {
            b.iter(|| simulate(mechanism, black_box(&scene.initial), method, &schedule).unwrap())
        });
        group.finish();
    }
}

fn all(c: &mut Criterion) {
    robots::<Pga>(c);
    robots::<Cga>(c);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(2));
    targets = all
}
criterion_main!(benches);
