//! The anchors file (`--anchors`, written by `tools/anchors/measure`) under careless edits: each breaks one
//! promise of the format and must fail with a message naming what is wrong, never panic or fall back silently.

use std::time::{Duration, SystemTime, UNIX_EPOCH};

use report::measured_anchors::{Anchors, AnchorsError};

/// A file as the runner writes it: a MuJoCo step time with its errors, a Pinocchio evaluation (no step) and a robot.
const VALID: &str = r#"{
 "format": 1,
 "measured_at": "2026-11-27T18:05:00Z",
 "machine": {"nproc": 2, "load_before": [1.16, 2.28, 2.39], "load_after": [1.5, 2.2, 2.3]},
 "figures": [
  {"key": "m1", "what": "MuJoCo 4.0 RK4 step at dt = 1e-3", "dt": 0.001,
   "command": "python double_pendulum.py OUTDIR m1 1.0 0.1 0.1 1.0 0.5 0.08 0.08 0.8 1.0 0.6 1.0 -0.5 10",
   "repeats": [5.5e-06, 5e-06, 6e-06, 5.2e-06, 5.1e-06], "min": 5e-06, "spread": 0.2,
   "errors": [{"dt": 0.01, "error": 2.06e-06}, {"dt": 0.001, "error": 2.22e-10}, {"dt": 0.0001, "error": 2.58e-13}]},
  {"key": "m3-pinocchio-8", "what": "Pinocchio 4.1 ABA evaluation, ball joints", "dt": null,
   "command": "python chain.py OUTDIR/pinocchio_chain.json",
   "repeats": [4e-06, 4e-06, 4e-06, 4e-06, 4e-06, 4e-06], "min": 4e-06, "spread": 0.0},
  {"key": "ur5-dt1e-4", "what": "MuJoCo 4.0 RK4 step at dt = 1e-4", "dt": 0.0001,
   "command": "python reference.py ur5 OUTDIR",
   "repeats": [7e-06, 7e-06, 7e-06, 7e-06, 9.8e-06], "min": 7e-06, "spread": 0.4,
   "errors": [{"dt": 0.0001, "error": 6.6e-14}]}
 ]
}"#;

/// A day after the file's measurement.
fn now() -> SystemTime {
    UNIX_EPOCH + Duration::from_secs(1_795_802_700 + 86_400)
}

#[test]
fn the_valid_file_parses() {
    let anchors = Anchors::parse(VALID, now()).expect("valid");
    assert_eq!(anchors.len(), 3);
    let occasion = anchors.occasion().expect("measured");
    assert_eq!(occasion.when, "2026-11-27 18:05 UTC");
    assert_eq!((occasion.cores, occasion.load), (2, (1.16, 1.5)));
    // Against the machine's clock, a file of the past parses.
    let old = VALID.replace("2026-11-27T18:05:00Z", "1970-01-02T00:00:00Z");
    assert!(Anchors::parse(&old, SystemTime::now()).is_ok());
}

/// The message of the error parsing `VALID` with `from` replaced by `to`.
fn error_with(from: &str, to: &str) -> String {
    assert!(VALID.contains(from), "{from}");
    match Anchors::parse(&VALID.replacen(from, to, 1), now()) {
        Ok(_) => panic!("replacing {from} by {to} should fail"),
        Err(error) => error.to_string(),
    }
}

#[test]
fn careless_files_fail_with_clear_messages() {
    let cases: &[(&str, &str, &[&str])] = &[
        ("\"min\": 5e-06, ", "", &["missing field `min`", "line "]),
        ("\"min\": 5e-06", "\"minimum\": 5e-06", &["unknown field `minimum`"]),
        ("\"min\": 5e-06", "\"min\": NaN", &["not an anchors file", "line "]),
        (
            "\"min\": 5e-06",
            "\"min\": 1e400",
            &["not an anchors file", "out of range"],
        ),
        ("\"spread\": 0.2", "\"spread\": \"20 %\"", &["invalid type: string"]),
        (
            "[5.5e-06, 5e-06,",
            "[-5.5e-06, 5e-06,",
            &["\"m1\"", "repeat 1 is -0.0000055 s", "positive and finite"],
        ),
        ("[5.5e-06, 5e-06,", "[0, 5e-06,", &["\"m1\"", "repeat 1 is 0 s"]),
        (
            "[5.5e-06, 5e-06, 6e-06, 5.2e-06, 5.1e-06]",
            "[5e-06, 6e-06]",
            &["\"m1\"", "2 repeats", "at least 5"],
        ),
        (
            "\"repeats\": [5.5e-06",
            "\"repeats\": 5, \"x\": [5.5e-06",
            &["invalid type: integer `5`"],
        ),
        (
            "\"min\": 5e-06",
            "\"min\": 5.1e-06",
            &["\"m1\"", "not the fastest repeat"],
        ),
        (
            "\"spread\": 0.2",
            "\"spread\": 0.02",
            &["\"m1\"", "spread 0.02", "largest/smallest − 1"],
        ),
        (
            "\"key\": \"m1\"",
            "\"key\": \"M1\"",
            &["\"M1\"", "not a figure the report uses"],
        ),
        (
            "\"key\": \"m1\"",
            "\"key\": \"m3-ball-3\"",
            &["\"m3-ball-3\"", "not a figure the report uses"],
        ),
        (
            "\"key\": \"m1\"",
            "\"key\": \"cuboid\"",
            &["\"cuboid\"", "not a figure the report uses"],
        ),
        (
            "\"key\": \"ur5-dt1e-4\"",
            "\"key\": \"m3-pinocchio-8\"",
            &["\"m3-pinocchio-8\""],
        ),
        (
            "\"key\": \"m3-pinocchio-8\"",
            "\"key\": \"m1\"",
            &["\"m1\"", "dt none", "at 1e-3 s"],
        ),
        (
            "\"dt\": 0.001,",
            "\"dt\": 0.01,",
            &["\"m1\"", "dt 1e-2 s", "compares it at 1e-3 s"],
        ),
        (
            "\"dt\": null",
            "\"dt\": 0.001",
            &["\"m3-pinocchio-8\"", "dt 1e-3 s", "none (a time per evaluation)"],
        ),
        (
            "\"error\": 2.22e-10",
            "\"error\": -2.22e-10",
            &["\"m1\"", "error -0.000000000222 at dt 0.001"],
        ),
        ("\"format\": 1", "\"format\": 2", &["format 2", "reads format 1"]),
        (
            "2026-11-27T18:05:00Z",
            "2027-01-01T00:00:00Z",
            &["2027-01-01T00:00:00Z", "later than"],
        ),
        (
            "2026-11-27T18:05:00Z",
            "2026-11-27 18:05",
            &["\"2026-11-27 18:05\"", "not a UTC date-time"],
        ),
        ("2026-11-27T18:05:00Z", "2026-02-30T18:05:00Z", &["not a UTC date-time"]),
        ("\"nproc\": 2", "\"nproc\": 0", &["machine: nproc is 0"]),
        ("\"nproc\": 2", "\"nproc\": -2", &["invalid value: integer `-2`"]),
        (
            "[1.16, 2.28, 2.39]",
            "[-1.16, 2.28, 2.39]",
            &["machine", "load average -1.16"],
        ),
        ("[1.16, 2.28, 2.39]", "[1.16, 2.28]", &["invalid length 2"]),
        ("\"figures\": [", "\"figures\": 0, \"x\": [", &["invalid type"]),
    ];
    for (from, to, parts) in cases {
        let message = error_with(from, to);
        for part in *parts {
            assert!(
                message.contains(part),
                "{from} → {to}: {message:?} should mention {part:?}"
            );
        }
    }
}

#[test]
fn a_figure_twice_is_refused() {
    let (start, end) = (
        VALID.find("  {\"key\": \"m3-pinocchio-8\"").unwrap(),
        VALID.find("  {\"key\": \"ur5").unwrap(),
    );
    let twice = format!("{}{}{}", &VALID[..end], &VALID[start..end], &VALID[end..]);
    let message = Anchors::parse(&twice, now()).unwrap_err().to_string();
    assert_eq!(message, "figure \"m3-pinocchio-8\" appears twice");
}

#[test]
fn not_a_file_or_not_json_fails_with_the_reason() {
    for text in ["", "{", "[]", "null", "{\"format\": 1}", "format = 1"] {
        let error = Anchors::parse(text, now()).unwrap_err();
        assert!(matches!(error, AnchorsError::Json(_)), "{text:?}: {error}");
        assert!(error.to_string().starts_with("not an anchors file"), "{error}");
    }
    let missing = std::path::Path::new("no/such/anchors.json");
    let message = Anchors::read(missing).unwrap_err().to_string();
    assert!(message.starts_with("cannot read no/such/anchors.json"), "{message}");
}

#[test]
fn the_report_says_which_figures_were_measured_in_this_run() {
    use dynamics::constraints::Stabilisation;
    use dynamics::integrate::{Integrator, Method};
    use report::job::run_job_with_robots;
    use report::mechanisms::{MechanismKind, MechanismPlan};
    use report::robots::RobotPlan;
    use report::single_bodies::SweepPlan;

    // M1 measured with repeats 50 % apart; M2 left to its recorded constant.
    let busy = VALID.replace(
        "[5.5e-06, 5e-06, 6e-06, 5.2e-06, 5.1e-06], \"min\": 5e-06, \"spread\": 0.2",
        "[5e-06, 5e-06, 5e-06, 5e-06, 7.5e-06], \"min\": 5e-06, \"spread\": 0.5",
    );
    let anchors = Anchors::parse(&busy, now()).expect("valid");
    let output = std::env::temp_dir().join("ga-dynamics-anchors-job");
    let _ = std::fs::remove_dir_all(&output);
    let plan = SweepPlan {
        scenes: Vec::new(),
        integrators: vec![Integrator::General(Method::Rk4)],
        steps: vec![1e-3],
        duration: Some(0.02),
        stabilisation: Stabilisation::PROJECTION,
    };
    let mechanisms = MechanismPlan {
        mechanisms: vec![MechanismKind::DoublePendulum, MechanismKind::FourBar],
        steps: vec![1e-3],
    };
    let summary = run_job_with_robots(
        &plan,
        &mechanisms,
        &RobotPlan::default(),
        &report::adaptive::AdaptivePlan::default(),
        &anchors,
        &output,
        false,
    )
    .expect("the job writes its report");
    assert!(summary.failures.is_empty(), "{:?}", summary.failures);
    let text = std::fs::read_to_string(output.join("report.md")).unwrap();
    let row = |label: &str| {
        text.lines()
            .find(|l| l.starts_with(label))
            .unwrap_or_default()
            .to_owned()
    };
    assert!(
        text.contains("MuJoCo's (measured in this run, except those recorded 2026-11-25)"),
        "{text}"
    );
    // M1's MuJoCo cost, 5 µs per step at dt = 1e-3, flagged; M2's recorded 11 µs is not.
    assert!(row("| M1 double pendulum").contains("| 5.0e-3 ± |"), "{}", row("| M1"));
    assert!(row("| M2 four-bar").contains("| 1.1e-2 |"), "{}", row("| M2"));
    assert!(text.contains("±: the repeats of this MuJoCo or Pinocchio figure"));
    assert!(text.contains("Measured in this run: 3 MuJoCo and Pinocchio figures"));
    assert!(text.contains("2026-11-27 18:05 UTC, 1-minute load average 1.16 before and 1.50 after on 2 cores"));
    assert!(text.contains("## MuJoCo and Pinocchio figures measured in this run"));
    assert!(text.contains("| m1 | MuJoCo 4.0 RK4 step at dt = 1e-3 | 5.00 | 5 | 50 % ± | `python double_pendulum.py"));
    let _ = std::fs::remove_dir_all(&output);
}
