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

/// The largest Baumgarte gain α or β accepted (1/s): the feedback's rates reach about the gain, which an explicit
/// method follows only with steps below about 1/gain (here 1 µs); stiffer gains are a wrong unit or a typo.
pub const MAX_BAUMGARTE_GAIN: f64 = 1e6;

impl Stabilisation {
    /// Projection with the 2 Gauss–Newton steps of theory §10.
    pub const PROJECTION: Stabilisation = Stabilisation::Projection { position_iterations: 2 };

    /// Why the parameters are unusable, if they are.
    pub(crate) fn invalid_reason(&self) -> Option<String> {
        match *self {
            Stabilisation::Baumgarte { alpha, beta }
                if !((0.0..=MAX_BAUMGARTE_GAIN).contains(&alpha) && (0.0..=MAX_BAUMGARTE_GAIN).contains(&beta)) =>
            {
                Some(format!(
                    "Baumgarte gains must be non-negative and at most {MAX_BAUMGARTE_GAIN:e} 1/s, got α = {alpha:?}, \
                     β = {beta:?}: gains of g 1/s need steps below about 1/g s with these explicit methods"
                ))
            }
            _ => None,
        }
    }

    /// The fastest rate (1/s) of the Baumgarte feedback: the largest |s| of `s² + 2α s + β² = 0`, the residual's
    /// own equation `ë + 2α ė + β² e = 0`; zero without feedback.
    pub fn feedback_rate(&self) -> f64 {
        match *self {
            Stabilisation::Baumgarte { alpha, beta } if alpha >= beta => alpha + (alpha * alpha - beta * beta).sqrt(),
            Stabilisation::Baumgarte { beta, .. } => beta,
            _ => 0.0,
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
