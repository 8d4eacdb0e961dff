//! The simulation loop: schedules land on the reference sample times or are refused, the record matches the
//! state it samples, splitting refuses what it cannot integrate, a state of the wrong size is refused, and a
//! blow-up is reported.

use crate::common;

use std::sync::Arc;

use common::cuboid;
use dynamics::integrate::SplittingError;
use dynamics::simulate::SAMPLE_INTERVAL;
use dynamics::{
    simulate, Algebra, Force, Integrator, Mechanism, Method, Schedule, SimulationError, SplittingMethod, StepError,
    Stepper,
};
use nalgebra::Vector3;
use reference::SceneId;

#[test]
fn a_step_that_misses_the_sample_times_is_refused() {
    assert!(matches!(
        Schedule::new(3e-3, 10.0),
        Err(SimulationError::StepDoesNotDivideInterval { .. })
    ));
    assert!(matches!(
        Schedule::new(2e-2, 10.0),
        Err(SimulationError::StepDoesNotDivideInterval { .. })
    ));
    // A duration off the sample grid is not refused: it ends with a shorter interval (`a_run_continues_…` below).
    assert_eq!(Schedule::new(1e-3, 10.005).unwrap().sample_count(), 1002);
    assert_eq!(Schedule::new(1e-3, 1e6).err(), Some(SimulationError::TooLong));
    assert_eq!(Schedule::new(1e-300, 10.0).err(), Some(SimulationError::TooLong));
    // 1e13 steps per sample interval and 1e5 intervals: 1e18 steps, beyond the 2⁵³ counted exactly.
    assert_eq!(Schedule::new(1e-15, 1000.0).err(), Some(SimulationError::TooLong));
    assert!(Schedule::new(1e-9, 1000.0).is_ok()); // 1e12 steps: long, but counted exactly
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Schedule::new(bad, 10.0),
            Err(SimulationError::NotPositive { .. })
        ));
        assert!(matches!(
            Schedule::new(1e-3, bad),
            Err(SimulationError::NotPositive { .. })
        ));
    }
}

#[test]
fn schedules_land_on_the_reference_sample_times() {
    let reference = SceneId::Cuboid
        .reference_trajectory()
        .expect("embedded reference parses");
    for (dt, steps_per_sample) in [(1e-2, 1), (5e-3, 2), (2.5e-3, 4), (1e-3, 10), (1e-4, 100), (2e-5, 500)] {
        let schedule = Schedule::new(dt, 10.0).expect("dt divides 0.01");
        assert_eq!(schedule.steps_per_sample(), Some(steps_per_sample));
        assert_eq!(schedule.sample_count(), reference.samples().len());
        assert_eq!(schedule.step_count(), 1000 * steps_per_sample);
        assert!((schedule.dt() - dt).abs() < 1e-18);
        for (index, sample) in reference.samples().iter().enumerate() {
            assert_eq!(schedule.sample_time(index), sample.t);
        }
    }
}

/// The record's first sample is the initial state in classical terms, and a run equals stepping by hand.
fn the_record_matches_the_state<A: Algebra>() {
    let scene = cuboid::<A>();
    let schedule = Schedule::new(1e-3, 0.5).expect("1e-3 divides 0.01");
    let run = simulate(&scene.system, &[scene.initial], Method::Rk4, &schedule).expect("scene 1 runs");
    assert_eq!(run.body(0).len(), 51);
    assert_eq!(run.statistics.accepted, 500);
    let first = &run.body(0)[0];
    let start = scene.scene.initial_state();
    assert_eq!(first.t, 0.0);
    assert!((first.position - start.position).norm() < 1e-15);
    assert!(first.orientation.angle_to(&start.orientation) < 1e-15);
    assert!((first.velocity - start.velocity).norm() < 1e-14);
    assert!((first.angular_velocity - start.angular_velocity).norm() < 1e-14);
    assert!((first.energy - scene.scene.initial_energy).abs() < 1e-12);

    let mut states = [scene.initial];
    let mut stepper = Stepper::new(&scene.system, Method::Rk4).expect("a general method");
    for k in 0..schedule.step_count() {
        stepper
            .step(k as f64 * schedule.dt(), &mut states, schedule.dt())
            .expect("a free body steps");
    }
    let [state] = states;
    assert_eq!(
        (run.final_state[0].motor, run.final_state[0].central_momentum),
        (state.motor, state.central_momentum)
    );
    let (position, orientation) = state.pose();
    let last = run.body(0).last().expect("51 samples");
    assert_eq!((last.position, last.orientation), (position, orientation));
}

/// A custom force may depend on the momentum, so the splitting refuses it (and the general methods take it).
fn splitting_refuses_custom_forces<A: Algebra>() {
    let scene = cuboid::<A>();
    let damping = Force::<A>::Custom(Arc::new(|_, state| state.momentum_about_origin() * -0.1));
    let system = scene.system.clone().with_force(Force::gravity()).with_force(damping);
    let schedule = Schedule::new(1e-3, 0.1).expect("1e-3 divides 0.01");
    for method in SplittingMethod::ALL {
        assert_eq!(
            simulate(&system, &[scene.initial], Integrator::Splitting(method), &schedule).err(),
            Some(SimulationError::Step(StepError::Splitting(
                SplittingError::CustomForce { index: 1 }
            )))
        );
    }
    for method in Method::ALL {
        assert!(simulate(&system, &[scene.initial], Integrator::General(method), &schedule).is_ok());
    }
    // A one-body mechanism is integrated by the general methods only.
    let mechanism = Mechanism::<A>::single(scene.body);
    assert_eq!(
        simulate(&mechanism, &[scene.initial], SplittingMethod::Strang, &schedule).err(),
        Some(SimulationError::Step(StepError::Splitting(
            SplittingError::NotAFreeBody
        )))
    );
}

/// The initial state needs one entry per body.
fn a_state_of_the_wrong_size_is_refused<A: Algebra>() {
    let scene = cuboid::<A>();
    let schedule = Schedule::new(1e-3, 0.1).expect("1e-3 divides 0.01");
    for states in [vec![], vec![scene.initial; 2]] {
        assert_eq!(
            simulate(&scene.system, &states, Method::Rk4, &schedule).err(),
            Some(SimulationError::BodyCount {
                expected: 1,
                got: states.len()
            })
        );
    }
}

/// A state that stops being finite ends the run with the time of the first bad step (the step that first
/// evaluates the force at t = 0.25 ends there).
fn a_blow_up_is_reported<A: Algebra>() {
    let scene = cuboid::<A>();
    let explosive = Force::<A>::Custom(Arc::new(|t, _| {
        dynamics::forces::couple::<A>(Vector3::repeat(if t < 0.25 { 0.0 } else { f64::NAN }))
    }));
    let system = scene.system.clone().with_force(explosive);
    let schedule = Schedule::new(1e-3, 1.0).expect("1e-3 divides 0.01");
    for method in Method::ALL {
        match simulate(&system, &[scene.initial], method, &schedule) {
            Err(SimulationError::Step(StepError::NonFinite { t, body: 0 })) => {
                assert!((t - 25.0 * SAMPLE_INTERVAL).abs() < 1e-12, "{}: t = {t}", method.name());
            }
            other => panic!("{}: {:?}", method.name(), other.err()),
        }
    }
}

/// A step that is not positive and finite, a time or a state that is not finite, is refused before anything
/// moves.
fn bad_steps_and_states_are_refused<A: Algebra>() {
    let scene = cuboid::<A>();
    let mut stepper = Stepper::new(&scene.system, Method::Rk4).expect("a general method");
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let mut states = [scene.initial];
        let error = stepper.step(0.0, &mut states, dt).unwrap_err();
        assert!(matches!(error, StepError::InvalidStep { .. }), "dt = {dt}: {error}");
        let unchanged = A::motor_coordinates(states[0].motor) == A::motor_coordinates(scene.initial.motor)
            && A::screw_coordinates(states[0].central_momentum) == A::screw_coordinates(scene.initial.central_momentum);
        assert!(unchanged, "dt = {dt}: the state moved");
    }
    for t in [f64::NAN, f64::INFINITY] {
        let error = stepper.step(t, &mut [scene.initial], 1e-3).unwrap_err();
        assert!(matches!(error, StepError::InvalidTime { .. }), "t = {t}: {error}");
    }
    let mut broken = scene.initial;
    broken.central_momentum = broken.central_momentum * f64::NAN;
    let mut states = [broken];
    let error = stepper.step(0.5, &mut states, 1e-3).unwrap_err();
    assert!(
        matches!(error, StepError::NonFiniteInput { t, body: 0 } if t == 0.5),
        "{error}"
    );
    assert!(error.to_string().contains("not finite"), "{error}");
}

for_both_algebras!(
    the_record_matches_the_state,
    splitting_refuses_custom_forces,
    a_state_of_the_wrong_size_is_refused,
    a_blow_up_is_reported,
    bad_steps_and_states_are_refused
);

/// Any step the caps allow runs, however small: a grid schedule counts its steps in integers, so that the sample
/// at the end of the 10⁷th step of 1e-6 s is taken there (it was once missed by the times' round-off and taken by
/// a partial step of zero length, "the step must be positive"); a sample time far below the step is one short step.
#[test]
fn tiny_steps_and_tiny_sample_times_run() {
    let body = dynamics::Body::sphere(1.0, 0.1).unwrap();
    let free = dynamics::FreeBody::<dynamics::Pga>::new(body);
    let start = dynamics::State::from_world_twist(
        &body,
        Vector3::zeros(),
        &nalgebra::UnitQuaternion::identity(),
        Vector3::new(0.0, 0.0, 1.0),
        Vector3::new(1.0, 0.0, 0.0),
    );
    let schedule = Schedule::new(1e-6, 10.0).unwrap();
    let run = simulate(&free, &[start], Method::Rk4, &schedule).unwrap();
    let samples = run.body(0);
    assert_eq!((run.statistics.accepted, samples.len()), (10_000_000, 1001));
    for (k, sample) in samples.iter().enumerate() {
        assert_eq!(sample.t, k as f64 * SAMPLE_INTERVAL);
        assert!(
            (sample.position.x - sample.t).abs() < 1e-9,
            "{}: {}",
            sample.t,
            sample.position.x
        );
    }
    let early = Schedule::at_times(1e-3, [1e-12]).unwrap();
    let run = simulate(&free, &[start], Method::Rk4, &early).unwrap();
    let samples = run.body(0);
    assert_eq!(samples.len(), 2);
    assert_eq!(samples[1].t, 1e-12);
    assert!((samples[1].position.x - 1e-12).abs() < 1e-24);
}

/// A run stopped at 0.4 s and continued from its last state with `starting_at(0.4)` is the run to 1 s, sample for
/// sample, under a force that reads the clock (it would differ if the continuation restarted at t = 0); and a
/// duration off the sample grid ends with a shorter interval at exactly its end. Careless start times are refused,
/// and so is one so large (1e12 s) that the clock no longer resolves a millisecond step; a day (86 400 s) is fine.
#[test]
fn a_run_continues_from_a_start_time_and_ends_off_the_grid() {
    use dynamics::Pga;
    let cuboid = cuboid::<Pga>();
    let pulse = dynamics::Force::Custom(Arc::new(|t: f64, _state: &dynamics::State<Pga>| {
        dynamics::forces::couple::<Pga>(Vector3::new(0.0, 0.0, (10.0 * t).sin()))
    }));
    let system = Mechanism::single(cuboid.body).with_force(pulse).unwrap();
    let whole = simulate(
        &system,
        &[cuboid.initial],
        Method::Rkmk6Body,
        &Schedule::new(1e-3, 1.0).unwrap(),
    )
    .unwrap();
    let first = simulate(
        &system,
        &[cuboid.initial],
        Method::Rkmk6Body,
        &Schedule::new(1e-3, 0.4).unwrap(),
    )
    .unwrap();
    let end = first.body(0).last().unwrap();
    let resumed_at = dynamics::State::<Pga>::from_world_twist(
        &cuboid.body,
        end.position,
        &end.orientation,
        end.angular_velocity,
        end.velocity,
    );
    let later = Schedule::new(1e-3, 0.6).unwrap().starting_at(0.4).unwrap();
    let second = simulate(&system, &[resumed_at], Method::Rkmk6Body, &later).unwrap();
    assert_eq!(second.body(0).len(), 61);
    for (continued, straight) in second.body(0).iter().zip(&whole.body(0)[40..]) {
        assert!(
            (continued.t - straight.t).abs() < 1e-15,
            "{} against {}",
            continued.t,
            straight.t
        );
        let turned = continued.orientation.angle_to(&straight.orientation);
        assert!(turned < 1e-13, "{turned:e} rad at t = {}", continued.t);
    }

    let uneven = simulate(
        &system,
        &[cuboid.initial],
        Method::Rkmk6Body,
        &Schedule::new(1e-3, 0.405).unwrap(),
    )
    .unwrap();
    let last = uneven.body(0).last().unwrap();
    assert_eq!((uneven.body(0).len(), last.t), (42, 0.405));
    let straight = simulate(
        &system,
        &[cuboid.initial],
        Method::Rkmk6Body,
        &Schedule::at_times(1e-3, [0.405]).unwrap(),
    )
    .unwrap();
    assert_eq!(last, straight.body(0).last().unwrap());

    for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY, f64::MAX, 1e12] {
        let refused = Schedule::new(1e-3, 1.0).unwrap().starting_at(bad);
        assert!(
            matches!(refused, Err(SimulationError::StartTime(t)) if t.to_bits() == bad.to_bits()),
            "{bad}"
        );
    }
    assert!(Schedule::new(1e-3, 1.0).unwrap().starting_at(86_400.0).is_ok());
}
