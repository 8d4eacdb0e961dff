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

use crate::blade::{grade, reorder_sign, BladeMask};
use crate::metric::Metric;
use crate::operation::Operation;

/// A signed basis blade: `coefficient · blade`. Rules on a diagonal metric give at most one.
pub type Term = (BladeMask, i64);

/// The product rules of one algebra.
#[derive(Clone, Debug)]
pub struct Rules<'a> {
    metric: &'a Metric,
    /// The pseudoscalar's blade (all bits set).
    pseudoscalar: BladeMask,
}

impl<'a> Rules<'a> {
    pub fn new(metric: &'a Metric) -> Self {
        let n = metric.dimension();
        let pseudoscalar = if n == 32 { u32::MAX } else { (1u32 << n) - 1 };
        Rules { metric, pseudoscalar }
    }

    /// The geometric product of two basis blades: `a XOR b`, signed by the reordering and by the
    /// squares of the shared vectors (zero if one of them is null).
    pub fn geometric(&self, a: BladeMask, b: BladeMask) -> Option<Term> {
        let factor = self.metric.shared_factor(a & b);
        (factor != 0).then(|| (a ^ b, reorder_sign(a, b) * factor))
    }

    /// A binary operation on two basis blades. `Sandwich` is not a blade-pair rule (see
    /// [`crate::expand`]); asking for it, or for a unary operation, returns `None`.
    pub fn binary(&self, operation: Operation, a: BladeMask, b: BladeMask) -> Option<Term> {
        let (ga, gb) = (grade(a), grade(b));
        let keep_grade = |wanted: Option<u32>| {
            let product = self.geometric(a, b)?;
            (Some(grade(product.0)) == wanted).then_some(product)
        };
        match operation {
            Operation::Geometric => self.geometric(a, b),
            Operation::Outer => (a & b == 0).then(|| (a | b, reorder_sign(a, b))),
            Operation::LeftContraction => keep_grade(gb.checked_sub(ga)),
            Operation::RightContraction => keep_grade(ga.checked_sub(gb)),
            Operation::ScalarProduct => keep_grade(Some(0)),
            Operation::HestenesInner if ga == 0 || gb == 0 => None,
            Operation::HestenesInner | Operation::FatDot => keep_grade(Some(ga.abs_diff(gb))),
            Operation::Regressive => self.regressive(a, b),
            Operation::Commutator => {
                let (blade, forward) = self.geometric(a, b)?;
                let (_, backward) = self.geometric(b, a)?;
                // (ab − ba)/2 with ba = ±ab: either ab or nothing.
                (forward != backward).then_some((blade, (forward - backward) / 2))
            }
            _ => None,
        }
    }

    /// The regressive product LC(RC(a) ∧ RC(b)) (metric-free; the PGA join for Cl(3,0,1)).
    fn regressive(&self, a: BladeMask, b: BladeMask) -> Option<Term> {
        let (ra, sa) = self.right_complement(a);
        let (rb, sb) = self.right_complement(b);
        if ra & rb != 0 {
            return None;
        }
        let (joined, sj) = (ra | rb, reorder_sign(ra, rb));
        let (result, sl) = self.left_complement(joined);
        Some((result, sa * sb * sj * sl))
    }

    /// RC(eₘ) = ±e₍∼ₘ₎ with the sign making eₘ ∧ RC(eₘ) = +I.
    pub fn right_complement(&self, blade: BladeMask) -> Term {
        let complement = self.pseudoscalar ^ blade;
        (complement, reorder_sign(blade, complement))
    }

    /// LC(eₘ) = ±e₍∼ₘ₎ with the sign making LC(eₘ) ∧ eₘ = +I.
    pub fn left_complement(&self, blade: BladeMask) -> Term {
        let complement = self.pseudoscalar ^ blade;
        (complement, reorder_sign(complement, blade))
    }

    /// The polarity A·I⁻¹ (only for non-degenerate metrics, where I² = ±1 so I⁻¹ = I²·I).
    pub fn polarity(&self, blade: BladeMask) -> Option<Term> {
        let (_, pseudoscalar_square) = self.geometric(self.pseudoscalar, self.pseudoscalar)?;
        let (result, sign) = self.geometric(blade, self.pseudoscalar)?;
        Some((result, sign * pseudoscalar_square))
    }

    /// A unary map of a basis blade; `None` where it is zero or undefined (polarity on a degenerate
    /// metric, or an operation that is not a blade map).
    pub fn unary(&self, operation: Operation, blade: BladeMask) -> Option<Term> {
        let k = grade(blade) as i64;
        let sign_of = |exponent: i64| if exponent % 2 == 0 { 1 } else { -1 };
        match operation {
            Operation::Reverse => Some((blade, sign_of(k * (k - 1) / 2))),
            Operation::Involute => Some((blade, sign_of(k))),
            Operation::Conjugate => Some((blade, sign_of(k * (k + 1) / 2))),
            Operation::RightComplement => Some(self.right_complement(blade)),
            Operation::LeftComplement => Some(self.left_complement(blade)),
            Operation::Polarity => self.polarity(blade),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pga() -> Metric {
        Metric::diagonal(vec![0, 1, 1, 1])
    }

    #[test]
    fn geometric_product_signs_and_null_vectors() {
        let metric = pga();
        let rules = Rules::new(&metric);
        // e1 e2 = e12, e2 e1 = −e12, e1 e1 = 1, e0 e0 = 0.
        assert_eq!(rules.geometric(0b0010, 0b0100), Some((0b0110, 1)));
        assert_eq!(rules.geometric(0b0100, 0b0010), Some((0b0110, -1)));
        assert_eq!(rules.geometric(0b0010, 0b0010), Some((0, 1)));
        assert_eq!(rules.geometric(0b0001, 0b0001), None);
    }

    #[test]
    fn pga_join_of_two_points_is_a_line() {
        let metric = pga();
        let rules = Rules::new(&metric);
        // The regressive product of e123 and e023 (meet of their complements) is ±e23.
        let term = rules.binary(Operation::Regressive, 0b1110, 0b1101).unwrap();
        assert_eq!(term.0, 0b1100);
    }

    #[test]
    fn commutator_keeps_anticommuting_pairs_only() {
        let metric = Metric::diagonal(vec![1, 1, 1]);
        let rules = Rules::new(&metric);
        assert_eq!(rules.binary(Operation::Commutator, 0b001, 0b010), Some((0b011, 1)));
        assert_eq!(rules.binary(Operation::Commutator, 0b011, 0b011), None);
    }
}
