//! Closed-form solutions behind the analytic values of `docs/scenes.md`: the torque-free asymmetric top
//! (scene 1), the physical pendulum (scene 2) and the heavy symmetric top (scene 3).
//!
//! Everything is computed from physical parameters and initial conditions, so the tests can compare it with the
//! numbers `docs/scenes.md` prints and with the reference trajectories.

use nalgebra::Vector3;
use thiserror::Error;

use crate::elliptic::{complete_elliptic_k, jacobi_elliptic, EllipticError, EllipticParameter};

/// Why a closed form could not be evaluated: invalid physical parameters, an initial state outside the
/// implemented branch, or a failure of the underlying elliptic functions or quadrature.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[non_exhaustive]
pub enum AnalyticError {
    /// An elliptic integral or function rejected its input (e.g. a parameter outside [0, 1]).
    #[error(transparent)]
    Elliptic(#[from] EllipticError),
    /// A physical parameter or initial condition is non-finite or out of range (e.g. a non-positive mass).
    #[error("{name} = {value} is outside its valid range ({requirement})")]
    InvalidParameter {
        /// Name of the offending parameter, e.g. `"mass"` or `"θ₀"`.
        name: &'static str,
        /// The value that was passed.
        value: f64,
        /// The range it must lie in, e.g. `"> 0"`.
        requirement: &'static str,
    },
    /// The closed form implemented here covers one branch of the motion only (see the function docs).
    #[error("initial state not covered by this closed form: {reason}")]
    UnsupportedInitialState {
        /// What about the initial state falls outside the covered branch.
        reason: &'static str,
    },
    /// The heavy top has no steady precession at this tilt and spin (the spin is too slow).
    #[error("no steady precession exists: discriminant (I₃ω₃)² − 4 I₁ cos θ M g l = {discriminant} < 0")]
    NoSteadyPrecession {
        /// (I₃ω₃)² − 4 I₁ cos θ M g l, negative.
        discriminant: f64,
    },
    /// The numerical integral for the precession per nutation period did not reach its tolerance.
    #[error("the precession integral did not converge with {evaluations} integrand evaluations")]
    QuadratureNotConverged {
        /// Number of integrand evaluations spent before giving up.
        evaluations: usize,
    },
}

fn require(name: &'static str, value: f64, requirement: &'static str, valid: bool) -> Result<(), AnalyticError> {
    if valid {
        Ok(())
    } else {
        Err(AnalyticError::InvalidParameter {
            name,
            value,
            requirement,
        })
    }
}

/// Body-frame angular velocity of a torque-free rigid body rotating near its intermediate axis
/// (Landau–Lifshitz §37, as quoted in `docs/scenes.md` scene 1), with I_x > I_y > I_z and L² > 2T I_y:
///
/// ω_x = A_x dn(u), ω_y = A_y sn(u), ω_z = −A_z cn(u), u = λt + K(k²),
///
/// A_x² = (L² − 2T I_z) / (I_x (I_x − I_z)), A_y² = (2T I_x − L²) / (I_y (I_x − I_y)),
/// A_z² = (2T I_x − L²) / (I_z (I_x − I_z)), λ² = (I_x − I_y)(L² − 2T I_z) / (I_x I_y I_z),
/// k² = (I_y − I_z)(2T I_x − L²) / ((I_x − I_y)(L² − 2T I_z)).
///
/// These are LL's formulas with their axes (1, 2, 3) relabelled (z, y, x), so that x is the largest axis as in
/// `docs/scenes.md`. u = K at t = 0 means the body starts at an extremum of ω_y, i.e. with ω_z = 0. The amplitudes
/// carry the signs of the initial ω_x, ω_y: the sign of ω_z then follows from Euler's equation
/// I_z ω̇_z = (I_x − I_y) ω_x ω_y, which is positive for ω_x, ω_y > 0 and −A_z cn(u) rises through u = K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DzhanibekovSolution {
    /// Signed amplitudes of dn, sn, cn in (ω_x, ω_y, ω_z).
    pub amplitudes: Vector3<f64>,
    /// λ (1/s).
    pub lambda: f64,
    /// k² (and its complement, which the near-separatrix motion is sensitive to).
    pub parameter: EllipticParameter,
    /// K(k²).
    pub quarter_period_integral: f64,
    /// 2T_rot = Σ I_i ω_i².
    pub twice_rotational_energy: f64,
    /// |L| = |I ω|.
    pub angular_momentum_norm: f64,
}

impl DzhanibekovSolution {
    /// From the principal moments (I_x, I_y, I_z) and the initial body angular velocity, which must have ω_z = 0
    /// and ω_x ≠ 0 (that is L² > 2T I_y: the largest-axis component never changes sign).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use reference::DzhanibekovSolution;
    ///
    /// // Scene 1: the cuboid spun about its intermediate axis, nudged about the largest.
    /// let moments = Vector3::new(13.0, 10.0, 5.0) / 12.0;
    /// let initial = Vector3::new(0.1, 10.0, 0.0);
    /// let solution = DzhanibekovSolution::new(&moments, &initial)?;
    /// assert!((solution.body_angular_velocity(0.0)? - initial).norm() < 1e-14);
    /// // It flips every 2K/λ = 2.34189094968257 s (`docs/scenes.md`): one interval later ω_y = −10 rad/s.
    /// assert!((solution.flip_interval() - 2.34189094968257).abs() < 1e-12);
    /// assert!((solution.body_angular_velocity(solution.flip_interval())?.y + 10.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(principal_moments: &Vector3<f64>, body_angular_velocity: &Vector3<f64>) -> Result<Self, AnalyticError> {
        let (ix, iy, iz) = (principal_moments.x, principal_moments.y, principal_moments.z);
        let omega = body_angular_velocity;
        require("I_x", ix, "finite and I_x > I_y", ix.is_finite() && ix > iy)?;
        require("I_y", iy, "I_y > I_z", iy > iz)?;
        require("I_z", iz, "I_z > 0", iz > 0.0)?;
        require("ω_x", omega.x, "finite", omega.x.is_finite())?;
        require("ω_y", omega.y, "finite", omega.y.is_finite())?;
        if omega.z != 0.0 {
            return Err(AnalyticError::UnsupportedInitialState {
                reason: "u = K at t = 0 requires ω_z = 0",
            });
        }
        if omega.x == 0.0 {
            return Err(AnalyticError::UnsupportedInitialState {
                reason: "ω_x = ω_z = 0 is the unstable rotation about the intermediate axis (separatrix, k² = 1)",
            });
        }
        // The combinations of L² and 2T as sums of non-negative terms (no cancellation), here with ω_z = 0:
        // L² − 2T I_z = Σ I_i (I_i − I_z) ω_i², 2T I_x − L² = Σ I_i (I_x − I_i) ω_i²,
        // L² − 2T I_y = Σ I_i (I_i − I_y) ω_i².
        let (wx2, wy2) = (omega.x * omega.x, omega.y * omega.y);
        let l2_minus_2t_iz = ix * (ix - iz) * wx2 + iy * (iy - iz) * wy2;
        let twice_t_ix_minus_l2 = iy * (ix - iy) * wy2;
        let l2_minus_2t_iy = ix * (ix - iy) * wx2;
        let lambda = ((ix - iy) * l2_minus_2t_iz / (ix * iy * iz)).sqrt();
        // k² is close to 1 near the separatrix, so build it from its complement (denominator minus numerator of k²,
        // simplified): 1 − k² = (I_x − I_z)(L² − 2T I_y) / ((I_x − I_y)(L² − 2T I_z)).
        // The numerator never exceeds the denominator (their difference is (I_x − I_y) I_y (I_y − I_z) ω_y² ≥ 0),
        // so a quotient above 1 is round-off (ω_y = 0 gives exactly 1: k = 0, no flip).
        let complement = (ix - iz) * l2_minus_2t_iy / ((ix - iy) * l2_minus_2t_iz);
        let parameter = EllipticParameter::from_complement(complement.min(1.0))?;
        let (sign_x, sign_y) = (omega.x.signum(), if omega.y < 0.0 { -1.0 } else { 1.0 });
        let amplitudes = Vector3::new(
            sign_x * (l2_minus_2t_iz / (ix * (ix - iz))).sqrt(),
            sign_y * (twice_t_ix_minus_l2 / (iy * (ix - iy))).sqrt(),
            -sign_x * sign_y * (twice_t_ix_minus_l2 / (iz * (ix - iz))).sqrt(),
        );
        Ok(Self {
            amplitudes,
            lambda,
            parameter,
            quarter_period_integral: complete_elliptic_k(parameter)?,
            twice_rotational_energy: ix * wx2 + iy * wy2,
            angular_momentum_norm: principal_moments.component_mul(omega).norm(),
        })
    }

    /// ω in the body frame at time t.
    pub fn body_angular_velocity(&self, t: f64) -> Result<Vector3<f64>, AnalyticError> {
        let jacobi = jacobi_elliptic(self.lambda * t + self.quarter_period_integral, self.parameter)?;
        Ok(self
            .amplitudes
            .component_mul(&Vector3::new(jacobi.dn, jacobi.sn, jacobi.cn)))
    }

    /// Period of the body-frame angular velocity, 4K/λ.
    pub fn angular_velocity_period(&self) -> f64 {
        4.0 * self.quarter_period_integral / self.lambda
    }

    /// Time between consecutive flips (sign changes of ω_y), 2K/λ.
    pub fn flip_interval(&self) -> f64 {
        2.0 * self.quarter_period_integral / self.lambda
    }

    /// The flip instants in [0, duration]: sn(λt + K) = 0 at λt + K = 2nK, so t_n = (2n − 1) K/λ. None when
    /// ω_y is identically zero (a spin about the largest axis alone never flips).
    pub fn flip_instants(&self, duration: f64) -> Result<Vec<f64>, AnalyticError> {
        require("duration", duration, "finite", duration.is_finite())?;
        if self.amplitudes.y == 0.0 {
            return Ok(Vec::new());
        }
        let half_interval = self.quarter_period_integral / self.lambda;
        Ok((1..)
            .map(|n| (2 * n - 1) as f64 * half_interval)
            .take_while(|&t| t <= duration)
            .collect())
    }
}

/// A rigid pendulum on a fixed horizontal axis: mass, gravity, pivot–CoM distance d and moment of inertia
/// about the pivot axis I_p.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    /// Mass m (kg).
    pub mass: f64,
    /// Gravitational acceleration g (m/s²).
    pub gravity: f64,
    /// Distance d from the pivot axis to the centre of mass (m).
    pub pivot_distance: f64,
    /// Moment of inertia I_p about the pivot axis (kg m²).
    pub pivot_moment: f64,
}

impl Pendulum {
    /// ω₀ = √(m g d / I_p).
    pub fn small_amplitude_frequency(&self) -> f64 {
        (self.mass * self.gravity * self.pivot_distance / self.pivot_moment).sqrt()
    }

    /// 2π/ω₀.
    pub fn small_amplitude_period(&self) -> f64 {
        std::f64::consts::TAU / self.small_amplitude_frequency()
    }

    /// The motion after release from rest at angle θ₀ ∈ (0, π) from the downward vertical.
    pub fn released_from_rest(&self, amplitude: f64) -> Result<PendulumSolution, AnalyticError> {
        let positive = |value: f64| value.is_finite() && value > 0.0;
        require("mass", self.mass, "> 0", positive(self.mass))?;
        require("gravity", self.gravity, "> 0", positive(self.gravity))?;
        require(
            "pivot distance",
            self.pivot_distance,
            "> 0",
            positive(self.pivot_distance),
        )?;
        require("pivot moment", self.pivot_moment, "> 0", positive(self.pivot_moment))?;
        require(
            "θ₀",
            amplitude,
            "0 < θ₀ < π",
            amplitude > 0.0 && amplitude < std::f64::consts::PI,
        )?;
        let (modulus, complementary_modulus) = (0.5 * amplitude).sin_cos();
        // k′² = cos²(θ₀/2) keeps its precision for amplitudes near π, where k² → 1.
        let parameter = EllipticParameter::from_complement(complementary_modulus * complementary_modulus)?;
        Ok(PendulumSolution {
            frequency: self.small_amplitude_frequency(),
            modulus,
            parameter,
            quarter_period_integral: complete_elliptic_k(parameter)?,
        })
    }
}

/// θ(t) of a pendulum released from rest (`docs/scenes.md` scene 2): sin(θ/2) = k sn(K − ω₀t | k²),
/// θ̇ = −2kω₀ cn(K − ω₀t | k²), with k = sin(θ₀/2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumSolution {
    /// ω₀.
    pub frequency: f64,
    /// k = sin(θ₀/2).
    pub modulus: f64,
    /// k².
    pub parameter: EllipticParameter,
    /// K(k²).
    pub quarter_period_integral: f64,
}

impl PendulumSolution {
    /// 4K/ω₀.
    pub fn exact_period(&self) -> f64 {
        4.0 * self.quarter_period_integral / self.frequency
    }

    /// The angle θ(t) from the downward vertical (rad) at time `t` (s) after release; fails only if the elliptic
    /// functions reject the argument (a non-finite `t`).
    pub fn angle(&self, t: f64) -> Result<f64, AnalyticError> {
        let jacobi = jacobi_elliptic(self.argument(t), self.parameter)?;
        Ok(2.0 * (self.modulus * jacobi.sn).asin())
    }

    /// The angular rate θ̇(t) (rad/s) at time `t` (s) after release; fails only for a non-finite `t`.
    pub fn angular_rate(&self, t: f64) -> Result<f64, AnalyticError> {
        let jacobi = jacobi_elliptic(self.argument(t), self.parameter)?;
        Ok(-2.0 * self.modulus * self.frequency * jacobi.cn)
    }

    fn argument(&self, t: f64) -> f64 {
        self.quarter_period_integral - self.frequency * t
    }
}

/// A heavy symmetric top with a fixed point on its axis: mass M, gravity g, pivot–CoM distance l, transverse moment
/// about the pivot I₁ and axial moment I₃. Formulas: Goldstein §5.7 with u = cos θ, θ the tilt from the upward
/// vertical, φ the precession angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTop {
    /// Mass M (kg).
    pub mass: f64,
    /// Gravitational acceleration g (m/s²).
    pub gravity: f64,
    /// Distance l from the fixed point to the centre of mass along the symmetry axis (m).
    pub pivot_distance: f64,
    /// Transverse moment of inertia I₁ about the fixed point (kg m²).
    pub transverse_moment: f64,
    /// Axial moment of inertia I₃ about the symmetry axis (kg m²).
    pub axial_moment: f64,
}

/// The two steady precession rates at one tilt and spin, the smaller magnitude first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyPrecessionRates {
    /// The slow precession rate φ̇ (rad/s), close to the gyroscopic M g l/(I₃ω₃) for a fast spin.
    pub slow: f64,
    /// The fast precession rate φ̇ (rad/s).
    pub fast: f64,
}

/// The nutation of a heavy top between its turning points u₁ = cos θ_max and u₂ = cos θ_min
/// ((du/dt)² = f(u) = (1 − u²)(α − βu) − (b − au)², `docs/scenes.md` scene 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nutation {
    /// a = I₃ω₃/I₁.
    pub a: f64,
    /// b = p_φ/I₁ = φ̇ sin²θ + a cos θ.
    pub b: f64,
    /// α = 2E'/I₁ = θ̇² + φ̇² sin²θ + β cos θ.
    pub alpha: f64,
    /// β = 2Mgl/I₁.
    pub beta: f64,
    /// Roots u₁ ≤ u₂ ≤ 1 < u₃ of f.
    pub roots: [f64; 3],
    /// acos u₂ (rad).
    pub theta_min: f64,
    /// acos u₁ (rad).
    pub theta_max: f64,
    /// 4K(m)/√(β(u₃ − u₁)), m = (u₂ − u₁)/(u₃ − u₁).
    pub period: f64,
    /// Δφ over one nutation period.
    pub precession_per_period: f64,
    /// Δφ / period.
    pub mean_precession_rate: f64,
}

impl HeavyTop {
    fn validate(&self) -> Result<(), AnalyticError> {
        let positive = |value: f64| value.is_finite() && value > 0.0;
        require("mass", self.mass, "> 0", positive(self.mass))?;
        require("gravity", self.gravity, "> 0", positive(self.gravity))?;
        require(
            "pivot distance",
            self.pivot_distance,
            "> 0",
            positive(self.pivot_distance),
        )?;
        require("I₁", self.transverse_moment, "> 0", positive(self.transverse_moment))?;
        require("I₃", self.axial_moment, "> 0", positive(self.axial_moment))
    }

    fn gravity_torque(&self) -> f64 {
        self.mass * self.gravity * self.pivot_distance
    }

    /// Roots of I₁ cos θ φ̇² − I₃ω₃ φ̇ + Mgl = 0, the condition for precession at constant θ (Goldstein §5.7;
    /// ω₃ is the total angular velocity component along the axis).
    pub fn steady_precession_rates(&self, tilt: f64, spin: f64) -> Result<SteadyPrecessionRates, AnalyticError> {
        self.validate()?;
        require("θ", tilt, "finite", tilt.is_finite())?;
        require("ω₃", spin, "finite", spin.is_finite())?;
        // I₁ cos θ is never exactly 0 for a finite f64 θ; towards θ = π/2 the fast root grows without bound.
        let quadratic = self.transverse_moment * tilt.cos();
        let linear = self.axial_moment * spin;
        let discriminant = linear * linear - 4.0 * quadratic * self.gravity_torque();
        if discriminant < 0.0 {
            return Err(AnalyticError::NoSteadyPrecession { discriminant });
        }
        // Cancellation-free pair: q = (I₃ω₃ + sign · √D)/2, roots q/(I₁ cos θ) and Mgl/q.
        let q = 0.5 * (linear + linear.signum() * discriminant.sqrt());
        let (first, second) = (q / quadratic, self.gravity_torque() / q);
        let (slow, fast) = if first.abs() <= second.abs() {
            (first, second)
        } else {
            (second, first)
        };
        Ok(SteadyPrecessionRates { slow, fast })
    }

    /// The gyroscopic approximation Mgl/(I₃ω₃) of the slow rate.
    pub fn gyroscopic_precession_rate(&self, spin: f64) -> f64 {
        self.gravity_torque() / (self.axial_moment * spin)
    }

    /// Minimum spin of a stable vertical ("sleeping") top, √(4 I₁ M g l)/I₃.
    pub fn minimum_stable_spin(&self) -> f64 {
        (4.0 * self.transverse_moment * self.gravity_torque()).sqrt() / self.axial_moment
    }

    /// Nutation from an initial tilt θ₀ ∈ (0, π), tilt rate θ̇₀, precession rate φ̇₀ and spin ω₃.
    pub fn nutation(
        &self,
        tilt: f64,
        tilt_rate: f64,
        precession_rate: f64,
        spin: f64,
    ) -> Result<Nutation, AnalyticError> {
        self.validate()?;
        require("θ₀", tilt, "0 < θ₀ < π", tilt > 0.0 && tilt < std::f64::consts::PI)?;
        require("θ̇₀", tilt_rate, "finite", tilt_rate.is_finite())?;
        require("φ̇₀", precession_rate, "finite", precession_rate.is_finite())?;
        require("ω₃", spin, "finite", spin.is_finite())?;

        let a = self.axial_moment * spin / self.transverse_moment;
        let beta = 2.0 * self.gravity_torque() / self.transverse_moment;
        let (sin_tilt, u0) = tilt.sin_cos();
        let b = precession_rate * sin_tilt * sin_tilt + a * u0;
        let alpha = tilt_rate * tilt_rate + (precession_rate * sin_tilt).powi(2) + beta * u0;
        let f = |u: f64| (1.0 - u * u) * (alpha - beta * u) - (b - a * u).powi(2);

        // Brackets: f(u₀) = (θ̇₀ sin θ₀)² ≥ 0 (taken as non-negative without evaluating it, which would
        // round at the cusp start where it is exactly 0), f(±1) = −(b ∓ a)² ≤ 0, f → +∞ as u → +∞.
        let u1 = bisect_sign_change(&f, -1.0, u0);
        let u2 = bisect_sign_change(&f, 1.0, u0);
        let mut upper = 2.0;
        while f(upper) <= 0.0 && upper < 1e300 {
            upper *= 2.0;
        }
        let u3 = bisect_sign_change(&f, 1.0, upper);

        let parameter = EllipticParameter::from_complement((u3 - u2) / (u3 - u1))?;
        let period = 4.0 * complete_elliptic_k(parameter)? / (beta * (u3 - u1)).sqrt();
        let precession_per_period = precession_per_nutation(a, b, beta, [u1, u2, u3])?;
        Ok(Nutation {
            a,
            b,
            alpha,
            beta,
            roots: [u1, u2, u3],
            theta_min: u2.acos(),
            theta_max: u1.acos(),
            period,
            precession_per_period,
            mean_precession_rate: precession_per_period / period,
        })
    }
}

/// The root of `f` between `negative_end` (f ≤ 0) and `positive_end` (f ≥ 0) by bisection to full precision:
/// robust at the exactly-zero ends of the brackets above, and f is cheap.
fn bisect_sign_change(f: &impl Fn(f64) -> f64, negative_end: f64, positive_end: f64) -> f64 {
    let (mut negative, mut positive) = (negative_end, positive_end);
    // 2100 halvings exhaust any f64 interval; the loop normally stops after ~55 when the midpoint rounds to an end.
    for _ in 0..2100 {
        let middle = 0.5 * (negative + positive);
        if middle == negative || middle == positive {
            break;
        }
        if f(middle) < 0.0 {
            negative = middle;
        } else {
            positive = middle;
        }
    }
    0.5 * (negative + positive)
}

/// Δφ over one nutation period: 2 ∫_{u₁}^{u₂} (b − au)/(1 − u²) du/√f(u), with φ̇ = (b − au)/(1 − u²)
/// (Goldstein §5.7). The substitution u = u₁ + (u₂ − u₁) sin²s turns du/√f into 2 ds/√(β(u₃ − u)), leaving
/// Δφ = 4 ∫₀^{π/2} (b − au) / ((1 − u²) √(β(u₃ − u))) ds, a smooth integrand that depends on s only through sin²s.
/// It is therefore even and π-periodic, so the trapezoidal rule converges geometrically; the step is halved until
/// two estimates agree to 1e-15.
fn precession_per_nutation(a: f64, b: f64, beta: f64, [u1, u2, u3]: [f64; 3]) -> Result<f64, AnalyticError> {
    let integrand = |s: f64| {
        let u = u1 + (u2 - u1) * s.sin().powi(2);
        (b - a * u) / ((1.0 - u * u) * (beta * (u3 - u)).sqrt())
    };
    let quarter = std::f64::consts::FRAC_PI_2;
    let mut intervals = 4_usize;
    let mut step = quarter / intervals as f64;
    let mut sum =
        0.5 * (integrand(0.0) + integrand(quarter)) + (1..intervals).map(|j| integrand(j as f64 * step)).sum::<f64>();
    let mut estimate = 4.0 * step * sum;
    while intervals < 1 << 20 {
        // Doubling reuses the previous nodes; only the midpoints are new.
        sum += (0..intervals).map(|j| integrand((j as f64 + 0.5) * step)).sum::<f64>();
        intervals *= 2;
        step *= 0.5;
        let refined = 4.0 * step * sum;
        if (refined - estimate).abs() <= 1e-15 * refined.abs() {
            return Ok(refined);
        }
        estimate = refined;
    }
    Err(AnalyticError::QuadratureNotConverged {
        evaluations: intervals + 1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::{
        SceneConstraint, SceneId, CUBOID_VALUES, HEAVY_TOP_VALUES, PENDULUM_INITIAL_ANGLE, PENDULUM_VALUES,
        TOP_INITIAL_TILT, TOP_SPIN,
    };

    fn assert_relative(value: f64, expected: f64, tolerance: f64, what: &str) {
        let relative = ((value - expected) / expected).abs();
        assert!(
            relative <= tolerance,
            "{what}: {value} vs {expected} (relative {relative:e})"
        );
    }

    fn cuboid_solution() -> DzhanibekovSolution {
        let parameters = SceneId::Cuboid.parameters();
        DzhanibekovSolution::new(&parameters.principal_moments, &parameters.initial_body_angular_velocity).unwrap()
    }

    /// The scene-3 cone as a `HeavyTop`: I₁ about the tip = transverse moment about the CoM + M l².
    fn scene_top() -> HeavyTop {
        let parameters = SceneId::TopCusp.parameters();
        let SceneConstraint::BallJoint { body_anchor, .. } = parameters.constraint else {
            panic!("scene 3 is pinned by a ball joint");
        };
        let pivot_distance = body_anchor.norm();
        HeavyTop {
            mass: parameters.mass,
            gravity: parameters.gravity,
            pivot_distance,
            transverse_moment: parameters.principal_moments.x + parameters.mass * pivot_distance.powi(2),
            axial_moment: parameters.principal_moments.z,
        }
    }

    /// A spin about the largest axis alone (ω_y = 0) is a steady rotation: k = 0 exactly, although the
    /// complement 1 − k² rounds above 1 for some moments (it used to be refused as out of range).
    #[test]
    fn a_spin_about_the_largest_axis_is_steady() {
        let moments = SceneId::Cuboid.parameters().principal_moments;
        for spin in [0.1, 1.0, 7.3, 1e3] {
            let solution = DzhanibekovSolution::new(&moments, &Vector3::new(spin, 0.0, 0.0)).unwrap();
            assert_eq!(solution.parameter.m(), 0.0);
            let omega = solution.body_angular_velocity(1.234).unwrap();
            assert!((omega - Vector3::new(spin, 0.0, 0.0)).norm() <= 1e-15 * spin, "{omega}");
            assert!(solution.flip_instants(100.0).unwrap().is_empty());
        }
    }

    #[test]
    fn invalid_moments_are_named() {
        let named = |moments: Vector3<f64>| match DzhanibekovSolution::new(&moments, &Vector3::new(1.0, 0.1, 0.0)) {
            Err(AnalyticError::InvalidParameter { name, .. }) => name,
            other => panic!("expected a refusal, got {other:?}"),
        };
        assert_eq!(named(Vector3::new(1.0, 2.0, 3.0)), "I_x");
        assert_eq!(named(Vector3::new(f64::INFINITY, 2.0, 1.0)), "I_x");
        assert_eq!(named(Vector3::new(3.0, 1.0, 2.0)), "I_y");
        assert_eq!(named(Vector3::new(3.0, 2.0, -1.0)), "I_z");
    }

    #[test]
    fn dzhanibekov_constants_match_scenes_md() {
        let solution = cuboid_solution();
        let published = CUBOID_VALUES;
        assert_relative(
            solution.twice_rotational_energy,
            published.twice_rotational_energy,
            1e-14,
            "2T",
        );
        assert_relative(
            solution.angular_momentum_norm,
            published.angular_momentum_norm,
            1e-14,
            "|L|",
        );
        assert_relative(solution.lambda, published.lambda, 1e-14, "λ");
        assert_relative(solution.parameter.m(), published.parameter, 1e-14, "k²");
        // docs/scenes.md's K and the periods derived from it are 3.4e-14 (relative) above the exact values below.
        assert_relative(
            solution.quarter_period_integral,
            published.quarter_period_integral,
            1e-13,
            "K",
        );
        assert_relative(
            solution.angular_velocity_period(),
            published.angular_velocity_period,
            1e-13,
            "4K/λ",
        );
        assert_relative(solution.flip_interval(), published.flip_interval, 1e-13, "2K/λ");
        let flips = solution.flip_instants(SceneId::Cuboid.parameters().duration).unwrap();
        assert_eq!(flips.len(), published.flip_instants.len());
        for (flip, expected) in flips.iter().zip(published.flip_instants) {
            // Printed with 12 decimals.
            assert!((flip - expected).abs() < 1e-12, "flip {flip} vs {expected}");
        }
    }

    #[test]
    fn dzhanibekov_constants_match_high_precision_values() {
        // mpmath at 40 digits from the exact rationals (I = (13, 10, 5)/12, ω₀ = (1/10, 10, 0)):
        // K = 5.625625086537179493, λ = 4.804344188015995688, K/λ = 1.170945474841247867.
        let solution = cuboid_solution();
        assert_relative(solution.quarter_period_integral, 5.6256250865371795, 4e-16, "K");
        assert_relative(solution.lambda, 4.804344188015996, 4e-16, "λ");
        assert_relative(solution.flip_interval(), 2.0 * 1.1709454748412478, 6e-16, "2K/λ");
    }

    #[test]
    fn dzhanibekov_closed_form_starts_at_the_initial_state() {
        let solution = cuboid_solution();
        let initial = SceneId::Cuboid.parameters().initial_body_angular_velocity;
        let at_zero = solution.body_angular_velocity(0.0).unwrap();
        // A few ulp of |ω| = 10 (from m instead of m₁, dn(K) = √m₁ alone would be off by ~3e-14).
        assert!((at_zero - initial).norm() < 4e-15, "{at_zero} vs {initial}");
    }

    #[test]
    fn dzhanibekov_closed_form_satisfies_euler_equations_for_all_sign_choices() {
        // I ω̇ = (Iω) × ω in the body frame (torque-free). Central differences, h = 1e-5: error ~ h² |ω⃛| ≈ 1e-7.
        let moments = SceneId::Cuboid.parameters().principal_moments;
        for initial in [
            Vector3::new(0.1, 10.0, 0.0),
            Vector3::new(-0.1, 10.0, 0.0),
            Vector3::new(0.3, -4.0, 0.0),
        ] {
            let solution = DzhanibekovSolution::new(&moments, &initial).unwrap();
            let h = 1e-5;
            for t in [0.0, 0.4, 1.17, 2.0, 7.3] {
                let omega = solution.body_angular_velocity(t).unwrap();
                let rate = (solution.body_angular_velocity(t + h).unwrap()
                    - solution.body_angular_velocity(t - h).unwrap())
                    / (2.0 * h);
                let residual = moments.component_mul(&rate) - moments.component_mul(&omega).cross(&omega);
                assert!(residual.norm() < 1e-6, "ω₀ = {initial}, t = {t}: residual {residual}");
            }
        }
    }

    #[test]
    fn dzhanibekov_closed_form_matches_the_reference_trajectory() {
        // docs/scenes.md: DOP853 vs the closed form, max |ω error| = 3e-10 rad/s.
        let solution = cuboid_solution();
        let reference = SceneId::Cuboid.reference_trajectory().unwrap();
        let max_error = reference
            .samples()
            .iter()
            .map(|sample| (solution.body_angular_velocity(sample.t).unwrap() - sample.body_angular_velocity()).norm())
            .fold(0.0, f64::max);
        assert!(max_error < 1e-9, "max |ω_closed − ω_ref| = {max_error:e}");
    }

    #[test]
    fn dzhanibekov_rejects_unsupported_states() {
        let moments = SceneId::Cuboid.parameters().principal_moments;
        assert!(matches!(
            DzhanibekovSolution::new(&moments, &Vector3::new(0.1, 10.0, 0.5)),
            Err(AnalyticError::UnsupportedInitialState { .. })
        ));
        assert!(matches!(
            DzhanibekovSolution::new(&moments, &Vector3::new(0.0, 10.0, 0.0)),
            Err(AnalyticError::UnsupportedInitialState { .. })
        ));
        assert!(matches!(
            DzhanibekovSolution::new(&Vector3::new(1.0, 2.0, 3.0), &Vector3::new(0.1, 10.0, 0.0)),
            Err(AnalyticError::InvalidParameter { .. })
        ));
    }

    fn scene_pendulum() -> Pendulum {
        // Thin rod, m = 1, L = 1, hinged at one end: d = L/2, I_p = m L²/3.
        Pendulum {
            mass: 1.0,
            gravity: crate::scenes::GRAVITY,
            pivot_distance: 0.5,
            pivot_moment: 1.0 / 3.0,
        }
    }

    #[test]
    fn pendulum_constants_match_scenes_md() {
        let pendulum = scene_pendulum();
        let solution = pendulum.released_from_rest(PENDULUM_INITIAL_ANGLE).unwrap();
        let published = PENDULUM_VALUES;
        assert_relative(
            pendulum.small_amplitude_frequency(),
            published.small_amplitude_frequency,
            1e-14,
            "ω₀",
        );
        assert_relative(
            pendulum.small_amplitude_period(),
            published.small_amplitude_period,
            1e-14,
            "2π/ω₀",
        );
        assert_relative(solution.modulus, published.modulus, 1e-14, "k");
        assert_relative(
            solution.quarter_period_integral,
            published.quarter_period_integral,
            1e-14,
            "K",
        );
        assert_relative(solution.exact_period(), published.exact_period, 1e-14, "4K/ω₀");
    }

    #[test]
    fn pendulum_closed_form_matches_the_reference_trajectory() {
        // docs/scenes.md: DOP853 agrees with the closed form to 1.4e-14 rad (measured here: 3.8e-15 rad, 1.5e-14 rad/s;
        // the rate bound is the angle bound times ω₀ ≈ 3.8). The reference's θ is the rotation angle
        // about world y: 2 atan2(q_y, q_w); θ̇ = ω_y (world).
        let solution = scene_pendulum().released_from_rest(PENDULUM_INITIAL_ANGLE).unwrap();
        let reference = SceneId::Pendulum.reference_trajectory().unwrap();
        let (mut angle_error, mut rate_error) = (0.0_f64, 0.0_f64);
        for sample in reference.samples() {
            let q = sample.orientation.quaternion();
            let angle = 2.0 * q.j.atan2(q.w);
            angle_error = angle_error.max((solution.angle(sample.t).unwrap() - angle).abs());
            rate_error = rate_error.max((solution.angular_rate(sample.t).unwrap() - sample.angular_velocity.y).abs());
        }
        assert!(angle_error < 1.4e-14, "max |θ_closed − θ_ref| = {angle_error:e}");
        assert!(rate_error < 5.4e-14, "max |θ̇_closed − θ̇_ref| = {rate_error:e}");
    }

    #[test]
    fn pendulum_rejects_invalid_amplitudes() {
        for amplitude in [0.0, std::f64::consts::PI, -1.0, f64::NAN] {
            assert!(matches!(
                scene_pendulum().released_from_rest(amplitude),
                Err(AnalyticError::InvalidParameter { .. })
            ));
        }
    }

    #[test]
    fn heavy_top_constants_match_scenes_md() {
        let top = scene_top();
        let published = HEAVY_TOP_VALUES;
        let spin = TOP_SPIN;
        let rates = top.steady_precession_rates(TOP_INITIAL_TILT, spin).unwrap();
        assert_relative(rates.slow, published.slow_precession_rate, 1e-13, "slow precession");
        assert_relative(rates.fast, published.fast_precession_rate, 1e-13, "fast precession");
        assert_relative(
            top.gyroscopic_precession_rate(spin),
            published.gyroscopic_precession_rate,
            1e-14,
            "Mgl/I₃ω₃",
        );
        assert_relative(
            top.minimum_stable_spin(),
            published.minimum_stable_spin,
            1e-14,
            "minimum spin",
        );

        let cusp = top.nutation(TOP_INITIAL_TILT, 0.0, 0.0, spin).unwrap();
        assert_relative(cusp.a, published.a, 1e-15, "a");
        assert_relative(cusp.beta, published.beta, 1e-15, "β");
        assert_relative(cusp.b, published.cusp_b, 1e-14, "b");
        assert_relative(cusp.alpha, published.cusp_alpha, 1e-14, "α");
        for (root, expected) in cusp.roots.iter().zip(published.cusp_roots) {
            assert_relative(*root, expected, 1e-13, "root of f");
        }
        assert_relative(cusp.theta_min, published.theta_min, 1e-13, "θ_min");
        assert_relative(cusp.theta_max, published.theta_max, 1e-13, "θ_max");
        assert_relative(cusp.period, published.nutation_period, 1e-12, "nutation period");
        assert_relative(
            cusp.precession_per_period,
            published.precession_per_nutation,
            1e-13,
            "Δφ per period",
        );
        assert_relative(
            cusp.mean_precession_rate,
            published.mean_precession_rate,
            1e-13,
            "mean precession rate",
        );
    }

    #[test]
    fn heavy_top_constants_match_high_precision_values() {
        // mpmath at 40 digits (polyroots on the cubic, quad on the precession integral). The roots, θ bounds and
        // precession figures printed in docs/scenes.md are off from these by 5e-15 to 5e-14 (within the 1e-13 of the
        // test above).
        let top = scene_top();
        let cusp = top.nutation(TOP_INITIAL_TILT, 0.0, 0.0, TOP_SPIN).unwrap();
        let exact_roots = [0.7171129870824912, 0.8660254037844386, 2.544864586821688];
        for (root, expected) in cusp.roots.iter().zip(exact_roots) {
            assert_relative(*root, expected, 3e-16, "root of f");
        }
        assert_relative(
            cusp.theta_min,
            TOP_INITIAL_TILT,
            3e-16,
            "θ_min = θ₀ (the cusp start is a turning point)",
        );
        assert_relative(cusp.theta_max, 0.771145196934745, 3e-16, "θ_max");
        assert_relative(cusp.period, 1.0716421634452016, 3e-16, "nutation period");
        assert_relative(cusp.precession_per_period, 1.505044537920387, 1e-15, "Δφ per period");
        assert_relative(
            cusp.mean_precession_rate,
            1.4044282590392378,
            1e-15,
            "mean precession rate",
        );
        let rates = top.steady_precession_rates(TOP_INITIAL_TILT, TOP_SPIN).unwrap();
        assert_relative(rates.slow, 1.455620044969843, 3e-16, "slow precession");
        assert_relative(rates.fast, 7.781984262064169, 3e-16, "fast precession");
    }

    #[test]
    fn steady_precession_has_no_nutation() {
        // Started on the slow steady precession, u₀ = cos θ₀ is a double root of f: the bounds collapse onto θ₀.
        // A double root is only determined to ~√ε relative (measured: 5e-9 rad; rate 1.6e-9 relative).
        let top = scene_top();
        let slow = top.steady_precession_rates(TOP_INITIAL_TILT, TOP_SPIN).unwrap().slow;
        let steady = top.nutation(TOP_INITIAL_TILT, 0.0, slow, TOP_SPIN).unwrap();
        for bound in [steady.theta_min, steady.theta_max] {
            assert!((bound - TOP_INITIAL_TILT).abs() < 3e-8, "nutation bound {bound}");
        }
        assert_relative(steady.mean_precession_rate, slow, 3e-8, "precession rate");
    }

    #[test]
    fn horizontal_top_precesses_at_the_gyroscopic_rate() {
        // At θ = π/2 the quadratic degenerates: the slow root is exactly Mgl/(I₃ω₃), the fast one runs off to infinity.
        let top = scene_top();
        let rates = top
            .steady_precession_rates(std::f64::consts::FRAC_PI_2, TOP_SPIN)
            .unwrap();
        assert_relative(
            rates.slow,
            top.gyroscopic_precession_rate(TOP_SPIN),
            1e-15,
            "slow rate at π/2",
        );
        assert!(rates.fast > 1e15, "fast rate at π/2: {}", rates.fast);
    }

    #[test]
    fn heavy_top_rejects_impossible_requests() {
        let top = scene_top();
        assert!(matches!(
            top.steady_precession_rates(TOP_INITIAL_TILT, 1.0),
            Err(AnalyticError::NoSteadyPrecession { .. })
        ));
        assert!(matches!(
            top.nutation(0.0, 0.0, 0.0, TOP_SPIN),
            Err(AnalyticError::InvalidParameter { .. })
        ));
        let massless = HeavyTop { mass: 0.0, ..top };
        assert!(matches!(
            massless.nutation(TOP_INITIAL_TILT, 0.0, 0.0, TOP_SPIN),
            Err(AnalyticError::InvalidParameter { .. })
        ));
    }
}
