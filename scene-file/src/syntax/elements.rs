//! Scene files' force elements and drives (docs/scene-files.md): `[[spring]]`, `[[couple]]`, `[[joint_torque]]`,
//! `[[joint_damping]]` and `[[pd]]` entries, and a `drive` on a hinge or prismatic `[[joint]]`.

use std::collections::BTreeMap;

use serde::Deserialize;

use super::arrays::{exactly, points};

/// `offset + amplitude sin(2π frequency t + phase)`: frequency in Hz, phase in rad.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sine {
    /// The value's centre.
    #[serde(default)]
    pub offset: f64,
    /// Half the swing.
    pub amplitude: f64,
    /// Hz, at least 0.
    pub frequency: f64,
    /// rad.
    #[serde(default)]
    pub phase: f64,
}

/// A value over time, written as a number (a constant) or `{ kind = "sine", offset, amplitude, frequency, phase }`.
#[derive(Clone, Copy, Debug)]
pub enum TimeValue {
    /// A number.
    Constant(f64),
    /// A sine of time.
    Sine(Sine),
}

/// The table form of a [`TimeValue`].
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
enum TimeForm {
    Constant { value: f64 },
    Sine(Sine),
}

impl<'de> Deserialize<'de> for TimeValue {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = TimeValue;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number or { kind = \"sine\", offset, amplitude, frequency, phase }")
            }

            fn visit_f64<E: serde::de::Error>(self, value: f64) -> Result<TimeValue, E> {
                Ok(TimeValue::Constant(value))
            }

            fn visit_i64<E: serde::de::Error>(self, value: i64) -> Result<TimeValue, E> {
                Ok(TimeValue::Constant(value as f64))
            }

            fn visit_u64<E: serde::de::Error>(self, value: u64) -> Result<TimeValue, E> {
                Ok(TimeValue::Constant(value as f64))
            }

            fn visit_map<M: serde::de::MapAccess<'de>>(self, map: M) -> Result<TimeValue, M::Error> {
                Ok(
                    match TimeForm::deserialize(serde::de::value::MapAccessDeserializer::new(map))? {
                        TimeForm::Constant { value } => TimeValue::Constant(value),
                        TimeForm::Sine(sine) => TimeValue::Sine(sine),
                    },
                )
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// A hinge's or prismatic joint's prescribed coordinate (rad or m): `{ kind = "constant_rate", start, rate }` or
/// `{ kind = "sine", offset, amplitude, frequency, phase }`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum DriveSpec {
    /// `start + rate t`.
    ConstantRate {
        /// The coordinate at t = 0 (rad or m).
        #[serde(default)]
        start: f64,
        /// rad/s or m/s.
        rate: f64,
    },
    /// `offset + amplitude sin(2π frequency t + phase)`.
    Sine(Sine),
}

/// `[[spring]]`: a linear spring and viscous damper between a point of each of two bodies (a body of the file, a
/// robot link, or `"world"`), each point in its body's (or link's, or the world's) coordinates.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    /// The element's name in messages and the summary; a default names it by kind and place.
    #[serde(default)]
    pub name: Option<String>,
    /// Its two ends: a body of the file, a robot link or `"world"`.
    #[serde(deserialize_with = "exactly")]
    pub between: [String; 2],
    /// A point of each end, in that end's coordinates (m).
    #[serde(deserialize_with = "points")]
    pub points: [[f64; 3]; 2],
    /// N/m.
    pub stiffness: f64,
    /// N s/m.
    #[serde(default)]
    pub damping: f64,
    /// m.
    pub rest_length: f64,
}

/// `[[couple]]`: a constant moment (N m, world axes) on the first body and its opposite on the second.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoupleSpec {
    /// The element's name in messages and the summary; a default names it by kind and place.
    #[serde(default)]
    pub name: Option<String>,
    /// The body the moment acts on, then the one its opposite acts on (a body, a robot link or `"world"`).
    #[serde(deserialize_with = "exactly")]
    pub between: [String; 2],
    /// N m, world axes.
    #[serde(deserialize_with = "exactly")]
    pub moment: [f64; 3],
}

/// `[[joint_torque]]`: a torque (N m) or force (N) on a one-coordinate joint by name, constant or a sine of time.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointTorqueSpec {
    /// The element's name in messages and the summary; a default names it by kind and place.
    #[serde(default)]
    pub name: Option<String>,
    /// The joint, by name: the robot's or the file's.
    pub joint: String,
    /// N m or N.
    pub torque: TimeValue,
}

/// `[[joint_damping]]`: viscous damping `−c q̇` on every coordinate of a joint by name.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointDampingSpec {
    /// The element's name in messages and the summary; a default names it by kind and place.
    #[serde(default)]
    pub name: Option<String>,
    /// The joint, by name: the robot's or the file's.
    pub joint: String,
    /// N m s/rad or N s/m.
    pub damping: f64,
}

/// `[[pd]]`: a PD controller on one-coordinate joints by name, `τ = kp (target − q) − kd q̇` (+ the bias forces h(q, v)
/// with `gravity_compensation = true`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PdSpec {
    /// The element's name in messages and the summary; a default names it by kind and place.
    #[serde(default)]
    pub name: Option<String>,
    /// N m/rad or N/m.
    pub kp: f64,
    /// N m s/rad or N s/m.
    pub kd: f64,
    /// rad or m, by joint name.
    pub target: BTreeMap<String, f64>,
    /// Add the bias forces h(q, v), so the controller holds the targets against gravity.
    #[serde(default)]
    pub gravity_compensation: bool,
}
