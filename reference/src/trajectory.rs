//! Sampled rigid-body trajectories and the CSV format of the reference files.
//!
//! Format (`docs/scenes.md`, "Files"): a header line `t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz`, then one row per
//! sample with the time, the CoM position, the orientation quaternion (w, x, y, z) mapping body → world, the CoM
//! velocity and the angular velocity, both in the world frame.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use thiserror::Error;

/// The header line of the reference CSV files.
pub const CSV_HEADER: &str = "t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

/// Column names, in file order (used in error messages).
const CSV_COLUMNS: [&str; 14] = [
    "t", "px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
];

/// How far a stored quaternion's norm may be from 1. The reference files are unit to ~1e-16; anything
/// visibly off is a corrupted or mis-ordered row rather than rounding.
pub const UNIT_QUATERNION_TOLERANCE: f64 = 1e-9;

/// The state of a rigid body at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// CoM position in the world frame (m).
    pub position: Vector3<f64>,
    /// Rotation body → world (body frame = principal axes, origin at the CoM).
    pub orientation: UnitQuaternion<f64>,
    /// CoM velocity in the world frame (m/s).
    pub velocity: Vector3<f64>,
    /// Angular velocity in the world frame (rad/s).
    pub angular_velocity: Vector3<f64>,
}

impl Sample {
    /// The angular velocity in the body frame, Rᵀ ω.
    pub fn body_angular_velocity(&self) -> Vector3<f64> {
        self.orientation.inverse_transform_vector(&self.angular_velocity)
    }

    /// World position of the body-fixed point at `body_offset` from the CoM (body frame).
    pub fn world_point(&self, body_offset: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.orientation * body_offset
    }
}

/// Malformed CSV text or an invalid sample sequence.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum TrajectoryError {
    /// The text is empty or blank, so it has no header line.
    #[error("the CSV text has no header line")]
    MissingHeader,
    /// The first non-blank line is not [`CSV_HEADER`].
    #[error("line {line}: expected the header `{CSV_HEADER}`, found `{found}`")]
    UnexpectedHeader {
        /// 1-based line number of the header.
        line: usize,
        /// The header line as found.
        found: String,
    },
    /// A data row has the wrong number of comma-separated fields.
    #[error("line {line}: expected 14 comma-separated fields, found {found}")]
    FieldCount {
        /// 1-based line number of the row.
        line: usize,
        /// Number of fields in the row.
        found: usize,
    },
    /// A field does not parse as a finite `f64`.
    #[error("line {line}, column {column}: `{text}` is not a finite number")]
    InvalidNumber {
        /// 1-based line number of the row.
        line: usize,
        /// Name of the column, e.g. `"qw"`.
        column: &'static str,
        /// The field's text.
        text: String,
    },
    /// A row's quaternion norm differs from 1 by more than [`UNIT_QUATERNION_TOLERANCE`].
    #[error("line {line}: the quaternion's norm {norm} is not 1 (tolerance {UNIT_QUATERNION_TOLERANCE})")]
    NotUnitQuaternion {
        /// 1-based line number of the row.
        line: usize,
        /// The stored quaternion's norm.
        norm: f64,
    },
    /// [`Trajectory::new`] was given no samples.
    #[error("a trajectory needs at least one sample")]
    Empty,
    /// A sample's time is not finite or does not exceed the previous sample's time.
    #[error("sample {index}: time {t} is not finite or not greater than the previous sample's")]
    TimeNotIncreasing {
        /// Index of the offending sample.
        index: usize,
        /// Its time (s).
        t: f64,
    },
}

/// A non-empty sequence of samples with finite, strictly increasing times.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory(Vec<Sample>);

impl Trajectory {
    /// Checks the invariants (at least one sample, finite strictly increasing times).
    ///
    /// ```
    /// use nalgebra::{UnitQuaternion, Vector3};
    /// use reference::{Sample, Trajectory, TrajectoryError};
    ///
    /// let start = Sample {
    ///     t: 0.0,
    ///     position: Vector3::zeros(),
    ///     orientation: UnitQuaternion::identity(),
    ///     velocity: Vector3::new(1.0, 0.0, 0.0),
    ///     angular_velocity: Vector3::zeros(),
    /// };
    /// let later = Sample { t: 0.01, position: Vector3::new(0.01, 0.0, 0.0), ..start };
    /// let trajectory = Trajectory::new(vec![start, later])?;
    /// assert_eq!(trajectory.samples().len(), 2);
    /// assert_eq!(trajectory.last().t, 0.01);
    ///
    /// // Times must increase strictly: the second sample is refused.
    /// assert_eq!(
    ///     Trajectory::new(vec![later, start]),
    ///     Err(TrajectoryError::TimeNotIncreasing { index: 1, t: 0.0 })
    /// );
    /// assert_eq!(Trajectory::new(vec![]), Err(TrajectoryError::Empty));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(samples: Vec<Sample>) -> Result<Self, TrajectoryError> {
        if samples.is_empty() {
            return Err(TrajectoryError::Empty);
        }
        let mut previous = f64::NEG_INFINITY;
        for (index, sample) in samples.iter().enumerate() {
            if !(sample.t.is_finite() && sample.t > previous) {
                return Err(TrajectoryError::TimeNotIncreasing { index, t: sample.t });
            }
            previous = sample.t;
        }
        Ok(Self(samples))
    }

    /// Parses the reference CSV format (see the module docs). Blank lines are skipped; whitespace
    /// around fields is allowed. Quaternions are renormalised after the unit-norm check.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use reference::Trajectory;
    ///
    /// // At t = 0.01 the body is turned 90° about z (q = (cos 45°, 0, 0, sin 45°)) and spins about world x.
    /// let csv = "t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
    ///            0,0,0,0,1,0,0,0,0,0,0,1,0,0
    ///            0.01,1,2,3,0.7071067811865476,0,0,0.7071067811865476,0,0,0,1,0,0";
    /// let trajectory = Trajectory::from_csv(csv)?;
    /// let sample = trajectory.last();
    /// assert_eq!((sample.t, sample.position), (0.01, Vector3::new(1.0, 2.0, 3.0)));
    /// // World x is body −y once the body is turned 90° about z.
    /// assert!((sample.body_angular_velocity() - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_csv(text: &str) -> Result<Self, TrajectoryError> {
        let mut lines = text.lines().enumerate().map(|(index, line)| (index + 1, line.trim()));
        let (header_line, header) = lines
            .find(|(_, line)| !line.is_empty())
            .ok_or(TrajectoryError::MissingHeader)?;
        let header_fields: Vec<&str> = header.split(',').map(str::trim).collect();
        if header_fields != CSV_COLUMNS {
            return Err(TrajectoryError::UnexpectedHeader {
                line: header_line,
                found: header.to_owned(),
            });
        }
        let samples = lines
            .filter(|(_, line)| !line.is_empty())
            .map(|(line_number, line)| parse_row(line_number, line))
            .collect::<Result<Vec<_>, _>>()?;
        Self::new(samples)
    }

    /// All samples, in time order.
    pub fn samples(&self) -> &[Sample] {
        &self.0
    }

    /// The earliest sample (a trajectory is never empty).
    pub fn first(&self) -> &Sample {
        &self.0[0]
    }

    /// The latest sample.
    pub fn last(&self) -> &Sample {
        &self.0[self.0.len() - 1]
    }
}

fn parse_row(line: usize, text: &str) -> Result<Sample, TrajectoryError> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != CSV_COLUMNS.len() {
        return Err(TrajectoryError::FieldCount {
            line,
            found: fields.len(),
        });
    }
    let mut values = [0.0; 14];
    for ((value, field), column) in values.iter_mut().zip(&fields).zip(CSV_COLUMNS) {
        *value = field
            .parse::<f64>()
            .ok()
            .filter(|number| number.is_finite())
            .ok_or_else(|| TrajectoryError::InvalidNumber {
                line,
                column,
                text: (*field).to_owned(),
            })?;
    }
    let [t, px, py, pz, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz] = values;
    let quaternion = Quaternion::new(qw, qx, qy, qz);
    let norm = quaternion.norm();
    if (norm - 1.0).abs() > UNIT_QUATERNION_TOLERANCE {
        return Err(TrajectoryError::NotUnitQuaternion { line, norm });
    }
    Ok(Sample {
        t,
        position: Vector3::new(px, py, pz),
        orientation: UnitQuaternion::from_quaternion(quaternion),
        velocity: Vector3::new(vx, vy, vz),
        angular_velocity: Vector3::new(wx, wy, wz),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_ROWS: &str = "t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n\
        0,0,0,0,1,0,0,0,1,0.5,0,0.1,10,0\n\
        0.01,0.01,0.005,0,1,0,0,0,1,0.5,0,0.1,10,0\n";

    #[test]
    fn parses_a_well_formed_file() {
        assert_eq!(CSV_HEADER, CSV_COLUMNS.join(","));
        let trajectory = Trajectory::from_csv(TWO_ROWS).unwrap();
        assert_eq!(trajectory.samples().len(), 2);
        let last = trajectory.last();
        assert_eq!(last.t, 0.01);
        assert_eq!(last.position, Vector3::new(0.01, 0.005, 0.0));
        assert_eq!(last.angular_velocity, Vector3::new(0.1, 10.0, 0.0));
        assert_eq!(last.orientation, UnitQuaternion::identity());
    }

    #[test]
    fn malformed_input_is_an_error_naming_the_line() {
        let with_row = |row: &str| format!("{CSV_HEADER}\n0,0,0,0,1,0,0,0,0,0,0,0,0,0\n{row}\n");
        assert_eq!(Trajectory::from_csv(""), Err(TrajectoryError::MissingHeader));
        assert!(matches!(
            Trajectory::from_csv("\nt,x,y\n0,1,2\n"),
            Err(TrajectoryError::UnexpectedHeader { line: 2, .. })
        ));
        assert_eq!(Trajectory::from_csv(CSV_HEADER), Err(TrajectoryError::Empty));
        assert_eq!(
            Trajectory::from_csv(&with_row("0.01,0,0")),
            Err(TrajectoryError::FieldCount { line: 3, found: 3 })
        );
        assert_eq!(
            Trajectory::from_csv(&with_row("0.01,0,0,zero,1,0,0,0,0,0,0,0,0,0")),
            Err(TrajectoryError::InvalidNumber {
                line: 3,
                column: "pz",
                text: "zero".into()
            })
        );
        assert!(matches!(
            Trajectory::from_csv(&with_row("0.01,0,0,0,1,0,0,0,0,0,0,NaN,0,0")),
            Err(TrajectoryError::InvalidNumber {
                line: 3,
                column: "wx",
                ..
            })
        ));
        assert!(matches!(
            Trajectory::from_csv(&with_row("0.01,0,0,0,1,1,0,0,0,0,0,0,0,0")),
            Err(TrajectoryError::NotUnitQuaternion { line: 3, .. })
        ));
        assert!(matches!(
            Trajectory::from_csv(&with_row("0,0,0,0,1,0,0,0,0,0,0,0,0,0")),
            Err(TrajectoryError::TimeNotIncreasing { index: 1, .. })
        ));
    }
}
