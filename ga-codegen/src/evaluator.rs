//! A runtime evaluator of the same product rules on dense coefficient vectors.
//!
//! A multivector is a slice of `2ⁿ` coefficients indexed by blade bitmask (the layout of the
//! reference data). Products loop over the non-zero coefficient pairs and apply the blade rule of
//! [`crate::product`]: no table is built, so the evaluator explores big algebras in O(4ⁿ) time and
//! O(2ⁿ) memory (times the terms per blade pair on a non-orthogonal basis). It is the oracle the tests
//! compare emitted code against.

use num_rational::Rational64;
use num_traits::ToPrimitive;

use crate::blade::{grade, BladeMask};
use crate::error::EvaluatorError;
use crate::metric::Metric;
use crate::operation::Operation;
use crate::product::Rules;

/// Dense evaluation of every operation in one algebra.
#[derive(Clone, Debug)]
pub struct Evaluator {
    metric: Metric,
}

/// A rule's exact coefficient as a float (exact for the dyadic rationals of ordinary metrics).
fn coefficient(c: Rational64) -> f64 {
    c.to_f64().unwrap_or(f64::NAN)
}

impl Evaluator {
    /// An evaluator for the diagonal metric with these squares (basis vector `i` = bit `i`); refused, as
    /// [`Metric::diagonal`] refuses them, for more than 32 vectors or squares too large for exact products.
    ///
    /// ```
    /// use ga_codegen::{Evaluator, Operation};
    ///
    /// // Cl(3,0): 2³ = 8 coefficients, indexed by blade mask (e12 = 0b011 = 3).
    /// let evaluator = Evaluator::new(&[1, 1, 1])?;
    /// assert_eq!(evaluator.blade_count(), 8);
    /// let e12 = [0., 0., 0., 1., 0., 0., 0., 0.];
    /// // A unit bivector squares to −1.
    /// let square = evaluator.binary(Operation::Geometric, &e12, &e12)?;
    /// assert_eq!(square, [-1., 0., 0., 0., 0., 0., 0., 0.]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(squares: &[i64]) -> Result<Self, crate::Error> {
        Ok(Evaluator {
            metric: Metric::diagonal(squares.to_vec())?,
        })
    }

    /// An evaluator for any metric, e.g. a general bilinear form from [`Metric::from_matrix`].
    ///
    /// ```
    /// use ga_codegen::metric::Metric;
    /// use ga_codegen::{Evaluator, Operation, Rational64};
    ///
    /// // The null basis n0 (bit 0), ninf (bit 1) with n0 · ninf = −1.
    /// let (zero, one) = (Rational64::from_integer(0), Rational64::from_integer(1));
    /// let evaluator = Evaluator::with_metric(Metric::from_matrix(&[vec![zero, -one], vec![-one, zero]])?);
    /// let (n0, ninf) = ([0., 1., 0., 0.], [0., 0., 1., 0.]);
    /// // n0 ninf = n0 · ninf + n0 ∧ ninf = −1 + n0∧ninf, and n0 is null.
    /// assert_eq!(evaluator.binary(Operation::Geometric, &n0, &ninf)?, [-1., 0., 0., 1.]);
    /// assert_eq!(evaluator.binary(Operation::Geometric, &n0, &n0)?, [0.; 4]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_metric(metric: Metric) -> Self {
        Evaluator { metric }
    }

    /// From a validated algebra: the evaluator uses the algebra's metric.
    ///
    /// ```
    /// use ga_codegen::{Algebra, Evaluator};
    /// # use ga_codegen::{AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
    /// # let basis = [("e0", 0), ("e1", 1), ("e2", 1), ("e3", 1)]
    /// #     .map(|(name, square)| BasisVectorDeclaration { name: name.into(), square });
    /// # let declaration = AlgebraDeclaration {
    /// #     scalar: ScalarType::F64,
    /// #     basis: basis.to_vec(),
    /// #     metric: None,
    /// #     types: vec![TypeDeclaration { name: "Motor".into(), layout: Layout::Grades(vec![0, 2, 4]) }],
    /// #     operations: None,
    /// #     lowering: vec![],
    /// #     expressions: vec![],
    /// # };
    /// // `declaration`: 3D PGA, e0² = 0 and e1² = e2² = e3² = 1.
    /// let algebra = Algebra::new(&declaration)?;
    /// let evaluator = Evaluator::of(&algebra);
    /// assert_eq!(evaluator.blade_count(), 16);
    /// let blade = |mask: usize| (0..16).map(|i| if i == mask { 1.0 } else { 0.0 }).collect::<Vec<f64>>();
    /// assert_eq!(evaluator.norm_squared(&blade(0b0001))?, 0.0); // e0 is null
    /// assert_eq!(evaluator.norm_squared(&blade(0b0010))?, 1.0); // e1 is not
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of(algebra: &crate::Algebra) -> Self {
        Evaluator {
            metric: algebra.metric.clone(),
        }
    }

    /// The number of coefficients of a dense multivector: 2ⁿ.
    pub fn blade_count(&self) -> usize {
        1 << self.metric.dimension()
    }

    fn rules(&self) -> Rules<'_> {
        Rules::new(&self.metric)
    }

    /// `Ok` if `a` has 2ⁿ coefficients.
    fn check(&self, operand: &'static str, a: &[f64]) -> Result<(), EvaluatorError> {
        if a.len() == self.blade_count() {
            Ok(())
        } else {
            Err(EvaluatorError::DenseLength {
                operand,
                expected: self.blade_count(),
                got: a.len(),
            })
        }
    }

    /// A binary operation, including the sandwich `a b ~a`.
    ///
    /// # Errors
    /// [`EvaluatorError::DenseLength`] if a slice does not have 2ⁿ coefficients.
    pub fn binary(&self, operation: Operation, a: &[f64], b: &[f64]) -> Result<Vec<f64>, EvaluatorError> {
        self.check("left operand", a)?;
        self.check("right operand", b)?;
        Ok(self.binary_unchecked(operation, a, b))
    }

    fn binary_unchecked(&self, operation: Operation, a: &[f64], b: &[f64]) -> Vec<f64> {
        if operation == Operation::Sandwich {
            let ab = self.binary_unchecked(Operation::Geometric, a, b);
            return self.binary_unchecked(Operation::Geometric, &ab, &self.unary_unchecked(Operation::Reverse, a));
        }
        let rules = self.rules();
        let mut out = vec![0.0; a.len()];
        for (i, &x) in a.iter().enumerate().filter(|(_, x)| **x != 0.0) {
            for (j, &y) in b.iter().enumerate().filter(|(_, y)| **y != 0.0) {
                for &(blade, c) in rules.binary(operation, i as BladeMask, j as BladeMask).terms() {
                    out[blade as usize] += coefficient(c) * x * y;
                }
            }
        }
        out
    }

    /// A unary blade map (reverse, involute, conjugate, complements, polarity). Operations that are
    /// not blade maps, and polarity on a degenerate metric, give zero.
    ///
    /// # Errors
    /// [`EvaluatorError::DenseLength`] if the slice does not have 2ⁿ coefficients.
    pub fn unary(&self, operation: Operation, a: &[f64]) -> Result<Vec<f64>, EvaluatorError> {
        self.check("operand", a)?;
        Ok(self.unary_unchecked(operation, a))
    }

    fn unary_unchecked(&self, operation: Operation, a: &[f64]) -> Vec<f64> {
        let rules = self.rules();
        let mut out = vec![0.0; a.len()];
        for (i, &x) in a.iter().enumerate() {
            for &(blade, c) in rules.unary(operation, i as BladeMask).terms() {
                out[blade as usize] += coefficient(c) * x;
            }
        }
        out
    }

    /// The grade-`k` part (of a slice of any length: blade `i` is coefficient `i`).
    pub fn grade_part(&self, a: &[f64], k: u32) -> Vec<f64> {
        a.iter()
            .enumerate()
            .map(|(i, &x)| if grade(i as BladeMask) == k { x } else { 0.0 })
            .collect()
    }

    /// ⟨a ~a⟩₀.
    ///
    /// # Errors
    /// [`EvaluatorError::DenseLength`] if the slice does not have 2ⁿ coefficients.
    pub fn norm_squared(&self, a: &[f64]) -> Result<f64, EvaluatorError> {
        self.check("operand", a)?;
        Ok(self.binary_unchecked(Operation::Geometric, a, &self.unary_unchecked(Operation::Reverse, a))[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrong_lengths_are_errors_naming_the_operand() {
        let evaluator = Evaluator::new(&[1, 1]).unwrap();
        let (good, short) = ([1.0, 2.0, 3.0, 4.0], [1.0, 2.0, 3.0]);
        assert_eq!(
            evaluator.binary(Operation::Geometric, &good, &short),
            Err(EvaluatorError::DenseLength {
                operand: "right operand",
                expected: 4,
                got: 3
            })
        );
        let error = evaluator.binary(Operation::Sandwich, &short, &good).unwrap_err();
        assert_eq!(
            error.to_string(),
            "the left operand has 3 coefficients, but a dense multivector of this algebra has 2^n = 4, one per blade"
        );
        assert_eq!(
            evaluator.unary(Operation::Reverse, &[1.0; 8]),
            Err(EvaluatorError::DenseLength {
                operand: "operand",
                expected: 4,
                got: 8
            })
        );
        assert!(evaluator.norm_squared(&[]).is_err());
        // e1 e2 e1 = −e2 e1 e1 = −e2.
        assert_eq!(
            evaluator.binary(Operation::Sandwich, &[0.0, 1.0, 0.0, 0.0], &[0.0, 0.0, 1.0, 0.0]),
            Ok(vec![0.0, 0.0, -1.0, 0.0])
        );
        assert_eq!(evaluator.norm_squared(&good), Ok(30.0));
    }
}
