//! The equations of motion (theory §5) are the classical Newton–Euler equations.
//!
//! For random bodies and states under gravity and a force along a random world line, the GA rates
//! `(dR/dt, dΩ/dt)` are followed for ±ε and the body velocity Ḃ = (ω, v) (body axes) read at both ends; its
//! central difference is compared with an independent formula in plain nalgebra:
//! `I ω̇ = τ − ω ⨯ Iω` (τ the torque about the centre of mass, body axes) and `m d(v_body)/dt = Rᵀf − m ω ⨯ v_body`.
//! The kinematics are checked the same way: the pose read from R moves with the velocity Ḃ describes.

use crate::common;

use common::Random;
use dynamics::{Algebra, Body, Force, FreeBody, ScrewCoordinates, State};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Step of the central differences, balancing their truncation error (∝ ε²: 7.7e-9 at ε = 1e-5) against
/// round-off (∝ 1/ε: CGA 5.1e-9 at ε = 1e-6).
const EPSILON: f64 = 3e-6;

/// Largest measured relative mismatch over the 200 states at ε = 3e-6: accelerations 4.2e-10 (PGA) and
/// 1.1e-9 (CGA, whose round-off grows with the squared distances up to 5 m), kinematics 2.1e-10 and 1.2e-9.
/// A sign or factor error in any term of the equations is O(1).
const TOLERANCE: f64 = 1e-8;

struct Case<A: Algebra> {
    body: Body,
    system: FreeBody<A>,
    state: State<A>,
    position: Vector3<f64>,
    rotation: UnitQuaternion<f64>,
    angular_body: Vector3<f64>,
    linear_world: Vector3<f64>,
    force: Vector3<f64>,
    force_point: Vector3<f64>,
}

fn random_case<A: Algebra>(random: &mut Random) -> Case<A> {
    // A cuboid with sides in [0.5, 2.5]: principal moments up to ~8× apart, always physical.
    let sides = Vector3::repeat(1.5) + random.vector(1.0);
    let body = Body::cuboid(1.0 + 0.5 * random.next(), sides).expect("positive sides");
    let (force, force_point) = (random.vector(5.0), random.vector(2.0));
    let system = FreeBody::<A>::new(body)
        .with_force(Force::gravity())
        .with_force(Force::Line {
            force,
            point: force_point,
        });
    let (position, rotation) = (random.vector(3.0), random.rotation());
    let (angular_body, linear_world) = (random.vector(5.0), random.vector(2.0));
    let state = State::<A>::new(&body, position, &rotation, angular_body, linear_world);
    Case {
        body,
        system,
        state,
        position,
        rotation,
        angular_body,
        linear_world,
        force,
        force_point,
    }
}

/// The state reached from `state` by following the GA rates linearly for `h` (the momentum rate is the wrench about
/// the centre of mass, the rate of the state's central momentum).
fn follow<A: Algebra>(system: &FreeBody<A>, state: &State<A>, h: f64) -> State<A> {
    let rates = system.rates_at(0.0, state);
    State {
        motor: state.motor + rates.motor_rate(state.motor) * h,
        central_momentum: state.central_momentum + rates.momentum_rate * h,
    }
}

fn body_velocity<A: Algebra>(system: &FreeBody<A>, state: &State<A>) -> ScrewCoordinates {
    A::screw_coordinates(system.rates_at(0.0, state).body_velocity)
}

fn relative(error: Vector3<f64>, scale: Vector3<f64>) -> f64 {
    error.norm() / scale.norm().max(1.0)
}

fn equations_of_motion_are_newton_euler<A: Algebra>() {
    let mut random = Random::new(41);
    let (mut worst_dynamics, mut worst_kinematics) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let case = random_case::<A>(&mut random);
        let (plus, minus) = (
            follow(&case.system, &case.state, EPSILON),
            follow(&case.system, &case.state, -EPSILON),
        );

        // Classical Newton–Euler, body axes, about the centre of mass.
        let inertia = case.body.moments();
        let m = case.body.mass();
        let gravity = Vector3::new(0.0, 0.0, -dynamics::forces::STANDARD_GRAVITY);
        let total_force = case.force + m * gravity;
        let torque_world = (case.force_point - case.position).cross(&case.force);
        let torque_body = case.rotation.inverse() * torque_world;
        let omega = case.angular_body;
        let omega_dot = (torque_body - omega.cross(&inertia.component_mul(&omega))).component_div(&inertia);
        let linear_body = case.rotation.inverse() * case.linear_world;
        let linear_body_dot = case.rotation.inverse() * total_force / m - omega.cross(&linear_body);

        // The GA state describes the same velocities ...
        let now = body_velocity(&case.system, &case.state);
        worst_kinematics = worst_kinematics
            .max(relative(now.l - omega, omega))
            .max(relative(now.t - linear_body, linear_body));
        // ... and its rates change them as Newton and Euler say.
        let (after, before) = (body_velocity(&case.system, &plus), body_velocity(&case.system, &minus));
        let ga_omega_dot = (after.l - before.l) / (2.0 * EPSILON);
        let ga_linear_dot = (after.t - before.t) / (2.0 * EPSILON);
        worst_dynamics = worst_dynamics
            .max(relative(ga_omega_dot - omega_dot, omega_dot))
            .max(relative(ga_linear_dot - linear_body_dot, linear_body_dot));

        // dR/dt = −½RḂ moves the pose with those velocities: ċ = v, q̇ = ½ q (0, ω_body).
        let ((c_plus, q_plus), (c_minus, q_minus)) = (plus.pose(), minus.pose());
        let c_dot = (c_plus - c_minus) / (2.0 * EPSILON);
        // Quaternion sign: both ends are near q, so compare with a consistent sign.
        let align = |q: UnitQuaternion<f64>| {
            let q = *q.quaternion();
            if q.dot(case.rotation.quaternion()) < 0.0 {
                -q
            } else {
                q
            }
        };
        let q_dot = (align(q_plus) - align(q_minus)) / (2.0 * EPSILON);
        let expected_q_dot = case.rotation.quaternion() * Quaternion::from_imag(omega) * 0.5;
        worst_kinematics = worst_kinematics
            .max(relative(c_dot - case.linear_world, case.linear_world))
            .max((q_dot - expected_q_dot).norm() / omega.norm().max(1.0));
    }
    println!(
        "{}: worst relative mismatch, accelerations {worst_dynamics:.1e}, kinematics {worst_kinematics:.1e}",
        A::NAME
    );
    assert!(worst_dynamics < TOLERANCE, "{worst_dynamics:.2e}");
    assert!(worst_kinematics < TOLERANCE, "{worst_kinematics:.2e}");
}

for_both_algebras!(equations_of_motion_are_newton_euler);
