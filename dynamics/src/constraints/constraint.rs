//! The interface every constraint implements — its name, rank and rows at one state — and the composite of several
//! constraints that act as one joint.

use std::sync::Arc;

use crate::algebra::Algebra;
use crate::constraints::error::ConstraintError;
use crate::constraints::kinematics::Kinematics;
use crate::constraints::rows::RowBuffer;

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
