//! Numbers a run can use: finite vectors, directions of any length, positive and bounded values; each refused with a
//! message naming the key.

use nalgebra::{SVector, Unit, Vector3};

use crate::error::{invalid, SceneFileError};

/// The values as a vector, if all are finite.
pub(crate) fn finite<const D: usize>(what: &str, values: [f64; D]) -> Result<SVector<f64, D>, SceneFileError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(SVector::from(values))
    } else {
        Err(invalid(what, format!("{values:?} is not finite")))
    }
}

/// Finite, non-zero values as `(scale, vector)`, the values = scale × vector, with a squared length that neither
/// overflows nor underflows: the values themselves (scale 1), unless their squared length does (lengths above
/// about 1e154 or below about 1e-154; a normal of 1e300 once became the zero vector), then divided by their
/// largest magnitude. So every finite, non-zero vector has its length and direction, and the usual ones are
/// computed exactly as before.
pub(crate) fn rescaled<const D: usize>(what: &str, values: [f64; D]) -> Result<(f64, SVector<f64, D>), SceneFileError> {
    let vector = finite(what, values)?;
    let largest = vector.amax();
    if largest == 0.0 {
        Err(invalid(what, "has no direction (zero vector)"))
    } else if vector.norm_squared().is_normal() {
        Ok((1.0, vector))
    } else {
        Ok((largest, vector / largest))
    }
}

/// The unit vector along finite, non-zero values (of any magnitude).
pub(crate) fn direction(what: &str, values: [f64; 3]) -> Result<Unit<Vector3<f64>>, SceneFileError> {
    Ok(Unit::new_normalize(rescaled(what, values)?.1))
}

pub(crate) fn positive(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(what, format!("must be positive and finite, got {value}")))
    }
}

/// The largest value a drive prescribes, or a parameter of an element: beyond it `dynamics` refuses joint positions
/// (1e50) and forces overflow long before anything physical.
pub(crate) const MAX_VALUE: f64 = 1e50;

/// A finite value of at most 1e50 in magnitude.
pub(crate) fn bounded(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value.is_finite() && value.abs() <= MAX_VALUE {
        Ok(value)
    } else {
        Err(invalid(what, format!("{value:?} is not finite or beyond 1e50")))
    }
}

/// Finite values of at most 1e50 in magnitude: a velocity, an acceleration or a force beyond it is no physics, and its
/// squares overflow where the joints are solved, which would then be blamed.
pub(crate) fn bounded_vector<const D: usize>(what: &str, values: [f64; D]) -> Result<SVector<f64, D>, SceneFileError> {
    if values.iter().all(|v| v.is_finite() && v.abs() <= MAX_VALUE) {
        Ok(SVector::from(values))
    } else {
        Err(invalid(what, format!("{values:?} is not finite or beyond 1e50")))
    }
}

/// A finite, non-negative value of at most 1e50.
pub(crate) fn non_negative(what: &str, value: f64) -> Result<f64, SceneFileError> {
    if value.is_finite() && (0.0..=MAX_VALUE).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(
            what,
            format!("{value:?} must be finite, non-negative and at most 1e50"),
        ))
    }
}
