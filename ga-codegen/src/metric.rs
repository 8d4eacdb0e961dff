//! The metric: the symmetric bilinear form B(eᵢ, eⱼ) on the basis vectors, with exact rational entries.
//!
//! Most algebras are declared on an orthogonal basis (a diagonal form: each vector squares to +1, −1
//! or 0), and the product rules take a fast path for them. A general form, such as CGA on a null
//! basis with `n0 · ninf = −1`, is given as a full matrix.

use num_rational::Rational64;
use num_traits::{Signed, ToPrimitive, Zero};

use crate::blade::{BladeMask, MAX_DIMENSION};
use crate::error::Error;

/// The largest coefficient magnitude a metric may produce (see [`Metric::from_matrix`]). The compiler
/// computes with `i64` rationals and multiplies at most two rule coefficients (sandwiches), so the
/// square of this bound, 2⁴⁸, leaves room for 2¹⁵ such products summed into one coefficient.
const MAX_COEFFICIENT_BOUND: f64 = (1u64 << 24) as f64;

/// A symmetric bilinear form on the basis vectors.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Metric {
    /// Row-major n×n entries B(eᵢ, eⱼ), symmetric.
    entries: Vec<Rational64>,
    dimension: usize,
    /// No off-diagonal entry is non-zero: the product rules take the single-term fast path.
    diagonal: bool,
}

impl Metric {
    /// A diagonal metric: basis vector `i` squares to `squares[i]`.
    ///
    /// ```
    /// use ga_codegen::metric::Metric;
    /// use ga_codegen::Rational64;
    ///
    /// // 3D PGA, Cl(3,0,1): e0² = 0, e1² = e2² = e3² = 1.
    /// let pga = Metric::diagonal(vec![0, 1, 1, 1])?;
    /// assert_eq!(pga.dimension(), 4);
    /// assert_eq!(pga.square(0), Rational64::from_integer(0));
    /// assert_eq!(pga.square(1), Rational64::from_integer(1));
    /// assert_eq!(pga.inner(1, 2), Rational64::from_integer(0)); // an orthogonal basis
    /// assert!(pga.is_diagonal());
    ///
    /// // Squares so large that products of blades would overflow exact 64-bit coefficients are refused.
    /// assert!(matches!(Metric::diagonal(vec![1 << 40; 3]), Err(ga_codegen::Error::MetricTooLarge { .. })));
    /// # Ok::<(), ga_codegen::Error>(())
    /// ```
    pub fn diagonal(squares: Vec<i64>) -> Result<Self, Error> {
        let n = squares.len();
        if n > MAX_DIMENSION {
            return Err(Error::TooManyBasisVectors {
                count: n,
                max: MAX_DIMENSION,
            });
        }
        let mut entries = vec![Rational64::zero(); n * n];
        for (i, square) in squares.into_iter().enumerate() {
            entries[i * n + i] = Rational64::from_integer(square);
        }
        let metric = Metric {
            entries,
            dimension: n,
            diagonal: true,
        };
        if metric.coefficient_bound() > MAX_COEFFICIENT_BOUND {
            return Err(Error::MetricTooLarge { dimension: n });
        }
        Ok(metric)
    }

    /// A general form from its rows: `rows[i][j]` = B(eᵢ, eⱼ). The matrix must be square and
    /// symmetric, and its entries small enough that every coefficient of every product stays exact in
    /// 64-bit arithmetic (ordinary metrics, with entries such as ±1, ±2 or ½, are far from the limit;
    /// see [`Error::MetricTooLarge`]).
    ///
    /// ```
    /// use ga_codegen::metric::Metric;
    /// use ga_codegen::{Error, Rational64};
    ///
    /// // A null basis of the Minkowski plane: n0² = ninf² = 0, n0 · ninf = −1.
    /// let (zero, one) = (Rational64::from_integer(0), Rational64::from_integer(1));
    /// let null_plane = Metric::from_matrix(&[vec![zero, -one], vec![-one, zero]])?;
    /// assert!(!null_plane.is_diagonal());
    /// assert_eq!(null_plane.square(0), zero);
    /// assert_eq!(null_plane.inner(0, 1), -one);
    ///
    /// // A bilinear form is symmetric: B(n0, ninf) ≠ B(ninf, n0) is refused.
    /// let asymmetric = Metric::from_matrix(&[vec![zero, -one], vec![one, zero]]);
    /// assert!(matches!(asymmetric, Err(Error::MetricNotSymmetric { row: 1, column: 0, .. })));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_matrix(rows: &[Vec<Rational64>]) -> Result<Self, Error> {
        let n = rows.len();
        for (row, entries) in rows.iter().enumerate() {
            if entries.len() != n {
                return Err(Error::MetricRowLength {
                    row,
                    length: entries.len(),
                    expected: n,
                });
            }
        }
        for (row, entries) in rows.iter().enumerate() {
            for (column, &value) in entries.iter().enumerate().take(row) {
                let transposed = rows[column][row];
                if value != transposed {
                    return Err(Error::MetricNotSymmetric {
                        row,
                        column,
                        value: value.to_string(),
                        transposed: transposed.to_string(),
                    });
                }
            }
        }
        let diagonal = (0..n).all(|i| (0..n).all(|j| i == j || rows[i][j].is_zero()));
        let metric = Metric {
            entries: rows.iter().flatten().copied().collect(),
            dimension: n,
            diagonal,
        };
        if metric.coefficient_bound() > MAX_COEFFICIENT_BOUND {
            return Err(Error::MetricTooLarge { dimension: n });
        }
        Ok(metric)
    }

    /// B(eᵢ, eⱼ).
    pub fn inner(&self, i: usize, j: usize) -> Rational64 {
        self.entries[i * self.dimension + j]
    }

    /// The square of basis vector `i`: B(eᵢ, eᵢ).
    pub fn square(&self, i: usize) -> Rational64 {
        self.inner(i, i)
    }

    /// The signature (p, q, r): how many basis vectors of an orthogonal basis square to +1, −1 and 0 (Sylvester's
    /// inertia, by symmetric elimination in exact arithmetic).
    ///
    /// ```
    /// use ga_codegen::metric::Metric;
    /// use ga_codegen::Rational64;
    ///
    /// assert_eq!(Metric::diagonal(vec![0, 1, 1, 1])?.signature(), (3, 0, 1));
    /// // CGA on the null basis: n0·n∞ = −1 makes one vector of each sign.
    /// let entry = |x: i64| Rational64::from(x);
    /// let mut rows = vec![vec![entry(0); 5]; 5];
    /// (0..3).for_each(|i| rows[i][i] = entry(1));
    /// (rows[3][4], rows[4][3]) = (entry(-1), entry(-1));
    /// assert_eq!(Metric::from_matrix(&rows)?.signature(), (4, 1, 0));
    /// # Ok::<(), ga_codegen::Error>(())
    /// ```
    pub fn signature(&self) -> (usize, usize, usize) {
        let n = self.dimension;
        let mut m: Vec<Vec<Rational64>> = (0..n).map(|i| (0..n).map(|j| self.inner(i, j)).collect()).collect();
        let (mut positive, mut negative) = (0, 0);
        while !m.is_empty() {
            let size = m.len();
            let pivot = match (0..size).find(|&i| !m[i][i].is_zero()) {
                Some(i) => i,
                None => {
                    // A zero diagonal with a non-zero entry (i, j): eᵢ + eⱼ squares to 2B(eᵢ, eⱼ) ≠ 0.
                    let Some((i, j)) = (0..size)
                        .flat_map(|i| (0..size).map(move |j| (i, j)))
                        .find(|&(i, j)| !m[i][j].is_zero())
                    else {
                        break;
                    };
                    let row_j = m[j].clone();
                    m[i].iter_mut().zip(&row_j).for_each(|(x, y)| *x += *y);
                    for row in m.iter_mut() {
                        let add = row[j];
                        row[i] += add;
                    }
                    i
                }
            };
            let d = m[pivot][pivot];
            if d > Rational64::zero() {
                positive += 1;
            } else {
                negative += 1;
            }
            let rest: Vec<usize> = (0..size).filter(|&k| k != pivot).collect();
            m = rest
                .iter()
                .map(|&a| rest.iter().map(|&b| m[a][b] - m[a][pivot] * m[pivot][b] / d).collect())
                .collect();
        }
        (positive, negative, n - positive - negative)
    }

    /// Whether the basis is orthogonal (every off-diagonal entry is zero).
    pub fn is_diagonal(&self) -> bool {
        self.diagonal
    }

    /// For a diagonal metric: the product of the squares of the vectors in `shared` (the vectors two
    /// blades have in common), zero if any of them is null.
    pub fn shared_factor(&self, shared: BladeMask) -> Rational64 {
        debug_assert!(self.diagonal, "only an orthogonal basis has single-term products");
        // Visits only the shared vectors and flips a sign for a square of −1, without rational arithmetic: the
        // products of full multivectors in 10 dimensions call this a million times each.
        let (one, minus_one) = (Rational64::from_integer(1), Rational64::from_integer(-1));
        let mut factor = one;
        let mut rest = shared;
        while rest != 0 {
            let square = self.square(rest.trailing_zeros() as usize);
            if square == minus_one {
                factor = -factor;
            } else if square != one {
                factor *= square;
            }
            rest &= rest - 1;
        }
        factor
    }

    /// The number of basis vectors.
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// An upper bound on the numerator of any coefficient of a product of two basis blades, written
    /// over the common denominator D^n (D = lcm of the entries' denominators).
    ///
    /// By Chevalley's recursion, multiplying by eᵢ maps a unit blade to at most one wedge term plus
    /// one contraction term per other factor, so the ℓ₁ norm of eᵢX is at most cᵢ‖X‖ with
    /// cᵢ = max(|Bᵢᵢ|, 1) + Σⱼ≠ᵢ |Bᵢⱼ|; and a blade e_i ∧ A' = e_i A' − e_i⌋A' adds a term of two
    /// grades lower. For an orthogonal basis with squares ±1 or 0 the bound is 1.
    fn coefficient_bound(&self) -> f64 {
        let n = self.dimension;
        let magnitude = |x: Rational64| x.abs().to_f64().unwrap_or(f64::INFINITY);
        let (mut growth, mut off_diagonal) = (1.0f64, 0.0f64);
        for i in 0..n {
            let off: f64 = (0..n).filter(|&j| j != i).map(|j| magnitude(self.inner(i, j))).sum();
            growth = growth.max(magnitude(self.square(i)).max(1.0) + off);
            off_diagonal = off_diagonal.max(off);
        }
        let (mut previous, mut current) = (1.0f64, 1.0f64);
        for _ in 0..n {
            (previous, current) = (current, growth * current + off_diagonal * previous);
        }
        // Capped (in i128, so the lcm itself cannot overflow): past the cap the bound is rejected anyway.
        let denominator = self.entries.iter().fold(1i128, |lcm, x| {
            num_integer::lcm(lcm, i128::from(*x.denom())).min(1 << 40)
        });
        current * (denominator as f64).powi(n as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::One;

    fn rational(numerator: i64, denominator: i64) -> Rational64 {
        Rational64::new(numerator, denominator)
    }

    fn null_cga_rows() -> Vec<Vec<Rational64>> {
        let mut rows = vec![vec![Rational64::zero(); 5]; 5];
        for (i, row) in rows.iter_mut().enumerate().take(3) {
            row[i] = Rational64::one();
        }
        rows[3][4] = -Rational64::one();
        rows[4][3] = -Rational64::one();
        rows
    }

    #[test]
    fn a_general_form_keeps_its_entries() {
        let metric = Metric::from_matrix(&null_cga_rows()).unwrap();
        assert!(!metric.is_diagonal());
        assert_eq!(metric.inner(3, 4), -Rational64::one());
        assert_eq!(metric.square(3), Rational64::zero());
        assert_eq!(metric.square(0), Rational64::one());
    }

    #[test]
    fn a_diagonal_matrix_takes_the_fast_path() {
        let rows = vec![
            vec![rational(1, 2), Rational64::zero()],
            vec![Rational64::zero(), rational(-2, 1)],
        ];
        let metric = Metric::from_matrix(&rows).unwrap();
        assert!(metric.is_diagonal());
        assert_eq!(metric.shared_factor(0b11), -Rational64::one());
    }

    #[test]
    fn malformed_matrices_are_refused() {
        let mut asymmetric = null_cga_rows();
        asymmetric[4][3] = Rational64::one();
        assert!(matches!(
            Metric::from_matrix(&asymmetric),
            Err(Error::MetricNotSymmetric { row: 4, column: 3, .. })
        ));
        let mut ragged = null_cga_rows();
        ragged[2].pop();
        assert!(matches!(
            Metric::from_matrix(&ragged),
            Err(Error::MetricRowLength {
                row: 2,
                length: 4,
                expected: 5
            })
        ));
        let huge = vec![vec![Rational64::from_integer(1 << 40); 3]; 3];
        assert_eq!(Metric::from_matrix(&huge), Err(Error::MetricTooLarge { dimension: 3 }));
    }

    #[test]
    fn orthogonal_unit_metrics_have_unit_coefficients() {
        let metric = Metric::diagonal(vec![1, -1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, -1, -1]).unwrap();
        assert_eq!(metric.coefficient_bound(), 1.0);
    }
}
