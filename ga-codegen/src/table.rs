//! Table-driven lowering: the alternative to [`crate::program`] for a product too big to unroll.
//!
//! An unrolled function's source grows with its term count, and so do rustc's time and stack: the sandwich of
//! a full Cl(5,1) multivector (68 608 monomials, 4223 hoisted locals) took rustc two minutes in
//! release and overflowed its stack in debug (every `let` opens a lexical scope nested in the previous one, and
//! LLVM walks the debug-info scope chain recursively). Here a bilinear product is instead a constant table of
//! entries `(i, j, k, c)` and one loop `out[k] += c · left[i] · right[j]`; a sandwich `a x ~a` is two such
//! stages, `m = a x` over every blade the products reach, then `m ~a` (the reverse's signs folded into the
//! coefficients). The emitted table is one byte-string literal ([`EncodedStage`]): eight bytes per entry and a
//! single token, so neither the macro's token stream nor rustc handles entries one by one (as an array of
//! tuples made them do: a 10-dimensional `all` with every operation took five minutes and 12 GB to build, now
//! half a minute).
//!
//! Exactness is kept where it matters: the output blades are those of the exact symbolic expansion (a blade
//! whose coefficient cancels identically is dropped, as in unrolled code), so only the rounding of the sums
//! differs from the unrolled form.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use num_rational::Rational64;
use num_traits::{ToPrimitive, Zero};

use crate::algebra::{Algebra, SparseType};
use crate::blade::BladeMask;
use crate::expand::{Expansion, Operand, Variable};
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
    /// A bilinear operation's exact expansion (each monomial `aᵢ xⱼ` of each output blade) as one stage: its
    /// entries are the monomials the unrolled code would sum, its outputs the expansion's blades (every other
    /// blade cancels identically).
    ///
    /// ```
    /// use ga_codegen::table::Table;
    /// use ga_codegen::{expand, Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, Operation, ScalarType};
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
    /// let table = Table::bilinear(&expand::binary(&plane, Operation::Geometric, vector, vector));
    /// assert_eq!((table.entries(), table.output_blades()), (4, [0b00, 0b11].as_slice()));
    /// // (3 e1 + 4 e2)(3 e1 + 4 e2) = 25: the scalar blade (mask 0) is 25, the e12 blade cancels.
    /// let square = table.evaluate(&[3.0, 4.0], &[3.0, 4.0]);
    /// assert_eq!((square[&0b00], square[&0b11]), (25.0, 0.0));
    /// # Ok::<(), ga_codegen::Error>(())
    /// ```
    pub fn bilinear(expansion: &Expansion) -> Table {
        let mut entries: Vec<Entry> = expansion
            .outputs
            .values()
            .enumerate()
            .flat_map(|(output, polynomial)| {
                polynomial
                    .terms
                    .iter()
                    .filter_map(move |(monomial, &coefficient)| match **monomial {
                        [Variable {
                            operand: Operand::Lhs,
                            field: left,
                        }, Variable {
                            operand: Operand::Rhs,
                            field: right,
                        }] => Some(Entry {
                            left,
                            right,
                            output,
                            coefficient,
                        }),
                        _ => None,
                    })
            })
            .collect();
        entries.sort_by_key(|e| (e.output, e.left, e.right));
        Table {
            stages: vec![Stage {
                left: Source::Lhs,
                right: Source::Rhs,
                blades: expansion.blades(),
                entries,
            }],
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

    /// The same table with only the outputs `blades` (a subset of [`Self::output_blades`], in this order): the
    /// last stage's other entries dropped.
    pub fn keeping(mut self, blades: &[BladeMask]) -> Table {
        if let Some(last) = self.stages.last_mut() {
            let position: BTreeMap<BladeMask, usize> = blades.iter().enumerate().map(|(k, &b)| (b, k)).collect();
            let old_blades = std::mem::replace(&mut last.blades, blades.to_vec());
            last.entries
                .retain_mut(|entry| match position.get(&old_blades[entry.output]) {
                    Some(&k) => {
                        entry.output = k;
                        true
                    }
                    None => false,
                });
            last.entries.sort_by_key(|e| (e.output, e.left, e.right));
        }
        self
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
                let encoded = EncodedStage::new(stage);
                for [i, j, k, n] in encoded.entries() {
                    output[k] += encoded.coefficients[n].to_f64().unwrap_or(f64::NAN) * left[i] * right[j];
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

/// Up to this many distinct coefficients a stage's encoding finds each by a linear search.
const LINEAR_SEARCH: usize = 16;

/// A stage's entries as the emitted code stores them: one byte string of entries `i, j, k, n`, each index a
/// little-endian integer of `width` bytes (2, or 4 where an index reaches 2¹⁶), `n` indexing `coefficients`
/// (the stage's distinct coefficients, in order of first use).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EncodedStage {
    /// The entries, `4 · width` bytes each, in the stage's order.
    pub bytes: Vec<u8>,
    /// Bytes per index: 2 or 4.
    pub width: usize,
    /// The distinct coefficients.
    pub coefficients: Vec<Rational64>,
}

impl EncodedStage {
    /// Encodes `stage`'s entries.
    ///
    /// ```
    /// use ga_codegen::table::{EncodedStage, Entry, Source, Stage};
    /// use ga_codegen::Rational64;
    ///
    /// // out[0] += −1 · left[2] · right[1]; out[1] += ½ · left[0] · right[0].
    /// let entry = |left, right, output, c| Entry { left, right, output, coefficient: Rational64::new(c, 2) };
    /// let stage = Stage {
    ///     left: Source::Lhs,
    ///     right: Source::Rhs,
    ///     blades: vec![0b00, 0b11],
    ///     entries: vec![entry(2, 1, 0, -2), entry(0, 0, 1, 1)],
    /// };
    /// let encoded = EncodedStage::new(&stage);
    /// assert_eq!(encoded.width, 2);
    /// assert_eq!(encoded.bytes, [2, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0]);
    /// assert_eq!(encoded.coefficients, [Rational64::from_integer(-1), Rational64::new(1, 2)]);
    /// assert_eq!(encoded.entries().collect::<Vec<_>>(), [[2, 1, 0, 0], [0, 0, 1, 1]]);
    /// ```
    pub fn new(stage: &Stage) -> EncodedStage {
        // Few distinct coefficients (±1 in an orthogonal basis): a linear search, and a map once there are many.
        let mut coefficients: Vec<Rational64> = Vec::new();
        let mut indexed: HashMap<Rational64, usize> = HashMap::new();
        let mut index_of = |c: Rational64| -> usize {
            let known = if coefficients.len() <= LINEAR_SEARCH {
                coefficients.iter().position(|&known| known == c)
            } else {
                indexed.get(&c).copied()
            };
            known.unwrap_or_else(|| {
                coefficients.push(c);
                if coefficients.len() > LINEAR_SEARCH {
                    indexed.extend(
                        coefficients
                            .iter()
                            .enumerate()
                            .skip(indexed.len())
                            .map(|(n, &c)| (c, n)),
                    );
                }
                coefficients.len() - 1
            })
        };
        let indices: Vec<[usize; 4]> = stage
            .entries
            .iter()
            .map(|e| [e.left, e.right, e.output, index_of(e.coefficient)])
            .collect();
        let largest = indices.iter().flatten().copied().max().unwrap_or(0);
        let width = if largest <= usize::from(u16::MAX) { 2 } else { 4 };
        let mut bytes = Vec::with_capacity(indices.len() * 4 * width);
        for index in indices.into_iter().flatten() {
            let index = u32::try_from(index).expect("a stage's indices are below its 2³² products");
            bytes.extend_from_slice(&index.to_le_bytes()[..width]);
        }
        EncodedStage {
            bytes,
            width,
            coefficients,
        }
    }

    /// The entries `[i, j, k, n]` read back from the bytes, as the emitted loop reads them.
    pub fn entries(&self) -> impl Iterator<Item = [usize; 4]> + '_ {
        self.bytes.chunks_exact(4 * self.width).map(|entry| {
            let mut indices = entry.chunks_exact(self.width).map(|index| {
                let mut word = [0u8; 4];
                word[..self.width].copy_from_slice(index);
                u32::from_le_bytes(word) as usize
            });
            std::array::from_fn(|_| indices.next().unwrap_or(0))
        })
    }
}

/// Collects `(i, j, blade, c)` products into a stage: zeros dropped, outputs restricted to `keep` (in its order)
/// or else every blade reached, in blade order. Each operand pair `(i, j)` comes once with its product's
/// distinct blades, so no two products share `(i, j, blade)` and nothing needs merging; the pairs come in
/// `(i, j)` order, so each output's entries are already in order.
fn stage(
    left: Source,
    right: Source,
    products: impl Iterator<Item = (usize, usize, BladeMask, Rational64)>,
    keep: Option<&[BladeMask]>,
) -> Stage {
    let kept: Option<BTreeSet<BladeMask>> = keep.map(|keep| keep.iter().copied().collect());
    let mut by_blade: BTreeMap<BladeMask, Vec<(usize, usize, Rational64)>> = BTreeMap::new();
    for (i, j, blade, c) in products {
        if !c.is_zero() && kept.as_ref().is_none_or(|kept| kept.contains(&blade)) {
            by_blade.entry(blade).or_default().push((i, j, c));
        }
    }
    let blades: Vec<BladeMask> = match keep {
        Some(keep) => keep.to_vec(),
        None => by_blade.keys().copied().collect(),
    };
    let entries = blades
        .iter()
        .enumerate()
        .flat_map(|(output, blade)| {
            let products = by_blade.remove(blade).unwrap_or_default();
            products.into_iter().map(move |(left, right, coefficient)| Entry {
                left,
                right,
                output,
                coefficient,
            })
        })
        .collect();
    Stage {
        left,
        right,
        blades,
        entries,
    }
}
