//! Scene files with a `[robot]`, force elements, drives and the universal and fixed joints (docs/scene-files.md):
//!
//! * in the shipped UR5-with-a-paddle file (a robot, an extra body on a driven hinge, a spring-damper, joint damping
//!   and a PD controller) the energy change equals the recorded work of the force elements and the drive;
//! * joint coordinates are zero where docs/scene-files.md says, drives are followed exactly, joints to robot links
//!   sit in the links' frames, universal and fixed joints hold;
//! * every new key with its careless inputs (NaN, zero, negative, huge, wrong length or type, unknown joint or link
//!   names, a missing file, an empty URDF, a massless moving link with and without the freeze repair) fails with a
//!   message naming the entry and the value: one row of a table each.
//!
//! The shipped robot files' runs against Pinocchio's are report's `scene_job_robots.rs`. Each test prints what it
//! measures (`cargo test --release -p scene-file --test integration robots:: -- --nocapture`).

use std::cell::RefCell;
use std::ops::ControlFlow;
use std::path::PathBuf;

use dynamics::simulate::{Plan, Sample};
use dynamics::{Cga, Pga, State};
use nalgebra::{UnitQuaternion, Vector3};
use scenarios::trajectory;
use scene_file::{FileAlgebra, Scene};

pub(super) fn scenes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

pub(super) fn robots() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../reference/data/robots")
}

/// A fresh folder in the temporary directory.
pub(super) fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene-file-robots-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The energy and the work along a run of `scene`: the largest |E(t) − E₀ − W(t)| at the samples with W the recorded
/// work (`Sample::work`: the force elements' and the drives'), the largest |W|, and, independently, the work of the
/// driven joint `driven` (if any), `∫ τ_drive q̇ dt` by Simpson's rule over the steps, with τ_drive the drive's
/// generalised force `[M q̈ + h]` at its coordinate (no actuator acts on it).
fn energy_balance<A: FileAlgebra>(scene: &Scene, driven: Option<&str>) -> (f64, f64, f64) {
    let system = scene.system::<A>().expect("the scene builds");
    let mechanism = system.mechanism();
    let schedule = &scene.checked().schedule;
    let slot = driven.map(|name| {
        let group = mechanism
            .joint_space()
            .unwrap()
            .group(name)
            .expect("the driven joint")
            .clone();
        (group.velocity_offset(), group)
    });
    let drive_power = |t: f64, states: &[State<A>]| -> f64 {
        let Some((k, _)) = &slot else { return 0.0 };
        let accelerations = mechanism.joint_accelerations(t, states).unwrap();
        let tau = mechanism.inverse_dynamics(t, states, &accelerations).unwrap();
        tau[*k] * mechanism.joint_velocities(states).unwrap()[*k]
    };
    let start = (
        mechanism.energy(system.initial()).expect("one state per body"),
        drive_power(0.0, system.initial()),
    );
    let seen = RefCell::new(vec![(0.0, start.0, start.1)]);
    let observer = |t: f64, states: &[State<A>]| {
        seen.borrow_mut().push((
            t,
            mechanism.energy(states).expect("one state per body"),
            drive_power(t, states),
        ));
        ControlFlow::Continue(())
    };
    let integrator = dynamics::Integrator::from(scene.checked().integrator);
    let run = dynamics::simulate(
        mechanism,
        system.initial(),
        integrator,
        Plan::new(schedule).observer(observer),
    )
    .expect("the scene runs");
    let seen = seen.into_inner();
    let steps = seen.len() - 1;
    assert_eq!(steps, schedule.step_count());
    // The elements' work at the samples, by time.
    let samples = &run.bodies[0];
    let per_sample = schedule.steps_per_sample().expect("dt divides the sample interval");
    let mut drive_work = 0.0;
    let mut worst = 0.0f64;
    let mut largest_work = 0.0f64;
    for pair in (0..steps).step_by(2) {
        let h = seen[pair + 2].0 - seen[pair].0;
        drive_work += h / 6.0 * (seen[pair].2 + 4.0 * seen[pair + 1].2 + seen[pair + 2].2);
        let step = pair + 2;
        if step % per_sample == 0 {
            let sample = &samples[step / per_sample];
            assert!((sample.t - seen[step].0).abs() < 1e-12);
            let change = seen[step].1 - start.0;
            worst = worst.max((change - sample.work).abs());
            largest_work = largest_work.max(sample.work.abs());
        }
    }
    (worst, largest_work, drive_work)
}

/// The shipped UR5 with a paddle: a PD controller with gravity compensation, joint damping on the elbow, a
/// spring-damper from the paddle to the world and the paddle's driven hinge. The energy changes by the recorded work
/// of the force elements and the drive (`Sample::work`, integrated by the method): E(t) − E₀ = W(t) at every sample to
/// 1e-9 J over 2 s, where the work is of order 1 J and the drive's alone, by Simpson's rule on the steps from its
/// generalised force, is −0.44 J (measured, both algebras: 3.2e-13 J; without the drive, the paddle swinging free,
/// 5.7e-13 J).
#[test]
fn energy_change_equals_the_work_in_the_damped_driven_scene() {
    let path = scenes().join("ur5_paddle.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let driven = Scene::load(&path).unwrap();
    let drive_line = text
        .lines()
        .find(|l| l.starts_with("drive = "))
        .expect("the drive")
        .to_owned();
    let free = Scene::parse_in(&text.replace(&drive_line, ""), &scenes()).expect("without the drive");
    for (label, scene, joint) in [("driven", &driven, Some("paddle_hinge")), ("free", &free, None)] {
        for (algebra, (worst, work, drive)) in [
            ("PGA", energy_balance::<Pga>(scene, joint)),
            ("CGA", energy_balance::<Cga>(scene, joint)),
        ] {
            println!(
                "{label} paddle, {algebra}: |E(t) − E₀ − W(t)| ≤ {worst:.1e} J, work up to {work:.2} J (the drive's {drive:.3} J)"
            );
            assert!(worst < 1e-9, "{label}, {algebra}: {worst:e} J");
            assert!(work > 0.1, "{label}, {algebra}: the elements do work ({work} J)");
            assert!(
                joint.is_none() || drive.abs() > 0.1,
                "{label}, {algebra}: the drive does work ({drive} J)"
            );
        }
    }
}

/// A single-body file with one joint to the world, `joint` its lines, the body at `orientation` with `spin` (rad/s,
/// body axes).
fn one_joint(joint: &str, orientation: &str, spin: [f64; 3]) -> String {
    format!(
        r#"
algebra = "pga"
integrator = "rkmk6-body"
dt = 1e-3
duration = 0.5
[[body]]
name = "arm"
mass = 1.0
shape = {{ kind = "cuboid", size = [0.1, 0.2, 0.4] }}
initial = {{ position = [0.0, 0.0, 0.0], orientation = {orientation}, body_angular_velocity = {spin:?} }}
[[joint]]
name = "j"
between = ["arm", "world"]
{joint}
"#
    )
}

/// The joint coordinates of a file's system at its start (after the projection).
fn start_coordinates(text: &str) -> Vec<f64> {
    let scene = Scene::parse(text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let system = scene.system::<Pga>().unwrap();
    system.mechanism().joint_positions(system.initial(), None).unwrap()
}

/// Coordinates are zero where docs/scene-files.md says: a hinge's angle is the turn about the reference axis after the
/// smallest rotation taking the body axis onto it (here body z onto world x: a quarter turn about y), a prismatic
/// joint's slide is along the reference axis from the reference point, a universal joint's angles turn about the
/// reference axis and then the body axis.
#[test]
fn joint_coordinates_are_zero_where_documented() {
    let hinge = "kind = \"hinge\"\nbody_point = [0.0, 0.0, 0.0]\nbody_axis = [0.0, 0.0, 2.0]\n\
                 reference_point = [0.0, 0.0, 0.0]\nreference_axis = [3.0, 0.0, 0.0]";
    // Rot(x, 0.3) after Rot(y, 90°) (which takes body z to world x).
    let turned = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.3)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2);
    let q = turned.quaternion();
    let orientation = format!("{{ quaternion = [{:?}, {:?}, {:?}, {:?}] }}", q.w, q.i, q.j, q.k);
    let q = start_coordinates(&one_joint(hinge, &orientation, [0.0; 3]));
    assert!((q[0] - 0.3).abs() < 1e-15, "hinge: {q:?}");
    let straight = start_coordinates(&one_joint(
        hinge,
        "{ axis = [0.0, 1.0, 0.0], degrees = 90.0 }",
        [0.0; 3],
    ));
    assert!(straight[0].abs() < 1e-15, "hinge: {straight:?}");

    let prismatic = "kind = \"prismatic\"\nbody_point = [0.0, 0.0, 0.0]\nbody_axis = [1.0, 0.0, 0.0]\n\
                     body_normal = [0.0, 0.0, 1.0]\nreference_point = [0.2, 0.0, 0.0]\nreference_axis = [1.0, 0.0, 0.0]\n\
                     reference_normal = [0.0, 0.0, 1.0]";
    let text = one_joint(prismatic, "{ axis = [1.0, 0.0, 0.0], angle = 0.0 }", [0.0; 3])
        .replace("position = [0.0, 0.0, 0.0]", "position = [0.7, 0.0, 0.0]");
    let slide = start_coordinates(&text);
    assert!((slide[0] - 0.5).abs() < 1e-15, "prismatic: {slide:?}");

    // Written normal: zero with the body's axes along the world's; q₁ about world x, then q₂ about body y.
    let universal = "kind = \"universal\"\nbody_point = [0.0, 0.0, 0.2]\nbody_axis = [0.0, 1.0, 0.0]\n\
                     reference_point = [0.0, 0.0, 0.0]\nreference_axis = [1.0, 0.0, 0.0]";
    let turned = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.4)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -0.7);
    let q = turned.quaternion();
    let orientation = format!("{{ quaternion = [{:?}, {:?}, {:?}, {:?}] }}", q.w, q.i, q.j, q.k);
    let angles = start_coordinates(&one_joint(universal, &orientation, [0.0; 3]));
    assert!(
        (angles[0] - 0.4).abs() < 1e-14 && (angles[1] + 0.7).abs() < 1e-14,
        "universal: {angles:?}"
    );
}

/// A driven hinge and a driven slider follow their paths exactly: the coordinate at every sample is the prescribed
/// value (the articulated solve takes the prescribed acceleration; the drive's value and rate are imposed at the
/// start; after that the coordinate is integrated, not projected onto the drive). Measured over 1 s, both
/// formulations: 1.8e-13 rad (3 rad/s), 8.5e-16 m (sine).
#[test]
fn drives_are_followed() {
    for (joint, drive, exact) in [
        (
            "kind = \"hinge\"\nbody_point = [0.0, 0.0, 0.2]\nbody_axis = [1.0, 0.0, 0.0]\n\
             reference_point = [0.0, 0.0, 0.0]\nreference_axis = [1.0, 0.0, 0.0]",
            "drive = { kind = \"constant_rate\", start = 0.5, rate = 3.0 }",
            (|t: f64| 0.5 + 3.0 * t) as fn(f64) -> f64,
        ),
        (
            "kind = \"prismatic\"\nbody_point = [0.0, 0.0, 0.0]\nbody_axis = [0.0, 0.0, 1.0]\n\
             body_normal = [1.0, 0.0, 0.0]\nreference_point = [0.0, 0.0, 0.0]\nreference_axis = [0.0, 0.0, 1.0]\n\
             reference_normal = [1.0, 0.0, 0.0]",
            "drive = { kind = \"sine\", offset = 0.1, amplitude = 0.2, frequency = 2.0, phase = 0.3 }",
            |t: f64| 0.1 + 0.2 * (std::f64::consts::TAU * 2.0 * t + 0.3).sin(),
        ),
    ] {
        for formulation in ["virtual_power", "pinning"] {
            let text = one_joint(
                &format!("{joint}\nformulation = \"{formulation}\"\n{drive}"),
                "{ axis = [1.0, 0.0, 0.0], angle = 0.0 }",
                [0.0; 3],
            )
            .replace("duration = 0.5", "duration = 1.0")
            .replace("name = \"arm\"", "name = \"arm\"\nforces = [{ kind = \"gravity\" }]");
            let scene = Scene::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
            let system = scene.system::<Pga>().unwrap();
            let run = scene.simulate::<Pga>().unwrap();
            let mut worst = 0.0f64;
            for sample in run.body(0) {
                let state = State::from_world_twist(
                    dynamics::Dynamics::body(system.mechanism(), 0),
                    sample.position,
                    &sample.orientation,
                    sample.angular_velocity,
                    sample.velocity,
                );
                let q = system.mechanism().joint_positions(&[state], None).unwrap()[0];
                let mut error = q - exact(sample.t);
                error -= std::f64::consts::TAU * (error / std::f64::consts::TAU).round();
                worst = worst.max(error.abs());
            }
            println!("{drive} ({formulation}): the coordinate within {worst:.1e} of the drive");
            assert!(worst < 1e-10, "{drive}, {formulation}: {worst:e}");
        }
    }
}

/// A body on a ball joint at a point of a robot link: the link's frame places the point. The UR5's `base_link` is the
/// world frame and its `base` link is turned half a turn about z, so the reference point (1, 0, 0) of `base` is the
/// world point (−1, 0, 0); and a body welded to `ee_link` moves as one welded to `wrist_3_link` at `ee_link`'s pose
/// there (x, y, z = 0, 0.0823, 0; a quarter turn about z), to round-off.
#[test]
fn joints_to_robot_links_sit_in_the_links_frames() {
    let arm = |body: &str, joints: &str| {
        format!(
            r#"
algebra = "both"
dt = 5e-3
duration = 0.5
[robot]
urdf = "ur5_robot.urdf"
q = {{ shoulder_lift_joint = -1.0, elbow_joint = 0.8 }}
v = {{ shoulder_pan_joint = 0.5, wrist_3_joint = 2.0 }}
{body}
{joints}
"#
        )
    };
    let bob = "[[body]]\nname = \"bob\"\nmass = 0.3\nshape = { kind = \"sphere\", radius = 0.05 }\n\
               forces = [{ kind = \"gravity\" }]\ninitial = { position = [-1.0, 0.0, -0.3] }";
    let hung = arm(
        bob,
        "[[joint]]\nname = \"pivot\"\nbetween = [\"bob\", \"base\"]\nkind = \"ball_joint\"\n\
         body_point = [0.0, 0.0, 0.3]\nreference_point = [1.0, 0.0, 0.0]",
    );
    let scene = Scene::parse_in(&hung, &robots()).unwrap_or_else(|e| panic!("{e}"));
    let run = scene.simulate::<Pga>().unwrap();
    let worst = run
        .body(6)
        .iter()
        .map(|s| (s.position + s.orientation * Vector3::new(0.0, 0.0, 0.3) - Vector3::new(-1.0, 0.0, 0.0)).norm())
        .fold(0.0, f64::max);
    println!("ball joint at the link `base`: the pivot within {worst:.1e} m of (−1, 0, 0)");
    assert!(worst < 1e-12, "{worst:e} m");

    let welded = |link: &str, pose: &str| {
        arm(
            &bob.replace("initial = { position = [-1.0, 0.0, -0.3] }", ""),
            &format!("[[joint]]\nname = \"weld\"\nbetween = [\"bob\", \"{link}\"]\nkind = \"fixed\"\n{pose}"),
        )
    };
    let on_ee = welded(
        "ee_link",
        "position = [0.1, 0.0, 0.0]\norientation = { axis = [0.0, 0.0, 1.0], degrees = 0.0 }",
    );
    // The URDF writes the quarter turn as 1.57079632679 rad.
    let on_wrist = welded(
        "wrist_3_link",
        "position = [0.0, 0.1823, 0.0]\norientation = { axis = [0.0, 0.0, 1.0], angle = 1.57079632679 }",
    );
    let runs: Vec<_> = [on_ee, on_wrist]
        .iter()
        .map(|text| {
            Scene::parse_in(text, &robots())
                .unwrap_or_else(|e| panic!("{e}"))
                .simulate::<Cga>()
                .unwrap()
        })
        .collect();
    let (angle, distance) = differences(runs[0].body(6), runs[1].body(6));
    println!("welded to ee_link and to wrist_3_link at ee_link's pose: {angle:.1e} rad, {distance:.1e} m apart");
    assert!(angle < 1e-12 && distance < 1e-12, "{angle:e} rad, {distance:e} m");
}

/// Universal and fixed joints between two moving bodies hold to round-off and conserve the energy, in both algebras
/// (a fixed joint in both formulations; a universal joint by virtual power, the only form it has). The universal's
/// body axis is written at 60° to the reference axis: its zero turns it into the normal plane. Measured (RK4,
/// dt = 1e-3, 0.5 s): joints within 3.4e-16 m, energy within 9.2e-13 relative.
#[test]
fn universal_and_fixed_joints_hold() {
    for (joint, formulation) in [
        (
            "kind = \"universal\"\nbody_point = [0.0, 0.0, 0.2]\nbody_axis = [0.5, 0.8660254037844386, 0.0]\n\
             reference_point = [0.0, 0.0, -0.2]\nreference_axis = [1.0, 0.0, 0.0]",
            "virtual_power",
        ),
        ("kind = \"fixed\"", "virtual_power"),
        ("kind = \"fixed\"", "pinning"),
        (
            "kind = \"fixed\"\nposition = [0.0, 0.0, -0.45]\norientation = { axis = [0.0, 0.0, 1.0], degrees = 10.0 }",
            "pinning",
        ),
    ] {
        for algebra in ["pga", "cga"] {
            let text = format!(
                r#"
algebra = "{algebra}"
dt = 1e-3
duration = 0.5
[[body]]
name = "upper"
mass = 1.0
shape = {{ kind = "cuboid", size = [0.1, 0.1, 0.4] }}
initial = {{ position = [0.0, 0.0, -0.2], body_angular_velocity = [1.0, 0.5, 0.0] }}
forces = [{{ kind = "gravity" }}]
[[body]]
name = "lower"
mass = 0.5
shape = {{ kind = "cuboid", size = [0.1, 0.1, 0.4] }}
initial = {{ position = [0.0, 0.0, -0.6], body_angular_velocity = [0.0, 2.0, 3.0] }}
forces = [{{ kind = "gravity" }}]
[[joint]]
name = "shoulder"
between = ["upper", "world"]
kind = "ball_joint"
body_point = [0.0, 0.0, 0.2]
world_point = [0.0, 0.0, 0.0]
[[joint]]
name = "under test"
between = ["lower", "upper"]
formulation = "{formulation}"
{joint}
"#
            );
            let scene = Scene::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
            let (bodies, violation) = match algebra {
                "pga" => violation_run::<Pga>(&scene),
                _ => violation_run::<Cga>(&scene),
            };
            let drift = (bodies[0].last().unwrap().energy - bodies[0][0].energy).abs() / bodies[0][0].energy.abs();
            let kind = joint.lines().next().unwrap();
            println!("{kind} ({formulation}, {algebra}): joint within {violation:.1e}, energy {drift:.1e}");
            assert!(
                violation < 1e-12 && drift < 1e-9,
                "{kind}, {formulation}, {algebra}: {violation:e}, {drift:e}"
            );
        }
    }
}

/// The run's samples and the largest joint violation over them.
fn violation_run<A: FileAlgebra>(scene: &Scene) -> (Vec<Vec<dynamics::simulate::Sample>>, f64) {
    let system = scene.system::<A>().unwrap();
    let run = scene.simulate::<A>().unwrap();
    let worst = (0..run.bodies[0].len())
        .map(|k| {
            let poses: Vec<_> = run.bodies.iter().map(|b| (b[k].position, b[k].orientation)).collect();
            system.joint_violation(&poses, None)
        })
        .fold(0.0, f64::max);
    (run.bodies, worst)
}

/// A small arm: a base, a link on a revolute `shoulder` (damping 0.5, friction 0.1), a `sensor` link on a continuous
/// `spin` joint below it (of 0.1 kg), and a `finger` on a prismatic joint that mimics nothing.
const ARM: &str = include_str!("../data/arm.urdf");

/// [`ARM`] with a massless `sensor`.
const ARM_MASSLESS_SENSOR: &str = include_str!("../data/arm_massless_sensor.urdf");

/// A scene of the arm in `dir` (URDF `arm.urdf`), `robot` the `[robot]` table's further lines.
fn arm_scene(robot: &str) -> String {
    format!("dt = 1e-3\nduration = 0.2\nalgebra = \"pga\"\n[robot]\nurdf = \"arm.urdf\"\n{robot}\n")
}

/// Mimics: coupled by default (a follower's start value contradicting its leader is refused, with the importer's
/// numbers), independent joints with `mimic = "independent"`.
#[test]
fn mimics_are_coupled_or_independent() {
    let dir = fresh("mimic");
    std::fs::write(
        dir.join("arm.urdf"),
        ARM.replace(
            "<limit lower=\"-0.1\" upper=\"0.1\" effort=\"10\" velocity=\"1\"/></joint>",
            "<limit lower=\"-0.1\" upper=\"0.1\" effort=\"10\" velocity=\"1\"/><mimic joint=\"shoulder\" multiplier=\"0.1\"/></joint>",
        ),
    )
    .unwrap();
    let coupled = Scene::parse_in(&arm_scene("q = { shoulder = 0.5, slide = 0.2 }"), &dir)
        .unwrap_err()
        .to_string();
    assert!(
        coupled.contains("`slide` follows `shoulder`") && coupled.contains("0.2 given, 0.05 implied"),
        "{coupled}"
    );
    let scene = Scene::parse_in(
        &arm_scene("mimic = \"independent\"\nq = { shoulder = 0.5, slide = 0.2 }"),
        &dir,
    )
    .expect("independent joints");
    let q = scene
        .system::<Pga>()
        .unwrap()
        .mechanism()
        .joint_positions(scene.system::<Pga>().unwrap().initial(), None)
        .unwrap();
    assert!((q[0] - 0.5).abs() < 1e-15 && (q[2] - 0.2).abs() < 1e-15, "{q:?}");
}

/// The heart of the careless-input table: a robot file using every new key (`[robot]` with every key but the base's,
/// a driven hinge to a link, a universal joint, a fixed joint, a spring, a couple, a joint torque, joint damping and
/// a PD controller), the UR5's URDF beside it.
const FIXED: &str = r#"
dt = 1e-3
duration = 0.01
[robot]
urdf = "ur5_robot.urdf"
root = "fixed"
mimic = "constraint"
joint_dynamics = "urdf"
limits = "ignore"
gravity = [0.0, 0.0, -9.81]
q = { shoulder_lift_joint = -1.2, elbow_joint = 1.0 }
v = { shoulder_pan_joint = 0.3 }
torque = { wrist_1_joint = 0.5 }
repairs = { massless_subtrees = "error", bound_mass = 1e-3, bound_inertia = 1e-6, balance_inertia = false }
[[body]]
name = "paddle"
mass = 0.5
shape = { kind = "cuboid", size = [0.02, 0.1, 0.3] }
forces = [{ kind = "gravity" }]
[[body]]
name = "bob"
mass = 0.2
shape = { kind = "sphere", radius = 0.05 }
initial = { position = [0.5, 0.5, 0.5] }
[[body]]
name = "tag"
mass = 0.1
shape = { kind = "cuboid", size = [0.05, 0.05, 0.01] }
[[joint]]
name = "hinge"
between = ["paddle", "tool0"]
kind = "hinge"
body_point = [0.0, 0.0, -0.15]
body_axis = [1.0, 0.0, 0.0]
reference_point = [0.0, 0.0, 0.05]
reference_axis = [1.0, 0.0, 0.0]
drive = { kind = "sine", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }
[[joint]]
name = "cardan"
between = ["bob", "paddle"]
kind = "universal"
body_point = [0.0, 0.0, 0.1]
body_axis = [0.0, 1.0, 0.0]
reference_point = [0.0, 0.0, 0.15]
reference_axis = [1.0, 0.0, 0.0]
[[joint]]
name = "weld"
between = ["tag", "wrist_2_link"]
kind = "fixed"
position = [0.0, 0.0, 0.1]
orientation = { axis = [0.0, 0.0, 1.0], degrees = 30.0 }
[[spring]]
between = ["bob", "world"]
points = [[0.0, 0.0, 0.0], [0.5, 0.3, 0.9]]
stiffness = 20.0
damping = 0.5
rest_length = 0.2
[[couple]]
between = ["tag", "bob"]
moment = [0.0, 0.0, 0.01]
[[joint_torque]]
joint = "wrist_2_joint"
torque = { kind = "sine", offset = 0.0, amplitude = 0.2, frequency = 2.0, phase = 0.0 }
[[joint_damping]]
joint = "elbow_joint"
damping = 2.0
[[pd]]
name = "hold"
kp = 100.0
kd = 2.0
gravity_compensation = true
target = { shoulder_pan_joint = 0.3, elbow_joint = 1.0 }
"#;

/// The free-root counterpart: Solo-12 with every base key.
const FREE: &str = r#"
dt = 5e-3
duration = 0.01
[robot]
urdf = "solo12.urdf"
root = "free"
base_position = [0.0, 0.0, 0.3]
base_orientation = { axis = [0.0, 0.0, 1.0], degrees = 20.0 }
base_velocity = [0.1, -0.2, 0.3]
base_angular_velocity = [0.5, -0.4, 0.3]
q = { FL_KFE = -0.5 }
"#;

#[test]
fn the_careless_input_bases_parse() {
    let enforced = FIXED.replace("limits = \"ignore\"", "limits = \"enforce\"\nlimit_restitution = 0.5");
    for base in [FIXED, FREE, &enforced] {
        let scene = Scene::parse_in(base, &robots()).unwrap_or_else(|e| panic!("{e}"));
        scene.simulate::<Pga>().expect("runs");
        scene.simulate::<Cga>().expect("runs");
    }
}

/// A careless input: in the base text, `from` replaced by `to`, and the parts its message must mention (the entry and
/// the value).
pub(super) type Row<'a> = (&'a str, &'a str, &'a str, &'a [&'a str]);

/// Every row's text (a robot's URDF relative to the robots' folder) fails with a message that contains every one of
/// its parts; the rows that do not are listed together.
pub(super) fn assert_each_refused(rows: &[Row]) {
    let mut failures = Vec::new();
    for (base, from, to, parts) in rows {
        assert!(base.contains(from), "{from:?} is not in the base");
        let text = base.replacen(from, to, 1);
        match Scene::parse_in(&text, &robots()) {
            Ok(_) => failures.push(format!("{from:?} → {to:?} parsed")),
            Err(error) => {
                let message = error.to_string();
                if let Some(part) = parts.iter().find(|p| !message.contains(**p)) {
                    failures.push(format!("{from:?} → {to:?}: {message:?} does not mention {part:?}"));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} rows:\n{}",
        failures.len(),
        rows.len(),
        failures.join("\n")
    );
    println!(
        "{} careless inputs, each refused naming the entry and the value",
        rows.len()
    );
}

/// A shipped scene file's text.
pub(super) fn shipped(name: &str) -> String {
    std::fs::read_to_string(scenes().join(name)).unwrap()
}

/// A free root that cannot move freely is refused naming what it lacks: mass, or (with mass) its moments of inertia.
#[test]
fn a_free_root_is_refused_naming_what_it_lacks() {
    let dir = fresh("free-root");
    for (mass, moments, lacks) in [
        ("1", "0", "give its links moments of inertia"),
        ("0", "0", "give its links mass"),
    ] {
        let link = format!(
            "<robot name=\"r\"><link name=\"base\"><inertial><mass value=\"{mass}\"/><inertia ixx=\"{moments}\" \
             ixy=\"0\" ixz=\"0\" iyy=\"{moments}\" iyz=\"0\" izz=\"{moments}\"/></inertial></link></robot>"
        );
        std::fs::write(dir.join("lone.urdf"), link).unwrap();
        let text = "dt = 1e-3\nduration = 0.01\n[robot]\nurdf = \"lone.urdf\"\nroot = \"free\"\n";
        let error = Scene::parse_in(text, &dir).unwrap_err().to_string();
        assert!(error.contains("root body `base`") && error.contains(lacks), "{error}");
    }
}

/// The `[robot]` table's keys with their careless inputs ([`FIXED`] and [`FREE`] edited), a missing, empty,
/// massless, weightless, lopsided or 100 000 elements deep URDF among them (their repairs named as the file writes
/// them).
#[test]
fn careless_robot_keys_fail_naming_the_entry_and_the_value() {
    let dir = fresh("careless");
    std::fs::write(dir.join("empty.urdf"), "").unwrap();
    std::fs::write(dir.join("massless.urdf"), ARM_MASSLESS_SENSOR).unwrap();
    // A massless link with mass below it, and a link whose moments no mass distribution has.
    let link = "<mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.002\"/></inertial></link>\n  <link name=\"sensor\">";
    assert!(ARM.contains(link));
    let weightless = link
        .replace("value=\"1\"", "value=\"0\"")
        .replace("0.01", "0")
        .replace("0.002", "0");
    std::fs::write(dir.join("weightless.urdf"), ARM.replace(link, &weightless)).unwrap();
    std::fs::write(
        dir.join("lopsided.urdf"),
        ARM.replace(link, &link.replace("0.002", "0.05")),
    )
    .unwrap();
    let [weightless, lopsided] =
        ["weightless", "lopsided"].map(|n| dir.join(format!("{n}.urdf")).display().to_string());
    let nested = format!(
        "<robot name=\"r\"><link name=\"base\"/>{}{}</robot>",
        "<a>".repeat(100_000),
        "</a>".repeat(100_000)
    );
    std::fs::write(dir.join("nested.urdf"), nested).unwrap();
    let nested = dir.join("nested.urdf").display().to_string();
    let ur5 = robots().join("ur5_robot.urdf").display().to_string();
    let solo = robots().join("solo12.urdf").display().to_string();
    let empty = dir.join("empty.urdf").display().to_string();
    let massless = dir.join("massless.urdf").display().to_string();
    let urdf = "urdf = \"ur5_robot.urdf\"";
    #[rustfmt::skip]
    let rows: &[Row] = &[
        // robot.urdf: missing, a folder, empty, a massless moving link, wrong type, wrong value.
        (FIXED, urdf, "urdf = \"no_such.urdf\"", &["robot.urdf", "cannot read", "no_such.urdf", "No such file"]),
        (FIXED, urdf, "urdf = \".\"", &["robot.urdf", "cannot read"]),
        (FIXED, urdf, "urdf = \"\"", &["robot.urdf", "cannot read"]),
        (FIXED, urdf, &format!("urdf = {empty:?}"), &["robot.urdf", "empty.urdf", "the URDF text is empty"]),
        (FIXED, urdf, &format!("urdf = {nested:?}"), &["robot.urdf", "nested.urdf", "nested more than 256 deep at line 1"]),
        (FREE, "urdf = \"solo12.urdf\"", &format!("urdf = {massless:?}"), &["robot.urdf", "massless.urdf", "joint `spin`", "links `sensor`", "mass 0 kg", "`repairs = { massless_subtrees = \"freeze\" }` in [robot]"]),
        // The repairs each message suggests are the file's keys, not the library's options.
        (FREE, "urdf = \"solo12.urdf\"", &format!("urdf = {weightless:?}"), &["joint `shoulder`", "mass 0 kg", "`repairs = { bound_mass = …, bound_inertia = … }`"]),
        (FREE, "urdf = \"solo12.urdf\"", &format!("urdf = {lopsided:?}"), &["link `link`", "triangle inequality", "`repairs = { balance_inertia = true }` in [robot]"]),
        (FIXED, urdf, "urdf = 3", &["invalid type: integer `3`", "expected a string"]),
        (FIXED, urdf, &format!("urdf = {:?}", ur5.replace("ur5_robot", "solo12")), &["joint hinge: between", "no body named \"tool0\"", "base_link"]),
        // root, mimic, joint_dynamics, limits.
        (FIXED, "root = \"fixed\"", "root = \"floating\"", &["unknown variant `floating`", "`fixed`", "`free`"]),
        (FIXED, "root = \"fixed\"", "root = 1", &["line 6", "root = 1", "wanted string or table"]),
        (FIXED, "mimic = \"constraint\"", "mimic = \"ignore\"", &["unknown variant `ignore`", "`independent`"]),
        (FIXED, "joint_dynamics = \"urdf\"", "joint_dynamics = \"friction\"", &["unknown variant `friction`", "`ignore`"]),
        // limit_restitution: NaN, negative, above 1, infinite, wrong type, without enforced limits; a start outside an
        // enforced limit (the UR5's elbow is limited to ±π).
        (FIXED, "limits = \"ignore\"", "limits = \"enforce\"\nlimit_restitution = nan", &["robot.limit_restitution", "NaN", "[0, 1]"]),
        (FIXED, "limits = \"ignore\"", "limits = \"enforce\"\nlimit_restitution = -0.5", &["robot.limit_restitution", "-0.5", "[0, 1]"]),
        (FIXED, "limits = \"ignore\"", "limits = \"enforce\"\nlimit_restitution = 1.5", &["robot.limit_restitution", "1.5", "[0, 1]"]),
        (FIXED, "limits = \"ignore\"", "limits = \"enforce\"\nlimit_restitution = inf", &["robot.limit_restitution", "inf", "[0, 1]"]),
        (FIXED, "limits = \"ignore\"", "limits = \"enforce\"\nlimit_restitution = [0.5]", &["invalid type: sequence", "expected f64"]),
        (FIXED, "limits = \"ignore\"", "limits = \"ignore\"\nlimit_restitution = 0.5", &["robot.limit_restitution", "enforced limits only"]),
        (FIXED, "limits = \"ignore\"\ngravity = [0.0, 0.0, -9.81]\nq = { shoulder_lift_joint = -1.2, elbow_joint = 1.0 }", "limits = \"enforce\"\ngravity = [0.0, 0.0, -9.81]\nq = { shoulder_lift_joint = -1.2, elbow_joint = 4.0 }", &["robot.q.elbow_joint", "4.0", "outside the joint's limits", "3.14159265359"]),
        (FIXED, "limits = \"ignore\"", "limits = \"clip\"", &["unknown variant `clip`"]),
        // gravity: NaN, huge, wrong length, wrong type.
        (FIXED, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, nan, -9.81]", &["robot.gravity", "NaN", "not finite"]),
        (FIXED, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -1e300]", &["robot.gravity", "-1e300", "beyond 1e50"]),
        (FIXED, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, -9.81]", &["invalid length 2"]),
        (FIXED, "gravity = [0.0, 0.0, -9.81]", "gravity = -9.81", &["invalid type: floating point `-9.81`"]),
        // q, v, torque: unknown names, NaN, huge, wrong type, a joint that is not there in the robot.
        (FIXED, "q = { shoulder_lift_joint = -1.2,", "q = { shoulder_lift = -1.2,", &["robot.q", "no joint named `shoulder_lift`", "shoulder_lift_joint, elbow_joint"]),
        (FIXED, "elbow_joint = 1.0 }\nv", "elbow_joint = nan }\nv", &["robot.q.elbow_joint", "NaN"]),
        (FIXED, "elbow_joint = 1.0 }\nv", "elbow_joint = 1e300 }\nv", &["robot.q.elbow_joint", "1e300", "beyond 1e50"]),
        (FIXED, "q = { shoulder_lift_joint = -1.2, elbow_joint = 1.0 }", "q = [1.0, 2.0]", &["invalid type: sequence", "expected a map"]),
        (FIXED, "q = { shoulder_lift_joint = -1.2, elbow_joint = 1.0 }", "q = { elbow_joint = \"bent\" }", &["invalid type: string \"bent\"", "expected f64"]),
        (FIXED, "v = { shoulder_pan_joint = 0.3 }", "v = { ee_fixed_joint = 0.3 }", &["robot.v", "no joint named `ee_fixed_joint`"]),
        (FIXED, "v = { shoulder_pan_joint = 0.3 }", "v = { shoulder_pan_joint = -inf }", &["robot.v.shoulder_pan_joint", "-inf"]),
        (FIXED, "torque = { wrist_1_joint = 0.5 }", "torque = { wrist_9_joint = 0.5 }", &["robot.torque", "no joint named `wrist_9_joint`"]),
        (FIXED, "torque = { wrist_1_joint = 0.5 }", "torque = { wrist_1_joint = nan }", &["robot.torque.wrist_1_joint", "NaN"]),
        // The base: refused for a fixed root; NaN, zero quaternion, wrong length for a free one.
        (FIXED, "root = \"fixed\"", "root = \"fixed\"\nbase_position = [0.0, 0.0, 1.0]", &["robot.base_position", "fixed to the world", "root = \"free\""]),
        (FIXED, "root = \"fixed\"", "root = \"fixed\"\nbase_angular_velocity = [0.0, 0.0, 1.0]", &["robot.base_angular_velocity", "fixed to the world"]),
        (FREE, "base_velocity = [0.1, -0.2, 0.3]", "base_velocity = [0.1, nan, 0.3]", &["robot.base_velocity", "NaN"]),
        (FREE, "base_position = [0.0, 0.0, 0.3]", "base_position = [0.0, 0.3]", &["invalid length 2"]),
        (FREE, "base_position = [0.0, 0.0, 0.3]", "base_position = [0.0, 0.0, inf]", &["robot.base_position", "inf"]),
        (FREE, "base_orientation = { axis = [0.0, 0.0, 1.0], degrees = 20.0 }", "base_orientation = { quaternion = [0.0, 0.0, 0.0, 0.0] }", &["robot.base_orientation", "zero"]),
        (FREE, "base_orientation = { axis = [0.0, 0.0, 1.0], degrees = 20.0 }", "base_orientation = { axis = [0.0, 0.0, 0.0], degrees = 20.0 }", &["robot.base_orientation.axis", "no direction"]),
        (FREE, "base_angular_velocity = [0.5, -0.4, 0.3]", "base_angular_velocity = [0.5, -0.4, 0.3, 0.0]", &["invalid length 4"]),
        (FREE, "urdf = \"solo12.urdf\"", &format!("urdf = {:?}", solo.replace("solo12.urdf", "nope.urdf")), &["robot.urdf", "nope.urdf"]),
        // repairs.
        (FIXED, "bound_mass = 1e-3", "bound_mass = -1.0", &["robot.repairs.bound_mass", "-1", "positive"]),
        (FIXED, "bound_mass = 1e-3", "bound_mass = 0.0", &["robot.repairs.bound_mass", "0 must be positive"]),
        (FIXED, "bound_inertia = 1e-6", "bound_inertia = nan", &["robot.repairs.bound_inertia", "NaN"]),
        (FIXED, "bound_inertia = 1e-6", "bound_inertia = 1e300", &["robot.repairs.bound_inertia", "1e300"]),
        (FIXED, "massless_subtrees = \"error\"", "massless_subtrees = \"melt\"", &["unknown variant `melt`", "`freeze`"]),
        (FIXED, "balance_inertia = false", "balance_inertia = \"yes\"", &["invalid type: string \"yes\"", "expected a boolean"]),
        (FIXED, "balance_inertia = false", "balance = false", &["unknown field `balance`"]),
    ];
    assert_each_refused(rows);
}

/// Bodies and joints beside a robot, the universal and fixed joints, drives and limits, with their careless inputs.
#[test]
fn careless_joints_fail_naming_the_entry_and_the_value() {
    #[rustfmt::skip]
    let rows: &[Row] = &[
        // Bodies and joints with the robot: link names, held links, name clashes, the single [body] layout.
        (FIXED, "between = [\"paddle\", \"tool0\"]", "between = [\"paddle\", \"tool9\"]", &["joint hinge: between", "no body named \"tool9\"", "tool0", "wrist_3_link"]),
        (FIXED, "between = [\"paddle\", \"tool0\"]", "between = [\"tool0\", \"paddle\"]", &["joint hinge: between", "held body", "tool0"]),
        (FIXED, "name = \"tag\"", "name = \"ee_link\"", &["body ee_link", "robot has a link of this name"]),
        (FIXED, "name = \"weld\"", "name = \"elbow_joint\"", &["joint elbow_joint", "robot has a joint of this name"]),
        (FREE, "q = { FL_KFE = -0.5 }", "q = { FL_KFE = -0.5 }\n[body]\nmass = 1.0\nshape = { kind = \"sphere\", radius = 0.1 }", &["body", "with a [robot]", "[[body]] entries"]),
        // The universal joint: along, zero, by pinning, NaN.
        (FIXED, "body_axis = [0.0, 1.0, 0.0]", "body_axis = [2.0, 0.0, 0.0]", &["joint cardan: body_axis", "along the reference axis"]),
        (FIXED, "body_axis = [0.0, 1.0, 0.0]", "body_axis = [0.0, 0.0, 0.0]", &["constraint cardan: body_axis", "no direction"]),
        (FIXED, "body_axis = [0.0, 1.0, 0.0]", "body_axis = [0.0, nan, 0.0]", &["constraint cardan: body_axis", "NaN"]),
        (FIXED, "kind = \"universal\"", "kind = \"universal\"\nformulation = \"pinning\"", &["cardan", "no pinned form", "virtual_power"]),
        (FIXED, "kind = \"universal\"", "kind = \"universal\"\nbody_normal = [1.0, 0.0, 0.0]", &["unknown field `body_normal`"]),
        // The fixed joint: NaN, zero quaternion, wrong length, a drive.
        (FIXED, "position = [0.0, 0.0, 0.1]", "position = [0.0, nan, 0.1]", &["constraint weld: position", "NaN"]),
        (FIXED, "position = [0.0, 0.0, 0.1]", "position = [0.0, 0.1]", &["invalid length 2"]),
        (FIXED, "orientation = { axis = [0.0, 0.0, 1.0], degrees = 30.0 }", "orientation = { quaternion = [0.0, 0.0, 0.0, 0.0] }", &["constraint weld: orientation", "zero"]),
        (FIXED, "orientation = { axis = [0.0, 0.0, 1.0], degrees = 30.0 }", "orientation = { axis = [0.0, 0.0, 1.0], degrees = inf }", &["constraint weld: orientation", "inf", "not finite"]),
        (FIXED, "kind = \"fixed\"", "kind = \"fixed\"\ndrive = { kind = \"constant_rate\", rate = 1.0 }", &["joint weld: drive", "only hinge and prismatic", "fixed joint"]),
        // The drive: kinds, NaN, negative, huge, missing, and on a joint that is not a joint model.
        (FIXED, "drive = { kind = \"sine\",", "drive = { kind = \"square\",", &["unknown variant `square`", "`constant_rate`"]),
        (FIXED, "frequency = 1.0, phase", "frequency = -1.0, phase", &["joint hinge: drive.frequency", "-1.0 Hz is negative"]),
        (FIXED, "amplitude = 0.6", "amplitude = nan", &["joint hinge: drive.amplitude", "NaN"]),
        (FIXED, "amplitude = 0.6", "amplitude = 1e300", &["joint hinge: drive", "amplitude 1e300", "beyond 1e50"]),
        (FIXED, "amplitude = 0.6, ", "", &["missing field `amplitude`"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "drive = { kind = \"constant_rate\", start = 0.0, rate = inf }", &["joint hinge: drive.rate", "inf"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "drive = { kind = \"constant_rate\", start = 1e50, rate = 1e49 }", &["joint hinge: drive", "reaches", "beyond 1e50"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "drive = 0.6", &["invalid type: floating point `0.6`"]),
        (FIXED, "kind = \"universal\"", "kind = \"universal\"\ndrive = { kind = \"constant_rate\", rate = 1.0 }", &["joint cardan: drive", "universal joint"]),
        // The limit: NaN, inverted, no bound, restitution out of [0, 1], unknown key, wrong type, on a universal and a
        // fixed joint, on a driven joint, and a start outside it.
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { lower = nan, upper = 1.0 }", &["joint hinge: limit", "NaN"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { lower = 1.0, upper = -1.0 }", &["joint hinge: limit", "lower < upper", "[1, -1]"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { restitution = 0.5 }", &["joint hinge: limit", "needs a lower or an upper bound"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { lower = -1.0, restitution = 2.0 }", &["joint hinge: limit", "restitution", "2"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { lower = -1.0, restitution = -inf }", &["joint hinge: limit", "restitution", "-inf"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { lower = -1.0, upper = 1.0, stiffness = 1.0 }", &["unknown field `stiffness`"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = [-1.0, 1.0]", &["invalid type: sequence", "expected a map"]),
        (FIXED, "kind = \"universal\"", "kind = \"universal\"\nlimit = { lower = -1.0 }", &["joint cardan: limit", "only revolute and prismatic joints can be limited", "universal"]),
        (FIXED, "kind = \"fixed\"", "kind = \"fixed\"\nlimit = { upper = 1.0 }", &["joint weld: limit", "only revolute and prismatic joints can be limited"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }\nlimit = { lower = -1.0, upper = 1.0 }", &["joint hinge: limit", "driven joint cannot be limited"]),
        (FIXED, "drive = { kind = \"sine\", offset = 0.0, amplitude = 0.6, frequency = 1.0, phase = 0.0 }", "limit = { lower = 0.5, upper = 1.0 }", &["joint hinge: limit", "the start puts the joint at", "outside [0.5, 1.0]"]),
    ];
    assert_each_refused(rows);
}

/// The force elements and the integrator with their careless inputs.
#[test]
fn careless_force_elements_fail_naming_the_entry_and_the_value() {
    #[rustfmt::skip]
    let rows: &[Row] = &[
        // The spring: names, points, stiffness, damping, rest length.
        (FIXED, "between = [\"bob\", \"world\"]", "between = [\"bob\", \"moon\"]", &["spring spring 1: between", "no body named \"moon\""]),
        (FIXED, "between = [\"bob\", \"world\"]", "between = [\"world\", \"base_link\"]", &["spring spring 1: between", "same body"]),
        (FIXED, "between = [\"bob\", \"world\"]", "between = [\"bob\"]", &["invalid length 1"]),
        (FIXED, "points = [[0.0, 0.0, 0.0], [0.5, 0.3, 0.9]]", "points = [[0.0, 0.0, 0.0]]", &["invalid length 1"]),
        (FIXED, "points = [[0.0, 0.0, 0.0], [0.5, 0.3, 0.9]]", "points = [[0.0, 0.0, 0.0], [0.5, nan, 0.9]]", &["spring spring 1: points", "NaN"]),
        (FIXED, "stiffness = 20.0", "stiffness = -20.0", &["spring spring 1: stiffness", "-20", "non-negative"]),
        (FIXED, "stiffness = 20.0", "stiffness = nan", &["spring spring 1: stiffness", "NaN"]),
        (FIXED, "damping = 0.5\nrest", "damping = -0.5\nrest", &["spring spring 1: damping", "-0.5"]),
        (FIXED, "rest_length = 0.2", "rest_length = 1e300", &["spring spring 1: rest_length", "1e300", "at most 1e50"]),
        (FIXED, "rest_length = 0.2", "", &["missing field `rest_length`"]),
        // The couple.
        (FIXED, "moment = [0.0, 0.0, 0.01]", "moment = [0.0, 0.0, nan]", &["couple couple 1: moment", "NaN"]),
        (FIXED, "between = [\"tag\", \"bob\"]", "between = [\"tag\", \"tag\"]", &["couple couple 1: between", "same body"]),
        (FIXED, "moment = [0.0, 0.0, 0.01]", "moment = 0.01", &["invalid type: floating point `0.01`"]),
        // Joint torques and damping: unknown joints, NaN, negative, the wrong kind of joint.
        (FIXED, "joint = \"wrist_2_joint\"", "joint = \"wrist_22\"", &["joint_torque torque on wrist_22: joint", "no joint named `wrist_22`", "wrist_2_joint"]),
        (FIXED, "joint = \"wrist_2_joint\"", "joint = \"hinge\"", &["joint_torque torque on hinge: joint", "`hinge` is driven"]),
        (FIXED, "joint = \"wrist_2_joint\"", "joint = \"cardan\"", &["joint_torque torque on cardan: joint", "universal joint, with 2 coordinates"]),
        (FIXED, "amplitude = 0.2", "amplitude = inf", &["joint_torque torque on wrist_2_joint: torque.amplitude", "inf"]),
        (FIXED, "torque = { kind = \"sine\", offset = 0.0, amplitude = 0.2, frequency = 2.0, phase = 0.0 }", "torque = nan", &["joint_torque torque on wrist_2_joint: torque", "NaN"]),
        (FIXED, "torque = { kind = \"sine\", offset = 0.0, amplitude = 0.2, frequency = 2.0, phase = 0.0 }", "torque = \"strong\"", &["invalid type: string \"strong\"", "a number"]),
        (FIXED, "joint = \"elbow_joint\"", "joint = \"elbow\"", &["joint_damping damping on elbow: joint", "no joint named `elbow`"]),
        (FIXED, "damping = 2.0", "damping = -2.0", &["joint_damping damping on elbow_joint: damping", "-2"]),
        (FIXED, "joint = \"elbow_joint\"", "joint = \"weld\"", &["joint_damping damping on weld: joint", "fixed joint", "no coordinates"]),
        // The PD controller.
        (FIXED, "kp = 100.0", "kp = -100.0", &["pd hold: kp", "-100"]),
        (FIXED, "kd = 2.0", "kd = nan", &["pd hold: kd", "NaN"]),
        (FIXED, "kp = 100.0", "kp = 1e300", &["pd hold: kp", "1e300"]),
        (FIXED, "target = { shoulder_pan_joint = 0.3, elbow_joint = 1.0 }", "target = { shoulder = 0.3 }", &["pd hold: target", "no joint named `shoulder`"]),
        (FIXED, "target = { shoulder_pan_joint = 0.3, elbow_joint = 1.0 }", "target = { elbow_joint = nan }", &["pd hold: target.elbow_joint", "NaN"]),
        (FIXED, "target = { shoulder_pan_joint = 0.3, elbow_joint = 1.0 }", "target = {}", &["pd hold: target", "names no joint"]),
        (FIXED, "target = { shoulder_pan_joint = 0.3, elbow_joint = 1.0 }", "target = { hinge = 0.1 }", &["pd hold: target", "`hinge` is driven"]),
        (FIXED, "gravity_compensation = true", "gravity_compensation = 1", &["invalid type: integer `1`", "expected a boolean"]),
        (FIXED, "name = \"hold\"", "name = \"\"", &["name", "must not be empty"]),
        (FIXED, "name = \"hold\"", "name = \"spring 1\"", &["force element \"spring 1\"", "two force elements have this name"]),
        // The integrator: the splittings run free bodies only.
        (FIXED, "dt = 1e-3", "dt = 1e-3\nintegrator = \"strang\"", &["integrator", "splitting method"]),
        (FIXED, "dt = 1e-3", "dt = 1e-3\nintegrator = \"rkmk8-joint\"\nstabilisation = \"baumgarte\"", &["integrator", "joint coordinates", "Baumgarte"]),
        (FIXED, "dt = 1e-3", "dt = 1e-3\nintegrator = \"euler\"", &["unknown variant `euler`", "`rkmk8-joint`"]),
        (FIXED, "dt = 1e-3", "tolerance = 1e-8\nintegrator = \"dop853-joint\"\nstabilisation = \"baumgarte\"", &["integrator", "joint coordinates", "Baumgarte"]),
        (FIXED, "dt = 1e-3", "tolerance = 1e-8\nintegrator = \"rkmk8-joint\"", &["integrator", "RKMK8-joint", "error estimate"]),
        (FIXED, "dt = 1e-3", "tolerance = nan\nintegrator = \"dop853-joint\"", &["tolerance", "NaN"]),
    ];
    assert_each_refused(rows);
}

/// `[[contact]]` with its careless inputs (the shipped bouncing block edited).
#[test]
fn careless_contacts_fail_naming_the_entry_and_the_value() {
    let block = shipped("bouncing_block.toml");
    let first = "[[contact]]\npoint = [-0.1, -0.1, -0.1]\nrestitution = 0.5";
    #[rustfmt::skip]
    let rows: &[Row] = &[
        // [[contact]]: points, normals, offsets and restitutions NaN, infinite, huge or out of range, wrong lengths
        // and types, unknown keys, an unknown body, the world, an empty or repeated name, a start below the floor,
        // Baumgarte stabilisation.
        (&block, first, "[[contact]]\npoint = [nan, -0.1, -0.1]", &["contact contact 1", "must be finite"]),
        (&block, first, "[[contact]]\npoint = [2e6, -0.1, -0.1]", &["contact contact 1", "within 1e6"]),
        (&block, first, "[[contact]]\npoint = [-0.1, -0.1]", &["invalid length 2"]),
        (&block, first, "[[contact]]\npoint = -0.1", &["invalid type: floating point"]),
        (&block, first, &format!("{first}\nnormal = [0.0, 0.0, 0.0]"), &["contact contact 1", "the normal"]),
        (&block, first, &format!("{first}\nnormal = [0.0, inf, 1.0]"), &["contact contact 1", "the normal"]),
        (&block, first, &format!("{first}\noffset = nan"), &["contact contact 1", "must be finite"]),
        (&block, first, &format!("{first}\noffset = -1e7"), &["contact contact 1", "within 1e6"]),
        (&block, first, "[[contact]]\npoint = [-0.1, -0.1, -0.1]\nrestitution = 1.5", &["contact contact 1", "restitution", "1.5"]),
        (&block, first, "[[contact]]\npoint = [-0.1, -0.1, -0.1]\nrestitution = -0.1", &["contact contact 1", "restitution", "-0.1"]),
        (&block, first, "[[contact]]\npoint = [-0.1, -0.1, -0.1]\nrestitution = nan", &["contact contact 1", "restitution", "NaN"]),
        // Friction and spheres: coefficients negative, NaN, huge, of the wrong type, static below kinetic; a sphere's
        // radius zero, negative, NaN or huge, its centre far away or of the wrong length, unknown keys, a sphere and a
        // point together or neither, a start with the sphere below the floor.
        (&block, first, &format!("{first}\nfriction = -0.1"), &["contact contact 1", "kinetic coefficient", "-0.1"]),
        (&block, first, &format!("{first}\nfriction = nan"), &["contact contact 1", "kinetic coefficient", "NaN"]),
        (&block, first, &format!("{first}\nfriction = 1e7"), &["contact contact 1", "kinetic coefficient", "1e6"]),
        (&block, first, &format!("{first}\nfriction = \"high\""), &["invalid type: string \"high\"", "expected f64"]),
        (&block, first, &format!("{first}\nfriction = 0.3\nstatic_friction = 0.1"), &["contact contact 1", "static coefficient 0.1 is below the kinetic one 0.3"]),
        (&block, first, &format!("{first}\nstatic_friction = inf"), &["contact contact 1", "static coefficient", "inf"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0], radius = 0.0 }", &["contact contact 1", "radius must be positive", "got 0"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0], radius = -0.1 }", &["contact contact 1", "radius must be positive", "-0.1"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0], radius = nan }", &["contact contact 1", "radius must be positive", "NaN"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0], radius = 1e7 }", &["contact contact 1", "radius", "within 1e6"]),
        (&block, first, "[[contact]]\nsphere = { centre = [2e6, 0.0, 0.0], radius = 0.1 }", &["contact contact 1", "within 1e6"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0], radius = 0.1 }", &["invalid length 2"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0], radius = 0.1, colour = 1 }", &["unknown field `colour`"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0] }", &["missing field `radius`"]),
        (&block, first, "[[contact]]\nsphere = 0.1", &["invalid type: floating point `0.1`"]),
        (&block, first, &format!("{first}\nsphere = {{ centre = [0.0, 0.0, 0.0], radius = 0.1 }}"), &["contact contact 1", "one of `point`, `sphere` and `disk`"]),
        (&block, first, "[[contact]]\nrestitution = 0.5", &["contact contact 1", "give the `point = [x, y, z]`, the `sphere", "the `disk"]),
        // Disks: a radius zero, negative, NaN or huge; an axis zero, NaN, infinite or of the wrong length; a centre far
        // away; unknown or missing keys; a disk with a point or a sphere; a start with the rim below the floor.
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 0.0 }", &["contact contact 1", "disk's radius must be positive", "got 0"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = -0.1 }", &["contact contact 1", "disk's radius", "-0.1"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = nan }", &["contact contact 1", "disk's radius", "NaN"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 1e7 }", &["contact contact 1", "disk's radius", "within 1e6"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 0.0], radius = 0.1 }", &["contact contact 1", "disk's axis", "not zero"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [nan, 0.0, 1.0], radius = 0.1 }", &["contact contact 1", "disk's axis", "NaN"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [0.0, inf, 1.0], radius = 0.1 }", &["contact contact 1", "disk's axis", "inf"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0], radius = 0.1 }", &["invalid length 2"]),
        (&block, first, "[[contact]]\ndisk = { centre = [2e6, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 0.1 }", &["contact contact 1", "within 1e6"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], radius = 0.1 }", &["missing field `axis`"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 0.1, width = 1 }", &["unknown field `width`"]),
        (&block, first, &format!("{first}\ndisk = {{ centre = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 0.1 }}"), &["contact contact 1", "one of `point`, `sphere` and `disk`"]),
        (&block, first, "[[contact]]\ndisk = { centre = [0.0, 0.0, -0.6], axis = [1.0, 0.0, 0.0], radius = 0.1 }", &["contact contact 1", "the start puts its disk", "below its plane"]),
        (&block, first, "[[contact]]\nsphere = { centre = [0.0, 0.0, 0.0], radius = 0.6 }", &["contact contact 1", "the start puts its sphere", "below its plane"]),
        (&block, first, &format!("{first}\nbody = \"moon\""), &["contact contact 1: body", "no body named \"moon\""]),
        (&block, first, &format!("{first}\nbody = \"world\""), &["contact contact 1: body", "the world has no point"]),
        (&block, first, &format!("{first}\nname = \"\""), &["contact : ", "non-empty name"]),
        (&block, first, &format!("{first}\nname = \"contact 2\""), &["contact contact 2", "already named"]),
        (&block, "position = [0.0, 0.0, 0.5]", "position = [0.0, 0.0, 0.05]", &["contact contact", "below its plane"]),
        (&block, "stabilisation = \"projection\"", "stabilisation = \"baumgarte\"", &["contact contact 1", "need the articulated solve"]),
    ];
    assert_each_refused(rows);
}

/// Points on surfaces and curves with their careless inputs (the shipped surface scenes edited).
#[test]
fn careless_surfaces_fail_naming_the_entry_and_the_value() {
    let torus = shipped("bead_on_torus.toml");
    let rod = shipped("rod_on_ellipsoid.toml");
    let table = shipped("turntable_pendulum.toml");
    let ring = "surface = { kind = \"torus\", centre = [0.0, 0.0, 1.0], axis = [0.3, 0.0, 1.0], major_radius = 1.0, minor_radius = 0.3 }";
    let egg = "radii = [1.2, 0.8, 0.5], orientation = { axis = [0.0, 1.0, 0.0], degrees = 15.0 } }";
    let curve = "kind = \"point_on_curve\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]";
    #[rustfmt::skip]
    let rows: &[Row] = &[
        // point_on_surface and point_on_curve: every surface kind's parameters NaN, zero, negative, huge, of the wrong
        // length or type, unknown kinds and keys, orientation given twice, a curve of one or three surfaces, a start at
        // a singular point or where the surfaces are tangent, a drive on a surface joint.
        (&torus, "kind = \"torus\"", "kind = \"donut\"", &["unknown variant `donut`", "`ellipsoid`", "`torus`"]),
        (&torus, "minor_radius = 0.3", "minor_radius = nan", &["constraint", "surface.minor_radius", "NaN"]),
        (&torus, "minor_radius = 0.3", "minor_radius = 1.0", &["surface.minor_radius", "below the major radius", "ring torus"]),
        (&torus, "major_radius = 1.0", "major_radius = -1.0", &["surface.major_radius", "-1", "positive"]),
        (&torus, "major_radius = 1.0", "major_radius = 1e7", &["surface.major_radius", "within 1e6"]),
        (&torus, "axis = [0.3, 0.0, 1.0]", "axis = [0.0, 0.0, 0.0]", &["surface.axis", "no direction"]),
        (&torus, "axis = [0.3, 0.0, 1.0]", "axis = [0.3, 1.0]", &["invalid length 2"]),
        (&torus, "centre = [0.0, 0.0, 1.0]", "centre = [0.0, 0.0, 2e6]", &["surface.centre", "within 1e6"]),
        (&torus, "centre = [0.0, 0.0, 1.0], axis", "centre = [0.0, 0.0, 1.0], colour = 1, axis", &["unknown field `colour`"]),
        (&torus, ring, "surface = 3", &["invalid type: integer `3`"]),
        (&torus, ring, "", &["missing field `surface`"]),
        (&torus, "body_point = [0.0, 0.0, 0.0]", "body_point = [0.0, nan, 0.0]", &["body_point", "NaN"]),
        (&torus, ring, "surface = { kind = \"plane\", normal = [0.0, 0.0, 0.0], offset = 1.0 }", &["surface.normal", "no direction"]),
        (&torus, ring, "surface = { kind = \"plane\", normal = [0.0, 0.0, 1.0], offset = nan }", &["surface.offset", "NaN"]),
        (&torus, ring, "surface = { kind = \"quadric\", coefficients = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0] }", &["invalid length 9"]),
        (&torus, ring, "surface = { kind = \"quadric\", coefficients = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0] }", &["surface.coefficients", "no first- or second-order term"]),
        (&torus, ring, "surface = { kind = \"quadric\", coefficients = [1e13, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0] }", &["surface.coefficients", "within 1e12"]),
        (&torus, ring, "surface = { kind = \"hyperboloid\", radii = [1.0, 1.0, 1.0], sheets = 3 }", &["surface.sheets", "3 is not 1 or 2"]),
        (&torus, ring, "surface = { kind = \"quadric\", coefficients = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0] }", &["surface.coefficients", "has no real points"]),
        (&torus, ring, "surface = { kind = \"quadric\", coefficients = [1.0, 1.0, 0.0, 0.0, 0.0, 0.0, -2.0, 0.0, 0.0, 1.0] }", &["surface.coefficients", "only singular real points"]),
        (&torus, ring, "surface = { kind = \"quadric\", coefficients = [-1.0, -1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1e-12] }", &["surface.coefficients", "has no real points"]),
        (&torus, ring, "surface = { kind = \"cone\", radii = [1.0, 1.0], centre = [1.190287161857, 0.368691212106, 0.819765066149] }", &["no normal", "singular point"]),
        (&rod, egg, "radii = [1.2, 0.0, 0.5] }", &["surface.radii", "positive"]),
        (&rod, egg, "radii = [1.2, nan, 0.5] }", &["surface.radii", "NaN"]),
        (&rod, egg, "radii = [1.2, 1e7, 0.5] }", &["surface.radii", "within 1e6"]),
        (&rod, egg, "radii = [1.2, 0.8] }", &["invalid length 2"]),
        (&rod, "{ axis = [0.0, 1.0, 0.0], degrees = 15.0 } }", "{ quaternion = [0.0, 0.0, 0.0, 0.0] } }", &["surface.orientation", "zero"]),
        (&rod, "{ axis = [0.0, 1.0, 0.0], degrees = 15.0 } }", "{ axis = [0.0, 1.0, 0.0], degrees = 15.0 }, axis = [0.0, 0.0, 1.0] }", &["surface", "not both"]),
        (&rod, "{ axis = [0.0, 1.0, 0.0], degrees = 15.0 } }", "{ axis = [0.0, 1.0, 0.0], degrees = inf } }", &["surface.orientation", "inf", "not finite"]),
        (&rod, egg, "radii = [1.2, 0.8, 0.5], axis = [0.0, 0.0, 0.0] }", &["surface.axis", "no direction"]),
        (&rod, egg, "radii = [1.2, 0.8, 0.5], centre = [nan, 0.0, 0.0] }", &["surface.centre", "NaN"]),
        (&rod, egg, "radii = [1.2, 0.8, 0.5], centre = [-3e6, 0.0, 0.0] }", &["surface.centre", "within 1e6"]),
        (&rod, "kind = \"ellipsoid\", radii", "kind = \"paraboloid\", hyperbolic = 1, radii", &["invalid type: integer `1`", "expected a boolean"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"plane\", normal = [0.0, 0.0, 1.0], offset = 0.8 }}]"), &["surfaces", "1 given", "exactly two surfaces"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = []"), &["surfaces", "0 given"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"sphere\", radius = 1.0 }}, {{ kind = \"plane\", normal = [0.0, 0.0, 1.0], offset = 0.8 }}]"), &["unknown variant `sphere`"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"plane\", normal = [0.0, 0.0, 1.0], offset = 0.819765066149 }}, {{ kind = \"plane\", normal = [0.0, 0.0, 2.0], offset = 1.639530132298 }}]"), &["no curve in common", "one plane"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0], centre = [1.190287161857, 0.368691212106, 1.819765066149] }}, {{ kind = \"ellipsoid\", radii = [2.0, 2.0, 0.5], centre = [1.190287161857, 0.368691212106, 1.319765066149] }}]"), &["tangent", "rank 1"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0], centre = [1.190287161857, 0.368691212106, 1.819765066149] }}, {{ kind = \"ellipsoid\", radii = [2.0, 1.0, 1.0], centre = [1.190287161857, 0.368691212106, 4.819765066149] }}]"), &["do not meet near it", "may not meet at all"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0] }}, {{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0], centre = [3.0, 0.0, 0.0] }}]"), &["constraint 1 (point on curve)", "no curve in common", "do not meet", "centres are 3 m apart"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0] }}, {{ kind = \"ellipsoid\", radii = [2.0, 2.0, 2.0], centre = [1.0, 0.0, 0.0] }}]"), &["no curve in common", "touch at one point"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), "kind = \"point_on_curve\"\nformulation = \"virtual_power\"\nbody_point = [0.0, 0.0, 0.0]\nsurfaces = [{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0] }, { kind = \"plane\", normal = [0.0, 0.0, 2.0], offset = 3.0 }]", &["no curve in common", "0.5 m from the plane"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"plane\", normal = [0.0, 0.0, 1.0], offset = 1.0 }}, {{ kind = \"plane\", normal = [0.0, 0.0, -3.0], offset = 1.5 }}]"), &["no curve in common", "parallel, 1.5 m apart"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0] }}, {{ kind = \"ellipsoid\", radii = [1.0, 1.0, 1.0] }}]"), &["no curve in common", "one sphere"]),
        (&torus, &format!("kind = \"point_on_surface\"\nformulation = \"pinning\"\nbody_point = [0.0, 0.0, 0.0]\n{ring}"), &format!("{curve}\nsurfaces = [{{ kind = \"plane\", normal = [0.0, 0.0, 1.0], offset = nan }}, {{ kind = \"plane\", normal = [1.0, 0.0, 0.0], offset = 1.19 }}]"), &["surfaces[0].offset", "NaN"]),
        (&table, "kind = \"point_on_surface\"", "kind = \"point_on_surface\"\ndrive = { kind = \"constant_rate\", rate = 1.0 }", &["joint rider: drive", "only hinge and prismatic"]),
    ];
    assert_each_refused(rows);
}

/// The same keys with values that are careless but valid run: zero gravity, zero gains, zero stiffness and damping, a
/// zero rest length, a zero drive amplitude, negative targets and torques.
#[test]
fn careless_but_valid_values_run() {
    #[rustfmt::skip]
    let cases: &[(&str, &str)] = &[
        ("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, 0.0]"),
        ("kp = 100.0", "kp = 0.0"),
        ("kd = 2.0", "kd = 0.0"),
        ("stiffness = 20.0", "stiffness = 0.0"),
        ("rest_length = 0.2", "rest_length = 0.0"),
        ("amplitude = 0.6", "amplitude = 0.0"),
        ("torque = { wrist_1_joint = 0.5 }", "torque = { wrist_1_joint = -0.5 }"),
        ("elbow_joint = 1.0 }\nv", "elbow_joint = -7.0 }\nv"),
        ("mimic = \"constraint\"", "mimic = \"independent\""),
        ("joint_dynamics = \"urdf\"", "joint_dynamics = \"ignore\""),
        ("balance_inertia = false", "balance_inertia = true"),
        ("dt = 1e-3", "dt = 1e-3\nintegrator = \"rk4\"\nstabilisation = \"none\""),
    ];
    for (from, to) in cases {
        assert!(FIXED.contains(from), "{from:?} is not in the base");
        let text = FIXED.replacen(from, to, 1);
        let scene = Scene::parse_in(&text, &robots()).unwrap_or_else(|e| panic!("{from} → {to}: {e}"));
        scene.simulate::<Pga>().unwrap_or_else(|e| panic!("{from} → {to}: {e}"));
    }
}

/// The largest orientation (rad) and position (m) difference between two runs of one body, by the metrics of the
/// `reference` crate.
fn differences(first: &[Sample], second: &[Sample]) -> (f64, f64) {
    let (first, second) = (trajectory(first).unwrap(), trajectory(second).unwrap());
    let errors = reference::metrics::trajectory_errors(&first, &second).unwrap();
    (errors.max_orientation, errors.max_position)
}

/// Collision shapes and `[[plane]]`s with their careless inputs (the shipped shapes scene edited): sizes zero,
/// negative, NaN or huge, wrong lengths, unknown kinds and keys, a cylinder reaching below the floor, hulls of too few,
/// coplanar, malformed or too many points, a missing or malformed mesh, a plane with no shape or shapes with no
/// plane, a plane's careless coefficients and normal, a start where a shape is below the plane.
#[test]
fn careless_collision_shapes_and_planes_fail_naming_the_entry_and_the_value() {
    let dir = fresh("careless-shapes");
    std::fs::write(dir.join("not_a_mesh.stl"), "solid nothing\nthis is not STL").unwrap();
    let missing = dir.join("missing.stl").display().to_string();
    let malformed = dir.join("not_a_mesh.stl").display().to_string();
    let many: Vec<String> = (0..300)
        .map(|k| {
            let (a, b) = (k as f64 * 0.7, k as f64 * 1.3);
            format!(
                "[{}, {}, {}]",
                0.1 * a.cos() * b.sin(),
                0.1 * a.sin() * b.sin(),
                0.1 * b.cos()
            )
        })
        .collect();
    let many = format!("collision = [{{ kind = \"convex\", points = [{}] }}]", many.join(", "));
    let scene = shipped("shapes_on_a_floor.toml");
    let crate_box = "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2] }]";
    let pill = "collision = [{ kind = \"capsule\", radius = 0.05, length = 0.2,";
    let gem = "collision = [{ kind = \"convex\", points = [[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, -0.1, 0.0], [0.0, 0.0, 0.15], [0.0, 0.0, -0.15], [0.0, 0.0, 0.0]] }]";
    let floor = "[[plane]]\nname = \"floor\"";
    let missing_mesh = format!("collision = [{{ kind = \"convex\", mesh = {missing:?} }}]");
    let malformed_mesh = format!("collision = [{{ kind = \"convex\", mesh = {malformed:?} }}]");
    #[rustfmt::skip]
    let rows: &[Row] = &[
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.0, 0.2] }]", &["body crate: collision 1: size", "positive", "got 0"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, -0.2, 0.2] }]", &["body crate: collision 1: size", "-0.2"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, nan, 0.2] }]", &["body crate: collision 1: size", "NaN"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 2e6, 0.2] }]", &["body crate: collision 1: size", "1e6"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.2] }]", &["invalid length 2"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2], position = [1e7, 0.0, 0.0] }]", &["body crate: collision 1: position", "within 1e6"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2], position = [inf, 0.0, 0.0] }]", &["body crate: collision 1: position", "not finite"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2], orientation = { axis = [0.0, 0.0, 0.0], degrees = 3.0 } }]", &["body crate: collision 1: orientation", "no direction"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.2], colour = 1 }]", &["unknown field `colour`"]),
        (&scene, crate_box, "collision = [{ kind = \"blob\", size = [0.2, 0.2, 0.2] }]", &["unknown variant `blob`", "`sphere`", "`convex`"]),
        (&scene, crate_box, "collision = [{ kind = \"sphere\", radius = 0.0 }]", &["body crate: collision 1: radius", "positive"]),
        (&scene, crate_box, "collision = [{ kind = \"sphere\", radius = -1.0 }]", &["body crate: collision 1: radius", "-1"]),
        (&scene, crate_box, "collision = [{ kind = \"sphere\", radius = 1e300 }]", &["body crate: collision 1: radius", "1e6"]),
        (&scene, crate_box, "collision = [{ kind = \"sphere\" }]", &["missing field `radius`"]),
        (&scene, crate_box, "collision = { kind = \"sphere\", radius = 0.1 }", &["invalid type: map", "expected a sequence"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 0.0, length = 0.2 }]", &["body crate: collision 1: radius", "positive", "got 0"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 0.1, length = -0.2 }]", &["body crate: collision 1: length", "-0.2"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 0.1, length = nan }]", &["body crate: collision 1: length", "NaN"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 1e300, length = 0.2 }]", &["body crate: collision 1: radius", "1e6"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 0.1 }]", &["missing field `length`"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 0.1, length = 0.2, position = [0.0, nan, 0.0] }]", &["body crate: collision 1: position", "not finite"]),
        (&scene, crate_box, "collision = [{ kind = \"cylinder\", radius = 0.1, length = 0.7 }]", &["contact floor: crate cylinder 1 cap 1", "the start puts its disk", "below its plane"]),
        (&scene, pill, "collision = [{ kind = \"capsule\", radius = 0.05, length = 0.0,", &["body pill: collision 1: length", "positive", "got 0"]),
        (&scene, pill, "collision = [{ kind = \"capsule\", radius = nan, length = 0.2,", &["body pill: collision 1: radius", "NaN"]),
        (&scene, gem, "collision = [{ kind = \"convex\", points = [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [-0.1, 0.0, 0.0]] }]", &["body gem: collision 1", "span no volume"]),
        (&scene, gem, "collision = [{ kind = \"convex\", points = [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [-0.1, 0.0, 0.0], [0.0, -0.1, 0.0], [0.05, 0.05, 0.0]] }]", &["body gem: collision 1", "span no volume", "one plane"]),
        (&scene, gem, "collision = [{ kind = \"convex\", points = [[0.1, 0.0], [0.0, 0.1, 0.0], [-0.1, 0.0, 0.0], [0.0, 0.0, 0.1]] }]", &["body gem: collision 1: points", "point 1 has 2 numbers"]),
        (&scene, gem, "collision = [{ kind = \"convex\", points = [[0.1, 0.0, nan], [0.0, 0.1, 0.0], [-0.1, 0.0, 0.0], [0.0, 0.0, 0.1]] }]", &["body gem: collision 1: points", "not finite"]),
        (&scene, gem, "collision = [{ kind = \"convex\", points = [[2e6, 0.0, 0.0], [0.0, 0.1, 0.0], [-0.1, 0.0, 0.0], [0.0, 0.0, 0.1]] }]", &["body gem: collision 1: points", "point 1 is beyond 1e6 m"]),
        (&scene, gem, "collision = [{ kind = \"convex\" }]", &["body gem: collision 1", "give the hull's `points` or a `mesh`"]),
        (&scene, gem, "collision = [{ kind = \"convex\", points = [[0.1, 0.0, 0.0]], mesh = \"gem.stl\" }]", &["body gem: collision 1", "not both"]),
        (&scene, gem, &missing_mesh, &["body gem: collision 1: mesh", "cannot read the mesh", "missing.stl"]),
        (&scene, gem, &malformed_mesh, &["body gem: collision 1: mesh", "not_a_mesh.stl"]),
        (&scene, gem, &many, &["body gem: collision 1", "more than 256"]),
        (&scene, floor, "[[plane]]\nname = \"floor\"\ncolour = 1", &["unknown field `colour`"]),
        (&scene, "friction = 0.5", "friction = -0.5", &["contact floor: crate box 1 corner 1", "kinetic coefficient", "-0.5"]),
        (&scene, "restitution = 0.3", "restitution = 2.0", &["contact floor: crate box 1 corner 1", "restitution", "2"]),
        (&scene, floor, "[[plane]]\nname = \"floor\"\nstatic_friction = 0.1", &["contact floor: crate box 1 corner 1", "static coefficient 0.1 is below the kinetic one 0.5"]),
        (&scene, "normal = [0.0, 0.0, 1.0]\noffset = 0.0", "normal = [0.0, 0.0, 0.0]\noffset = 0.0", &["contact floor: crate box 1 corner 1", "the normal"]),
        (&scene, "normal = [0.0, 0.0, 1.0]\noffset = 0.0", "normal = [0.0, 0.0, 1.0]\noffset = 0.25", &["contact floor: crate box 1 corner", "the start puts its point", "below its plane"]),
        (&scene, crate_box, "collision = [{ kind = \"box\", size = [0.2, 0.2, 0.7] }]", &["contact floor: crate box 1 corner", "below its plane"]),
        // A robot's `collisions`: an unknown value; URDF shapes with no plane; a plane where every URDF shape is a
        // mesh whose file is not there (Solo-12's, package:// addresses), so no shape is left to keep above it.
        (FREE, "root = \"free\"", "root = \"free\"\ncollisions = \"all\"", &["unknown variant `all`", "`none`", "`urdf`"]),
        (FREE, "root = \"free\"", "root = \"free\"\ncollisions = \"urdf\"", &["robot.collisions", "no [[plane]]"]),
        (FREE, "q = { FL_KFE = -0.5 }", "q = { FL_KFE = -0.5 }\ncollisions = \"urdf\"\n[[plane]]", &["plane 1", "no body has a collision shape", "could not be used", "solo_12_base.stl is not found"]),
        (&scene, floor, "[[not_a_plane]]\nname = \"floor\"", &["unknown field `not_a_plane`"]),
    ];
    assert_each_refused(rows);
    // A plane with no shape, and shapes with no plane.
    let bare = scene
        .replace(crate_box, "")
        .replace(
            &format!("{pill} orientation = {{ axis = [0.0, 1.0, 0.0], degrees = 60.0 }} }}]"),
            "",
        )
        .replace(gem, "")
        .replace("collision = [{ kind = \"cylinder\", radius = 0.05, length = 0.2 }]", "");
    assert!(!bare.contains("collision = ["), "{bare}");
    let message = Scene::parse_in(&bare, &robots())
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        message.contains("plane 1") && message.contains("no body has a collision shape"),
        "{message}"
    );
    let planeless = scene[..scene.find(floor).unwrap()].to_owned();
    let message = Scene::parse_in(&planeless, &robots())
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(message.contains("no [[plane]]"), "{message}");
}
