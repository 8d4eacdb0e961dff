//! Screws in world coordinates about one reference point o, for the articulated solve and the joint-space
//! algorithms (docs/mechanisms.md §M7): velocities `V = (ω; v_o)` (v_o the velocity of the body point at o), forces
//! `F = (n_o; f)` (the moment about o), paired by the power `V·F`; the inertia maps between them, symmetric, stored
//! packed; the motion and force cross products.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

use crate::algebra::Algebra;
use crate::body::Body;
use crate::constraints::Kinematics;

/// A symmetric 6×6 inertia map `F = I V`, its upper triangle stored row by row (21 numbers: a rank-one update or a
/// sum costs 21 operations, not 36).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Inertia6([f64; 21]);

/// Where entry (i, j), i ≤ j, of the upper triangle is stored.
const fn packed(i: usize, j: usize) -> usize {
    i * 6 - i * (i + 1) / 2 + j
}

/// The packed index of every (i, j), either order.
const INDEX: [[usize; 6]; 6] = {
    let mut index = [[0; 6]; 6];
    let mut i = 0;
    while i < 6 {
        let mut j = 0;
        while j < 6 {
            index[i][j] = if i <= j { packed(i, j) } else { packed(j, i) };
            j += 1;
        }
        i += 1;
    }
    index
};

impl Inertia6 {
    pub const ZERO: Inertia6 = Inertia6([0.0; 21]);

    /// `I V`.
    #[inline]
    pub fn apply(&self, v: &Vector6<f64>) -> Vector6<f64> {
        let a = &self.0;
        let (x0, x1, x2, x3, x4, x5) = (v[0], v[1], v[2], v[3], v[4], v[5]);
        Vector6::new(
            a[0] * x0 + a[1] * x1 + a[2] * x2 + a[3] * x3 + a[4] * x4 + a[5] * x5,
            a[1] * x0 + a[6] * x1 + a[7] * x2 + a[8] * x3 + a[9] * x4 + a[10] * x5,
            a[2] * x0 + a[7] * x1 + a[11] * x2 + a[12] * x3 + a[13] * x4 + a[14] * x5,
            a[3] * x0 + a[8] * x1 + a[12] * x2 + a[15] * x3 + a[16] * x4 + a[17] * x5,
            a[4] * x0 + a[9] * x1 + a[13] * x2 + a[16] * x3 + a[18] * x4 + a[19] * x5,
            a[5] * x0 + a[10] * x1 + a[14] * x2 + a[17] * x3 + a[19] * x4 + a[20] * x5,
        )
    }

    /// `self += other`.
    #[inline]
    pub fn add(&mut self, other: &Inertia6) {
        self.0.iter_mut().zip(&other.0).for_each(|(a, b)| *a += b);
    }

    /// `self −= s u uᵀ`.
    #[inline]
    pub fn subtract_outer(&mut self, u: &Vector6<f64>, s: f64) {
        let a = &mut self.0;
        let (u0, u1, u2, u3, u4, u5) = (u[0], u[1], u[2], u[3], u[4], u[5]);
        let (w0, w1, w2, w3, w4, w5) = (u0 * s, u1 * s, u2 * s, u3 * s, u4 * s, u5 * s);
        a[0] -= w0 * u0;
        a[1] -= w0 * u1;
        a[2] -= w0 * u2;
        a[3] -= w0 * u3;
        a[4] -= w0 * u4;
        a[5] -= w0 * u5;
        a[6] -= w1 * u1;
        a[7] -= w1 * u2;
        a[8] -= w1 * u3;
        a[9] -= w1 * u4;
        a[10] -= w1 * u5;
        a[11] -= w2 * u2;
        a[12] -= w2 * u3;
        a[13] -= w2 * u4;
        a[14] -= w2 * u5;
        a[15] -= w3 * u3;
        a[16] -= w3 * u4;
        a[17] -= w3 * u5;
        a[18] -= w4 * u4;
        a[19] -= w4 * u5;
        a[20] -= w5 * u5;
    }

    /// `self −= (u wᵀ + w uᵀ)/2 · s`: the symmetric part of a product of two columns (a joint with several degrees
    /// of freedom).
    #[inline]
    pub fn subtract_symmetric(&mut self, u: &Vector6<f64>, w: &Vector6<f64>, s: f64) {
        let mut k = 0;
        for i in 0..6 {
            for j in i..6 {
                self.0[k] -= 0.5 * s * (u[i] * w[j] + w[i] * u[j]);
                k += 1;
            }
        }
    }

    /// The full matrix.
    pub fn matrix(&self) -> Matrix6<f64> {
        Matrix6::from_fn(|i, j| self.0[INDEX[i][j]])
    }
}

#[inline]
pub(crate) fn angular(v: &Vector6<f64>) -> Vector3<f64> {
    Vector3::new(v[0], v[1], v[2])
}

#[inline]
pub(crate) fn linear(v: &Vector6<f64>) -> Vector3<f64> {
    Vector3::new(v[3], v[4], v[5])
}

#[inline]
pub(crate) fn join(top: Vector3<f64>, bottom: Vector3<f64>) -> Vector6<f64> {
    Vector6::new(top.x, top.y, top.z, bottom.x, bottom.y, bottom.z)
}

/// The motion cross product `V × W = (ω × ω'; ω × v' + v × ω')` (the rate of a screw W carried by the motion V).
#[inline]
pub(crate) fn motion_cross(a: &Vector6<f64>, b: &Vector6<f64>) -> Vector6<f64> {
    let (w, v, w2, v2) = (angular(a), linear(a), angular(b), linear(b));
    join(w.cross(&w2), w.cross(&v2) + v.cross(&w2))
}

/// The force cross product `V ×* F = (ω × n + v × f; ω × f)`.
#[inline]
pub(crate) fn force_cross(a: &Vector6<f64>, f: &Vector6<f64>) -> Vector6<f64> {
    let (w, v, n, force) = (angular(a), linear(a), angular(f), linear(f));
    join(w.cross(&n) + v.cross(&force), w.cross(&force))
}

/// A body's world kinematics about o: its velocity `(ω; v_o)`, its inertia about o and its momentum `(L_o; p)`.
pub(crate) struct SpatialBody {
    pub velocity: Vector6<f64>,
    pub inertia: Inertia6,
    pub momentum: Vector6<f64>,
    /// `r = c − o`.
    pub offset: Vector3<f64>,
}

/// The spatial body of a body with kinematics `kinematics`, about `origin`. With r = c − o and `Ī = R diag(I) Rᵀ`:
/// `p = m(v_o + ω × r)`, `L_o = Īω + r × p`, so the inertia is `[[Ī − m[r]ₓ², m[r]ₓ], [−m[r]ₓ, m𝟙]]`
/// (`−[r]ₓ² = |r|²𝟙 − r rᵀ`).
#[inline]
pub(crate) fn spatial_body<A: Algebra>(body: &Body, kinematics: &Kinematics<A>, origin: &Vector3<f64>) -> SpatialBody {
    let rotation: &Matrix3<f64> = kinematics.frame.rotation.matrix();
    let r = kinematics.frame.position - origin;
    let mass = body.mass();
    let moments = body.moments();
    // Ī_ij = Σ_k R_ik I_k R_jk, the upper triangle.
    let central = |i: usize, j: usize| {
        rotation[(i, 0)] * moments.x * rotation[(j, 0)]
            + rotation[(i, 1)] * moments.y * rotation[(j, 1)]
            + rotation[(i, 2)] * moments.z * rotation[(j, 2)]
    };
    let (mx, my, mz) = (mass * r.x, mass * r.y, mass * r.z);
    let (xx, yy, zz) = (mx * r.x, my * r.y, mz * r.z);
    let (xy, xz, yz) = (mx * r.y, mx * r.z, my * r.z);
    let (i00, i01, i02, i11, i12, i22) = (
        central(0, 0),
        central(0, 1),
        central(0, 2),
        central(1, 1),
        central(1, 2),
        central(2, 2),
    );
    // Upper triangle, rows of [[Ī + m(|r|²𝟙 − r rᵀ), m[r]ₓ], [·, m𝟙]]; m[r]ₓ = [[0, −mz, my], [mz, 0, −mx], [−my, mx, 0]].
    let inertia = Inertia6([
        i00 + yy + zz,
        i01 - xy,
        i02 - xz,
        0.0,
        -mz,
        my,
        i11 + xx + zz,
        i12 - yz,
        mz,
        0.0,
        -mx,
        i22 + xx + yy,
        -my,
        mx,
        0.0,
        mass,
        0.0,
        0.0,
        mass,
        0.0,
        mass,
    ]);
    let (omega, v) = (kinematics.angular_velocity, kinematics.linear_velocity);
    let p = v * mass;
    let spin = Vector3::new(
        i00 * omega.x + i01 * omega.y + i02 * omega.z,
        i01 * omega.x + i11 * omega.y + i12 * omega.z,
        i02 * omega.x + i12 * omega.y + i22 * omega.z,
    );
    SpatialBody {
        velocity: join(omega, v + r.cross(&omega)),
        inertia,
        momentum: join(spin + r.cross(&p), p),
        offset: r,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{motor, Pga, ScrewCoordinates};
    use nalgebra::UnitQuaternion;

    /// The packed inertia about o maps a body's velocity to its momentum about o (`L_o = Īω + r × m v_c`), and its
    /// quadratic form is twice the kinetic energy.
    #[test]
    fn spatial_inertia_gives_the_momentum_about_the_point() {
        let body = Body::new(2.0, Vector3::new(0.3, 0.5, 0.7)).unwrap();
        let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.7, 1.1));
        let centre = Vector3::new(1.0, -2.0, 0.5);
        let velocity = <Pga as Algebra>::screw(ScrewCoordinates {
            l: Vector3::new(0.4, -0.3, 0.9),
            t: Vector3::new(1.5, 0.2, -0.8),
        });
        let kinematics = Kinematics::<Pga>::new(0.0, motor::from_pose::<Pga>(centre, &rotation), velocity);
        let origin = Vector3::new(0.2, 0.1, -0.3);
        let spatial = spatial_body(&body, &kinematics, &origin);
        let applied = spatial.inertia.apply(&spatial.velocity);
        assert!(
            (applied - spatial.momentum).norm() < 1e-14,
            "{applied} vs {}",
            spatial.momentum
        );
        let central = rotation.to_rotation_matrix().matrix()
            * Matrix3::from_diagonal(&body.moments())
            * rotation.to_rotation_matrix().matrix().transpose();
        let omega = kinematics.angular_velocity;
        let expected = central * omega + (centre - origin).cross(&(kinematics.linear_velocity * 2.0));
        assert!((angular(&spatial.momentum) - expected).norm() < 1e-14);
        let energy = 0.5 * spatial.velocity.dot(&applied);
        let direct = 0.5 * (omega.dot(&(central * omega)) + 2.0 * kinematics.linear_velocity.norm_squared());
        assert!((energy - direct).abs() < 1e-14);
        assert!((spatial.inertia.matrix() - spatial.inertia.matrix().transpose()).norm() == 0.0);
    }
}
