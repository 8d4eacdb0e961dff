//! Table-driven lowering: the alternative to [`crate::program`] for a product too big to unroll.
//!
//! An unrolled function's source grows with its term count, and so do rustc's time and stack: the sandwich of
//! a full Cl(5,1) multivector (68 608 monomials, 4223 hoisted locals) took rustc two minutes in
//! release and overflowed its stack in debug (every `let` opens a lexical scope nested in the previous one, and
//! LLVM walks the debug-info scope chain recursively). Here a bilinear product is instead a constant table of
//! entries `(i, j, k, c)` and one loop `out[k] += c · left[i] · right[j]`; a sandwich `a x ~a` is two such
//! stages, `m = a x` over every blade the products reach, then `m ~a` (the reverse's signs folded into the
//! coefficients). The source is a few bytes per entry and compiles in time linear in it.
//!
//! Exactness is kept where it matters: the output blades are those of the exact symbolic expansion (a blade
//! whose coefficient cancels identically is dropped, as in unrolled code), so only the rounding of the sums
//! differs from the unrolled form.

use std::collections::{BTreeMap, BTreeSet};

use num_rational::Rational64;
use num_traits::{ToPrimitive, Zero};

use crate::algebra::{Algebra, SparseType};
use crate::blade::BladeMask;
use crate::operation::Operation;
use crate::product::{reverse_sign, Rules};
use crate::program::Cost;

/// Unroll at most this many monomials; a bigger expansion is lowered to tables (unless the declaration
/// chooses per operation). Unrolled code of this size builds in about a second in debug; the full Cl(5,1)
/// geometric product (4096 monomials) stays unrolled, its sandwich (68 608) does not.
pub const MAX_UNROLLED_TERMS: usize = 8192;

/// Unroll with at most this many hoisted locals (each a `let`, each a lexical scope nested in the previous
/// one): rustc 1.95 with debug info overflowed its stack between 3000 and 4000 chained `let`s.
pub const MAX_UNROLLED_LOCALS: usize = 1024;

/// Expand a sandwich exactly (to find which output blades cancel identically) only up to this many products
/// `aᵢ x_k aⱼ` (|a|²|x|; the full Cl(5,1) sandwich has 262 144); beyond, its output blades are those its two
/// products reach, and a blade that cancels identically is kept (as zero), since the exact expansion would take
/// minutes to hours (a full 10-dimensional sandwich has 2³⁰ products).
pub const MAX_EXACT_SANDWICH_PRODUCTS: usize = 1 << 22;

/// Whether the sandwich of `operand` by `versor` has too many products to expand exactly.
pub fn too_big_to_expand(versor: &SparseType, operand: &SparseType) -> bool {
    let products = versor
        .fields
        .len()
        .saturating_mul(versor.fields.len())
        .saturating_mul(operand.fields.len());
    products > MAX_EXACT_SANDWICH_PRODUCTS
}

/// Where a stage reads an operand from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The coefficients of `self`, in storage order.
    Lhs,
    /// The coefficients of the right-hand operand, in storage order.
    Rhs,
    /// The output of an earlier stage (its index).
    Stage(usize),
}

/// `output[k] += coefficient · left[i] · right[j]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    /// Index `i` into the left source.
    pub left: usize,
    /// Index `j` into the right source.
    pub right: usize,
    /// Index `k` into the stage's output.
    pub output: usize,
    /// The exact coefficient (field signs and the reverse's signs folded in).
    pub coefficient: Rational64,
}

/// One bilinear stage: a dense output over `blades`, accumulated entry by entry.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stage {
    /// The left factor.
    pub left: Source,
    /// The right factor.
    pub right: Source,
    /// The blade of each output position.
    pub blades: Vec<BladeMask>,
    /// The products to accumulate, ordered by output position.
    pub entries: Vec<Entry>,
}

/// A product lowered to tables: its stages in order; the last stage's outputs are the function's blades.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Table {
    /// The stages; each reads only the operands and earlier stages.
    pub stages: Vec<Stage>,
}

impl Table {
    /// The bilinear operation `operation` of `left` and `right`, keeping only `outputs` (the exact
    /// expansion's blades: every other blade cancels identically).
    ///
    /// ```
    /// use ga_codegen::table::Table;
    /// use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, Operation, ScalarType};
    /// use ga_codegen::TypeDeclaration;
    ///
    /// // The plane's geometric product of vectors: e1 e1 = 1, e1 e2 = e12, …: four products, one per pair.
    /// let plane = Algebra::new(&AlgebraDeclaration {
    ///     scalar: ScalarType::F64,
    ///     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
    ///     metric: None,
    ///     types: vec![TypeDeclaration { name: "Vector".into(), layout: Layout::Grades(vec![1]) }],
    ///     operations: None,
    ///     lowering: vec![],
    ///     expressions: vec![],
    /// })?;
    /// let vector = &plane.types[0];
    /// let table = Table::binary(&plane, Operation::Geometric, vector, vector, &[0b00, 0b11]);
    /// assert_eq!(table.entries(), 4);
    /// // (3 e1 + 4 e2)(3 e1 + 4 e2) = 25: the scalar blade (mask 0) is 25, the e12 blade cancels.
    /// let square = table.evaluate(&[3.0, 4.0], &[3.0, 4.0]);
    /// assert_eq!((square[&0b00], square[&0b11]), (25.0, 0.0));
    /// # Ok::<(), ga_codegen::Error>(())
    /// ```
    pub fn binary(
        algebra: &Algebra,
        operation: Operation,
        left: &SparseType,
        right: &SparseType,
        outputs: &[BladeMask],
    ) -> Table {
        let rules = Rules::new(&algebra.metric);
        let pairs = left.fields.iter().enumerate().flat_map(|(i, a)| {
            let rules = &rules;
            right.fields.iter().enumerate().flat_map(move |(j, b)| {
                let sign = Rational64::from_integer(a.sign * b.sign);
                let terms = rules.binary(operation, a.blade, b.blade).terms().to_vec();
                terms.into_iter().map(move |(blade, c)| (i, j, blade, c * sign))
            })
        });
        Table {
            stages: vec![stage(Source::Lhs, Source::Rhs, pairs, Some(outputs))],
        }
    }

    /// The sandwich `a x ~a` of `operand` (x) by `versor` (a) as two products, keeping only `outputs` of the
    /// second (for a unit versor's `transform`, the operand's grades), or every blade it reaches.
    ///
    /// ```
    /// use ga_codegen::table::{Source, Table};
    /// use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType};
    /// use ga_codegen::TypeDeclaration;
    ///
    /// // A rotor (scalar, e12) turning a vector of the plane by 90°.
    /// let plane = Algebra::new(&AlgebraDeclaration {
    ///     scalar: ScalarType::F64,
    ///     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
    ///     metric: None,
    ///     types: vec![
    ///         TypeDeclaration { name: "Rotor".into(), layout: Layout::Grades(vec![0, 2]) },
    ///         TypeDeclaration { name: "Vector".into(), layout: Layout::Grades(vec![1]) },
    ///     ],
    ///     operations: None,
    ///     lowering: vec![],
    ///     expressions: vec![],
    /// })?;
    /// let table = Table::sandwich(&plane, &plane.types[0], &plane.types[1], None);
    /// assert_eq!(table.stages[1].left, Source::Stage(0)); // (a x) ~a
    /// let half = std::f64::consts::FRAC_PI_4;
    /// let turned = table.evaluate(&[half.cos(), half.sin()], &[1.0, 0.0]);
    /// assert!((turned[&0b01] - 0.0).abs() < 1e-15 && (turned[&0b10].abs() - 1.0).abs() < 1e-15);
    /// # Ok::<(), ga_codegen::Error>(())
    /// ```
    pub fn sandwich(
        algebra: &Algebra,
        versor: &SparseType,
        operand: &SparseType,
        outputs: Option<&[BladeMask]>,
    ) -> Table {
        let rules = Rules::new(&algebra.metric);
        let first_pairs = versor.fields.iter().enumerate().flat_map(|(i, a)| {
            let rules = &rules;
            operand.fields.iter().enumerate().flat_map(move |(j, x)| {
                let sign = Rational64::from_integer(a.sign * x.sign);
                let terms = rules.geometric(a.blade, x.blade).terms().to_vec();
                terms.into_iter().map(move |(blade, c)| (i, j, blade, c * sign))
            })
        });
        let first = stage(Source::Lhs, Source::Rhs, first_pairs, None);
        let second_pairs = first.blades.iter().enumerate().flat_map(|(m, &middle)| {
            let rules = &rules;
            versor.fields.iter().enumerate().flat_map(move |(j, b)| {
                let sign = reverse_sign(b.blade) * Rational64::from_integer(b.sign);
                let terms = rules.geometric(middle, b.blade).terms().to_vec();
                terms.into_iter().map(move |(blade, c)| (m, j, blade, c * sign))
            })
        });
        let second = stage(Source::Stage(0), Source::Lhs, second_pairs, outputs);
        Table {
            stages: vec![first, second],
        }
    }

    /// The blades of the result, in output order.
    pub fn output_blades(&self) -> &[BladeMask] {
        self.stages.last().map_or(&[], |stage| stage.blades.as_slice())
    }

    /// The number of entries over all stages.
    pub fn entries(&self) -> usize {
        self.stages.iter().map(|s| s.entries.len()).sum()
    }

    /// What the emitted loops compute: two multiplies and one add per entry.
    pub fn cost(&self) -> Cost {
        let entries = self.entries();
        Cost {
            multiplies: 2 * entries,
            adds: entries,
            divisions: 0,
        }
    }

    /// Runs the tables on numeric operands (field values in storage order): the emitted loops' semantics, for
    /// testing them against the [`crate::Evaluator`] without compiling them.
    pub fn evaluate(&self, lhs: &[f64], rhs: &[f64]) -> BTreeMap<BladeMask, f64> {
        let mut results: Vec<Vec<f64>> = Vec::with_capacity(self.stages.len());
        for stage in &self.stages {
            let mut output = vec![0.0; stage.blades.len()];
            {
                let read = |source: Source| match source {
                    Source::Lhs => lhs,
                    Source::Rhs => rhs,
                    Source::Stage(s) => results[s].as_slice(),
                };
                let (left, right) = (read(stage.left), read(stage.right));
                for entry in &stage.entries {
                    output[entry.output] +=
                        entry.coefficient.to_f64().unwrap_or(f64::NAN) * left[entry.left] * right[entry.right];
                }
            }
            results.push(output);
        }
        self.output_blades()
            .iter()
            .copied()
            .zip(results.pop().unwrap_or_default())
            .collect()
    }
}

/// Collects `(i, j, blade, c)` products into a stage: equal `(i, j, blade)` merged, zeros dropped, outputs
/// restricted to `keep` (in its order) or else every blade reached, in blade order.
fn stage(
    left: Source,
    right: Source,
    products: impl Iterator<Item = (usize, usize, BladeMask, Rational64)>,
    keep: Option<&[BladeMask]>,
) -> Stage {
    let kept: Option<BTreeSet<BladeMask>> = keep.map(|keep| keep.iter().copied().collect());
    let mut merged: BTreeMap<(BladeMask, usize, usize), Rational64> = BTreeMap::new();
    for (i, j, blade, c) in products {
        if kept.as_ref().is_none_or(|kept| kept.contains(&blade)) {
            *merged.entry((blade, i, j)).or_insert_with(Rational64::zero) += c;
        }
    }
    merged.retain(|_, c| !c.is_zero());
    let blades: Vec<BladeMask> = match keep {
        Some(keep) => keep.to_vec(),
        None => {
            let mut reached: Vec<BladeMask> = merged.keys().map(|&(blade, _, _)| blade).collect();
            reached.dedup();
            reached
        }
    };
    let position: BTreeMap<BladeMask, usize> = blades.iter().enumerate().map(|(k, &b)| (b, k)).collect();
    let mut entries: Vec<Entry> = merged
        .into_iter()
        .map(|((blade, i, j), coefficient)| Entry {
            left: i,
            right: j,
            output: position[&blade],
            coefficient,
        })
        .collect();
    entries.sort_by_key(|e| (e.output, e.left, e.right));
    Stage {
        left,
        right,
        blades,
        entries,
    }
}
