//! Scene files' force elements and drives (docs/scene-files.md): `[[spring]]`, `[[couple]]`, `[[joint_torque]]`,
//! `[[joint_damping]]` and `[[pd]]` entries, and a `drive` on a hinge or prismatic `[[joint]]`. Each becomes a
//! `dynamics` force element or a driven joint model when the system is built ([`super::SceneFile::system`]); the
//! values are checked here, every message naming the entry and the value.

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use dynamics::constraints::PathPoint;
use serde::Deserialize;

use super::{invalid, SceneFileError};

/// The largest value a drive prescribes, or a parameter of an element: beyond it `dynamics` refuses joint positions
/// (1e50) and forces overflow long before anything physical.
const MAX_VALUE: f64 = 1e50;

/// `offset + amplitude sin(2π frequency t + phase)`: frequency in Hz, phase in rad.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sine {
    #[serde(default)]
    pub offset: f64,
    pub amplitude: f64,
    pub frequency: f64,
    #[serde(default)]
    pub phase: f64,
}

impl Sine {
    /// Checks the parameters: finite, a non-negative frequency, and a value, rate and acceleration within
    /// [`MAX_VALUE`].
    fn checked(self, what: &str) -> Result<Sine, SceneFileError> {
        for (key, value) in [
            ("offset", self.offset),
            ("amplitude", self.amplitude),
            ("frequency", self.frequency),
            ("phase", self.phase),
        ] {
            if !value.is_finite() {
                return Err(invalid(format!("{what}.{key}"), format!("{value:?} is not finite")));
            }
        }
        if self.frequency < 0.0 {
            return Err(invalid(
                format!("{what}.frequency"),
                format!(
                    "{:?} Hz is negative (write a phase of π to reverse the sine)",
                    self.frequency
                ),
            ));
        }
        let omega = TAU * self.frequency;
        let largest = [
            self.offset.abs() + self.amplitude.abs(),
            self.amplitude.abs() * omega,
            self.amplitude.abs() * omega * omega,
        ];
        if largest.iter().any(|v| !(v.is_finite() && *v <= MAX_VALUE)) {
            return Err(invalid(
                what,
                format!(
                    "offset {:?}, amplitude {:?} and frequency {:?} Hz give values, rates or accelerations beyond 1e50",
                    self.offset, self.amplitude, self.frequency
                ),
            ));
        }
        Ok(self)
    }

    /// The value, its rate and acceleration at `t` (exact).
    pub fn at(&self, t: f64) -> PathPoint<f64> {
        let omega = TAU * self.frequency;
        let (sin, cos) = (omega * t + self.phase).sin_cos();
        PathPoint {
            value: self.offset + self.amplitude * sin,
            rate: self.amplitude * omega * cos,
            acceleration: -self.amplitude * omega * omega * sin,
        }
    }
}

/// A value over time, written as a number (a constant) or `{ kind = "sine", offset, amplitude, frequency, phase }`.
#[derive(Clone, Copy, Debug)]
pub enum TimeValue {
    Constant(f64),
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

impl TimeValue {
    /// Checked: finite, and within 1e50.
    pub fn checked(self, what: &str) -> Result<TimeValue, SceneFileError> {
        match self {
            TimeValue::Constant(value) => Ok(TimeValue::Constant(bounded(what, value)?)),
            TimeValue::Sine(sine) => Ok(TimeValue::Sine(sine.checked(what)?)),
        }
    }

    /// The value at `t`.
    pub fn at(&self, t: f64) -> f64 {
        match self {
            TimeValue::Constant(value) => *value,
            TimeValue::Sine(sine) => sine.at(t).value,
        }
    }

    /// "2 N m" or "sine", for the summary.
    pub fn describe(&self) -> String {
        match self {
            TimeValue::Constant(value) => format!("{value}"),
            TimeValue::Sine(s) => format!(
                "{} + {} sin(2π {} Hz t + {})",
                s.offset, s.amplitude, s.frequency, s.phase
            ),
        }
    }
}

/// A finite value of at most 1e50 in magnitude.
pub fn bounded(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value.is_finite() && value.abs() <= MAX_VALUE {
        Ok(value)
    } else {
        Err(invalid(what, format!("{value:?} is not finite or beyond 1e50")))
    }
}

/// A finite, non-negative value of at most 1e50.
pub fn non_negative(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value.is_finite() && (0.0..=MAX_VALUE).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(
            what,
            format!("{value:?} must be finite, non-negative and at most 1e50"),
        ))
    }
}

/// A hinge's or prismatic joint's prescribed coordinate (rad or m): `{ kind = "constant_rate", start, rate }` or
/// `{ kind = "sine", offset, amplitude, frequency, phase }`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum DriveSpec {
    /// `start + rate t`.
    ConstantRate {
        #[serde(default)]
        start: f64,
        rate: f64,
    },
    /// `offset + amplitude sin(2π frequency t + phase)`.
    Sine(Sine),
}

impl DriveSpec {
    /// The checked drive over a run of `duration` s: finite parameters whose value stays within 1e50.
    pub fn checked(self, what: &str, duration: f64) -> Result<DriveSpec, SceneFileError> {
        match self {
            DriveSpec::ConstantRate { start, rate } => {
                let start = bounded(&format!("{what}.start"), start)?;
                let rate = bounded(&format!("{what}.rate"), rate)?;
                let end = start + rate * duration;
                if !(end.is_finite() && end.abs() <= MAX_VALUE) {
                    return Err(invalid(
                        what,
                        format!("start {start:?} at rate {rate:?} reaches {end:?} after {duration} s, beyond 1e50"),
                    ));
                }
                Ok(DriveSpec::ConstantRate { start, rate })
            }
            DriveSpec::Sine(sine) => Ok(DriveSpec::Sine(sine.checked(what)?)),
        }
    }

    /// The prescribed value, rate and acceleration at `t` (exact).
    pub fn at(&self, t: f64) -> PathPoint<f64> {
        match *self {
            DriveSpec::ConstantRate { start, rate } => PathPoint {
                value: start + rate * t,
                rate,
                acceleration: 0.0,
            },
            DriveSpec::Sine(sine) => sine.at(t),
        }
    }

    /// For the summary.
    pub fn describe(&self) -> String {
        match self {
            DriveSpec::ConstantRate { start, rate } => format!("{start} + {rate} t"),
            DriveSpec::Sine(s) => format!(
                "{} + {} sin(2π {} Hz t + {})",
                s.offset, s.amplitude, s.frequency, s.phase
            ),
        }
    }
}

/// `[[spring]]`: a linear spring and viscous damper between a point of each of two bodies (a body of the file, a
/// robot link, or `"world"`), each point in its body's (or link's, or the world's) coordinates.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    #[serde(default)]
    pub name: Option<String>,
    #[serde(deserialize_with = "super::exactly")]
    pub between: [String; 2],
    #[serde(deserialize_with = "super::points")]
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
    #[serde(default)]
    pub name: Option<String>,
    #[serde(deserialize_with = "super::exactly")]
    pub between: [String; 2],
    #[serde(deserialize_with = "super::exactly")]
    pub moment: [f64; 3],
}

/// `[[joint_torque]]`: a torque (N m) or force (N) on a one-coordinate joint by name, constant or a sine of time.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointTorqueSpec {
    #[serde(default)]
    pub name: Option<String>,
    pub joint: String,
    pub torque: TimeValue,
}

/// `[[joint_damping]]`: viscous damping `−c q̇` on every coordinate of a joint by name.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointDampingSpec {
    #[serde(default)]
    pub name: Option<String>,
    pub joint: String,
    /// N m s/rad or N s/m.
    pub damping: f64,
}

/// `[[pd]]`: a PD controller on one-coordinate joints by name, `τ = kp (target − q) − kd q̇` (+ the bias forces h(q, v)
/// with `gravity_compensation = true`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PdSpec {
    #[serde(default)]
    pub name: Option<String>,
    /// N m/rad or N/m.
    pub kp: f64,
    /// N m s/rad or N s/m.
    pub kd: f64,
    /// rad or m, by joint name.
    pub target: BTreeMap<String, f64>,
    #[serde(default)]
    pub gravity_compensation: bool,
}

/// An element's name: the one written, or `default`; checked non-empty and unique among `taken`.
pub fn element_name(
    written: &Option<String>,
    default: impl FnOnce() -> String,
    taken: &mut Vec<String>,
) -> Result<String, SceneFileError> {
    let name = written.clone().unwrap_or_else(default);
    if name.is_empty() {
        return Err(invalid("name", "a force element's name must not be empty"));
    }
    if taken.contains(&name) {
        return Err(invalid(
            format!("force element {name:?}"),
            "two force elements have this name",
        ));
    }
    taken.push(name.clone());
    Ok(name)
}
