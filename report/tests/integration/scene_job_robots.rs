//! Scene files with a `[robot]` run by the scene job (docs/scene-files.md):
//!
//! * the shipped UR5 and Solo-12 files write joints CSVs with the columns of `reference/data/robots/*.csv` that match
//!   Pinocchio's runs there at every sample (both files read back), stepping the bodies or the joint coordinates;
//! * the paddle's summary states the work against the energy change and what of the URDF is not modelled;
//! * a massless moving link, frozen by the repair, is a constant column of the joints CSV, and the URDF's damping does
//!   the work the energy change equals;
//! * a robot link meets a table, and comes to rest on it.
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

/// A CSV file's header and rows.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let rows = lines
        .map(|line| line.split(',').map(|v| v.parse::<f64>().unwrap()).collect())
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
