//! Lowering: the polynomials of an [`Expansion`] become a straight-line program of hoisted locals and
//! output sums. Emission prints this program and the cost model counts it, so the counts in the doc
//! comments are exactly what the emitted code computes.
//!
//! Cubic expansions (sandwiches) are factored as `out = Σₖ xₖ · Qₖ(a)`: every pair product `aᵢaⱼ`
//! is computed once and shared by all outputs, and a pair that only ever appears doubled is built
//! as `(aᵢ + aᵢ)·aⱼ` — an add instead of a multiply. Quadratic terms with coefficient ±2 use the same
//! doubling.

use std::collections::BTreeMap;

use num_integer::Integer;
use num_rational::Rational64;
use num_traits::{One, Signed, ToPrimitive};

use crate::blade::BladeMask;
use crate::expand::{Expansion, Operand, Variable};

/// A value the program can read: an input field or a hoisted local.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Value {
    Input(Variable),
    Local(usize),
}

/// `coefficient · Π factors`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Term {
    pub coefficient: Rational64,
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
pub struct Local {
    pub name: String,
    pub definition: Definition,
}

/// A straight-line program: locals in dependency order, then one sum per output blade.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Program {
    pub locals: Vec<Local>,
    pub outputs: BTreeMap<BladeMask, Vec<Term>>,
}

/// The exact operation count of a program (sign flips are free and not counted).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Cost {
    pub multiplies: usize,
    pub adds: usize,
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

fn sum_cost(terms: &[Term]) -> Cost {
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

/// Builds programs, naming locals after the fields they combine.
struct Builder<'a> {
    program: Program,
    field_name: &'a dyn Fn(Variable) -> String,
    blade_name: &'a dyn Fn(BladeMask) -> String,
    doubles: BTreeMap<Variable, usize>,
}

impl Builder<'_> {
    fn local(&mut self, name: String, definition: Definition) -> Value {
        self.program.locals.push(Local { name, definition });
        Value::Local(self.program.locals.len() - 1)
    }

    /// The hoisted `v + v`, shared by every use.
    fn double(&mut self, variable: Variable) -> Value {
        if let Some(&index) = self.doubles.get(&variable) {
            return Value::Local(index);
        }
        let name = format!("twice_{}", (self.field_name)(variable));
        let value = self.local(name, Definition::Double(Value::Input(variable)));
        if let Value::Local(index) = value {
            self.doubles.insert(variable, index);
        }
        value
    }

    /// A term `c · Π factors`, with a coefficient of ±2 folded into a doubled first factor.
    fn term(&mut self, coefficient: Rational64, factors: &[Variable]) -> Term {
        let two = Rational64::from(2);
        if coefficient.abs() == two && factors.len() >= 2 {
            let mut values = vec![self.double(factors[0])];
            values.extend(factors[1..].iter().map(|&v| Value::Input(v)));
            return Term {
                coefficient: coefficient / two,
                factors: values,
            };
        }
        Term {
            coefficient,
            factors: factors.iter().map(|&v| Value::Input(v)).collect(),
        }
    }
}

/// Lowers an expansion to a program. The names of variables and output blades name the locals.
pub fn lower(
    expansion: &Expansion,
    field_name: &dyn Fn(Variable) -> String,
    blade_name: &dyn Fn(BladeMask) -> String,
) -> Program {
    let mut builder = Builder {
        program: Program::default(),
        field_name,
        blade_name,
        doubles: BTreeMap::new(),
    };
    let cubic = expansion.outputs.values().any(|p| p.degree() == 3);
    if cubic {
        lower_sandwich(&mut builder, expansion);
    } else {
        for (&blade, polynomial) in &expansion.outputs {
            let terms = polynomial
                .terms
                .iter()
                .map(|(factors, &c)| builder.term(c, factors))
                .collect();
            builder.program.outputs.insert(blade, terms);
        }
    }
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
    let mut pairs: BTreeMap<(Variable, Variable), (Value, i64)> = BTreeMap::new();
    for (&(a, b), coefficients) in &pair_uses {
        let factor = common_factor(coefficients.iter());
        let name = format!("{}_{}", (builder.field_name)(a), (builder.field_name)(b));
        let term = builder.term(Rational64::from(factor), &[a, b]);
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
                let name = format!("{}_into_{}", (builder.field_name)(x), (builder.blade_name)(blade));
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
