//! Constraints (`docs/theory.md` §6–§9): by virtual power, by pinning multivectors, parametric paths and linear
//! functions of them. Each is written for one body against a reference frame — the world, or, as a joint of a
//! [`crate::Mechanism`], another body — and evaluated at every evaluation of the equations of motion.
//!
//! # One formulation for all of them
//!
//! Every constraint here reduces, at one state, to scalar **rows** in the body velocity coordinates
//! `x = (ω; v)` of Ḃ (theory §3; for a joint, the velocity relative to the reference) — see [`ConstraintRow`]:
//!
//! * a velocity residual `ė = a·x + s(t)`, linear in x with the Jacobian row `a`;
//! * its rate along the motion `ë = a·ẍ + b`, where `ẍ` are the coordinates of B̈ and b (the *bias*) collects
//!   every term without B̈;
//! * optionally a position residual e with `de/dt = ė`, which the stabilisation uses (theory §10).
//!
//! Virtual power (§6): `ė = ⟨Ḃ ∧ T_b⟩_Π`, so `a` holds the wrench coordinates `(τ; f)` of `T_b = ~R T R`.
//! Pinning (§7–§9): `ė = A[Ḃ × V_b + V̇_b] − U̇`, one row per multivector coefficient, column j of `a` holding
//! `A[Ḃⱼ × V_b]` for the basis velocity Ḃⱼ. With `B̈ = M⁻¹[Ḃ×Ω_b + S + F]` (theory §5), i.e.
//! `ẍ = H⁻¹(g + y)` in wrench coordinates, the acceleration condition `ë = 0` becomes a linear system for the
//! reaction y (theory §6 and §7.1), which [`crate::mechanism`] solves for all joints of a system at once in the
//! kinetic metric, each joint with its known rank.

mod kinematics;
pub mod linear;
pub mod objects;
mod on_surfaces;
pub mod paths;
pub mod pinning;
mod rows;
pub mod stabilise;
pub mod virtual_power;

use std::sync::Arc;

pub use kinematics::Kinematics;
pub use objects::{Coefficients, Pinnable, PinningAlgebra};
pub use on_surfaces::{SurfacePin, TANGENT};
pub use paths::{CarriedPath, MotorPath, MotorPoint, Path, PathPoint, ScrewMotion};
pub use pinning::{LinearFunction, Pin};
pub use rows::{ConstraintRow, RowBuffer, MAX_ROWS};
pub use stabilise::Stabilisation;
pub use virtual_power::{VirtualPower, WrenchPath, WrenchPoint};

use crate::algebra::Algebra;

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
    /// More scalar rows than [`MAX_ROWS`].
    #[error("constraint {name}: the system needs {rows} rows, more than the {capacity} supported")]
    TooManyRows {
        /// The name of the constraint.
        name: String,
        /// How many rows it needs.
        rows: usize,
        /// How many rows are supported ([`MAX_ROWS`]).
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
        /// The name of the constraint (or "stabilisation" for a bad [`Stabilisation`]).
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

/// A constraint on one body: emits its rows at a state (see the module docs).
pub trait Constraint<A: Algebra>: Send + Sync {
    /// A name for error messages and reports.
    fn name(&self) -> &str;
    /// The number of degrees of freedom removed on the constraint manifold (theory §7 table, §9 table).
    fn rank(&self) -> usize;
    /// How many rows [`Constraint::rows`] pushes.
    fn row_count(&self) -> usize;
    /// Whether every row has a position residual (needed by projection, theory §10).
    fn has_position_residual(&self) -> bool;
    /// Pushes the rows at this state.
    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError>;
    /// Whether [`Constraint::rows`] reads the motor ([`Kinematics::motor`] or [`Kinematics::reverse`]) rather than
    /// only the frame and velocities. A joint between two bodies composes their relative motor only for
    /// constraints that do; for the others those fields hold NaN, so that a constraint answering `false` wrongly
    /// gets non-finite rows (an error), never a quiet wrong answer.
    fn uses_motor(&self) -> bool {
        true
    }
}

/// Several constraints acting as one, with a declared rank: a hinge pinned as a line plus a point has rank 5,
/// not 4 + 3 (theory §7 table, E7), and a circle by virtual power is a sphere plus a plane (theory §6).
#[derive(Clone)]
pub struct Composite<A: Algebra> {
    name: String,
    parts: Vec<Arc<dyn Constraint<A>>>,
    rank: usize,
}

impl<A: Algebra> Composite<A> {
    /// The parts act together with `rank` constrained degrees of freedom.
    ///
    /// A point kept on the x axis as the meet of two planes: two rows, rank 2, and the point free to slide along
    /// the axis.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use dynamics::constraints::{Composite, Constraint, VirtualPower};
    /// use dynamics::{Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let planes: Vec<Arc<dyn Constraint<Pga>>> = vec![
    ///     Arc::new(VirtualPower::point_on_plane("y = 0", Vector3::zeros(), (Vector3::y(), 0.0))?),
    ///     Arc::new(VirtualPower::point_on_plane("z = 0", Vector3::zeros(), (Vector3::z(), 0.0))?),
    /// ];
    /// let on_axis = Composite::new("on the x axis", planes, 2);
    /// assert_eq!((on_axis.rank(), on_axis.row_count()), (2, 2));
    /// let bead = Body::sphere(0.1, 0.01)?;
    /// let system = Mechanism::single(bead).with_constraint(on_axis)?;
    /// let still = UnitQuaternion::identity();
    /// let sliding = State::new(&bead, Vector3::x() * 3.0, &still, Vector3::zeros(), Vector3::x());
    /// let on = system.violation(0.0, &[sliding])?;
    /// assert!(on.position == 0.0 && on.velocity == 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(name: impl Into<String>, parts: Vec<Arc<dyn Constraint<A>>>, rank: usize) -> Self {
        Composite {
            name: name.into(),
            parts,
            rank,
        }
    }

    /// The constraints that act together, in the order their rows are pushed.
    pub fn parts(&self) -> &[Arc<dyn Constraint<A>>] {
        &self.parts
    }
}

impl<A: Algebra> Constraint<A> for Composite<A> {
    fn name(&self) -> &str {
        &self.name
    }

    fn rank(&self) -> usize {
        self.rank
    }

    fn row_count(&self) -> usize {
        self.parts.iter().map(|part| part.row_count()).sum()
    }

    fn has_position_residual(&self) -> bool {
        self.parts.iter().all(|part| part.has_position_residual())
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        self.parts.iter().try_for_each(|part| part.rows(kinematics, rows))
    }

    fn uses_motor(&self) -> bool {
        self.parts.iter().any(|part| part.uses_motor())
    }
}

impl<A: Algebra> std::fmt::Debug for Composite<A> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<&str> = self.parts.iter().map(|part| part.name()).collect();
        f.debug_struct("Composite")
            .field("name", &self.name)
            .field("parts", &names)
            .field("rank", &self.rank)
            .finish()
    }
}

/// A shared constraint is a constraint (e.g. one [`Arc`] used in several systems).
impl<A: Algebra, C: Constraint<A> + ?Sized> Constraint<A> for Arc<C> {
    fn name(&self) -> &str {
        (**self).name()
    }

    fn rank(&self) -> usize {
        (**self).rank()
    }

    fn row_count(&self) -> usize {
        (**self).row_count()
    }

    fn has_position_residual(&self) -> bool {
        (**self).has_position_residual()
    }

    fn rows(&self, kinematics: &Kinematics<A>, rows: &mut RowBuffer) -> Result<(), ConstraintError> {
        (**self).rows(kinematics, rows)
    }

    fn uses_motor(&self) -> bool {
        (**self).uses_motor()
    }
}
