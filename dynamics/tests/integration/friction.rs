//! Coulomb friction at contacts (docs/contacts.md "Friction"), against the closed forms of classical mechanics: a
//! ball struck without spin slides, then rolls from `2v₀/(7μg)` on at `5v₀/7`; a ball rolls down an incline at
//! `(5/7) g sin α`; a block on an incline sticks below its friction angle and slides above it at `g(sin α − μ cos α)`;
//! a block thrown up an incline stops at `v₀/(g(sin α + μ cos α))` and stays or slides back; a box pushed with a force
//! below `μ_s m g` stays, above it slides at `(F − μ m g)/m`; friction never adds energy; impacts with friction: a
//! ball thrown at the floor leaves rolling or sliding as Coulomb's law on its impulse says, a cube landing flat on
//! four corners slides on unturned.

use dynamics::contacts::{Friction, PlaneContact};
use dynamics::limits::LimitChange;
use dynamics::{
    simulate, Algebra, Body, Force, JointMethod, Mechanism, Method, Schedule, Simulation, State, Tolerance,
};
use nalgebra::{UnitQuaternion, Vector3};

const G: f64 = 9.81;
/// The ball's radius (m) and mass (kg).
const RADIUS: f64 = 0.1;
const MASS: f64 = 2.0;
/// The block's half side (m): a 0.2 m cube of 1 kg.
const HALF: f64 = 0.1;

pub(crate) fn adaptive(tolerance: f64, duration: f64) -> Schedule {
    Schedule::adaptive(Tolerance::new(tolerance, tolerance).unwrap(), duration, 0.01).unwrap()
}

fn ball() -> Body {
    Body::sphere(MASS, RADIUS).unwrap()
}

/// A ball under gravity on the plane through the origin with unit normal `normal`, friction `friction`.
fn ball_on<A: Algebra>(normal: Vector3<f64>, friction: Friction) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("ball", ball()).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    let contact = PlaneContact::sphere(Vector3::zeros(), RADIUS, normal, 0.0)
        .unwrap()
        .with_friction(friction);
    system.add_contact("ball", id, contact).unwrap();
    system
}

/// The runs every test makes: body-momentum stepping adaptive (DOP853-body at a tight tolerance) and fixed
/// (RKMK8-body), and joint-coordinate stepping adaptive (DOP853-joint) and fixed (RKMK8-joint).
pub(crate) fn runs<A: Algebra>(system: &Mechanism<A>, start: &[State<A>], duration: f64) -> Vec<Simulation<A>> {
    vec![
        simulate(system, start, Method::Dop853Body, &adaptive(1e-12, duration)).unwrap(),
        simulate(
            system,
            start,
            Method::Rkmk8Body,
            &Schedule::new(2e-3, duration).unwrap(),
        )
        .unwrap(),
        simulate(
            system,
            start,
            JointMethod::Rkmk8,
            &Schedule::new(2e-3, duration).unwrap(),
        )
        .unwrap(),
        simulate(system, start, JointMethod::Dop853, &adaptive(1e-12, duration)).unwrap(),
    ]
}

/// The friction transitions of a run, in order, with their times.
pub(crate) fn friction_changes<A: Algebra>(run: &Simulation<A>) -> Vec<(f64, LimitChange)> {
    (run.transitions.iter())
        .filter(|t| matches!(t.change, LimitChange::Stuck { .. } | LimitChange::Slipped { .. }))
        .map(|t| (t.t, t.change))
        .collect()
}

/// Struck without spin along x, the ball slides: friction `μ m g` slows it and spins it up until its contact point
/// stops, at `t = 2v₀/(7μg)`; from there it rolls at `5v₀/7` without friction. The energy friction takes is the
/// run's recorded work at every sample (1e-9 J; joint-coordinate steps once left the sliding friction's power out).
fn a_struck_ball_slides_then_rolls<A: Algebra>() {
    let (v0, mu) = (2.0, 0.3);
    let system = ball_on::<A>(Vector3::z(), Friction::coulomb(mu).unwrap());
    let start = [State::<A>::from_world_twist(
        &ball(),
        Vector3::new(0.0, 0.0, RADIUS),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::x() * v0,
    )];
    let stop = 2.0 * v0 / (7.0 * mu * G);
    for run in runs(&system, &start, 1.0) {
        let changes = friction_changes(&run);
        assert_eq!(changes.len(), 1, "{:?}", run.transitions);
        assert!(matches!(changes[0].1, LimitChange::Stuck { .. }));
        assert!(
            (changes[0].0 - stop).abs() < 1e-12,
            "stopped slipping at {} s, {stop} s exact",
            changes[0].0
        );
        for sample in run.body(0) {
            let (speed, spin) = if sample.t < stop {
                (v0 - mu * G * sample.t, 2.5 * mu * G * sample.t / RADIUS)
            } else {
                (5.0 * v0 / 7.0, 5.0 * v0 / (7.0 * RADIUS))
            };
            assert!(
                (sample.velocity - Vector3::x() * speed).norm() < 1e-11,
                "t = {}: {}",
                sample.t,
                sample.velocity
            );
            assert!(
                (sample.angular_velocity - Vector3::y() * spin).norm() < 1e-10,
                "t = {}",
                sample.t
            );
            assert!((sample.position.z - RADIUS).abs() < 1e-12);
            let balance = sample.energy - run.body(0)[0].energy - sample.work;
            assert!(balance.abs() < 1e-9, "t = {}: E − E₀ − W = {balance:e} J", sample.t);
        }
    }
}

/// Far from the origin (a floor 1e4 m away in x and z): the struck ball's slip still stops at `2v₀/(7μg)`, within
/// 1e-10 s, and it rolls on at `5v₀/7` (1e-10 m/s): the round-off of coordinates 1e4 large, not of the method.
fn a_struck_ball_far_from_the_origin_slides_then_rolls<A: Algebra>() {
    let (v0, mu, far) = (2.0, 0.3, 1e4);
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("ball", ball()).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    let contact = PlaneContact::sphere(Vector3::zeros(), RADIUS, Vector3::z(), far)
        .unwrap()
        .with_friction(Friction::coulomb(mu).unwrap());
    system.add_contact("ball", id, contact).unwrap();
    let start = [State::<A>::from_world_twist(
        &ball(),
        Vector3::new(far, 0.0, far + RADIUS),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::x() * v0,
    )];
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-12, 0.5)).unwrap();
    let changes = friction_changes(&run);
    assert_eq!(changes.len(), 1, "{:?}", run.transitions);
    let stop = 2.0 * v0 / (7.0 * mu * G);
    assert!(
        (changes[0].0 - stop).abs() < 1e-10,
        "stopped slipping at {} s, {stop} s exact",
        changes[0].0
    );
    let end = run.body(0).last().unwrap();
    assert!((end.velocity.x - 5.0 * v0 / 7.0).abs() < 1e-10, "{}", end.velocity.x);
}

/// The incline's angle (rad), about x.
const SLOPE: f64 = 0.3;

/// The incline of [`a_ball_rolls_down_an_incline`] (and of a cylinder's): its unit normal and the direction down it.
pub(crate) fn incline() -> (Vector3<f64>, Vector3<f64>) {
    (
        Vector3::new(0.0, SLOPE.sin(), SLOPE.cos()),
        Vector3::new(0.0, SLOPE.cos(), -SLOPE.sin()),
    )
}

/// Asserts that `run`, of a body of touching radius `radius` started at rest at `centre` on the [`incline`], rolls
/// down it at `factor · g sin α` (1e-11 m), its centre `radius` above it (1e-12 m), its touching point at rest (1e-11
/// m/s), without a friction transition.
pub(crate) fn assert_rolls_down<A: Algebra>(run: &Simulation<A>, centre: Vector3<f64>, radius: f64, factor: f64) {
    let (normal, down) = incline();
    assert!(friction_changes(run).is_empty(), "{:?}", run.transitions);
    for sample in run.body(0) {
        let exact = 0.5 * factor * G * SLOPE.sin() * sample.t * sample.t;
        let travelled = (sample.position - centre).dot(&down);
        assert!(
            (travelled - exact).abs() < 1e-11,
            "t = {}: {travelled} m, {exact} m",
            sample.t
        );
        assert!((normal.dot(&sample.position) - radius).abs() < 1e-12);
        let contact = sample.velocity + sample.angular_velocity.cross(&(-normal * radius));
        assert!(contact.norm() < 1e-11, "t = {}: slip {}", sample.t, contact.norm());
    }
}

/// Released at rest on an incline of 0.3 rad with enough friction to roll (`tan α < 7μ/2`), the ball sticks at its
/// contact point and rolls down at `(5/7) g sin α`.
fn a_ball_rolls_down_an_incline<A: Algebra>() {
    let (normal, _) = incline();
    let system = ball_on::<A>(normal, Friction::coulomb(0.5).unwrap());
    let centre = normal * RADIUS;
    let start = [State::<A>::from_world_twist(
        &ball(),
        centre,
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
    )];
    for run in runs(&system, &start, 1.0) {
        assert_rolls_down(&run, centre, RADIUS, 5.0 / 7.0);
    }
}

/// A 1 kg cube under gravity held on four bottom corners on the plane through the origin with unit normal `normal`,
/// friction `friction`, pushed by a constant world force `push` along the line through its starting centre (which
/// it moves along).
fn block_on<A: Algebra>(normal: Vector3<f64>, friction: Friction, push: Vector3<f64>) -> Mechanism<A> {
    let block = Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap();
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("block", block).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    if push != Vector3::zeros() {
        let point = normal * HALF;
        system.add_force(id, Force::Line { force: push, point }).unwrap();
    }
    for (k, (x, y)) in [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)]
        .into_iter()
        .enumerate()
    {
        let corner = PlaneContact::new(Vector3::new(x, y, -HALF), normal, 0.0)
            .unwrap()
            .with_friction(friction);
        system.add_contact(format!("corner {k}"), id, corner).unwrap();
    }
    system
}

/// The cube resting on the incline of slope `slope` (about x), moving up it at `speed`.
fn block_start<A: Algebra>(slope: f64, speed: f64) -> [State<A>; 1] {
    let normal = Vector3::new(0.0, slope.sin(), slope.cos());
    let up = Vector3::new(0.0, -slope.cos(), slope.sin());
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -slope);
    let block = Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap();
    [State::from_world_twist(
        &block,
        normal * HALF,
        &rotation,
        Vector3::zeros(),
        up * speed,
    )]
}

/// Below its friction angle a block at rest stays where it is; above it, it slides at `g(sin α − μ cos α)`.
fn a_block_sticks_or_slides_on_an_incline<A: Algebra>() {
    let slope = 0.3f64; // tan α = 0.309
    let normal = Vector3::new(0.0, slope.sin(), slope.cos());
    let down = Vector3::new(0.0, slope.cos(), -slope.sin());
    let sticking = block_on::<A>(normal, Friction::coulomb(0.35).unwrap(), Vector3::zeros());
    for run in runs(&sticking, &block_start::<A>(slope, 0.0), 1.0) {
        assert!(friction_changes(&run).is_empty(), "{:?}", run.transitions);
        for sample in run.body(0) {
            assert!((sample.position - normal * HALF).norm() < 1e-12, "t = {}", sample.t);
            assert!(sample.velocity.norm() < 1e-12 && sample.angular_velocity.norm() < 1e-12);
        }
    }
    let mu = 0.2;
    let sliding = block_on::<A>(normal, Friction::coulomb(mu).unwrap(), Vector3::zeros());
    for run in runs(&sliding, &block_start::<A>(slope, 0.0), 1.0) {
        for sample in run.body(0) {
            let exact = 0.5 * G * (slope.sin() - mu * slope.cos()) * sample.t * sample.t;
            let travelled = (sample.position - normal * HALF).dot(&down);
            assert!(
                (travelled - exact).abs() < 1e-11,
                "t = {}: {travelled} m, {exact} m",
                sample.t
            );
            assert!(sample.angular_velocity.norm() < 1e-11);
        }
    }
}

/// Thrown up an incline at 2 m/s, a block slows at `g(sin α + μ cos α)` and stops at `v₀/(g(sin α + μ cos α))`,
/// located to round-off; below the friction angle it stays there, above it it slides back at `g(sin α − μ cos α)`.
fn a_block_thrown_up_an_incline_stops<A: Algebra>() {
    let (slope, v0) = (0.3f64, 2.0);
    let normal = Vector3::new(0.0, slope.sin(), slope.cos());
    let up = Vector3::new(0.0, -slope.cos(), slope.sin());
    for (mu, stays) in [(0.4, true), (0.25, false)] {
        let system = block_on::<A>(normal, Friction::coulomb(mu).unwrap(), Vector3::zeros());
        let deceleration = G * (slope.sin() + mu * slope.cos());
        let stop = v0 / deceleration;
        let top = 0.5 * v0 * stop;
        for run in runs(&system, &block_start::<A>(slope, v0), 1.0) {
            let changes = friction_changes(&run);
            assert!(!changes.is_empty(), "{:?}", run.transitions);
            for (time, _) in &changes {
                assert!(
                    (time - stop).abs() < 1e-12,
                    "a transition at {time} s, the stop at {stop} s"
                );
            }
            let slid_back = changes.iter().any(|(_, c)| matches!(c, LimitChange::Slipped { .. }));
            assert_eq!(slid_back, !stays, "{changes:?}");
            for sample in run.body(0) {
                let along = (sample.position - normal * HALF).dot(&up);
                let exact = if sample.t <= stop {
                    v0 * sample.t - 0.5 * deceleration * sample.t * sample.t
                } else if stays {
                    top
                } else {
                    let after = sample.t - stop;
                    top - 0.5 * G * (slope.sin() - mu * slope.cos()) * after * after
                };
                assert!(
                    (along - exact).abs() < 1e-11,
                    "μ = {mu}, t = {}: {along} m, {exact} m",
                    sample.t
                );
            }
        }
    }
}

/// A box on a level floor pushed sideways by a constant force: below `μ_s m g` it stays; above it it slides at
/// `(F − μ m g)/m`, from rest.
fn a_pushed_box_stays_or_slides<A: Algebra>() {
    let friction = Friction::new(0.4, 0.5).unwrap();
    for (push, accelerates) in [(0.45 * G, false), (0.6 * G, true)] {
        let system = block_on::<A>(Vector3::z(), friction, Vector3::x() * push);
        for run in runs(&system, &block_start::<A>(0.0, 0.0), 0.5) {
            for sample in run.body(0) {
                let exact = if accelerates {
                    0.5 * (push - friction.kinetic() * G) * sample.t * sample.t
                } else {
                    0.0
                };
                assert!(
                    (sample.position.x - exact).abs() < 1e-11,
                    "F = {push}, t = {}: {}",
                    sample.t,
                    sample.position.x
                );
                assert!((sample.position.z - HALF).abs() < 1e-12);
            }
        }
    }
}

/// Friction only takes energy: a block sliding, stopping and sticking on a level floor, spun about the vertical as
/// well, never gains energy between samples, and ends at rest.
fn friction_never_adds_energy<A: Algebra>() {
    let system = block_on::<A>(Vector3::z(), Friction::coulomb(0.3).unwrap(), Vector3::zeros());
    let block = Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap();
    let start = [State::<A>::from_world_twist(
        &block,
        Vector3::z() * HALF,
        &UnitQuaternion::identity(),
        Vector3::z() * 4.0,
        Vector3::new(1.5, 0.5, 0.0),
    )];
    for run in runs(&system, &start, 2.0) {
        let energies: Vec<f64> = run.energies().collect();
        for pair in energies.windows(2) {
            assert!(
                pair[1] <= pair[0] + 1e-12,
                "energy rose from {} J to {} J",
                pair[0],
                pair[1]
            );
        }
        let end = run.body(0).last().unwrap();
        assert!(
            end.velocity.norm() < 1e-12 && end.angular_velocity.norm() < 1e-12,
            "{end:?}"
        );
    }
}

/// A ball (no gravity) thrown at the floor at `(v_x, 0, −v_z)` without spin, restitution e: the normal impulse is
/// `m(1+e)v_z`; the friction impulse that would leave it rolling is `(2/7) m v_x`. Inside the cone (`2v_x/7 ≤
/// μ(1+e)v_z`) it leaves rolling at `5v_x/7`, spin `5v_x/(7R)`; outside it slides through the impact, leaving at
/// `v_x − μ(1+e)v_z` with spin `(5/2)μ(1+e)v_z/R`. It never leaves with more energy than it came with.
fn a_ball_thrown_at_the_floor_leaves_rolling_or_sliding<A: Algebra>() {
    let (vx, vz, e) = (1.0, 2.0, 0.5);
    for mu in [0.5, 0.05] {
        let mut system = Mechanism::<A>::new();
        let id = system.add_body("ball", ball()).unwrap();
        let contact = PlaneContact::sphere(Vector3::zeros(), RADIUS, Vector3::z(), 0.0)
            .unwrap()
            .with_restitution(e)
            .unwrap()
            .with_friction(Friction::coulomb(mu).unwrap());
        system.add_contact("ball", id, contact).unwrap();
        let start = [State::<A>::from_world_twist(
            &ball(),
            Vector3::new(0.0, 0.0, RADIUS + 0.1),
            &UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::new(vx, 0.0, -vz),
        )];
        let impulse = mu * (1.0 + e) * vz;
        let (speed, spin) = if 2.0 * vx / 7.0 <= impulse {
            (5.0 * vx / 7.0, 5.0 * vx / (7.0 * RADIUS))
        } else {
            (vx - impulse, 2.5 * impulse / RADIUS)
        };
        for run in runs(&system, &start, 0.2) {
            assert_eq!(run.transitions.len(), 1, "μ = {mu}: {:?}", run.transitions);
            assert!((run.transitions[0].t - 0.05).abs() < 1e-12);
            let end = run.body(0).last().unwrap();
            let exact = Vector3::new(speed, 0.0, e * vz);
            assert!(
                (end.velocity - exact).norm() < 1e-12,
                "μ = {mu}: {} after, {exact} exact",
                end.velocity
            );
            assert!((end.angular_velocity - Vector3::y() * spin).norm() < 1e-10, "μ = {mu}");
            let energies: Vec<f64> = run.energies().collect();
            assert!(energies.last().unwrap() < &energies[0]);
        }
    }
}

/// A cube (no gravity) landing flat on its four corners at `(v_x, 0, −v_z)`, restitution 0, friction μ: the corners
/// meet the floor together, take `m v_z` between them and slide through the impact, the push split so that the
/// friction at the bottom face does not pitch the cube: it leaves at `v_x − μ v_z` along the floor, unturned.
fn a_cube_landing_flat_slides_on<A: Algebra>() {
    let (vx, vz, mu) = (2.0, 1.0, 0.3);
    let block = Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap();
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("block", block).unwrap();
    for (k, (x, y)) in [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)]
        .into_iter()
        .enumerate()
    {
        let corner = PlaneContact::new(Vector3::new(x, y, -HALF), Vector3::z(), 0.0)
            .unwrap()
            .with_friction(Friction::coulomb(mu).unwrap());
        system.add_contact(format!("corner {k}"), id, corner).unwrap();
    }
    let start = [State::<A>::from_world_twist(
        &block,
        Vector3::new(0.0, 0.0, HALF + 0.05),
        &UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::new(vx, 0.0, -vz),
    )];
    for run in runs(&system, &start, 0.1) {
        let impacts = run
            .transitions
            .iter()
            .filter(|t| matches!(t.change, LimitChange::Held { .. }))
            .count();
        assert_eq!(impacts, 4, "{:?}", run.transitions);
        let end = run.body(0).last().unwrap();
        // After the impact the cube slides on the frictional floor: v_x − μ v_z at the impact, then μ g = 0 (no
        // gravity, no push): it keeps that speed.
        assert!(
            (end.velocity - Vector3::x() * (vx - mu * vz)).norm() < 1e-12,
            "{}",
            end.velocity
        );
        assert!(end.angular_velocity.norm() < 1e-12, "{}", end.angular_velocity);
        assert!((end.position.z - HALF).abs() < 1e-12);
    }
}

/// Painlevé's rod: a uniform 1 m rod at 30° to a floor with friction μ = 3, its lower end on the floor, sliding.
/// With the lower end leading, a push λ changes the end's normal acceleration by `λ (1 + 3cos²θ − 3μ sinθ cosθ)/m`,
/// negative here (μ > 2.5): holding it would take a pull, and released it falls into the floor. No state is
/// consistent: the run ends in an error naming the contact and the paradox. Trailing, the same rod slides.
fn painleves_rod_is_an_error_naming_the_contact<A: Algebra>() {
    let rod = Body::cuboid(1.0, Vector3::new(0.01, 0.01, 1.0)).unwrap();
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("rod", rod).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    let end = PlaneContact::new(Vector3::new(0.0, 0.0, -0.5), Vector3::z(), 0.0)
        .unwrap()
        .with_friction(Friction::coulomb(3.0).unwrap());
    system.add_contact("lower end", id, end).unwrap();
    // Body z tilted 60° from the vertical about y: the lower end at the centre − (0.433, 0, 0.25).
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 60f64.to_radians());
    let start = |vx: f64| {
        [State::<A>::from_world_twist(
            &rod,
            Vector3::z() * 0.25,
            &rotation,
            Vector3::zeros(),
            Vector3::x() * vx,
        )]
    };
    let leading = simulate(&system, &start(-1.0), Method::Dop853Body, &adaptive(1e-10, 0.1));
    let Err(error) = leading else {
        panic!("Painlevé's rod ran: no state is consistent");
    };
    let message = format!("{error:?}");
    for part in ["lower end", "Painlevé"] {
        assert!(message.contains(part), "{message}");
    }
    let trailing = simulate(&system, &start(1.0), Method::Dop853Body, &adaptive(1e-10, 0.1)).unwrap();
    assert!(trailing.body(0).iter().all(|s| s.position.z > 0.2));
}

/// A tumbling cube with its eight corners on a floor with friction 0.5 and restitution 0.5: corners meet the floor
/// alone and together, stick and slide through impacts (some of which the active sets do not settle, and the
/// Gauss–Seidel iteration on Coulomb's law resolves). No impact adds energy, no corner goes below the floor, and the
/// cube comes to rest on a face, its centre 0.1 m up.
fn a_tumbling_cube_with_friction_comes_to_rest<A: Algebra>() {
    let block = Body::cuboid(1.0, Vector3::repeat(2.0 * HALF)).unwrap();
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("block", block).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    for c in 0..8 {
        let sign = |bit: usize| if c & (1 << bit) == 0 { -HALF } else { HALF };
        let corner = PlaneContact::new(Vector3::new(sign(0), sign(1), sign(2)), Vector3::z(), 0.0)
            .unwrap()
            .with_restitution(0.5)
            .unwrap()
            .with_friction(Friction::coulomb(0.5).unwrap());
        system.add_contact(format!("corner {}", c + 1), id, corner).unwrap();
    }
    let start = [State::<A>::from_world_twist(
        &block,
        Vector3::new(0.0, 0.0, 0.3),
        &UnitQuaternion::identity(),
        Vector3::new(0.0, 2.0, 1.0),
        Vector3::new(1.0, 0.0, 0.0),
    )];
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-10, 3.0)).unwrap();
    assert!(run.transitions.len() > 10, "{:?}", run.transitions);
    for transition in &run.transitions {
        assert!(transition.energy_change <= 1e-12, "{transition:?}");
    }
    for sample in run.body(0) {
        let heights = system.contact_heights(&[State::<A>::from_world_twist(
            &block,
            sample.position,
            &sample.orientation,
            Vector3::zeros(),
            Vector3::zeros(),
        )]);
        assert!(heights.unwrap().iter().all(|&h| h > -1e-12), "t = {}", sample.t);
    }
    let end = run.body(0).last().unwrap();
    assert!((end.position.z - HALF).abs() < 1e-12, "{} m", end.position.z);
    assert!(
        end.velocity.norm() < 1e-12 && end.angular_velocity.norm() < 1e-12,
        "{end:?}"
    );
}

for_both_algebras!(
    a_tumbling_cube_with_friction_comes_to_rest,
    painleves_rod_is_an_error_naming_the_contact,
    a_ball_thrown_at_the_floor_leaves_rolling_or_sliding,
    a_cube_landing_flat_slides_on,
    a_struck_ball_slides_then_rolls,
    a_struck_ball_far_from_the_origin_slides_then_rolls,
    a_ball_rolls_down_an_incline,
    a_block_sticks_or_slides_on_an_incline,
    a_block_thrown_up_an_incline_stops,
    a_pushed_box_stays_or_slides,
    friction_never_adds_energy,
);
