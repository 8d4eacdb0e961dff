//! Symbolic expansion: an operation on sparse types becomes, per output blade, a polynomial in the
//! operands' fields with exact rational coefficients. Terms that cancel vanish, so the set of output
//! blades is exactly the set whose coefficient is not identically zero.

use std::collections::btree_map::Entry;
use std::collections::BTreeMap;

use num_rational::Rational64;
use num_traits::Zero;

use crate::algebra::{Algebra, SparseType};
use crate::blade::{grade, BladeMask};
use crate::operation::Operation;
use crate::product::Rules;

/// Which operand a variable belongs to: `self` or the right-hand side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Operand {
    Lhs,
    Rhs,
}

/// One input coefficient: field number `field` of an operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Variable {
    pub operand: Operand,
    pub field: usize,
}

/// A product of variables, sorted (so `a₁a₂` and `a₂a₁` are the same monomial).
pub type Monomial = Vec<Variable>;

/// A polynomial with exact coefficients; a zero coefficient is never stored.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Polynomial {
    pub terms: BTreeMap<Monomial, Rational64>,
}

impl Polynomial {
    /// Adds `coefficient · Π factors`.
    pub fn add_term(&mut self, mut factors: Monomial, coefficient: Rational64) {
        factors.sort_unstable();
        match self.terms.entry(factors) {
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

    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The total degree (all monomials of one expansion share it).
    pub fn degree(&self) -> usize {
        self.terms.keys().map(Vec::len).max().unwrap_or(0)
    }
}

/// The expansion of one operation: the polynomial of every output blade that is not identically zero.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Expansion {
    pub outputs: BTreeMap<BladeMask, Polynomial>,
}

impl Expansion {
    fn add(&mut self, blade: BladeMask, factors: Monomial, coefficient: Rational64) {
        let polynomial = self.outputs.entry(blade).or_default();
        polynomial.add_term(factors, coefficient);
        if polynomial.is_zero() {
            self.outputs.remove(&blade);
        }
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

/// Expands a blade-pair operation (every binary operation but the sandwich) on two types.
pub fn binary(algebra: &Algebra, operation: Operation, left: &SparseType, right: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut expansion = Expansion::default();
    for (i, a) in left.fields.iter().enumerate() {
        for (j, b) in right.fields.iter().enumerate() {
            if let Some((blade, sign)) = rules.binary(operation, a.blade, b.blade) {
                expansion.add(blade, vec![lhs(i), rhs(j)], Rational64::from(sign * a.sign * b.sign));
            }
        }
    }
    expansion
}

/// Expands the sandwich `a x ~a` as one cubic polynomial (`a` = `versor`, `x` = `operand`): the
/// symmetric terms `aᵢ x aⱼ` and `aⱼ x aᵢ` merge into one monomial, which is why the fused form
/// costs less than two products.
pub fn sandwich(algebra: &Algebra, versor: &SparseType, operand: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut expansion = Expansion::default();
    for (i, a) in versor.fields.iter().enumerate() {
        for (k, x) in operand.fields.iter().enumerate() {
            let Some((ax, s1)) = rules.geometric(a.blade, x.blade) else {
                continue;
            };
            for (j, b) in versor.fields.iter().enumerate() {
                let Some((blade, s2)) = rules.geometric(ax, b.blade) else {
                    continue;
                };
                let Some((_, reverse_sign)) = rules.unary(Operation::Reverse, b.blade) else {
                    continue;
                };
                let coefficient = s1 * s2 * reverse_sign * a.sign * x.sign * b.sign;
                expansion.add(blade, vec![lhs(i), rhs(k), lhs(j)], Rational64::from(coefficient));
            }
        }
    }
    expansion
}

/// Expands a unary blade map (reverse, involutions, complements, polarity).
pub fn unary(algebra: &Algebra, operation: Operation, ty: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut expansion = Expansion::default();
    for (i, a) in ty.fields.iter().enumerate() {
        if let Some((blade, sign)) = rules.unary(operation, a.blade) {
            expansion.add(blade, vec![lhs(i)], Rational64::from(sign * a.sign));
        }
    }
    expansion
}

/// The grade-`k` part of a type.
pub fn grade_part(ty: &SparseType, k: u32) -> Expansion {
    let mut expansion = Expansion::default();
    for (i, a) in ty.fields.iter().enumerate().filter(|(_, a)| grade(a.blade) == k) {
        expansion.add(a.blade, vec![lhs(i)], Rational64::from(a.sign));
    }
    expansion
}

/// `a ~a` with both factors taken from `self` (so symmetric terms merge). Its scalar part is the
/// squared norm; where it has nothing else, `~a / (a ~a)` is the inverse.
pub fn times_own_reverse(algebra: &Algebra, ty: &SparseType) -> Expansion {
    let rules = Rules::new(&algebra.metric);
    let mut expansion = Expansion::default();
    for (i, a) in ty.fields.iter().enumerate() {
        for (j, b) in ty.fields.iter().enumerate() {
            let Some((blade, sign)) = rules.geometric(a.blade, b.blade) else {
                continue;
            };
            let Some((_, reverse_sign)) = rules.unary(Operation::Reverse, b.blade) else {
                continue;
            };
            expansion.add(
                blade,
                vec![lhs(i), lhs(j)],
                Rational64::from(sign * reverse_sign * a.sign * b.sign),
            );
        }
    }
    expansion
}

/// The sum or difference of two types, blade by blade.
pub fn sum(left: &SparseType, right: &SparseType, subtract: bool) -> Expansion {
    let mut expansion = Expansion::default();
    for (i, a) in left.fields.iter().enumerate() {
        expansion.add(a.blade, vec![lhs(i)], Rational64::from(a.sign));
    }
    let sign = if subtract { -1 } else { 1 };
    for (j, b) in right.fields.iter().enumerate() {
        expansion.add(b.blade, vec![rhs(j)], Rational64::from(sign * b.sign));
    }
    expansion
}
