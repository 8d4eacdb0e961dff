//! Joint limits (docs/limits.md): a pendulum released at rest meets its limit at the time the incomplete elliptic
//! integral gives, to 1e-12 s; an elastic bound keeps the energy to round-off and the bounces periodic; an inelastic
//! bound stops the pendulum there, held while gravity pushes it on, released at once where gravity pulls it off;
//! nothing passes a bound by more than 1e-12 rad; a double pendulum's elbow held and released agrees between the
//! algebras and the integrators; careless limits are refused by name.

use dynamics::limits::{Bound, JointLimit, LimitChange};
use dynamics::{
    simulate, Algebra, Body, Force, JointKind, JointMethod, JointModel, Mechanism, Method, Reference, Schedule,
    Simulation, SimulationError, Tolerance,
};
use nalgebra::{Isometry3, Vector3};

/// 1 kg, 1 m: the rod of the pendulums below, hinged at its top end.
fn rod() -> Body {
    Body::rod(1.0, 1.0, 1e-3).unwrap()
}

/// A hinge about world x at the origin, holding a body at its top end (0.5 m above its centre).
fn hinge(name: &str, parent_frame: Isometry3<f64>) -> JointModel {
    JointModel::new(
        name,
        JointKind::Revolute { axis: Vector3::x() },
        parent_frame,
        Isometry3::translation(0.0, 0.0, 0.5),
    )
    .unwrap()
}

/// The rod hinged at its top end to the world, under gravity, its hinge limited to `limit`.
fn pendulum<A: Algebra>(limit: JointLimit) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let body = system.add_body("rod", rod()).unwrap();
    system.add_force(body, Force::gravity()).unwrap();
    let joint = hinge("pivot", Isometry3::identity()).with_limit(limit).unwrap();
    system.connect(body, Reference::World, joint).unwrap();
    system
}

/// The pendulum's angular frequency for small swings, `√(m g d / I)` about the pivot (1/s).
fn frequency() -> f64 {
    let body = rod();
    let pivot_moment = body.moments().x + body.mass() * 0.25;
    (body.mass() * 9.81 * 0.5 / pivot_moment).sqrt()
}

/// F(φ | k²) from the `reference` crate (Carlson's symmetric form, checked there against quadrature).
fn elliptic_f(phi: f64, k: f64) -> f64 {
    reference::incomplete_elliptic_f(phi, reference::EllipticParameter::new(k * k).unwrap()).unwrap()
}

/// The time a pendulum released at rest from `start` (rad from hanging) takes to swing down through the bottom and
/// up the other side to `-reach` (0 < reach < start): a quarter period `K(k)/ω` and then `F(φ, k)/ω`, with
/// `k = sin(start/2)` and `sin φ = sin(reach/2)/k` (the exact pendulum, e.g. Lawden, *Elliptic functions and
/// applications*, §5.2).
fn swing_time(start: f64, reach: f64) -> f64 {
    let k = (start / 2.0).sin();
    let phi = ((reach / 2.0).sin() / k).asin();
    (elliptic_f(std::f64::consts::FRAC_PI_2, k) + elliptic_f(phi, k)) / frequency()
}

/// The joint angle of every sample of a one-pendulum run.
fn angles<A: Algebra>(system: &Mechanism<A>, run: &Simulation<A>) -> Vec<f64> {
    run.body(0)
        .iter()
        .map(|sample| system.joint_positions(&[sample.state(&rod())], None).unwrap()[0])
        .collect()
}

const START: f64 = 1.0; // rad
const REACH: f64 = 0.3; // rad

fn adaptive(tolerance: f64, duration: f64) -> Schedule {
    Schedule::adaptive(Tolerance::new(tolerance, tolerance).unwrap(), duration, 0.01).unwrap()
}

fn the_impact_is_at_the_elliptic_integrals_time<A: Algebra>() {
    let limit = JointLimit::new(-REACH, 2.0).unwrap();
    let system = pendulum::<A>(limit);
    let start = system.states_from_joints(&[START], &[0.0]).unwrap();
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 1.5)).unwrap();
    let exact = swing_time(START, REACH);
    let first = &run.transitions[0];
    assert!(
        (first.t - exact).abs() < 1e-12,
        "impact at {} s, the elliptic integral gives {exact} s: {:e} s apart",
        first.t,
        first.t - exact
    );
    assert!(matches!(
        first.change,
        LimitChange::Held {
            bound: Bound::Lower,
            ..
        }
    ));
    // Gravity pulls it back off the lower bound: released at once, it swings between ±0.3 rad.
    assert!(matches!(
        run.transitions[1].change,
        LimitChange::Released { bound: Bound::Lower }
    ));
    assert_eq!(run.transitions[1].t, first.t);
    let q = angles(&system, &run);
    let lowest = q.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(
        lowest >= -REACH - 1e-12,
        "passed the bound by {:e} rad",
        -REACH - lowest
    );
    let later = q.iter().zip(run.body(0)).filter(|(_, s)| s.t > first.t + 0.01);
    let highest = later.map(|(q, _)| *q).fold(f64::NEG_INFINITY, f64::max);
    assert!((highest - REACH).abs() < 1e-3, "swings back up to {highest} rad");
}

fn an_elastic_bound_keeps_the_energy<A: Algebra>() {
    let limit = JointLimit::new(-REACH, 2.0).unwrap().with_restitution(1.0).unwrap();
    let system = pendulum::<A>(limit);
    let start = system.states_from_joints(&[START], &[0.0]).unwrap();
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 5.0)).unwrap();
    let period = 2.0 * swing_time(START, REACH);
    assert!(run.transitions.len() >= 3);
    for (n, transition) in run.transitions.iter().enumerate() {
        let exact = (n as f64 + 0.5) * period;
        assert!(
            (transition.t - exact).abs() < 1e-11,
            "bounce {n} at {} s, {exact} s exact",
            transition.t
        );
        let LimitChange::Bounced {
            speed_before,
            speed_after,
            ..
        } = transition.change
        else {
            panic!("{:?}", transition.change)
        };
        assert!((speed_after - speed_before).abs() < 1e-13 * speed_before);
        assert!(
            transition.energy_change.abs() < 1e-14,
            "bounce {n}: {:e} J",
            transition.energy_change
        );
    }
    // Over the run the energy drifts by the integrator's error alone: no more than without the bound.
    let drift = |run: &Simulation<A>| {
        let energies: Vec<f64> = run.energies().collect();
        energies.iter().map(|e| (e - energies[0]).abs()).fold(0.0, f64::max)
    };
    let free = pendulum::<A>(JointLimit::new(-3.0, 3.0).unwrap());
    let unbounded = simulate(&free, &start, Method::Dop853Body, &adaptive(1e-12, 5.0)).unwrap();
    assert!(
        drift(&run) < 2.0 * drift(&unbounded),
        "energy drifts by {:e} J bouncing, {:e} J swinging free",
        drift(&run),
        drift(&unbounded)
    );
}

fn an_inelastic_bound_holds_the_pendulum<A: Algebra>() {
    // Released from -1 rad, the pendulum swings up to its upper bound at -0.3 rad, where gravity keeps pushing it.
    let limit = JointLimit::new(-2.0, -REACH).unwrap();
    let system = pendulum::<A>(limit);
    let start = system.states_from_joints(&[-START], &[0.0]).unwrap();
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 2.0)).unwrap();
    // The time from -1 rad to -0.3 rad on the way up: a quarter period less the time from -0.3 rad to the bottom.
    let k = (START / 2.0).sin();
    let exact =
        (elliptic_f(std::f64::consts::FRAC_PI_2, k) - elliptic_f(((REACH / 2.0).sin() / k).asin(), k)) / frequency();
    assert_eq!(run.transitions.len(), 1, "{:?}", run.transitions);
    assert!(
        (run.transitions[0].t - exact).abs() < 1e-12,
        "{} vs {exact}",
        run.transitions[0].t
    );
    let q = angles(&system, &run);
    for (q, sample) in q.iter().zip(run.body(0)).filter(|(_, s)| s.t > exact) {
        assert!(
            (q + REACH).abs() < 1e-12,
            "at {} s the pendulum is at {q} rad",
            sample.t
        );
        assert!(sample.angular_velocity.norm() < 1e-12);
    }
    // What the transitions took, up to a time: nothing before the impact, all of it after; NaN and -inf times are
    // before every transition.
    use dynamics::limits::energy_changed_by;
    let taken = run.transitions[0].energy_change;
    assert!(taken < 0.0);
    for (t, expected) in [
        (0.0, 0.0),
        (exact - 1e-3, 0.0),
        (exact + 1e-3, taken),
        (f64::INFINITY, taken),
    ] {
        assert_eq!(energy_changed_by(&run.transitions, t), expected, "t = {t}");
    }
    assert_eq!(energy_changed_by(&run.transitions, f64::NAN), 0.0);
    assert_eq!(energy_changed_by(&run.transitions, f64::NEG_INFINITY), 0.0);
    assert_eq!(energy_changed_by(&[], 1.0), 0.0);
    // The impact took the kinetic energy: the pendulum rests at the potential energy of -0.3 rad.
    let body = rod();
    let resting = -body.mass() * 9.81 * 0.5 * REACH.cos();
    let end = run.body(0).last().unwrap().energy;
    assert!((end - resting).abs() < 1e-12, "{end} J at rest, {resting} J expected");
}

/// Two rods, the upper hinged at its top end to the world, the lower at its top end to the upper's bottom end, both
/// about x; the elbow limited to `elbow`.
fn double_pendulum<A: Algebra>(elbow: JointLimit) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let upper = system.add_body("upper", rod()).unwrap();
    let lower = system.add_body("lower", rod()).unwrap();
    for body in [upper, lower] {
        system.add_force(body, Force::gravity()).unwrap();
    }
    system
        .connect(upper, Reference::World, hinge("shoulder", Isometry3::identity()))
        .unwrap();
    let elbow = hinge("elbow", Isometry3::translation(0.0, 0.0, -0.5))
        .with_limit(elbow)
        .unwrap();
    system.connect(lower, upper, elbow).unwrap();
    system
}

/// The double pendulum released with the upper rod at 1.2 rad and the elbow straight: the elbow folds onto a bound,
/// is held there while the swing presses it on, and released where the swing would pull it off.
fn the_elbow_is_held_and_released_alike_by_every_method<A: Algebra>() {
    let system = double_pendulum::<A>(JointLimit::new(-0.3, 0.3).unwrap());
    let start = system.states_from_joints(&[1.2, 0.0], &[0.0, 0.0]).unwrap();
    let runs = [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 3.0)).unwrap(),
        simulate(&system, &start, Method::Dopri5Body, &adaptive(1e-12, 3.0)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(1e-3, 3.0).unwrap()).unwrap(),
    ];
    let changes: Vec<_> = runs[0]
        .transitions
        .iter()
        .map(|t| std::mem::discriminant(&t.change))
        .collect();
    assert!(runs[0]
        .transitions
        .iter()
        .any(|t| matches!(t.change, LimitChange::Held { .. })));
    assert!(runs[0]
        .transitions
        .iter()
        .any(|t| matches!(t.change, LimitChange::Released { .. })));
    for run in &runs[1..] {
        let others: Vec<_> = run
            .transitions
            .iter()
            .map(|t| std::mem::discriminant(&t.change))
            .collect();
        assert_eq!(changes, others, "{:?}\nvs\n{:?}", runs[0].transitions, run.transitions);
        for (a, b) in runs[0].transitions.iter().zip(&run.transitions) {
            assert!((a.t - b.t).abs() < 1e-9, "{} s vs {} s", a.t, b.t);
        }
    }
    // Held, the elbow is on its bound to round-off and the energy holds (the hold does no work); it never passes one.
    let state = |sample: &dynamics::simulate::Sample| sample.state::<A>(&rod());
    let samples: Vec<(f64, f64, f64)> = (runs[0].body(0).iter().zip(runs[0].body(1)))
        .map(|(upper, lower)| {
            let q = system.joint_positions(&[state(upper), state(lower)], None).unwrap()[1];
            (upper.t, q, upper.energy)
        })
        .collect();
    assert!(
        samples.iter().all(|&(_, q, _)| q.abs() <= 0.3 + 1e-12),
        "the elbow passes a bound"
    );
    for pair in runs[0].transitions.chunks(2) {
        let (LimitChange::Held { bound, .. }, LimitChange::Released { .. }) = (pair[0].change, pair[1].change) else {
            panic!("{pair:?}");
        };
        let at = JointLimit::new(-0.3, 0.3).unwrap().at(bound);
        let during: Vec<_> = samples
            .iter()
            .filter(|(t, ..)| *t > pair[0].t && *t < pair[1].t)
            .collect();
        for &&(t, q, _) in &during {
            assert!((q - at).abs() < 1e-12, "held, at {t} s the elbow is at {q} rad");
        }
        let spread = during.iter().map(|(.., e)| (e - during[0].2).abs()).fold(0.0, f64::max);
        assert!(
            spread < 1e-11,
            "held from {} s, the energy moves by {spread:e} J",
            pair[0].t
        );
    }
}

for_both_algebras!(
    the_elbow_is_held_and_released_alike_by_every_method,
    the_impact_is_at_the_elliptic_integrals_time,
    an_elastic_bound_keeps_the_energy,
    an_inelastic_bound_holds_the_pendulum,
);

/// Careless limits, each refused naming what is wrong: bounds NaN, inverted, equal or both infinite; a restitution
/// outside [0, 1]; a limit on a joint with other than one coordinate or driven, a drive on a limited joint; a
/// coupling whose follower is limited; a start beyond a bound; a change that would take the articulated solve a limit
/// needs (Baumgarte, a joint that is not a joint model). Huge and one-sided bounds are limits like any other.
#[test]
fn careless_limits_are_refused() {
    use dynamics::constraints::{PathPoint, Stabilisation, VirtualPower};
    use dynamics::Pga;
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    for (lower, upper) in [
        (nan, 1.0),
        (-1.0, nan),
        (1.0, -1.0),
        (0.5, 0.5),
        (-inf, inf),
        (inf, inf),
        (-inf, -inf),
    ] {
        let error = JointLimit::new(lower, upper).unwrap_err().to_string();
        assert!(error.contains("lower < upper"), "[{lower}, {upper}]: {error}");
    }
    for (lower, upper) in [(-1e300, 1e300), (-inf, 0.0), (0.0, inf), (-1e-300, 1e-300)] {
        assert!(JointLimit::new(lower, upper).is_ok(), "[{lower}, {upper}]");
    }
    for restitution in [nan, -0.1, 1.0 + 1e-12, inf, -inf] {
        let error = JointLimit::new(-1.0, 1.0)
            .unwrap()
            .with_restitution(restitution)
            .unwrap_err()
            .to_string();
        assert!(error.contains("restitution"), "{restitution}: {error}");
    }
    let limit = JointLimit::new(-1.0, 1.0).unwrap();
    let frame = Isometry3::identity();
    for kind in [
        JointKind::Spherical,
        JointKind::Cylindrical { axis: Vector3::z() },
        JointKind::Free,
    ] {
        let error = JointModel::new("j", kind, frame, frame)
            .unwrap()
            .with_limit(limit)
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("only revolute and prismatic joints can be limited"),
            "{error}"
        );
    }
    let spin = |t: f64| PathPoint {
        value: t,
        rate: 1.0,
        acceleration: 0.0,
    };
    let driven = hinge("axle", frame).driven(spin).unwrap();
    assert!(driven
        .with_limit(limit)
        .unwrap_err()
        .to_string()
        .contains("driven joint cannot be limited"));
    let limited = hinge("axle", frame).with_limit(limit).unwrap();
    assert!(limited
        .driven(spin)
        .unwrap_err()
        .to_string()
        .contains("limited joint cannot be driven"));

    // A limited follower of a coupling.
    let mut pair = Mechanism::<Pga>::new();
    let (a, b) = (pair.add_body("a", rod()).unwrap(), pair.add_body("b", rod()).unwrap());
    let leader = pair.connect(a, Reference::World, hinge("leader", frame)).unwrap();
    let follower = pair
        .connect(
            b,
            Reference::World,
            hinge("follower", Isometry3::translation(1.0, 0.0, 0.0))
                .with_limit(limit)
                .unwrap(),
        )
        .unwrap();
    let error = pair.couple(follower, leader, 1.0, 0.0).unwrap_err().to_string();
    assert!(error.contains("limited joint cannot follow"), "{error}");
    // Baumgarte, and a joint that is not a joint model, would take the articulated solve away.
    let error = pair
        .set_stabilisation(Stabilisation::Baumgarte { alpha: 1.0, beta: 1.0 })
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("limits joint coordinates") && error.contains("follower"),
        "{error}"
    );
    let ball = VirtualPower::ball_joint("tie", Vector3::zeros(), Vector3::x());
    let error = pair.add_joint(b, a, ball).unwrap_err().to_string();
    assert!(error.contains("limits joint coordinates"), "{error}");

    // A start beyond a bound by more than 1e-12 rad, by a little and by far; on the bound, or within 1e-12 of it,
    // is a start at the bound.
    let system = pendulum::<Pga>(JointLimit::new(-0.5, 0.5).unwrap());
    let schedule = Schedule::new(1e-3, 0.01).unwrap();
    for q in [0.5 + 1e-11, -0.5 - 1e-9, 3.0, -3.0] {
        let start = system.states_from_joints(&[q], &[0.0]).unwrap();
        let error = simulate(&system, &start, Method::Rkmk4Body, &schedule).unwrap_err();
        assert!(
            matches!(&error, SimulationError::BeyondLimit { constraint, .. } if constraint == "pivot"),
            "{q}: {error}"
        );
    }
    // The limits' interface to simulate: a limit that is not there, the wrong number of states or of values.
    use dynamics::Dynamics;
    let start = system.states_from_joints(&[0.0], &[0.0]).unwrap();
    let mut workspace = system.workspace();
    assert_eq!(
        (system.limit_count(), system.limit_name(0), system.limit_name(1)),
        (1, Some("pivot"), None)
    );
    let mut states = start.clone();
    let error = system
        .limit_transition(1, 0.0, &mut states, &mut workspace)
        .unwrap_err()
        .to_string();
    assert!(error.contains("no one-sided constraint 1"), "{error}");
    let error = system
        .limit_transition(0, 0.0, &mut [], &mut workspace)
        .unwrap_err()
        .to_string();
    assert!(error.contains("states: 0 given"), "{error}");
    for values in [&mut [][..], &mut [0.0, 0.0][..]] {
        let error = system
            .limit_values(0.0, &start, &mut workspace, values)
            .unwrap_err()
            .to_string();
        assert!(error.contains("limit values"), "{error}");
    }
    let mut values = [f64::NAN];
    system.limit_values(0.0, &start, &mut workspace, &mut values).unwrap();
    assert!(
        (values[0] - 0.5).abs() < 1e-15,
        "the gap at the bottom is 0.5 rad, got {}",
        values[0]
    );
    // A sample that is not finite gives a state the run refuses before its first step.
    let mut sample = simulate(&system, &start, Method::Rkmk4Body, &schedule).unwrap().body(0)[0];
    sample.position.x = f64::NAN;
    let error = simulate(&system, &[sample.state(&rod())], Method::Rkmk4Body, &schedule).unwrap_err();
    assert!(error.to_string().contains("not finite"), "{error}");
    for q in [0.5, 0.5 + 5e-13, -0.5] {
        let start = system.states_from_joints(&[q], &[0.0]).unwrap();
        let run = simulate(&system, &start, Method::Rkmk4Body, &schedule).unwrap();
        assert!(matches!(run.transitions[0].change, LimitChange::Held { speed_before, .. } if speed_before == 0.0));
        assert_eq!(run.transitions[0].t, 0.0);
    }
}
