//! The scene in words, for `summary.md`: how it steps, the robot (its model, repairs and warnings, what of the URDF
//! is not modelled), the force elements and drives.

use std::fmt::Write as _;

use scene_file::syntax::elements::{DriveSpec, TimeValue};
use scene_file::syntax::robot::{JointDynamicsName, LimitsName, MimicName, RootName};
use scene_file::{CheckedScene, LoadedRobot, Stepping};

use crate::markdown::escape;

/// How the run steps, for titles and summaries: "dt = 0.001 s", or "tolerance = 1e-8 (adaptive steps)".
pub(crate) fn stepping(scene: &CheckedScene) -> String {
    match scene.stepping {
        Stepping::Adaptive { tolerance } => format!("tolerance = {tolerance:e} (adaptive steps)"),
        Stepping::Fixed { dt } => format!("dt = {dt:e} s"),
    }
}

/// The force elements, for the summary: "spring 1 (spring-damper, k = 100 N/m, …)".
pub(crate) fn element_list(scene: &CheckedScene) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(robot) = scene.robot.as_ref().map(|robot| &robot.loaded) {
        if robot.spec.joint_dynamics == JointDynamicsName::Urdf {
            for j in robot.model.joints.iter().filter(|j| j.damping > 0.0) {
                out.push(format!("{} damping (URDF): {} on {}", j.name, j.damping, j.name));
            }
        }
        for (name, value) in &robot.spec.torque {
            out.push(format!("torque on {name}: {value} (constant)"));
        }
    }
    for (k, s) in scene.springs.iter().enumerate() {
        out.push(format!(
            "{} (spring-damper {} – {}: k = {} N/m, c = {} N s/m, rest length {} m)",
            s.name.clone().unwrap_or_else(|| format!("spring {}", k + 1)),
            s.between[0],
            s.between[1],
            s.stiffness,
            s.damping,
            s.rest_length
        ));
    }
    for (k, c) in scene.couples.iter().enumerate() {
        out.push(format!(
            "{} (couple {:?} N m on {}, its opposite on {})",
            c.name.clone().unwrap_or_else(|| format!("couple {}", k + 1)),
            c.moment,
            c.between[0],
            c.between[1]
        ));
    }
    for t in &scene.joint_torques {
        out.push(format!(
            "{} (joint torque {} on {})",
            t.name.clone().unwrap_or_else(|| format!("torque on {}", t.joint)),
            describe_time_value(&t.torque),
            t.joint
        ));
    }
    for d in &scene.joint_dampings {
        out.push(format!(
            "{} (joint damping {} on {})",
            d.name.clone().unwrap_or_else(|| format!("damping on {}", d.joint)),
            d.damping,
            d.joint
        ));
    }
    for (k, pd) in scene.pds.iter().enumerate() {
        let targets: Vec<String> = pd.target.iter().map(|(j, v)| format!("{j} → {v}")).collect();
        out.push(format!(
            "{} (PD, kp = {}, kd = {}{}: {})",
            pd.name.clone().unwrap_or_else(|| format!("pd {}", k + 1)),
            pd.kp,
            pd.kd,
            if pd.gravity_compensation {
                ", with the bias forces h(q, v) added"
            } else {
                ""
            },
            targets.join(", ")
        ));
    }
    for j in &scene.layout.joints {
        if let Some(drive) = j.drive {
            out.push(format!("drive of {}: q(t) = {}", j.name, describe_drive(&drive)));
        }
    }
    out
}

/// "2 N m" or "sine", for the summary.
fn describe_time_value(value: &TimeValue) -> String {
    match value {
        TimeValue::Constant(value) => format!("{value}"),
        TimeValue::Sine(s) => format!(
            "{} + {} sin(2π {} Hz t + {})",
            s.offset, s.amplitude, s.frequency, s.phase
        ),
    }
}

/// For the summary.
fn describe_drive(drive: &DriveSpec) -> String {
    match drive {
        DriveSpec::ConstantRate { start, rate } => format!("{start} + {rate} t"),
        DriveSpec::Sine(s) => format!(
            "{} + {} sin(2π {} Hz t + {})",
            s.offset, s.amplitude, s.frequency, s.phase
        ),
    }
}

/// What the summary says about the robot: the model, the repairs and warnings, what of the URDF is not modelled.
pub(crate) fn robot_summary(robot: &LoadedRobot) -> String {
    let mut out = String::new();
    write_robot_model(&mut out, robot);
    write_robot_lists(&mut out, robot);
    out
}

/// The robot's model: its links, bodies, root, joints and degrees of freedom.
fn write_robot_model(out: &mut String, robot: &LoadedRobot) {
    let (model, spec) = (&robot.model, &robot.spec);
    let links: usize = model.bodies.iter().map(|b| b.links.len()).sum();
    let kinds: Vec<String> = model
        .joint_counts()
        .iter()
        .map(|(kind, n)| format!("{n} {kind}"))
        .collect();
    let joint_dof: usize = model.joints.iter().map(|j| j.kind.degrees_of_freedom()).sum();
    let free = spec.root == RootName::Free;
    let _ = writeln!(
        out,
        "Robot `{}` from {}: {links} links, {} merged into other links' bodies (fixed joints), so {} bodies ({} \
         moving); root {}; joints: {}; {} degrees of freedom{}.\n",
        escape(&model.name),
        escape(&robot.path.display().to_string()),
        model.merged_links,
        model.bodies.len(),
        robot.body_count(),
        if free {
            "free (a floating base)"
        } else {
            "fixed to the world"
        },
        if kinds.is_empty() {
            "none".to_owned()
        } else {
            kinds.join(", ")
        },
        joint_dof + if free { 6 } else { 0 },
        if free { " (6 of them the base's)" } else { "" },
    );
}

/// `title` and its items as a list item with a nested list, or "none".
fn write_list(out: &mut String, title: &str, items: Vec<String>) {
    if items.is_empty() {
        let _ = writeln!(out, "- {title}: none");
    } else {
        let _ = writeln!(out, "- {title}:");
        for item in items {
            let _ = writeln!(out, "  - {}", escape(&item));
        }
    }
}

/// The repairs and warnings of the import, and what of the URDF is modelled and how: joint damping and friction,
/// limits, mimics, the elements ignored, the gravity.
fn write_robot_lists(out: &mut String, robot: &LoadedRobot) {
    let (model, spec) = (&robot.model, &robot.spec);
    write_list(out, "Repairs", model.repairs.iter().map(ToString::to_string).collect());
    write_list(
        out,
        "Frozen joints (massless subtrees, coordinate 0)",
        model
            .frozen_joints
            .iter()
            .map(|f| format!("{} ({}, line {})", f.name, f.kind, f.line))
            .collect(),
    );
    write_list(out, "Importer warnings", model.warnings.clone());
    let damped: Vec<String> = model
        .joints
        .iter()
        .filter(|j| j.damping > 0.0)
        .map(|j| format!("{}: {}", j.name, j.damping))
        .collect();
    let friction: Vec<String> = model
        .joints
        .iter()
        .filter(|j| j.friction != 0.0)
        .map(|j| format!("{}: {} (not modelled)", j.name, j.friction))
        .collect();
    match spec.joint_dynamics {
        JointDynamicsName::Urdf => {
            write_list(
                out,
                "URDF joint damping, applied as joint damping (N m s/rad or N s/m)",
                damped,
            );
            write_list(out, "URDF Coulomb friction, not modelled", friction);
        }
        JointDynamicsName::Ignore => {
            write_list(out, "URDF joint damping, ignored (joint_dynamics = \"ignore\")", damped);
            write_list(
                out,
                "URDF Coulomb friction, ignored (joint_dynamics = \"ignore\"; never modelled)",
                friction,
            );
        }
    }
    let limited = model
        .joints
        .iter()
        .filter(|j| j.limit.is_some_and(|l| l.lower.is_some() || l.upper.is_some()))
        .count();
    let _ = match spec.limits {
        LimitsName::Ignore => writeln!(
            out,
            "- Joint limits: not enforced (limits = \"ignore\"); {limited} joints have position limits in the URDF"
        ),
        LimitsName::Enforce => writeln!(
            out,
            "- Joint limits: enforced on the {limited} joints with position limits in the URDF (restitution {})",
            spec.limit_restitution.unwrap_or(0.0)
        ),
    };
    let mimics: Vec<String> = model
        .joints
        .iter()
        .filter_map(|j| {
            j.mimic
                .as_ref()
                .map(|m| format!("{} = {} {} + {}", j.name, m.multiplier, m.joint, m.offset))
        })
        .collect();
    write_list(
        out,
        match spec.mimic {
            MimicName::Constraint => "Mimics, coupled (mimic = \"constraint\")",
            MimicName::Independent => "Mimics, independent joints (mimic = \"independent\")",
        },
        mimics,
    );
    if !model.ignored.is_empty() {
        let ignored: Vec<String> = model.ignored.iter().map(|(tag, n)| format!("<{tag}> × {n}")).collect();
        let _ = writeln!(out, "- Ignored elements: {}", escape(&ignored.join(", ")));
    }
    let _ = writeln!(out, "- Gravity on the robot's bodies: {:?} m/s²\n", spec.gravity);
}
