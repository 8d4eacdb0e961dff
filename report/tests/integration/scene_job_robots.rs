//! Scene files with a `[robot]` run by the scene job (docs/scene-files.md):
//!
//! * the shipped UR5 and Solo-12 files write joints CSVs with the columns of `reference/data/robots/*.csv` that match
//!   Pinocchio's runs there at every sample (both files read back), stepping the bodies or the joint coordinates;
//! * the paddle's summary states the work against the energy change and what of the URDF is not modelled;
//! * a massless moving link, frozen by the repair, is a constant column of the joints CSV, and the URDF's damping does
//!   the work the energy change equals;
//! * a robot link meets a table, and comes to rest on it;
//! * Solo-12 dropped onto a floor with friction lands on its four foot spheres and stands still on them (its base
//!   within 1e-9 m for 5 s), and pulled harder than friction holds, its feet slide.
//!
//! Each test prints what it measures (`cargo test --release -p report --test integration scene_job_robots:: -- --nocapture`).

use std::path::{Path, PathBuf};

use report::scene_job::run_scene_file;
use scene_file::Scene;

fn scenes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

fn robots() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../reference/data/robots")
}

/// A CSV file's header and rows, read as RFC 4180 says (the `csv` crate: quoted names, every row as long as the
/// header).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut reader = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let header = reader.headers().unwrap().iter().map(str::to_owned).collect();
    let rows = (reader.records())
        .map(|record| record.unwrap().iter().map(|v| v.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

/// A fresh folder in the temporary directory.
fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("report-scene-robots-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs a shipped robot file and compares its joints CSVs (both algebras) with the reference's, column by column at
/// every sample: the largest difference of the coordinates (rad, m) and of the energy (J).
fn against_reference(file: &str, reference: &str) -> [(f64, f64); 2] {
    let output = fresh(file);
    let summary = run_scene_file(&scenes().join(file), &output).expect("the file runs");
    assert_eq!(summary.runs.len(), 2);
    let (expected_header, expected) = read_csv(&robots().join(reference));
    let stem = file.trim_end_matches(".toml");
    ["pga", "cga"].map(|algebra| {
        let (header, rows) = read_csv(&output.join(format!("{stem}_joints_{algebra}.csv")));
        assert_eq!(header, expected_header, "{file}, {algebra}: the columns");
        assert_eq!(rows.len(), expected.len(), "{file}, {algebra}: the samples");
        let mut worst = (0.0f64, 0.0f64);
        for (ours, theirs) in rows.iter().zip(&expected) {
            assert!(
                (ours[0] - theirs[0]).abs() < 1e-12,
                "t {} against {}",
                ours[0],
                theirs[0]
            );
            let n = ours.len();
            for (a, b) in ours[1..n - 1].iter().zip(&theirs[1..n - 1]) {
                worst.0 = worst.0.max((a - b).abs());
            }
            worst.1 = worst.1.max((ours[n - 1] - theirs[n - 1]).abs());
        }
        println!(
            "{file} {algebra}: coordinates within {:.1e}, energy within {:.1e} J of {reference}",
            worst.0, worst.1
        );
        worst
    })
}

/// The UR5 file runs as Pinocchio's reference (RKMK8-body at dt = 5 ms, its default with a robot): every joint at
/// every sample within 1e-9 rad. Measured, both algebras: 1.7e-13 rad, energy 1.7e-12 J.
#[test]
fn ur5_file_matches_the_reference() {
    for (coordinates, energy) in against_reference("ur5.toml", "ur5.csv") {
        assert!(coordinates < 1e-9 && energy < 1e-9, "{coordinates:e} rad, {energy:e} J");
    }
}

/// Stepping in joint coordinates (`integrator = "rkmk8-joint"`) the robot files run as Pinocchio's reference too,
/// more closely still on the floating base (no precision lost reading the coordinates back from the bodies). Measured,
/// both algebras: UR5 5.7e-14 rad, Solo-12 1.3e-13.
#[test]
fn robot_files_in_joint_coordinates_match_the_references() {
    let dir = fresh("joint-coordinates");
    for (file, reference) in [("ur5.toml", "ur5.csv"), ("solo12.toml", "solo12.csv")] {
        let text = std::fs::read_to_string(scenes().join(file)).unwrap().replacen(
            "\ndt = ",
            "\nintegrator = \"rkmk8-joint\"\ndt = ",
            1,
        );
        let path = dir.join(file);
        std::fs::write(
            &path,
            text.replace("\"../reference", &format!("\"{}/../reference", scenes().display())),
        )
        .unwrap();
        let output = dir.join(file.trim_end_matches(".toml"));
        run_scene_file(&path, &output).expect("the file runs");
        let (expected_header, expected) = read_csv(&robots().join(reference));
        for algebra in ["pga", "cga"] {
            let stem = file.trim_end_matches(".toml");
            let (header, rows) = read_csv(&output.join(format!("{stem}_joints_{algebra}.csv")));
            assert_eq!(header, expected_header);
            let worst = rows
                .iter()
                .zip(&expected)
                .flat_map(|(a, b)| {
                    a[1..a.len() - 1]
                        .iter()
                        .zip(&b[1..b.len() - 1])
                        .map(|(x, y)| (x - y).abs())
                })
                .fold(0.0, f64::max);
            println!("{file} {algebra}, rkmk8-joint: coordinates within {worst:.1e} of {reference}");
            assert!(worst < 1e-9, "{file}, {algebra}: {worst:e}");
        }
    }
}

/// A run whose energy change the impacts and the work of its forces without a potential do not explain, by more than
/// 1e-6 of its energy, is flagged (stderr and summary.md) with the advice to give a tolerance: the UR5 file with a
/// damper of 5 N m s on its wrist at the file's fixed 5 ms (E − E₀ − L − W measured 1.1e-5 of |E₀|); with
/// `tolerance = 1e-10` in place of `dt` nothing is said.
#[test]
fn a_damped_robot_on_coarse_fixed_steps_is_flagged() {
    let dir = fresh("damped");
    let text = std::fs::read_to_string(scenes().join("ur5.toml"))
        .unwrap()
        .replace("\"../reference", &format!("\"{}/../reference", scenes().display()))
        + "\n[[joint_damping]]\njoint = \"wrist_3_joint\"\ndamping = 5.0\n";
    for (name, text, flagged) in [
        ("coarse", text.clone(), true),
        (
            "tolerance",
            text.replacen("\ndt = 5e-3", "\ntolerance = 1e-10", 1),
            false,
        ),
    ] {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(&file, &text).unwrap();
        let output = dir.join(name);
        let summary = run_scene_file(&file, &output).expect("the file runs");
        let written = std::fs::read_to_string(output.join("summary.md")).unwrap();
        if flagged {
            assert_eq!(summary.warnings.len(), 2, "{:?}", summary.warnings);
            for warning in &summary.warnings {
                assert!(
                    warning.contains("E − E₀ − L − W") && warning.contains("dt = 5e-3 s"),
                    "{warning}"
                );
                assert!(warning.contains("a `tolerance` in place of `dt`"), "{warning}");
                assert!(written.contains(warning.as_str()), "{written}");
            }
        } else {
            assert!(summary.warnings.is_empty(), "{:?}", summary.warnings);
            let balance = summary
                .runs
                .iter()
                .map(|r| r.unexplained_energy().abs())
                .fold(0.0, f64::max);
            assert!(balance < 1e-9, "{balance:e} J");
        }
    }
}

/// The Solo-12 file (floating base) runs as Pinocchio's reference: every joint and the base's position and quaternion
/// at every sample within 1e-9. Measured, both algebras: 1.8e-11 (round-off growing as the base falls away from the
/// origin, see scenarios/tests/integration/robots.rs), energy 2.1e-11 J.
#[test]
fn solo12_file_matches_the_reference() {
    for (coordinates, energy) in against_reference("solo12.toml", "solo12.csv") {
        assert!(coordinates < 1e-9 && energy < 1e-9, "{coordinates:e}, {energy:e} J");
    }
}

/// The summary states the work against the energy change and lists what the URDF has that is not modelled.
#[test]
fn the_paddle_summary_reports_work_and_model() {
    let output = fresh("paddle-summary");
    let file = output.join("paddle.toml");
    let text = std::fs::read_to_string(scenes().join("ur5_paddle.toml"))
        .unwrap()
        .replace("duration = 2.0", "duration = 0.05")
        .replace(
            "../reference/data/robots/ur5_robot.urdf",
            &robots().join("ur5_robot.urdf").display().to_string(),
        );
    std::fs::write(&file, text).unwrap();
    let summary = run_scene_file(&file, &output.join("out")).expect("runs");
    let text = std::fs::read_to_string(output.join("out/summary.md")).unwrap();
    for part in [
        "Robot `ur5`",
        "11 links, 4 merged",
        "6 revolute",
        "6 degrees of freedom",
        "Joint limits: not enforced",
        "E(T) − E₀ − W(T)",
        "W is the work of the forces without a potential (force elements, drives",
        "hold (PD, kp = 100",
    ] {
        assert!(text.contains(part), "{part:?} not in\n{text}");
    }
    let run = &summary.runs[0];
    let (headers, rows) = run.joints.as_ref().expect("a joints table");
    assert_eq!(headers.len(), 6);
    assert_eq!(rows.len(), run.bodies[0].len());
    assert_eq!(run.names.len(), 7, "{:?}", run.names);
    assert_eq!(run.names[6], "paddle");
}

/// A small arm (scene-file's test data): a base, a link on a revolute `shoulder` (damping 0.5, friction 0.1), a
/// massless `sensor` link on a continuous `spin` joint below it, and a `finger` on a prismatic joint.
const ARM_MASSLESS_SENSOR: &str = include_str!("../../../scene-file/tests/data/arm_massless_sensor.urdf");

/// A scene of the arm in `dir` (URDF `arm.urdf`), `robot` the `[robot]` table's further lines.
fn arm_scene(robot: &str) -> String {
    format!("dt = 1e-3\nduration = 0.2\nalgebra = \"pga\"\n[robot]\nurdf = \"arm.urdf\"\n{robot}\n")
}

/// Joint and link names with commas, quotes and spaces (the arm's shoulder `shoulder, left "a"`, its link `upper,
/// arm`) are written into the joints and bodies CSVs quoted as RFC 4180 says: read back by the `csv` crate, the
/// headers hold the names as the URDF spells them and every row has as many fields as its header.
#[test]
fn names_with_commas_and_quotes_are_quoted_in_the_csvs() {
    let dir = fresh("quoted-names");
    let urdf = ARM_MASSLESS_SENSOR
        .replace("joint name=\"shoulder\"", "joint name=\"shoulder, left &quot;a&quot;\"")
        .replace("\"link\"", "\"upper, arm\"");
    assert_ne!(urdf, ARM_MASSLESS_SENSOR);
    std::fs::write(dir.join("arm.urdf"), urdf).unwrap();
    let scene = arm_scene("q = { \"shoulder, left \\\"a\\\"\" = 0.5 }\nrepairs = { massless_subtrees = \"freeze\" }");
    std::fs::write(dir.join("quoted.toml"), &scene).unwrap();
    run_scene_file(&dir.join("quoted.toml"), &dir.join("out")).expect("the scene runs");
    let (joints, rows) = read_csv(&dir.join("out/quoted_joints_pga.csv"));
    assert_eq!(joints, ["t", "shoulder, left \"a\"", "spin", "slide", "energy"]);
    assert!((rows[0][1] - 0.5).abs() < 1e-15);
    let (bodies, rows) = read_csv(&dir.join("out/quoted_pga.csv"));
    assert!(bodies.iter().any(|c| c == "upper, arm.x"), "{bodies:?}");
    assert!(rows.iter().all(|r| r.len() == bodies.len()));
    let text = std::fs::read_to_string(dir.join("out/quoted_joints_pga.csv")).unwrap();
    assert!(
        text.starts_with("t,\"shoulder, left \"\"a\"\"\",spin,slide,energy\n"),
        "{}",
        &text[..80]
    );
}

/// A URDF with a massless moving link: an error naming the joint and the link without the freeze repair; frozen at 0
/// with it, listed in the summary and written as a constant column of the joints CSV in file order. The URDF's
/// damping becomes joint damping (`joint_dynamics = "urdf"`), whose work the energy change equals; its friction is
/// listed as not modelled.
#[test]
fn massless_moving_links_and_urdf_dynamics() {
    let dir = fresh("arm");
    std::fs::write(dir.join("arm.urdf"), ARM_MASSLESS_SENSOR).unwrap();
    let refused = Scene::parse_in(&arm_scene("q = { shoulder = 0.5 }"), &dir)
        .unwrap_err()
        .to_string();
    println!("{refused}");
    assert!(
        refused.contains("robot.urdf") && refused.contains("spin") && refused.contains("sensor"),
        "{refused}"
    );
    let frozen = arm_scene("q = { shoulder = 0.5 }\nv = { slide = 0.2 }\nrepairs = { massless_subtrees = \"freeze\" }");
    std::fs::write(dir.join("frozen.toml"), &frozen).unwrap();
    let summary = run_scene_file(&dir.join("frozen.toml"), &dir.join("out")).expect("frozen, it runs");
    let (header, rows) = read_csv(&dir.join("out/frozen_joints_pga.csv"));
    assert_eq!(header, ["t", "shoulder", "spin", "slide", "energy"]);
    assert!(rows.iter().all(|r| r[2] == 0.0), "the frozen joint stays at 0");
    assert!((rows[0][1] - 0.5).abs() < 1e-15);
    let text = std::fs::read_to_string(dir.join("out/summary.md")).unwrap();
    for part in [
        "continuous joint \\`spin\\` (line 9) frozen at 0: its subtree is massless",
        "spin (continuous, line 9)",
        "shoulder: 0.1 (not modelled)",
        "shoulder: 0.5",
    ] {
        assert!(text.contains(part), "{part:?} not in\n{text}");
    }
    let run = &summary.runs[0];
    let samples = &run.bodies[0];
    let worst = samples
        .iter()
        .map(|s| (s.energy - samples[0].energy - s.work).abs())
        .fold(0.0, f64::max);
    let work = samples.last().unwrap().work;
    println!("URDF damping: work {work:.3e} J, |E(t) − E₀ − W(t)| ≤ {worst:.1e} J");
    assert!(work < -1e-3 && worst < 1e-10, "work {work:e} J, balance {worst:e} J");
    // The frozen joint has no coordinate to start at.
    let message = Scene::parse_in(
        &frozen.replace("q = { shoulder = 0.5 }", "q = { shoulder = 0.5, spin = 1.0 }"),
        &dir,
    )
    .unwrap_err()
    .to_string();
    assert!(
        message.contains("robot.q") && message.contains("`spin` is frozen"),
        "{message}"
    );
}

/// A UR5 falling under gravity with its tool flange (`tool0`) kept above a table 0.3 m below the base: the flange
/// strikes the table, bounces at restitution 0.3 and comes to rest on it, never below it by 1e-12 m at a sample; both
/// algebras make the same transitions; the energy less what the impacts took holds to the tolerance.
#[test]
fn a_robot_link_meets_a_table() {
    let dir = fresh("table");
    let urdf = robots().join("ur5_robot.urdf").display().to_string();
    let text = std::fs::read_to_string(scenes().join("ur5.toml"))
        .unwrap()
        .replace("urdf = \"../reference/data/robots/ur5_robot.urdf\"", &format!("urdf = {urdf:?}"))
        .replace("dt = 5e-3", "tolerance = 1e-10")
        + "\n[[contact]]\nname = \"tool on table\"\nbody = \"tool0\"\npoint = [0.0, 0.0, 0.0]\noffset = -0.3\nrestitution = 0.3\n";
    let file = dir.join("ur5_table.toml");
    std::fs::write(&file, text).unwrap();
    let summary = run_scene_file(&file, &dir.join("out")).expect("the scene runs");
    let [pga, cga] = &summary.runs[..] else {
        panic!("two runs")
    };
    assert!(pga.transitions.len() >= 3, "{:?}", pga.transitions);
    assert!(matches!(
        pga.transitions[0].change,
        dynamics::limits::LimitChange::Bounced { .. }
    ));
    assert!(pga
        .transitions
        .iter()
        .any(|t| matches!(t.change, dynamics::limits::LimitChange::Held { .. })));
    assert_eq!(pga.transitions.len(), cga.transitions.len());
    for (a, b) in pga.transitions.iter().zip(&cga.transitions) {
        assert_eq!(
            (&a.constraint, std::mem::discriminant(&a.change)),
            (&b.constraint, std::mem::discriminant(&b.change))
        );
        assert!((a.t - b.t).abs() < 1e-9, "{} vs {} s", a.t, b.t);
    }
    for run in [pga, cga] {
        assert!(run.deepest < 1e-12, "{:e} m below the table", run.deepest);
        assert!(run.max_energy_change() < 1e-8, "{}", run.max_energy_change());
    }
}

/// The base position (columns `base.x`, `base.y`, `base.z`) at each sample of a joints CSV, with the sample's time.
fn base_positions(path: &Path) -> Vec<(f64, [f64; 3])> {
    let (header, rows) = read_csv(path);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (x, y, z) = (column("base.x"), column("base.y"), column("base.z"));
    rows.iter().map(|row| (row[0], [row[x], row[y], row[z]])).collect()
}

/// The shipped Solo-12 dropped 3 cm onto a floor with friction 0.8, standing on a PD stance with gravity compensation
/// (scenes/solo12_standing.toml, DOP853-body at 1e-10): its four foot spheres land and stick, never slipping, both
/// algebras making the same transitions; no foot goes below the floor by 1e-12 m; from t = 2 s to t = 7 s its base
/// moves less than 1e-9 m (sticking feet are rows held to round-off, where soft contact creeps); and the energy change
/// less the impacts' and the PD's and friction's work is the integration error (1e-8 J).
#[test]
fn solo12_lands_and_stands_still_on_its_feet() {
    let output = fresh("solo12-standing");
    let summary = run_scene_file(&scenes().join("solo12_standing.toml"), &output).expect("the file runs");
    let [pga, cga] = &summary.runs[..] else {
        panic!("two runs")
    };
    use dynamics::limits::LimitChange;
    assert_eq!(pga.transitions.len(), cga.transitions.len());
    for (a, b) in pga.transitions.iter().zip(&cga.transitions) {
        assert_eq!(
            (&a.constraint, std::mem::discriminant(&a.change)),
            (&b.constraint, std::mem::discriminant(&b.change))
        );
        assert!((a.t - b.t).abs() < 1e-9, "{} vs {} s", a.t, b.t);
    }
    assert!(
        !pga.transitions
            .iter()
            .any(|t| matches!(t.change, LimitChange::Slipped { .. })),
        "{:?}",
        pga.transitions
    );
    // Each foot is held once, sticking from its landing (no slip left after the impact) or from the stop of its
    // slide, and never released.
    let held = |kind: fn(&LimitChange) -> bool| pga.transitions.iter().filter(|t| kind(&t.change)).count();
    assert_eq!(
        held(|c| matches!(c, LimitChange::Held { .. })),
        4,
        "{:?}",
        pga.transitions
    );
    assert_eq!(
        held(|c| matches!(c, LimitChange::Released { .. })),
        0,
        "{:?}",
        pga.transitions
    );
    for (run, algebra) in [(pga, "pga"), (cga, "cga")] {
        assert!(run.deepest < 1e-12, "{:e} m below the floor", run.deepest);
        let (first, last) = (run.bodies[0].first().unwrap(), run.bodies[0].last().unwrap());
        let impacts: f64 = run.transitions.iter().map(|t| t.energy_change).sum();
        let error = last.energy - first.energy - impacts - run.work.last().unwrap();
        assert!(error.abs() < 1e-8, "E − E₀ − L − W = {error:e} J");
        let base = base_positions(&output.join(format!("solo12_standing_joints_{algebra}.csv")));
        let (_, settled) = *base.iter().find(|(t, _)| *t >= 2.0).unwrap();
        let moved = (base.iter().filter(|(t, _)| *t >= 2.0))
            .map(|(_, p)| (0..3).map(|k| (p[k] - settled[k]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        println!("solo12_standing {algebra}: the base moved {moved:.1e} m from t = 2 s to 7 s, E − E₀ − L − W = {error:.1e} J");
        assert!(moved < 1e-9, "{algebra}: the standing base moved {moved:e} m");
        assert!(settled[2] > 0.15, "{algebra}: the base at {} m", settled[2]);
    }
}

/// The same robot pulled forward by a nearly constant 35 N (a soft spring to a far anchor), more than its feet's
/// friction holds (μ = 0.8, about 2.5 kg): its feet slide (slips located as events), it travels forward, and no foot
/// goes below the floor.
#[test]
fn solo12_pulled_harder_than_friction_holds_slides() {
    let dir = fresh("solo12-pulled");
    let text = std::fs::read_to_string(scenes().join("solo12_standing.toml"))
        .unwrap()
        .replace("\"../reference", &format!("\"{}/../reference", scenes().display()))
        .replace("duration = 7.0", "duration = 1.0")
        + "\n[[spring]]\nname = \"pull\"\nbetween = [\"base_link\", \"world\"]\npoints = [[0.0, 0.0, -0.1], [100.0, 0.0, 0.066]]\nstiffness = 0.35\nrest_length = 0.0\n";
    let file = dir.join("solo12_pulled.toml");
    std::fs::write(&file, text).unwrap();
    let summary = run_scene_file(&file, &dir.join("out")).expect("the scene runs");
    for run in &summary.runs {
        let slips = run
            .transitions
            .iter()
            .filter(|t| matches!(t.change, dynamics::limits::LimitChange::Slipped { .. }));
        assert!(slips.count() >= 4, "{:?}", run.transitions);
        assert!(run.deepest < 1e-12, "{:e} m below the floor", run.deepest);
    }
    let base = base_positions(&dir.join("out").join("solo12_pulled_joints_pga.csv"));
    let travelled = base.last().unwrap().1[0] - base[0].1[0];
    println!("solo12 pulled: travelled {travelled:.3} m in 1 s");
    assert!(travelled > 1.0, "{travelled} m");
}

/// A two-link robot whose URDF gives collision shapes (`collisions = "urdf"`): a box on its base link, a sphere at its
/// leg's end, a cylinder along the leg and a mesh whose file is missing. Dropped with a free root onto a `[[plane]]`
/// with friction, the box's corners and the sphere stay above the plane (no sample below it by 1e-12 m) through
/// contacts named after the links, the cylinder through its cap rims; the missing mesh is named in the summary's
/// importer warnings, not silently dropped.
#[test]
fn urdf_collision_shapes_stay_above_a_plane() {
    let dir = fresh("urdf-collisions");
    let urdf = r#"<robot name="hopper">
  <link name="base">
    <inertial><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0"/><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <collision><geometry><mesh filename="package://hopper/meshes/shell.stl"/></geometry></collision>
  </link>
  <link name="leg">
    <inertial><origin xyz="0 0 -0.1"/><mass value="0.2"/><inertia ixx="0.001" iyy="0.001" izz="0.0001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 -0.2"/><geometry><sphere radius="0.03"/></geometry></collision>
    <collision><origin xyz="0 0 -0.1"/><geometry><cylinder radius="0.01" length="0.2"/></geometry></collision>
  </link>
  <joint name="hip" type="revolute">
    <parent link="base"/><child link="leg"/><origin xyz="0.05 0 -0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="10"/>
  </joint>
</robot>"#;
    std::fs::write(dir.join("hopper.urdf"), urdf).unwrap();
    let scene = r#"title = "hopper"
algebra = "both"
tolerance = 1e-10
duration = 1.0

[robot]
urdf = "hopper.urdf"
root = "free"
collisions = "urdf"
base_position = [0.0, 0.0, 0.4]
base_orientation = { axis = [1.0, 0.0, 0.0], degrees = 10.0 }
q = { hip = 0.3 }

[[plane]]
name = "floor"
friction = 0.6
restitution = 0.2
"#;
    std::fs::write(dir.join("hopper.toml"), scene).unwrap();
    let summary = run_scene_file(&dir.join("hopper.toml"), &dir.join("out")).expect("the scene runs");
    for run in &summary.runs {
        assert!(run.transitions.len() >= 4, "{:?}", run.transitions);
        assert!(run.deepest < 1e-12, "{:e} m below the floor", run.deepest);
        assert!(
            run.transitions.iter().any(|t| t.constraint == "floor: leg sphere 1"),
            "{:?}",
            run.transitions
        );
        assert!(run
            .transitions
            .iter()
            .any(|t| t.constraint.starts_with("floor: base box 1 corner")));
    }
    let text = std::fs::read_to_string(dir.join("out").join("summary.md")).unwrap();
    for part in [
        "floor: leg cylinder 2 cap 1: the rim of the disk of radius 0.01 m",
        "floor: leg cylinder 2 cap 2",
        "the mesh",
        "shell.stl is not found",
    ] {
        assert!(text.contains(part), "{part:?} not in the summary");
    }
    assert!(!text.contains("the cylinder <collision>"), "{text}");
}

/// The shipped UR5 sweeping a box across a table (scenes/ur5_pushes_a_box.toml): the ball welded to its flange meets
/// the box's face (a `[[collision]]` pair) and pushes it; both algebras make the same transitions; no sample has the
/// box or the ball in the table, or the ball in the box, by 1e-12 m; the box slides on more than half a metre and
/// stops on the table, its centre at the box's half height; and the energy less the impacts' and the PD's and
/// friction's work is the integration error (1e-8 J).
#[test]
fn a_ur5_pushes_a_box_across_a_table() {
    let output = fresh("ur5-push");
    let summary = run_scene_file(&scenes().join("ur5_pushes_a_box.toml"), &output).expect("the file runs");
    let [pga, cga] = &summary.runs[..] else {
        panic!("two runs")
    };
    assert_eq!(pga.transitions.len(), cga.transitions.len());
    for (a, b) in pga.transitions.iter().zip(&cga.transitions) {
        assert_eq!(a.constraint, b.constraint);
        assert!((a.t - b.t).abs() < 1e-9, "{} vs {} s", a.t, b.t);
    }
    let pushed = (pga.transitions.iter())
        .filter(|t| t.constraint.starts_with("push: pusher sphere 1 on box box 1 face"))
        .count();
    assert!(pushed >= 1, "{:?}", pga.transitions);
    for run in [pga, cga] {
        assert!(run.deepest < 1e-12, "{:e} m into the table or the box", run.deepest);
        let body = run.names.iter().position(|n| n == "box").unwrap();
        let (start, end) = (run.bodies[body].first().unwrap(), run.bodies[body].last().unwrap());
        assert!(
            (end.position.xy() - start.position.xy()).norm() > 0.5,
            "{}",
            end.position
        );
        assert!((end.position.z + 0.15).abs() < 1e-12, "{}", end.position.z);
        assert!(
            end.velocity.norm() < 1e-9 && end.angular_velocity.norm() < 1e-9,
            "{end:?}"
        );
        let (first, last) = (run.bodies[0].first().unwrap(), run.bodies[0].last().unwrap());
        let impacts: f64 = run.transitions.iter().map(|t| t.energy_change).sum();
        let error = last.energy - first.energy - impacts - run.work.last().unwrap();
        assert!(error.abs() < 1e-8, "E − E₀ − L − W = {error:e} J");
    }
}
