//! `[[collision]]` pairs in scene files (docs/contacts.md "Between bodies", docs/scene-files.md): careless pairs
//! refused by name, contacts and shapes on robot links where the kinematics put them, `"all"` and `except`, a box
//! tipping off a stack, crossed edges meeting, and a cylinder's rims rolling on a box's face.

use dynamics::{Cga, Dynamics, Pga};
use nalgebra::{UnitQuaternion, Vector3};
use scene_file::{FileAlgebra, Scene};

use super::robots::{assert_each_refused, fresh, scenes, shipped, Row};

/// A hopper: a base with a box shape (0.2 × 0.2 × 0.1 m) and a leg on a hip about y at (0.05, 0, −0.05), its centre of
/// mass at (0, 0, −0.1) of its frame and its principal axes turned about y, a foot sphere of 3 cm at (0, 0, −0.2).
const HOPPER: &str = r#"<robot name="hopper">
  <link name="base">
    <inertial><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="leg">
    <inertial><origin xyz="0 0 -0.1"/><mass value="0.2"/><inertia ixx="0.002" iyy="0.002" izz="0.0005" ixy="0" ixz="0.0003" iyz="0"/></inertial>
    <collision><origin xyz="0 0 -0.2"/><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <joint name="hip" type="revolute">
    <parent link="base"/><child link="leg"/><origin xyz="0.05 0 -0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="10"/>
  </joint>
</robot>"#;

/// `[[collision]]` pairs with their careless inputs (the shipped stack and billiards scene edited): the wrong number of
/// bodies, one body twice, an unknown body or one without shapes, a word other than "all", coefficients out of range,
/// unknown keys, a start where two shapes interpenetrate (naming the pair, the shapes and the depth), a capsule or a
/// cylinder against a sphere, a box too elongated for parry3d's hull.
#[test]
fn careless_collision_pairs_fail_naming_the_entry_and_the_value() {
    let scene = shipped("stack_and_billiards.toml");
    let pair = "bodies = [\"top\", \"middle\"]\nfriction = 0.5";
    let balls = "bodies = [\"cue\", \"red\"]";
    let top_shape =
        "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2] }]\ninitial = { position = [0.0, 0.0, 0.6] }";
    // A hull of 250 points on a sphere of 0.1 m: its vertices, faces and edges against the middle box's are more
    // feature pairs than a pair watches.
    let many: Vec<String> = (0..250)
        .map(|k| {
            let (z, turn) = (1.0 - (k as f64 + 0.5) / 125.0, k as f64 * 2.399963229728653);
            let r = (1.0 - z * z).sqrt();
            format!("[{}, {}, {}]", 0.1 * r * turn.cos(), 0.1 * r * turn.sin(), 0.1 * z)
        })
        .collect();
    let many = many.join(", ");
    #[rustfmt::skip]
    let rows: &[Row] = &[
        (&scene, pair, "bodies = [\"top\"]", &["collision 2: bodies", "name two bodies", "got 1 names"]),
        (&scene, pair, "bodies = [\"top\", \"middle\", \"base\"]", &["collision 2: bodies", "got 3 names"]),
        (&scene, pair, "bodies = [\"top\", \"top\"]", &["collision 2: bodies", "`top` twice"]),
        (&scene, balls, "bodies = [\"cue\", \"cue\"]", &["balls: bodies", "`cue` twice"]),
        (&scene, pair, "bodies = [\"top\", \"moon\"]", &["collision 2: bodies", "no body or robot link named `moon`"]),
        (&scene, pair, "bodies = [\"top\", \"world\"]", &["collision 2: bodies", "named `world`"]),
        (&scene, pair, "bodies = \"everything\"", &["collision 2: bodies", "\"all\"", "everything"]),
        (&scene, pair, "bodies = 3", &["did not match any variant"]),
        (&scene, pair, "friction = 0.5", &["missing field `bodies`"]),
        (&scene, pair, &format!("{pair}\nfriction = -0.5"), &["duplicate key"]),
        (&scene, pair, "bodies = [\"top\", \"middle\"]\nfriction = -0.5", &["collision 2: friction", "kinetic coefficient", "-0.5"]),
        (&scene, pair, "bodies = [\"top\", \"middle\"]\nfriction = nan", &["collision 2: friction", "NaN"]),
        (&scene, pair, "bodies = [\"top\", \"middle\"]\nfriction = 1e300", &["collision 2: friction", "1e6"]),
        (&scene, pair, &format!("{pair}\nstatic_friction = 0.1"), &["collision 2: friction", "static coefficient 0.1 is below the kinetic one 0.5"]),
        (&scene, pair, &format!("{pair}\nrestitution = 1.5"), &["collision 2: restitution", "1.5"]),
        (&scene, pair, &format!("{pair}\nrestitution = nan"), &["collision 2: restitution", "NaN"]),
        (&scene, pair, &format!("{pair}\ncolour = 1"), &["unknown field `colour`"]),
        (&scene, top_shape, "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2] }]\ninitial = { position = [0.0, 0.0, 0.55] }", &["collision top / middle: `top` box 1 and `middle` box 1", "5.000e-2 m into each other"]),
        (&scene, "position = [0.0, 1.03, 0.0285]", "position = [-0.98, 1.0, 0.0285]", &["collision balls: `cue` sphere 1 and `red` sphere 1", "into each other"]),
        (&scene, top_shape, "initial = { position = [0.0, 0.0, 0.6] }", &["collision 2: bodies", "no body or robot link named `top` has collision shapes"]),
        // A box parry3d cannot take the hull of (found by the fuzz test: it panicked).
        (&scene, "collision = [{ kind = \"box\", size = [0.6, 0.6, 0.3] }]", "collision = [{ kind = \"box\", size = [1000.0, 0.6, 0.3] }]", &["collision middle / base", "cannot build the hull of box 1", "1.000e3, 6.000e-1 and 3.000e-1 m"]),
        (&scene, top_shape, &format!("collision = [{{ kind = \"convex\", points = [{many}] }}]\ninitial = {{ position = [0.0, 0.0, 0.6] }}"), &["collision top / middle: `top` convex 1 and `middle` box 1", "feature pairs, more than 10000"]),
        (&scene, "collision = [{ kind = \"sphere\", radius = 0.0285 }]\ninitial = { position = [-1.0", "collision = [{ kind = \"capsule\", radius = 0.0285, length = 0.1 }]\ninitial = { position = [-1.0", &["balls: bodies", "`cue` capsule 1 against `red` sphere 1", "not modelled"]),
        (&scene, "collision = [{ kind = \"sphere\", radius = 0.0285 }]\ninitial = { position = [-1.0", "collision = [{ kind = \"cylinder\", radius = 0.0285, length = 0.1 }]\ninitial = { position = [-1.0", &["balls: bodies", "`cue` cylinder 1 against `red` sphere 1", "not modelled"]),
    ];
    assert_each_refused(rows);
}

/// Contacts and collision shapes on robot links sit where the URDF's kinematics put them, also on a link whose centre
/// of mass is off its frame's origin (its body's principal frame is not the link frame): the [`HOPPER`] with a free
/// base at (0, 0, 0.4) turned 10° about x, its hip at 0.3 rad, and a free ball of 5 cm beside it in a `[[collision]]`
/// pair with the leg. At the start the base's corners and the foot stand above the floor as forward kinematics by hand
/// puts them (less the foot's 3 cm), and the pair's gap is the distance of the centres less 8 cm, each to 1e-12 m, in
/// both algebras.
#[test]
fn contacts_on_robot_links_sit_where_the_kinematics_put_them() {
    let dir = fresh("link-contacts");
    std::fs::write(dir.join("hopper.urdf"), HOPPER).unwrap();
    let scene = r#"title = "hopper"
algebra = "both"
tolerance = 1e-10
duration = 0.1

[robot]
urdf = "hopper.urdf"
root = "free"
collisions = "urdf"
base_position = [0.0, 0.0, 0.4]
base_orientation = { axis = [1.0, 0.0, 0.0], degrees = 10.0 }
q = { hip = 0.3 }

[[body]]
name = "ball"
mass = 0.1
shape = { kind = "sphere", radius = 0.05 }
collision = [{ kind = "sphere", radius = 0.05 }]
initial = { position = [0.3, 0.1, 0.2] }

[[plane]]
name = "floor"

[[collision]]
bodies = ["leg", "ball"]
"#;
    let parsed = Scene::parse_in(scene, &dir).unwrap();
    let base = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 10f64.to_radians());
    let hip = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 0.3);
    let foot =
        Vector3::new(0.0, 0.0, 0.4) + base * (Vector3::new(0.05, 0.0, -0.05) + hip * Vector3::new(0.0, 0.0, -0.2));
    let ball = Vector3::new(0.3, 0.1, 0.2);
    let mut expected = vec![("floor: ball sphere 1".to_owned(), ball.z - 0.05)];
    for c in 0..8 {
        let sign = |bit: usize| if c & (1 << bit) == 0 { -1.0 } else { 1.0 };
        let corner = base * Vector3::new(0.1 * sign(0), 0.1 * sign(1), 0.05 * sign(2));
        expected.push((format!("floor: base box 1 corner {}", c + 1), 0.4 + corner.z));
    }
    expected.push(("floor: leg sphere 1".to_owned(), foot.z - 0.03));
    expected.push((
        "leg / ball: leg sphere 1 on ball sphere 1".to_owned(),
        (foot - ball).norm() - 0.08,
    ));
    fn check<A: FileAlgebra>(parsed: &Scene, expected: &[(String, f64)]) {
        let system = parsed.system::<A>().unwrap();
        let heights = system.mechanism().contact_heights(system.initial()).unwrap();
        let names: Vec<&str> = system.mechanism().contact_names().collect();
        assert_eq!(names, expected.iter().map(|e| e.0.as_str()).collect::<Vec<_>>());
        for ((name, exact), height) in expected.iter().zip(heights) {
            assert!(
                (height - exact).abs() < 1e-12,
                "{name}: {height} m, {exact} m from the kinematics"
            );
        }
    }
    check::<Pga>(&parsed, &expected);
    check::<Cga>(&parsed, &expected);
}

/// `bodies = "all"` pairs every two bodies with collision shapes, robot links among them, but for links joined by a
/// joint (their shapes meet at the joint by design) and the pairs `except` leaves out.
#[test]
fn all_pairs_skip_joined_links_and_those_left_out() {
    let dir = fresh("all-pairs");
    std::fs::write(dir.join("hopper.urdf"), HOPPER).unwrap();
    let scene = r#"title = "hopper among things"
algebra = "pga"
tolerance = 1e-10
duration = 0.1

[robot]
urdf = "hopper.urdf"
root = "free"
collisions = "urdf"
base_position = [0.0, 0.0, 0.4]

[[body]]
name = "ball"
mass = 0.1
shape = { kind = "sphere", radius = 0.05 }
collision = [{ kind = "sphere", radius = 0.05 }]
initial = { position = [1.0, 0.0, 0.05] }

[[body]]
name = "crate"
mass = 1.0
shape = { kind = "cuboid", size = [0.2, 0.2, 0.2] }
collision = [{ kind = "box", size = [0.2, 0.2, 0.2] }]
initial = { position = [-1.0, 0.0, 0.1] }

[[plane]]
name = "floor"

[[collision]]
bodies = "all"
except = [["crate", "ball"]]
"#;
    let parsed = Scene::parse_in(scene, &dir).unwrap();
    let system = parsed.system::<Pga>().unwrap();
    let mut pairs: Vec<&str> = (system.mechanism().contact_names())
        .filter(|name| !name.starts_with("floor: "))
        .map(|name| name.split(": ").next().unwrap())
        .collect();
    pairs.dedup();
    assert_eq!(pairs, ["ball / base", "ball / leg", "crate / base", "crate / leg"]);
    // `except` names two bodies with shapes, with "all" only.
    for (from, to, part) in [
        (
            "except = [[\"crate\", \"ball\"]]",
            "except = [[\"crate\"]]",
            "each pair left out is two names",
        ),
        (
            "except = [[\"crate\", \"ball\"]]",
            "except = [[\"crate\", \"moon\"]]",
            "no body or robot link named `moon`",
        ),
        (
            "bodies = \"all\"",
            "bodies = [\"crate\", \"ball\"]",
            "has none to leave out",
        ),
    ] {
        let message = Scene::parse_in(&scene.replace(from, to), &dir)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(message.contains("collision 1") && message.contains(part), "{message}");
    }
}

/// The shipped stack with its top box thrown at 2 m/s off the middle one, no friction between them (docs/contacts.md
/// "Edges"): the top box's leading corners let go of the middle box's top face as they pass its edge, at
/// (0.2 − 0.1)/2 s (and `OUTSIDE_FACE` past it), its bottom edges then ride on the middle box's edge, its trailing
/// corners let go when its centre passes the edge at 0.2/2 s, and it tips over the edge and falls off; at no sample
/// do the two boxes go into each other (parry3d's query), in both algebras.
#[test]
fn a_box_thrown_off_a_stack_tips_over_the_edge_and_falls() {
    let text = shipped("stack_and_billiards.toml")
        .replace(
            "initial = { position = [0.0, 0.0, 0.6] }",
            "initial = { position = [0.0, 0.0, 0.6], velocity = [2.0, 0.0, 0.0] }",
        )
        .replace(
            "bodies = [\"top\", \"middle\"]\nfriction = 0.5",
            "bodies = [\"top\", \"middle\"]",
        )
        .replace("duration = 2.0", "duration = 0.4");
    assert!(text.contains("velocity = [2.0, 0.0, 0.0] }") && !text.contains("\"middle\"]\nfriction = 0.5"));
    let scene = Scene::parse_in(&text, &scenes()).unwrap();
    let (leading, trailing) = ((0.2 - 0.1) / 2.0 + dynamics::contacts::OUTSIDE_FACE / 2.0, 0.2 / 2.0);
    fn check<A: FileAlgebra>(scene: &Scene, leading: f64, trailing: f64) {
        let system = scene.system::<A>().unwrap();
        let run = scene.simulate::<A>().unwrap();
        let let_go: Vec<f64> = (run.transitions.iter())
            .filter(|t| {
                t.constraint.starts_with("top / middle: top box 1 vertex")
                    && t.constraint.ends_with("on middle box 1 face 6")
                    && matches!(t.change, dynamics::limits::LimitChange::Released { .. })
            })
            .map(|t| t.t)
            .collect();
        assert_eq!(let_go.len(), 4, "{:?}", run.transitions);
        assert!(
            let_go[..2].iter().all(|t| (t - leading).abs() < 1e-12),
            "{let_go:?}: {leading} s"
        );
        assert!(
            let_go[2..].iter().all(|t| (t - trailing).abs() < 1e-12),
            "{let_go:?}: {trailing} s"
        );
        let riding = (run.transitions.iter())
            .filter(|t| {
                t.constraint.contains(" edge ") && matches!(t.change, dynamics::limits::LimitChange::Held { .. })
            })
            .count();
        assert_eq!(riding, 2, "{:?}", run.transitions);
        let top = run.body(2).last().unwrap();
        assert!(top.position.x > 0.3 && top.position.z < 0.5, "{}", top.position);
        for k in 0..run.body(0).len() {
            let states: Vec<dynamics::State<A>> = (0..system.mechanism().body_count())
                .map(|b| {
                    let s = &run.body(b)[k];
                    let body = system.mechanism().body(b);
                    dynamics::State::from_world_twist(body, s.position, &s.orientation, s.angular_velocity, s.velocity)
                })
                .collect();
            if let Some((shapes, depth)) = system.deepest_overlap(&states) {
                assert!(depth < 1e-9, "{shapes}: {depth} m at t = {}", run.body(0)[k].t);
            }
        }
    }
    check::<Pga>(&scene, leading, trailing);
    check::<Cga>(&scene, leading, trailing);
}

/// Two boxes whose edges cross, one turned 45° about x above the other turned 45° about y, no gravity: the upper
/// moving down at 1 m/s meets the lower, at rest, edge on edge where the edges cross, on the line of their centres,
/// at `(0.5 − 2 · 0.1√2)/1` s; the impact (restitution 0, equal masses) leaves both at 0.5 m/s, without spin, the
/// edges touching with no push (docs/contacts.md "Edges"). Lowered until its bottom edge is 3.28 cm below the lower box's top edge, the pair
/// overlaps by at most that depth (`SceneSystem::deepest_overlap`, parry3d's query, independent of the contacts).
#[test]
fn crossed_edges_meet_edge_on_edge() {
    let scene = r#"title = "crossed edges"
algebra = "both"
tolerance = 1e-10
duration = 0.4

[[body]]
name = "upper"
mass = 1.0
shape = { kind = "cuboid", size = [0.2, 0.2, 0.2] }
collision = [{ kind = "box", size = [0.2, 0.2, 0.2] }]
initial = { position = [0.0, 0.0, 0.5], orientation = { axis = [1.0, 0.0, 0.0], degrees = 45.0 }, velocity = [0.0, 0.0, -1.0] }

[[body]]
name = "lower"
mass = 1.0
shape = { kind = "cuboid", size = [0.2, 0.2, 0.2] }
collision = [{ kind = "box", size = [0.2, 0.2, 0.2] }]
initial = { position = [0.0, 0.0, 0.0], orientation = { axis = [0.0, 1.0, 0.0], degrees = 45.0 } }

[[collision]]
bodies = ["upper", "lower"]
"#;
    let parsed = Scene::parse(scene).unwrap();
    let system = parsed.system::<Pga>().unwrap();
    assert_eq!(system.deepest_overlap(system.initial()), None);
    let half_diagonal = 0.1 * std::f64::consts::SQRT_2;
    let lowered = 2.0 * half_diagonal - 0.0328;
    let body = |i: usize| *system.mechanism().body(i);
    let turned = |axis: Vector3<f64>| UnitQuaternion::from_scaled_axis(axis * std::f64::consts::FRAC_PI_4);
    let states = [
        dynamics::State::<Pga>::from_world_twist(
            &body(0),
            Vector3::z() * lowered,
            &turned(Vector3::x()),
            Vector3::zeros(),
            Vector3::zeros(),
        ),
        dynamics::State::<Pga>::from_world_twist(
            &body(1),
            Vector3::zeros(),
            &turned(Vector3::y()),
            Vector3::zeros(),
            Vector3::zeros(),
        ),
    ];
    let (shapes, depth) = system.deepest_overlap(&states).expect("the edges cross");
    assert_eq!(shapes, "upper / lower: upper box 1 and lower box 1");
    assert!(depth > 0.0 && depth <= 0.0328 + 1e-9, "{depth} m");
    // Careless states: the wrong count is no overlap; non-finite or far-away poses do not panic.
    assert_eq!(system.deepest_overlap(&states[..1]), None);
    for far in [f64::NAN, f64::INFINITY, 1e300, 1e6] {
        let mut moved = states;
        moved[0] = dynamics::State::<Pga>::from_world_twist(
            &body(0),
            Vector3::new(far, 0.0, far),
            &turned(Vector3::x()),
            Vector3::zeros(),
            Vector3::zeros(),
        );
        let _ = system.deepest_overlap(&moved);
    }
    let meet = 0.5 - 2.0 * half_diagonal;
    fn check<A: FileAlgebra>(scene: &Scene, meet: f64) {
        let run = scene.simulate::<A>().unwrap();
        // Moving together with no push between them, the edges rest on each other: any later hold is met at rest
        // and changes nothing.
        let held = &run.transitions[0];
        assert!(
            matches!(held.change, dynamics::limits::LimitChange::Held { .. }),
            "{held:?}"
        );
        for later in &run.transitions[1..] {
            assert_eq!(later.constraint, held.constraint);
            assert!(later.energy_change.abs() < 1e-12, "{later:?}");
            if let dynamics::limits::LimitChange::Held { speed_before, .. } = later.change {
                assert!(speed_before.abs() < 1e-12, "{later:?}");
            }
        }
        assert!(
            held.constraint.starts_with("upper / lower: upper box 1 edge")
                && held.constraint.contains("on lower box 1 edge"),
            "{}",
            held.constraint
        );
        assert!((held.t - meet).abs() < 1e-12, "{} s, {meet} s exact", held.t);
        for b in 0..2 {
            let end = run.body(b).last().unwrap();
            assert!(
                (end.velocity - Vector3::z() * -0.5).norm() < 1e-12,
                "{b}: {}",
                end.velocity
            );
            assert!(end.angular_velocity.norm() < 1e-12, "{b}: {}", end.angular_velocity);
        }
    }
    check::<Pga>(&parsed, meet);
    check::<Cga>(&parsed, meet);
}

/// A can (a solid cylinder of 5 cm radius, 20 cm long, 1 kg) lying on the top face of a 10 kg crate that stands on a
/// floor, struck across its axis at 1 m/s without spin, friction 0.3 between them: its cap rims slide on the face
/// until they stop slipping at `v₀/(3μg)`, and it rolls on at `2v₀/3` (I = m r²/2), its centre at the height of the
/// face plus its radius, while the crate, its corners sticking on the floor (μ = 0.5 holds the 2.9 N the can drags it
/// with), does not move; both algebras. Stood upright and dropped 5 cm, the can meets the face with its whole lower
/// rim, and the run stops there with an error naming the rim.
#[test]
fn a_can_rolls_on_a_crate_and_one_landing_upright_stops_the_run() {
    let text = r#"title = "a can on a crate"
algebra = "both"
tolerance = 1e-12
duration = 0.4

[[body]]
name = "crate"
mass = 10.0
shape = { kind = "cuboid", size = [1.0, 1.0, 0.2] }
collision = [{ kind = "box", size = [1.0, 1.0, 0.2] }]
initial = { position = [0.0, 0.0, 0.1] }
forces = [{ kind = "gravity" }]

[[body]]
name = "can"
mass = 1.0
principal_moments = [0.00395833333333333, 0.00395833333333333, 0.00125]
collision = [{ kind = "cylinder", radius = 0.05, length = 0.2 }]
initial = { position = [0.0, 0.0, 0.25], orientation = { axis = [0.0, 1.0, 0.0], degrees = 90.0 }, velocity = [0.0, 1.0, 0.0] }
forces = [{ kind = "gravity" }]

[[plane]]
name = "floor"
friction = 0.5

[[collision]]
bodies = ["can", "crate"]
friction = 0.3
"#;
    let (v0, mu, g) = (1.0, 0.3, 9.81);
    let stop = v0 / (3.0 * mu * g);
    let scene = Scene::parse(text).unwrap();
    fn check<A: FileAlgebra>(scene: &Scene, v0: f64, mu: f64, g: f64, stop: f64) {
        let run = scene.simulate::<A>().unwrap();
        let stuck: Vec<_> = (run.transitions.iter())
            .filter(|t| t.constraint.starts_with("can / crate: can cylinder 1 cap"))
            .filter(|t| matches!(t.change, dynamics::limits::LimitChange::Stuck { .. }))
            .collect();
        assert_eq!(stuck.len(), 2, "{:?}", run.transitions);
        for t in &stuck {
            assert!(
                (t.t - stop).abs() < 1e-12,
                "{}: {} s, {stop} s exact",
                t.constraint,
                t.t
            );
        }
        for (crate_box, can) in run.body(0).iter().zip(run.body(1)) {
            let speed = if can.t < stop {
                v0 - mu * g * can.t
            } else {
                2.0 * v0 / 3.0
            };
            assert!(
                (can.velocity - Vector3::y() * speed).norm() < 1e-10,
                "t = {}: {}",
                can.t,
                can.velocity
            );
            assert!(
                (can.position.z - 0.25).abs() < 1e-12,
                "t = {}: {}",
                can.t,
                can.position.z
            );
            let moved = (crate_box.position - Vector3::z() * 0.1).norm();
            assert!(moved < 1e-12, "t = {}: the crate moved {moved:e} m", crate_box.t);
        }
    }
    check::<Pga>(&scene, v0, mu, g, stop);
    check::<Cga>(&scene, v0, mu, g, stop);
    let upright = text.replace(
        "position = [0.0, 0.0, 0.25], orientation = { axis = [0.0, 1.0, 0.0], degrees = 90.0 }, velocity = [0.0, 1.0, 0.0]",
        "position = [0.0, 0.0, 0.35]",
    );
    assert_ne!(upright, text);
    let error = Scene::parse(&upright)
        .unwrap()
        .simulate::<Pga>()
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        error.contains("can / crate: can cylinder 1 cap 1 on crate box 1 face") && error.contains("lies flat"),
        "{error}"
    );
}
