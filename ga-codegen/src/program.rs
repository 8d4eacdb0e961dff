//! Lowering: the polynomials of an [`Expansion`] become a straight-line program of hoisted locals and
//! output sums. Emission prints this program and the cost model counts it, so the counts in the doc
//! comments are exactly what the emitted code computes.
//!
//! - Products: a monomial that several outputs share (on a non-orthogonal basis one blade pair feeds
//!   several blades) is computed once; a term with coefficient ±2 doubles one of its factors — an add
//!   instead of a multiply, the doubled value shared by every use, and the factors to double chosen
//!   so that few are (a greedy cover of the doubled terms).
//! - Cubic expansions (sandwiches) are factored as `out = Σₖ xₖ · Qₖ(a)`: every pair product `aᵢaⱼ`
//!   is computed once and shared by all outputs, and a pair that only ever appears doubled is built
//!   as `(aᵢ + aᵢ)·aⱼ`.
//! - The commutator form of a sandwich, `N x + a C` with `N = a ~a` (or `x + a C` for a unit versor),
//!   computes the blades of `N` and `C` as locals, then their products with the operand and versor.

use std::collections::{BTreeMap, BTreeSet};

use num_integer::Integer;
use num_rational::Rational64;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::blade::BladeMask;
use crate::expand::{CommutatorForm, Expansion, Operand, Polynomial, Variable};

/// A value the program can read: an input field or a hoisted local.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Value {
    /// A coefficient of one of the operands.
    Input(Variable),
    /// The local at this index of [`Program::locals`].
    Local(usize),
}

/// `coefficient · Π factors`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Term {
    /// The exact constant factor.
    pub coefficient: Rational64,
    /// The values multiplied together (none for a constant term).
    pub factors: Vec<Value>,
}

/// How a local is computed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Definition {
    /// A sum of terms.
    Sum(Vec<Term>),
    /// `v + v`.
    Double(Value),
}

#[derive(Clone, Debug, PartialEq, Eq)]
/// A hoisted intermediate value: a named `let` in the emitted code.
pub struct Local {
    /// The local's identifier, formed from the fields and blades it combines.
    pub name: String,
    /// How the local is computed.
    pub definition: Definition,
}

/// A straight-line program: locals in dependency order, then one sum per output blade.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Program {
    /// The hoisted locals, each defined only from inputs and earlier locals.
    pub locals: Vec<Local>,
    /// The sum of terms that gives each non-zero output blade's coefficient.
    pub outputs: BTreeMap<BladeMask, Vec<Term>>,
}

/// The exact operation count of a program (sign flips are free and not counted).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Cost {
    /// Multiplications, including those by a constant other than ±1.
    pub multiplies: usize,
    /// Additions and subtractions (a doubling `v + v` counts as one).
    pub adds: usize,
    /// Divisions (the `inverse`'s division by `a ~a`).
    pub divisions: usize,
}

impl std::ops::Add for Cost {
    type Output = Cost;
    fn add(self, other: Cost) -> Cost {
        Cost {
            multiplies: self.multiplies + other.multiplies,
            adds: self.adds + other.adds,
            divisions: self.divisions + other.divisions,
        }
    }
}

impl std::fmt::Display for Cost {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} multiplies, {} adds", self.multiplies, self.adds)?;
        if self.divisions > 0 {
            write!(f, ", {} divisions", self.divisions)?;
        }
        Ok(())
    }
}

pub(crate) fn sum_cost(terms: &[Term]) -> Cost {
    let multiplies = terms
        .iter()
        .map(|t| t.factors.len().saturating_sub(1) + usize::from(!t.coefficient.abs().is_one()))
        .sum();
    Cost {
        multiplies,
        adds: terms.len().saturating_sub(1),
        divisions: 0,
    }
}

impl Program {
    /// The number of multiplies and adds the program performs.
    pub fn cost(&self) -> Cost {
        let locals = self.locals.iter().map(|local| match &local.definition {
            Definition::Sum(terms) => sum_cost(terms),
            Definition::Double(_) => Cost {
                adds: 1,
                ..Cost::default()
            },
        });
        let outputs = self.outputs.values().map(|terms| sum_cost(terms));
        locals.chain(outputs).fold(Cost::default(), |total, cost| total + cost)
    }
}

impl Program {
    /// Whether the program reads an input variable for which `predicate` holds.
    pub fn reads(&self, predicate: impl Fn(Variable) -> bool) -> bool {
        let read = |value: &Value| matches!(value, Value::Input(variable) if predicate(*variable));
        let reads_any = |terms: &[Term]| terms.iter().any(|term| term.factors.iter().any(read));
        self.outputs.values().any(|terms| reads_any(terms))
            || self.locals.iter().any(|local| match &local.definition {
                Definition::Sum(terms) => reads_any(terms),
                Definition::Double(value) => read(value),
            })
    }

    /// Runs the program on numeric operands (field values in storage order): the emitted code's
    /// semantics, for testing it against the [`crate::Evaluator`] without compiling it.
    pub fn evaluate(&self, lhs: &[f64], rhs: &[f64]) -> BTreeMap<BladeMask, f64> {
        let mut locals = Vec::with_capacity(self.locals.len());
        let read = |value: Value, locals: &[f64]| match value {
            Value::Input(Variable {
                operand: Operand::Lhs,
                field,
            }) => lhs[field],
            Value::Input(Variable {
                operand: Operand::Rhs,
                field,
            }) => rhs[field],
            Value::Local(index) => locals[index],
        };
        let sum = |terms: &[Term], locals: &[f64]| -> f64 {
            terms
                .iter()
                .map(|t| {
                    t.coefficient.to_f64().unwrap_or(f64::NAN)
                        * t.factors.iter().map(|&v| read(v, locals)).product::<f64>()
                })
                .sum()
        };
        for local in &self.locals {
            let value = match &local.definition {
                Definition::Sum(terms) => sum(terms, &locals),
                Definition::Double(value) => 2.0 * read(*value, &locals),
            };
            locals.push(value);
        }
        self.outputs
            .iter()
            .map(|(&blade, terms)| (blade, sum(terms, &locals)))
            .collect()
    }
}

/// Names locals after the fields and blades they combine.
pub struct Names<'a> {
    /// The name of an input coefficient.
    pub field: &'a dyn Fn(Variable) -> String,
    /// The name of a blade.
    pub blade: &'a dyn Fn(BladeMask) -> String,
}

/// Builds programs. Local names are unique even where field names contain `_` (a pair `e1`·`e2_e3`
/// and a pair `e1_e2`·`e3` would both be called `e1_e2_e3`).
pub(crate) struct Builder<'a> {
    pub(crate) program: Program,
    names: &'a Names<'a>,
    doubles: BTreeMap<Value, usize>,
    /// The values a ±2 term prefers to double (see [`Builder::plan_doubling`]).
    planned: BTreeSet<Value>,
    taken: BTreeSet<String>,
}

impl<'a> Builder<'a> {
    pub(crate) fn new(names: &'a Names<'a>) -> Self {
        Builder {
            program: Program::default(),
            names,
            doubles: BTreeMap::new(),
            planned: BTreeSet::new(),
            taken: BTreeSet::new(),
        }
    }

    /// Chooses which values to double so that every product in `doubled` (the factor lists of terms
    /// with coefficient ±2) has one, using few of them: a greedy set cover, taking the value in the
    /// most uncovered products first (values already chosen cover for free).
    fn plan_doubling(&mut self, mut doubled: Vec<Vec<Value>>) {
        doubled.retain(|factors| factors.len() >= 2 && !factors.iter().any(|v| self.planned.contains(v)));
        while !doubled.is_empty() {
            let mut counts: BTreeMap<Value, usize> = BTreeMap::new();
            for factors in &doubled {
                for &value in factors {
                    *counts.entry(value).or_default() += 1;
                }
            }
            // The most used value; among equals, the first (inputs before locals, lhs before rhs).
            let Some((&best, _)) = counts.iter().rev().max_by_key(|(_, &count)| count) else {
                break;
            };
            self.planned.insert(best);
            doubled.retain(|factors| !factors.contains(&best));
        }
    }

    /// Keeps `name` free: no local is given it (a parameter of the emitted function has it).
    pub(crate) fn reserve(&mut self, name: &str) {
        self.taken.insert(name.to_string());
    }

    pub(crate) fn local(&mut self, name: String, definition: Definition) -> Value {
        let mut unique = name.clone();
        let mut suffix = 1;
        while !self.taken.insert(unique.clone()) {
            suffix += 1;
            unique = format!("{name}_{suffix}");
        }
        self.program.locals.push(Local {
            name: unique,
            definition,
        });
        Value::Local(self.program.locals.len() - 1)
    }

    /// The name of a value, to name the locals built from it.
    pub(crate) fn value_name(&self, value: Value) -> String {
        match value {
            Value::Input(variable) => (self.names.field)(variable),
            Value::Local(index) => self.program.locals[index].name.clone(),
        }
    }

    /// The hoisted `v + v`, shared by every use.
    fn double(&mut self, value: Value) -> Value {
        if let Some(&index) = self.doubles.get(&value) {
            return Value::Local(index);
        }
        let name = format!("twice_{}", self.value_name(value));
        let doubled = self.local(name, Definition::Double(value));
        if let Value::Local(index) = doubled {
            self.doubles.insert(value, index);
        }
        doubled
    }

    /// A term `c · Π factors`, with a coefficient of ±2 folded into a doubled factor: a planned one if
    /// any, else the first.
    fn term(&mut self, coefficient: Rational64, factors: &[Value]) -> Term {
        let two = Rational64::from(2);
        if coefficient.abs() == two && factors.len() >= 2 {
            let chosen = factors.iter().position(|v| self.planned.contains(v)).unwrap_or(0);
            let mut values = factors.to_vec();
            values[chosen] = self.double(factors[chosen]);
            return Term {
                coefficient: coefficient / two,
                factors: values,
            };
        }
        Term {
            coefficient,
            factors: factors.to_vec(),
        }
    }

    /// Sums of products, one per output blade. A product of several factors that more than one output
    /// uses is hoisted into a local (with the common integer factor of its uses folded in).
    pub(crate) fn products(&mut self, outputs: &BTreeMap<BladeMask, Vec<(Vec<Value>, Rational64)>>) {
        let mut uses: BTreeMap<&[Value], Vec<Rational64>> = BTreeMap::new();
        for terms in outputs.values() {
            for (factors, c) in terms {
                uses.entry(factors.as_slice()).or_default().push(*c);
            }
        }
        let shared = |factors: &[Value], uses: usize| uses >= 2 && factors.len() >= 2;
        let doubled = uses
            .iter()
            .filter(|(factors, coefficients)| {
                if shared(factors, coefficients.len()) {
                    common_factor(coefficients.iter()) == 2
                } else {
                    coefficients.iter().all(|c| c.abs() == Rational64::from(2))
                }
            })
            .map(|(factors, _)| factors.to_vec())
            .collect();
        self.plan_doubling(doubled);
        let mut hoisted: BTreeMap<Vec<Value>, (Value, i64)> = BTreeMap::new();
        for (factors, coefficients) in uses {
            if !shared(factors, coefficients.len()) {
                continue;
            }
            let factor = common_factor(coefficients.iter());
            let name = factors
                .iter()
                .map(|&v| self.value_name(v))
                .collect::<Vec<_>>()
                .join("_");
            let term = self.term(Rational64::from(factor), factors);
            let value = self.local(name, Definition::Sum(vec![term]));
            hoisted.insert(factors.to_vec(), (value, factor));
        }
        for (&blade, terms) in outputs {
            let lowered = terms
                .iter()
                .map(|(factors, c)| match hoisted.get(factors) {
                    Some(&(value, factor)) => Term {
                        coefficient: c / factor,
                        factors: vec![value],
                    },
                    None => self.term(*c, factors),
                })
                .collect();
            self.program.outputs.insert(blade, lowered);
        }
    }
}

impl Builder<'_> {
    /// Locals for the blades of `expansion` whose index is in `read`, named `{blade}_{role}`; returns
    /// the local of each index.
    fn intermediates(&mut self, expansion: &Expansion, read: &BTreeSet<usize>, role: &str) -> BTreeMap<usize, Value> {
        let read: Vec<(BladeMask, &Polynomial)> = expansion
            .outputs
            .iter()
            .enumerate()
            .filter(|(index, _)| read.contains(index))
            .map(|(_, (&blade, polynomial))| (blade, polynomial))
            .collect();
        let doubled = read
            .iter()
            .flat_map(|(_, p)| &p.terms)
            .filter(|(_, c)| c.abs() == Rational64::from(2))
            .map(|(factors, _)| inputs(factors))
            .collect();
        self.plan_doubling(doubled);
        let mut locals = BTreeMap::new();
        for (index, (&blade, polynomial)) in expansion.outputs.iter().enumerate() {
            if read.iter().any(|&(b, _)| b == blade) {
                let terms = polynomial
                    .terms
                    .iter()
                    .map(|(f, &c)| self.term(c, &inputs(f)))
                    .collect();
                let name = format!("{}_{role}", (self.names.blade)(blade));
                locals.insert(index, self.local(name, Definition::Sum(terms)));
            }
        }
        locals
    }
}

fn inputs(factors: &[Variable]) -> Vec<Value> {
    factors.iter().map(|&v| Value::Input(v)).collect()
}

/// Lowers an expansion to a program. The names of variables and output blades name the locals.
pub fn lower(expansion: &Expansion, names: &Names) -> Program {
    let mut builder = Builder::new(names);
    let cubic = expansion.outputs.values().any(|p| p.degree() == 3);
    if cubic {
        lower_sandwich(&mut builder, expansion);
    } else {
        let outputs = expansion
            .outputs
            .iter()
            .map(|(&blade, polynomial)| {
                let terms = polynomial.terms.iter().map(|(f, &c)| (inputs(f), c)).collect();
                (blade, terms)
            })
            .collect();
        builder.products(&outputs);
    }
    builder.program
}

/// Lowers the commutator form of a sandwich, `N x + a C` (see [`CommutatorForm`]): the blades of
/// `N` and `C` that the outputs read become locals, then the outputs sum their products with the
/// operand and the versor. For a unit versor, whose `a C` has vanishing blades, the bilinear part is also
/// tried in paired form (see `PairedProducts`) under every pairing of versor fields with commutator
/// blades and every subset of its pairs; the program with the fewest multiplies within an operation budget
/// wins (see `PAIRING_BUDGET_PERCENT`).
pub fn lower_commutator_form(form: &CommutatorForm, names: &Names) -> Program {
    let plain = lower_commutator_form_with(form, names, None);
    if form.vanishing.outputs.is_empty() {
        return plain;
    }
    let outputs = bilinear_forms(&form.product);
    let relations: Vec<Bilinear> = bilinear_forms(&form.vanishing).into_values().collect();
    let versor: BTreeSet<usize> = outputs.values().flat_map(|b| b.keys().map(|&(i, _)| i)).collect();
    let commutator: BTreeSet<usize> = outputs.values().flat_map(|b| b.keys().map(|&(_, k)| k)).collect();
    let (versor, commutator): (Vec<usize>, Vec<usize>) =
        (versor.into_iter().collect(), commutator.into_iter().collect());
    if versor.len() != commutator.len() || versor.len() > MAX_PAIRED_FIELDS {
        return plain;
    }
    let budget = operations(plain.cost()) * (100 + PAIRING_BUDGET_PERCENT) / 100;
    let mut best_rank = rank(plain.cost(), budget);
    let mut best = plain;
    for permutation in permutations(commutator.len()) {
        let pairing: BTreeMap<usize, usize> = versor
            .iter()
            .zip(&permutation)
            .map(|(&i, &p)| (i, commutator[p]))
            .collect();
        let candidates = PairedProducts::candidates(&outputs, &pairing);
        if candidates.len() > MAX_PAIRS {
            continue;
        }
        for subset in 0..1u32 << candidates.len() {
            let allowed: BTreeSet<(usize, usize)> = candidates
                .iter()
                .enumerate()
                .filter(|(bit, _)| subset >> bit & 1 == 1)
                .map(|(_, &pair)| pair)
                .collect();
            let paired = PairedProducts::new(&outputs, &relations, &pairing, &allowed);
            let program = lower_commutator_form_with(form, names, Some(&paired));
            let program_rank = rank(program.cost(), budget);
            if program_rank < best_rank {
                (best, best_rank) = (program, program_rank);
            }
        }
    }
    best
}

/// The most fields on each side for which every pairing is tried (4! = 24 pairings), and the most
/// transposed pairs per pairing whose subsets are all tried (2⁶): at most 1536 small programs per
/// function, so expansion stays fast in every algebra (a unit PGA motor on a point pairs 4 with 4).
const MAX_PAIRED_FIELDS: usize = 4;
const MAX_PAIRS: usize = 6;

/// How far pairing may raise the operation count (multiplies + adds) above the plain program's, in percent.
/// Each pair trades one multiply for three adds. Measured on a unit PGA motor moving points
/// (`cargo bench --bench floor`, one run): the plain 22 multiplies + 22 adds and the paired 21 + 25 ran
/// equally fast (2.85 and 2.84 µs per 1024), every pair used (18 + 34) 15% slower.
const PAIRING_BUDGET_PERCENT: usize = 5;

/// Multiplies plus adds.
fn operations(cost: Cost) -> usize {
    cost.multiplies + cost.adds
}

/// How programs are ranked: those within the operation `budget` first, then by multiplies, then adds.
fn rank(cost: Cost, budget: usize) -> (bool, usize, usize) {
    (operations(cost) > budget, cost.multiplies, cost.adds)
}

/// `(versor field i, commutator blade k) → coefficient` of a bilinear form `Σ c·aᵢCₖ`.
type Bilinear = BTreeMap<(usize, usize), Rational64>;

/// The bilinear forms of an expansion whose monomials are `aᵢ·Cₖ`, per blade.
fn bilinear_forms(expansion: &Expansion) -> BTreeMap<BladeMask, Bilinear> {
    expansion
        .outputs
        .iter()
        .map(|(&blade, polynomial)| {
            let form = polynomial
                .terms
                .iter()
                .map(|(monomial, &c)| ((monomial[0].field, monomial[1].field), c))
                .collect();
            (blade, form)
        })
        .collect()
}

/// Every permutation of `0..n`, in lexicographic order.
fn permutations(n: usize) -> Vec<Vec<usize>> {
    if n == 0 {
        return vec![Vec::new()];
    }
    permutations(n - 1)
        .into_iter()
        .flat_map(|shorter| {
            (0..n).map(move |position| {
                let mut longer: Vec<usize> = shorter.iter().map(|&p| p + usize::from(p >= position)).collect();
                longer.insert(0, position);
                longer
            })
        })
        .collect()
}

/// One piece of a paired bilinear form.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Piece {
    /// `(aᵢ + σ aⱼ)(C_π(i) + C_π(j))` with `i < j`, σ = ±1.
    Pair {
        first: usize,
        second: usize,
        difference: bool,
    },
    /// `aᵢ Cₖ` as it is.
    Plain { versor: usize, commutator: usize },
    /// `aᵢ C_π(i)`.
    Diagonal { versor: usize },
}

/// The bilinear part `a C` of a unit versor's transform rewritten with a pairing π of versor fields with
/// commutator blades (Karatsuba's trick, with the vanishing blades of `a C` as free relations):
///
/// - two terms that are each other's transpose under π, `α aᵢ C_π(j) + β aⱼ C_π(i)` with β = ±α, cost one
///   multiply: `α (aᵢ ± aⱼ)(C_π(i) + C_π(j))` minus the diagonal products `aᵢ C_π(i)`, `aⱼ C_π(j)`;
/// - the diagonal products are shared by every output, and each vanishing blade of `a C` that is a
///   combination of diagonal products alone (for a unit versor it is zero) removes one of them.
///
/// In PGA, `x + a C` for a unit motor on a point has `C = (c₀ e0, c)` and outputs
/// `s c + c₀ b + b × c`, with the vanishing e0 blade `s c₀ − b·c`. Under the pairing s ↔ c₀, bᵢ ↔ cᵢ the
/// twelve products become six pairs and three diagonal products (the relation removes `s c₀`): 18 multiplies
/// in all instead of 22, for 12 more adds. [`lower_commutator_form`] keeps as many pairs as its operation
/// budget allows: one, giving 21 multiplies and 25 adds.
struct PairedProducts {
    pairing: BTreeMap<usize, usize>,
    outputs: BTreeMap<BladeMask, BTreeMap<Piece, Rational64>>,
}

impl PairedProducts {
    /// The pieces with the transposed pairs in `allowed` (by their versor fields, ascending) paired.
    fn new(
        outputs: &BTreeMap<BladeMask, Bilinear>,
        relations: &[Bilinear],
        pairing: &BTreeMap<usize, usize>,
        allowed: &BTreeSet<(usize, usize)>,
    ) -> Self {
        let inverse: BTreeMap<usize, usize> = pairing.iter().map(|(&i, &k)| (k, i)).collect();
        let mut paired: BTreeMap<BladeMask, BTreeMap<Piece, Rational64>> = outputs
            .iter()
            .map(|(&blade, form)| (blade, Self::pair(form, pairing, &inverse, allowed)))
            .collect();
        // Relations among diagonal products only: each eliminates one diagonal product from the outputs.
        let mut relations: Vec<BTreeMap<Piece, Rational64>> = relations
            .iter()
            .map(|form| Self::pair(form, pairing, &inverse, allowed))
            .filter(|pieces| pieces.keys().all(|piece| matches!(piece, Piece::Diagonal { .. })))
            .collect();
        while let Some(relation) = relations.pop() {
            // The diagonal product used by the most outputs goes.
            let uses = |piece: &Piece| paired.values().filter(|pieces| pieces.contains_key(piece)).count();
            let Some((&pivot, &pivot_coefficient)) = relation.iter().max_by_key(|(piece, _)| uses(piece)) else {
                continue;
            };
            let eliminate = |pieces: &mut BTreeMap<Piece, Rational64>| {
                if let Some(c) = pieces.remove(&pivot) {
                    for (&piece, &r) in relation.iter().filter(|(&piece, _)| piece != pivot) {
                        accumulate(pieces, piece, -c * r / pivot_coefficient);
                    }
                }
            };
            paired.values_mut().for_each(eliminate);
            relations.iter_mut().for_each(eliminate);
        }
        PairedProducts {
            pairing: pairing.clone(),
            outputs: paired,
        }
    }

    /// The transposed pairs of the outputs under a pairing, by their versor fields (ascending).
    fn candidates(outputs: &BTreeMap<BladeMask, Bilinear>, pairing: &BTreeMap<usize, usize>) -> Vec<(usize, usize)> {
        let inverse: BTreeMap<usize, usize> = pairing.iter().map(|(&i, &k)| (k, i)).collect();
        let every: BTreeSet<(usize, usize)> = pairing
            .keys()
            .flat_map(|&i| pairing.keys().map(move |&j| (i, j)))
            .filter(|(i, j)| i < j)
            .collect();
        let pairs: BTreeSet<(usize, usize)> = outputs
            .values()
            .flat_map(|form| Self::pair(form, pairing, &inverse, &every).into_keys())
            .filter_map(|piece| match piece {
                Piece::Pair { first, second, .. } => Some((first, second)),
                _ => None,
            })
            .collect();
        pairs.into_iter().collect()
    }

    /// One bilinear form in pieces.
    fn pair(
        form: &Bilinear,
        pairing: &BTreeMap<usize, usize>,
        inverse: &BTreeMap<usize, usize>,
        allowed: &BTreeSet<(usize, usize)>,
    ) -> BTreeMap<Piece, Rational64> {
        let mut pieces: BTreeMap<Piece, Rational64> = BTreeMap::new();
        let mut done: BTreeSet<(usize, usize)> = BTreeSet::new();
        for (&(i, k), &alpha) in form {
            if done.contains(&(i, k)) {
                continue;
            }
            done.insert((i, k));
            if pairing.get(&i) == Some(&k) {
                accumulate(&mut pieces, Piece::Diagonal { versor: i }, alpha);
                continue;
            }
            // The transpose of aᵢ C_π(j) is aⱼ C_π(i).
            let partner = inverse.get(&k).zip(pairing.get(&i)).map(|(&j, &pi)| (j, pi));
            let beta = partner.and_then(|p| form.get(&p).copied());
            match (partner, beta) {
                (Some((j, pi)), Some(beta))
                    if !done.contains(&(j, pi))
                        && beta.abs() == alpha.abs()
                        && allowed.contains(&(i.min(j), i.max(j))) =>
                {
                    done.insert((j, pi));
                    let difference = beta != alpha;
                    // α aᵢC_π(j) ± α aⱼC_π(i) = α(aᵢ ± aⱼ)(C_π(i) + C_π(j)) − α aᵢC_π(i) ∓ α aⱼC_π(j).
                    let (first, second) = (i.min(j), i.max(j));
                    // (aᵢ − aⱼ) is stored as (a_first − a_second): flip α when i is the second.
                    let scale = if difference && i > j { -alpha } else { alpha };
                    accumulate(
                        &mut pieces,
                        Piece::Pair {
                            first,
                            second,
                            difference,
                        },
                        scale,
                    );
                    accumulate(&mut pieces, Piece::Diagonal { versor: i }, -alpha);
                    accumulate(&mut pieces, Piece::Diagonal { versor: j }, -beta);
                }
                _ => accumulate(
                    &mut pieces,
                    Piece::Plain {
                        versor: i,
                        commutator: k,
                    },
                    alpha,
                ),
            }
        }
        pieces
    }
}

/// Adds `c · piece`, dropping the piece when its coefficient cancels to zero.
fn accumulate(pieces: &mut BTreeMap<Piece, Rational64>, piece: Piece, c: Rational64) {
    let entry = pieces.entry(piece).or_default();
    *entry += c;
    if entry.is_zero() {
        pieces.remove(&piece);
    }
}

/// [`lower_commutator_form`] with the bilinear part as it is (`None`) or paired.
fn lower_commutator_form_with(form: &CommutatorForm, names: &Names, paired: Option<&PairedProducts>) -> Program {
    let mut builder = Builder::new(names);
    let read = |product: &Expansion, operand: Operand| -> BTreeSet<usize> {
        let variables = product
            .outputs
            .values()
            .flat_map(|p| p.terms.keys().flat_map(|m| m.iter()));
        variables.filter(|v| v.operand == operand).map(|v| v.field).collect()
    };
    let norms = builder.intermediates(&form.norm, &read(&form.norm_product, Operand::Lhs), "norm");
    let commutators = builder.intermediates(&form.commutator, &read(&form.product, Operand::Rhs), "commutator");
    let mut outputs: BTreeMap<BladeMask, Vec<(Vec<Value>, Rational64)>> = BTreeMap::new();
    let mut collect = |product: &Expansion, resolve: &dyn Fn(&Variable) -> Value| {
        for (&blade, polynomial) in &product.outputs {
            let terms = polynomial
                .terms
                .iter()
                .map(|(f, &c)| (f.iter().map(resolve).collect(), c));
            outputs.entry(blade).or_default().extend(terms);
        }
    };
    collect(&form.norm_product, &|v| match v.operand {
        Operand::Lhs => norms[&v.field],
        Operand::Rhs => Value::Input(*v),
    });
    match paired {
        None => collect(&form.product, &|v| match v.operand {
            Operand::Lhs => Value::Input(*v),
            Operand::Rhs => commutators[&v.field],
        }),
        Some(paired) => {
            let versor = |i: usize| {
                Value::Input(Variable {
                    operand: Operand::Lhs,
                    field: i,
                })
            };
            let mut sums: BTreeMap<(Value, Value, bool), Value> = BTreeMap::new();
            let mut sum = |builder: &mut Builder, first: Value, second: Value, difference: bool| {
                *sums.entry((first, second, difference)).or_insert_with(|| {
                    let joiner = if difference { "minus" } else { "plus" };
                    let name = format!("{}_{joiner}_{}", builder.value_name(first), builder.value_name(second));
                    let sign = if difference {
                        -Rational64::one()
                    } else {
                        Rational64::one()
                    };
                    let terms = vec![
                        Term {
                            coefficient: Rational64::one(),
                            factors: vec![first],
                        },
                        Term {
                            coefficient: sign,
                            factors: vec![second],
                        },
                    ];
                    builder.local(name, Definition::Sum(terms))
                })
            };
            for (&blade, pieces) in &paired.outputs {
                for (&piece, &c) in pieces {
                    let factors = match piece {
                        Piece::Pair {
                            first,
                            second,
                            difference,
                        } => {
                            let left = sum(&mut builder, versor(first), versor(second), difference);
                            let (k, l) = (paired.pairing[&first], paired.pairing[&second]);
                            let right = sum(&mut builder, commutators[&k], commutators[&l], false);
                            vec![left, right]
                        }
                        Piece::Plain { versor: i, commutator } => vec![versor(i), commutators[&commutator]],
                        Piece::Diagonal { versor: i } => vec![versor(i), commutators[&paired.pairing[&i]]],
                    };
                    outputs.entry(blade).or_default().push((factors, c));
                }
            }
        }
    }
    for &(blade, variable, coefficient) in &form.passthrough {
        outputs
            .entry(blade)
            .or_default()
            .push((vec![Value::Input(variable)], coefficient));
    }
    builder.products(&outputs);
    builder.program
}

/// Integer gcd of the coefficients' magnitudes (1 if any is not an integer).
fn common_factor<'a>(coefficients: impl Iterator<Item = &'a Rational64>) -> i64 {
    coefficients
        .fold(0i64, |g, c| if c.is_integer() { g.gcd(c.numer()) } else { 1 })
        .max(1)
}

/// `out = Σₖ xₖ · Σ c·(aᵢaⱼ)`: monomials are sorted with the versor's two factors first.
fn lower_sandwich(builder: &mut Builder, expansion: &Expansion) {
    // Every use of each pair (aᵢ, aⱼ): its coefficients decide whether the pair is built doubled.
    let mut pair_uses: BTreeMap<(Variable, Variable), Vec<Rational64>> = BTreeMap::new();
    for polynomial in expansion.outputs.values() {
        for (factors, &c) in &polynomial.terms {
            debug_assert!(factors[2].operand == Operand::Rhs && factors[1].operand == Operand::Lhs);
            pair_uses.entry((factors[0], factors[1])).or_default().push(c);
        }
    }
    let doubled = pair_uses
        .iter()
        .filter(|(_, coefficients)| common_factor(coefficients.iter()) == 2)
        .map(|(&(a, b), _)| inputs(&[a, b]))
        .collect();
    builder.plan_doubling(doubled);
    let mut pairs: BTreeMap<(Variable, Variable), (Value, i64)> = BTreeMap::new();
    for (&(a, b), coefficients) in &pair_uses {
        let factor = common_factor(coefficients.iter());
        let name = format!("{}_{}", (builder.names.field)(a), (builder.names.field)(b));
        let term = builder.term(Rational64::from(factor), &inputs(&[a, b]));
        let value = builder.local(name, Definition::Sum(vec![term]));
        pairs.insert((a, b), (value, factor));
    }
    for (&blade, polynomial) in &expansion.outputs {
        let mut by_operand: BTreeMap<Variable, Vec<Term>> = BTreeMap::new();
        for (factors, &c) in &polynomial.terms {
            let (pair, factor) = pairs[&(factors[0], factors[1])];
            by_operand.entry(factors[2]).or_default().push(Term {
                coefficient: c / factor,
                factors: vec![pair],
            });
        }
        let mut output = Vec::with_capacity(by_operand.len());
        for (x, mut quadratic) in by_operand {
            if quadratic.len() == 1 {
                let Term { coefficient, factors } = quadratic.pop().expect("one term");
                output.push(Term {
                    coefficient,
                    factors: vec![Value::Input(x), factors[0]],
                });
            } else {
                let name = format!("{}_into_{}", (builder.names.field)(x), (builder.names.blade)(blade));
                let q = builder.local(name, Definition::Sum(quadratic));
                output.push(Term {
                    coefficient: Rational64::one(),
                    factors: vec![Value::Input(x), q],
                });
            }
        }
        builder.program.outputs.insert(blade, output);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn variable(operand: Operand, field: usize) -> Variable {
        Variable { operand, field }
    }

    /// Fields `e1`, `e1_e2` (left) and `e2_e3`, `e3` (right): the products `e1 · e2_e3` and
    /// `e1_e2 · e3` would both be named `e1_e2_e3`.
    fn names() -> (impl Fn(Variable) -> String, impl Fn(BladeMask) -> String) {
        let field = |v: Variable| match (v.operand, v.field) {
            (Operand::Lhs, 0) => "e1".to_string(),
            (Operand::Lhs, _) => "e1_e2".to_string(),
            (_, 0) => "e2_e3".to_string(),
            _ => "e3".to_string(),
        };
        (field, |blade: BladeMask| format!("b{blade}"))
    }

    #[test]
    fn permutations_are_all_distinct() {
        let all = permutations(4);
        let distinct: BTreeSet<Vec<usize>> = all.iter().cloned().collect();
        assert_eq!((all.len(), distinct.len()), (24, 24));
        assert!(all
            .iter()
            .all(|p| p.iter().copied().collect::<BTreeSet<_>>().len() == 4));
    }

    #[test]
    fn products_shared_by_outputs_are_hoisted_under_unique_names() {
        let (a, b) = (
            vec![variable(Operand::Lhs, 0), variable(Operand::Rhs, 0)],
            vec![variable(Operand::Lhs, 1), variable(Operand::Rhs, 1)],
        );
        let mut expansion = Expansion::default();
        for blade in [1, 2] {
            let mut polynomial = Polynomial::default();
            polynomial.add_term(&a, Rational64::from(1));
            polynomial.add_term(&b, Rational64::from(2));
            expansion.outputs.insert(blade, polynomial);
        }
        let (field, blade) = names();
        let program = lower(
            &expansion,
            &Names {
                field: &field,
                blade: &blade,
            },
        );
        let local_names: Vec<&str> = program.locals.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(local_names, ["e1_e2_e3", "twice_e1_e2", "e1_e2_e3_2"]);
        // Two shared products (one of them doubled: an add), then two adds per output.
        assert_eq!(
            program.cost(),
            Cost {
                multiplies: 2,
                adds: 3,
                divisions: 0
            }
        );
        let values = program.evaluate(&[2.0, 3.0], &[5.0, 7.0]);
        assert_eq!(values[&1], 2.0 * 5.0 + 2.0 * 3.0 * 7.0);
        assert_eq!(values[&2], values[&1]);
    }
}
