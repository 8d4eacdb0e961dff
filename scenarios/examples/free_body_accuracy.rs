//! Scene 1 (the Dzhanibekov cuboid, docs/scenes.md) with every integrator in both algebras over a range of steps:
//! error at T = 10 s against the reference trajectory, energy drift, flip-time error, and CPU time per step
//! and per simulated second; then the comparison with the anchor, and classic RK4 on (q, ω_body) for contrast.
//!
//! `cargo run --release -p scenarios --example free_body_accuracy`
//!
//! The anchor (task brief): MuJoCo 4.0 RK4 takes 4.3 µs/step and reaches 2e-10 rad orientation error at
//! dt = 1e-3, i.e. 4.3 ms CPU per simulated second; the target is ≥ 10× less CPU per simulated second at
//! equal or smaller error.

use std::time::Instant;

use dynamics::{simulate, Algebra, Body, Cga, FreeBody, Integrator, Pga, Schedule, State};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use reference::{flip_time_error, flip_times, trajectory_errors, SceneId, SceneParameters, Trajectory};

const STEPS: [f64; 8] = [1e-2, 5e-3, 2.5e-3, 2e-3, 1e-3, 1e-2 / 11.0, 5e-4, 1e-4];
const ANCHOR_ERROR: f64 = 2e-10;
const ANCHOR_MILLISECONDS_PER_SECOND: f64 = 4.3;

/// One row of the table.
struct Row {
    algebra: &'static str,
    integrator: &'static str,
    dt: f64,
    end_orientation: f64,
    milliseconds_per_second: f64,
}

fn table<A: Algebra>(scene: &SceneParameters, reference: &Trajectory, rows: &mut Vec<Row>) {
    let body = Body::new(scene.mass, scene.principal_moments).expect("scene 1 body is physical");
    let system = FreeBody::<A>::new(body);
    let initial = State::<A>::new(
        &body,
        scene.initial_com,
        &scene.initial_orientation,
        scene.initial_body_angular_velocity,
        scene.initial_com_velocity,
    );
    let e0 = scene.initial_energy;
    for integrator in Integrator::ALL {
        for dt in STEPS {
            let schedule = Schedule::new(dt, scene.duration).expect("dt divides 0.01");
            // Best of three for the timing: the machine may be shared.
            let runs: Vec<_> = (0..3)
                .map(|_| simulate(&system, &[initial], integrator, &schedule))
                .collect::<Result<_, _>>()
                .expect("scene 1 runs");
            let run = runs.iter().min_by_key(|r| r.stepping_time).expect("three runs");
            let simulated = scenarios::trajectory(run.body(0)).expect("samples with increasing times");
            let errors = trajectory_errors(reference, &simulated).expect("same grid");
            let flips = flip_times(&simulated, &scene.principal_moments);
            let flip_error =
                flip_time_error(&flips, &reference::scenes::CUBOID_VALUES.flip_instants).unwrap_or(f64::NAN);
            let energy = run
                .body(0)
                .iter()
                .map(|s| (s.energy - e0).abs() / e0)
                .fold(0.0, f64::max);
            let per_step = run.time_per_step().as_secs_f64() * 1e6;
            let per_second = run.stepping_time.as_secs_f64() * 1e3 / scene.duration;
            println!(
                "{:<4} {:<10} {:>8.2e} {:>10.2e} {:>10.2e} {:>10.2e} {:>10.2e} {:>10.2e} {:>8.3} {:>9.3}",
                A::NAME,
                integrator.name(),
                dt,
                errors.end_orientation,
                errors.max_orientation,
                errors.max_position,
                energy,
                flip_error,
                per_step,
                per_second,
            );
            rows.push(Row {
                algebra: A::NAME,
                integrator: integrator.name(),
                dt,
                end_orientation: errors.end_orientation,
                milliseconds_per_second: per_second,
            });
        }
    }
}

/// Classic RK4 on the unit quaternion and the body angular velocity (Euler's equations), plain nalgebra, with
/// the quaternion renormalised after each step: the formulation of the classical references and of MuJoCo's
/// free joint, in which errors of the orientation never feed back into the angular velocity.
fn classic_rk4(scene: &SceneParameters, reference: &Trajectory, dt: f64) -> (f64, f64) {
    let inertia = scene.principal_moments;
    let rates = |q: &Quaternion<f64>, w: &Vector3<f64>| {
        let q_dot = q * Quaternion::from_imag(*w) * 0.5;
        let w_dot = (-w.cross(&inertia.component_mul(w))).component_div(&inertia);
        (q_dot, w_dot)
    };
    let steps_per_sample = (reference::scenes::SAMPLE_INTERVAL / dt).round() as usize;
    let mut q = *scene.initial_orientation.quaternion();
    let mut w = scene.initial_body_angular_velocity;
    let (mut end, mut worst) = (0.0, 0.0f64);
    for expected in &reference.samples()[1..] {
        for _ in 0..steps_per_sample {
            let (q1, w1) = rates(&q, &w);
            let (q2, w2) = rates(&(q + q1 * (0.5 * dt)), &(w + w1 * (0.5 * dt)));
            let (q3, w3) = rates(&(q + q2 * (0.5 * dt)), &(w + w2 * (0.5 * dt)));
            let (q4, w4) = rates(&(q + q3 * dt), &(w + w3 * dt));
            q = (q + (q1 + q2 * 2.0 + q3 * 2.0 + q4) * (dt / 6.0)).normalize();
            w += (w1 + w2 * 2.0 + w3 * 2.0 + w4) * (dt / 6.0);
        }
        end = expected.orientation.angle_to(&UnitQuaternion::from_quaternion(q));
        worst = worst.max(end);
    }
    (end, worst)
}

fn main() {
    let scene = SceneId::Cuboid.parameters();
    let reference = SceneId::Cuboid
        .reference_trajectory()
        .expect("embedded reference parses");
    let started = Instant::now();
    println!(
        "{:<4} {:<10} {:>8} {:>10} {:>10} {:>10} {:>10} {:>10} {:>8} {:>9}",
        "alg", "method", "dt", "end rad", "max rad", "max pos m", "max dE/E0", "flip s", "us/step", "ms/sim s"
    );
    let mut rows = Vec::new();
    table::<Pga>(&scene, &reference, &mut rows);
    table::<Cga>(&scene, &reference, &mut rows);

    println!(
        "\nAnchor: MuJoCo RK4, {ANCHOR_ERROR:.0e} rad at {ANCHOR_MILLISECONDS_PER_SECOND} ms CPU per simulated second."
    );
    for algebra in [Pga::NAME, Cga::NAME] {
        let cheapest = rows
            .iter()
            .filter(|r| r.algebra == algebra && r.end_orientation <= ANCHOR_ERROR)
            .min_by(|a, b| a.milliseconds_per_second.total_cmp(&b.milliseconds_per_second));
        match cheapest {
            Some(row) => println!(
                "{algebra}: cheapest run with end orientation error ≤ {ANCHOR_ERROR:.0e} rad: {} at dt = {:.2e}, \
                 {:.2e} rad, {:.3} ms per simulated second: {:.1}× less CPU than the anchor",
                row.integrator,
                row.dt,
                row.end_orientation,
                row.milliseconds_per_second,
                ANCHOR_MILLISECONDS_PER_SECOND / row.milliseconds_per_second
            ),
            None => println!("{algebra}: no run reaches {ANCHOR_ERROR:.0e} rad"),
        }
    }

    println!("\nClassic RK4 on (q, ω_body), plain nalgebra (end / max orientation error, rad):");
    for dt in [2e-3, 1e-3, 5e-4, 1e-4] {
        let (end, worst) = classic_rk4(&scene, &reference, dt);
        println!("  dt {dt:.0e}: {end:.2e} / {worst:.2e}");
    }
    println!("\n(total {:.1} s)", started.elapsed().as_secs_f64());
}
