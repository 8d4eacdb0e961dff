//! A scene file's `[robot]` (docs/scene-files.md): a URDF robot read by `urdf_import`, built as the first bodies and
//! joints of the scene's mechanism, started at joint positions and velocities by name (and for a floating base its
//! pose and twist), with the URDF's joint damping as force elements and constant joint torques; its joint
//! coordinates are written to `<stem>_joints_<algebra>.csv` in the columns of `reference/data/robots/*.csv`.

use std::collections::BTreeMap;
use std::io::Read as _;
use std::path::{Path, PathBuf};

use dynamics::{Algebra, CoordinateGroup, JointId, JointModel, JointSpace, Mechanism, Reference, State};
use nalgebra::{UnitQuaternion, Vector3};
use serde::Deserialize;
use urdf_import::{
    BaseStart, BuildOptions, ImportOptions, Limits, MasslessSubtrees, MimicMode, Robot, RobotModel, RobotStart, Root,
};

use super::{finite, invalid, standard_gravity, OrientationSpec, SceneFileError};

/// URDF files larger than this are refused before they are read to the end (a typo naming /dev/zero must not hang).
const MAX_URDF_BYTES: u64 = 64 << 20;

/// `root = "fixed" | "free"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RootName {
    #[default]
    Fixed,
    Free,
}

/// `mimic = "constraint" | "independent"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MimicName {
    #[default]
    Constraint,
    Independent,
}

/// `joint_dynamics = "urdf" | "ignore"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointDynamicsName {
    #[default]
    Urdf,
    Ignore,
}

/// `limits = "ignore" | "enforce"`: the URDF's position limits of revolute and prismatic joints.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitsName {
    #[default]
    Ignore,
    Enforce,
}

/// `massless_subtrees = "error" | "freeze"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MasslessName {
    #[default]
    Error,
    Freeze,
}

/// `repairs = { … }`: the importer's opt-in repairs ([`ImportOptions`]).
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RepairsSpec {
    #[serde(default)]
    massless_subtrees: MasslessName,
    #[serde(default)]
    bound_mass: Option<f64>,
    #[serde(default)]
    bound_inertia: Option<f64>,
    #[serde(default)]
    balance_inertia: bool,
}

/// The `[robot]` table.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSpec {
    /// The URDF file, relative to the scene file.
    pub urdf: String,
    #[serde(default)]
    pub root: RootName,
    #[serde(default)]
    pub mimic: MimicName,
    #[serde(default)]
    pub joint_dynamics: JointDynamicsName,
    #[serde(default)]
    pub limits: LimitsName,
    /// The restitution of every enforced bound, in [0, 1] (default 0: a joint stops at its bound).
    #[serde(default)]
    pub limit_restitution: Option<f64>,
    /// m/s², world.
    #[serde(default = "standard_gravity")]
    #[serde(deserialize_with = "super::exactly")]
    pub gravity: [f64; 3],
    /// Joint positions by name (rad or m).
    #[serde(default)]
    pub q: BTreeMap<String, f64>,
    /// Joint velocities by name (rad/s or m/s).
    #[serde(default)]
    pub v: BTreeMap<String, f64>,
    /// The root link frame's origin (m, world), for a free root.
    #[serde(default)]
    #[serde(deserialize_with = "super::maybe_exactly")]
    pub base_position: Option<[f64; 3]>,
    /// The root link frame's orientation (world ← root), for a free root.
    #[serde(default)]
    pub base_orientation: Option<OrientationSpec>,
    /// The root link frame origin's velocity (m/s, world), for a free root.
    #[serde(default)]
    #[serde(deserialize_with = "super::maybe_exactly")]
    pub base_velocity: Option<[f64; 3]>,
    /// The angular velocity (rad/s, world), for a free root.
    #[serde(default)]
    #[serde(deserialize_with = "super::maybe_exactly")]
    pub base_angular_velocity: Option<[f64; 3]>,
    /// Constant joint torques (N m) or forces (N) by joint name.
    #[serde(default)]
    pub torque: BTreeMap<String, f64>,
    #[serde(default)]
    pub repairs: Option<RepairsSpec>,
}

/// The robot's URDF, read and imported.
#[derive(Clone, Debug)]
pub struct LoadedRobot {
    /// The URDF file as found (the scene file's folder joined with `urdf`).
    pub path: PathBuf,
    pub model: RobotModel,
}

impl RobotSpec {
    fn import_options(&self) -> ImportOptions {
        let repairs = self.repairs.unwrap_or_default();
        ImportOptions {
            massless_subtrees: match repairs.massless_subtrees {
                MasslessName::Error => MasslessSubtrees::Error,
                MasslessName::Freeze => MasslessSubtrees::Freeze,
            },
            bound_mass: repairs.bound_mass,
            bound_inertia: repairs.bound_inertia,
            balance_inertia: repairs.balance_inertia,
            mimic: match self.mimic {
                MimicName::Constraint => MimicMode::Constraint,
                MimicName::Independent => MimicMode::Independent,
            },
        }
    }

    /// The importer's limit option: a restitution only with `limits = "enforce"`, and in [0, 1].
    pub fn limits(&self) -> Result<Limits, SceneFileError> {
        match (self.limits, self.limit_restitution) {
            (LimitsName::Ignore, None) => Ok(Limits::Ignore),
            (LimitsName::Ignore, Some(_)) => Err(invalid(
                "robot.limit_restitution",
                "applies to enforced limits only: write limits = \"enforce\" or leave it out",
            )),
            (LimitsName::Enforce, restitution) => {
                let restitution = restitution.unwrap_or(0.0);
                if !(0.0..=1.0).contains(&restitution) {
                    return Err(invalid(
                        "robot.limit_restitution",
                        format!("{restitution:?} must be in [0, 1]"),
                    ));
                }
                Ok(Limits::Enforce { restitution })
            }
        }
    }

    pub fn root(&self) -> Root {
        match self.root {
            RootName::Fixed => Root::Fixed,
            RootName::Free => Root::Free,
        }
    }

    /// Reads the URDF at `urdf` relative to `dir` and imports it: an error naming the path when the file cannot be
    /// read, the importer's error verbatim otherwise.
    pub fn load(&self, dir: &Path) -> Result<LoadedRobot, SceneFileError> {
        self.limits()?;
        let repairs = self.repairs.unwrap_or_default();
        for (key, value) in [
            ("bound_mass", repairs.bound_mass),
            ("bound_inertia", repairs.bound_inertia),
        ] {
            if let Some(value) = value {
                if !(value.is_finite() && value > 0.0 && value <= 1e50) {
                    return Err(invalid(
                        format!("robot.repairs.{key}"),
                        format!("{value:?} must be positive, finite and at most 1e50"),
                    ));
                }
            }
        }
        let path = dir.join(&self.urdf);
        let cannot = |e: &dyn std::fmt::Display| invalid("robot.urdf", format!("cannot read {}: {e}", path.display()));
        let file = std::fs::File::open(&path).map_err(|e| cannot(&e))?;
        let mut bytes = Vec::new();
        file.take(MAX_URDF_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| cannot(&e))?;
        if bytes.len() as u64 > MAX_URDF_BYTES {
            return Err(cannot(&format!("it is larger than {MAX_URDF_BYTES} bytes")));
        }
        let text = String::from_utf8(bytes).map_err(|e| cannot(&format!("it is not UTF-8 ({e})")))?;
        let model = urdf_import::read(&text, &self.import_options())
            .map_err(|e| invalid("robot.urdf", format!("{}: {e}", path.display())))?;
        Ok(LoadedRobot { path, model })
    }
}

impl LoadedRobot {
    /// The moving joints' names in file order, for messages.
    fn joint_list(&self) -> String {
        let names: Vec<&str> = self.model.joints.iter().map(|j| j.name.as_str()).collect();
        if names.is_empty() {
            "it has none".to_owned()
        } else {
            format!("the robot's joints: {}", names.join(", "))
        }
    }

    /// The index of the moving joint `name` in the model, or an error under `what` naming it and listing the robot's
    /// joints (or saying it is frozen).
    pub fn joint_index(&self, what: &str, name: &str) -> Result<usize, SceneFileError> {
        if let Some(index) = self.model.joints.iter().position(|j| j.name == name) {
            return Ok(index);
        }
        if self.model.frozen_joints.iter().any(|f| f.name == name) {
            return Err(invalid(
                what,
                format!(
                    "joint `{name}` is frozen at 0 (repairs.massless_subtrees = \"freeze\": its subtree has no mass), \
                     so it has no coordinate"
                ),
            ));
        }
        Err(invalid(
            what,
            format!("no joint named `{name}` ({})", self.joint_list()),
        ))
    }

    /// The index of a one-coordinate moving joint.
    pub fn single_coordinate_joint(&self, what: &str, name: &str) -> Result<usize, SceneFileError> {
        let index = self.joint_index(what, name)?;
        let kind = self.model.joints[index].kind;
        if kind.degrees_of_freedom() != 1 {
            return Err(invalid(
                what,
                format!(
                    "joint `{name}` is {kind}, with {} coordinates; only one-coordinate joints take a value here",
                    kind.degrees_of_freedom()
                ),
            ));
        }
        Ok(index)
    }

    /// Every link name, body by body.
    pub fn links(&self) -> impl Iterator<Item = &str> {
        self.model
            .bodies
            .iter()
            .flat_map(|b| b.links.iter().map(|l| l.name.as_str()))
    }

    /// Whether `name` is one of the robot's joints (moving or frozen).
    pub fn has_joint(&self, name: &str) -> bool {
        self.model.joints.iter().any(|j| j.name == name) || self.model.frozen_joints.iter().any(|f| f.name == name)
    }

    /// The number of mechanism bodies the robot adds (its root is the world when fixed).
    pub fn body_count(&self, spec: &RobotSpec) -> usize {
        self.model.bodies.len() - usize::from(spec.root == RootName::Fixed)
    }

    /// The start: joint positions and velocities by name, the base's pose and twist (free root only).
    fn start(&self, spec: &RobotSpec) -> Result<RobotStart, SceneFileError> {
        let mut start = RobotStart::default();
        for (key, values, target) in [
            ("q", &spec.q, &mut start.positions),
            ("v", &spec.v, &mut start.velocities),
        ] {
            for (name, value) in values {
                let what = format!("robot.{key}");
                self.single_coordinate_joint(&what, name)?;
                if !(value.is_finite() && value.abs() <= 1e50) {
                    return Err(invalid(
                        format!("{what}.{name}"),
                        format!("{value:?} is not finite or beyond 1e50"),
                    ));
                }
                target.push((name.clone(), *value));
            }
        }
        if spec.limits == LimitsName::Enforce {
            // A start outside a limit is refused here by the joint's name and value (the states alone read an angle
            // only modulo 2π); a coupled follower has its leader's limit only.
            let coupled =
                |joint: &urdf_import::MovingJoint| joint.mimic.is_some() && spec.mimic == MimicName::Constraint;
            for joint in self.model.joints.iter().filter(|joint| !coupled(joint)) {
                let Some((lower, upper)) = joint.position_range() else {
                    continue;
                };
                let q = (start.positions.iter().find(|(name, _)| *name == joint.name)).map_or(0.0, |(_, q)| *q);
                if q < lower - dynamics::simulate::AT_BOUND || q > upper + dynamics::simulate::AT_BOUND {
                    return Err(invalid(
                        format!("robot.q.{}", joint.name),
                        format!("{q:?} is outside the joint's limits [{lower:?}, {upper:?}] (limits = \"enforce\")"),
                    ));
                }
            }
        }
        let given = [
            ("robot.base_position", spec.base_position.is_some()),
            ("robot.base_orientation", spec.base_orientation.is_some()),
            ("robot.base_velocity", spec.base_velocity.is_some()),
            ("robot.base_angular_velocity", spec.base_angular_velocity.is_some()),
        ];
        if spec.root == RootName::Fixed {
            if let Some((what, _)) = given.iter().find(|(_, given)| *given) {
                return Err(invalid(
                    *what,
                    "the root is fixed to the world (root = \"fixed\"): a base pose or twist needs root = \"free\"",
                ));
            }
            return Ok(start);
        }
        let vector = |what: &str, value: Option<[f64; 3]>| match value {
            Some(v) => finite(what, v),
            None => Ok(Vector3::zeros()),
        };
        start.base = BaseStart {
            position: vector("robot.base_position", spec.base_position)?,
            orientation: match &spec.base_orientation {
                Some(o) => o.rotation_of("robot.base_orientation")?,
                None => UnitQuaternion::identity(),
            },
            velocity: vector("robot.base_velocity", spec.base_velocity)?,
            angular_velocity: vector("robot.base_angular_velocity", spec.base_angular_velocity)?,
        };
        Ok(start)
    }

    /// The robot built in algebra `A` (its mechanism the scene's first bodies and joints) and its bodies' states at
    /// the start.
    pub fn build<A: Algebra>(&self, spec: &RobotSpec) -> Result<(Robot<A>, Vec<State<A>>), SceneFileError> {
        let gravity = finite("robot.gravity", spec.gravity)?;
        if gravity.amax() > 1e50 {
            return Err(invalid(
                "robot.gravity",
                format!("{:?} is beyond 1e50 m/s²", spec.gravity),
            ));
        }
        let start = self.start(spec)?;
        let options = BuildOptions {
            root: spec.root(),
            gravity,
            limits: spec.limits()?,
        };
        let robot = Robot::<A>::build(self.model.clone(), &options).map_err(|e| invalid("robot", e.to_string()))?;
        let states = robot
            .initial_states(&start)
            .map_err(|e| invalid("robot", format!("the start: {e}")))?;
        Ok((robot, states))
    }
}

/// A robot joint's model, its child and parent bodies (mechanism indices; `None`: the world) and where its position
/// coordinates start.
pub type RobotJoint = (JointModel, usize, Option<usize>, usize);

/// Where a joints-CSV column comes from.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// A position coordinate of the mechanism's joint space.
    Position(usize),
    /// A frozen joint's constant coordinate.
    Constant(f64),
}

/// The columns of `<stem>_joints_<algebra>.csv` between `t` and `energy`: every non-fixed joint in URDF file order
/// (frozen ones at their constant 0), then for a free root `base.x, base.y, base.z, base.qw, base.qx, base.qy,
/// base.qz` (the root link frame, world ← root).
#[derive(Clone, Debug)]
pub struct RobotColumns {
    pub headers: Vec<String>,
    sources: Vec<Source>,
}

impl RobotColumns {
    /// The columns' values at joint positions `q` (the mechanism's joint space).
    pub fn row(&self, q: &[f64]) -> Vec<f64> {
        self.sources
            .iter()
            .map(|s| match s {
                Source::Position(i) => q[*i],
                Source::Constant(value) => *value,
            })
            .collect()
    }
}

/// The suffixes of a URDF joint kind's coordinates, with the constant value of a frozen one.
fn frozen_coordinates(kind: urdf_import::JointKind) -> &'static [(&'static str, f64)] {
    match kind {
        urdf_import::JointKind::Planar => &[("x", 0.0), ("y", 0.0), ("theta", 0.0)],
        urdf_import::JointKind::Floating => &[
            ("x", 0.0),
            ("y", 0.0),
            ("z", 0.0),
            ("qw", 1.0),
            ("qx", 0.0),
            ("qy", 0.0),
            ("qz", 0.0),
        ],
        urdf_import::JointKind::Fixed => &[],
        _ => &[("", 0.0)],
    }
}

/// A moving URDF joint of `robot` and its coordinates in `space` (the robot's mechanism, with the scene's bodies
/// added).
fn coordinate_group<'s, A: Algebra>(
    robot: &Robot<A>,
    space: &'s JointSpace,
    name: &str,
) -> Result<(JointId, &'s CoordinateGroup), SceneFileError> {
    let id = robot.joint(name).expect("every moving joint is in the mechanism");
    let group = space
        .groups()
        .iter()
        .find(|g| g.joint() == Some(id))
        .ok_or_else(|| invalid("robot", format!("joint {name} has no coordinates")))?;
    Ok((id, group))
}

impl LoadedRobot {
    /// The joints CSV's columns in `mechanism` (the robot's, with the scene's bodies added).
    pub fn columns<A: Algebra>(
        &self,
        robot: &Robot<A>,
        mechanism: &Mechanism<A>,
    ) -> Result<RobotColumns, SceneFileError> {
        let space = mechanism
            .joint_space()
            .map_err(|e| invalid("robot", format!("no joint coordinates: {e}")))?;
        // Moving and frozen joints in file order (by line).
        let mut entries: Vec<(u32, Vec<(String, Source)>)> = Vec::new();
        for joint in &self.model.joints {
            let (_, group) = coordinate_group(robot, space, &joint.name)?;
            let suffixes = group.model().kind().position_names();
            let columns = suffixes
                .iter()
                .enumerate()
                .map(|(k, suffix)| {
                    let header = if suffix.is_empty() {
                        joint.name.clone()
                    } else {
                        format!("{}.{suffix}", joint.name)
                    };
                    (header, Source::Position(group.position_offset() + k))
                })
                .collect();
            entries.push((joint.line, columns));
        }
        for frozen in &self.model.frozen_joints {
            let columns = frozen_coordinates(frozen.kind)
                .iter()
                .map(|(suffix, value)| {
                    let header = if suffix.is_empty() {
                        frozen.name.clone()
                    } else {
                        format!("{}.{suffix}", frozen.name)
                    };
                    (header, Source::Constant(*value))
                })
                .collect();
            entries.push((frozen.line, columns));
        }
        entries.sort_by_key(|(line, _)| *line);
        let (mut headers, mut sources): (Vec<String>, Vec<Source>) = entries.into_iter().flat_map(|(_, c)| c).unzip();
        if let Some(base) = robot.base() {
            let group = space
                .groups()
                .iter()
                .find(|g| g.body() == base && g.joint().is_none())
                .ok_or_else(|| invalid("robot", "the free root has no coordinates"))?;
            for (k, suffix) in ["x", "y", "z", "qw", "qx", "qy", "qz"].iter().enumerate() {
                headers.push(format!("base.{suffix}"));
                sources.push(Source::Position(group.position_offset() + k));
            }
        }
        Ok(RobotColumns { headers, sources })
    }

    /// Every moving joint's model with its child and parent body (mechanism indices) and where its positions start,
    /// to measure how far the bodies are from the pose their joint coordinates give.
    pub fn joint_models<A: Algebra>(
        &self,
        robot: &Robot<A>,
        mechanism: &Mechanism<A>,
    ) -> Result<Vec<RobotJoint>, SceneFileError> {
        let space = mechanism
            .joint_space()
            .map_err(|e| invalid("robot", format!("no joint coordinates: {e}")))?;
        self.model
            .joints
            .iter()
            .map(|joint| {
                let (id, group) = coordinate_group(robot, space, &joint.name)?;
                let parent = match mechanism.joint(id).map(|(_, _, reference)| reference) {
                    Some(Reference::Body(body)) => Some(body.index()),
                    _ => None,
                };
                Ok((
                    group.model().clone(),
                    group.body().index(),
                    parent,
                    group.position_offset(),
                ))
            })
            .collect()
    }
}
