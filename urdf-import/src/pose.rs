//! URDF poses: `<origin xyz="x y z" rpy="roll pitch yaw"/>` as a rigid transform.
//!
//! URDF's rpy are fixed-axis angles: roll about x first, then pitch about the fixed y, then yaw about the fixed z,
//! so `R = Rz(yaw) Ry(pitch) Rx(roll)`. The pose maps a point given in the child frame to the parent frame:
//! `p_parent = R p_child + xyz`. Built here from the three elementary rotations by hand, so the convention is
//! written down once and tested against matrices built by hand, not inherited from a library's Euler-angle naming.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

/// The rotation `Rz(yaw) Ry(pitch) Rx(roll)` of URDF's `rpy` (radians).
///
/// ```
/// use nalgebra::Vector3;
/// use urdf_import::pose::rpy_rotation;
///
/// // A quarter turn of yaw takes x to y.
/// let r = rpy_rotation([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
/// assert!((r * Vector3::x() - Vector3::y()).norm() < 1e-15);
/// ```
pub fn rpy_rotation(rpy: [f64; 3]) -> UnitQuaternion<f64> {
    let [roll, pitch, yaw] = rpy;
    let rx = UnitQuaternion::from_axis_angle(&Unit::new_unchecked(Vector3::x()), roll);
    let ry = UnitQuaternion::from_axis_angle(&Unit::new_unchecked(Vector3::y()), pitch);
    let rz = UnitQuaternion::from_axis_angle(&Unit::new_unchecked(Vector3::z()), yaw);
    rz * ry * rx
}

/// The pose of an `<origin xyz rpy>` (metres, radians): the child frame in the parent frame.
pub fn pose(xyz: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::new(xyz[0], xyz[1], xyz[2]), rpy_rotation(rpy))
}
