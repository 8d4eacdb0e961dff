//! A shortened main job (every scene and mechanism, both algebras, both formulations, RK4 at dt = 1e-3, 2 s)
//! whose report is checked against the references, so the report cannot silently rot.

use dynamics::constraints::Stabilisation;
use dynamics::integrate::{Integrator, Method};
use reference::SceneId;
use report::job::run_job;
use report::measure::agreement;
use report::mechanisms::{MechanismKind, MechanismPlan};
use report::single_bodies::SweepPlan;
use scenarios::MechanismId;
use scene_file::AlgebraKind;

#[test]
fn shortened_job_matches_the_references() {
    let output = std::env::temp_dir().join("ga-dynamics-shortened-job");
    let _ = std::fs::remove_dir_all(&output);
    let plan = SweepPlan {
        scenes: SceneId::ALL.to_vec(),
        integrators: vec![Integrator::General(Method::Rk4)],
        steps: vec![1e-3],
        duration: Some(2.0),
        stabilisation: Stabilisation::PROJECTION,
    };
    let mechanisms = MechanismPlan {
        mechanisms: MechanismKind::ALL.to_vec(),
        steps: vec![1e-3],
    };
    let summary = run_job(&plan, &mechanisms, &output, false).expect("the job writes its output");
    assert!(summary.failures.is_empty(), "{:?}", summary.failures);
    check_mechanisms(&summary.mechanisms);
    // 1 free scene × 2 algebras + 3 hinge/top scenes × 2 algebras × 2 formulations + 2 scene-4 × 3.
    assert_eq!(summary.results.len(), 2 + 12 + 6);

    for (config, result) in &summary.results {
        let outcome = result.as_ref().unwrap();
        let m = &outcome.measurements;
        let label = format!("{:?} {}", config.scene, config.series_label());
        // Bounds: the largest maximum over the run measured on this configuration set (RK4, dt = 1e-3,
        // 2 s; both algebras and formulations) times 5, for machine differences in round-off. Measured:
        // orientation 2.0e-9 (scene 1), 2.2e-10 (2), 4.5e-8 (3a, 3b), 5.6e-7 (sphere: the spin about the
        // rod, whose axial moment is 1e-3, is poorly determined), 3.3e-9 (circle); position 2.5e-10,
        // 1.1e-10, 2.2e-9, 7.7e-9, 1.0e-11; energy drift 7.5e-11, 4.7e-11, 6.0e-11, 5.7e-9, 1.6e-13;
        // scene features at most 1.9e-9 (flip times 2.9e-10 s, period 8.5e-11 s, top features 1.9e-9).
        let (orientation, position, energy) = match config.scene {
            SceneId::Cuboid => (1e-8, 1.3e-9, 3.8e-10),
            SceneId::Pendulum => (1.1e-9, 5.5e-10, 2.4e-10),
            SceneId::TopCusp | SceneId::TopSteady => (2.3e-7, 1.1e-8, 3e-10),
            SceneId::RodOnSphere => (2.8e-6, 3.9e-8, 2.9e-8),
            SceneId::RodOnCircle => (1.7e-8, 5e-11, 8e-13),
        };
        assert!(
            m.orientation_max < orientation,
            "{label}: orientation error {}",
            m.orientation_max
        );
        assert!(m.position_max < position, "{label}: position error {}", m.position_max);
        assert!(
            m.energy_drift_max < energy,
            "{label}: energy drift {}",
            m.energy_drift_max
        );
        // Projection holds every constraint at round-off (theory §10).
        if let Some(violation) = m.violation_max {
            assert!(violation <= 1e-12, "{label}: constraint violation {violation}");
        }
        for feature in &m.features {
            assert!(
                feature.error() < 1e-8,
                "{label}: {} error {}",
                feature.name,
                feature.error()
            );
        }
    }

    // CGA and PGA give the same trajectories with identical steps.
    for (config, result) in summary.results.iter().filter(|(c, _)| c.algebra == AlgebraKind::Cga) {
        let twin = config.same_but(AlgebraKind::Pga);
        let Some((_, Ok(pga))) = summary.results.iter().find(|(c, _)| *c == twin) else {
            continue;
        };
        let (angle, distance) = agreement(&result.as_ref().unwrap().samples, &pga.samples);
        assert!(
            angle < 1e-10 && distance < 1e-10,
            "{config:?}: CGA and PGA differ by {angle} rad, {distance} m"
        );
    }

    // The report states these numbers, and the figures and trajectories exist.
    let report = std::fs::read_to_string(output.join("report.md")).unwrap();
    for scene in SceneId::ALL {
        assert!(
            report.contains(&format!("## Scene {}", scene.label())),
            "report lacks {scene:?}"
        );
    }
    for section in ["### M1 double pendulum", "### M2 four-bar linkage", "### M3 chain"] {
        assert!(report.contains(section), "report lacks {section}");
    }
    // Bodies on the ground: the shipped friction, shape and collision scenes, both algebras, with their figure.
    for part in [
        "## Bodies on the ground",
        "![ground.png](ground.png)",
        "![bodies_meeting.png](bodies_meeting.png)",
        "| solo12_standing | PGA |",
        "| shapes_on_a_floor | CGA |",
        "| stack_and_billiards | PGA |",
        "| ur5_pushes_a_box | CGA |",
        "| box_off_a_ledge | PGA |",
        "Solo-12 stands on its sticking feet",
    ] {
        assert!(report.contains(part), "report lacks {part:?}");
    }
    assert!(!report.contains(".toml: failed"), "a ground scene failed");
    // MuJoCo's errors are at each scene's full T: a 2 s run is not compared with them (no ratio, "n/a").
    for row in [
        "| 1 cuboid",
        "| 2 pendulum",
        "| 3a top",
        "| 4 rod end on circle",
        "| M1 double pendulum",
        "| M2 four-bar linkage",
    ] {
        let line = report.lines().find(|l| l.starts_with(row)).expect(row);
        assert!(line.contains("n/a: shortened run (2 s of T = "), "{line}");
        assert!(!line.contains('×'), "{line}");
    }
    assert!(!report.contains("the five cheapest configurations"));
    let (config, outcome) = summary
        .results
        .iter()
        .find(|(c, _)| c.scene == SceneId::Cuboid)
        .map(|(c, r)| (c, r.as_ref().unwrap()))
        .unwrap();
    let row = format!("| {} | 1e-3 |", config.series_label());
    let line = report.lines().find(|l| l.starts_with(&row)).expect("the cuboid row");
    assert!(
        line.contains(&format!("{:.1e}", outcome.measurements.orientation_end)),
        "{line}"
    );
    for entry in std::fs::read_dir(&output).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "png") {
            assert!(
                std::fs::metadata(&path).unwrap().len() > 10_000,
                "{} is too small",
                path.display()
            );
        }
    }
    assert!(std::fs::read_dir(output.join("trajectories")).unwrap().count() >= summary.results.len());
}

/// The mechanisms' runs: M1 and M2 in 2 algebras × 2 formulations, the chain at 7 lengths and the long run in
/// each algebra.
fn check_mechanisms(results: &[report::mechanisms::MechanismResult]) {
    assert_eq!(results.len(), 4 + 4 + 2 * 8);
    for (config, result) in results {
        let label = format!("{} {}", config.id.label(), config.series_label());
        let m = result.as_ref().unwrap_or_else(|e| panic!("{label}: {e}")).measures;
        // Projection holds every joint at round-off.
        assert!(m.violation <= 1e-12, "{label}: joint violation {}", m.violation);
        // Bounds: measured at 2 s (both algebras and formulations) times 5. M1: orientation 2.7e-9 rad,
        // position 1.3e-9 m, energy 2.4e-9 J; M2: coupler 8.2e-9 m, period 9.9e-10, angles 4.7e-8 rad, energy
        // 8.4e-8 J; the 64-link chain (RKMK6-body): energy 2.8e-9 J.
        match config.id {
            MechanismId::DoublePendulum => {
                assert!(m.orientation_end.unwrap() < 1.4e-8, "{label}: {m:?}");
                assert!(m.position_end.unwrap() < 6.5e-9, "{label}: {m:?}");
                assert!(m.energy_drift < 1.2e-8, "{label}: {m:?}");
            }
            MechanismId::FourBar => {
                let four_bar = m.four_bar.unwrap();
                assert_eq!(four_bar.revolutions, 2, "{label}");
                assert!(four_bar.coupler_error < 4.1e-8, "{label}: {m:?}");
                assert!(four_bar.period_error < 5e-9, "{label}: {m:?}");
                assert!(four_bar.angle_error < 2.4e-7, "{label}: {m:?}");
                assert!(m.energy_drift < 4.2e-7, "{label}: {m:?}");
            }
            MechanismId::Chain(64) if !config.is_chain_timing() => {
                assert!(m.energy_drift < 1.4e-8, "{label}: {m:?}");
            }
            MechanismId::Chain(_) => {}
        }
    }
}

/// Plans of scene 1 and M1 with `method` at (the cuboid's steps, M1's steps), for `duration`.
fn cuboid_and_double_pendulum(
    method: Method,
    (steps, m1_steps): (&[f64], &[f64]),
    duration: f64,
) -> (SweepPlan, MechanismPlan) {
    let plan = SweepPlan {
        scenes: vec![SceneId::Cuboid],
        integrators: vec![Integrator::General(method)],
        steps: steps.to_vec(),
        duration: Some(duration),
        stabilisation: Stabilisation::PROJECTION,
    };
    let mechanisms = MechanismPlan {
        mechanisms: vec![MechanismKind::DoublePendulum],
        steps: m1_steps.to_vec(),
    };
    (plan, mechanisms)
}

/// Runs that fail are listed with their configuration and reason (the command line prints them and exits with
/// an error status): a step that does not divide the sample interval fails every run it is given to.
#[test]
fn failed_runs_are_named_with_their_reason() {
    let output = std::env::temp_dir().join("ga-dynamics-failed-runs");
    let _ = std::fs::remove_dir_all(&output);
    let (plan, mechanisms) = cuboid_and_double_pendulum(Method::Rk4, (&[1e-3, 3e-3], &[3e-3]), 0.02);
    let summary = run_job(&plan, &mechanisms, &output, false).expect("the job writes its report");
    // The cuboid at dt = 3e-3 in both algebras, the double pendulum in both algebras and formulations.
    assert_eq!(summary.failures.len(), 2 + 4, "{:?}", summary.failures);
    for failure in &summary.failures {
        assert!(failure.contains("does not divide the sample interval"), "{failure}");
    }
    assert!(summary.failures.iter().any(|f| f.starts_with("1 cuboid")));
    assert!(summary.failures.iter().any(|f| f.starts_with("M1 double pendulum")));
}

/// The adaptive part of the job: the embedded pair over two tolerances on scene 1 and M1 (2 s), beside the
/// fixed-step runs of the same scenes. Every run succeeds, the tighter tolerance gives the smaller error, the report
/// has the section, its three figures and a table row per run.
#[test]
fn adaptive_runs_are_reported_beside_the_fixed_steps() {
    use report::adaptive::{AdaptiveCase, AdaptivePlan};
    let output = std::env::temp_dir().join("ga-dynamics-adaptive-job");
    let _ = std::fs::remove_dir_all(&output);
    let (plan, mechanisms) = cuboid_and_double_pendulum(Method::Rkmk8Body, (&[1e-2, 5e-3], &[2e-2, 1e-2]), 2.0);
    let adaptive = AdaptivePlan {
        cases: vec![
            AdaptiveCase::SingleBody(SceneId::Cuboid),
            AdaptiveCase::Mechanism(MechanismId::DoublePendulum),
        ],
        methods: vec![
            Method::Dop853Body.into(),
            Method::Rk4.into(),
            dynamics::JointMethod::Dop853.into(),
        ],
        tolerances: vec![1e-6, 1e-10],
        duration: Some(2.0),
    };
    let summary = report::job::run_job_with_robots(
        &plan,
        &mechanisms,
        &report::robots::RobotPlan::default(),
        &adaptive,
        &report::measured_anchors::Anchors::none(),
        &output,
        false,
    )
    .expect("the job writes its report");
    assert!(summary.failures.is_empty(), "{:?}", summary.failures);
    // RK4 has no error estimate, and DOP853-joint runs on the robots only: both left out of the adaptive runs.
    assert_eq!(summary.adaptive.len(), 2 * 2);
    for pair in summary.adaptive.chunks(2) {
        let (loose, tight) = (pair[0].1.as_ref().unwrap(), pair[1].1.as_ref().unwrap());
        assert!(tight.error < loose.error, "{} vs {}", tight.error, loose.error);
        assert!(tight.statistics.accepted > loose.statistics.accepted);
        assert_eq!(loose.steps.len(), loose.statistics.accepted);
        let last = loose.steps.last().unwrap();
        assert!((last.0 - 2.0).abs() < 1e-12, "the steps end at {}", last.0);
        let covered: f64 = loose.steps.iter().map(|s| s.1).sum();
        assert!((covered - 2.0).abs() < 1e-9, "the steps cover {covered} s");
    }
    let text = std::fs::read_to_string(output.join("report.md")).unwrap();
    for part in [
        "## Adaptive steps",
        "![adaptive_single_bodies.png](adaptive_single_bodies.png)",
        "![adaptive_mechanisms_and_robots.png](adaptive_mechanisms_and_robots.png)",
        "![adaptive_tolerance.png](adaptive_tolerance.png)",
        "![adaptive_steps.png](adaptive_steps.png)",
        "### scene 1 cuboid (Dzhanibekov): adaptive steps",
        "### M1 double pendulum: adaptive steps",
        "| DOP853-body | 1e-6 |",
        "| DOP853-body | 1e-10 |",
        "## Joint limits",
        "![limits.png](limits.png)",
        "![limits_energy.png](limits_energy.png)",
        "| pendulum stopping at a limit | PGA | 0 | 1 | 0 |",
        "| double pendulum bouncing off a limit | CGA |",
        "## Contacts",
        "![contacts.png](contacts.png)",
        "| cube dropped flat | PGA |",
        "| cube dropped tumbling | CGA |",
    ] {
        assert!(text.contains(part), "the report lacks {part:?}");
    }
    assert!(!text.contains("failed:"), "a limit or contact scene failed");
    for name in [
        "adaptive_single_bodies.png",
        "adaptive_mechanisms_and_robots.png",
        "adaptive_tolerance.png",
        "adaptive_steps.png",
        "limits.png",
        "limits_energy.png",
        "contacts.png",
    ] {
        assert!(std::fs::metadata(output.join(name)).unwrap().len() > 10_000, "{name}");
    }
}

/// Careless adaptive plans through the library (the command line refuses them before running): each tolerance or
/// duration is a failed run that names its reason, never a panic or a silent result.
#[test]
fn careless_adaptive_plans_fail_with_their_reasons() {
    use report::adaptive::{AdaptiveCase, AdaptivePlan};
    let output = std::env::temp_dir().join("ga-dynamics-careless-adaptive-job");
    let _ = std::fs::remove_dir_all(&output);
    let empty = SweepPlan {
        scenes: Vec::new(),
        integrators: Vec::new(),
        steps: Vec::new(),
        duration: None,
        stabilisation: Stabilisation::PROJECTION,
    };
    // (tolerance, duration, words of the failure)
    let cases = [
        (f64::NAN, Some(0.1), "relative tolerance"),
        (0.0, Some(0.1), "absolute tolerance"),
        (-1e-8, Some(0.1), "relative tolerance"),
        (1.5, Some(0.1), "relative tolerance"),
        (f64::INFINITY, Some(0.1), "relative tolerance"),
        (1e-16, Some(0.1), "absolute tolerance"),
        (1e-8, Some(0.0), "the duration must be positive"),
        (1e-8, Some(-1.0), "the duration must be positive"),
        (1e-8, Some(f64::NAN), "the duration must be positive"),
        (1e-8, Some(1e300), "more than 10000000 samples"),
    ];
    for (tolerance, duration, words) in cases {
        let adaptive = AdaptivePlan {
            cases: vec![AdaptiveCase::SingleBody(SceneId::Cuboid)],
            methods: vec![Method::Dop853Body.into()],
            tolerances: vec![tolerance],
            duration,
        };
        let summary = report::job::run_job_with_robots(
            &empty,
            &MechanismPlan::default(),
            &report::robots::RobotPlan::default(),
            &adaptive,
            &report::measured_anchors::Anchors::none(),
            &output,
            false,
        )
        .expect("the job writes its report");
        assert_eq!(summary.failures.len(), 1, "{tolerance}, {duration:?}");
        assert!(
            summary.failures[0].contains(words),
            "{tolerance}, {duration:?}: {}",
            summary.failures[0]
        );
    }
}
