//! Adaptive schedules (`dynamics::integrate::step_control`, `Schedule::adaptive`) with the embedded pairs DP5(4)-body and
//! DOP853-body: exact motions followed to the tolerance, samples and events from the continuous extension (no step
//! shortened; no evaluation added by DP5's, four per step by DOP853's, only in steps that hold a sample or an
//! event), mechanisms' samples on their joints, the statistics, and every careless input refused with its reason.

use std::sync::Arc;

use dynamics::integrate::step_control::ToleranceError;
use dynamics::simulate::{Event, Plan, Stop};
use dynamics::{
    simulate, Algebra, Body, Force, FreeBody, Method, Schedule, SimulationError, SplittingMethod, State, Tolerance,
};
use nalgebra::{UnitQuaternion, Vector3};

/// The embedded pairs.
const PAIRS: [Method; 2] = [Method::Dopri5Body, Method::Dop853Body];

/// Checks a run's evaluation count: 7 per step tried for DP5(4)-body; 12 per step tried for DOP853-body, and 4 more
/// for each kept step whose continuous extension was read (at most once per step).
fn assert_evaluations(method: Method, statistics: &dynamics::StepStatistics) {
    let tried = statistics.accepted + statistics.rejected;
    match method {
        Method::Dopri5Body => assert_eq!(statistics.evaluations, 7 * tried, "{statistics:?}"),
        _ => {
            let extensions = statistics.evaluations - 12 * tried;
            assert!(
                extensions.is_multiple_of(4) && extensions <= 4 * statistics.accepted,
                "{statistics:?}"
            );
        }
    }
}

fn tolerance(value: f64) -> Tolerance {
    Tolerance::new(value, value).expect("a valid tolerance")
}

/// A 1 kg ball of 0.1 m radius at rest at the origin.
fn ball_at_rest<A: Algebra>() -> (Body, State<A>) {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let still = UnitQuaternion::identity();
    (
        ball,
        State::new(&ball, Vector3::zeros(), &still, Vector3::zeros(), Vector3::zeros()),
    )
}

/// Careless tolerances: each row is (relative, absolute) and the error it must give.
#[test]
fn careless_tolerances_are_refused() {
    let cases = [
        (f64::NAN, 1e-9, ToleranceError::Relative(f64::NAN)),
        (-1e-9, 1e-9, ToleranceError::Relative(-1e-9)),
        (1.0, 1e-9, ToleranceError::Relative(1.0)),
        (1e300, 1e-9, ToleranceError::Relative(1e300)),
        (f64::INFINITY, 1e-9, ToleranceError::Relative(f64::INFINITY)),
        (1e-9, 0.0, ToleranceError::Absolute(0.0)),
        (1e-9, -1e-9, ToleranceError::Absolute(-1e-9)),
        (1e-9, 1e-16, ToleranceError::Absolute(1e-16)),
        (1e-9, f64::NAN, ToleranceError::Absolute(f64::NAN)),
        (1e-9, f64::INFINITY, ToleranceError::Absolute(f64::INFINITY)),
    ];
    for (relative, absolute, expected) in cases {
        let error = Tolerance::new(relative, absolute).expect_err("refused");
        // NaN ≠ NaN: compare the variant and the message.
        assert_eq!(error.to_string(), expected.to_string(), "({relative}, {absolute})");
    }
    // The edges that are valid: no relative part, the smallest absolute one, a huge absolute one.
    for (relative, absolute) in [(0.0, 1e-15), (0.999, 1e300), (1e-300, 1e-3)] {
        assert!(Tolerance::new(relative, absolute).is_ok(), "({relative}, {absolute})");
    }
}

/// Careless adaptive schedules: each row is (duration, sample interval) and words of the error.
#[test]
fn careless_adaptive_schedules_are_refused() {
    let cases = [
        (f64::NAN, 0.01, "the duration must be positive"),
        (0.0, 0.01, "the duration must be positive"),
        (-1.0, 0.01, "the duration must be positive"),
        (f64::INFINITY, 0.01, "the duration must be positive"),
        (1.0, 0.0, "the sample interval must be positive"),
        (1.0, -0.01, "the sample interval must be positive"),
        (1.0, f64::NAN, "the sample interval must be positive"),
        (1e300, 0.01, "more than 10000000 samples"),
        (1.0, 1e-12, "more than 10000000 samples"),
    ];
    for (duration, interval, words) in cases {
        let error = Schedule::adaptive(tolerance(1e-8), duration, interval).expect_err("refused");
        assert!(error.to_string().contains(words), "({duration}, {interval}): {error}");
    }
    // An interval longer than the run: samples at the start and the end only.
    let schedule = Schedule::adaptive(tolerance(1e-8), 0.5, 2.0).unwrap();
    assert_eq!((schedule.sample_count(), schedule.sample_time(1)), (2, 0.5));
    // An interval that does not divide the run: the last one is shorter.
    let schedule = Schedule::adaptive(tolerance(1e-8), 1.0, 0.3).unwrap();
    assert_eq!((schedule.sample_count(), schedule.sample_time(4)), (5, 1.0));
}

/// Careless step limits: zero, or any on a fixed schedule, is refused; a limit of one ends a long run after its first
/// step with the time it reached; the largest is the default's kind of bound and runs.
#[test]
fn careless_step_limits_are_refused() {
    let adaptive = Schedule::adaptive(tolerance(1e-8), 1.0, 0.1).unwrap();
    assert_eq!(adaptive.step_limit(), dynamics::simulate::MAX_ADAPTIVE_STEPS);
    let fixed = Schedule::new(1e-3, 1.0).unwrap();
    for (schedule, limit, words) in [
        (&adaptive, 0, "got 0 for an adaptive schedule"),
        (&fixed, 10, "got 10 for a fixed schedule"),
        (&fixed, 0, "got 0 for a fixed schedule"),
        (&fixed, usize::MAX, "for a fixed schedule"),
    ] {
        let error = schedule.clone().with_step_limit(limit).expect_err("refused");
        assert!(error.to_string().contains(words), "{limit}: {error}");
    }
    let (ball, _) = ball_at_rest::<dynamics::Pga>();
    let spinning = State::<dynamics::Pga>::new(
        &ball,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::new(0.0, 0.0, 30.0),
        Vector3::zeros(),
    );
    for method in PAIRS {
        let one = adaptive.clone().with_step_limit(1).unwrap();
        match simulate(&FreeBody::new(ball), &[spinning], method, &one).expect_err("one step is not enough") {
            SimulationError::TooManySteps { t, steps } => assert!(steps == 1 && t > 0.0 && t < 1.0, "{t}, {steps}"),
            other => panic!("{other}"),
        }
        let unbounded = adaptive.clone().with_step_limit(usize::MAX).unwrap();
        assert!(simulate(&FreeBody::new(ball), &[spinning], method, &unbounded).is_ok());
    }
}

/// Only an embedded pair estimates its error: the others are refused by name before any step.
#[test]
fn integrators_without_an_error_estimate_are_refused() {
    let (ball, start) = ball_at_rest::<dynamics::Pga>();
    let schedule = Schedule::adaptive(tolerance(1e-8), 1.0, 0.1).unwrap();
    let integrators: [dynamics::Integrator; 3] = [
        Method::Rk4.into(),
        Method::Rkmk8Body.into(),
        SplittingMethod::Strang.into(),
    ];
    let with_estimates: Vec<Method> = Method::ALL
        .into_iter()
        .filter(|m| m.estimate_order().is_some())
        .collect();
    assert_eq!(with_estimates, PAIRS);
    for integrator in integrators {
        assert_eq!(integrator.estimate_order(), None);
        let error = simulate(&FreeBody::new(ball), &[start], integrator, &schedule).expect_err("refused");
        assert!(
            matches!(error, SimulationError::NoErrorEstimate { method } if method == integrator.name()),
            "{error}"
        );
    }
}

/// A body dropped from 1 m spinning at 5 rad/s, to 1e-10: the spin is an exact rotation, the centre's parabola is
/// stepped in the turning body frame (so not exactly: measured 3.0e-11 m at most); the floor is reached at
/// `√(2h/g)`, located on the continuous extension (measured 3.0e-12 s early with DP5(4)-body, 1.2e-13 s late with
/// DOP853-body); every sample lies on the 0.01 s grid. Locating the crossing and taking the samples inside the steps
/// adds no evaluation for DP5(4)-body and four per step at most for DOP853-body.
fn dropped_spinning_ball<A: Algebra>() {
    for method in PAIRS {
        dropped_spinning_ball_with::<A>(method);
    }
}

fn dropped_spinning_ball_with<A: Algebra>(method: Method) {
    let ball = Body::sphere(1.0, 0.1).unwrap();
    let system = FreeBody::<A>::new(ball).with_force(Force::gravity());
    let spin = Vector3::new(0.0, 3.0, 4.0); // rad/s
    let start = State::<A>::from_world_twist(&ball, Vector3::z(), &UnitQuaternion::identity(), spin, Vector3::zeros());
    let schedule = Schedule::adaptive(tolerance(1e-10), 1.0, 0.01).unwrap();
    let height = |_t: f64, states: &[State<A>]| states[0].pose().0.z;
    let plan = Plan::new(&schedule).event(Event::new("floor", height).terminal());
    let run = simulate(&system, &[start], method, plan).unwrap();
    let landing = (2.0 / dynamics::forces::STANDARD_GRAVITY).sqrt();
    println!(
        "{} {}: landing {:.1e} s early",
        A::NAME,
        method.name(),
        landing - run.events[0].t
    );
    assert_eq!(run.stopped, Some(Stop::Event(0)));
    assert!(
        (run.events[0].t - landing).abs() < 1e-11,
        "{} vs {landing}",
        run.events[0].t
    );
    for (k, sample) in run.body(0).iter().enumerate() {
        if sample.t < run.events[0].t {
            assert_eq!(sample.t, k as f64 * 0.01);
        }
        let exact = UnitQuaternion::from_scaled_axis(spin * sample.t);
        assert!(sample.orientation.angle_to(&exact) < 1e-10, "t = {}", sample.t);
        let fall = 1.0 - 0.5 * dynamics::forces::STANDARD_GRAVITY * sample.t * sample.t;
        assert!(
            (sample.position - Vector3::new(0.0, 0.0, fall)).norm() < 1e-10,
            "t = {}",
            sample.t
        );
    }
    let statistics = run.statistics;
    assert_evaluations(method, &statistics);
    assert!(statistics.smallest_step <= statistics.largest_step && statistics.smallest_step > 0.0);

    // At 1e-6 the steps are longer than the sample interval, and the samples inside them cost nothing either.
    let loose = Schedule::adaptive(tolerance(1e-6), 0.4, 0.01).unwrap();
    let run = simulate(&system, &[start], method, &loose).unwrap();
    let statistics = run.statistics;
    assert!(statistics.largest_step > 0.01, "{statistics:?}");
    assert_evaluations(method, &statistics);
    assert_eq!(run.body(0).len(), 41);
    assert_eq!(run.body(0).last().unwrap().t, 0.4);
}

/// A pendulum (a rod hinged at its top, released at 1 rad) to 1e-10: its period from two turning points against
/// the elliptic-integral value (measured 1.3e-11 relative with DP5(4)-body, 1.4e-12 with DOP853-body), and every
/// sample (from the continuous extension, projected) on its hinge.
fn pendulum_period_and_hinge<A: Algebra>() {
    for method in PAIRS {
        pendulum_period_and_hinge_with::<A>(method);
    }
}

fn pendulum_period_and_hinge_with<A: Algebra>(method: Method) {
    let (rod, pendulum, start, exact) = crate::events::released_pendulum::<A>(1.0);
    let schedule = Schedule::adaptive(tolerance(1e-10), 4.0, 0.01).unwrap();
    let swing = |_t: f64, states: &[State<A>]| states[0].world_velocity(&rod).angular.x;
    let plan = Plan::new(&schedule).event(Event::new("turning point", swing));
    let run = simulate(&pendulum, &[start], method, plan).unwrap();
    println!(
        "{} {}: period {:.1e} off",
        A::NAME,
        method.name(),
        (2.0 * (run.events[1].t - run.events[0].t) - exact) / exact
    );
    let half_period = run.events[1].t - run.events[0].t;
    assert!(
        (2.0 * half_period - exact).abs() < 1e-10 * exact,
        "{} vs {exact}",
        2.0 * half_period
    );
    for sample in run.body(0) {
        let state = [State::from_world_twist(
            &rod,
            sample.position,
            &sample.orientation,
            sample.angular_velocity,
            sample.velocity,
        )];
        let violation = pendulum.violation(sample.t, &state).unwrap();
        assert!(violation.position < 1e-12, "t = {}: {violation:?}", sample.t);
    }
}

/// A force that stops being finite at t = 0.5 s: the steps shrink towards it until the clock cannot resolve them,
/// and the run ends with the time and the reason, not a hang.
fn a_singular_force_ends_the_run_with_its_time<A: Algebra>() {
    let (ball, start) = ball_at_rest::<A>();
    let singular = Force::Custom(Arc::new(|t: f64, _state: &State<A>| {
        let magnitude = if t > 0.5 { f64::NAN } else { 1.0 };
        dynamics::forces::force_line::<A>(Vector3::x() * magnitude, Vector3::zeros())
    }));
    let system = FreeBody::<A>::new(ball).with_force(singular);
    let schedule = Schedule::adaptive(tolerance(1e-8), 1.0, 0.01).unwrap();
    for method in PAIRS {
        let error = simulate(&system, &[start], method, &schedule).expect_err("the force is singular");
        match error {
            SimulationError::StepSizeUnderflow { t, h, ref reason } => {
                assert!((t - 0.5).abs() < 1e-12 && h < 1e-13, "{error}");
                assert!(reason.contains("no longer finite"), "{error}");
            }
            other => panic!("{other}"),
        }
    }
}

/// Two crossings inside one step: a ball coasting at 1 m/s crosses x = 0.6 m and x = 0.75 m, where the event
/// `(x − 0.6)(x − 0.75)` changes sign twice and is positive at both ends of the long steps a free coast allows (the
/// values at a step's ends alone would miss both). The scan of each step's continuous extension finds both, located
/// to 1e-12 s.
fn two_crossings_in_one_step<A: Algebra>() {
    let (ball, _) = ball_at_rest::<A>();
    let start = State::<A>::new(
        &ball,
        Vector3::zeros(),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::x(),
    );
    let schedule = Schedule::adaptive(tolerance(1e-8), 1.0, 1.0).unwrap();
    let band = |_t: f64, states: &[State<A>]| {
        let x = states[0].pose().0.x;
        (x - 0.6) * (x - 0.75)
    };
    for method in PAIRS {
        let plan = Plan::new(&schedule).event(Event::new("band", band));
        let run = simulate(&FreeBody::new(ball), &[start], method, plan).unwrap();
        let times: Vec<f64> = run.events.iter().map(|hit| hit.t).collect();
        assert!(run.statistics.largest_step > 0.15, "{:?}", run.statistics);
        assert_eq!(times.len(), 2, "{}: {times:?}", method.name());
        assert!(
            (times[0] - 0.6).abs() < 1e-12 && (times[1] - 0.75).abs() < 1e-12,
            "{times:?}"
        );
    }
}

for_both_algebras!(
    two_crossings_in_one_step,
    dropped_spinning_ball,
    pendulum_period_and_hinge,
    a_singular_force_ends_the_run_with_its_time
);
