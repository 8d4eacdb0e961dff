//! Events, observers and output at any time: crossings located to round-off against exact times, a
//! terminal event and an observer ending a run, samples between steps on exact motions.

use std::ops::ControlFlow;

use dynamics::constraints::VirtualPower;
use dynamics::{
    simulate, Algebra, Body, Cga, Crossing, Event, Force, FreeBody, Mechanism, Method, Pga, Plan, Schedule,
    SimulationError, State, Stop,
};
use nalgebra::{UnitQuaternion, Vector3};

const G: f64 = dynamics::forces::STANDARD_GRAVITY;

/// K(k) = π / 2 AGM(1, √(1 − k²)); the mean converges quadratically, to round-off in six steps for k < 0.9.
fn complete_elliptic_k(modulus: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - modulus * modulus).sqrt());
    for _ in 0..8 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// A 1 m, 1 kg rod hinged at its top end about world x, released at rest from `amplitude` (rad), and its
/// period `4√(I/mgd) K(sin(θ₀/2))` with `I/md = (l²/3)/(l/2) = 2l/3` (s).
pub(crate) fn released_pendulum<A: Algebra>(amplitude: f64) -> (Body, Mechanism<A>, State<A>, f64) {
    let rod = Body::rod(1.0, 1.0, 1e-3).unwrap();
    let hinge = VirtualPower::hinge(
        "pivot",
        (Vector3::new(0.0, 0.0, 0.5), Vector3::x()),
        (Vector3::zeros(), Vector3::x()),
    )
    .unwrap();
    let pendulum = Mechanism::<A>::single(rod)
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(hinge)
        .unwrap();
    let tilted = UnitQuaternion::from_scaled_axis(Vector3::new(amplitude, 0.0, 0.0));
    let start = State::from_world_twist(
        &rod,
        tilted * Vector3::new(0.0, 0.0, -0.5),
        &tilted,
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let period = 4.0 * (2.0 / (3.0 * G)).sqrt() * complete_elliptic_k((0.5 * amplitude).sin());
    (rod, pendulum, start, period)
}

/// The pendulum of [`released_pendulum`]: the turning points (the angular velocity's crossings) in each direction
/// are a period apart, and the two directions half a period.
fn pendulum_period<A: Algebra>(amplitude: f64) {
    let (rod, pendulum, start, exact) = released_pendulum::<A>(amplitude);
    let swing = |_t: f64, states: &[State<A>]| states[0].world_velocity(&rod).angular.x;
    let schedule = Schedule::new(1e-3, 12.0).unwrap();
    let plan = Plan::new(&schedule)
        .event(Event::new("rising", swing).crossing(Crossing::Rising))
        .event(Event::new("falling", swing).crossing(Crossing::Falling));
    let run = simulate(&pendulum, &[start], Method::Rkmk6Body, plan).unwrap();
    let times = |event: usize| -> Vec<f64> { run.events.iter().filter(|h| h.event == event).map(|h| h.t).collect() };
    let (rising, falling) = (times(0), times(1));
    assert!(rising.len() >= 3 && falling.len() >= 3, "{rising:?} {falling:?}");
    assert_eq!(run.stopped, None);
    // Released at rest at +amplitude, it swings back first (angular velocity falling through... negative), so
    // the first crossing is the rising one at the far side, half a period in.
    let mut worst: f64 = 0.0;
    for (k, t) in rising.iter().enumerate() {
        worst = worst.max((t - (k as f64 + 0.5) * exact).abs() / exact);
    }
    for (k, t) in falling.iter().enumerate() {
        worst = worst.max((t - (k as f64 + 1.0) * exact).abs() / exact);
    }
    println!(
        "{} amplitude {amplitude}: period {exact}, worst relative time error {worst:e}",
        A::NAME
    );
    assert!(worst < 1e-12, "{}: {worst:e}", A::NAME);
    // The located states are at the turning points: angular velocity zero to round-off.
    for hit in &run.events {
        assert!(swing(hit.t, &hit.states).abs() < 1e-13, "{}", swing(hit.t, &hit.states));
    }
}

/// Measured worst relative errors of the crossing times over 12 s (RKMK6-body, dt = 1e-3): 4.9e-15 at 0.3 rad,
/// 4.2e-14 at 1 rad, 3.4e-13 at 2.5 rad; the bound asked of event location is 1e-12.
#[test]
fn a_pendulum_period_from_events_matches_the_elliptic_integral() {
    for amplitude in [0.3, 1.0, 2.5] {
        pendulum_period::<Pga>(amplitude);
        pendulum_period::<Cga>(amplitude);
    }
}

/// A ball dropped from rest at 2 m reaches the floor at √(2h/g): a terminal event ends the run there, with a final
/// sample at the crossing (RK4 integrates the parabola exactly: the translator is quadratic in t, so the time is
/// exact to round-off).
#[test]
fn a_terminal_event_ends_the_run_at_the_crossing() {
    let ball = Body::sphere(0.5, 0.1).unwrap();
    let system = FreeBody::<Pga>::new(ball).with_force(Force::gravity());
    let start = State::from_world_twist(
        &ball,
        Vector3::new(0.0, 0.0, 2.0),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let height = |_t: f64, states: &[State<Pga>]| states[0].pose().0.z;
    let schedule = Schedule::new(1e-3, 5.0).unwrap();
    let plan = Plan::new(&schedule).event(Event::new("floor", height).crossing(Crossing::Falling).terminal());
    let run = simulate(&system, &[start], Method::Rk4, plan).unwrap();
    let exact = (2.0 * 2.0 / G).sqrt();
    assert_eq!(run.stopped, Some(Stop::Event(0)));
    assert_eq!(run.events.len(), 1);
    // The bracket closes to 4 ulps; the 639 steps before it add their round-off (measured 1.7e-15 relative).
    assert!(
        (run.events[0].t - exact).abs() < 1e-14 * exact,
        "{} vs {exact}",
        run.events[0].t
    );
    let last = run.body(0).last().unwrap();
    assert_eq!(last.t, run.events[0].t);
    assert!(last.position.z.abs() < 1e-14, "{}", last.position.z);
    assert!(
        run.statistics.accepted < 700,
        "the run went on: {} steps",
        run.statistics.accepted
    );
}

/// An observer sees every step and stops the run; the run ends with a sample at that step.
#[test]
fn an_observer_sees_every_step_and_can_stop_the_run() {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let system = FreeBody::<Pga>::new(ball);
    let start = State::from_world_twist(
        &ball,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::x(),
    );
    let schedule = Schedule::new(1e-3, 1.0).unwrap();
    let mut seen = Vec::new();
    let plan = Plan::new(&schedule).observer(|t, states: &[State<Pga>]| {
        seen.push((t, states[0].pose().0.x));
        if t >= 0.2345 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    let run = simulate(&system, &[start], Method::Rkmk4, plan).unwrap();
    assert_eq!(run.stopped, Some(Stop::Observer));
    assert_eq!(run.statistics.accepted, 235);
    assert_eq!(seen.len(), 235);
    for (k, (t, x)) in seen.iter().enumerate() {
        // Both sums of 1e-3 steps, rounded differently (at most ~1e-16 per step).
        assert!(
            (t - (k + 1) as f64 * 1e-3).abs() < 1e-14 && (x - t).abs() < 1e-14,
            "{k}: {t} {x}"
        );
    }
    let samples = run.body(0);
    // Samples every 0.01 s up to 0.23, then the stop at 0.235.
    assert_eq!(samples.len(), 25);
    assert!((samples[24].t - 0.235).abs() < 1e-15);
}

/// Samples at times the step does not divide: a partial step from the last step's state. A sphere thrown
/// straight up spinning about the vertical is integrated exactly by RKMK4 (its body velocity, a turn about and a
/// slide along one axis, commutes with itself at all times, and its slide is linear in t), so the samples are exact
/// to round-off at every requested time.
fn samples_between_steps<A: Algebra>() {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let system = FreeBody::<A>::new(ball).with_force(Force::gravity());
    let (spin, velocity) = (Vector3::new(0.0, 0.0, 5.0), Vector3::new(0.0, 0.0, 4.0));
    let start = State::from_world_twist(&ball, Vector3::zeros(), &UnitQuaternion::identity(), spin, velocity);
    let times = [0.001, 0.0105, 0.25, 0.3333, 1.0];
    let schedule = Schedule::at_times(0.003, times).unwrap();
    let run = simulate(&system, &[start], Method::Rkmk4, &schedule).unwrap();
    let samples = run.body(0);
    assert_eq!(samples.len(), times.len() + 1);
    for (sample, &t) in samples[1..].iter().zip(&times) {
        assert_eq!(sample.t, t);
        let expected = velocity * t - Vector3::new(0.0, 0.0, 0.5 * G * t * t);
        assert!(
            (sample.position - expected).norm() < 1e-14,
            "{}: {}",
            A::NAME,
            sample.position - expected
        );
        let turned = UnitQuaternion::from_scaled_axis(spin * t);
        assert!(sample.orientation.angle_to(&turned) < 1e-14, "{}", A::NAME);
    }
    // 1.0 / 0.003 = 333.3 steps: 333 whole and a shortened last one.
    assert_eq!(run.statistics.accepted, 334);
    assert_eq!(schedule.steps_per_sample(), None);
}

#[test]
fn samples_at_any_time_between_steps() {
    samples_between_steps::<Pga>();
    samples_between_steps::<Cga>();
}

#[test]
fn output_times_must_increase() {
    for (times, index) in [(vec![0.1, 0.1], 1), (vec![-1.0], 0), (vec![0.5, f64::NAN], 1)] {
        assert!(
            matches!(Schedule::at_times(1e-3, times), Err(SimulationError::OutputTime { index: i, .. }) if i == index)
        );
    }
    let none = Schedule::at_times(1e-3, []).unwrap_err();
    assert!(matches!(none, SimulationError::NoOutputTimes));
    assert!(none.to_string().contains("no output times"), "{none}");
}

/// An event function that is not finite would never (or always) cross zero: the run stops with an error naming
/// the event and the time instead of running without it.
#[test]
fn an_event_that_is_not_finite_is_an_error() {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let system = FreeBody::<Pga>::new(ball);
    let start = State::from_world_twist(
        &ball,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::x(),
    );
    let schedule = Schedule::new(1e-3, 1.0).unwrap();
    let broken = |t: f64, _: &[State<Pga>]| if t > 0.5 { f64::NAN } else { 1.0 };
    let plan = Plan::new(&schedule).event(Event::new("broken", broken));
    let error = simulate(&system, &[start], Method::Rk4, plan).unwrap_err();
    assert!(
        matches!(error, SimulationError::EventNotFinite { ref name, t, .. } if name == "broken" && t > 0.5 && t < 0.502),
        "{error}"
    );
}
