//! The complete elliptic integral of the first kind K(m) and the Jacobi elliptic functions sn, cn, dn,
//! for a real argument and a parameter 0 ≤ m ≤ 1.
//!
//! Parameter convention: m = k² (Abramowitz & Stegun, and `docs/scenes.md`, which writes `K(k²)` and `sn(u | k²)`).
//! Both algorithms come from the arithmetic–geometric mean (AGM) and converge quadratically:
//! * K(m) = π / (2 AGM(1, √(1 − m)))  (A&S 17.6.1);
//! * sn, cn, dn by the descending Landen transformation in its AGM form (A&S 16.4): run the AGM
//!   forward, then recover the amplitude φ = am(u | m) backwards; sn = sin φ, cn = cos φ.

use thiserror::Error;

/// Invalid input to the elliptic functions.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[non_exhaustive]
pub enum EllipticError {
    /// The parameter m or its complement 1 − m lies outside [0, 1] (or is NaN).
    #[error("elliptic parameter m = {m} (complement {complement}) is outside [0, 1]")]
    ParameterOutOfRange {
        /// The parameter m that was requested.
        m: f64,
        /// Its complement m₁ = 1 − m.
        complement: f64,
    },
    /// [`complete_elliptic_k`] was called with m = 1 (complement 0), where K is infinite.
    #[error("K(m) diverges at m = 1")]
    CompleteIntegralDiverges,
    /// [`incomplete_elliptic_f`] was called with an amplitude beyond ±π/2 (or NaN).
    #[error("elliptic amplitude φ = {phi} is outside [-π/2, π/2]")]
    AmplitudeOutOfRange {
        /// The amplitude that was passed.
        phi: f64,
    },
    /// [`jacobi_elliptic`] was called with an infinite or NaN argument.
    #[error("elliptic function argument u = {u} is not finite")]
    NonFiniteArgument {
        /// The argument that was passed.
        u: f64,
    },
}

/// The elliptic parameter m = k² together with its complement m₁ = 1 − m.
///
/// Near m = 1 the functions depend on m₁ (K ≈ ln(4/√m₁)), but an f64 m fixes m₁ only to ±½ ulp(1) ≈ 1e-16 in
/// absolute terms: for the scene-1 cuboid (m₁ ≈ 2e-4) one ulp of m is 5e-13 of m₁ and 5e-14 of K. A caller who has
/// m₁ from a formula without cancellation should build the parameter with [`EllipticParameter::from_complement`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticParameter {
    m: f64,
    complement: f64,
}

impl EllipticParameter {
    /// From m ∈ [0, 1].
    ///
    /// ```
    /// use reference::{complete_elliptic_k, EllipticParameter};
    ///
    /// // K(½) = 1.854074677301372 (A&S table 17.1; the pendulum of `docs/scenes.md` scene 2).
    /// let half = EllipticParameter::new(0.5)?;
    /// assert!((complete_elliptic_k(half)? - 1.854074677301372).abs() < 1e-14);
    /// assert_eq!(half.complement(), 0.5);
    /// assert!(EllipticParameter::new(1.5).is_err()); // m = k² lies in [0, 1]
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(m: f64) -> Result<Self, EllipticError> {
        Self::checked(m, 1.0 - m)
    }

    /// From the complement m₁ = 1 − m ∈ [0, 1].
    ///
    /// ```
    /// use reference::{complete_elliptic_k, EllipticParameter};
    ///
    /// // The scene-1 cuboid, close to the separatrix: m₁ ≈ 2e-4, K(1 − m₁) = 5.625625086537179 (mpmath).
    /// let complement = 2.0795674499704062e-4;
    /// let parameter = EllipticParameter::from_complement(complement)?;
    /// assert_eq!(parameter.complement(), complement); // kept exactly, not recomputed as 1 − m
    /// assert!((complete_elliptic_k(parameter)? - 5.625625086537179).abs() < 1e-14);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_complement(complement: f64) -> Result<Self, EllipticError> {
        Self::checked(1.0 - complement, complement)
    }

    fn checked(m: f64, complement: f64) -> Result<Self, EllipticError> {
        if (0.0..=1.0).contains(&m) && (0.0..=1.0).contains(&complement) {
            Ok(Self { m, complement })
        } else {
            Err(EllipticError::ParameterOutOfRange { m, complement })
        }
    }

    /// The parameter m = k².
    pub fn m(self) -> f64 {
        self.m
    }

    /// The complement m₁ = 1 − m, exact if the parameter was built with [`EllipticParameter::from_complement`].
    pub fn complement(self) -> f64 {
        self.complement
    }
}

/// Upper bound on AGM steps. The AGM of (1, √m₁) converges quadratically; even m₁ = 1e-300 reaches machine
/// precision in about 12 steps, so this bound is never reached.
const MAX_AGM_STEPS: usize = 32;

/// Complete elliptic integral of the first kind, K(m) = ∫₀^{π/2} dθ / √(1 − m sin²θ), for m < 1.
pub fn complete_elliptic_k(parameter: EllipticParameter) -> Result<f64, EllipticError> {
    if parameter.complement == 0.0 {
        return Err(EllipticError::CompleteIntegralDiverges);
    }
    let (mut a, mut b) = (1.0_f64, parameter.complement.sqrt());
    for _ in 0..MAX_AGM_STEPS {
        if a - b <= f64::EPSILON * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    Ok(std::f64::consts::FRAC_PI_2 / a)
}

/// Incomplete elliptic integral of the first kind, F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ), for |φ| ≤ π/2 (and m < 1 at
/// |φ| = π/2), by Carlson's symmetric form F = sin φ · R_F(cos²φ, 1 − m sin²φ, 1) with R_F by the duplication theorem
/// (Carlson 1995, *Numerical Algorithms* 10, §2). The time a pendulum takes to swing between two angles is one
/// (docs/limits.md).
///
/// ```
/// use reference::{complete_elliptic_k, incomplete_elliptic_f, EllipticParameter};
///
/// let m = EllipticParameter::new(0.5)?;
/// let quarter = incomplete_elliptic_f(std::f64::consts::FRAC_PI_2, m)?;
/// assert!((quarter - complete_elliptic_k(m)?).abs() < 1e-15); // F(π/2 | m) = K(m)
/// assert!((incomplete_elliptic_f(0.3, EllipticParameter::new(0.0)?)? - 0.3).abs() < 1e-16); // F(φ | 0) = φ
/// assert!(incomplete_elliptic_f(2.0, m).is_err()); // beyond π/2
/// # Ok::<(), reference::EllipticError>(())
/// ```
pub fn incomplete_elliptic_f(phi: f64, parameter: EllipticParameter) -> Result<f64, EllipticError> {
    if phi.is_nan() || phi.abs() > std::f64::consts::FRAC_PI_2 {
        return Err(EllipticError::AmplitudeOutOfRange { phi });
    }
    let (s, c) = phi.sin_cos();
    if parameter.complement == 0.0 && c.abs() < f64::EPSILON {
        return Err(EllipticError::CompleteIntegralDiverges);
    }
    // 1 − m sin²φ = cos²φ + m₁ sin²φ, without the cancellation of 1 − m near m = 1.
    let y = c * c + parameter.complement * s * s;
    Ok(s * carlson_rf(c * c, y, 1.0))
}

/// Carlson's R_F(x, y, z) for x, y, z ≥ 0, at most one zero: duplicate until the arguments agree to 1e-4 relative,
/// then the fifth-order series (its error is below 1e-20 there).
fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    for _ in 0..MAX_AGM_STEPS * 4 {
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = (1.0 - x / mean, 1.0 - y / mean, 1.0 - z / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-4 {
            let (e2, e3) = (dx * dy - dz * dz, dx * dy * dz);
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / mean.sqrt();
        }
        let root = (x * y).sqrt() + (y * z).sqrt() + (z * x).sqrt();
        (x, y, z) = ((x + root) / 4.0, (y + root) / 4.0, (z + root) / 4.0);
    }
    unreachable!("the duplication shrinks the spread fourfold per step")
}

/// The three Jacobi elliptic functions at one argument.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobiElliptic {
    /// sn(u | m) = sin φ, with φ = am(u | m).
    pub sn: f64,
    /// cn(u | m) = cos φ.
    pub cn: f64,
    /// dn(u | m) = √(1 − m sn²).
    pub dn: f64,
}

/// sn(u | m), cn(u | m), dn(u | m) for a finite argument u.
pub fn jacobi_elliptic(u: f64, parameter: EllipticParameter) -> Result<JacobiElliptic, EllipticError> {
    if !u.is_finite() {
        return Err(EllipticError::NonFiniteArgument { u });
    }
    let EllipticParameter { m, complement } = parameter;
    if complement == 0.0 {
        // The AGM of (1, 0) does not converge quadratically; the limit is elementary (A&S 16.6).
        let sech = 1.0 / u.cosh();
        return Ok(JacobiElliptic {
            sn: u.tanh(),
            cn: sech,
            dn: sech,
        });
    }

    // Forward AGM (A&S 16.4): a₀ = 1, b₀ = √m₁, c₀ = √m; a_{n+1} = (a_n + b_n)/2, b_{n+1} = √(a_n b_n),
    // c_{n+1} = (a_n − b_n)/2, until c_N is negligible.
    let mut a = [0.0_f64; MAX_AGM_STEPS + 1];
    let mut c = [0.0_f64; MAX_AGM_STEPS + 1];
    a[0] = 1.0;
    c[0] = m.sqrt();
    let mut b = complement.sqrt();
    let mut steps = 0;
    while steps < MAX_AGM_STEPS && c[steps] > f64::EPSILON * a[steps] {
        a[steps + 1] = 0.5 * (a[steps] + b);
        c[steps + 1] = 0.5 * (a[steps] - b);
        b = (a[steps] * b).sqrt();
        steps += 1;
    }

    // Backward: φ_N = 2^N a_N u, then φ_{n−1} = (φ_n + asin((c_n / a_n) sin φ_n)) / 2; φ₀ = am(u | m).
    let mut phi = 2.0_f64.powi(steps as i32) * a[steps] * u;
    for n in (1..=steps).rev() {
        phi = 0.5 * (phi + (c[n] / a[n] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();

    // dn² = 1 − m sn² = m₁ + m cn². Each form is a sum without cancellation where it is used: the first while
    // sn² ≤ ½, the second otherwise (A&S's cos φ₀ / cos(φ₁ − φ₀) is 0/0 at u = K, exactly where the scenes start).
    let dn = if sn * sn <= 0.5 {
        (1.0 - m * sn * sn).sqrt()
    } else {
        (complement + m * cn * cn).sqrt()
    };
    Ok(JacobiElliptic { sn, cn, dn })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// `docs/scenes.md` scene 1: k² of the Dzhanibekov cuboid, as printed.
    const CUBOID_M: f64 = 0.999792043255003;
    /// Its complement 1 − k², from the cancellation-free formula (see `analytic::DzhanibekovSolution`).
    const CUBOID_COMPLEMENT: f64 = 2.0795674499704062e-4;

    fn parameter(m: f64) -> EllipticParameter {
        EllipticParameter::new(m).unwrap()
    }

    fn relative_difference(value: f64, expected: f64) -> f64 {
        ((value - expected) / expected).abs()
    }

    /// Incomplete integral F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ) by composite Simpson: an independent
    /// (slow, quadrature) route to the amplitude, so sn(F(φ)) = sin φ tests the AGM algorithm.
    fn incomplete_integral_by_simpson(phi: f64, m: f64) -> f64 {
        let intervals: u32 = 20_000;
        let h = phi / intervals as f64;
        let integrand = |theta: f64| 1.0 / (1.0 - m * theta.sin().powi(2)).sqrt();
        let interior: f64 = (1..intervals)
            .map(|j| if j.is_multiple_of(2) { 2.0 } else { 4.0 } * integrand(j as f64 * h))
            .sum();
        h / 3.0 * (integrand(0.0) + interior + integrand(phi))
    }

    #[test]
    fn complete_integral_matches_scenes_md() {
        // docs/scenes.md scene 2: K(0.5); scene 1: K(k²).
        let k_half = complete_elliptic_k(parameter(0.5)).unwrap();
        let k_cuboid = complete_elliptic_k(parameter(CUBOID_M)).unwrap();
        assert!(
            relative_difference(k_half, 1.85407467730137) < 1e-14,
            "K(0.5) = {k_half}"
        );
        assert!(
            relative_difference(k_cuboid, 5.62562508653737) < 1e-14,
            "K(m) = {k_cuboid}"
        );
        assert_eq!(complete_elliptic_k(parameter(0.0)).unwrap(), FRAC_PI_2);
    }

    #[test]
    fn complete_integral_matches_quadrature() {
        for m in [0.1, 0.5, 0.9] {
            let quadrature = incomplete_integral_by_simpson(FRAC_PI_2, m);
            let agm = complete_elliptic_k(parameter(m)).unwrap();
            assert!(
                relative_difference(agm, quadrature) < 1e-13,
                "m = {m}: {agm} vs {quadrature}"
            );
        }
    }

    #[test]
    fn incomplete_integral_matches_quadrature() {
        for m in [0.0, 0.2, 0.5, 0.9, CUBOID_M] {
            for phi in [-1.2f64, 0.0, 0.3, 1.0, 1.5] {
                let quadrature = incomplete_integral_by_simpson(phi.abs(), m) * phi.signum();
                let carlson = incomplete_elliptic_f(phi, parameter(m)).unwrap();
                assert!(
                    (carlson - quadrature).abs() < 1e-13,
                    "m = {m}, φ = {phi}: {carlson} vs {quadrature}"
                );
            }
            if m < 1.0 {
                let quarter = incomplete_elliptic_f(FRAC_PI_2, parameter(m)).unwrap();
                assert!(relative_difference(quarter, complete_elliptic_k(parameter(m)).unwrap()) < 1e-15);
            }
        }
        for phi in [f64::NAN, 1.6, -2.0, f64::INFINITY] {
            assert!(incomplete_elliptic_f(phi, parameter(0.5)).is_err(), "φ = {phi}");
        }
        assert!(incomplete_elliptic_f(FRAC_PI_2, EllipticParameter::new(1.0).unwrap()).is_err());
        assert!(
            (incomplete_elliptic_f(1.0, EllipticParameter::new(1.0).unwrap()).unwrap() - 1.0f64.tan().asinh()).abs()
                < 1e-15
        );
    }

    #[test]
    fn amplitude_inverts_the_incomplete_integral() {
        for m in [0.2, 0.5, 0.9] {
            for phi in [0.3, 1.0, 1.5, 2.5, 4.0] {
                let u = incomplete_integral_by_simpson(phi, m);
                let jacobi = jacobi_elliptic(u, parameter(m)).unwrap();
                let expected_dn = (1.0 - m * phi.sin().powi(2)).sqrt();
                assert!((jacobi.sn - phi.sin()).abs() < 1e-13, "sn, m = {m}, φ = {phi}");
                assert!((jacobi.cn - phi.cos()).abs() < 1e-13, "cn, m = {m}, φ = {phi}");
                assert!((jacobi.dn - expected_dn).abs() < 1e-13, "dn, m = {m}, φ = {phi}");
            }
        }
    }

    #[test]
    fn identities_hold() {
        for m in [0.0, 0.3, 0.5, 0.9, CUBOID_M] {
            for j in 0..200 {
                let u = -20.0 + 0.2 * j as f64;
                let JacobiElliptic { sn, cn, dn } = jacobi_elliptic(u, parameter(m)).unwrap();
                assert!((sn * sn + cn * cn - 1.0).abs() < 1e-15, "sn²+cn², m = {m}, u = {u}");
                assert!(
                    (dn * dn + m * sn * sn - 1.0).abs() < 1e-15,
                    "dn²+m sn², m = {m}, u = {u}"
                );
            }
        }
    }

    #[test]
    fn derivative_of_sn_is_cn_dn() {
        // Central difference with h = 1e-5: truncation ~ h² sn‴/6, rounding ~ 1e-16/h.
        let h = 1e-5;
        for m in [0.5, CUBOID_M] {
            for u in [0.1, 1.3, 4.0, 7.7] {
                let numeric = (jacobi_elliptic(u + h, parameter(m)).unwrap().sn
                    - jacobi_elliptic(u - h, parameter(m)).unwrap().sn)
                    / (2.0 * h);
                let JacobiElliptic { cn, dn, .. } = jacobi_elliptic(u, parameter(m)).unwrap();
                assert!(
                    (numeric - cn * dn).abs() < 1e-9,
                    "m = {m}, u = {u}: {numeric} vs {}",
                    cn * dn
                );
            }
        }
    }

    #[test]
    fn quarter_and_half_periods() {
        // Built from the complement, so dn(K) = √m₁ can be checked to full relative precision even where m₁ = 2e-4.
        for complement in [0.5, CUBOID_COMPLEMENT] {
            let m = EllipticParameter::from_complement(complement).unwrap();
            let k = complete_elliptic_k(m).unwrap();
            let at_quarter = jacobi_elliptic(k, m).unwrap();
            assert!((at_quarter.sn - 1.0).abs() < 1e-15, "sn(K) = {}", at_quarter.sn);
            assert!(at_quarter.cn.abs() < 1e-15, "cn(K) = {}", at_quarter.cn);
            assert!(
                relative_difference(at_quarter.dn, complement.sqrt()) < 1e-15,
                "dn(K) = {}",
                at_quarter.dn
            );
            // sn(u + 2K) = −sn(u), cn(u + 2K) = −cn(u), dn(u + 2K) = dn(u).
            for u in [0.37, 2.9, 11.0] {
                let here = jacobi_elliptic(u, m).unwrap();
                let shifted = jacobi_elliptic(u + 2.0 * k, m).unwrap();
                assert!((here.sn + shifted.sn).abs() < 1e-13, "m₁ = {complement}, u = {u}");
                assert!((here.cn + shifted.cn).abs() < 1e-13, "m₁ = {complement}, u = {u}");
                assert!((here.dn - shifted.dn).abs() < 1e-13, "m₁ = {complement}, u = {u}");
            }
        }
    }

    #[test]
    fn limits_are_trigonometric_and_hyperbolic() {
        for u in [-3.0, -0.5, 0.0, 0.8, PI, 12.0] {
            let circular = jacobi_elliptic(u, parameter(0.0)).unwrap();
            assert!((circular.sn - u.sin()).abs() < 1e-15 && (circular.cn - u.cos()).abs() < 1e-15);
            assert_eq!(circular.dn, 1.0);
            let hyperbolic = jacobi_elliptic(u, parameter(1.0)).unwrap();
            assert!((hyperbolic.sn - u.tanh()).abs() < 1e-15);
            assert!((hyperbolic.cn - 1.0 / u.cosh()).abs() < 1e-15 && hyperbolic.cn == hyperbolic.dn);
            // Just below m = 1 the AGM path must agree with the limit.
            let nearly_hyperbolic = jacobi_elliptic(u, parameter(1.0 - 1e-14)).unwrap();
            assert!((nearly_hyperbolic.sn - u.tanh()).abs() < 1e-12, "u = {u}");
        }
    }

    #[test]
    fn complement_keeps_the_precision_near_one() {
        // Scene 1's m₁ = (I_x − I_z)(L² − 2T I_y) / ((I_x − I_y)(L² − 2T I_z)) = 2.0795674499704062e-4 in double,
        // and K(1 − m₁) = 5.62562508653717948 (mpmath, 40 digits). From m instead, one ulp of m moves K by 5e-14.
        let k = complete_elliptic_k(EllipticParameter::from_complement(CUBOID_COMPLEMENT).unwrap()).unwrap();
        assert!(relative_difference(k, 5.6256250865371795) < 2e-16, "K = {k}");
    }

    #[test]
    fn bad_input_is_an_error() {
        for m in [-0.1, 1.5, f64::NAN] {
            assert!(matches!(
                EllipticParameter::new(m),
                Err(EllipticError::ParameterOutOfRange { .. })
            ));
            assert!(matches!(
                EllipticParameter::from_complement(m),
                Err(EllipticError::ParameterOutOfRange { .. })
            ));
        }
        assert_eq!(
            complete_elliptic_k(parameter(1.0)),
            Err(EllipticError::CompleteIntegralDiverges)
        );
        assert!(matches!(
            jacobi_elliptic(f64::INFINITY, parameter(0.5)),
            Err(EllipticError::NonFiniteArgument { .. })
        ));
    }
}
