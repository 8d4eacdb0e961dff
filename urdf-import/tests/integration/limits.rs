//! The URDF's `<limit>` enforced ([`Limits::Enforce`], docs/limits.md): an arm swinging under gravity stops at its
//! bound and never passes it, where the same arm with the limits ignored swings through; one-sided limits, a
//! continuous joint's limit (ignored, as the URDF specification says) and a mimic follower's (its leader's governs)
//! build; an empty range or a restitution outside [0, 1] is refused naming the joint. The same arm's careless starts
//! (an unknown joint, a value not finite, a joint given twice) are refused naming the joint.

use dynamics::limits::LimitChange;
use dynamics::{simulate, Method, Pga, Schedule, Tolerance};
use urdf_import::{read, BuildError, BuildOptions, ImportOptions, Limits, Robot, RobotStart};

/// A base bolted to the world and an arm hinged to it about y, its centre of mass 0.3 m out along x: gravity swings
/// it down. The hinge is of `kind` with `limit` (attributes of `<limit>`).
fn arm(kind: &str, limit: &str) -> String {
    format!(
        r#"<robot name="arm">
  <link name="base"/>
  <link name="arm">
    <inertial><origin xyz="0.3 0 0"/><mass value="1.0"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="shoulder" type="{kind}">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 1"/><axis xyz="0 1 0"/>
    <limit {limit} effort="10" velocity="3"/>
  </joint>
</robot>"#
    )
}

fn build(text: &str, limits: Limits) -> Result<Robot<Pga>, BuildError> {
    let model = read(text, &ImportOptions::default()).unwrap();
    let options = BuildOptions {
        limits,
        ..BuildOptions::default()
    };
    Robot::<Pga>::build(model, &options)
}

/// The shoulder angle over a 1 s swing from horizontal at rest, and the run's limit transitions.
fn swing(robot: &Robot<Pga>) -> (Vec<f64>, Vec<LimitChange>) {
    let start = robot.initial_states(&RobotStart::default()).unwrap();
    let schedule = Schedule::adaptive(Tolerance::new(1e-11, 1e-11).unwrap(), 1.0, 0.01).unwrap();
    let run = simulate(robot.mechanism(), &start, Method::Dop853Body, &schedule).unwrap();
    let mechanism = robot.mechanism();
    let angles = (0..run.body(0).len())
        .map(|k| {
            let state = run.body(0)[k].state(dynamics::Dynamics::body(mechanism, 0));
            mechanism.joint_positions(&[state], None).unwrap()[0]
        })
        .collect();
    (angles, run.transitions.iter().map(|t| t.change).collect())
}

#[test]
fn an_enforced_limit_stops_the_arm_where_an_ignored_one_does_not() {
    // About y, a positive turn takes x toward -z: gravity turns the arm toward +q, onto the upper bound at 0.4 rad.
    let text = arm("revolute", "lower=\"-0.4\" upper=\"0.4\"");
    let (free, _) = swing(&build(&text, Limits::Ignore).unwrap());
    let highest = free.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(highest > 1.0, "without limits the arm swings to {highest} rad");
    let (held, changes) = swing(&build(&text, Limits::Enforce { restitution: 0.0 }).unwrap());
    let highest = held.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(highest <= 0.4 + 1e-12, "enforced, the arm reaches {highest} rad");
    assert!((held.last().unwrap() - 0.4).abs() < 1e-12, "it rests on the bound");
    assert!(matches!(changes[..], [LimitChange::Held { .. }]), "{changes:?}");
    // Bouncing at restitution 0.5, it meets the bound again and again, slower each time, and comes to rest on it.
    let (bouncing, changes) = swing(&build(&text, Limits::Enforce { restitution: 0.5 }).unwrap());
    let top = bouncing.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(top <= 0.4 + 1e-12, "bouncing, the arm reaches {top} rad: {changes:#?}");
    let bounces = changes
        .iter()
        .filter(|c| matches!(c, LimitChange::Bounced { .. }))
        .count();
    assert!(bounces >= 5, "{changes:?}");
    assert!(matches!(changes.last(), Some(LimitChange::Held { .. })), "{changes:?}");
}

#[test]
fn limits_build_as_the_urdf_means_them_and_careless_ones_are_refused() {
    let enforce = Limits::Enforce { restitution: 0.0 };
    let limited = |text: &str, limits| {
        let robot = build(text, limits).unwrap();
        let count = robot.mechanism().joint_space().unwrap().groups().len();
        let (joint, ..) = robot.mechanism().joint(robot.joint("shoulder").unwrap()).unwrap();
        (
            count,
            joint.name().to_owned(),
            dynamics::Dynamics::limit_count(robot.mechanism()),
        )
    };
    // One-sided: only the upper bound.
    assert_eq!(limited(&arm("revolute", "upper=\"0.4\""), enforce).2, 1);
    // A continuous joint's limits are ignored; a prismatic joint's are enforced.
    assert_eq!(
        limited(&arm("continuous", "lower=\"-0.4\" upper=\"0.4\""), enforce).2,
        0
    );
    assert_eq!(limited(&arm("prismatic", "lower=\"-0.4\" upper=\"0.4\""), enforce).2, 1);
    assert_eq!(
        limited(&arm("revolute", "lower=\"-0.4\" upper=\"0.4\""), Limits::Ignore).2,
        0
    );
    // No range (lower = upper), and restitutions outside [0, 1]: refused naming the joint.
    let error = build(&arm("revolute", "lower=\"0.2\" upper=\"0.2\""), enforce)
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("joint `shoulder`") && error.contains("lower < upper"),
        "{error}"
    );
    for restitution in [-0.1, 1.5, f64::NAN, f64::INFINITY] {
        let text = arm("revolute", "lower=\"-0.4\" upper=\"0.4\"");
        let error = build(&text, Limits::Enforce { restitution }).err().unwrap().to_string();
        assert!(
            error.contains("joint `shoulder`") && error.contains("restitution"),
            "{restitution}: {error}"
        );
    }
}

/// Careless starts, each refused naming the joint: an unknown joint, a position that is not finite, a joint's
/// position or velocity given twice (which of the two would hold is a guess).
#[test]
fn careless_starts_are_refused_naming_the_joint() {
    let robot = build(&arm("revolute", r#"lower="-1" upper="1""#), Limits::Ignore).unwrap();
    let named = |pairs: &[(&str, f64)]| pairs.iter().map(|&(name, value)| (name.to_owned(), value)).collect();
    let cases = [
        (
            RobotStart {
                positions: named(&[("elbow", 0.1)]),
                ..RobotStart::default()
            },
            "no moving joint is named `elbow`",
        ),
        (
            RobotStart {
                positions: named(&[("shoulder", f64::NAN)]),
                ..RobotStart::default()
            },
            "position of joint `shoulder` must be finite",
        ),
        (
            RobotStart {
                positions: named(&[("shoulder", 0.1), ("shoulder", 0.2)]),
                ..RobotStart::default()
            },
            "the start gives the position of joint `shoulder` twice (0.1 and 0.2)",
        ),
        (
            RobotStart {
                velocities: named(&[("shoulder", 1.0), ("shoulder", 1.0)]),
                ..RobotStart::default()
            },
            "the start gives the velocity of joint `shoulder` twice (1 and 1)",
        ),
    ];
    for (start, words) in cases {
        let error = robot.initial_states(&start).unwrap_err().to_string();
        assert!(error.contains(words), "{start:?}: {error}");
    }
}
