//! The metric: the bilinear form on the basis vectors.

use crate::blade::BladeMask;

/// A diagonal metric: basis vector `i` squares to `squares[i]` ∈ {+1, −1, 0}.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Metric {
    squares: Vec<i64>,
}

impl Metric {
    pub fn diagonal(squares: Vec<i64>) -> Self {
        Metric { squares }
    }

    /// The square of basis vector `i`.
    pub fn square(&self, i: usize) -> i64 {
        self.squares[i]
    }

    /// The product of the squares of the vectors shared by two blades (0 if any is null).
    pub fn shared_factor(&self, shared: BladeMask) -> i64 {
        (0..self.squares.len())
            .filter(|i| shared & (1 << i) != 0)
            .map(|i| self.squares[i])
            .product()
    }

    /// Whether some basis vector squares to 0.
    pub fn is_degenerate(&self) -> bool {
        self.squares.contains(&0)
    }

    pub fn dimension(&self) -> usize {
        self.squares.len()
    }
}
