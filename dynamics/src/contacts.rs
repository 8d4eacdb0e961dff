//! Contacts: a body point kept on one side of a world plane, `n · p ≥ d` (docs/contacts.md). The same one-sided
//! machinery as [`crate::limits`], on a point instead of a joint coordinate; a mechanism enforces it exactly
//! ([`crate::Mechanism::add_contact`]):
//!
//! * while the point is above the plane [`crate::simulate()`] watches its height `n · p − d` as an event;
//! * where the height reaches zero (located to round-off) the point meets the plane in an **impact**: impulses
//!   along n through the kinetic metric, at that point and at every other point touching the plane and moving into
//!   it, that reverse their normal speeds times the restitution, pull on no point and change no held relation;
//! * a point that does not bounce away is **held** on the plane by a row `n · a_p = 0` of the articulated solve,
//!   whose multiplier is the plane's push; it is released where that push would pull.
//!
//! Contacts are frictionless: the plane pushes along its normal only.

use nalgebra::{Unit, Vector3};

use crate::constraints::ConstraintError;
pub use crate::state::LARGEST_COORDINATE;

/// A plane below a body point: the point `p` (body coordinates) is kept where `n · p ≥ offset` (world, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneContact {
    point: Vector3<f64>,
    normal: Unit<Vector3<f64>>,
    offset: f64,
    restitution: f64,
}

/// Contact points within this height (m) of their planes at an impact take part in it: a block landing flat meets
/// the floor with four corners at once, whose heights differ by round-off at the located time.
pub const TOUCHING: f64 = 1e-9;

impl PlaneContact {
    /// The body point `point` (m, the body's frame) kept on the side of the plane `normal · x = offset` (world)
    /// that `normal` points to; inelastic (restitution 0). The normal need not be unit (the plane is scaled to a unit
    /// normal); it must be
    /// finite and not zero, and every coordinate finite and within [`LARGEST_COORDINATE`].
    ///
    /// ```
    /// use dynamics::contacts::PlaneContact;
    /// use nalgebra::Vector3;
    ///
    /// // A block's corner 0.1 m below and beside its centre, above the floor z = 0, bouncing at half speed.
    /// let corner = PlaneContact::new(Vector3::new(0.1, 0.1, -0.1), Vector3::z(), 0.0)?.with_restitution(0.5)?;
    /// assert_eq!(corner.height(&Vector3::new(0.0, 0.0, 0.25)), 0.25);
    /// assert!(PlaneContact::new(Vector3::zeros(), Vector3::zeros(), 0.0).is_err()); // no normal
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(point: Vector3<f64>, normal: Vector3<f64>, offset: f64) -> Result<Self, ConstraintError> {
        let refuse = |reason: String| ConstraintError::InvalidParameter {
            name: "plane contact".to_owned(),
            reason,
        };
        let within = |x: f64| x.is_finite() && x.abs() <= LARGEST_COORDINATE;
        if !(point.iter().all(|&x| within(x)) && within(offset)) {
            return Err(refuse(format!(
                "the body point {:?} and the offset {offset} must be finite and within {LARGEST_COORDINATE:e} m",
                point.as_slice()
            )));
        }
        let length = normal.norm();
        if !(length.is_finite() && length > 0.0 && normal.iter().all(|&x| within(x))) {
            return Err(refuse(format!(
                "the normal {:?} must be finite, within {LARGEST_COORDINATE:e} and not zero",
                normal.as_slice()
            )));
        }
        Ok(PlaneContact {
            point,
            normal: Unit::new_unchecked(normal / length),
            offset: offset / length,
            restitution: 0.0,
        })
    }

    /// The same contact with Newton's restitution coefficient `restitution` in [0, 1]: the point leaves the plane at
    /// `restitution` times the normal speed it met it with (1: elastic; 0: it stays).
    pub fn with_restitution(self, restitution: f64) -> Result<Self, ConstraintError> {
        if !(0.0..=1.0).contains(&restitution) {
            return Err(ConstraintError::InvalidParameter {
                name: "plane contact".to_owned(),
                reason: format!("a restitution coefficient is in [0, 1], got {restitution}"),
            });
        }
        Ok(PlaneContact { restitution, ..self })
    }

    /// The body point (m, the body's frame).
    pub fn point(&self) -> Vector3<f64> {
        self.point
    }

    /// The plane's unit normal (world), pointing to the side the point is kept on.
    pub fn normal(&self) -> Vector3<f64> {
        self.normal.into_inner()
    }

    /// The plane's offset d in `n · x = d` (m, n unit).
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// The restitution coefficient.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The height `n · x − d` (m) of the world point `x` above the plane: negative below it.
    pub fn height(&self, x: &Vector3<f64>) -> f64 {
        self.normal.dot(x) - self.offset
    }
}
