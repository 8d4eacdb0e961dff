//! Why a constrained system could not be evaluated: the one error type of the constraints, the mechanism's
//! reaction solve and the systems the integrators step.

/// Why a constrained system could not be evaluated. Each variant names the constraint(s) involved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConstraintError {
    /// The rows lost rank: the `rank`-th singular value of the (kinetic-metric scaled) constraint map is
    /// negligible against the largest, so the reaction is not determined (theory §7.1).
    #[error(
        "constraint {names}: rank deficient, expected rank {rank} but singular value {rank} is {singular_value:e} \
         (largest {largest:e})"
    )]
    RankDeficient {
        /// The names of the joints involved, joined by " + ".
        names: String,
        /// The declared rank (or the size of the joint's reaction basis).
        rank: usize,
        /// The `rank`-th singular value counting from the largest (or the pivot of the factorisation that found
        /// the deficiency).
        singular_value: f64,
        /// The largest singular value, against which it is negligible.
        largest: f64,
    },
    /// The acceleration conditions have no solution within the declared rank (or the supplied reaction basis):
    /// the relative residual `|C y − r| / |r|` exceeds [`SolverSettings::consistency_tolerance`].
    ///
    /// [`SolverSettings::consistency_tolerance`]: crate::SolverSettings::consistency_tolerance
    #[error("constraint {names}: inconsistent, relative residual {relative_residual:e} of the reaction solve")]
    Inconsistent {
        /// The names of the joints involved (a joint and the joints closing its loops), joined by " + ".
        names: String,
        /// The relative residual `|C y − r| / |r|` of the reaction solve.
        relative_residual: f64,
    },
    /// Projection cannot bring the positions onto these joints together (e.g. one body point held at two
    /// places): after Gauss–Newton steps their position residual is still this large.
    #[error("constraint {names}: cannot hold together, position residual {residual:e} after projection")]
    Unreachable {
        /// The names of the joints left unsatisfied, joined by " + ".
        names: String,
        /// The largest of their position residuals after projection.
        residual: f64,
    },
    /// A constraint produced a non-finite row (e.g. the state or a user path is not finite).
    #[error("constraint {name}: non-finite residual or Jacobian at t = {t}")]
    NonFinite {
        /// The name of the constraint, or of the joints at the body whose reaction is not finite.
        name: String,
        /// The time of the evaluation (s).
        t: f64,
    },
    /// More scalar rows than [`MAX_ROWS`](crate::constraints::MAX_ROWS).
    #[error("constraint {name}: the system needs {rows} rows, more than the {capacity} supported")]
    TooManyRows {
        /// The name of the constraint.
        name: String,
        /// How many rows it needs.
        rows: usize,
        /// How many rows are supported ([`MAX_ROWS`](crate::constraints::MAX_ROWS)).
        capacity: usize,
    },
    /// A declared rank that cannot hold: zero, or more than 6 (the body's degrees of freedom) or than the rows.
    #[error("constraint {name}: declared rank {rank} is not between 1 and min(6, {rows} rows)")]
    InvalidRank {
        /// The name of the constraint.
        name: String,
        /// The rank it declares.
        rank: usize,
        /// The number of rows it emits.
        rows: usize,
    },
    /// Projection (theory §10) needs a position residual, which this constraint does not provide (e.g. virtual
    /// power from user wrenches, theory §6).
    #[error(
        "constraint {name}: has no position-level residual, so it cannot be stabilised by projection (the default): \
         choose Stabilisation::None or Baumgarte before adding it"
    )]
    NoPositionResidual {
        /// The name of the constraint.
        name: String,
    },
    /// A parameter of a constraint is not usable (zero axis, non-positive radius, …).
    #[error("constraint {name}: {reason}")]
    InvalidParameter {
        /// The name of the constraint (or "stabilisation" for a bad [`Stabilisation`](crate::Stabilisation)).
        name: String,
        /// What is wrong with the parameter.
        reason: String,
    },
    /// A point held on a surface reached a singular point of it (a cone's apex: no normal), or the two surfaces of
    /// a curve are tangent there (their rows have lost rank).
    #[error("constraint {name}: {reason}")]
    Singular {
        /// The name of the constraint.
        name: String,
        /// Where and what: no normal, or tangent surfaces.
        reason: String,
    },
    /// A slice given to a system does not hold one entry per body (states, motors, momenta, rates) or per joint
    /// coordinate (positions, velocities, accelerations).
    #[error("{what}: {got} given, the system has {expected}")]
    Count {
        /// What was counted.
        what: &'static str,
        /// The number the system needs.
        expected: usize,
        /// The number given.
        got: usize,
    },
}
