//! Product rules on pairs of basis blades, and unary maps on single blades.
//!
//! Every rule is computed per blade pair on demand — there is no 2ⁿ×2ⁿ table — so algebras of 15 or
//! more dimensions cost nothing until a declared type uses their blades. Conventions are those of the
//! reference data (clifford 1.5.1; see `tests/data/refdata`):
//!
//! | operation | rule for homogeneous Aᵣ, Bₛ |
//! |---|---|
//! | geometric | AB |
//! | outer | ⟨AB⟩ᵣ₊ₛ |
//! | left contraction | ⟨AB⟩ₛ₋ᵣ, 0 if s < r |
//! | right contraction | ⟨AB⟩ᵣ₋ₛ, 0 if r < s |
//! | scalar product | ⟨AB⟩₀ |
//! | Hestenes inner | ⟨AB⟩\|ᵣ₋ₛ\|, 0 if r = 0 or s = 0 |
//! | fat dot | ⟨AB⟩\|ᵣ₋ₛ\| |
//! | regressive | LC(RC(A) ∧ RC(B)), metric-free |
//! | commutator | (AB − BA)/2 |
//!
//! ## Non-orthogonal bases
//!
//! With a general bilinear form the basis blades are outer products `e_{i₁} ∧ … ∧ e_{iₖ}` (still
//! homogeneous, so every grade selection above keeps its meaning), and a product of two blades is a
//! sum of several blades, computed exactly by Chevalley's recursion: `eᵢB = eᵢ ∧ B + eᵢ ⌋ B` with
//! `eᵢ ⌋ (e_{b₁} ∧ … ∧ e_{bₖ}) = Σₚ (−1)ᵖ B(eᵢ, e_{bₚ}) (… without e_{bₚ} …)`, and
//! `(eᵢ ∧ A')X = eᵢ(A'X) − (eᵢ ⌋ A')X`. On an orthogonal basis this reduces to the single signed blade
//! `a XOR b` — the fast path every diagonal metric takes.
//!
//! The complements (and so the regressive product) stay metric-free: they are defined on the basis
//! blades, relative to the basis pseudoscalar `I = e₁ ∧ … ∧ eₙ`. The regressive product depends
//! only on `I`: a change of basis with determinant d scales `I`, and with it the regressive product
//! of the same two elements, by d. The complements themselves are tied to the basis, not to the
//! form. The polarity is `A I⁻¹` with `I⁻¹ = I / (I I)`, so it uses the metric; it is defined when the
//! form is non-degenerate.

use std::collections::BTreeMap;

use num_rational::Rational64;
use num_traits::{One, Zero};

use crate::blade::{grade, reorder_sign, BladeMask};
use crate::metric::Metric;
use crate::operation::Operation;

/// A basis blade with an exact coefficient.
pub type Term = (BladeMask, Rational64);

/// A linear combination of basis blades: what a rule gives for one blade or blade pair. A diagonal
/// metric never gives more than one term (and so never allocates); a general metric may give several.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Combination {
    #[default]
    /// No terms: the rule gives zero.
    Zero,
    /// One blade with a non-zero coefficient.
    Blade(Term),
    /// Several blades in increasing mask order, each with a non-zero coefficient.
    Sum(Vec<Term>),
}

impl Combination {
    /// `coefficient · blade` (zero if the coefficient is).
    ///
    /// ```
    /// use ga_codegen::product::Combination;
    /// use ga_codegen::Rational64;
    ///
    /// let half_e12 = Combination::blade(0b11, Rational64::new(1, 2));
    /// assert_eq!(half_e12.terms(), [(0b11, Rational64::new(1, 2))]);
    /// assert!(Combination::blade(0b11, Rational64::from_integer(0)).is_zero());
    /// ```
    pub fn blade(blade: BladeMask, coefficient: Rational64) -> Self {
        if coefficient.is_zero() {
            Combination::Zero
        } else {
            Combination::Blade((blade, coefficient))
        }
    }

    /// Collects terms, merging repeated blades and dropping those that cancel.
    ///
    /// ```
    /// use ga_codegen::product::Combination;
    /// use ga_codegen::Rational64;
    ///
    /// let r = Rational64::from_integer;
    /// // e2 + e1 + 2 e2 − e1: the e1 terms cancel, the e2 terms merge.
    /// let combination = Combination::from_terms([(0b10, r(1)), (0b01, r(1)), (0b10, r(2)), (0b01, r(-1))]);
    /// assert_eq!(combination, Combination::Blade((0b10, r(3))));
    /// // Several blades come out in increasing mask order.
    /// assert_eq!(Combination::from_terms([(0b10, r(1)), (0b01, r(5))]).terms(), [(0b01, r(5)), (0b10, r(1))]);
    /// ```
    pub fn from_terms(terms: impl IntoIterator<Item = Term>) -> Self {
        let mut merged: BTreeMap<BladeMask, Rational64> = BTreeMap::new();
        for (blade, coefficient) in terms {
            *merged.entry(blade).or_default() += coefficient;
        }
        let mut terms: Vec<Term> = merged.into_iter().filter(|(_, c)| !c.is_zero()).collect();
        match terms.len() {
            0 => Combination::Zero,
            1 => Combination::Blade(terms.remove(0)),
            _ => Combination::Sum(terms),
        }
    }

    /// The terms, in increasing mask order.
    pub fn terms(&self) -> &[Term] {
        match self {
            Combination::Zero => &[],
            Combination::Blade(term) => std::slice::from_ref(term),
            Combination::Sum(terms) => terms,
        }
    }

    /// Whether the combination has no terms.
    pub fn is_zero(&self) -> bool {
        matches!(self, Combination::Zero)
    }

    /// Every coefficient times `factor`.
    pub fn scaled(self, factor: Rational64) -> Self {
        match self {
            Combination::Zero => Combination::Zero,
            Combination::Blade((blade, c)) => Combination::blade(blade, c * factor),
            Combination::Sum(terms) => Combination::from_terms(terms.into_iter().map(|(b, c)| (b, c * factor))),
        }
    }

    /// The terms whose grade is `wanted`, or nothing if `wanted` is `None`.
    fn of_grade(self, wanted: Option<u32>) -> Self {
        let Some(k) = wanted else {
            return Combination::Zero;
        };
        match self {
            Combination::Blade((blade, _)) if grade(blade) != k => Combination::Zero,
            Combination::Sum(terms) => Combination::from_terms(terms.into_iter().filter(|&(b, _)| grade(b) == k)),
            kept => kept,
        }
    }
}

/// The product rules of one algebra.
#[derive(Clone, Debug)]
pub struct Rules<'a> {
    metric: &'a Metric,
    /// The pseudoscalar's blade (all bits set).
    pseudoscalar: BladeMask,
}

/// `(−1)^count` as a rational.
fn parity(count: u32) -> Rational64 {
    if count.is_multiple_of(2) {
        Rational64::one()
    } else {
        -Rational64::one()
    }
}

/// The factors of a blade in increasing order, with their positions.
fn factors(blade: BladeMask) -> impl Iterator<Item = (u32, usize)> {
    (0..32usize)
        .filter(move |&i| blade & (1 << i) != 0)
        .enumerate()
        .map(|(position, i)| (position as u32, i))
}

impl<'a> Rules<'a> {
    /// The product rules of the algebra with this metric.
    ///
    /// ```
    /// use ga_codegen::metric::Metric;
    /// use ga_codegen::product::{Combination, Rules};
    /// use ga_codegen::{Operation, Rational64};
    ///
    /// let metric = Metric::diagonal(vec![1, 1])?;
    /// let rules = Rules::new(&metric);
    /// // e2 e1 = −e12, and e1 ∧ e1 = 0.
    /// assert_eq!(rules.geometric(0b10, 0b01), Combination::blade(0b11, Rational64::from_integer(-1)));
    /// assert!(rules.binary(Operation::Outer, 0b01, 0b01).is_zero());
    /// # Ok::<(), ga_codegen::Error>(())
    /// ```
    pub fn new(metric: &'a Metric) -> Self {
        let n = metric.dimension();
        let pseudoscalar = if n == 32 { u32::MAX } else { (1u32 << n) - 1 };
        Rules { metric, pseudoscalar }
    }

    /// The geometric product of two basis blades. On an orthogonal basis: `a XOR b`, signed by the
    /// reordering and scaled by the squares of the shared vectors (zero if one of them is null).
    pub fn geometric(&self, a: BladeMask, b: BladeMask) -> Combination {
        if self.metric.is_diagonal() {
            let factor = self.metric.shared_factor(a & b);
            return Combination::blade(a ^ b, Rational64::from_integer(reorder_sign(a, b)) * factor);
        }
        let mut products = BTreeMap::new();
        Combination::from_terms(self.blade_times(a, b, &mut products))
    }

    /// Chevalley's recursion for `a · b` on a general metric: with `eᵢ` the first factor of `a`,
    /// `a = eᵢ ∧ a' = eᵢa' − eᵢ ⌋ a'`, so `ab = eᵢ(a'b) − (eᵢ ⌋ a')b`. The products `sb` of the
    /// sub-blades `s` of `a` are shared through `products`.
    fn blade_times(&self, a: BladeMask, b: BladeMask, products: &mut BTreeMap<BladeMask, Vec<Term>>) -> Vec<Term> {
        if a == 0 {
            return vec![(b, Rational64::one())];
        }
        if let Some(known) = products.get(&a) {
            return known.clone();
        }
        let first = a.trailing_zeros() as usize;
        let rest = a & !(1 << first);
        let mut terms = self.vector_times(first, &self.blade_times(rest, b, products));
        for (position, j) in factors(rest) {
            let inner = self.metric.inner(first, j);
            if inner.is_zero() {
                continue;
            }
            let coefficient = -inner * parity(position);
            let lower = self.blade_times(rest & !(1 << j), b, products);
            terms.extend(lower.into_iter().map(|(blade, c)| (blade, c * coefficient)));
        }
        let terms = Combination::from_terms(terms).terms().to_vec();
        products.insert(a, terms.clone());
        terms
    }

    /// `eᵢ X = eᵢ ∧ X + eᵢ ⌋ X` for a combination `X` (the terms may repeat blades).
    fn vector_times(&self, i: usize, x: &[Term]) -> Vec<Term> {
        let mut out = Vec::with_capacity(x.len() * 2);
        for &(blade, c) in x {
            if blade & (1 << i) == 0 {
                let before = (blade & ((1 << i) - 1)).count_ones();
                out.push((blade | (1 << i), c * parity(before)));
            }
            for (position, j) in factors(blade) {
                let inner = self.metric.inner(i, j);
                if !inner.is_zero() {
                    out.push((blade & !(1 << j), c * inner * parity(position)));
                }
            }
        }
        out
    }

    /// A binary operation on two basis blades. `Sandwich` and `Transform` are not blade-pair rules
    /// (see [`crate::expand`]); asking for them, or for a unary operation, gives zero.
    pub fn binary(&self, operation: Operation, a: BladeMask, b: BladeMask) -> Combination {
        let (ga, gb) = (grade(a), grade(b));
        match operation {
            Operation::Geometric => self.geometric(a, b),
            Operation::Outer => {
                if a & b == 0 {
                    Combination::blade(a | b, Rational64::from_integer(reorder_sign(a, b)))
                } else {
                    Combination::Zero
                }
            }
            Operation::LeftContraction => self.geometric(a, b).of_grade(gb.checked_sub(ga)),
            Operation::RightContraction => self.geometric(a, b).of_grade(ga.checked_sub(gb)),
            Operation::ScalarProduct => self.geometric(a, b).of_grade(Some(0)),
            Operation::HestenesInner if ga == 0 || gb == 0 => Combination::Zero,
            Operation::HestenesInner | Operation::FatDot => self.geometric(a, b).of_grade(Some(ga.abs_diff(gb))),
            Operation::Regressive => self.regressive(a, b),
            Operation::Commutator => {
                let half = Rational64::new(1, 2);
                let (forward, backward) = (self.geometric(a, b), self.geometric(b, a));
                let forward = forward.terms().iter().map(|&(blade, c)| (blade, c * half));
                let backward = backward.terms().iter().map(|&(blade, c)| (blade, -c * half));
                Combination::from_terms(forward.chain(backward))
            }
            _ => Combination::Zero,
        }
    }

    /// The regressive product LC(RC(a) ∧ RC(b)) (metric-free; the PGA join for Cl(3,0,1)).
    fn regressive(&self, a: BladeMask, b: BladeMask) -> Combination {
        let (ra, sa) = self.right_complement(a);
        let (rb, sb) = self.right_complement(b);
        if ra & rb != 0 {
            return Combination::Zero;
        }
        let (joined, sj) = (ra | rb, reorder_sign(ra, rb));
        let (result, sl) = self.left_complement(joined);
        Combination::blade(result, Rational64::from_integer(sa * sb * sj * sl))
    }

    /// RC(eₘ) = ±e₍∼ₘ₎ with the sign making eₘ ∧ RC(eₘ) = +I.
    pub fn right_complement(&self, blade: BladeMask) -> (BladeMask, i64) {
        let complement = self.pseudoscalar ^ blade;
        (complement, reorder_sign(blade, complement))
    }

    /// LC(eₘ) = ±e₍∼ₘ₎ with the sign making LC(eₘ) ∧ eₘ = +I.
    pub fn left_complement(&self, blade: BladeMask) -> (BladeMask, i64) {
        let complement = self.pseudoscalar ^ blade;
        (complement, reorder_sign(complement, blade))
    }

    /// `I I`, a scalar: zero exactly when the form is degenerate.
    pub fn pseudoscalar_square(&self) -> Rational64 {
        match self.geometric(self.pseudoscalar, self.pseudoscalar).terms() {
            [(0, square)] => *square,
            _ => Rational64::zero(),
        }
    }

    /// The polarity `A I⁻¹` with `I⁻¹ = I / (I I)`; zero on a degenerate form, where `I` has no inverse.
    pub fn polarity(&self, blade: BladeMask) -> Combination {
        let square = self.pseudoscalar_square();
        if square.is_zero() {
            return Combination::Zero;
        }
        self.geometric(blade, self.pseudoscalar).scaled(square.recip())
    }

    /// A unary map of a basis blade; zero where it is zero or undefined (polarity on a degenerate
    /// metric, or an operation that is not a blade map).
    pub fn unary(&self, operation: Operation, blade: BladeMask) -> Combination {
        let k = grade(blade);
        let signed = |exponent: u32| Combination::blade(blade, parity(exponent));
        let single = |(blade, sign): (BladeMask, i64)| Combination::blade(blade, Rational64::from_integer(sign));
        match operation {
            Operation::Reverse => signed(k * k.saturating_sub(1) / 2),
            Operation::Involute => signed(k),
            Operation::Conjugate => signed(k * (k + 1) / 2),
            Operation::RightComplement => single(self.right_complement(blade)),
            Operation::LeftComplement => single(self.left_complement(blade)),
            Operation::Polarity => self.polarity(blade),
            _ => Combination::Zero,
        }
    }
}

/// The sign of a blade under reversion: (−1)^{k(k−1)/2} for grade k.
pub fn reverse_sign(blade: BladeMask) -> Rational64 {
    let k = grade(blade);
    parity(k * k.saturating_sub(1) / 2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pga() -> Metric {
        Metric::diagonal(vec![0, 1, 1, 1]).unwrap()
    }

    fn blade(blade: BladeMask, coefficient: i64) -> Combination {
        Combination::blade(blade, Rational64::from_integer(coefficient))
    }

    /// e1, e2 Euclidean; n0, ninf null with n0 · ninf = −1.
    fn null_plane() -> Metric {
        let (zero, one) = (Rational64::zero(), Rational64::one());
        Metric::from_matrix(&[
            vec![one, zero, zero, zero],
            vec![zero, one, zero, zero],
            vec![zero, zero, zero, -one],
            vec![zero, zero, -one, zero],
        ])
        .unwrap()
    }

    #[test]
    fn geometric_product_signs_and_null_vectors() {
        let metric = pga();
        let rules = Rules::new(&metric);
        // e1 e2 = e12, e2 e1 = −e12, e1 e1 = 1, e0 e0 = 0.
        assert_eq!(rules.geometric(0b0010, 0b0100), blade(0b0110, 1));
        assert_eq!(rules.geometric(0b0100, 0b0010), blade(0b0110, -1));
        assert_eq!(rules.geometric(0b0010, 0b0010), blade(0, 1));
        assert_eq!(rules.geometric(0b0001, 0b0001), Combination::Zero);
    }

    #[test]
    fn pga_join_of_two_points_is_a_line() {
        let metric = pga();
        let rules = Rules::new(&metric);
        // The regressive product of e123 and e023 (meet of their complements) is ±e23.
        let terms = rules.binary(Operation::Regressive, 0b1110, 0b1101);
        assert_eq!(terms.terms()[0].0, 0b1100);
    }

    #[test]
    fn commutator_keeps_anticommuting_pairs_only() {
        let metric = Metric::diagonal(vec![1, 1, 1]).unwrap();
        let rules = Rules::new(&metric);
        assert_eq!(rules.binary(Operation::Commutator, 0b001, 0b010), blade(0b011, 1));
        assert_eq!(rules.binary(Operation::Commutator, 0b011, 0b011), Combination::Zero);
    }

    #[test]
    fn null_vectors_multiply_into_a_scalar_and_a_bivector() {
        let metric = null_plane();
        let rules = Rules::new(&metric);
        let (n0, ninf) = (0b0100, 0b1000);
        // n0 ninf = n0 · ninf + n0 ∧ ninf = −1 + n0∧ninf, and ninf n0 = −1 − n0∧ninf.
        let expected = |sign: i64| {
            Combination::Sum(vec![
                (0, -Rational64::one()),
                (n0 | ninf, Rational64::from_integer(sign)),
            ])
        };
        assert_eq!(rules.geometric(n0, ninf), expected(1));
        assert_eq!(rules.geometric(ninf, n0), expected(-1));
        assert_eq!(rules.geometric(n0, n0), Combination::Zero);
        // (n0 ∧ ninf)² = 1: the Minkowski plane's unit pseudoscalar.
        assert_eq!(rules.geometric(n0 | ninf, n0 | ninf), blade(0, 1));
        // e1 commutes past the null pair untouched.
        assert_eq!(rules.geometric(0b0001, n0 | ninf), blade(0b1101, 1));
    }

    #[test]
    fn polarity_divides_by_the_pseudoscalar_square() {
        let metric = null_plane();
        let rules = Rules::new(&metric);
        // I = e1 e2 (n0 ∧ ninf): I I = (e12)² (n0∧ninf)² = −1.
        assert_eq!(rules.pseudoscalar_square(), -Rational64::one());
        let degenerate = pga();
        assert_eq!(Rules::new(&degenerate).pseudoscalar_square(), Rational64::zero());
        assert_eq!(Rules::new(&degenerate).polarity(0b0010), Combination::Zero);
    }
}
