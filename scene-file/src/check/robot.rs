//! A scene file's robot: its URDF read (at most 64 MiB) and imported by `urdf_import` ([`LoadedRobot`]), its joints
//! found by name, then its gravity and start (joint positions and velocities by name, a floating base's pose and twist)
//! checked ([`CheckedRobot`]).

use std::io::Read as _;
use std::path::{Path, PathBuf};

use nalgebra::{UnitQuaternion, Vector3};
use urdf_import::{
    BaseStart, BuildOptions, ImportOptions, Limits, MasslessSubtrees, MimicMode, RobotModel, RobotStart, Root,
};

use super::values::finite;
use crate::error::{invalid, SceneFileError};
use crate::syntax::robot::{LimitsName, MasslessName, MimicName, RobotSpec, RootName};

/// URDF files larger than this are refused before they are read to the end (a typo naming /dev/zero must not hang).
const MAX_URDF_BYTES: u64 = 64 << 20;

/// The `[robot]` table with its URDF read and imported.
#[derive(Clone, Debug)]
pub struct LoadedRobot {
    /// The table as written.
    pub spec: RobotSpec,
    /// The URDF file as found (the scene file's folder joined with `urdf`).
    pub path: PathBuf,
    /// The URDF imported.
    pub model: RobotModel,
    /// Whether its joint limits are enforced, checked.
    limits: Limits,
}

/// The `[robot]` table checked: its URDF read and imported, its gravity and start checked.
#[derive(Clone, Debug)]
pub struct CheckedRobot {
    /// The table and its URDF.
    pub loaded: LoadedRobot,
    /// Joint positions and velocities by name, a floating base's pose and twist.
    pub start: RobotStart,
    /// Its root, gravity and limits.
    pub options: BuildOptions,
}

impl LoadedRobot {
    /// Reads the URDF at `spec.urdf` relative to `dir` and imports it.
    pub(crate) fn load(spec: &RobotSpec, dir: &Path) -> Result<LoadedRobot, SceneFileError> {
        let limits = spec.limits()?;
        let (path, model) = spec.load(dir)?;
        Ok(LoadedRobot {
            spec: spec.clone(),
            path,
            model,
            limits,
        })
    }

    /// The robot with its gravity and start checked.
    pub(crate) fn checked(self) -> Result<CheckedRobot, SceneFileError> {
        let gravity = finite("robot.gravity", self.spec.gravity)?;
        if gravity.amax() > 1e50 {
            return Err(invalid(
                "robot.gravity",
                format!("{:?} is beyond 1e50 m/s²", self.spec.gravity),
            ));
        }
        let start = self.start()?;
        let options = BuildOptions {
            root: self.spec.root(),
            gravity,
            limits: self.limits,
        };
        Ok(CheckedRobot {
            loaded: self,
            start,
            options,
        })
    }
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
    fn limits(&self) -> Result<Limits, SceneFileError> {
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

    fn root(&self) -> Root {
        match self.root {
            RootName::Fixed => Root::Fixed,
            RootName::Free => Root::Free,
        }
    }

    /// Reads the URDF at `urdf` relative to `dir` and imports it: its path and model, or an error naming the path when
    /// the file cannot be read, the importer's error verbatim otherwise.
    fn load(&self, dir: &Path) -> Result<(PathBuf, RobotModel), SceneFileError> {
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
        let model = urdf_import::read(&text, &self.import_options()).map_err(|e| {
            invalid(
                "robot.urdf",
                format!("{}: {}", path.display(), in_file_terms(&e.to_string())),
            )
        })?;
        Ok((path, model))
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
    pub(crate) fn joint_index(&self, what: &str, name: &str) -> Result<usize, SceneFileError> {
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
    pub(crate) fn single_coordinate_joint(&self, what: &str, name: &str) -> Result<usize, SceneFileError> {
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
    pub(crate) fn links(&self) -> impl Iterator<Item = &str> {
        self.model
            .bodies
            .iter()
            .flat_map(|b| b.links.iter().map(|l| l.name.as_str()))
    }

    /// Whether `name` is one of the robot's joints (moving or frozen).
    pub(crate) fn has_joint(&self, name: &str) -> bool {
        self.model.joints.iter().any(|j| j.name == name) || self.model.frozen_joints.iter().any(|f| f.name == name)
    }

    /// The number of mechanism bodies the robot adds (its root is the world when fixed).
    pub fn body_count(&self) -> usize {
        self.model.bodies.len() - usize::from(self.spec.root == RootName::Fixed)
    }

    /// The start: joint positions and velocities by name, the base's pose and twist (free root only).
    fn start(&self) -> Result<RobotStart, SceneFileError> {
        let spec = &self.spec;
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
}

/// The importer's message with its repairs named as a scene file writes them (`repairs = { … }` in `[robot]`) in
/// place of the Rust options (`ImportOptions::balance_inertia`) the library's users set.
fn in_file_terms(message: &str) -> String {
    const REPAIRS: [(&str, &str); 3] = [
        (
            "ImportOptions::balance_inertia repairs it",
            "`repairs = { balance_inertia = true }` in [robot] repairs it",
        ),
        (
            "MasslessSubtrees::Freeze treats such a joint as fixed, or set bound_mass and bound_inertia",
            "`repairs = { massless_subtrees = \"freeze\" }` in [robot] treats such a joint as fixed, or \
             `repairs = { bound_mass = …, bound_inertia = … }` (kg, kg m²) raises them",
        ),
        (
            "set ImportOptions::bound_mass and bound_inertia to raise them",
            "`repairs = { bound_mass = …, bound_inertia = … }` (kg, kg m²) in [robot] raises them",
        ),
    ];
    REPAIRS
        .iter()
        .fold(message.to_owned(), |text, (rust, file)| text.replace(rust, file))
}
