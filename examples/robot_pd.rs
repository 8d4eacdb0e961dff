//! A UR5 arm, loaded from its URDF, held at a pose by a joint-space PD controller with gravity compensation:
//!
//! ```text
//! τ = h(q, v) + Kp (q* − q) − Kd v
//! ```
//!
//! where h(q, v) are the bias forces (gravity and the velocity products, `JointState::bias_forces`). Starting from
//! the zero pose at rest, the arm moves to shoulder_lift = −1.0 rad, elbow = 1.2 rad (the other joints held at 0)
//! and stays there. Prints the joint angles and the controller's torques every 0.5 s, and checks at the end that
//! every joint is within 1e-3 rad of its target and that the energy balance holds (energy change = controller work).
//!
//! ```sh
//! cargo run --release --example robot_pd
//! ```

use std::ops::ControlFlow;
use std::sync::Arc;

use dynamics::mechanism::force_elements::{ForceElement, JointState};
use dynamics::simulate::Plan;
use dynamics::{simulate, Method, Pga, Schedule, State};
use nalgebra::DVector;
use urdf_import::{read_file, BuildOptions, ImportOptions, Robot, RobotStart};

/// The closed loop's natural frequency (rad/s) and damping ratio, the same for every joint.
const OMEGA: f64 = 6.0;
const ZETA: f64 = 1.0;

/// The PD law with gravity compensation: one torque per joint (N m).
fn pd(h: &DVector<f64>, q: &[f64], v: &[f64], target: &[f64], kp: &[f64], kd: &[f64]) -> DVector<f64> {
    DVector::from_fn(h.len(), |i, _| h[i] + kp[i] * (target[i] - q[i]) - kd[i] * v[i])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The URDF as shipped with the reference data; a fixed base, gravity 9.81 m/s² along −z.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/reference/data/robots/ur5_robot.urdf");
    let mut robot = Robot::<Pga>::build(read_file(path, &ImportOptions::default())?, &BuildOptions::default())?;
    let names: Vec<String> = robot.joint_names().map(str::to_owned).collect();
    let space = robot.mechanism().joint_space()?.clone();
    // Six revolute joints on a fixed base: one position and one velocity per joint, in the same order.
    assert_eq!((space.position_count(), space.velocity_count()), (6, 6));

    // The target pose (rad), by joint name.
    let mut target = vec![0.0; 6];
    for (name, angle) in [("shoulder_lift_joint", -1.0), ("elbow_joint", 1.2)] {
        target[space.group(name).ok_or("no such joint")?.velocity_offset()] = angle;
    }
    // Gains per joint from the arm's inertia at the target (the diagonal of M(q*)), so each joint, taken alone,
    // closes like a critically damped oscillator at OMEGA (M_ii from 0.017 kg m² at wrist 3 to 3.1 at the shoulder).
    let at_target = robot.mechanism().states_from_joints(&target, &[0.0; 6])?;
    let inertia = robot.mechanism().mass_matrix(&at_target)?;
    let kp: Vec<f64> = (0..6).map(|i| OMEGA * OMEGA * inertia[(i, i)]).collect(); // N m / rad
    let kd: Vec<f64> = (0..6).map(|i| 2.0 * ZETA * OMEGA * inertia[(i, i)]).collect(); // N m s / rad

    // The controller sees the joint positions and velocities and the bodies' states at every evaluation.
    let (goal, p, d) = (target.clone(), kp.clone(), kd.clone());
    let law = move |state: &JointState<'_, Pga>| {
        let h = state.bias_forces().expect("the bias forces of a tree");
        pd(&h, state.positions, state.velocities, &goal, &p, &d)
    };
    robot
        .mechanism_mut()
        .add_force_element(ForceElement::controller("pd", Arc::new(law)))?;
    let mechanism = robot.mechanism();

    // From the zero pose at rest, 3 s with the eighth-order Lie-group method at 5 ms steps, sampled every 0.5 s;
    // the observer keeps the states at the sample times to print them.
    let start = robot.initial_states(&RobotStart::default())?;
    let schedule = Schedule::with_sample_interval(5e-3, 3.0, 0.5)?;
    let mut printed: Vec<(f64, Vec<State<Pga>>)> = vec![(0.0, start.clone())];
    let keep = |t: f64, states: &[State<Pga>]| {
        if ((t / 0.5).round() - t / 0.5).abs() < 1e-9 {
            printed.push((t, states.to_vec()));
        }
        ControlFlow::Continue(())
    };
    let run = simulate(
        mechanism,
        &start,
        Method::Rkmk8Body,
        Plan::new(&schedule).observer(keep),
    )?;

    let short: Vec<&str> = names.iter().map(|n| n.trim_end_matches("_joint")).collect();
    println!("UR5 held by PD + gravity compensation; joints: {}", short.join(", "));
    println!("target (rad): {}", format_row(&target));
    println!("Kp (N m/rad): {}", format_row(&kp));
    let mut q = vec![0.0; 6];
    for (t, states) in &printed {
        // The same law, evaluated again at the printed state: the torques the controller applies there.
        q = mechanism.joint_positions(states, Some(&q))?;
        let v = mechanism.joint_velocities(states)?;
        let tau = pd(&mechanism.bias_forces(*t, states)?, &q, &v, &target, &kp, &kd);
        println!(
            "t = {t:.1} s  q (rad): {}  τ (N m): {}",
            format_row(&q),
            format_row(tau.as_slice())
        );
    }

    // Every joint at its target, and the energy balance: the change of kinetic + potential energy equals the work
    // the controller did (Sample::work, its power integrated by the method's own weights).
    let worst = q.iter().zip(&target).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let samples = run.body(0);
    let (first, last) = (&samples[0], &samples[samples.len() - 1]);
    let (change, work) = (last.energy - first.energy, last.work);
    let balance = change - work;
    println!("largest joint error at 3 s: {worst:.1e} rad");
    println!("energy change {change:+.9} J, controller work {work:+.9} J, difference {balance:.1e} J");
    assert!(worst <= 1e-3, "a joint is {worst} rad from its target");
    assert!(
        balance.abs() <= 1e-6 * work.abs().max(1.0),
        "energy balance off by {balance} J"
    );
    Ok(())
}

/// Six numbers in columns.
fn format_row(values: &[f64]) -> String {
    values.iter().map(|x| format!("{x:+8.3}")).collect::<Vec<_>>().join(" ")
}
