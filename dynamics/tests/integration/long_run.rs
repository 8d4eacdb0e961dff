//! A long run: 10⁶ steps of a torque-free asymmetric body with every integrator in both algebras.
//! Its momentum (linear, and angular about the centre of mass, which the state holds) is a constant of the motion, so
//! every method must keep it to round-off; its energy may drift only by the method's truncation error; its motor must
//! stay unit. (The angular momentum about the origin adds `c × m v`, which follows the centre's error off its straight
//! line: `scenarios/tests/integration/scene1_free_body.rs`.)
//!
//! Measured (`cargo test --release -p dynamics --test integration long_run:: -- --nocapture`): the momentum is kept
//! exactly by every method (before the body-momentum methods projected onto it, RKMK4-body and RKMK6-body lost
//! 7.1e-9 of it); the largest relative energy change is 1.1e-7 for Strang (order 2), 6.5e-12 for the order-4
//! methods and 2.8e-13 for RKMK6-body; the motor norm error at most 2.7e-15 in PGA and 8.9e-14 in CGA.

use dynamics::{motor, Algebra, Body, Cga, FreeBody, Integrator, Pga, ScrewCoordinates, State, Stepper};
use nalgebra::{UnitQuaternion, Vector3};

const STEPS: usize = 1_000_000;
const DT: f64 = 1e-3;

/// What a run kept: the largest relative change of the central momentum's coordinates and of the energy, and
/// the largest motor norm error, over the checks every 1000 steps.
#[derive(Debug)]
struct Drift {
    momentum: f64,
    energy: f64,
    motor_norm: f64,
}

fn momentum_change<A: Algebra>(start: &ScrewCoordinates, now: &State<A>) -> f64 {
    let now = A::screw_coordinates(now.central_momentum);
    (now.l - start.l).norm().max((now.t - start.t).norm()) / start.l.norm().max(start.t.norm())
}

fn run<A: Algebra>(integrator: Integrator) -> Drift {
    // An asymmetric body tumbling near its middle axis (flipping every few seconds, the hardest case for the
    // body-frame methods) while it drifts away from the origin, so the angular momentum about the origin has an
    // orbital part.
    let body = Body::cuboid(2.0, Vector3::new(0.3, 0.6, 1.1)).unwrap();
    let system = FreeBody::<A>::new(body);
    let start = State::<A>::new(
        &body,
        Vector3::new(0.4, -0.3, 0.2),
        &UnitQuaternion::from_euler_angles(0.3, -0.2, 0.9),
        Vector3::new(0.05, 4.0, 0.1),
        Vector3::new(0.02, 0.01, -0.015),
    );
    let momentum = A::screw_coordinates(start.central_momentum);
    let energy = start.kinetic_energy(&body);
    let mut stepper = Stepper::new(&system, integrator).unwrap();
    let mut states = [start];
    let mut drift = Drift {
        momentum: 0.0,
        energy: 0.0,
        motor_norm: 0.0,
    };
    for k in 0..STEPS {
        stepper.step(k as f64 * DT, &mut states, DT).unwrap();
        if k % 1000 == 999 {
            let state = &states[0];
            drift.momentum = drift.momentum.max(momentum_change::<A>(&momentum, state));
            drift.energy = drift.energy.max((state.kinetic_energy(&body) - energy).abs() / energy);
            drift.motor_norm = drift.motor_norm.max(motor::norm_error::<A>(state.motor));
        }
    }
    drift
}

fn every_method_keeps_the_invariants<A: Algebra>() {
    for integrator in Integrator::ALL {
        let drift = run::<A>(integrator);
        println!("{} {}: {drift:?}", A::NAME, integrator.name());
        assert!(
            drift.momentum < 1e-15,
            "{} {}: momentum changed by {:e}",
            A::NAME,
            integrator.name(),
            drift.momentum
        );
        assert!(drift.motor_norm < 1e-12, "{} {}: {drift:?}", A::NAME, integrator.name());
        // The truncation error's share: Strang is of order 2, the others of order 4 and 6.
        let energy_bound = if integrator.order() == 2 { 3e-7 } else { 3e-11 };
        assert!(
            drift.energy < energy_bound,
            "{} {}: {drift:?}",
            A::NAME,
            integrator.name()
        );
    }
}

#[test]
fn a_million_steps_of_a_torque_free_body_in_pga() {
    every_method_keeps_the_invariants::<Pga>();
}

#[test]
fn a_million_steps_of_a_torque_free_body_in_cga() {
    every_method_keeps_the_invariants::<Cga>();
}
