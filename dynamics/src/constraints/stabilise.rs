//! Stabilisation against drift (`docs/theory.md` §10). All formulations here hold the constraints at the acceleration
//! level only, so position and velocity errors grow (∝ t³ and t² for the hinge, E9) unless corrected:
//!
//! * **Baumgarte**: solve `ë + 2α ė + β² e = 0` instead of `ë = 0`. In the solve's right-hand side
//!   `r' = −a·H⁻¹g − b` this subtracts `2α ė + β² e`; in theory §7.1's `C y = r` with `C = −A H⁻¹` it is the
//!   `r + 2α ė + β² e` with the **+** sign. Rows without a position residual get the α term only.
//! * **Projection** after each step: normalise R, then Gauss–Newton steps on the position,
//!   `δ = −H⁻¹Aᵀ(AH⁻¹Aᵀ)⁺_r e`, `R ← normalise(R exp(−½δ))` (the motion with body velocity δ for unit time),
//!   then the velocity projection in the kinetic metric, `x ← x − H⁻¹Aᵀ(AH⁻¹Aᵀ)⁺_r ė`. Both are the
//!   kinetic-metric reaction solve of [`crate::mechanism`] with right-hand sides `−e` and `−ė`, for all the
//!   bodies of a mechanism at once.

use crate::constraints::rows::ConstraintRow;

/// How a constrained system is kept on its constraint manifold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stabilisation {
    /// None: the bare acceleration-level constraints (theory §6–§9).
    None,
    /// Baumgarte feedback with damping α and stiffness β (1/s); theory §10 uses α = β = 10 (pendulum,
    /// circle) or 20 (top).
    Baumgarte {
        /// The damping α (1/s): the `2α ė` term.
        alpha: f64,
        /// The stiffness β (1/s): the `β² e` term.
        beta: f64,
    },
    /// Projection onto the manifold after every step that leaves the joints off it by more than round-off
    /// (1e-14 in position, 1e-12 in velocity, or 16 ulp of the largest coordinate), with at most this many
    /// Gauss–Newton steps on the position.
    Projection {
        /// The most Gauss–Newton steps on the position per projection.
        position_iterations: usize,
    },
}

impl Stabilisation {
    /// Projection with the 2 Gauss–Newton steps of theory §10.
    pub const PROJECTION: Stabilisation = Stabilisation::Projection { position_iterations: 2 };

    /// Why the parameters are unusable, if they are.
    pub(crate) fn invalid_reason(&self) -> Option<String> {
        match *self {
            Stabilisation::Baumgarte { alpha, beta }
                if !(alpha.is_finite() && beta.is_finite() && alpha >= 0.0 && beta >= 0.0) =>
            {
                Some(format!(
                    "Baumgarte gains must be finite and non-negative, got α = {alpha}, β = {beta}"
                ))
            }
            _ => None,
        }
    }

    /// The Baumgarte term `2α ė + β² e` of a row (zero without Baumgarte).
    #[inline]
    pub(crate) fn feedback(&self, row: &ConstraintRow) -> f64 {
        match *self {
            Stabilisation::Baumgarte { alpha, beta } => {
                2.0 * alpha * row.velocity_residual + beta * beta * row.position_residual.unwrap_or(0.0)
            }
            _ => 0.0,
        }
    }
}
