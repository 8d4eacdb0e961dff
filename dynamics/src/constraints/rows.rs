//! The scalar rows every constraint reduces to (see the module docs of [`crate::constraints`]), and a
//! fixed-capacity buffer for them, so an evaluation of the equations of motion does not allocate.

use arrayvec::ArrayVec;

/// The most rows one system can have: a CGA hinge pinned as an OPNS line (10 coefficients) and a point
/// (5) needs 15; twice that leaves room for several pins.
pub const MAX_ROWS: usize = 32;

/// One scalar constraint at one state, in the body velocity coordinates `x = (ω; v)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ConstraintRow {
    /// `a`: the velocity residual is `a·x + s(t)`.
    pub jacobian: [f64; 6],
    /// `ė`, the velocity residual at this state.
    pub velocity_residual: f64,
    /// `b`: the rate of the velocity residual is `a·ẍ + b`.
    pub bias: f64,
    /// `e`, with `de/dt = ė`, if the constraint has a position-level form.
    pub position_residual: Option<f64>,
}

impl ConstraintRow {
    #[inline]
    pub(crate) fn is_finite(&self) -> bool {
        // x·0 is ±0 for finite x and NaN for ±∞ or NaN, so the sum is zero exactly when every entry is finite
        // (one branch instead of one per entry).
        let zeroes = self.jacobian.iter().map(|a| a * 0.0).sum::<f64>()
            + self.velocity_residual * 0.0
            + self.bias * 0.0
            + self.position_residual.map_or(0.0, |e| e * 0.0);
        zeroes == 0.0
    }
}

/// Up to [`MAX_ROWS`] rows. Rows pushed beyond the capacity are counted, not stored, and reported by the
/// system as [`crate::constraints::ConstraintError::TooManyRows`]. The storage is not initialised until rows
/// are pushed: an evaluation creates a buffer at every stage, and zeroing 32 rows cost 14% of a step.
#[derive(Clone, Debug, Default)]
pub struct RowBuffer {
    rows: ArrayVec<ConstraintRow, MAX_ROWS>,
    requested: usize,
}

impl RowBuffer {
    /// An empty buffer.
    ///
    /// The buffer a constraint pushes its rows into: a hinge about x by virtual power pushes five, and a body
    /// turning about the hinge axis has zero velocity residual on each.
    ///
    /// ```
    /// use dynamics::constraints::{Constraint, Kinematics, RowBuffer, VirtualPower};
    /// use dynamics::{motor, Algebra, Pga, ScrewCoordinates};
    /// use nalgebra::Vector3;
    ///
    /// let axis = (Vector3::zeros(), Vector3::x()); // (point, direction): the x axis, in the body and the world
    /// let hinge = VirtualPower::<Pga>::hinge("hinge", axis, axis)?;
    /// let turning = Pga::screw(ScrewCoordinates { l: Vector3::x() * 3.0, t: Vector3::zeros() }); // rad/s
    /// let at = Kinematics::<Pga>::new(0.0, motor::identity::<Pga>(), turning);
    /// let mut rows = RowBuffer::new();
    /// hinge.rows(&at, &mut rows)?;
    /// assert_eq!((rows.len(), rows.requested()), (5, 5));
    /// assert!(rows.rows().iter().all(|row| row.velocity_residual == 0.0));
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends a row (see the type docs for overflow).
    #[inline]
    pub fn push(&mut self, row: ConstraintRow) {
        self.requested += 1;
        // Full: only counted.
        let _ = self.rows.try_push(row);
    }

    /// The stored rows.
    #[inline]
    pub fn rows(&self) -> &[ConstraintRow] {
        &self.rows
    }

    /// How many rows were pushed, including any beyond the capacity.
    pub fn requested(&self) -> usize {
        self.requested
    }

    /// The number of stored rows (at most [`MAX_ROWS`]; see [`RowBuffer::requested`] for all pushed).
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether no row is stored.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Removes every row and resets the count of pushed rows.
    pub fn clear(&mut self) {
        self.rows.clear();
        self.requested = 0;
    }
}
