//! The values of drives, sines, joint torques and limits checked (finite, within 1e50), and the force elements'
//! names.

use std::f64::consts::TAU;

use dynamics::constraints::{ConstraintError, PathPoint};
use dynamics::limits::JointLimit;

use super::values::{bounded, MAX_VALUE};
use crate::error::{invalid, SceneFileError};
use crate::syntax::elements::{DriveSpec, Sine, TimeValue};
use crate::syntax::joints::LimitSpec;

impl Sine {
    /// Checks the parameters: finite, a non-negative frequency, and a value, rate and acceleration within
    /// [`MAX_VALUE`].
    pub(crate) fn checked(self, what: &str) -> Result<Sine, SceneFileError> {
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
    pub(crate) fn at(&self, t: f64) -> PathPoint<f64> {
        let omega = TAU * self.frequency;
        let (sin, cos) = (omega * t + self.phase).sin_cos();
        PathPoint {
            value: self.offset + self.amplitude * sin,
            rate: self.amplitude * omega * cos,
            acceleration: -self.amplitude * omega * omega * sin,
        }
    }
}

impl TimeValue {
    /// Checked: finite, and within 1e50.
    pub(crate) fn checked(self, what: &str) -> Result<TimeValue, SceneFileError> {
        match self {
            TimeValue::Constant(value) => Ok(TimeValue::Constant(bounded(what, value)?)),
            TimeValue::Sine(sine) => Ok(TimeValue::Sine(sine.checked(what)?)),
        }
    }

    /// The value at `t`.
    pub(crate) fn at(&self, t: f64) -> f64 {
        match self {
            TimeValue::Constant(value) => *value,
            TimeValue::Sine(sine) => sine.at(t).value,
        }
    }
}

impl DriveSpec {
    /// The checked drive over a run of `duration` s: finite parameters whose value stays within 1e50.
    pub(crate) fn checked(self, what: &str, duration: f64) -> Result<DriveSpec, SceneFileError> {
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
    pub(crate) fn at(&self, t: f64) -> PathPoint<f64> {
        match *self {
            DriveSpec::ConstantRate { start, rate } => PathPoint {
                value: start + rate * t,
                rate,
                acceleration: 0.0,
            },
            DriveSpec::Sine(sine) => sine.at(t),
        }
    }
}

impl LimitSpec {
    /// The limit, or an error naming `what` (the joint's `limit` entry) and the values.
    pub(crate) fn limit(&self, what: &str) -> Result<JointLimit, SceneFileError> {
        if self.lower.is_none() && self.upper.is_none() {
            return Err(invalid(what, "needs a lower or an upper bound, or both"));
        }
        let refused = |error: ConstraintError| match error {
            ConstraintError::InvalidParameter { reason, .. } => invalid(what, reason),
            other => invalid(what, other.to_string()),
        };
        JointLimit::new(
            self.lower.unwrap_or(f64::NEG_INFINITY),
            self.upper.unwrap_or(f64::INFINITY),
        )
        .and_then(|limit| limit.with_restitution(self.restitution.unwrap_or(0.0)))
        .map_err(refused)
    }
}

/// An element's name: the one written, or `default`; checked non-empty and unique among `taken`.
pub(crate) fn element_name(
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
