//! Contacts between bodies (docs/contacts.md "Between bodies"), against closed forms: two equal balls meeting off
//! centre, elastic and frictionless, leave at right angles, the struck one along the line of centres; Newton's
//! cradle passes the speed down a row of balls with gaps between them, and moves a touching row as the simultaneous
//! impact law predicts; a box thrown across a box on a frictionless floor drags it until both move at the common
//! speed `m₁v₀/(m₁ + m₂)`, from `t = v₀/(μg(1 + m₁/m₂))`; a stack of boxes rests 10 s without creep.

use dynamics::contacts::{BallContact, Friction, PlaneContact};
use dynamics::limits::LimitChange;
use dynamics::{simulate, Algebra, Body, Force, JointMethod, Mechanism, Method, Schedule, Simulation, State};
use nalgebra::{UnitQuaternion, Vector3};

// The runs every test makes, as the friction tests make them: body-momentum stepping adaptive (DOP853-body) and
// fixed (RKMK8-body), and joint-coordinate stepping (RKMK8-joint).
use super::friction::{adaptive, runs};

const G: f64 = 9.81;
/// The balls' radius (m) and mass (kg).
const RADIUS: f64 = 0.1;
const MASS: f64 = 1.0;

fn ball() -> Body {
    Body::sphere(MASS, RADIUS).unwrap()
}

fn moving<A: Algebra>(body: &Body, position: Vector3<f64>, velocity: Vector3<f64>) -> State<A> {
    State::from_world_twist(body, position, &UnitQuaternion::identity(), Vector3::zeros(), velocity)
}

/// `count` free balls in a row along x, no gravity, each touching the next by an elastic frictionless ball contact.
fn balls<A: Algebra>(count: usize) -> Mechanism<A> {
    let mut system = Mechanism::<A>::new();
    let ids: Vec<_> = (0..count)
        .map(|k| system.add_body(format!("ball {k}"), ball()).unwrap())
        .collect();
    let touching = BallContact::new(Vector3::zeros(), RADIUS, Vector3::zeros(), RADIUS)
        .unwrap()
        .with_restitution(1.0)
        .unwrap();
    for k in 0..count {
        for l in k + 1..count {
            system
                .add_ball_contact(format!("{k} on {l}"), ids[l], ids[k], touching)
                .unwrap();
        }
    }
    system
}

/// The velocities of every body at the end of `run`.
fn final_velocities<A: Algebra>(run: &Simulation<A>, count: usize) -> Vec<Vector3<f64>> {
    (0..count).map(|b| run.body(b).last().unwrap().velocity).collect()
}

/// Ball 0 moving at 1 m/s along x, 0.5 m short of ball 1 at rest and off its centre by the radius, about `origin`:
/// the start, the time they meet and ball 1's velocity after an elastic frictionless impact.
fn off_centre<A: Algebra>(origin: Vector3<f64>) -> ([State<A>; 2], f64, Vector3<f64>) {
    let (speed, offset, distance) = (1.0, RADIUS, 0.5);
    let start = [
        moving::<A>(
            &ball(),
            origin + Vector3::new(-distance, 0.0, 0.0),
            Vector3::x() * speed,
        ),
        moving::<A>(&ball(), origin + Vector3::new(0.0, offset, 0.0), Vector3::zeros()),
    ];
    let reach = (4.0 * RADIUS * RADIUS - offset * offset).sqrt();
    let line = Vector3::new(reach, offset, 0.0) / (2.0 * RADIUS);
    (start, (distance - reach) / speed, line * speed * line.x)
}

/// Ball 0 moving at 1 m/s along x meets ball 1 at rest, off centre by the radius (sin θ = 1/2): it meets it where
/// its centre is √(4r² − b²) short of ball 1's in x. Equal masses, elastic, no friction: ball 1 leaves along the line
/// of centres at `v cos θ`, ball 0 at right angles to it with `v sin θ`, neither spinning.
fn two_balls_meeting_off_centre_leave_at_right_angles<A: Algebra>() {
    let (start, impact, struck) = off_centre::<A>(Vector3::zeros());
    let (system, speed) = (balls::<A>(2), 1.0);
    for run in runs(&system, &start, 1.0) {
        assert_eq!(run.transitions.len(), 1, "{:?}", run.transitions);
        assert!(matches!(run.transitions[0].change, LimitChange::Bounced { .. }));
        assert!(
            (run.transitions[0].t - impact).abs() < 1e-12,
            "{} s, {impact} s exact",
            run.transitions[0].t
        );
        let [first, second] = final_velocities(&run, 2)[..] else {
            unreachable!()
        };
        assert!((second - struck).norm() < 1e-12, "{second} against {struck}");
        assert!((first - (Vector3::x() * speed - struck)).norm() < 1e-12, "{first}");
        assert!(first.dot(&second).abs() < 1e-12);
        for b in 0..2 {
            assert!(run.body(b).last().unwrap().angular_velocity.norm() < 1e-12);
        }
    }
}

/// The same two balls meeting 1e4 m from the origin (in x and z): the impact within 1e-10 s of its time and the exit
/// velocities within 1e-10 m/s, the round-off of coordinates 1e4 large.
fn two_balls_meeting_far_from_the_origin<A: Algebra>() {
    let (start, impact, struck) = off_centre::<A>(Vector3::new(1e4, 0.0, 1e4));
    let run = simulate(&balls::<A>(2), &start, Method::Dop853Body, &adaptive(1e-12, 1.0)).unwrap();
    assert_eq!(run.transitions.len(), 1, "{:?}", run.transitions);
    assert!((run.transitions[0].t - impact).abs() < 1e-10);
    let [first, second] = final_velocities(&run, 2)[..] else {
        unreachable!()
    };
    assert!((second - struck).norm() < 1e-10 && (first - (Vector3::x() - struck)).norm() < 1e-10);
}

/// Balls at `positions` along x, the first moving at `speed` along x into the others at rest.
fn cradle<A: Algebra>(positions: &[f64], speed: f64) -> Vec<State<A>> {
    (positions.iter().enumerate())
        .map(|(k, &x)| {
            let velocity = if k == 0 { Vector3::x() * speed } else { Vector3::zeros() };
            moving::<A>(&ball(), Vector3::x() * x, velocity)
        })
        .collect()
}

/// Newton's cradle, three balls 1 mm apart: each impact is between two balls, so ball 0 stops and ball 1 moves on at
/// its speed, then ball 1 stops and ball 2 leaves at it: (0, 0, v), at `g/v` and `2g/v`.
fn newtons_cradle_with_gaps_passes_the_speed_down_the_row<A: Algebra>() {
    let (speed, gap) = (1.0, 1e-3);
    let system = balls::<A>(3);
    let start = cradle::<A>(&[0.0, 2.0 * RADIUS + gap, 4.0 * RADIUS + 2.0 * gap], speed);
    for run in runs(&system, &start, 0.01) {
        let times: Vec<f64> = run.transitions.iter().map(|t| t.t).collect();
        assert_eq!(times.len(), 2, "{:?}", run.transitions);
        assert!(
            (times[0] - gap / speed).abs() < 1e-12 && (times[1] - 2.0 * gap / speed).abs() < 1e-12,
            "{times:?}"
        );
        let velocities = final_velocities(&run, 3);
        for (k, velocity) in velocities.iter().enumerate() {
            let exact = if k == 2 { Vector3::x() * speed } else { Vector3::zeros() };
            assert!((velocity - exact).norm() < 1e-12, "ball {k}: {velocity}");
        }
    }
}

/// Ball 0 meets a row of two touching balls at rest: both contacts take part in one impact, solved together by
/// Newton's law with complementarity (docs/contacts.md "Between bodies"). Contact 0–1 leaves at the speed it met, v;
/// contact 1–2 met at rest, so leaves at rest: momentum gives `(−v/3, 2v/3, 2v/3)`, which keeps the energy. (A real
/// cradle's balls are not quite touching, and pass the speed on one at a time as in the test above.)
fn newtons_cradle_touching_moves_as_the_simultaneous_law_says<A: Algebra>() {
    let (speed, gap) = (1.0, 1e-3);
    let system = balls::<A>(3);
    let start = cradle::<A>(&[-2.0 * RADIUS - gap, 0.0, 2.0 * RADIUS], speed);
    for run in runs(&system, &start, 0.01) {
        let velocities = final_velocities(&run, 3);
        for (velocity, exact) in velocities
            .iter()
            .zip([-speed / 3.0, 2.0 * speed / 3.0, 2.0 * speed / 3.0])
        {
            assert!((velocity - Vector3::x() * exact).norm() < 1e-12, "{velocities:?}");
        }
        let energy: f64 = velocities.iter().map(|v| 0.5 * MASS * v.norm_squared()).sum();
        assert!((energy - 0.5 * MASS * speed * speed).abs() < 1e-12);
    }
}

/// Box `name` of mass `mass` and sides `sides`, its four bottom corners (body frame).
fn bottom_corners(sides: Vector3<f64>) -> [Vector3<f64>; 4] {
    let (x, y, z) = (sides.x / 2.0, sides.y / 2.0, -sides.z / 2.0);
    [
        Vector3::new(-x, -y, z),
        Vector3::new(x, -y, z),
        Vector3::new(x, y, z),
        Vector3::new(-x, y, z),
    ]
}

/// Boxes of `masses` and `sides` stacked on the floor z = 0 under gravity, each resting on the one below by its four
/// bottom corners on that box's top face, with friction `between` there and `floor` on the floor; the boxes' centres
/// and the mechanism.
fn stack<A: Algebra>(
    boxes: &[(f64, Vector3<f64>)],
    floor: Friction,
    between: Friction,
) -> (Mechanism<A>, Vec<Vector3<f64>>) {
    let mut system = Mechanism::<A>::new();
    let mut centres = Vec::new();
    let mut below: Option<(dynamics::BodyId, f64)> = None;
    let mut height = 0.0;
    for (k, &(mass, sides)) in boxes.iter().enumerate() {
        let id = system
            .add_body(format!("box {k}"), Body::cuboid(mass, sides).unwrap())
            .unwrap();
        system.add_force(id, Force::gravity()).unwrap();
        centres.push(Vector3::new(0.0, 0.0, height + sides.z / 2.0));
        for (c, corner) in bottom_corners(sides).into_iter().enumerate() {
            match below {
                None => {
                    let contact = PlaneContact::new(corner, Vector3::z(), 0.0)
                        .unwrap()
                        .with_friction(floor);
                    system.add_contact(format!("box {k} corner {c}"), id, contact).unwrap();
                }
                Some((lower, top)) => {
                    let contact = PlaneContact::new(corner, Vector3::z(), top)
                        .unwrap()
                        .with_friction(between);
                    system
                        .add_contact_on(format!("box {k} corner {c}"), id, lower, contact)
                        .unwrap();
                }
            }
        }
        below = Some((id, sides.z / 2.0));
        height += sides.z;
    }
    (system, centres)
}

/// A 1 kg box thrown at 1 m/s across the top of a 3 kg box that rests on a frictionless floor, friction 0.4 between
/// them: the friction `μ m₁ g` slows the top box and speeds the bottom one until they move together at
/// `m₁ v₀/(m₁ + m₂)`, from `t = v₀/(μ g (1 + m₁/m₂))`, where the top box's four corners stick at once.
fn a_box_thrown_across_a_box_drags_it_along<A: Algebra>() {
    let (top, bottom, mu, v0) = (1.0, 3.0, 0.4, 1.0);
    let boxes = [(bottom, Vector3::new(0.6, 0.6, 0.2)), (top, Vector3::repeat(0.2))];
    let (system, centres) = stack::<A>(&boxes, Friction::NONE, Friction::coulomb(mu).unwrap());
    let start = [
        moving::<A>(&Body::cuboid(bottom, boxes[0].1).unwrap(), centres[0], Vector3::zeros()),
        moving::<A>(&Body::cuboid(top, boxes[1].1).unwrap(), centres[1], Vector3::x() * v0),
    ];
    let stop = v0 / (mu * G * (1.0 + top / bottom));
    let common = top * v0 / (top + bottom);
    for run in runs(&system, &start, 0.5) {
        let stuck: Vec<f64> = (run.transitions.iter())
            .filter(|t| matches!(t.change, LimitChange::Stuck { .. }))
            .map(|t| t.t)
            .collect();
        assert_eq!(stuck.len(), 4, "{:?}", run.transitions);
        assert!(
            stuck.iter().all(|t| (t - stop).abs() < 1e-11),
            "{stuck:?}, {stop} s exact"
        );
        for sample in run.body(1) {
            let speed = if sample.t < stop {
                v0 - mu * G * sample.t
            } else {
                common
            };
            assert!(
                (sample.velocity - Vector3::x() * speed).norm() < 1e-10,
                "t = {}: {}",
                sample.t,
                sample.velocity
            );
            assert!((sample.position.z - centres[1].z).abs() < 1e-12, "t = {}", sample.t);
        }
        for sample in run.body(0) {
            let speed = (mu * G * top / bottom) * sample.t.min(stop);
            assert!(
                (sample.velocity - Vector3::x() * speed).norm() < 1e-10,
                "t = {}: {}",
                sample.t,
                sample.velocity
            );
            assert!(sample.angular_velocity.norm() < 1e-10);
        }
    }
}

/// Three boxes stacked on a floor with friction, at rest: the contacts hold (each on its four corners, rows of rank
/// three) and no box moves by more than 1e-9 m in 10 s.
fn a_stack_of_boxes_rests_without_creep<A: Algebra>() {
    let boxes = [
        (3.0, Vector3::new(0.6, 0.6, 0.3)),
        (2.0, Vector3::new(0.4, 0.4, 0.2)),
        (1.0, Vector3::repeat(0.2)),
    ];
    let friction = Friction::coulomb(0.5).unwrap();
    let (system, centres) = stack::<A>(&boxes, friction, friction);
    let start: Vec<State<A>> = (boxes.iter().zip(&centres))
        .map(|(&(mass, sides), &centre)| moving::<A>(&Body::cuboid(mass, sides).unwrap(), centre, Vector3::zeros()))
        .collect();
    for run in [
        simulate(&system, &start, Method::Dop853Body, &adaptive(1e-10, 10.0)).unwrap(),
        simulate(&system, &start, JointMethod::Rkmk8, &Schedule::new(1e-2, 10.0).unwrap()).unwrap(),
    ] {
        for (b, centre) in centres.iter().enumerate() {
            for sample in run.body(b) {
                assert!(
                    (sample.position - centre).norm() <= 1e-9,
                    "box {b} at t = {}: {}",
                    sample.t,
                    sample.position
                );
            }
        }
    }
}

/// A frictionless ball of radius r on top of a fixed ball of radius R (a body of 1e15 kg, not moved by it), nudged
/// off the top (to θ₀, at rest): its centre moves on the circle of radius L = R + r, held there by the push until
/// `cos θ = (2/3) cos θ₀`, where the push `m g cos θ − m v²/L` reaches zero and it leaves. The held row's rate carries the turning of the line of
/// centres, `v²/L` (docs/contacts.md "Between bodies"): without it the ball would stay on to θ = 90°.
fn a_ball_leaves_a_ball_at_the_classical_angle<A: Algebra>() {
    let (big, nudge): (f64, f64) = (0.4, 0.05);
    let length = big + RADIUS;
    let mut system = Mechanism::<A>::new();
    let anchor = Body::sphere(1e15, big).unwrap();
    let fixed = system.add_body("anchor", anchor).unwrap();
    let rolling = system.add_body("ball", ball()).unwrap();
    system.add_force(rolling, Force::gravity()).unwrap();
    let touching = BallContact::new(Vector3::zeros(), RADIUS, Vector3::zeros(), big).unwrap();
    system
        .add_ball_contact("ball on anchor", rolling, fixed, touching)
        .unwrap();
    let start = [
        moving::<A>(&anchor, Vector3::zeros(), Vector3::zeros()),
        moving::<A>(
            &ball(),
            Vector3::new(length * nudge.sin(), 0.0, length * nudge.cos()),
            Vector3::zeros(),
        ),
    ];
    for run in runs(&system, &start, 1.5) {
        let released: Vec<f64> = (run.transitions.iter())
            .filter(|t| matches!(t.change, LimitChange::Released { .. }))
            .map(|t| t.t)
            .collect();
        assert_eq!(released.len(), 1, "{:?}", run.transitions);
        for sample in run.body(1) {
            if sample.t <= released[0] {
                // On the circle until the release, at the speed energy gives: `v² = 2 g L (cos θ₀ − cos θ)`.
                let cos = sample.position.z / length;
                let speed = (2.0 * G * length * (nudge.cos() - cos)).sqrt();
                assert!((sample.position.norm() - length).abs() < 1e-12, "t = {}", sample.t);
                assert!((sample.velocity.norm() - speed).abs() < 1e-10, "t = {}", sample.t);
            } else {
                // In flight, at the horizontal speed it left with: `v cos θ` at cos θ = (2/3) cos θ₀.
                let cos = 2.0 * nudge.cos() / 3.0;
                let leaving = (2.0 * G * length * (nudge.cos() - cos)).sqrt() * cos;
                assert!(
                    (sample.velocity.x - leaving).abs() < 1e-10,
                    "t = {}: {}",
                    sample.t,
                    sample.velocity.x
                );
            }
        }
        assert!(run.body(1).last().unwrap().t > released[0] + 0.1);
    }
}

/// A block resting on a turntable (a box spinning on a frictionless floor), 0.3 m from the turntable's axis, the two
/// started turning together at 2 rad/s about their common centre of mass: the friction it needs, `m ω² ρ`, is
/// within `μ m g`, so it sticks and the pair turns as one rigid body, each centre on its circle about the common
/// centre and each turned by ωt. The tangential rows turn with the table (docs/contacts.md "Between bodies").
fn a_block_on_a_turntable_turns_with_it<A: Algebra>() {
    let (omega, radius, mu) = (2.0, 0.3, 0.5);
    let boxes = [(3.0, Vector3::new(1.0, 1.0, 0.2)), (1.0, Vector3::repeat(0.2))];
    let (system, centres) = stack::<A>(&boxes, Friction::NONE, Friction::coulomb(mu).unwrap());
    let (table, block) = (
        Body::cuboid(boxes[0].0, boxes[0].1).unwrap(),
        Body::cuboid(boxes[1].0, boxes[1].1).unwrap(),
    );
    let block_centre = centres[1] + Vector3::x() * radius;
    let common = Vector3::x() * (boxes[1].0 * radius / (boxes[0].0 + boxes[1].0));
    let spin = Vector3::z() * omega;
    let start = [
        State::<A>::from_world_twist(
            &table,
            centres[0],
            &UnitQuaternion::identity(),
            spin,
            spin.cross(&(centres[0] - common)),
        ),
        State::<A>::from_world_twist(
            &block,
            block_centre,
            &UnitQuaternion::identity(),
            spin,
            spin.cross(&(block_centre - common)),
        ),
    ];
    // The common centre's vertical line, at each body's height.
    let axis = |height: f64| Vector3::new(common.x, common.y, height);
    for run in runs(&system, &start, 2.0) {
        assert!(
            run.transitions
                .iter()
                .all(|t| !matches!(t.change, LimitChange::Slipped { .. })),
            "{:?}",
            run.transitions
        );
        for (b, centre) in [centres[0], block_centre].into_iter().enumerate() {
            for sample in run.body(b) {
                let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), omega * sample.t);
                let exact = axis(centre.z) + turn * (centre - axis(centre.z));
                assert!(
                    (sample.position - exact).norm() < 1e-9,
                    "body {b} at t = {}: {} against {exact}",
                    sample.t,
                    sample.position
                );
                assert!(
                    sample.orientation.angle_to(&turn) < 1e-9,
                    "body {b} at t = {}",
                    sample.t
                );
            }
        }
    }
}

/// A block sliding without friction at 2 m/s across a table top 1 m square (a plane bounded to a face): its leading
/// corners reach the table's edge at `(0.5 − 0.1)/2` s, where the run stops with an error naming a corner and saying
/// it is outside its face, rather than holding the block up on the plane beyond the table.
fn a_block_sliding_off_a_bounded_face_stops_the_run<A: Algebra>() {
    let block = Body::cuboid(1.0, Vector3::repeat(0.2)).unwrap();
    let mut system = Mechanism::<A>::new();
    let id = system.add_body("block", block).unwrap();
    system.add_force(id, Force::gravity()).unwrap();
    let sides = [
        (Vector3::x(), 0.5),
        (-Vector3::x(), 0.5),
        (Vector3::y(), 0.5),
        (-Vector3::y(), 0.5),
    ];
    for (c, corner) in bottom_corners(Vector3::repeat(0.2)).into_iter().enumerate() {
        let name = format!("corner {c}");
        system
            .add_contact(name.as_str(), id, PlaneContact::new(corner, Vector3::z(), 0.8).unwrap())
            .unwrap();
        system.set_contact_face(&name, &sides).unwrap();
    }
    let start = [moving::<A>(&block, Vector3::new(0.0, 0.0, 0.9), Vector3::x() * 2.0)];
    let edge = (0.5 - 0.1) / 2.0;
    let error = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-10, 1.0))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        error.contains("corner") && error.contains("outside its face"),
        "{error}"
    );
    let at: f64 = error
        .split("at t = ")
        .nth(1)
        .and_then(|rest| rest.split([' ', ':']).next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{error}"));
    assert!(
        at > edge && at < edge + 0.05,
        "stopped at t = {at}, the edge at {edge} s"
    );
    // On the table the same block slides on undisturbed.
    let run = simulate(&system, &start, Method::Dop853Body, &adaptive(1e-10, 0.15)).unwrap();
    let end = run.body(0).last().unwrap();
    assert!(
        (end.position - Vector3::new(0.3, 0.0, 0.9)).norm() < 1e-10,
        "{}",
        end.position
    );
}

/// Careless contacts between bodies are refused naming the cause: ball radii zero, negative, NaN, infinite or huge;
/// centres NaN, infinite or far away; restitution outside [0, 1]; a body in contact with itself; a body of another
/// mechanism.
#[test]
fn careless_contacts_between_bodies_are_refused() {
    use dynamics::{MechanismError, Pga};
    let (nan, inf) = (f64::NAN, f64::INFINITY);
    let point = Vector3::new(0.0, 0.0, -0.1);
    let block = || Body::cuboid(1.0, Vector3::repeat(0.2)).unwrap();
    // Balls between bodies: radii zero, negative, NaN, infinite or huge; centres NaN, infinite or far away;
    // restitution outside [0, 1].
    for (a, b) in [(0.0, 0.1), (0.1, -0.1), (nan, 0.1), (0.1, inf), (2e6, 0.1)] {
        let error = BallContact::new(point, a, point, b).unwrap_err().to_string();
        assert!(error.contains("radius"), "{a} {b}: {error}");
    }
    for (c, d) in [
        (Vector3::new(nan, 0.0, 0.0), point),
        (point, Vector3::new(0.0, -inf, 0.0)),
        (point, Vector3::new(0.0, 0.0, 2e6)),
    ] {
        let error = BallContact::new(c, 0.1, d, 0.1).unwrap_err().to_string();
        assert!(error.contains("must be finite and within"), "{c:?} {d:?}: {error}");
    }
    for e in [nan, -0.1, 1.5] {
        let error = BallContact::new(point, 0.1, point, 0.1)
            .unwrap()
            .with_restitution(e)
            .unwrap_err()
            .to_string();
        assert!(error.contains("restitution"), "{e}: {error}");
    }
    // Between bodies: a body with itself, or a body of another mechanism.
    {
        let ball = BallContact::new(Vector3::zeros(), 0.1, Vector3::zeros(), 0.1).unwrap();
        let face = PlaneContact::new(point, Vector3::z(), 0.0).unwrap();
        let mut pair = Mechanism::<Pga>::new();
        let a = pair.add_body("a", block()).unwrap();
        let error = pair.add_ball_contact("c", a, a, ball).unwrap_err().to_string();
        assert!(error.contains("two different bodies"), "{error}");
        let error = pair.add_contact_on("c", a, a, face).unwrap_err().to_string();
        assert!(error.contains("two different bodies"), "{error}");
        let stranger = {
            let mut m = Mechanism::<Pga>::new();
            m.add_body("a", block()).unwrap();
            m.add_body("b", block()).unwrap()
        };
        assert!(matches!(
            pair.add_ball_contact("c", a, stranger, ball),
            Err(MechanismError::UnknownBody(1))
        ));
        assert!(matches!(
            pair.add_contact_on("c", stranger, a, face),
            Err(MechanismError::UnknownBody(1))
        ));
        assert_eq!(pair.contact_names().count(), 0);
        assert!(matches!(
            pair.reference_frame(stranger),
            Err(MechanismError::UnknownBody(1))
        ));
        assert_eq!(pair.reference_frame(a), Ok(nalgebra::Isometry3::identity()));
    }
    // Faces: an unknown contact, a ball contact; normals zero, NaN or infinite; offsets NaN, or a plane 1e7 m away;
    // more than MAX_FACE_PLANES planes. Normals of huge or tiny numbers are directions like any other.
    use dynamics::contacts::MAX_FACE_PLANES;
    let mut pair = Mechanism::<Pga>::new();
    let (a, b) = (
        pair.add_body("a", block()).unwrap(),
        pair.add_body("b", block()).unwrap(),
    );
    let corner = PlaneContact::new(point, Vector3::z(), 0.0).unwrap();
    pair.add_contact_on("corner", a, b, corner).unwrap();
    let ball = BallContact::new(Vector3::zeros(), 0.1, Vector3::zeros(), 0.1).unwrap();
    pair.add_ball_contact("balls", a, b, ball).unwrap();
    let side = |normal: Vector3<f64>, offset: f64| vec![(normal, offset)];
    for (name, solid, words) in [
        ("edge", side(Vector3::x(), 0.5), "no contact has this name"),
        ("balls", side(Vector3::x(), 0.5), "a ball contact has no face"),
        ("corner", side(Vector3::zeros(), 0.5), "non-zero normal"),
        ("corner", side(Vector3::new(nan, 0.0, 1.0), 0.5), "non-zero normal"),
        ("corner", side(Vector3::new(0.0, inf, 1.0), 0.5), "non-zero normal"),
        ("corner", side(Vector3::x(), nan), "distance from the origin"),
        ("corner", side(Vector3::x(), 1e7), "distance from the origin"),
        ("corner", side(Vector3::x() * 1e-300, 1.0), "distance from the origin"),
        (
            "corner",
            vec![(Vector3::x(), 0.5); MAX_FACE_PLANES + 1],
            "at most 1024 planes",
        ),
    ] {
        let error = pair.set_contact_face(name, &solid).unwrap_err().to_string();
        assert!(
            error.contains(name) && error.contains(words),
            "{name} {solid:?}: {error}"
        );
    }
    for normal in [Vector3::x() * 1e300, Vector3::x() * 1e-300] {
        pair.set_contact_face("corner", &side(normal, normal.x * 0.5)).unwrap();
    }
}

for_both_algebras!(
    two_balls_meeting_far_from_the_origin,
    a_block_sliding_off_a_bounded_face_stops_the_run,
    a_ball_leaves_a_ball_at_the_classical_angle,
    a_block_on_a_turntable_turns_with_it,
    two_balls_meeting_off_centre_leave_at_right_angles,
    newtons_cradle_with_gaps_passes_the_speed_down_the_row,
    newtons_cradle_touching_moves_as_the_simultaneous_law_says,
    a_box_thrown_across_a_box_drags_it_along,
    a_stack_of_boxes_rests_without_creep,
);
