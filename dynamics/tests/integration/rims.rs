//! Disks' rims on planes (docs/contacts.md "Rims"): a cylinder is the rims of its two caps, whose touching points run
//! along the rims as it turns. Against closed forms: a solid cylinder rolls down an incline at `(2/3) g sin α`; struck
//! without spin on a level floor it slides, then rolls from `v₀/(3μg)` on at `2v₀/3`; balanced on one rim on a
//! frictionless floor it falls over with its centre of mass on a vertical line, its energy kept, landing on its side
//! when the time the energy equation gives is up. A disk that comes to lie flat stops the run with an error.

use dynamics::contacts::{Friction, PlaneContact};
use dynamics::limits::LimitChange;
use dynamics::{simulate, Algebra, Body, Force, Mechanism, Method, State};
use nalgebra::{UnitQuaternion, Vector3};

use super::friction::{adaptive, assert_rolls_down, friction_changes, incline, runs};

const G: f64 = 9.81;
/// The cylinder's mass (kg), radius and length (m), its axis along the body's z.
const MASS: f64 = 2.0;
const RADIUS: f64 = 0.1;
const LENGTH: f64 = 0.3;

fn cylinder() -> Body {
    Body::cylinder(MASS, RADIUS, LENGTH).unwrap()
}

/// A cylinder under gravity whose two cap rims stay above the plane through the origin with unit normal `normal`.
fn cylinder_on<A: Algebra>(normal: Vector3<f64>, friction: Friction) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("can", cylinder()).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    for (k, sign) in [(1, -1.0), (2, 1.0)] {
        let rim = PlaneContact::disk(Vector3::z() * sign * LENGTH / 2.0, Vector3::z(), RADIUS, normal, 0.0)
            .unwrap()
            .with_friction(friction);
        system.add_contact(format!("cap {k}"), id, rim).unwrap();
    }
    system
}

/// The cylinder lying with its axis along world x, its centre at `centre`, moving at `velocity`.
fn lying<A: Algebra>(centre: Vector3<f64>, velocity: Vector3<f64>) -> [State<A>; 1] {
    let along_x = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
    [State::from_world_twist(
        &cylinder(),
        centre,
        &along_x,
        Vector3::zeros(),
        velocity,
    )]
}

/// Released at rest on its side on an incline of 0.3 rad with enough friction to roll (`tan α < 3μ`), the cylinder
/// sticks along its touching line and rolls down at `(2/3) g sin α`, the line at rest.
fn a_cylinder_rolls_down_an_incline<A: Algebra>() {
    let (normal, _) = incline();
    let system = cylinder_on::<A>(normal, Friction::coulomb(0.5).unwrap());
    let centre = normal * RADIUS;
    for run in runs(&system, &lying(centre, Vector3::zeros()), 1.0) {
        assert_rolls_down(&run, centre, RADIUS, 2.0 / 3.0);
        let drift = run.body(0).iter().fold(0.0f64, |m, s| m.max(s.position.x.abs()));
        assert!(drift < 1e-12, "drifts {drift:e} m along its axis");
    }
}

/// Struck across its axis without spin on a level floor, μ = 0.3: friction `μ m g` slows it and spins it up
/// (`I = m r²/2`) until its touching line stops, at `t = v₀/(3μg)`; from there it rolls at `2v₀/3`.
fn a_struck_cylinder_slides_then_rolls<A: Algebra>() {
    let (v0, mu) = (2.0, 0.3);
    let system = cylinder_on::<A>(Vector3::z(), Friction::coulomb(mu).unwrap());
    let start = lying::<A>(Vector3::z() * RADIUS, Vector3::y() * v0);
    let stop = v0 / (3.0 * mu * G);
    for run in runs(&system, &start, 0.6) {
        let changes = friction_changes(&run);
        // Both rims stop slipping at the same instant.
        assert!(!changes.is_empty() && changes.len() <= 2, "{:?}", run.transitions);
        for (t, change) in &changes {
            assert!(matches!(change, LimitChange::Stuck { .. }));
            assert!((t - stop).abs() < 1e-12, "stopped slipping at {t} s, {stop} s exact");
        }
        for sample in run.body(0) {
            let (speed, spin) = if sample.t < stop {
                (v0 - mu * G * sample.t, 2.0 * mu * G * sample.t / RADIUS)
            } else {
                (2.0 * v0 / 3.0, 2.0 * v0 / (3.0 * RADIUS))
            };
            let expected = Vector3::y() * speed;
            assert!(
                (sample.velocity - expected).norm() < 1e-11,
                "t = {}: {}",
                sample.t,
                sample.velocity
            );
            let turning = -Vector3::x() * spin;
            assert!((sample.angular_velocity - turning).norm() < 1e-10, "t = {}", sample.t);
            assert!((sample.position.z - RADIUS).abs() < 1e-12);
        }
    }
}

/// The time the cylinder of [`a_cylinder_balanced_on_its_rim_falls_over`] takes to fall from tilt θ₀ to its side
/// (θ = π/2), from the energy equation of its one degree of freedom: the centre at height `z(θ) = (L/2) cos θ + r
/// sin θ` on a vertical line, `(m z'(θ)² + I) θ̇² = 2 m g (z(θ₀) − z(θ))`. With θ = θ₀ + s² the integrand of `t = ∫
/// dθ / θ̇` is smooth; Gauss–Legendre (three points) on 4000 panels, which agrees with mpmath's quadrature at 40
/// digits (0.26035292644155245 s) to 1e-16.
fn fall_time(tilt: f64) -> f64 {
    let transverse = MASS * (3.0 * RADIUS * RADIUS + LENGTH * LENGTH) / 12.0;
    let slope = |theta: f64| -LENGTH / 2.0 * theta.sin() + RADIUS * theta.cos();
    let integrand = |s: f64| {
        let (rise, theta) = (s * s, tilt + s * s);
        // z(θ₀) − z(θ₀ + δ) by the sum-to-product forms: the difference itself would lose the digits near the start.
        let middle = tilt + rise / 2.0;
        let drop = 2.0 * (rise / 2.0).sin() * (LENGTH / 2.0 * middle.sin() - RADIUS * middle.cos());
        let rate = (2.0 * MASS * G * drop / (MASS * slope(theta).powi(2) + transverse)).sqrt();
        2.0 * s / rate
    };
    let end = (std::f64::consts::FRAC_PI_2 - tilt).sqrt();
    let panels = 4000;
    let width = end / panels as f64;
    let (node, weight) = ((0.6f64).sqrt() / 2.0, [5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0]);
    (0..panels)
        .map(|k| {
            let middle = (k as f64 + 0.5) * width;
            let points = [middle - node * width, middle, middle + node * width];
            width * (0..3).map(|j| weight[j] * integrand(points[j])).sum::<f64>()
        })
        .sum()
}

/// On a frictionless floor, balanced at rest on its lower rim at 0.7 rad from upright (beyond the balance at
/// `tan θ = 2r/L`): nothing pushes it sideways, so its centre falls on a vertical line; the rim slides on the floor
/// as the touching point runs round it, the energy stays, and the upper rim meets the floor with the axis level at
/// the time the energy equation gives ([`fall_time`]); it then lies still on its side.
fn a_cylinder_balanced_on_its_rim_falls_over<A: Algebra>() {
    let tilt = 0.7f64;
    let system = cylinder_on::<A>(Vector3::z(), Friction::NONE);
    let turn = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt);
    let centre = Vector3::z() * (LENGTH / 2.0 * tilt.cos() + RADIUS * tilt.sin());
    let start = [State::<A>::from_world_twist(
        &cylinder(),
        centre,
        &turn,
        Vector3::zeros(),
        Vector3::zeros(),
    )];
    let land = fall_time(tilt);
    for run in runs(&system, &start, 1.0) {
        let impacts: Vec<_> = (run.transitions.iter())
            .filter(|t| matches!(t.change, LimitChange::Held { speed_before, .. } if speed_before > 0.0))
            .collect();
        assert_eq!(impacts.len(), 1, "{:?}", run.transitions);
        assert_eq!(impacts[0].constraint, "cap 2");
        assert!(
            (impacts[0].t - land).abs() < 1e-12,
            "landed at {} s, {land} s by the energy",
            impacts[0].t
        );
        let released = run
            .transitions
            .iter()
            .any(|t| matches!(t.change, LimitChange::Released { .. }));
        assert!(!released, "{:?}", run.transitions);
        let energy = run.energies().next().unwrap();
        for (sample, e) in run.body(0).iter().zip(run.energies()) {
            assert!(
                sample.position.xy().norm() < 1e-12,
                "t = {}: {}",
                sample.t,
                sample.position
            );
            if sample.t < land {
                assert!(
                    (e - energy).abs() < 1e-11,
                    "t = {}: energy {e} J, {energy} J at the start",
                    sample.t
                );
            } else {
                assert!((sample.position.z - RADIUS).abs() < 1e-12, "t = {}", sample.t);
                assert!(sample.velocity.norm() < 1e-11 && sample.angular_velocity.norm() < 1e-10);
            }
        }
    }
}

/// Dropped upright, the cylinder meets the floor with its whole lower rim, which one touching point cannot hold: the
/// run stops there with an error naming the rim; so does a start standing on it.
fn a_disk_lying_flat_is_an_error_naming_it<A: Algebra>() {
    let system = cylinder_on::<A>(Vector3::z(), Friction::coulomb(0.5).unwrap());
    for (height, at) in [(0.1, "t = 0.14"), (0.0, "t = 0")] {
        let centre = Vector3::z() * (LENGTH / 2.0 + height);
        let start = [State::<A>::from_world_twist(
            &cylinder(),
            centre,
            &UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::zeros(),
        )];
        let error = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-10, 0.5))
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("cap 1") && error.contains("lies flat") && error.contains(at),
            "{error}"
        );
    }
}

for_both_algebras!(
    a_cylinder_rolls_down_an_incline,
    a_struck_cylinder_slides_then_rolls,
    a_cylinder_balanced_on_its_rim_falls_over,
    a_disk_lying_flat_is_an_error_naming_it,
);
