//! Two real robots moving passively under gravity, with Pinocchio's reference motion (`data/robots/README.md`): the
//! UR5 arm (fixed base, 6 revolute joints) and the Solo-12 quadruped (floating base, 12 revolute joints). Each has
//! its URDF (copied unchanged from example-robot-data 6.0.0), its start (joint positions and velocities by name, the
//! base's pose and twist), the accelerations at t = 0, the motion over 1 s sampled every 0.01 s, and the cost anchors
//! of Pinocchio and MuJoCo measured when the reference was made.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde_json::Value;

/// A reference robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RobotId {
    /// Universal Robots UR5: fixed base, a chain of 6 revolute joints.
    Ur5,
    /// ODRI Solo-12: floating base, four legs of three revolute joints.
    Solo12,
}

impl RobotId {
    /// Both robots.
    pub const ALL: [RobotId; 2] = [RobotId::Ur5, RobotId::Solo12];

    /// "ur5" or "solo12", as the files are named.
    pub fn name(self) -> &'static str {
        match self {
            RobotId::Ur5 => "ur5",
            RobotId::Solo12 => "solo12",
        }
    }

    /// The URDF text.
    pub fn urdf(self) -> &'static str {
        match self {
            RobotId::Ur5 => include_str!("../data/robots/ur5_robot.urdf"),
            RobotId::Solo12 => include_str!("../data/robots/solo12.urdf"),
        }
    }

    fn json(self) -> &'static str {
        match self {
            RobotId::Ur5 => include_str!("../data/robots/ur5.json"),
            RobotId::Solo12 => include_str!("../data/robots/solo12.json"),
        }
    }

    fn csv(self) -> &'static str {
        match self {
            RobotId::Ur5 => include_str!("../data/robots/ur5.csv"),
            RobotId::Solo12 => include_str!("../data/robots/solo12.csv"),
        }
    }

    /// The reference: its start, accelerations, motion and cost anchors.
    pub fn reference(self) -> Result<RobotReference, RobotDataError> {
        RobotReference::parse(self.name(), self.json(), self.csv())
    }
}

/// A floating base's pose and twist: the root link frame's origin and orientation (world ← root), the velocity of its
/// origin and the angular velocity, world axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaseState {
    /// m, world.
    pub position: Vector3<f64>,
    /// world ← root.
    pub orientation: UnitQuaternion<f64>,
    /// m/s, world axes.
    pub velocity: Vector3<f64>,
    /// rad/s, world axes.
    pub angular_velocity: Vector3<f64>,
}

/// A floating base's acceleration at t = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaseAcceleration {
    /// The second derivative of the root frame origin's world position (m/s²).
    pub origin: Vector3<f64>,
    /// The derivative of the world angular velocity (rad/s²).
    pub angular: Vector3<f64>,
    /// Pinocchio's free-flyer `v̇`: the time derivatives of the root frame's own twist coordinates (linear, then
    /// angular; m/s², rad/s²).
    pub local: [f64; 6],
}

/// One sample of the reference motion.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotSample {
    /// s.
    pub t: f64,
    /// The joint positions in URDF file order (rad or m; continuous joints unwrapped).
    pub joints: Vec<f64>,
    /// The floating base's root frame: origin (m) and orientation (world ← root; continuous in time, not
    /// sign-normalised).
    pub base: Option<(Vector3<f64>, UnitQuaternion<f64>)>,
    /// Kinetic plus potential energy (J, potential zero at z = 0).
    pub energy: f64,
}

/// MuJoCo's RK4 on the same URDF at one step size, as measured when the reference was made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MujocoRun {
    /// The step (s).
    pub dt: f64,
    /// The largest joint position error against the reference over the run (rad).
    pub max_joint_error: f64,
    /// CPU time per step (µs).
    pub microseconds_per_step: f64,
}

/// A robot's reference.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotReference {
    /// "ur5" or "solo12".
    pub name: &'static str,
    /// Whether the root is a floating base.
    pub free_base: bool,
    /// The moving joints in URDF file order.
    pub joints: Vec<String>,
    /// The start: joint positions (rad or m) in URDF file order.
    pub positions: Vec<f64>,
    /// The start: joint velocities (rad/s or m/s) in URDF file order.
    pub velocities: Vec<f64>,
    /// The floating base's start.
    pub base: Option<BaseState>,
    /// q̈ at t = 0 in URDF file order (rad/s² or m/s²).
    pub accelerations: Vec<f64>,
    /// The floating base's acceleration at t = 0.
    pub base_acceleration: Option<BaseAcceleration>,
    /// The gravitational acceleration (m/s², world).
    pub gravity: Vector3<f64>,
    /// The motion, every 0.01 s from 0 to 1 s.
    pub samples: Vec<RobotSample>,
    /// Pinocchio's C++ ABA, µs per evaluation (median), when the reference was made.
    pub pinocchio_aba_microseconds: f64,
    /// MuJoCo's RK4 runs.
    pub mujoco: Vec<MujocoRun>,
    /// The reference's own accuracy estimate (largest position difference between refined runs, rad or m).
    pub accuracy: f64,
}

/// The embedded robot data does not read as expected (a key, a number or a CSV row), with what was wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("robot reference data: {0}")]
pub struct RobotDataError(String);

fn bad(reason: impl Into<String>) -> RobotDataError {
    RobotDataError(reason.into())
}

fn number(value: &Value, path: &str) -> Result<f64, RobotDataError> {
    value.as_f64().ok_or_else(|| bad(format!("{path} is not a number")))
}

fn vector(value: &Value, path: &str) -> Result<Vector3<f64>, RobotDataError> {
    let items = value
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| bad(format!("{path} is not 3 numbers")))?;
    Ok(Vector3::new(
        number(&items[0], path)?,
        number(&items[1], path)?,
        number(&items[2], path)?,
    ))
}

fn field<'a>(value: &'a Value, key: &str) -> Result<&'a Value, RobotDataError> {
    value.get(key).ok_or_else(|| bad(format!("missing `{key}`")))
}

impl RobotReference {
    fn parse(name: &'static str, json: &str, csv: &str) -> Result<Self, RobotDataError> {
        let root: Value = serde_json::from_str(json).map_err(|e| bad(format!("{name}.json: {e}")))?;
        let joints: Vec<String> = field(&root, "joints")?
            .as_array()
            .ok_or_else(|| bad("`joints` is not a list"))?
            .iter()
            .map(|j| {
                j.as_str()
                    .map(str::to_owned)
                    .ok_or_else(|| bad("a joint name is not a string"))
            })
            .collect::<Result<_, _>>()?;
        let by_name = |key: &str| -> Result<Vec<f64>, RobotDataError> {
            let table = field(&root, key)?;
            joints
                .iter()
                .map(|j| number(field(table, j)?, &format!("{key}.{j}")))
                .collect()
        };
        let free_base = field(&root, "root")?.as_str() == Some("free-flyer");
        let base = if free_base {
            let b = field(&root, "base_initial")?;
            let q = field(b, "quaternion_wxyz")?
                .as_array()
                .filter(|a| a.len() == 4)
                .ok_or_else(|| bad("base quaternion"))?;
            let q = Quaternion::new(
                number(&q[0], "qw")?,
                number(&q[1], "qx")?,
                number(&q[2], "qy")?,
                number(&q[3], "qz")?,
            );
            Some(BaseState {
                position: vector(field(b, "position")?, "base position")?,
                orientation: UnitQuaternion::from_quaternion(q),
                velocity: vector(field(b, "linear_velocity")?, "base velocity")?,
                angular_velocity: vector(field(b, "angular_velocity")?, "base angular velocity")?,
            })
        } else {
            None
        };
        let accelerations = by_name("qdd_t0")?;
        let base_acceleration = if free_base {
            let b = field(field(&root, "qdd_t0")?, "base")?;
            let local = field(b, "pinocchio_vdot_local")?
                .as_array()
                .filter(|a| a.len() == 6)
                .ok_or_else(|| bad("vdot"))?;
            let mut l = [0.0; 6];
            for (out, v) in l.iter_mut().zip(local) {
                *out = number(v, "pinocchio_vdot_local")?;
            }
            Some(BaseAcceleration {
                origin: vector(field(b, "origin_linear_acceleration")?, "base acceleration")?,
                angular: vector(field(b, "angular_acceleration")?, "base angular acceleration")?,
                local: l,
            })
        } else {
            None
        };
        let mujoco = field(field(&root, "mujoco")?, "rk4")?
            .as_object()
            .ok_or_else(|| bad("mujoco.rk4"))?
            .iter()
            .map(|(dt, run)| {
                Ok(MujocoRun {
                    dt: dt.parse().map_err(|_| bad(format!("mujoco step {dt}")))?,
                    max_joint_error: number(field(run, "max_joint_pos_err")?, "max_joint_pos_err")?,
                    microseconds_per_step: number(field(run, "us_per_step")?, "us_per_step")?,
                })
            })
            .collect::<Result<Vec<_>, RobotDataError>>()?;
        let samples = parse_samples(csv, &joints, free_base)?;
        Ok(RobotReference {
            name,
            free_base,
            positions: by_name("q0")?,
            velocities: by_name("v0")?,
            joints,
            base,
            accelerations,
            base_acceleration,
            gravity: vector(field(&root, "gravity")?, "gravity")?,
            samples,
            pinocchio_aba_microseconds: number(field(field(field(&root, "cost")?, "cpp")?, "aba_us_median")?, "aba")?,
            mujoco,
            accuracy: number(field(&root, "accuracy_estimate_max_abs_position")?, "accuracy")?,
        })
    }

    /// The start positions as (name, value) pairs.
    pub fn named_positions(&self) -> Vec<(String, f64)> {
        self.joints
            .iter()
            .cloned()
            .zip(self.positions.iter().copied())
            .collect()
    }

    /// The start velocities as (name, value) pairs.
    pub fn named_velocities(&self) -> Vec<(String, f64)> {
        self.joints
            .iter()
            .cloned()
            .zip(self.velocities.iter().copied())
            .collect()
    }
}

/// The CSV: `t`, the joints, for a floating base `base.x … base.qz`, `energy` (RFC 4180: a name may be quoted).
fn parse_samples(csv: &str, joints: &[String], free_base: bool) -> Result<Vec<RobotSample>, RobotDataError> {
    let mut reader = ::csv::ReaderBuilder::new()
        .trim(::csv::Trim::All)
        .from_reader(csv.as_bytes());
    let header: Vec<String> = (reader.headers())
        .map_err(|e| bad(format!("CSV header: {e}")))?
        .iter()
        .map(str::to_owned)
        .collect();
    let mut expected: Vec<String> = std::iter::once("t".to_owned()).chain(joints.iter().cloned()).collect();
    if free_base {
        expected.extend(["base.x", "base.y", "base.z", "base.qw", "base.qx", "base.qy", "base.qz"].map(str::to_owned));
    }
    expected.push("energy".to_owned());
    if header != expected {
        return Err(bad(format!("CSV header {header:?}, expected {expected:?}")));
    }
    reader
        .records()
        .map(|record| {
            let record = record.map_err(|e| bad(format!("CSV row: {e}")))?;
            let values: Vec<f64> = record
                .iter()
                .map(|v| v.parse::<f64>().map_err(|_| bad(format!("not a number: {v}"))))
                .collect::<Result<_, _>>()?;
            let n = joints.len();
            let base = free_base.then(|| {
                let b = &values[1 + n..];
                (
                    Vector3::new(b[0], b[1], b[2]),
                    UnitQuaternion::from_quaternion(Quaternion::new(b[3], b[4], b[5], b[6])),
                )
            });
            Ok(RobotSample {
                t: values[0],
                joints: values[1..1 + n].to_vec(),
                base,
                energy: values[values.len() - 1],
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_references_parse_with_their_columns() {
        for id in RobotId::ALL {
            let reference = id.reference().unwrap();
            assert_eq!(reference.samples.len(), 101, "{}", id.name());
            // The CSV and the JSON print the same start to the last ulp or so.
            let first = &reference.samples[0].joints;
            assert!(first
                .iter()
                .zip(&reference.positions)
                .all(|(a, b)| (a - b).abs() <= 1e-16));
            assert_eq!(reference.free_base, id == RobotId::Solo12);
            assert!(reference.mujoco.iter().any(|run| run.dt == 1e-3));
        }
    }
}
