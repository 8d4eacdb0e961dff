//! A scene file's `[robot]` (docs/scene-files.md): a URDF robot, what its root is fixed to, how its mimics, joint
//! dynamics and limits are modelled, its start and joint torques, and the importer's repairs.

use std::collections::BTreeMap;

use serde::Deserialize;

use super::arrays::{exactly, maybe_exactly};
use super::bodies::{standard_gravity, OrientationSpec};

/// `root = "fixed" | "free"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RootName {
    /// Bolted to the world.
    #[default]
    Fixed,
    /// A floating base.
    Free,
}

/// `collisions = "urdf" | "none"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CollisionsName {
    /// The links touch nothing but through the file's `[[contact]]`s.
    #[default]
    None,
    /// The links' URDF `<collision>` shapes stay above every `[[plane]]`.
    Urdf,
}

/// `mimic = "constraint" | "independent"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MimicName {
    /// A follower coupled to its leader by a constraint.
    #[default]
    Constraint,
    /// Every mimic joint a joint of its own.
    Independent,
}

/// `joint_dynamics = "urdf" | "ignore"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointDynamicsName {
    /// The URDF's `<dynamics>` damping as joint damping (its friction is not modelled).
    #[default]
    Urdf,
    /// No damping.
    Ignore,
}

/// `limits = "ignore" | "enforce"`: the URDF's position limits of revolute and prismatic joints.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitsName {
    /// Not enforced.
    #[default]
    Ignore,
    /// Enforced exactly, as one-sided constraints.
    Enforce,
}

/// `massless_subtrees = "error" | "freeze"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MasslessName {
    /// A moving link with no mass below it is an error.
    #[default]
    Error,
    /// Its joint is frozen at 0.
    Freeze,
}

/// `repairs = { … }`: the importer's opt-in repairs ([`ImportOptions`](urdf_import::ImportOptions)).
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RepairsSpec {
    #[serde(default)]
    pub(crate) massless_subtrees: MasslessName,
    #[serde(default)]
    pub(crate) bound_mass: Option<f64>,
    #[serde(default)]
    pub(crate) bound_inertia: Option<f64>,
    #[serde(default)]
    pub(crate) balance_inertia: bool,
}

/// The `[robot]` table.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSpec {
    /// The URDF file, relative to the scene file.
    pub urdf: String,
    /// What the root link is attached to.
    #[serde(default)]
    pub root: RootName,
    /// How `<mimic>` joints move.
    #[serde(default)]
    pub mimic: MimicName,
    /// Whether the URDF's joint damping applies.
    #[serde(default)]
    pub joint_dynamics: JointDynamicsName,
    /// Whether the URDF's position limits are enforced.
    #[serde(default)]
    pub limits: LimitsName,
    /// Whether the links' URDF `<collision>` shapes take part in the `[[plane]]`s (default "none").
    #[serde(default)]
    pub collisions: CollisionsName,
    /// The restitution of every enforced bound, in [0, 1] (default 0: a joint stops at its bound).
    #[serde(default)]
    pub limit_restitution: Option<f64>,
    /// m/s², world.
    #[serde(default = "standard_gravity")]
    #[serde(deserialize_with = "exactly")]
    pub gravity: [f64; 3],
    /// Joint positions by name (rad or m).
    #[serde(default)]
    pub q: BTreeMap<String, f64>,
    /// Joint velocities by name (rad/s or m/s).
    #[serde(default)]
    pub v: BTreeMap<String, f64>,
    /// The root link frame's origin (m, world), for a free root.
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub base_position: Option<[f64; 3]>,
    /// The root link frame's orientation (world ← root), for a free root.
    #[serde(default)]
    pub base_orientation: Option<OrientationSpec>,
    /// The root link frame origin's velocity (m/s, world), for a free root.
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub base_velocity: Option<[f64; 3]>,
    /// The angular velocity (rad/s, world), for a free root.
    #[serde(default)]
    #[serde(deserialize_with = "maybe_exactly")]
    pub base_angular_velocity: Option<[f64; 3]>,
    /// Constant joint torques (N m) or forces (N) by joint name.
    #[serde(default)]
    pub torque: BTreeMap<String, f64>,
    /// The importer's opt-in repairs of a messy URDF.
    #[serde(default)]
    pub repairs: Option<RepairsSpec>,
}
