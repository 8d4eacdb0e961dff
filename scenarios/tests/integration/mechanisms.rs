//! The mechanisms of docs/scenes.md against their references (GA-independent, `reference::multibody`): the
//! double pendulum's end state, energy and hinges (M1), the four-bar linkage's closed loop, crank period and end
//! angles (M2), the 64-link chain's energy and joints over 10 s (M3), in both algebras and both joint
//! formulations. Joint violations are measured from the sampled poses alone, not from the solver's residuals.
//!
//! Bounds are the measured values (quoted) times a margin of 3–10, or docs/scenes.md's requirement where that is
//! tighter, so a regression of the formulation fails while round-off does not.

use dynamics::constraints::{PinningAlgebra, Stabilisation};
use dynamics::{motor, simulate, Cga, Dynamics, Method, Pga, Rates, Schedule, ScrewCoordinates, Simulation};
use dynamics::{State, Stepper};
use nalgebra::{UnitQuaternion, Vector3};
use scenarios::mechanism_measures::measure;
use scenarios::{build_mechanism, build_mechanism_at, Formulation, MechanismId};

fn run<A: PinningAlgebra>(
    id: MechanismId,
    formulation: Formulation,
    method: Method,
    dt: f64,
    sample_interval: f64,
) -> Simulation<A> {
    run_at(id, formulation, method, (dt, sample_interval), Vector3::zeros())
}

/// [`run`] with the mechanism moved by `offset` (`scenarios::build_mechanism_at`), its samples moved back.
fn run_at<A: PinningAlgebra>(
    id: MechanismId,
    formulation: Formulation,
    method: Method,
    (dt, sample_interval): (f64, f64),
    offset: Vector3<f64>,
) -> Simulation<A> {
    let scene = build_mechanism_at::<A>(id, formulation, Stabilisation::PROJECTION, offset).unwrap();
    let schedule = Schedule::with_sample_interval(dt, id.duration(), sample_interval).unwrap();
    let mut run = simulate(&scene.system, &scene.initial, method, &schedule).unwrap();
    for sample in run.bodies.iter_mut().flatten() {
        sample.position -= offset;
    }
    run
}

/// End orientation (rad) and position (m) errors against M1's reference, and the largest energy drift and hinge
/// violation over the run.
fn double_pendulum_errors<A: PinningAlgebra>(formulation: Formulation, method: Method, dt: f64) -> [f64; 4] {
    double_pendulum_errors_at::<A>(formulation, method, dt, Vector3::zeros())
}

/// [`double_pendulum_errors`] of M1 moved by `offset`.
fn double_pendulum_errors_at<A: PinningAlgebra>(
    formulation: Formulation,
    method: Method,
    dt: f64,
    offset: Vector3<f64>,
) -> [f64; 4] {
    let run = run_at::<A>(MechanismId::DoublePendulum, formulation, method, (dt, 0.01), offset);
    assert_eq!(run.body(0).last().unwrap().t, 10.0);
    let measures = measure(MechanismId::DoublePendulum, &run.bodies).unwrap();
    let (orientation, position) = (measures.orientation_end.unwrap(), measures.position_end.unwrap());
    let (energy, violation) = (measures.energy_drift, measures.violation);
    println!(
        "M1 {} {} {} dt = {dt:e}, {:.0e} m out: orientation {orientation:.2e} rad, position {position:.2e} m, energy \
         {energy:.2e} J, hinges {violation:.2e} m",
        A::NAME,
        formulation.name(),
        method.name(),
        offset.norm()
    );
    [orientation, position, energy, violation]
}

/// M1 with RKMK6-body at dt = 2e-3: the reference's own accuracy. Measured in both algebras and formulations:
/// orientation 3.2e-13–4.0e-13 rad, position 1.3e-13–1.6e-13 m (the reference differs from a 1e-12 run by 2e-12
/// rad), energy drift 1.1e-13–1.5e-13 J, hinges 1.3e-14–1.6e-14 m.
fn double_pendulum_to_the_reference<A: PinningAlgebra>() {
    for formulation in Formulation::ALL {
        let [orientation, position, energy, violation] =
            double_pendulum_errors::<A>(formulation, Method::Rkmk6Body, 2e-3);
        assert!(
            orientation < 3e-12 && position < 1.5e-12,
            "{orientation:e} {position:e}"
        );
        assert!(energy < 1e-12, "{energy:e}");
        assert!(violation < 1e-13, "{violation:e}");
    }
}

/// theory §14.3: maximal coordinates cost almost no accuracy against reduced ones. A fourth-order method at
/// MuJoCo's step (dt = 1e-3) reaches MuJoCo's RK4 error (2.2e-10 rad, 9.2e-11 m, docs/scenes.md) within 2×: the
/// body-momentum RKMK4 measures 1.3e-10 rad and 7.0e-11 m (pinning: 1.75e-10, 9.4e-11). RK4 on the momenta about
/// the centres of mass is 8× less accurate (1.08e-9 rad): its body velocity `M⁻¹[Ω_b]` inherits the truncation
/// error of R's rotation. (On the paper's momentum about the origin it inherited R's position error too, and was
/// 2.2e-8 rad.)
fn double_pendulum_matches_reduced_coordinates<A: PinningAlgebra>() {
    for formulation in Formulation::ALL {
        let [orientation, position, _, violation] = double_pendulum_errors::<A>(formulation, Method::Rkmk4Body, 1e-3);
        assert!(
            orientation < 2.0 * 2.2e-10 && position < 2.0 * 9.2e-11,
            "{orientation:e} {position:e}"
        );
        assert!(violation < 1e-13, "{violation:e}");
    }
    let [orientation, ..] = double_pendulum_errors::<A>(Formulation::VirtualPower, Method::Rk4, 1e-3);
    assert!(orientation > 5e-10 && orientation < 2.5e-9, "{orientation:e}");
}

/// M2 with RKMK6-body at dt = 2e-3, sampled every step: the loop (20 hinge rows of rank 17) holds to round-off,
/// the crank's revolutions come every 0.7906242901366745 s, and the link angles and coupler at T match the
/// reference. Measured in both algebras and formulations: loop violation ≤ 1.4e-14 m; revolution times within
/// 3e-12 relative; end angles within 1.6e-11 rad (φ ≈ 40); coupler centre within 1.4e-11 m.
fn four_bar_closes_exactly<A: PinningAlgebra>() {
    for formulation in Formulation::ALL {
        let run = run::<A>(MechanismId::FourBar, formulation, Method::Rkmk6Body, 2e-3, 2e-3);
        let measures = measure(MechanismId::FourBar, &run.bodies).unwrap();
        let violation = measures.violation;
        let four_bar = measures.four_bar.unwrap();
        let (period_error, angle_error, coupler) =
            (four_bar.period_error, four_bar.angle_error, four_bar.coupler_error);
        println!(
            "M2 {} {}: loop {violation:.2e} m, {} revolutions, period {period_error:.2e} relative, end angles \
             {angle_error:.2e} rad, coupler {coupler:.2e} m",
            A::NAME,
            formulation.name(),
            four_bar.revolutions
        );
        assert!(violation < 1e-12, "{violation:e}");
        assert_eq!(four_bar.revolutions, 6);
        assert!(period_error < 1e-9, "{period_error:e}");
        assert!(angle_error < 1e-8, "{angle_error:e}");
        assert!(coupler < 1e-9, "{coupler:e}");
    }
}

/// M3, 64 links released from horizontal, 10 s, RKMK6-body at dt = 1e-3 with projection: every ball joint holds
/// to round-off, and the energy (zero at the start; the chain exchanges about 5 kJ between potential and kinetic
/// energy) stays flat except at the two whip-like events where the chain straightens and its tip speeds peak
/// (near 1.5 s and 8 s). Measured (PGA; CGA the same to two digits): joints ≤ 2.0e-14 m; energy 2.1e-6 J at 5 s
/// (MuJoCo's RK4 chain at dt = 1e-3: 3.6e-4 J at 5 s, `chain.py`), 0.33 J at 10 s, after the second event (RKMK4-body:
/// 3.3e-4 J and 5.5 J; the events are where the step matters).
fn chain_of_64_holds<A: PinningAlgebra>() {
    let run = run::<A>(
        MechanismId::Chain(64),
        Formulation::VirtualPower,
        Method::Rkmk6Body,
        1e-3,
        0.5,
    );
    let violation = measure(MechanismId::Chain(64), &run.bodies).unwrap().violation;
    let energy_at = |t: f64| {
        let k = run.body(0).iter().position(|s| (s.t - t).abs() < 1e-9).unwrap();
        run.body(0)[..=k].iter().map(|s| s.energy.abs()).fold(0.0, f64::max)
    };
    let (half, end) = (energy_at(5.0), energy_at(10.0));
    println!(
        "M3 {} 64 links: joints {violation:.2e} m, largest energy error {half:.2e} J by 5 s, {end:.2e} J by 10 s",
        A::NAME
    );
    assert!(violation < 1e-12, "{violation:e}");
    assert!(half < 1e-5, "{half:e}");
    assert!(end < 1.0, "{end:e}");
}

#[test]
fn pga_double_pendulum_to_the_reference() {
    double_pendulum_to_the_reference::<Pga>();
}

#[test]
fn cga_double_pendulum_to_the_reference() {
    double_pendulum_to_the_reference::<Cga>();
}

/// M1 1 km from the origin. The states hold each body's momentum about its centre of mass and forces act about the
/// centres (docs/dynamics.md, "Momentum about the centre of mass"), so nothing is lost to a momentum about the
/// origin; what remains is the resolution of positions 1 km out, ε |c| = 1.1e-13 m. The joints see the bodies'
/// relative positions, `c_b − c_a` and `a − p`, to that resolution at every evaluation, which moves the
/// accelerations by about ε |c| / L of themselves: errors grow by a part proportional to |c| (measured 10× at 10 km)
/// on top of the errors at the origin. Measured at 1 km (virtual power, PGA and CGA alike), at the origin → 1 km:
/// RKMK4-body orientation 1.31e-10 → 1.65e-10 rad, energy 1.6e-11 → 6.4e-11 J; RKMK6-body 5.3e-13 → 1.0e-11 rad,
/// 8.6e-13 → 3.8e-11 J; RK4 1.08e-9 → 1.09e-9 rad; positions within 8e-11 m, hinges within 5.5e-12 m. The bounds:
/// 2× the errors at the origin plus that part with a margin of 2.5: 2.5e-14 rad, 1e-13 J and 1.5e-14 m per metre
/// from the origin (a moving origin, not built, would remove it).
fn double_pendulum_far_from_the_origin<A: PinningAlgebra>() {
    let offset = Vector3::new(600.0, -800.0, 0.0);
    let distance = offset.norm();
    for (method, dt) in [
        (Method::Rkmk4Body, 1e-3),
        (Method::Rkmk6Body, 2e-3),
        (Method::Rk4, 1e-3),
    ] {
        let near = double_pendulum_errors::<A>(Formulation::VirtualPower, method, dt);
        let far = double_pendulum_errors_at::<A>(Formulation::VirtualPower, method, dt, offset);
        let bounds = [2.5e-14, 1.5e-14, 1e-13, 1.5e-14].map(|per_metre| per_metre * distance);
        for k in 0..4 {
            assert!(
                far[k] <= 2.0 * near[k] + bounds[k],
                "{} [orientation, position, energy, hinges]: {far:?} against {near:?}",
                method.name()
            );
        }
    }
}

#[test]
fn pga_double_pendulum_far_from_the_origin() {
    double_pendulum_far_from_the_origin::<Pga>();
}

#[test]
fn cga_double_pendulum_far_from_the_origin() {
    double_pendulum_far_from_the_origin::<Cga>();
}

#[test]
fn pga_double_pendulum_matches_reduced_coordinates() {
    double_pendulum_matches_reduced_coordinates::<Pga>();
}

#[test]
fn cga_double_pendulum_matches_reduced_coordinates() {
    double_pendulum_matches_reduced_coordinates::<Cga>();
}

#[test]
fn pga_four_bar_closes_exactly() {
    four_bar_closes_exactly::<Pga>();
}

#[test]
fn cga_four_bar_closes_exactly() {
    four_bar_closes_exactly::<Cga>();
}

#[test]
fn pga_chain_of_64_holds() {
    chain_of_64_holds::<Pga>();
}

#[test]
fn cga_chain_of_64_holds() {
    chain_of_64_holds::<Cga>();
}

/// The projection after a step takes its Gauss–Newton and velocity steps with the factors of the last dynamics
/// evaluation as a chord (docs/mechanisms.md M5), checked exactly to first order and completed with fresh factors
/// when short. Here the last evaluation is of another configuration (the chain's start, at rest, for the chain
/// swinging 0.3 s later, and the other way round), and the projection must still land on the joints to
/// round-off in both of its paths (evaluating the joints again after the position step, for the moving chain, or
/// not, for the chain at rest). For the moving chain the velocity chord falls short (without its check the chain
/// stays 3.7e-9 m/s off, measured); the position chord contracts to round-off by itself on this chain of ball
/// joints.
fn stale_chord_is_checked_and_completed<A: PinningAlgebra>() {
    let scene = build_mechanism::<A>(
        MechanismId::Chain(16),
        Formulation::VirtualPower,
        Stabilisation::PROJECTION,
    )
    .unwrap();
    let system = &scene.system;
    let mut swinging = scene.initial.clone();
    let mut stepper = Stepper::new(system, Method::Rk4).unwrap();
    for k in 0..300 {
        stepper.step(k as f64 * 1e-3, &mut swinging, 1e-3).unwrap();
    }
    // Every body moved a little (body i by i·3e-12 m along x and turned by ±2e-11 rad about its own y axis, so
    // every joint is off by about 5e-12 m) and, with `push`, given a little momentum: residuals well above
    // round-off and far below the checked loop's threshold (1e-8 m).
    let drifted = |states: &[State<A>], push: f64| -> Vec<State<A>> {
        states
            .iter()
            .enumerate()
            .map(|(i, state)| State {
                motor: A::compose(
                    A::compose(
                        motor::translator::<A>(Vector3::new(3e-12 * i as f64, 0.0, 0.0)),
                        state.motor,
                    ),
                    motor::rotor_from_quaternion::<A>(&UnitQuaternion::from_scaled_axis(
                        Vector3::y() * if i % 2 == 0 { 2e-11 } else { -2e-11 },
                    )),
                ),
                central_momentum: state.central_momentum
                    + A::screw(ScrewCoordinates {
                        l: Vector3::new(0.0, push * i as f64, 0.0),
                        t: Vector3::zeros(),
                    }),
            })
            .collect()
    };
    // The swinging chain projected after factors of the horizontal start (its velocities make the projection
    // evaluate the joints again, so the velocity chord is what the check completes), and the chain at rest
    // projected after factors of the swinging one (one evaluation: the position chord is checked alone).
    for (at, factored_at, push) in [(&swinging, &scene.initial, 2e-11), (&scene.initial, &swinging, 0.0)] {
        let mut projected = drifted(at, push);
        let before = system.violation(0.3, &projected).unwrap();
        assert!(
            before.position > 1e-12 && (push == 0.0 || before.velocity > 1e-11),
            "{before:?}"
        );
        let mut workspace = system.workspace();
        let zero = A::screw(ScrewCoordinates::default());
        let mut rates = vec![
            Rates::<A> {
                body_velocity: zero,
                momentum_rate: zero,
            };
            at.len()
        ];
        system.rates(0.0, factored_at, &mut rates, &mut workspace).unwrap();
        system.after_step(0.3, &mut projected, &mut workspace).unwrap();
        let after = system.violation(0.3, &projected).unwrap();
        println!("{} stale chord: {before:?} -> {after:?}", A::NAME);
        // The projection's tolerances here: 1e-14 m (16 ulp of 8 m is 2.8e-14) and 1e-12 m/s; the violation
        // query evaluates the joints again, with its own round-off.
        assert!(after.position < 1e-13 && after.velocity < 2e-12, "{after:?}");
    }
}

#[test]
fn pga_stale_chord_is_checked_and_completed() {
    stale_chord_is_checked_and_completed::<Pga>();
}

#[test]
fn cga_stale_chord_is_checked_and_completed() {
    stale_chord_is_checked_and_completed::<Cga>();
}
