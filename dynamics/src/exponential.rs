//! Closed-form exponential and logarithm between screws and motors, written once for both algebras
//! in the coordinates of the motor subalgebra.
//!
//! Why this works: with `Π` central and `Π² = 0`, and `lᵢΠ = −tᵢ`, a motor splits as
//! `M = q_r + q_d Π` into two quaternions over the `lᵢ` (for which `lᵢlⱼ = −δᵢⱼ − εᵢⱼₖlₖ`), and a screw
//! `B = a·l + b·t` as `A + DΠ` with `A = a·l`, `D = −b·l`. Then `exp(B) = exp(A) + Π·dexp_A(D)` where,
//! with θ = |a|, `exp(A) = cos θ + sinc θ · A` and `dexp_A(D) = D∥ exp(A) + sinc θ · D⊥`. The
//! algebra-specific part — that lᵢ, tᵢ and Π multiply the same way in CGA and PGA — is what
//! [`crate::equivalence`] checks at compile time.
//!
//! The series branches keep both maps accurate at θ → 0 (pure translation); `log` returns the
//! principal logarithm (θ ≤ π/2, i.e. rotation angles up to π, choosing the sign of `±M`).

use nalgebra::Vector3;

use crate::algebra::{Algebra, MotorCoordinates, ScrewCoordinates};

/// Below this θ the trigonometric ratios use their Taylor series (error below 1e-17).
const SERIES_THRESHOLD: f64 = 1e-3;

/// sin θ / θ.
fn sinc(theta: f64) -> f64 {
    if theta < SERIES_THRESHOLD {
        let t2 = theta * theta;
        1.0 - t2 / 6.0 + t2 * t2 / 120.0
    } else {
        theta.sin() / theta
    }
}

/// (cos θ − sinc θ) / θ².
fn cos_minus_sinc_over_square(theta: f64) -> f64 {
    if theta < SERIES_THRESHOLD {
        let t2 = theta * theta;
        -1.0 / 3.0 + t2 / 30.0 - t2 * t2 / 840.0
    } else {
        (theta.cos() - sinc(theta)) / (theta * theta)
    }
}

/// (1 − θ cot θ) / θ².
fn one_minus_theta_cot_over_square(theta: f64) -> f64 {
    if theta < SERIES_THRESHOLD {
        let t2 = theta * theta;
        1.0 / 3.0 + t2 / 45.0 + 2.0 * t2 * t2 / 945.0
    } else {
        (1.0 - theta * theta.cos() / theta.sin()) / (theta * theta)
    }
}

/// `exp(B)` for a screw `B = a·l + b·t`.
pub fn exp<A: Algebra>(screw: A::Screw) -> A::Motor {
    let ScrewCoordinates { l: a, t: b } = A::screw_coordinates(screw);
    let theta = a.norm();
    let sinc = sinc(theta);
    let ab = a.dot(&b);
    A::motor(MotorCoordinates {
        scalar: theta.cos(),
        l: sinc * a,
        t: sinc * b + cos_minus_sinc_over_square(theta) * ab * a,
        pseudoscalar: sinc * ab,
    })
}

/// The principal `log(M)` of a unit motor: the screw B with `exp(B) = ±M` and rotation part
/// `|a| ≤ π/2`. At `|a| = π/2` exactly (a half turn) the axis sign is that of M's lᵢ part.
pub fn log<A: Algebra>(motor: A::Motor) -> A::Screw {
    let mut m = A::motor_coordinates(motor);
    if m.scalar < 0.0 {
        m = MotorCoordinates {
            scalar: -m.scalar,
            l: -m.l,
            t: -m.t,
            pseudoscalar: -m.pseudoscalar,
        };
    }
    let theta = m.l.norm().atan2(m.scalar);
    let a = m.l / sinc(theta);
    // w = q_d ~q_r, the pure quaternion from which D = −b is recovered.
    let w: Vector3<f64> = -m.pseudoscalar * m.l - m.scalar * m.t - m.t.cross(&m.l);
    let cos_over_sinc = if theta < SERIES_THRESHOLD {
        1.0 - theta * theta / 3.0
    } else {
        theta / theta.tan()
    };
    let d = cos_over_sinc * w + one_minus_theta_cot_over_square(theta) * w.dot(&a) * a - w.cross(&a);
    A::screw(ScrewCoordinates { l: a, t: -d })
}
