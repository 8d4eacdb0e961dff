//! The constraint machinery on one body held by the world: rows against finite differences (the theory §6–§9
//! derivatives, E3), the ranks of the theory §7 and §9 tables, the dual line of E4, translator paths (§8), the
//! reaction solve (§7.1) and the errors.

use std::sync::Arc;

use dynamics::constraints::objects::cga_circle;
use dynamics::constraints::paths::{moving_point, Fixed, TranslatedPath};
use dynamics::constraints::{
    linear, pinning, Composite, Constraint, ConstraintError, Kinematics, Path, PathPoint, Pinnable, PinningAlgebra,
    RowBuffer, Stabilisation, VirtualPower, WrenchPoint,
};
use dynamics::exponential::exp;
use dynamics::forces::force_line;
use dynamics::{
    Algebra, Body, Cga, Force, Mechanism, MechanismError, Method, Pga, Reference, State, StepError, Stepper,
};
use nalgebra::{DMatrix, UnitQuaternion, Vector3};

fn body() -> Body {
    Body::new(1.3, Vector3::new(0.4, 0.3, 0.2)).unwrap()
}

/// A generic pose and velocity (no symmetry to hide a wrong sign).
fn state<A: Algebra>() -> State<A> {
    State::new(
        &body(),
        Vector3::new(0.3, -0.2, 0.5),
        &UnitQuaternion::from_euler_angles(0.4, -0.7, 1.1),
        Vector3::new(0.9, -1.3, 2.1),
        Vector3::new(-0.4, 0.7, 0.2),
    )
}

/// The motion with constant body velocity Ḃ: `R(s) = R exp(−½ s Ḃ)` (theory §3), so B̈ = 0 and the rate of
/// the velocity residual along it is the row's bias alone.
fn kinematics_along<A: Algebra>(state: &State<A>, s: f64, t: f64) -> Kinematics<A> {
    let velocity = state.body_velocity(&body());
    let motor = A::compose(state.motor, exp::<A>(velocity * (-0.5 * s)));
    Kinematics::new(t + s, motor, velocity)
}

fn rows_at<A: Algebra>(constraint: &dyn Constraint<A>, kinematics: &Kinematics<A>) -> RowBuffer {
    let mut rows = RowBuffer::new();
    constraint.rows(kinematics, &mut rows).unwrap();
    assert_eq!(rows.len(), constraint.row_count());
    rows
}

/// ė = de/dt and b = dė/dt along a motion with B̈ = 0, by central differences (error O(h²) ≈ 1e-8).
fn rows_are_derivatives<A: Algebra>(constraint: &dyn Constraint<A>, state: &State<A>) {
    let (h, t) = (1e-4, 0.3);
    let at = |s| rows_at(constraint, &kinematics_along(state, s, t));
    let (before, here, after) = (at(-h), at(0.0), at(h));
    let scale = here
        .rows()
        .iter()
        .map(|r| r.bias.abs() + r.velocity_residual.abs())
        .fold(1.0, f64::max);
    for i in 0..here.len() {
        let (b, r, a) = (before.rows()[i], here.rows()[i], after.rows()[i]);
        if let (Some(eb), Some(ea)) = (b.position_residual, a.position_residual) {
            let rate = (ea - eb) / (2.0 * h);
            assert!(
                (rate - r.velocity_residual).abs() < 1e-7 * scale,
                "{} row {i}: de/dt {rate} vs ė {}",
                constraint.name(),
                r.velocity_residual
            );
        }
        let rate = (a.velocity_residual - b.velocity_residual) / (2.0 * h);
        assert!(
            (rate - r.bias).abs() < 1e-7 * scale,
            "{} row {i}: dė/dt {rate} vs bias {}",
            constraint.name(),
            r.bias
        );
        // For a constraint that does not move, ė = a·x exactly (no explicit time term).
        let power: f64 = r
            .jacobian
            .iter()
            .zip(kinematics_along(state, 0.0, t).velocity.iter())
            .map(|(a, x)| a * x)
            .sum();
        if constraint.name().starts_with("static") {
            assert!(
                (power - r.velocity_residual).abs() < 1e-12 * scale,
                "{}",
                constraint.name()
            );
        }
    }
}

/// World objects equal to the body ones moved by the state's motor, so the pins start on their manifold.
fn on_manifold<A: Algebra, X: Pinnable<A>>(body_object: X, state: &State<A>) -> X {
    body_object.transformed(state.motor)
}

fn pins_and_wrenches<A: PinningAlgebra>() -> Vec<Arc<dyn Constraint<A>>> {
    let s = state::<A>();
    let a = Vector3::new(0.1, -0.3, 0.25);
    let oscillation = |t: f64| PathPoint {
        value: Vector3::new(0.2 * t.sin(), 0.1 * t * t, -0.3),
        rate: Vector3::new(0.2 * t.cos(), 0.2 * t, 0.0),
        acceleration: Vector3::new(-0.2 * t.sin(), 0.2, 0.0),
    };
    vec![
        Arc::new(pinning::Pin::new(
            "static point",
            A::point_object(a),
            on_manifold(A::point_object(a), &s),
            3,
        )),
        Arc::new(pinning::Pin::new(
            "static line",
            A::line_object(a, Vector3::new(0.3, 0.5, -0.8)),
            on_manifold(A::line_object(a, Vector3::new(0.3, 0.5, -0.8)), &s),
            4,
        )),
        Arc::new({
            // {x_b : n·x_b = δ} moves to {x : (R n)·x = δ + (R n)·c}.
            let (normal, offset) = (Vector3::new(0.0, 0.6, 0.8), 0.2);
            let (centre, rotation) = s.pose();
            let world_normal = rotation * normal;
            pinning::plane::<A>(
                "static plane",
                (normal, offset),
                (world_normal, offset + world_normal.dot(&centre)),
            )
            .unwrap()
        }),
        Arc::new(pinning::driven_point::<A>("driven pivot", a, oscillation)),
        Arc::new(pinning::sliding_attachment::<A>(
            "sliding attachment",
            oscillation,
            Vector3::new(0.5, 0.1, 0.2),
        )),
        Arc::new(linear::point_on_plane::<A>(
            "point on plane",
            a,
            (Vector3::new(1.0, 2.0, 2.0), 0.3),
        )),
        Arc::new(VirtualPower::ball_joint("ball", a, Vector3::new(0.1, 0.2, 0.3))),
        Arc::new(
            VirtualPower::hinge(
                "hinge",
                (a, Vector3::new(0.0, 0.0, 1.0)),
                (Vector3::zeros(), Vector3::y()),
            )
            .unwrap(),
        ),
        Arc::new(
            VirtualPower::cylindrical(
                "cylinder",
                (a, Vector3::new(1.0, 0.0, 0.0)),
                (Vector3::zeros(), Vector3::z()),
            )
            .unwrap(),
        ),
        Arc::new(VirtualPower::point_on_plane("plane", a, (Vector3::new(0.0, 0.0, 2.0), 0.4)).unwrap()),
        Arc::new(VirtualPower::point_on_moving_sphere("moving sphere", a, oscillation, 0.7).unwrap()),
        Arc::new(VirtualPower::point_on_circle("circle", a, (Vector3::x(), 0.6, Vector3::new(0.0, 1.0, 1.0))).unwrap()),
    ]
}

/// The body point `a` on a circle about `centre` through its current world position.
fn on_circle(s: &State<Cga>, a: Vector3<f64>, centre: Vector3<f64>) -> impl Constraint<Cga> {
    let radial = s.world_point(a) - centre;
    let normal = radial.cross(&Vector3::new(0.3, 1.0, -0.2));
    linear::cga_point_on_circle("point on circle", a, (centre, radial.norm(), normal))
}

fn cga_only() -> Vec<Arc<dyn Constraint<Cga>>> {
    let s = state::<Cga>();
    let a = Vector3::new(0.1, -0.3, 0.25);
    vec![
        Arc::new(pinning::cga_sphere_pin("static sphere", a, s.world_point(a), 0.4)),
        Arc::new(pinning::cga_circle_pin(
            "static circle",
            (a, Vector3::new(1.0, 1.0, 0.0)),
            (s.world_point(a), s.pose().1 * Vector3::new(1.0, 1.0, 0.0)),
            0.4,
        )),
        // The same circle built directly: the world object is the body object moved by R.
        Arc::new(pinning::Pin::new(
            "static circle object",
            cga_circle(a, 0.4, Vector3::new(1.0, 1.0, 0.0)),
            on_manifold(cga_circle(a, 0.4, Vector3::new(1.0, 1.0, 0.0)), &s),
            5,
        )),
        Arc::new(linear::cga_point_on_sphere("point on sphere", a, Vector3::x(), 0.9)),
        Arc::new(on_circle(&s, a, Vector3::x())),
        Arc::new(linear::cga_point_on_moving_sphere(
            "point on moving sphere",
            a,
            |t: f64| PathPoint {
                value: Vector3::new(t.cos(), t.sin(), 0.1 * t),
                rate: Vector3::new(-t.sin(), t.cos(), 0.1),
                acceleration: Vector3::new(-t.cos(), -t.sin(), 0.0),
            },
            0.9,
        )),
    ]
}

#[test]
fn rows_are_the_derivatives_of_the_residuals() {
    for constraint in pins_and_wrenches::<Pga>() {
        rows_are_derivatives(constraint.as_ref(), &state::<Pga>());
    }
    for constraint in pins_and_wrenches::<Cga>().into_iter().chain(cga_only()) {
        rows_are_derivatives(constraint.as_ref(), &state::<Cga>());
    }
}

/// The number of singular values of `A H^{-1/2}` above 1e-6 of the largest (the solver's rank tolerance).
fn numerical_rank<A: Algebra>(constraint: &dyn Constraint<A>, state: &State<A>) -> usize {
    let rows = rows_at(
        constraint,
        &Kinematics::new(0.0, state.motor, state.body_velocity(&body())),
    );
    let scale = body().kinetic_metric().diagonal().map(|h| 1.0 / h.sqrt());
    let scaled = DMatrix::from_fn(rows.len(), 6, |i, j| rows.rows()[i].jacobian[j] * scale[j]);
    let values = scaled.singular_values();
    let largest = values.max();
    values.iter().filter(|&&v| v > 1e-6 * largest).count()
}

/// theory §7 and §9 tables, checked on the manifold.
#[test]
fn ranks_match_the_spec_tables() {
    let s = state::<Pga>();
    let pga = pins_and_wrenches::<Pga>();
    let cga = pins_and_wrenches::<Cga>();
    for (pga, cga) in pga.iter().zip(&cga) {
        let rank = pga.rank();
        // Pins start on the manifold; the incidence and wrench constraints have the rank of their rows anywhere.
        assert_eq!(numerical_rank(pga.as_ref(), &s), rank, "{}", pga.name());
        assert_eq!(numerical_rank(cga.as_ref(), &state::<Cga>()), rank, "{}", cga.name());
    }
    for constraint in cga_only() {
        assert_eq!(
            numerical_rank(constraint.as_ref(), &state::<Cga>()),
            constraint.rank(),
            "{}",
            constraint.name()
        );
    }
    // E8: 1 mm off its circle the incidence picks up spurious rank (4 instead of 2).
    let displaced = State::<Cga> {
        motor: Cga::compose(
            dynamics::motor::translator::<Cga>(Vector3::repeat(1e-3)),
            state::<Cga>().motor,
        ),
        ..state::<Cga>()
    };
    let circle = on_circle(&state::<Cga>(), Vector3::new(0.1, -0.3, 0.25), Vector3::x());
    assert_eq!(numerical_rank(&circle, &displaced), 4);
    let expected = [3, 4, 3, 3, 3, 1, 3, 5, 4, 1, 1, 2];
    assert_eq!(pga.iter().map(|c| c.rank()).collect::<Vec<_>>(), expected);
    // Line + point = hinge (rank 5, not 4 + 3; E7).
    let a = Vector3::new(0.1, -0.3, 0.25);
    let world = |x: Vector3<f64>| s.world_point(x);
    let hinge = pinning::hinge::<Pga>(
        "pinned hinge",
        (a, Vector3::z()),
        (world(a), world(a + Vector3::z()) - world(a)),
    )
    .unwrap();
    assert_eq!(numerical_rank(&hinge, &s), 5);
}

/// E4: the sphere constraint's wrench is the dual line `(A∧up(c)∧n∞)I₅` — the force line through A towards c —
/// not the OPNS line itself.
#[test]
fn sphere_wrench_is_the_dual_line() {
    use dynamics::cga::generated::{Bivector, Pseudoscalar, Vector};
    let (a, c) = (Vector3::new(0.3, -0.5, 0.2), Vector3::new(-0.1, 0.4, 0.7));
    let infinity = Vector {
        ninf: 1.0,
        ..Vector::ZERO
    };
    let line = Cga::point(a) ^ Cga::point(c) ^ infinity;
    // I₅ = e12345 = −e1_e2_e3_n0_ninf (e4∧e5 = −n0∧n∞).
    let dual = (line * Pseudoscalar { e1_e2_e3_n0_ninf: -1.0 }).grade_2();
    let expected = Bivector::from(force_line::<Cga>(c - a, a));
    let difference = (dual - expected)
        .to_array()
        .iter()
        .fold(0.0f64, |worst, d| worst.max(d.abs()));
    assert!(difference < 1e-14, "{dual:?} vs {expected:?}");
}

/// theory §8: the translator path is exactly `T(c) V₀ ~T(c)`, with derivatives matching finite differences.
#[test]
fn translated_paths_are_exact() {
    let c = |t: f64| PathPoint {
        value: Vector3::new(t.sin(), 0.5 * t, t * t),
        rate: Vector3::new(t.cos(), 0.5, 2.0 * t),
        acceleration: Vector3::new(-t.sin(), 0.0, 2.0),
    };
    let base = cga_circle(Vector3::new(0.2, 0.1, -0.4), 0.7, Vector3::new(1.0, -1.0, 0.5));
    let path = TranslatedPath::<Cga, _, _>::new(base, c);
    let pga_path = moving_point::<Pga, _>(c);
    let (t, h) = (0.7, 1e-5);
    let point = path.at(t);
    let direct = base.transformed(dynamics::motor::translator::<Cga>(c(t).value));
    let distance = |x: dynamics::cga::generated::Trivector, y: dynamics::cga::generated::Trivector| {
        x.to_array()
            .iter()
            .zip(y.to_array())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    assert!(distance(point.value, direct) < 1e-14);
    let rate = (path.at(t + h).value - path.at(t - h).value) * (0.5 / h);
    assert!(distance(rate, point.rate) < 1e-8, "{}", distance(rate, point.rate));
    let acceleration = (path.at(t + h).rate - path.at(t - h).rate) * (0.5 / h);
    assert!(distance(acceleration, point.acceleration) < 1e-8);
    assert!((Pga::position(pga_path.at(t).value) - c(t).value).norm() < 1e-15);
    assert!(Fixed(base).is_fixed() && !path.is_fixed());
}

/// A constraint whose rows are another's, each emitted twice: more rows than its rank, so the reduction goes
/// through the kinetic-metric truncated decomposition instead of taking the rows as they are.
struct Doubled<C>(C);

impl<A: Algebra, C: Constraint<A>> Constraint<A> for Doubled<C> {
    fn name(&self) -> &str {
        self.0.name()
    }

    fn rank(&self) -> usize {
        self.0.rank()
    }

    fn row_count(&self) -> usize {
        2 * self.0.row_count()
    }

    fn has_position_residual(&self) -> bool {
        self.0.has_position_residual()
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        let mut single = RowBuffer::new();
        self.0.rows(kinematics, &mut single)?;
        for row in single.rows() {
            rows.push(*row);
            rows.push(*row);
        }
        Ok(())
    }
}

/// The first joint's world reaction wrench on the body.
fn reaction<A: Algebra>(system: &Mechanism<A>, state: &State<A>) -> dynamics::ScrewCoordinates {
    A::screw_coordinates(system.reactions(0.0, std::slice::from_ref(state)).unwrap()[0])
}

fn close(a: dynamics::ScrewCoordinates, b: dynamics::ScrewCoordinates, tolerance: f64) -> bool {
    (a.l - b.l).norm() < tolerance && (a.t - b.t).norm() < tolerance
}

/// The reaction of the kinetic-metric solve does no work on the motions the constraint allows, and equals
/// that of a supplied basis of the same span (theory §7.1 methods 1 and 2); the reduction's two evaluations
/// (rows as they are, truncated decomposition of redundant rows) agree.
#[test]
fn reaction_solves_agree() {
    let s = state::<Pga>();
    let tip = Vector3::new(0.1, -0.3, 0.25);
    let pivot = s.world_point(tip);
    let system = |reaction_basis: bool| {
        let system = Mechanism::<Pga>::single(body())
            .with_force(Force::gravity())
            .unwrap()
            .with_constraint(pinning::point::<Pga>("tip", tip, pivot))
            .unwrap();
        if reaction_basis {
            let forces = (0..3).map(|k| force_line::<Pga>(Vector3::ith(k, 1.0), pivot)).collect();
            system.with_reaction_basis(forces).unwrap()
        } else {
            system
        }
    };
    let kinetic = reaction(&system(false), &s);
    let basis = reaction(&system(true), &s);
    assert!(close(kinetic, basis, 1e-12), "{kinetic:?} vs {basis:?}");
    // A pure force through the pivot: no moment about it (zero power on rotations about the pivot).
    assert!((kinetic.t - pivot.cross(&kinetic.l)).norm() < 1e-12, "{kinetic:?}");

    let ball = || VirtualPower::<Pga>::ball_joint("ball", tip, pivot);
    let single = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(ball())
        .unwrap();
    let doubled = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(Doubled(ball()))
        .unwrap();
    let (a, b) = (reaction(&single, &s), reaction(&doubled, &s));
    assert!(close(a, b, 1e-12 * (a.l.norm() + a.t.norm())), "{a:?} vs {b:?}");
    // On the velocity manifold the pinned point and the ball by virtual power are the same joint. (Off it their
    // residuals' second derivatives differ, and so do their reactions.)
    let mut on_manifold = [s];
    single.project(0.0, &mut on_manifold).unwrap();
    let (power, pin) = (
        reaction(&single, &on_manifold[0]),
        reaction(&system(false), &on_manifold[0]),
    );
    assert!(
        close(power, pin, 1e-12 * (pin.l.norm() + pin.t.norm())),
        "{power:?} vs {pin:?}"
    );
}

fn error_of<A: Algebra>(system: &Mechanism<A>, state: &State<A>) -> ConstraintError {
    system.rates_at(0.0, std::slice::from_ref(state)).unwrap_err()
}

/// Redundant joints that agree are solved (the loop they form has a rank-deficient but consistent Schur
/// complement); joints that contradict each other are an error naming them.
#[test]
fn redundant_joints_run_and_contradictions_are_named() {
    let s = state::<Pga>();
    let tip = Vector3::new(0.1, -0.3, 0.25);
    let pivot = s.world_point(tip);
    let one = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(pinning::point::<Pga>("first", tip, pivot))
        .unwrap();
    // Two pins of the same point: 6 declared degrees of freedom, 3 real ones.
    let twice = one
        .clone()
        .with_constraint(pinning::point::<Pga>("second", tip, pivot))
        .unwrap();
    let (single, double) = (one.rates_at(0.0, &[s]).unwrap(), twice.rates_at(0.0, &[s]).unwrap());
    let rate = |r: &dynamics::Rates<Pga>| Pga::screw_coordinates(r.momentum_rate);
    assert!(close(rate(&single[0]), rate(&double[0]), 1e-12));
    // A line and a point on it pinned separately (rank 4 + 3 declared) make the hinge of rank 5.
    let axis = s.pose().1 * Vector3::z();
    let hinge = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(pinning::hinge::<Pga>("hinge", (tip, Vector3::z()), (pivot, axis)).unwrap())
        .unwrap();
    let separate = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(pinning::line::<Pga>("line", (tip, Vector3::z()), (pivot, axis)).unwrap())
        .unwrap()
        .with_constraint(pinning::point::<Pga>("point", tip, pivot))
        .unwrap();
    // (At a state that satisfies the joint's velocity conditions, where the stacked rows are consistent.)
    let mut on_manifold = [s];
    hinge.project(0.0, &mut on_manifold).unwrap();
    let (a, b) = (
        hinge.rates_at(0.0, &on_manifold).unwrap(),
        separate.rates_at(0.0, &on_manifold).unwrap(),
    );
    assert!(
        close(rate(&a[0]), rate(&b[0]), 1e-11),
        "{:?} vs {:?}",
        rate(&a[0]),
        rate(&b[0])
    );

    // The same body point pulled to two places 10 cm apart, accelerating apart: contradictory rows.
    let apart = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(VirtualPower::ball_joint("left", tip, pivot))
        .unwrap()
        .with_constraint(VirtualPower::driven_ball_joint("right", tip, move |t: f64| PathPoint {
            value: pivot + Vector3::new(0.1 + t * t, 0.0, 0.0),
            rate: Vector3::new(2.0 * t, 0.0, 0.0),
            acceleration: Vector3::new(2.0, 0.0, 0.0),
        }))
        .unwrap();
    let error = error_of(&apart, &s);
    assert!(
        matches!(error, ConstraintError::Inconsistent { ref names, .. } if names.contains("left") && names.contains("right")),
        "{error}"
    );
}

/// Bad systems fail with an error naming the constraint, never with NaN.
#[test]
fn failures_name_the_constraint() {
    let s = state::<Pga>();
    let tip = Vector3::new(0.1, -0.3, 0.25);
    let pivot = s.world_point(tip);

    // Horizontal forces cannot hold a point against gravity: the supplied basis leaves the acceleration
    // conditions unsolved (relative residual of order 1).
    let couples = (0..2).map(|k| force_line::<Pga>(Vector3::ith(k, 1.0), pivot)).collect();
    let wrong_basis = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(pinning::point::<Pga>("pivot", tip, pivot))
        .unwrap()
        .with_reaction_basis(couples)
        .unwrap();
    let error = error_of(&wrong_basis, &s);
    assert!(
        matches!(error, ConstraintError::Inconsistent { ref names, .. } if names == "pivot"),
        "{error}"
    );

    // A path that is not finite.
    let broken = |_t: f64| PathPoint::at_rest(Pga::point(Vector3::repeat(f64::NAN)));
    let nan = Mechanism::<Pga>::single(body())
        .with_constraint(pinning::Pin::with_paths("broken", Fixed(Pga::point(tip)), broken, 3))
        .unwrap();
    assert!(matches!(error_of(&nan, &s), ConstraintError::NonFinite { ref name, .. } if name == "broken"));
    // A step fails with the error and its time, and leaves the state as it was.
    let mut states = [s];
    let error = Stepper::new(&nan, Method::Rk4)
        .unwrap()
        .step(0.5, &mut states, 1e-3)
        .unwrap_err();
    assert!(
        matches!(error, StepError::Constraint { t, error: ConstraintError::NonFinite { .. } } if t == 0.5),
        "{error}"
    );
    assert_eq!(states[0], s);

    // User wrenches have no position residual: no projection, which is the default, so it must be chosen away first.
    let wrench = force_line::<Pga>(Vector3::z(), Vector3::zeros());
    let custom = || VirtualPower::<Pga>::from_wrenches("custom", vec![Arc::new(move |_t| WrenchPoint::fixed(wrench))]);
    let refused = Mechanism::<Pga>::single(body()).with_constraint(custom());
    assert!(
        matches!(refused, Err(MechanismError::Constraint(ConstraintError::NoPositionResidual { ref name })) if name == "custom")
    );
    let unstabilised = Mechanism::<Pga>::single(body())
        .with_stabilisation(Stabilisation::None)
        .unwrap();
    let refused = unstabilised
        .with_constraint(custom())
        .unwrap()
        .with_stabilisation(Stabilisation::PROJECTION);
    assert!(
        matches!(refused, Err(MechanismError::Constraint(ConstraintError::NoPositionResidual { ref name })) if name == "custom")
    );

    let declared = Mechanism::<Pga>::single(body()).with_constraint(Composite::new(
        "overdeclared",
        vec![Arc::new(
            VirtualPower::<Pga>::point_on_plane("plane", tip, (Vector3::z(), 0.0)).unwrap(),
        )],
        2,
    ));
    assert!(matches!(
        declared,
        Err(MechanismError::Constraint(ConstraintError::InvalidRank {
            rank: 2,
            rows: 1,
            ..
        }))
    ));
    let zero_rank = Mechanism::<Pga>::single(body()).with_constraint(pinning::Pin::new(
        "zero rank",
        Pga::point(tip),
        Pga::point(pivot),
        0,
    ));
    assert!(matches!(
        zero_rank,
        Err(MechanismError::Constraint(ConstraintError::InvalidRank { rank: 0, .. }))
    ));
    assert!(VirtualPower::<Pga>::hinge("zero axis", (tip, Vector3::zeros()), (pivot, Vector3::z())).is_err());
    assert!(VirtualPower::<Pga>::point_on_sphere("zero radius", tip, pivot, 0.0).is_err());
}

/// A point on a sphere whose centre moves, by virtual power (prescribed power `(c − a)·ċ`) and by pinning the
/// translated CGA sphere (theory §8, §9): both hold it, and agree.
#[test]
fn moving_sphere_by_both_formulations() {
    let centre = |t: f64| PathPoint {
        value: Vector3::new(0.3 * t.sin(), 0.0, 0.0),
        rate: Vector3::new(0.3 * t.cos(), 0.0, 0.0),
        acceleration: Vector3::new(-0.3 * t.sin(), 0.0, 0.0),
    };
    let rod = Body::rod(1.0, 1.0, 1e-3).unwrap();
    let end = Vector3::new(0.0, 0.0, 0.5);
    let initial = State::<Cga>::new(
        &rod,
        Vector3::new(0.5, 0.0, -0.5),
        &UnitQuaternion::identity(),
        Vector3::x(),
        Vector3::new(0.0, 0.5, 0.0),
    );
    let system = |constraint: Arc<dyn Constraint<Cga>>| {
        Mechanism::<Cga>::single(rod)
            .with_force(Force::gravity())
            .unwrap()
            .with_constraint(constraint)
            .unwrap()
            .with_stabilisation(Stabilisation::PROJECTION)
            .unwrap()
    };
    let by_power = system(Arc::new(
        VirtualPower::point_on_moving_sphere("power", end, centre, 0.5).unwrap(),
    ));
    let by_pin = system(Arc::new(linear::cga_point_on_moving_sphere("pin", end, centre, 0.5)));
    let (mut x, mut y) = ([initial], [initial]);
    by_power.project(0.0, &mut x).unwrap();
    by_pin.project(0.0, &mut y).unwrap();
    let (mut power_stepper, mut pin_stepper) = (
        Stepper::new(&by_power, Method::Rk4).unwrap(),
        Stepper::new(&by_pin, Method::Rk4).unwrap(),
    );
    let dt = 1e-3;
    let mut worst: f64 = 0.0;
    for k in 0..2000 {
        let t = k as f64 * dt;
        power_stepper.step(t, &mut x, dt).unwrap();
        pin_stepper.step(t, &mut y, dt).unwrap();
        let ([x], [y]) = (&x, &y);
        let c = centre(t + dt).value;
        worst = worst.max(((x.world_point(end) - c).norm() - 0.5).abs());
        worst = worst.max(((y.world_point(end) - c).norm() - 0.5).abs());
    }
    // Measured: both hold the moving sphere to 2e-14 m and agree to 3.4e-10 m after 2 s.
    assert!(worst < 1e-13, "{worst:e}");
    let (x, y) = (x[0].pose().0, y[0].pose().0);
    assert!((x - y).norm() < 3e-9, "{x:?} vs {y:?}");
}

/// Joints whose positions contradict each other (one body point held at two world points 3 m apart) cannot be
/// met by projection: projecting the initial state ends in an error naming the joint left broken, and a run in
/// an error naming the joints, never a run with a joint 3 m off.
#[test]
fn joints_that_cannot_hold_together_are_an_error() {
    let s = state::<Pga>();
    let tip = Vector3::new(0.1, -0.3, 0.25);
    let pivot = s.world_point(tip);
    let system = Mechanism::<Pga>::single(body())
        .with_force(Force::gravity())
        .unwrap()
        .with_constraint(pinning::point::<Pga>("here", tip, pivot))
        .unwrap()
        .with_constraint(pinning::point::<Pga>("there", tip, pivot + Vector3::new(0.0, 0.0, 3.0)))
        .unwrap()
        .with_stabilisation(Stabilisation::PROJECTION)
        .unwrap();
    let mut states = [s];
    match system.project(0.0, &mut states) {
        Err(ConstraintError::Unreachable { names, residual }) => {
            assert!(names.contains("here") || names.contains("there"), "{names}");
            assert!(residual > 1.0, "{residual}");
        }
        other => panic!("expected an unreachable-joints error, got {other:?}"),
    }
    let schedule = dynamics::Schedule::new(1e-3, 0.1).unwrap();
    // Unprojected, the first evaluation already finds the acceleration conditions contradictory.
    let error = dynamics::simulate(&system, &[s], Method::Rk4, &schedule).unwrap_err();
    assert!(error.to_string().contains("there"), "{error}");
}

/// Lines pinned together must have equal weights: directions of different lengths (the pivot once drifted
/// 0.25–0.30 m from where it was put), zero or non-finite ones are refused with the reason.
#[test]
fn pinned_lines_of_different_weights_are_refused() {
    let (p, z) = (Vector3::new(0.1, 0.2, 0.3), Vector3::z());
    for (body, world, reason) in [
        (z, 2.0 * z, "equal weights"),
        (z, Vector3::zeros(), "zero"),
        (z * f64::NAN, z, "finite"),
        (Vector3::repeat(1e308), Vector3::repeat(1e308), "finite"),
    ] {
        let error = pinning::line::<Pga>("slide", (p, body), (p, world)).unwrap_err();
        assert!(error.to_string().contains(reason), "{error}");
        assert!(error.to_string().contains("slide"), "{error}");
    }
    // Equal lengths need not be unit, and unit directions up to round-off pass.
    assert!(pinning::line::<Cga>("slide", (p, 3.0 * z), (p, Vector3::new(0.0, 3.0, 0.0))).is_ok());
    let tilted = Vector3::new(1.0, 2.0, 3.0).normalize();
    assert!(pinning::line::<Pga>("slide", (p, tilted), (p, z)).is_ok());
}

/// A pinned plane needs a plane on each side: a zero normal (once accepted, holding a falling puck at z = 0), a
/// non-finite normal or offset are refused, naming the constraint; a normal of any other length (1e-3, 1e200,
/// whose square overflows) is the same plane.
#[test]
fn pinned_planes_need_planes() {
    let z = Vector3::z();
    for (body, world, reason) in [
        ((Vector3::zeros(), 0.0), (z, 0.0), "body plane"),
        ((z, 0.0), (Vector3::zeros(), 0.0), "world plane"),
        ((z * f64::NAN, 0.0), (z, 0.0), "finite nonzero normal"),
        ((z, f64::INFINITY), (z, 0.0), "finite offset"),
        ((z, 0.0), (Vector3::repeat(f64::INFINITY), 0.0), "world plane"),
    ] {
        let error = pinning::plane::<Pga>("floor", body, world).unwrap_err().to_string();
        assert!(error.contains(reason) && error.contains("floor"), "{error}");
    }
    // z = 0.02 written with a normal of length 1e-3 and one of 1e200 is the plane of the unit normal.
    let puck = Body::cylinder(0.2, 0.04, 0.04).unwrap();
    let on = State::<Pga>::from_world_twist(
        &puck,
        Vector3::new(3.0, -1.0, 0.04),
        &UnitQuaternion::from_scaled_axis(z * 0.7),
        z,
        Vector3::x(),
    );
    for scale in [1e-3, 1.0, 1e200] {
        let face = pinning::plane::<Pga>("floor", (z * scale, -0.02 * scale), (z, 0.02)).unwrap();
        let system = Mechanism::single(puck).with_constraint(face).unwrap();
        let violation = system.violation(0.0, &[on]).unwrap();
        assert!(
            violation.position < 1e-15 && violation.velocity < 1e-13,
            "{scale}: {violation:?}"
        ); // round-off
    }
}

/// At the centre of its sphere a point's constraint row vanishes (the gradient `a − c` is zero), so no reaction
/// can be found there, but the residual `½(ρ² − |a − c|²)` is defined: `violation` reports it (it used to fail
/// with the rank deficiency the reaction solve meets), while the equations of motion still refuse the state,
/// naming the joint.
#[test]
fn a_violation_is_reported_where_the_rows_lose_rank() {
    let bob = Body::sphere(1.0, 0.05).unwrap();
    let centre = Vector3::z() * 2.0;
    let on_sphere = VirtualPower::<Pga>::point_on_sphere("string", Vector3::zeros(), centre, 1.5).unwrap();
    let system = Mechanism::single(bob).with_constraint(on_sphere).unwrap();
    let at_centre = State::new(
        &bob,
        centre,
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::x(),
    );
    let violation = system.violation(0.0, &[at_centre]).unwrap();
    assert!((violation.position - 0.5 * 1.5 * 1.5).abs() < 1e-15, "{violation:?}");
    assert_eq!(violation.velocity, 0.0);
    match system.rates_at(0.0, &[at_centre]) {
        Err(ConstraintError::RankDeficient { names, .. }) => assert_eq!(names, "string"),
        other => panic!("expected a rank deficiency, got {other:?}"),
    }
}

/// A mechanism holds its joints to round-off without asking: projection is the default stabilisation (a 3-link arm
/// left unstabilised drifted 2.2e-5 m in 2 s).
#[test]
fn a_mechanism_holds_its_joints_by_default() {
    let rod = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 0.5)).unwrap();
    let (top, bottom) = (Vector3::new(0.0, 0.0, 0.25), Vector3::new(0.0, 0.0, -0.25));
    let mut arm = Mechanism::<Pga>::new();
    let links: Vec<_> = (0..3)
        .map(|i| arm.add_body(format!("link {i}"), rod).unwrap())
        .collect();
    let axes = [Vector3::x(), Vector3::y(), Vector3::new(1.0, 1.0, 0.0)];
    for (i, &link) in links.iter().enumerate() {
        arm.add_force(link, Force::gravity()).unwrap();
        let (reference, at) = if i == 0 {
            (Reference::World, Vector3::zeros())
        } else {
            (links[i - 1].into(), bottom)
        };
        let hinge = VirtualPower::hinge(format!("hinge {i}"), (top, axes[i]), (at, axes[i])).unwrap();
        arm.add_joint(link, reference, Arc::new(hinge)).unwrap();
    }
    let tilt = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.2);
    let mut start: Vec<State<Pga>> = (0..3)
        .map(|k| {
            let centre = tilt * Vector3::new(0.0, 0.0, -0.25 - 0.5 * k as f64);
            State::new(
                &rod,
                centre,
                &tilt,
                Vector3::new(0.0, 2.0 * k as f64, 0.0),
                Vector3::zeros(),
            )
        })
        .collect();
    arm.project(0.0, &mut start).unwrap();
    let run = dynamics::simulate(&arm, &start, Method::Rk4, &dynamics::Schedule::new(1e-3, 2.0).unwrap()).unwrap();
    let end: Vec<State<Pga>> = (0..3)
        .map(|i| {
            let s = run.body(i).last().unwrap();
            State::from_world_twist(&rod, s.position, &s.orientation, s.angular_velocity, s.velocity)
        })
        .collect();
    let violation = arm.violation(2.0, &end).unwrap();
    assert!(violation.position < 1e-12, "{violation:?}");
}
