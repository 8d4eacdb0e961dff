//! Whole-expression fusion: a declared expression ([`crate::expression`]) becomes one polynomial per output
//! blade in its parameters' fields, exactly, and then one straight-line program sharing work across all
//! outputs.
//!
//! **Expansion.** A parameter is the multivector `Σ sign · xᵢ eᵢ` of its fields (the sign of a permuted
//! blade name). Sums, scalar literals and the blade rules of [`crate::product`] act on such multivectors with
//! polynomial coefficients exactly, term by term; a call is inlined with its arguments substituted. Products
//! nest to any depth, so the polynomials have any degree; whatever cancels (`m * l * ~m` of a motor and a
//! line has no grade-0 or grade-4 part) vanishes before any code exists.
//!
//! **Lowering**, recursively on a set of polynomials (at first, the outputs):
//! - when one parameter enters every term of every polynomial exactly once (the line `l` in `m * l * ~m`),
//!   each polynomial is `Σᵥ v · Qᵥ` over that parameter's fields `v`. The coefficients `Qᵥ` that are equal
//!   up to a constant factor are computed once (each scaled so that its first coefficient is 1), and the set
//!   of distinct `Qᵥ` is lowered the same way. This is the structure of a linear map: for a motor on a
//!   line, the entries of its 6×6 matrix, each a quadratic in the motor, then one product per entry;
//! - otherwise each polynomial is a sum of products of fields, and a product that more than one polynomial
//!   uses is computed once (as for the products, [`crate::program`]).
//!
//! An expression of a sandwich's shape (`a * x * ~a`, `a.sandwich(x)`) also tries the emitted sandwich's program
//! (its commutator form) and keeps whichever costs fewer operations.
//!
//! A fused expression is always unrolled; an expansion past
//! [`MAX_UNROLLED_TERMS`] terms is refused with
//! [`Error::ExpressionTooBig`] (split the expression, or use the table-driven products).

use std::collections::BTreeMap;
use std::ops::Range;

use num_rational::Rational64;
use num_traits::{One, Signed, Zero};

use crate::algebra::Algebra;
use crate::blade::{grade, BladeMask};
use crate::error::Error;
use crate::expand::{Operand, Variable};
use crate::expression::{called, Expression, ExpressionDeclaration, ExpressionKind, Function};
use crate::functions::Output;
use crate::operation::Operation;
use crate::product::{Combination, Rules};
use crate::program::{self, Builder, Cost, Program, Term, Value};
use crate::table::MAX_UNROLLED_TERMS;

/// A fused expression: its parameters' types, its result, and the program computing the result's blades.
#[derive(Clone, Debug)]
pub struct Fused {
    /// Each parameter's type: a declared type, or the bare scalar.
    pub parameters: Vec<Output>,
    /// Where the first field of each parameter is among the program's inputs: the inputs are the parameters'
    /// fields one after the other, read as [`Operand::Lhs`] variables.
    pub offsets: Vec<usize>,
    /// The result's type.
    pub output: Output,
    /// The straight-line program; its outputs are the result's non-zero blades (before the result's field
    /// signs, as for every emitted function).
    pub program: Program,
    /// The program's exact operation count.
    pub cost: Cost,
}

impl Fused {
    /// The parameter whose fields include program input `input`.
    pub fn parameter_of(&self, input: usize) -> usize {
        parameter_of(&self.offsets, input)
    }

    /// Runs the program on one slice of field values per parameter (in storage order): what the emitted
    /// function computes, blade by blade.
    ///
    /// # Panics
    /// If the number of slices is not the number of parameters.
    ///
    /// ```
    /// use ga_codegen::expression::{Expression, ExpressionKind, Parameter};
    /// use ga_codegen::{Algebra, AlgebraDeclaration, BasisVectorDeclaration, ExpressionDeclaration, Layout};
    /// use ga_codegen::{Operation, ScalarType, TypeDeclaration};
    ///
    /// // The plane: a rotor turns a vector, r * v * ~r, fused.
    /// let basis = ["e1", "e2"].map(|name| BasisVectorDeclaration { name: name.into(), square: 1 });
    /// let ty = |name: &str, grades| TypeDeclaration { name: name.into(), layout: Layout::Grades(grades) };
    /// let node = |kind| Expression::new(kind);
    /// let name = |n: &str| Box::new(node(ExpressionKind::Parameter(n.into())));
    /// let turned = node(ExpressionKind::Binary(Operation::Sandwich, name("r"), name("v")));
    /// let parameter = |name: &str, ty: &str| Parameter { name: name.into(), type_name: ty.into() };
    /// let declaration = AlgebraDeclaration {
    ///     scalar: ScalarType::F64,
    ///     basis: basis.to_vec(),
    ///     metric: None,
    ///     types: vec![ty("Vector", vec![1]), ty("Rotor", vec![0, 2])],
    ///     operations: None,
    ///     lowering: vec![],
    ///     expressions: vec![ExpressionDeclaration {
    ///         name: "turned".into(),
    ///         parameters: vec![parameter("r", "Rotor"), parameter("v", "Vector")],
    ///         result: None,
    ///         body: turned,
    ///         linear: None,
    ///         doc: None,
    ///     }],
    /// };
    /// let fused = ga_codegen::fuse::fuse(&Algebra::new(&declaration)?, 0)?;
    /// // A quarter turn, r = cos(π/4) + sin(π/4) e12, takes e1 to -e2 (r v ~r turns by -2 · π/4).
    /// let half = std::f64::consts::FRAC_1_SQRT_2;
    /// let out = fused.evaluate(&[&[half, half], &[1.0, 0.0]]);
    /// assert!((out[&0b01] - 0.0).abs() < 1e-15 && (out[&0b10] + 1.0).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn evaluate(&self, arguments: &[&[f64]]) -> BTreeMap<BladeMask, f64> {
        assert_eq!(arguments.len(), self.parameters.len(), "one slice per parameter");
        let inputs: Vec<f64> = arguments.iter().flat_map(|values| values.iter().copied()).collect();
        self.program.evaluate(&inputs, &[])
    }
}

pub(crate) fn parameter_of(offsets: &[usize], input: usize) -> usize {
    offsets.iter().rposition(|&offset| offset <= input).unwrap_or(0)
}

/// A product of inputs: their indices, sorted (repeated for powers).
pub(crate) type Monomial = Vec<u32>;

/// A polynomial in the inputs with exact coefficients; no zero coefficient is stored.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Polynomial(pub(crate) BTreeMap<Monomial, Rational64>);

impl Polynomial {
    fn add_term(&mut self, monomial: Monomial, coefficient: Rational64) {
        let entry = self.0.entry(monomial).or_insert_with(Rational64::zero);
        *entry += coefficient;
        if entry.is_zero() {
            self.0.retain(|_, c| !c.is_zero());
        }
    }

    fn scaled(&self, factor: Rational64) -> Polynomial {
        Polynomial(self.0.iter().map(|(m, &c)| (m.clone(), c * factor)).collect())
    }
}

/// A multivector with polynomial coefficients: each blade with a non-zero polynomial.
pub(crate) type Symbolic = BTreeMap<BladeMask, Polynomial>;

/// Adds `factor · polynomial` to the blade's coefficient, dropping it if it cancels.
pub(crate) fn accumulate(target: &mut Symbolic, blade: BladeMask, polynomial: &Polynomial, factor: Rational64) {
    let coefficient = target.entry(blade).or_default();
    for (monomial, &c) in &polynomial.0 {
        coefficient.add_term(monomial.clone(), c * factor);
    }
    if coefficient.0.is_empty() {
        target.remove(&blade);
    }
}

fn term_count(x: &Symbolic) -> usize {
    x.values().map(|p| p.0.len()).sum()
}

/// The image of `x` under a map of blades.
fn linear(x: &Symbolic, map: impl Fn(BladeMask) -> Combination) -> Symbolic {
    let mut out = Symbolic::new();
    for (&blade, polynomial) in x {
        for &(image, c) in map(blade).terms() {
            accumulate(&mut out, image, polynomial, c);
        }
    }
    out
}

/// Expands one declared expression at a time; `top` is the expression being fused (calls inline others).
pub(crate) struct Expander<'a> {
    pub(crate) algebra: &'a Algebra,
    pub(crate) rules: Rules<'a>,
    pub(crate) top: usize,
}

impl Expander<'_> {
    fn too_big(&self, terms: usize) -> Error {
        Error::ExpressionTooBig {
            index: self.top,
            expression: self.algebra.expressions[self.top].name.clone(),
            terms,
            max: MAX_UNROLLED_TERMS,
        }
    }

    /// The bilinear image of `a` and `b` under a rule on blade pairs, refused once past the term limit.
    fn bilinear(
        &self,
        a: &Symbolic,
        b: &Symbolic,
        rule: impl Fn(BladeMask, BladeMask) -> Combination,
    ) -> Result<Symbolic, Error> {
        let mut out = Symbolic::new();
        for (&blade_a, pa) in a {
            for (&blade_b, pb) in b {
                let combination = rule(blade_a, blade_b);
                if combination.is_zero() {
                    continue;
                }
                let mut product = Polynomial::default();
                for (ma, &ca) in &pa.0 {
                    for (mb, &cb) in &pb.0 {
                        let mut monomial = [ma.as_slice(), mb.as_slice()].concat();
                        monomial.sort_unstable();
                        product.add_term(monomial, ca * cb);
                    }
                }
                for &(blade, c) in combination.terms() {
                    accumulate(&mut out, blade, &product, c);
                }
            }
            let terms = term_count(&out);
            if terms > MAX_UNROLLED_TERMS {
                return Err(self.too_big(terms));
            }
        }
        Ok(out)
    }

    pub(crate) fn product(&self, operation: Operation, a: &Symbolic, b: &Symbolic) -> Result<Symbolic, Error> {
        self.bilinear(a, b, |x, y| self.rules.binary(operation, x, y))
    }

    pub(crate) fn reverse(&self, x: &Symbolic) -> Symbolic {
        linear(x, |blade| self.rules.unary(Operation::Reverse, blade))
    }

    /// The value of `node`, a node of expression `at`'s body, with the parameters bound in `scope`;
    /// `calls` holds the expressions being inlined (to refuse recursion).
    fn evaluate(
        &self,
        at: usize,
        node: &Expression,
        scope: &BTreeMap<&str, Symbolic>,
        calls: &mut Vec<usize>,
    ) -> Result<Symbolic, Error> {
        let expression_name = || self.algebra.expressions[at].name.clone();
        let not_fusable = |operation: Operation, reason| Error::NotFusable {
            index: at,
            node: node.id,
            operation: operation.name().to_string(),
            reason,
        };
        let operand = |x: &Expression, calls: &mut Vec<usize>| self.evaluate(at, x, scope, calls);
        Ok(match &node.kind {
            ExpressionKind::Parameter(name) => match scope.get(name.as_str()) {
                Some(value) => value.clone(),
                None => {
                    return Err(Error::UnknownName {
                        index: at,
                        node: node.id,
                        expression: expression_name(),
                        name: name.clone(),
                    })
                }
            },
            ExpressionKind::Scalar(value) => {
                let mut scalar = Symbolic::new();
                accumulate(
                    &mut scalar,
                    0,
                    &Polynomial([(vec![], *value)].into()),
                    Rational64::one(),
                );
                scalar
            }
            ExpressionKind::Negate(x) => linear(&operand(x, calls)?, |blade| {
                Combination::blade(blade, -Rational64::one())
            }),
            ExpressionKind::Sum { lhs, rhs, subtract } => {
                let mut sum = operand(lhs, calls)?;
                let sign = if *subtract {
                    -Rational64::one()
                } else {
                    Rational64::one()
                };
                for (blade, polynomial) in &operand(rhs, calls)? {
                    accumulate(&mut sum, *blade, polynomial, sign);
                }
                sum
            }
            ExpressionKind::Grade(k, x) => {
                let max = self.algebra.dimension();
                if *k as usize > max {
                    return Err(Error::ExpressionGradeOutOfRange {
                        index: at,
                        node: node.id,
                        grade: *k,
                        max,
                    });
                }
                let mut x = operand(x, calls)?;
                x.retain(|&blade, _| grade(blade) == *k);
                x
            }
            ExpressionKind::Unary(operation, x) => match operation {
                Operation::Inverse => {
                    return Err(not_fusable(
                        *operation,
                        "it divides by `a ~a`: fuse the numerator `~a` and divide by `a.norm_squared()`",
                    ))
                }
                Operation::NormSquared => {
                    let x = operand(x, calls)?;
                    let mut square = self.product(Operation::Geometric, &x, &self.reverse(&x))?;
                    square.retain(|&blade, _| blade == 0);
                    square
                }
                Operation::Reverse
                | Operation::Involute
                | Operation::Conjugate
                | Operation::RightComplement
                | Operation::LeftComplement
                | Operation::Polarity => linear(&operand(x, calls)?, |blade| self.rules.unary(*operation, blade)),
                _ => return Err(not_fusable(*operation, "it is not a unary operation")),
            },
            ExpressionKind::Binary(operation, a, b) => match operation {
                Operation::Transform => {
                    return Err(not_fusable(
                        *operation,
                        "its emitted form assumes a unit versor, which a fused expression cannot check: write \
                         the sandwich `a.sandwich(x)` or `a * x * ~a`",
                    ))
                }
                Operation::Sandwich => {
                    let (a, x) = (operand(a, calls)?, operand(b, calls)?);
                    let left = self.product(Operation::Geometric, &a, &x)?;
                    self.product(Operation::Geometric, &left, &self.reverse(&a))?
                }
                _ if operation.is_binary() => self.product(*operation, &operand(a, calls)?, &operand(b, calls)?)?,
                _ => return Err(not_fusable(*operation, "it is not a binary operation")),
            },
            ExpressionKind::Call(name, arguments) => self.call(at, node, name, arguments, scope, calls)?,
        })
    }

    /// Inlines the expression `name` with `arguments` (nodes of expression `at`).
    fn call(
        &self,
        at: usize,
        node: &Expression,
        name: &str,
        arguments: &[Expression],
        scope: &BTreeMap<&str, Symbolic>,
        calls: &mut Vec<usize>,
    ) -> Result<Symbolic, Error> {
        let expressions = &self.algebra.expressions;
        let not_polynomial = |function: Function, reason: String| Error::TranscendentalUse {
            index: at,
            node: node.id,
            function: function.name(),
            reason,
        };
        if let Some(function) = Function::named(name) {
            return Err(not_polynomial(
                function,
                "it is not a polynomial, so it cannot be part of a larger formula".to_string(),
            ));
        }
        let Some(callee) = expressions.iter().position(|e| e.name == name) else {
            return Err(Error::UnknownName {
                index: at,
                node: node.id,
                expression: expressions[at].name.clone(),
                name: name.to_string(),
            });
        };
        if calls.contains(&callee) {
            return Err(Error::RecursiveCall {
                index: at,
                node: node.id,
                expression: expressions[at].name.clone(),
                name: name.to_string(),
            });
        }
        let declared = &expressions[callee];
        if let Some(function) = called(declared) {
            return Err(not_polynomial(
                function,
                format!("`{name}` is not a polynomial, so it cannot be called inside a formula; call it from Rust"),
            ));
        }
        if declared.parameters.len() != arguments.len() {
            return Err(Error::ArgumentCount {
                index: at,
                node: node.id,
                name: name.to_string(),
                expected: declared.parameters.len(),
                found: arguments.len(),
            });
        }
        let mut bound = BTreeMap::new();
        for (parameter, argument) in declared.parameters.iter().zip(arguments) {
            let value = self.evaluate(at, argument, scope, calls)?;
            let outside = outside(self.algebra, value.keys(), &parameter.type_name);
            if !outside.is_empty() {
                return Err(Error::ArgumentDoesNotFit {
                    index: at,
                    node: argument.id,
                    name: name.to_string(),
                    parameter: parameter.name.clone(),
                    type_name: parameter.type_name.clone(),
                    blades: outside,
                });
            }
            bound.insert(parameter.name.as_str(), value);
        }
        calls.push(callee);
        let value = self.evaluate(callee, &declared.body, &bound, calls)?;
        calls.pop();
        self.check_result(callee, &value)?;
        Ok(value)
    }

    /// The declared result type of expression `index` holds `value`.
    fn check_result(&self, index: usize, value: &Symbolic) -> Result<(), Error> {
        let declared = &self.algebra.expressions[index];
        match &declared.result {
            Some(result) => {
                let outside = outside(self.algebra, value.keys(), result);
                match outside.is_empty() {
                    true => Ok(()),
                    false => Err(Error::ResultDoesNotFit {
                        index,
                        expression: declared.name.clone(),
                        result: result.clone(),
                        blades: outside,
                    }),
                }
            }
            None => Ok(()),
        }
    }
}

/// The names of the `blades` that the type (or scalar) named `type_name` cannot hold.
fn outside<'b>(algebra: &Algebra, blades: impl IntoIterator<Item = &'b BladeMask>, type_name: &str) -> Vec<String> {
    let holds = |blade: BladeMask| match algebra.type_named(type_name) {
        Some(ty) => ty.field_of(blade).is_some(),
        None => blade == 0,
    };
    blades
        .into_iter()
        .filter(|&&blade| !holds(blade))
        .map(|&blade| algebra.blade_name(blade))
        .collect()
}

/// The result type of expression `index` whose value has the non-zero `blades`: the declared type, which must
/// hold them, or else the smallest declared type that does.
pub(crate) fn result_type(algebra: &Algebra, index: usize, blades: &[BladeMask]) -> Result<Output, Error> {
    let declared = &algebra.expressions[index];
    match &declared.result {
        Some(result) => {
            let outside = outside(algebra, blades, result);
            if !outside.is_empty() {
                return Err(Error::ResultDoesNotFit {
                    index,
                    expression: declared.name.clone(),
                    result: result.clone(),
                    blades: outside,
                });
            }
            Ok(value_type(algebra, result))
        }
        None => match algebra.smallest_type_holding(blades) {
            Some(ty) => Ok(value_type(algebra, &ty.name)),
            None => Err(Error::NoExpressionResultType {
                index,
                expression: declared.name.clone(),
                blades: blades.iter().map(|&b| algebra.blade_name(b)).collect(),
            }),
        },
    }
}

/// The type a parameter or result named `type_name` has: a declared type, or the bare scalar.
pub(crate) fn value_type(algebra: &Algebra, type_name: &str) -> Output {
    match algebra.types.iter().position(|ty| ty.name == type_name) {
        Some(index) => Output::Type(index),
        None => Output::Scalar,
    }
}

/// An expression expanded: its parameters, the program inputs they occupy, its value and result type.
struct Expanded {
    parameters: Vec<Output>,
    offsets: Vec<usize>,
    /// The range of program inputs of each parameter.
    groups: Vec<Range<u32>>,
    value: Symbolic,
    output: Output,
}

impl Expanded {
    /// The program computing `outputs` (keyed as its outputs are to be), polynomials in the inputs of the
    /// parameters `groups`; its locals are named after the parameters' fields (`m_e12`), never a parameter's name.
    fn program(
        &self,
        algebra: &Algebra,
        index: usize,
        outputs: &BTreeMap<BladeMask, Polynomial>,
        groups: &[Range<u32>],
    ) -> Program {
        let polynomials: Vec<&Polynomial> = outputs.values().collect();
        let (mut program, sums) = lower_parameters(
            algebra,
            &algebra.expressions[index],
            (&self.parameters, &self.offsets),
            &polynomials,
            groups,
        );
        program.outputs = outputs.keys().copied().zip(sums).collect();
        program
    }
}

/// Lowers polynomials in the fields of `declared`'s parameters (of types `parameters`, first inputs at `offsets`)
/// into one program sharing products, and each polynomial's sum; locals are named after the parameters' fields
/// (`m_e12`), never a parameter's name.
pub(crate) fn lower_parameters(
    algebra: &Algebra,
    declared: &ExpressionDeclaration,
    (parameters, offsets): (&[Output], &[usize]),
    polynomials: &[&Polynomial],
    groups: &[Range<u32>],
) -> (Program, Vec<Vec<Term>>) {
    let input_name = |variable: Variable| {
        let parameter = parameter_of(offsets, variable.field);
        let name = &declared.parameters[parameter].name;
        match parameters[parameter] {
            Output::Type(ty) => {
                let field = &algebra.types[ty].fields[variable.field - offsets[parameter]];
                format!("{name}_{}", field.name)
            }
            Output::Scalar => name.clone(),
        }
    };
    let blade_name = |blade| algebra.blade_name(blade);
    let names = program::Names {
        field: &input_name,
        blade: &blade_name,
    };
    let mut builder = Builder::new(&names);
    for parameter in &declared.parameters {
        builder.reserve(&parameter.name);
    }
    let sums = lower(&mut builder, polynomials, groups);
    (builder.program, sums)
}

/// Expands `algebra.expressions[index]` exactly and picks its result type.
fn expand(algebra: &Algebra, index: usize) -> Result<Expanded, Error> {
    let declared = &algebra.expressions[index];
    let parameters: Vec<Output> = declared
        .parameters
        .iter()
        .map(|p| value_type(algebra, &p.type_name))
        .collect();
    let mut offsets = Vec::with_capacity(parameters.len());
    let mut scope = BTreeMap::new();
    let mut groups = Vec::new();
    let mut next = 0;
    for (parameter, kind) in declared.parameters.iter().zip(&parameters) {
        let mut value = Symbolic::new();
        let fields = blades_and_signs(algebra, *kind);
        offsets.push(next);
        for (offset, (blade, sign)) in fields.iter().enumerate() {
            let input = Polynomial([(vec![(next + offset) as u32], Rational64::from(*sign))].into());
            accumulate(&mut value, *blade, &input, Rational64::one());
        }
        groups.push(next as u32..(next + fields.len()) as u32);
        next += fields.len();
        scope.insert(parameter.name.as_str(), value);
    }
    let expander = Expander {
        algebra,
        rules: Rules::new(&algebra.metric),
        top: index,
    };
    let value = expander.evaluate(index, &declared.body, &scope, &mut vec![index])?;
    if declared.result.is_none() && value.is_empty() {
        return Err(Error::ZeroExpression {
            index,
            expression: declared.name.clone(),
        });
    }
    let blades: Vec<BladeMask> = value.keys().copied().collect();
    let output = result_type(algebra, index, &blades)?;
    Ok(Expanded {
        parameters,
        offsets,
        groups,
        value,
        output,
    })
}

/// Fuses `algebra.expressions[index]`: expands it exactly, picks its result type and lowers it.
///
/// # Errors
/// An unknown name, a call with the wrong arguments or a recursive one, an operation that is not
/// polynomial (`inverse`, `transform`), a grade out of range, a result that does not fit the declared type
/// (or no declared type when none is declared, or an identically zero result without one), or an expansion
/// past the term limit.
pub fn fuse(algebra: &Algebra, index: usize) -> Result<Fused, Error> {
    let declared = &algebra.expressions[index];
    if let Some(function) = called(declared) {
        return Err(Error::TranscendentalUse {
            index,
            node: declared.body.id,
            function: function.name(),
            reason: "it is generated in closed form (`transcendental::closed_form`), not fused".to_string(),
        });
    }
    Ok(fuse_expanded(algebra, index, expand(algebra, index)?))
}

/// Lowers an expansion of `algebra.expressions[index]`.
fn fuse_expanded(algebra: &Algebra, index: usize, expanded: Expanded) -> Fused {
    let generic = expanded.program(algebra, index, &expanded.value, &expanded.groups);
    let total = |cost: Cost| cost.multiplies + cost.adds;
    let program = match sandwich_program(algebra, index, &expanded) {
        Some(sandwich) if total(sandwich.cost()) < total(generic.cost()) => sandwich,
        _ => generic,
    };
    Fused {
        cost: program.cost(),
        parameters: expanded.parameters,
        offsets: expanded.offsets,
        output: expanded.output,
        program,
    }
}

/// For an expression that is a sandwich of one parameter on another (`a * x * ~a` or `a.sandwich(x)`), the
/// program of the emitted `sandwich` of their types, on the expression's inputs: its commutator form
/// (`N x + a C`, see [`crate::expand`]) is a structure the generic lowering does not find (a motor on a point:
/// 30 multiplies and 25 adds against 35 and 40). `None` for any other expression, or where the emitted sandwich
/// is not unrolled or its locals would shadow a parameter.
fn sandwich_program(algebra: &Algebra, index: usize, expanded: &Expanded) -> Option<Program> {
    let declared = &algebra.expressions[index];
    let parameter = |node: &Expression| match &node.kind {
        ExpressionKind::Parameter(name) => declared.parameters.iter().position(|p| p.name == *name),
        _ => None,
    };
    let (versor, operand) = match &declared.body.kind {
        ExpressionKind::Binary(Operation::Sandwich, a, x) => (parameter(a)?, parameter(x)?),
        ExpressionKind::Binary(Operation::Geometric, left, reversed) => match (&left.kind, &reversed.kind) {
            (ExpressionKind::Binary(Operation::Geometric, a, x), ExpressionKind::Unary(Operation::Reverse, b))
                if parameter(a).is_some() && parameter(a) == parameter(b) =>
            {
                (parameter(a)?, parameter(x)?)
            }
            _ => return None,
        },
        _ => return None,
    };
    let (Output::Type(lhs), Output::Type(rhs)) = (expanded.parameters[versor], expanded.parameters[operand]) else {
        return None;
    };
    if versor == operand {
        return None;
    }
    let function = crate::functions::binary(algebra, Operation::Sandwich, lhs, rhs).ok()?;
    let crate::functions::Code::Unrolled(mut program) = function.code else {
        return None;
    };
    if program
        .locals
        .iter()
        .any(|local| declared.parameters.iter().any(|p| p.name == local.name))
    {
        return None;
    }
    let moved = |value: &mut Value| {
        if let Value::Input(variable) = value {
            let offset = match variable.operand {
                Operand::Lhs => expanded.offsets[versor],
                Operand::Rhs => expanded.offsets[operand],
            };
            *variable = Variable {
                operand: Operand::Lhs,
                field: offset + variable.field,
            };
        }
    };
    for local in &mut program.locals {
        match &mut local.definition {
            program::Definition::Sum(terms) => terms.iter_mut().flat_map(|t| &mut t.factors).for_each(moved),
            program::Definition::Double(value) => moved(value),
        }
    }
    program
        .outputs
        .values_mut()
        .flatten()
        .flat_map(|t| &mut t.factors)
        .for_each(moved);
    // The same exact expansion: the same blades survive.
    (program.outputs.keys().eq(expanded.value.keys())).then_some(program)
}

/// An expression linear in one parameter, as its matrix: `result field i = Σⱼ matrix[i][j] · x field j`,
/// the entries polynomials in the other parameters (the motor's 6×6 on lines, built once and applied to many).
#[derive(Clone, Debug)]
pub struct LinearMap {
    /// The fused expression's parameters (the linear one included) and their inputs, as in [`Fused`].
    pub fused: Fused,
    /// The linear parameter's index.
    pub linear: usize,
    /// The matrix's shape: (fields of the result, fields of the linear parameter).
    pub shape: (usize, usize),
    /// The program computing the entries: output `k` is the entry `(k / columns, k % columns)`; entries that
    /// vanish identically have no output (and cost nothing to apply).
    pub entries: Program,
    /// The exact operation count of building the matrix.
    pub cost: Cost,
}

impl LinearMap {
    /// The cost of `apply`: a product per entry that does not vanish identically, summed per row.
    pub fn apply_cost(&self) -> Cost {
        let columns = self.shape.1;
        let rows_used = (0..self.shape.0)
            .filter(|row| (0..columns).any(|c| self.entries.outputs.contains_key(&((row * columns + c) as BladeMask))))
            .count();
        let products = self.entries.outputs.len();
        Cost {
            multiplies: products,
            adds: products - rows_used,
            divisions: 0,
        }
    }

    /// The matrix for one slice of field values per parameter (the linear parameter's is not read): what
    /// the emitted `{name}_map` builds.
    ///
    /// # Panics
    /// If the number of slices is not the number of parameters.
    pub fn matrix(&self, arguments: &[&[f64]]) -> Vec<Vec<f64>> {
        assert_eq!(arguments.len(), self.fused.parameters.len(), "one slice per parameter");
        let inputs: Vec<f64> = arguments.iter().flat_map(|values| values.iter().copied()).collect();
        let entries = self.entries.evaluate(&inputs, &[]);
        let (rows, columns) = self.shape;
        (0..rows)
            .map(|row| {
                (0..columns)
                    .map(|column| {
                        entries
                            .get(&((row * columns + column) as BladeMask))
                            .copied()
                            .unwrap_or(0.0)
                    })
                    .collect()
            })
            .collect()
    }
}

/// The matrix of `algebra.expressions[index]` in its parameter `linear` (see [`LinearMap`]).
///
/// # Errors
/// Those of [`fuse`], and [`Error::NotLinear`] if the parameter does not enter every term exactly once.
pub fn linear_map(algebra: &Algebra, index: usize, linear: usize) -> Result<LinearMap, Error> {
    let expanded = expand(algebra, index)?;
    let declared = &algebra.expressions[index];
    let group = expanded.groups[linear].clone();
    if !enters_every_term_once(expanded.value.values(), &group) {
        return Err(Error::NotLinear {
            index,
            expression: declared.name.clone(),
            parameter: declared.parameters[linear].name.clone(),
        });
    }
    let rows = blades_and_signs(algebra, expanded.output);
    let columns = group.len();
    // Entry (i, j): the coefficient of the linear parameter's field j in the result's field i.
    let mut entries: BTreeMap<BladeMask, Polynomial> = BTreeMap::new();
    for (row, &(blade, sign)) in rows.iter().enumerate() {
        for (monomial, &c) in expanded.value.get(&blade).map(|p| &p.0).into_iter().flatten() {
            let (field, rest) = split_off(monomial, &group);
            let column = (field - group.start) as usize;
            let entry = entries.entry((row * columns + column) as BladeMask).or_default();
            entry.add_term(rest, c * Rational64::from(sign));
        }
    }
    entries.retain(|_, p| !p.0.is_empty());
    let others: Vec<Range<u32>> = (expanded.groups.iter().enumerate())
        .filter(|&(p, _)| p != linear)
        .map(|(_, g)| g.clone())
        .collect();
    let program = expanded.program(algebra, index, &entries, &others);
    Ok(LinearMap {
        fused: fuse_expanded(algebra, index, expanded),
        linear,
        shape: (rows.len(), columns),
        cost: program.cost(),
        entries: program,
    })
}

/// The blades a value of this type stores, with the sign of each field (storage order; the bare scalar is `1`).
pub(crate) fn blades_and_signs(algebra: &Algebra, kind: Output) -> Vec<(BladeMask, i64)> {
    match kind {
        Output::Type(ty) => algebra.types[ty].fields.iter().map(|f| (f.blade, f.sign)).collect(),
        Output::Scalar => vec![(0, 1)],
    }
}

/// Whether every term of every polynomial has exactly one factor among the inputs `group`.
fn enters_every_term_once<'p>(mut set: impl Iterator<Item = &'p Polynomial>, group: &Range<u32>) -> bool {
    set.all(|p| p.0.keys().all(|m| m.iter().filter(|v| group.contains(v)).count() == 1))
}

/// A monomial's one factor from `group`, and the product of the others.
fn split_off(monomial: &Monomial, group: &Range<u32>) -> (u32, Monomial) {
    let mut rest = monomial.clone();
    let at = rest
        .iter()
        .position(|v| group.contains(v))
        .expect("the group enters every term");
    let field = rest.remove(at);
    (field, rest)
}

/// Lowers each polynomial of `set` to a sum of terms, sharing work between them (see the module docs).
pub(crate) fn lower(builder: &mut Builder, set: &[&Polynomial], groups: &[Range<u32>]) -> Vec<Vec<Term>> {
    if set.iter().all(|p| p.0.is_empty()) {
        return vec![Vec::new(); set.len()];
    }
    let linear_in = |group: &Range<u32>| enters_every_term_once(set.iter().copied(), group);
    match groups.iter().filter(|g| linear_in(g)).min_by_key(|g| g.len()) {
        Some(group) => factored(builder, set, group, groups),
        None => sums_of_products(builder, set),
    }
}

/// `Σᵥ v · Qᵥ` over the fields `v` of the parameter `group`, which enters every term exactly once.
fn factored(builder: &mut Builder, set: &[&Polynomial], group: &Range<u32>, groups: &[Range<u32>]) -> Vec<Vec<Term>> {
    let mut distinct: BTreeMap<Polynomial, usize> = BTreeMap::new();
    let mut coefficients: Vec<Polynomial> = Vec::new();
    // Per polynomial: (field, scale, index of its normalised coefficient).
    let mut splits: Vec<Vec<(u32, Rational64, usize)>> = Vec::with_capacity(set.len());
    for polynomial in set {
        let mut by_field: BTreeMap<u32, Polynomial> = BTreeMap::new();
        for (monomial, &c) in &polynomial.0 {
            let (field, rest) = split_off(monomial, group);
            by_field.entry(field).or_default().add_term(rest, c);
        }
        let mut split = Vec::new();
        for (field, q) in by_field.into_iter().filter(|(_, q)| !q.0.is_empty()) {
            let scale = *q.0.values().next().expect("non-empty");
            let normalised = q.scaled(scale.recip());
            let index = *distinct.entry(normalised.clone()).or_insert_with(|| {
                coefficients.push(normalised);
                coefficients.len() - 1
            });
            split.push((field, scale, index));
        }
        splits.push(split);
    }
    let mut uses = vec![0usize; coefficients.len()];
    for &(_, _, index) in splits.iter().flatten() {
        uses[index] += 1;
    }
    // A factor that every use of a coefficient shares (the 2 of `2(bc − ad)` in a rotation matrix) is folded
    // into it, where its ±2 terms cost additions (doubled factors) instead of one multiply per use.
    for (index, coefficient) in coefficients.iter_mut().enumerate() {
        let mut scales = splits
            .iter()
            .flatten()
            .filter(|&&(_, _, q)| q == index)
            .map(|(_, s, _)| s.abs());
        let first = scales.next().expect("every coefficient is used");
        if scales.all(|s| s == first) && !first.is_one() {
            *coefficient = coefficient.scaled(first);
            for (_, scale, _) in splits.iter_mut().flatten().filter(|(_, _, q)| *q == index) {
                *scale /= first;
            }
        }
    }
    let first_field: BTreeMap<usize, u32> = splits.iter().flatten().rev().map(|&(f, _, q)| (q, f)).collect();
    let references: Vec<&Polynomial> = coefficients.iter().collect();
    let lowered = lower(builder, &references, groups);
    // A coefficient that is one product used once is written inline; any other becomes a local.
    let coefficient_values: Vec<Result<Term, Value>> = lowered
        .into_iter()
        .enumerate()
        .map(|(index, terms)| match <[Term; 1]>::try_from(terms) {
            Ok([term]) if term.factors.len() <= 1 || uses[index] == 1 => Ok(term),
            Ok([term]) => Err(builder.local(
                coefficient_name(builder, first_field[&index]),
                program::Definition::Sum(vec![term]),
            )),
            Err(terms) => Err(builder.local(
                coefficient_name(builder, first_field[&index]),
                program::Definition::Sum(terms),
            )),
        })
        .collect();
    splits
        .into_iter()
        .map(|split| {
            split
                .into_iter()
                .map(|(field, scale, index)| {
                    let input = Value::Input(Variable {
                        operand: Operand::Lhs,
                        field: field as usize,
                    });
                    match &coefficient_values[index] {
                        Ok(term) => Term {
                            coefficient: scale * term.coefficient,
                            factors: std::iter::once(input).chain(term.factors.iter().copied()).collect(),
                        },
                        Err(local) => Term {
                            coefficient: scale,
                            factors: vec![input, *local],
                        },
                    }
                })
                .collect()
        })
        .collect()
}

/// The name of a coefficient local: after the first field it multiplies.
fn coefficient_name(builder: &Builder, field: u32) -> String {
    let input = Value::Input(Variable {
        operand: Operand::Lhs,
        field: field as usize,
    });
    format!("per_{}", builder.value_name(input))
}

/// Each polynomial as a sum of products, a product used by several of them computed once.
fn sums_of_products(builder: &mut Builder, set: &[&Polynomial]) -> Vec<Vec<Term>> {
    let outputs: BTreeMap<BladeMask, Vec<(Vec<Value>, Rational64)>> = set
        .iter()
        .enumerate()
        .map(|(index, polynomial)| {
            let terms = polynomial
                .0
                .iter()
                .map(|(monomial, &c)| {
                    let factors = monomial
                        .iter()
                        .map(|&field| {
                            Value::Input(Variable {
                                operand: Operand::Lhs,
                                field: field as usize,
                            })
                        })
                        .collect();
                    (factors, c)
                })
                .collect();
            (index as BladeMask, terms)
        })
        .collect();
    let outer = std::mem::take(&mut builder.program.outputs);
    builder.products(&outputs);
    let sums = std::mem::replace(&mut builder.program.outputs, outer);
    sums.into_values().collect()
}
