//! Symbolic expansion: an operation on sparse types becomes, per output blade, a polynomial in the
//! operands' fields with exact rational coefficients. Terms that cancel vanish, so the set of output
//! blades is exactly the set whose coefficient is not identically zero.

use std::collections::btree_map::Entry;
use std::collections::BTreeMap;

use num_rational::Rational64;
use num_traits::{One, Zero};

use crate::algebra::{Algebra, SparseType};
use crate::blade::{grade, BladeMask};
use crate::operation::Operation;
use crate::product::{reverse_sign, Rules};

/// Which operand a variable belongs to: `self` or the right-hand side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Operand {
    /// The left operand, `self` (the only operand of a unary operation).
    Lhs,
    /// The right-hand operand of a binary operation.
    Rhs,
}

/// One input coefficient: field number `field` of an operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Variable {
    /// Which operand the coefficient belongs to.
    pub operand: Operand,
    /// Index of the field in that operand's type.
    pub field: usize,
}

/// The highest degree of any expansion: the sandwich is cubic.
const MAX_DEGREE: usize = 3;

/// A product of at most `MAX_DEGREE` (3) variables, sorted (so `a₁a₂` and `a₂a₁` are the same
/// monomial). Stored inline, since a big expansion builds millions of them, and ordered by a packed
/// key (degree, then the factors lexicographically) for fast map lookups; it dereferences to its
/// factors.
#[derive(Clone, Copy, Debug)]
pub struct Monomial {
    key: u128,
    degree: u8,
    factors: [Variable; MAX_DEGREE],
}

impl Monomial {
    /// The sorted product of `factors`.
    ///
    /// # Panics
    /// If there are more than three factors: every expansion the compiler builds is at most cubic.
    ///
    /// ```
    /// use ga_codegen::expand::{Monomial, Operand, Variable};
    ///
    /// let (a0, a1) = (Variable { operand: Operand::Lhs, field: 0 }, Variable { operand: Operand::Lhs, field: 1 });
    /// let x0 = Variable { operand: Operand::Rhs, field: 0 };
    /// // The factors are sorted (left operand first), so the order they are given in does not matter.
    /// let monomial = Monomial::new(&[x0, a1, a0]);
    /// assert_eq!(monomial, Monomial::new(&[a0, a1, x0]));
    /// assert_eq!(&*monomial, [a0, a1, x0]);
    /// ```
    pub fn new(factors: &[Variable]) -> Self {
        assert!(factors.len() <= MAX_DEGREE, "expansions are at most cubic");
        let filler = Variable {
            operand: Operand::Lhs,
            field: 0,
        };
        let mut sorted = [filler; MAX_DEGREE];
        sorted[..factors.len()].copy_from_slice(factors);
        sorted[..factors.len()].sort_unstable();
        // 32 bits per factor: the operand, then the field (a type has far fewer than 2³¹ fields).
        let packed = |v: &Variable| u128::from(v.operand == Operand::Rhs) << 31 | v.field as u128;
        let key = sorted[..factors.len()]
            .iter()
            .fold(factors.len() as u128, |key, v| key << 32 | packed(v))
            << (32 * (MAX_DEGREE - factors.len()));
        Monomial {
            key,
            degree: factors.len() as u8,
            factors: sorted,
        }
    }
}

impl PartialEq for Monomial {
    fn eq(&self, other: &Self) -> bool {
        self.key == other.key
    }
}

impl Eq for Monomial {}

impl PartialOrd for Monomial {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Monomial {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.key.cmp(&other.key)
    }
}

impl std::ops::Deref for Monomial {
    type Target = [Variable];

    fn deref(&self) -> &[Variable] {
        &self.factors[..usize::from(self.degree)]
    }
}

/// A polynomial with exact coefficients; a zero coefficient is never stored.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Polynomial {
    /// Each monomial with its non-zero coefficient.
    pub terms: BTreeMap<Monomial, Rational64>,
}

impl Polynomial {
    /// Adds `coefficient · Π factors`.
    pub fn add_term(&mut self, factors: &[Variable], coefficient: Rational64) {
        match self.terms.entry(Monomial::new(factors)) {
            Entry::Occupied(mut existing) => {
                *existing.get_mut() += coefficient;
                if existing.get().is_zero() {
                    existing.remove(); // the terms cancel
                }
            }
            Entry::Vacant(slot) => {
                if !coefficient.is_zero() {
                    slot.insert(coefficient);
                }
            }
        }
    }

    /// Whether the polynomial has no terms (is identically zero).
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The total degree (all monomials of one expansion share it).
    pub fn degree(&self) -> usize {
        self.terms.keys().map(|monomial| monomial.len()).max().unwrap_or(0)
    }
}

/// The expansion of one operation: the polynomial of every output blade that is not identically zero.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Expansion {
    /// Each output blade with its (non-zero) polynomial in the input coefficients.
    pub outputs: BTreeMap<BladeMask, Polynomial>,
}

impl Expansion {
    /// Sums `coefficient · monomial` into each blade's polynomial: equal monomials of a blade merged, zero sums
    /// dropped (so a blade that cancels identically is absent), each polynomial built from its sorted terms in
    /// one pass, where inserting a million products one by one was most of a big product's expansion. A binary
    /// product's terms arrive sorted per blade, so only the sandwich's need sorting.
    fn from_terms(terms: Vec<(BladeMask, Monomial, Rational64)>) -> Expansion {
        let mut by_blade: BTreeMap<BladeMask, Vec<(Monomial, Rational64)>> = BTreeMap::new();
        for (blade, monomial, coefficient) in terms {
            by_blade.entry(blade).or_default().push((monomial, coefficient));
        }
        let outputs = by_blade
            .into_iter()
            .filter_map(|(blade, mut terms)| {
                if !terms.is_sorted_by(|a, b| a.0 <= b.0) {
                    terms.sort_unstable_by_key(|term| term.0);
                }
                let mut merged: Vec<(Monomial, Rational64)> = Vec::with_capacity(terms.len());
                for (monomial, coefficient) in terms {
                    match merged.last_mut() {
                        Some(last) if last.0 == monomial => last.1 += coefficient,
                        _ => merged.push((monomial, coefficient)),
                    }
                }
                merged.retain(|term| !term.1.is_zero());
                (!merged.is_empty()).then(|| {
                    let terms = merged.into_iter().collect();
                    (blade, Polynomial { terms })
                })
            })
            .collect();
        Expansion { outputs }
    }

    /// The output blades, in canonical bitmask order.
    pub fn blades(&self) -> Vec<BladeMask> {
        self.outputs.keys().copied().collect()
    }

    /// The number of monomials over all outputs.
    pub fn term_count(&self) -> usize {
        self.outputs.values().map(|p| p.terms.len()).sum()
    }
}

fn lhs(field: usize) -> Variable {
    Variable {
        operand: Operand::Lhs,
        field,
    }
}

fn rhs(field: usize) -> Variable {
    Variable {
        operand: Operand::Rhs,
        field,
    }
}

/// Expands a blade-pair operation (every binary operation but the sandwich and transform) on two
/// types.
///
/// ```
/// use ga_codegen::{expand, Operation};
/// # use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
/// # use ga_codegen::expand::{Monomial, Operand, Variable};
/// # use ga_codegen::Rational64;
/// # let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// # let algebra = Algebra::new(&AlgebraDeclaration {
/// #     scalar: ScalarType::F64,
/// #     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
/// #     metric: None,
/// #     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
/// #     operations: None,
/// #     lowering: vec![],
/// #     expressions: vec![],
/// # })?;
/// # let a = |field| Variable { operand: Operand::Lhs, field };
/// # let x = |field| Variable { operand: Operand::Rhs, field };
/// // The plane (e1² = e2² = 1) with Vector = (e1, e2) and Rotor = (scalar, e12).
/// // `a(i)` is field i of the left operand, `x(i)` field i of the right one.
/// let (vector, rotor) = (algebra.type_named("Vector").unwrap(), algebra.type_named("Rotor").unwrap());
/// // The product of two vectors: a scalar a0 x0 + a1 x1 and a bivector (a0 x1 − a1 x0) e12.
/// let product = expand::binary(&algebra, Operation::Geometric, vector, vector);
/// assert_eq!(product.blades(), [0b00, 0b11]);
/// assert_eq!(product.term_count(), 4);
/// assert_eq!(product.outputs[&0b11].terms[&Monomial::new(&[a(1), x(0)])], Rational64::from_integer(-1));
/// // In the plane a rotor times a vector is a vector.
/// assert_eq!(expand::binary(&algebra, Operation::Geometric, rotor, vector).blades(), [0b01, 0b10]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn binary(algebra: &Algebra, operation: Operation, left: &SparseType, right: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut terms = Vec::new();
    for (i, a) in left.fields.iter().enumerate() {
        for (j, b) in right.fields.iter().enumerate() {
            let signs = Rational64::from_integer(a.sign * b.sign);
            for &(blade, c) in rules.binary(operation, a.blade, b.blade).terms() {
                terms.push((blade, Monomial::new(&[lhs(i), rhs(j)]), c * signs));
            }
        }
    }
    Expansion::from_terms(terms)
}

/// Expands the sandwich `a x ~a` as one cubic polynomial (`a` = `versor`, `x` = `operand`): the
/// symmetric terms `aᵢ x aⱼ` and `aⱼ x aᵢ` merge into one monomial, which is why the fused form
/// costs less than two products.
///
/// ```
/// use ga_codegen::expand;
/// # use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
/// # use ga_codegen::expand::{Monomial, Operand, Variable};
/// # use ga_codegen::Rational64;
/// # let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// # let algebra = Algebra::new(&AlgebraDeclaration {
/// #     scalar: ScalarType::F64,
/// #     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
/// #     metric: None,
/// #     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
/// #     operations: None,
/// #     lowering: vec![],
/// #     expressions: vec![],
/// # })?;
/// # let a = |field| Variable { operand: Operand::Lhs, field };
/// # let x = |field| Variable { operand: Operand::Rhs, field };
/// // The plane (e1² = e2² = 1) with Vector = (e1, e2) and Rotor = (scalar, e12).
/// // `a(i)` is field i of the left operand, `x(i)` field i of the right one.
/// let (vector, rotor) = (algebra.type_named("Vector").unwrap(), algebra.type_named("Rotor").unwrap());
/// // R x ~R with R = s + b e12 is a vector again: its e1 is (s² − b²) x1 + 2 s b x2.
/// let rotated = expand::sandwich(&algebra, rotor, vector);
/// assert_eq!(rotated.blades(), [0b01, 0b10]);
/// assert_eq!(rotated.term_count(), 6); // s x b and b x s merged into one monomial
/// assert_eq!(rotated.outputs[&0b01].terms[&Monomial::new(&[a(0), a(1), x(1)])], Rational64::from_integer(2));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn sandwich(algebra: &Algebra, versor: &SparseType, operand: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut terms = Vec::new();
    for (i, a) in versor.fields.iter().enumerate() {
        for (k, x) in operand.fields.iter().enumerate() {
            let ax = rules.geometric(a.blade, x.blade);
            for &(middle, c1) in ax.terms() {
                for (j, b) in versor.fields.iter().enumerate() {
                    let signs = reverse_sign(b.blade) * Rational64::from_integer(a.sign * x.sign * b.sign);
                    for &(blade, c2) in rules.geometric(middle, b.blade).terms() {
                        terms.push((blade, Monomial::new(&[lhs(i), rhs(k), lhs(j)]), c1 * c2 * signs));
                    }
                }
            }
        }
    }
    Expansion::from_terms(terms)
}

/// Which side of `x` the commutator form of the sandwich puts the versor's norm on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// `a x ~a = (a ~a) x + a (x ~a − ~a x)`.
    Left,
    /// `a x ~a = x (a ~a) + (a x − x a) ~a`.
    Right,
}

/// Whether the versor is known to be unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Norm {
    /// Any versor: `a ~a` is expanded symbolically.
    General,
    /// `a ~a = 1`: the norm term is `x` itself.
    Unit,
}

/// The sandwich in commutator form: `N x + a C` (or `x N + C ~a`), with `N = a ~a` (1 for a unit
/// versor) and the commutator `C`. Every part of the versor that commutes with `x` (its scalar, at
/// least) cancels from `C` symbolically, and `C`'s few blades are shared by every output.
#[derive(Clone, Debug, Default)]
pub struct CommutatorForm {
    /// `N = a ~a` in the versor's fields (empty for a unit versor).
    pub norm: Expansion,
    /// `N x` (or `x N`): left-hand variable `k` is the `k`-th blade of `norm`.
    pub norm_product: Expansion,
    /// For a unit versor, `x` itself: `coefficient · variable` added to a blade.
    pub passthrough: Vec<(BladeMask, Variable, Rational64)>,
    /// `C` in the versor (left-hand) and operand (right-hand) fields.
    pub commutator: Expansion,
    /// `a C` (or `C ~a`): right-hand variable `k` is the `k`-th blade of `commutator`.
    pub product: Expansion,
    /// For a unit versor, the blades of `a C` (or `C ~a`) outside `outputs`: `x + a C` is the sandwich,
    /// which keeps `x`'s grades, so these bilinear forms vanish whenever `a ~a = 1` — relations the
    /// lowering may use (see [`crate::program::lower_commutator_form`]). Empty for any versor.
    pub vanishing: Expansion,
}

/// Expands the sandwich of `operand` by `versor` in commutator form, keeping the `outputs` blades.
pub fn commutator_form(
    algebra: &Algebra,
    versor: &SparseType,
    operand: &SparseType,
    side: Side,
    norm: Norm,
    outputs: &[BladeMask],
) -> CommutatorForm {
    let rules = Rules::new(&algebra.metric);
    let mut form = CommutatorForm::default();
    let mut commutator = Vec::new();
    // C = x ~a − ~a x (left) or a x − x a (right), term by term.
    for (i, a) in versor.fields.iter().enumerate() {
        let a_sign = Rational64::from_integer(a.sign);
        let reversed = match side {
            Side::Left => reverse_sign(a.blade),
            Side::Right => Rational64::one(),
        };
        for (k, x) in operand.fields.iter().enumerate() {
            let signs = reversed * a_sign * Rational64::from_integer(x.sign);
            let (first, second) = match side {
                Side::Left => (rules.geometric(x.blade, a.blade), rules.geometric(a.blade, x.blade)),
                Side::Right => (rules.geometric(a.blade, x.blade), rules.geometric(x.blade, a.blade)),
            };
            for &(blade, c) in first.terms() {
                commutator.push((blade, Monomial::new(&[lhs(i), rhs(k)]), c * signs));
            }
            for &(blade, c) in second.terms() {
                commutator.push((blade, Monomial::new(&[lhs(i), rhs(k)]), -c * signs));
            }
        }
    }
    form.commutator = Expansion::from_terms(commutator);
    let (mut product_terms, mut vanishing) = (Vec::new(), Vec::new());
    for (k, &c_blade) in form.commutator.outputs.keys().enumerate() {
        for (i, a) in versor.fields.iter().enumerate() {
            let (product, signs) = match side {
                Side::Left => (rules.geometric(a.blade, c_blade), Rational64::from_integer(a.sign)),
                Side::Right => (
                    rules.geometric(c_blade, a.blade),
                    reverse_sign(a.blade) * Rational64::from_integer(a.sign),
                ),
            };
            for &(blade, c) in product.terms() {
                if outputs.contains(&blade) {
                    product_terms.push((blade, Monomial::new(&[lhs(i), rhs(k)]), c * signs));
                } else if norm == Norm::Unit {
                    vanishing.push((blade, Monomial::new(&[lhs(i), rhs(k)]), c * signs));
                }
            }
        }
    }
    form.product = Expansion::from_terms(product_terms);
    form.vanishing = Expansion::from_terms(vanishing);
    match norm {
        Norm::Unit => {
            for (k, x) in operand.fields.iter().enumerate() {
                if outputs.contains(&x.blade) {
                    form.passthrough
                        .push((x.blade, rhs(k), Rational64::from_integer(x.sign)));
                }
            }
        }
        Norm::General => {
            form.norm = times_own_reverse(algebra, versor);
            let mut norm_product = Vec::new();
            for (k, &n_blade) in form.norm.outputs.keys().enumerate() {
                for (j, x) in operand.fields.iter().enumerate() {
                    let product = match side {
                        Side::Left => rules.geometric(n_blade, x.blade),
                        Side::Right => rules.geometric(x.blade, n_blade),
                    };
                    for &(blade, c) in product.terms() {
                        if outputs.contains(&blade) {
                            let sign = Rational64::from_integer(x.sign);
                            norm_product.push((blade, Monomial::new(&[lhs(k), rhs(j)]), c * sign));
                        }
                    }
                }
            }
            form.norm_product = Expansion::from_terms(norm_product);
        }
    }
    form
}

/// Expands a unary blade map (reverse, involutions, complements, polarity).
///
/// ```
/// use ga_codegen::{expand, Operation};
/// # use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
/// # use ga_codegen::expand::{Monomial, Operand, Variable};
/// # use ga_codegen::Rational64;
/// # let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// # let algebra = Algebra::new(&AlgebraDeclaration {
/// #     scalar: ScalarType::F64,
/// #     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
/// #     metric: None,
/// #     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
/// #     operations: None,
/// #     lowering: vec![],
/// #     expressions: vec![],
/// # })?;
/// # let a = |field| Variable { operand: Operand::Lhs, field };
/// // The plane (e1² = e2² = 1) with Vector = (e1, e2) and Rotor = (scalar, e12).
/// // `a(i)` is field i of the (left) operand.
/// let (vector, rotor) = (algebra.type_named("Vector").unwrap(), algebra.type_named("Rotor").unwrap());
/// // The reverse of s + b e12 is s − b e12.
/// let reverse = expand::unary(&algebra, Operation::Reverse, rotor);
/// assert_eq!(reverse.outputs[&0b00].terms[&Monomial::new(&[a(0)])], Rational64::from_integer(1));
/// assert_eq!(reverse.outputs[&0b11].terms[&Monomial::new(&[a(1)])], Rational64::from_integer(-1));
/// // A vector's reverse is itself.
/// assert_eq!(expand::unary(&algebra, Operation::Reverse, vector).blades(), [0b01, 0b10]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn unary(algebra: &Algebra, operation: Operation, ty: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut terms = Vec::new();
    for (i, a) in ty.fields.iter().enumerate() {
        for &(blade, c) in rules.unary(operation, a.blade).terms() {
            terms.push((blade, Monomial::new(&[lhs(i)]), c * Rational64::from_integer(a.sign)));
        }
    }
    Expansion::from_terms(terms)
}

/// The grade-`k` part of a type.
///
/// ```
/// use ga_codegen::expand;
/// # use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
/// # let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// # let algebra = Algebra::new(&AlgebraDeclaration {
/// #     scalar: ScalarType::F64,
/// #     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
/// #     metric: None,
/// #     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
/// #     operations: None,
/// #     lowering: vec![],
/// #     expressions: vec![],
/// # })?;
/// // The plane (e1² = e2² = 1) with Vector = (e1, e2) and Rotor = (scalar, e12).
/// let (vector, rotor) = (algebra.type_named("Vector").unwrap(), algebra.type_named("Rotor").unwrap());
/// assert_eq!(expand::grade_part(rotor, 2).blades(), [0b11]);
/// assert!(expand::grade_part(vector, 2).outputs.is_empty()); // a vector has no bivector part
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn grade_part(ty: &SparseType, k: u32) -> Expansion {
    let mut terms = Vec::new();
    for (i, a) in ty.fields.iter().enumerate().filter(|(_, a)| grade(a.blade) == k) {
        terms.push((a.blade, Monomial::new(&[lhs(i)]), Rational64::from(a.sign)));
    }
    Expansion::from_terms(terms)
}

/// `a ~a` with both factors taken from `self` (so symmetric terms merge). Its scalar part is the
/// squared norm; where it has nothing else, `~a / (a ~a)` is the inverse.
///
/// ```
/// use ga_codegen::expand;
/// # use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
/// # use ga_codegen::expand::{Monomial, Operand, Variable};
/// # use ga_codegen::Rational64;
/// # let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// # let algebra = Algebra::new(&AlgebraDeclaration {
/// #     scalar: ScalarType::F64,
/// #     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
/// #     metric: None,
/// #     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
/// #     operations: None,
/// #     lowering: vec![],
/// #     expressions: vec![],
/// # })?;
/// # let a = |field| Variable { operand: Operand::Lhs, field };
/// // The plane (e1² = e2² = 1) with Vector = (e1, e2) and Rotor = (scalar, e12).
/// // `a(i)` is field i of the (left) operand.
/// let (vector, rotor) = (algebra.type_named("Vector").unwrap(), algebra.type_named("Rotor").unwrap());
/// // R ~R = s² + b²: the bivector terms s b e12 − b s e12 cancel, so a rotor has an inverse.
/// let norm = expand::times_own_reverse(&algebra, rotor);
/// assert_eq!(norm.blades(), [0b00]);
/// assert_eq!(norm.term_count(), 2);
/// assert_eq!(norm.outputs[&0b00].terms[&Monomial::new(&[a(1), a(1)])], Rational64::from_integer(1));
/// // A vector times itself is a scalar too: x ~x = x1² + x2².
/// assert_eq!(expand::times_own_reverse(&algebra, vector).blades(), [0b00]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn times_own_reverse(algebra: &Algebra, ty: &SparseType) -> Expansion {
    times_own_reverse_where(algebra, ty, |_| true)
}

/// The scalar part of [`times_own_reverse`] alone, `⟨a ~a⟩₀` (the squared norm): only the products that reach
/// the scalar are expanded, where a full multivector in 10 dimensions has a million.
pub fn norm_squared(algebra: &Algebra, ty: &SparseType) -> Expansion {
    times_own_reverse_where(algebra, ty, |blade| blade == 0)
}

fn times_own_reverse_where(algebra: &Algebra, ty: &SparseType, keep: impl Fn(BladeMask) -> bool) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut terms = Vec::new();
    for (i, a) in ty.fields.iter().enumerate() {
        for (j, b) in ty.fields.iter().enumerate() {
            let signs = reverse_sign(b.blade) * Rational64::from_integer(a.sign * b.sign);
            for &(blade, c) in rules.geometric(a.blade, b.blade).terms() {
                if keep(blade) {
                    terms.push((blade, Monomial::new(&[lhs(i), lhs(j)]), c * signs));
                }
            }
        }
    }
    Expansion::from_terms(terms)
}

/// The sum or difference of two types, blade by blade.
///
/// ```
/// use ga_codegen::expand;
/// # use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, Layout, ScalarType, TypeDeclaration};
/// # use ga_codegen::expand::{Monomial, Operand, Variable};
/// # use ga_codegen::Rational64;
/// # let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
/// # let algebra = Algebra::new(&AlgebraDeclaration {
/// #     scalar: ScalarType::F64,
/// #     basis: ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 }).to_vec(),
/// #     metric: None,
/// #     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
/// #     operations: None,
/// #     lowering: vec![],
/// #     expressions: vec![],
/// # })?;
/// # let x = |field| Variable { operand: Operand::Rhs, field };
/// // The plane (e1² = e2² = 1) with Vector = (e1, e2) and Rotor = (scalar, e12).
/// // `x(i)` is field i of the right operand.
/// let (vector, rotor) = (algebra.type_named("Vector").unwrap(), algebra.type_named("Rotor").unwrap());
/// // Vector − Rotor has every blade of the plane; its e12 coefficient is −x(1), minus the rotor's e12.
/// let difference = expand::sum(vector, rotor, true);
/// assert_eq!(difference.blades(), [0b00, 0b01, 0b10, 0b11]);
/// assert_eq!(difference.outputs[&0b11].terms[&Monomial::new(&[x(1)])], Rational64::from_integer(-1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn sum(left: &SparseType, right: &SparseType, subtract: bool) -> Expansion {
    let mut terms = Vec::new();
    for (i, a) in left.fields.iter().enumerate() {
        terms.push((a.blade, Monomial::new(&[lhs(i)]), Rational64::from(a.sign)));
    }
    let sign = if subtract { -1 } else { 1 };
    for (j, b) in right.fields.iter().enumerate() {
        terms.push((b.blade, Monomial::new(&[rhs(j)]), Rational64::from(sign * b.sign)));
    }
    Expansion::from_terms(terms)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn monomials_are_sorted_products_ordered_by_degree_then_factors() {
        let (a0, a1, x0) = (lhs(0), lhs(1), rhs(0));
        assert_eq!(Monomial::new(&[x0, a1, a0]), Monomial::new(&[a0, a1, x0]));
        assert_eq!(&*Monomial::new(&[x0, a1, a0]), &[a0, a1, x0]);
        assert!(Monomial::new(&[a0, x0]) < Monomial::new(&[a1, x0]));
        assert!(Monomial::new(&[a1, x0]) < Monomial::new(&[x0, x0]));
        assert!(Monomial::new(&[x0]) < Monomial::new(&[a0, a0]));
        let big = Variable {
            operand: Operand::Lhs,
            field: 1 << 20,
        };
        assert!(Monomial::new(&[a0, big]) > Monomial::new(&[a0, a1]));
        assert!(Monomial::new(&[a0, big]) < Monomial::new(&[a0, x0]));
    }

    #[test]
    fn cancelling_terms_vanish() {
        let mut polynomial = Polynomial::default();
        polynomial.add_term(&[lhs(0), rhs(1)], Rational64::from(2));
        polynomial.add_term(&[rhs(1), lhs(0)], Rational64::from(-2));
        assert!(polynomial.is_zero());
    }
}
