//! Where a system's joint coordinates are in its position and velocity vectors, by kind (docs/mechanisms.md §M9):
//! a coordinate whose rate is its velocity (a revolute angle, a slide, a universal or planar coordinate) is a
//! vector coordinate; a rotation (a spherical joint, a free root's orientation) is a unit quaternion turned by its
//! angular velocity in its own axes; a free root's position moves with its velocity in the rotation's axes. And the
//! one group operation on them: positions moved by a velocity-coordinate displacement.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Where a system's joint coordinates are, by kind (vector coordinates, rotations as unit quaternions, free
/// translations: see the module docs), in its position and velocity vectors.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct JointLayout {
    /// The number of positions.
    pub positions: usize,
    /// The number of velocities.
    pub velocities: usize,
    /// Vector coordinates: (position, velocity) indices with `q̇ = v`.
    pub vectors: Vec<(usize, usize)>,
    /// Rotations: the index of a unit quaternion (w, x, y, z) in the positions and of its angular velocity (three,
    /// in its own axes) in the velocities.
    pub rotations: Vec<(usize, usize)>,
    /// Free translations: the index of a position (three) and of its velocity (three, in the axes of the rotation
    /// at the third index, a quaternion's position index).
    pub translations: Vec<(usize, usize, usize)>,
}

impl JointLayout {
    /// The positions `q` moved by the small velocity-coordinate displacement `delta` (a Newton step): `q + δ` on the
    /// vector coordinates, `p + R(r) δ` on free translations (R before the turn), `r exp(δ)` on the rotations.
    pub(crate) fn retract(&self, q: &mut [f64], delta: &[f64]) {
        for &(p, v) in &self.vectors {
            q[p] += delta[v];
        }
        for &(p, v, rotation) in &self.translations {
            let moved = quaternion_at(q, rotation) * vector_at(delta, v);
            for axis in 0..3 {
                q[p + axis] += moved[axis];
            }
        }
        for &(p, v) in &self.rotations {
            let turned = quaternion_at(q, p) * UnitQuaternion::from_scaled_axis(vector_at(delta, v));
            write_quaternion(q, p, &turned);
        }
    }
}

/// The unit quaternion (w, x, y, z) at `at` in the positions `q`.
pub(crate) fn quaternion_at(q: &[f64], at: usize) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q[at], q[at + 1], q[at + 2], q[at + 3]))
}

/// Writes the unit quaternion `r` at `at` in the positions `q`.
pub(crate) fn write_quaternion(q: &mut [f64], at: usize, r: &UnitQuaternion<f64>) {
    let c = r.quaternion();
    q[at..at + 4].copy_from_slice(&[c.w, c.i, c.j, c.k]);
}

/// The three entries of `v` from `at`.
pub(crate) fn vector_at(v: &[f64], at: usize) -> Vector3<f64> {
    Vector3::new(v[at], v[at + 1], v[at + 2])
}
