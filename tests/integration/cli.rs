//! The main job's command line refuses what cannot make a job, with a message naming the flag and an error exit
//! status, before running anything (`--steps 0.003` used to end with every run failed and status 0).

use std::process::{Command, Output};

fn job(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ga-dynamics"))
        .args(arguments)
        .args(["--quiet", "--output", env!("CARGO_TARGET_TMPDIR")])
        .output()
        .expect("the job binary runs")
}

#[test]
fn nonsensical_flags_are_refused_with_a_message() {
    for (arguments, mentions) in [
        (
            &["--steps", "0.003"][..],
            &["--steps 0.003", "does not divide the sample interval"][..],
        ),
        (&["--steps", "0"], &["--steps 0", "positive"]),
        (&["--steps", "nan"], &["--steps NaN", "positive"]),
        (&["--steps", "-1e-3"], &["--steps -0.001", "positive"]),
        (&["--duration", "0"], &["--duration", "positive"]),
        (&["--duration", "-1"], &["--duration", "got -1"]),
        (&["--duration", "1e308"], &["--duration", "at most 1000"]),
        (
            &["--duration", "0.015"],
            &["--duration 0.015", "a whole number of 0.01 s"],
        ),
        (
            &["--duration", "20"],
            &["--duration 20", "longer than the reference trajectory", "(10 s)"],
        ),
        (
            &["--duration", "6", "--scenes", "four-bar"],
            &["--duration 6", "M2 four-bar linkage (5 s)"],
        ),
        (&["--steps", "1e-12"], &["--steps", "1e13 steps", "at most 1e8"]),
        (
            &["--integrators", "strang", "--scenes", "pendulum"],
            &["make no run", "only scene 1"],
        ),
        (
            &["--integrators", "rkmk8-joint", "--scenes", "double-pendulum"],
            &["make no run", "only the robots"],
        ),
        (&["--tolerances", "0"], &["--tolerances 0", "absolute tolerance"]),
        (&["--tolerances", "nan"], &["--tolerances NaN", "relative tolerance"]),
        (
            &["--tolerances", "-1e-8"],
            &["--tolerances -0.00000001", "relative tolerance"],
        ),
        (&["--tolerances", "1.5"], &["--tolerances 1.5", "relative tolerance"]),
        (&["--tolerances", "inf"], &["--tolerances inf", "relative tolerance"]),
        (
            &["--tolerances", "1e-16"],
            &["--tolerances 0.0000000000000001", "absolute tolerance"],
        ),
        (
            &["--tolerances", "1e-8", "--scene-file", "scenes/heavy_top.toml"],
            &["--tolerances", "cannot be used with"],
        ),
        (&["--threads", "100000"], &["--threads", "four per core"]),
        (&["--threads", "0"], &["--threads", "got 0"]),
    ] {
        let output = job(arguments);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{arguments:?}: {stderr}");
        for part in mentions {
            assert!(stderr.contains(part), "{arguments:?}: {stderr:?} lacks {part:?}");
        }
        assert!(
            output.stdout.is_empty(),
            "{arguments:?} ran: {}",
            String::from_utf8_lossy(&output.stdout)
        );
    }
}

#[test]
fn the_version_names_the_program() {
    let output = Command::new(env!("CARGO_BIN_EXE_ga-dynamics"))
        .arg("--version")
        .output()
        .expect("the job binary runs");
    assert!(output.status.success());
    assert_eq!(
        String::from_utf8_lossy(&output.stdout).trim(),
        format!("ga-dynamics {}", env!("CARGO_PKG_VERSION"))
    );
}

/// A scene file whose conservative scene's energy drifts far runs, and says so on stderr (status 0: the run
/// itself succeeded): a cuboid tumbling about its middle axis at 80 rad/s, stepped by RK4 at dt = 1e-2 (0.8 rad
/// per step, under the 1 rad a step may turn).
#[test]
fn a_drifting_scene_file_warns_on_stderr() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-drifting-scene");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("spinning.toml");
    std::fs::write(
        &file,
        "integrator = \"rk4\"\ndt = 1e-2\nduration = 1.0\n[body]\nmass = 1.0\n\
         shape = { kind = \"cuboid\", size = [0.1, 0.2, 0.3] }\n[initial]\n\
         body_angular_velocity = [0.1, 80.0, 0.0]\n",
    )
    .unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_ga-dynamics"))
        .arg("--scene-file")
        .arg(&file)
        .arg("--output")
        .arg(dir.join("out"))
        .output()
        .expect("the job binary runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: PGA: the energy of this conservative scene changed"),
        "{stderr}"
    );
}

/// An output directory that cannot be made stops the job (and a scene-file run) before anything runs, naming the
/// path and the reason, with an error status.
#[test]
fn an_output_directory_that_cannot_be_made_is_an_error() {
    let file = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-output-is-a-file");
    std::fs::write(&file, "").unwrap();
    let unwritable = file.join("out");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/heavy_top.toml");
    for arguments in [&["--quiet"][..], &["--scene-file", scene]] {
        let output = Command::new(env!("CARGO_BIN_EXE_ga-dynamics"))
            .args(arguments)
            .arg("--output")
            .arg(&unwritable)
            .output()
            .expect("the job binary runs");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{arguments:?}: {stderr}");
        assert!(
            stderr.contains("cannot write") && stderr.contains("cli-output-is-a-file/out"),
            "{arguments:?}: {stderr}"
        );
    }
}
