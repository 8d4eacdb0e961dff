//! The catalogue of emitted functions: for each operation and type (pair), its expansion, result
//! type and lowered code (unrolled, or tables for products too big to unroll). Emission prints these; [`cost`] reports their exact operation counts.

use num_traits::Zero;

use crate::algebra::{Algebra, SparseType};
use crate::blade::{grade, BladeMask};
use crate::declaration::Lowering;
use crate::error::Error;
use crate::expand::{self, Expansion, Norm, Operand, Side, Variable};
use crate::operation::Operation;
use crate::product::Rules;
use crate::program::{self, Cost, Program};
use crate::table::{too_big_to_expand, Table, MAX_UNROLLED_LOCALS, MAX_UNROLLED_TERMS};

/// What a function returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// A declared type (index into `Algebra::types`).
    Type(usize),
    /// The bare scalar (`scalar_product`, `norm_squared`).
    Scalar,
}

/// How the program's result becomes the return value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Finish {
    /// The outputs are the result's coefficients.
    Coefficients,
    /// `inverse`: the program computes `a ~a` (a scalar); the result is `~a / (a ~a)`.
    DivideReverseByNorm,
}

/// How a function computes its outputs.
#[derive(Clone, Debug)]
pub enum Code {
    /// Straight-line code: hoisted locals, then one sum per output blade.
    Unrolled(Program),
    /// Constant tables and a loop per stage, for products too big to unroll (see [`crate::table`]).
    Table(Table),
}

impl Code {
    /// Runs the code on numeric operands (field values in storage order), output blade by blade: what
    /// the emitted function computes, before the result's field signs.
    pub fn evaluate(&self, lhs: &[f64], rhs: &[f64]) -> std::collections::BTreeMap<BladeMask, f64> {
        match self {
            Code::Unrolled(program) => program.evaluate(lhs, rhs),
            Code::Table(table) => table.evaluate(lhs, rhs),
        }
    }

    /// The exact operation count of the code.
    pub fn cost(&self) -> Cost {
        match self {
            Code::Unrolled(program) => program.cost(),
            Code::Table(table) => table.cost(),
        }
    }
}

#[derive(Clone, Debug)]
/// One emitted function: an operation on a type (pair), with its lowered program and cost.
pub struct Function {
    /// The operation, or `None` for the sum and difference (always emitted).
    pub operation: Option<Operation>,
    /// The method name (`geometric`, `grade_2`, …).
    pub method: String,
    /// The left (or only) operand's type, an index into `Algebra::types`.
    pub lhs: usize,
    /// The right operand's type (an index into `Algebra::types`), or `None` for a unary operation.
    pub rhs: Option<usize>,
    /// What the function returns.
    pub output: Output,
    /// The code that computes the outputs.
    pub code: Code,
    /// How the program's outputs become the return value.
    pub finish: Finish,
    /// The exact operation count of the program and the finish.
    pub cost: Cost,
}

/// The build work of one unrolled multiply, in table entries: an unrolled function is lowered with common
/// subexpressions and emitted as source rustc checks term by term, a table entry is eight bytes of one literal.
/// Measured in debug builds on 2026-11-27: 6.2 million table entries (a 10-dimensional `all` with every
/// operation) took 23 s, 302 000 unrolled multiplies and 298 000 entries (ten types of Cl(5,1) with every
/// operation, now refused) 55 s.
pub const UNROLLED_MULTIPLY_WORK: usize = 32;

/// The most build work ([`Function::build_work`]) a declaration's functions may take together: about 45 s for a
/// debug build on a 2-core machine (estimated from the two measurements of [`UNROLLED_MULTIPLY_WORK`], 3.7 to
/// 5.5 µs per unit), where the macro itself runs unoptimised.
pub const MAX_BUILD_WORK: usize = 8_000_000;

impl Function {
    /// What building this function costs, in table entries: its entries if tabled, else
    /// [`UNROLLED_MULTIPLY_WORK`] per multiply (and per add, for a function without multiplies such as a sum).
    pub fn build_work(&self) -> usize {
        match &self.code {
            Code::Table(table) => table.entries(),
            Code::Unrolled(_) => UNROLLED_MULTIPLY_WORK * self.cost.multiplies.max(self.cost.adds),
        }
    }
}

/// Lowers with the names of the operands' fields and of the algebra's blades.
fn lower_with(
    algebra: &Algebra,
    lhs: &SparseType,
    rhs: Option<&SparseType>,
    lower: impl FnOnce(&program::Names) -> Program,
) -> Program {
    let field_name = |v: Variable| match v.operand {
        Operand::Lhs => lhs.fields[v.field].name.clone(),
        Operand::Rhs => rhs.map_or_else(String::new, |r| r.fields[v.field].name.clone()),
    };
    let blade_name = |blade| algebra.blade_name(blade);
    lower(&program::Names {
        field: &field_name,
        blade: &blade_name,
    })
}

fn lower(algebra: &Algebra, expansion: &Expansion, lhs: &SparseType, rhs: Option<&SparseType>) -> Program {
    lower_with(algebra, lhs, rhs, |names| program::lower(expansion, names))
}

/// The smallest declared type holding `blades` (any type for an identically zero result).
fn result_type(
    algebra: &Algebra,
    blades: &[BladeMask],
    describe: impl Fn() -> (String, String, String),
) -> Result<usize, Error> {
    let holding = algebra
        .types
        .iter()
        .enumerate()
        .filter(|(_, t)| t.holds(blades))
        .min_by_key(|(_, t)| t.fields.len());
    match holding {
        Some((index, _)) => Ok(index),
        None => {
            let (operation, lhs, rhs) = describe();
            let blades = blades.iter().map(|&b| algebra.blade_name(b)).collect();
            Err(Error::NoResultType {
                operation,
                lhs,
                rhs,
                blades,
            })
        }
    }
}

/// The function `lhs.operation(rhs)` for a binary operation.
pub fn binary(algebra: &Algebra, operation: Operation, lhs: usize, rhs: usize) -> Result<Function, Error> {
    if operation == Operation::Transform {
        return transform(algebra, lhs, rhs);
    }
    let (left, right) = (&algebra.types[lhs], &algebra.types[rhs]);
    if operation == Operation::Sandwich && too_big_to_expand(left, right) {
        return sandwich_by_reach(algebra, operation, (lhs, rhs), None);
    }
    let expansion = match operation {
        Operation::Sandwich => expand::sandwich(algebra, left, right),
        _ => expand::binary(algebra, operation, left, right),
    };
    let output = if operation == Operation::ScalarProduct {
        Output::Scalar
    } else {
        let describe = || (operation.name().to_string(), left.name.clone(), right.name.clone());
        Output::Type(result_type(algebra, &expansion.blades(), describe)?)
    };
    let blades = expansion.blades();
    let table = || match operation {
        Operation::Sandwich => Table::sandwich(algebra, left, right, Some(&blades)),
        _ => Table::bilinear(&expansion),
    };
    let declared = algebra.declared_lowering(operation);
    if declared == Some(Lowering::Table) || (declared.is_none() && expansion.term_count() > MAX_UNROLLED_TERMS) {
        return Ok(tabled(operation, (lhs, rhs), output, table()));
    }
    let mut function = finish(
        algebra,
        Some(operation),
        operation.name().to_string(),
        lhs,
        Some(rhs),
        output,
        &expansion,
    );
    if operation == Operation::Sandwich {
        use_cheapest_commutator_form(algebra, &mut function, (left, right), Norm::General, &blades);
    }
    if declared.is_none() && too_many_locals(&function) {
        return Ok(tabled(operation, (lhs, rhs), output, table()));
    }
    Ok(function)
}

/// Whether unrolled code would nest more `let`s than rustc's debug builds take.
fn too_many_locals(function: &Function) -> bool {
    matches!(&function.code, Code::Unrolled(program) if program.locals.len() > MAX_UNROLLED_LOCALS)
}

/// A sandwich (or a transform, keeping the operand's `grades`) too big to expand exactly: tabled, with the
/// blades its products reach (see [`MAX_EXACT_SANDWICH_PRODUCTS`](crate::table::MAX_EXACT_SANDWICH_PRODUCTS)).
fn sandwich_by_reach(
    algebra: &Algebra,
    operation: Operation,
    (lhs, rhs): (usize, usize),
    grades: Option<&[u32]>,
) -> Result<Function, Error> {
    let (left, right) = (&algebra.types[lhs], &algebra.types[rhs]);
    let declared_unrolled = algebra
        .lowering
        .iter()
        .position(|&lowering| lowering == (operation, Lowering::Unrolled));
    if let Some(index) = declared_unrolled {
        return Err(Error::TooBigToUnroll {
            index,
            name: operation.name().to_string(),
            lhs: left.name.clone(),
            rhs: right.name.clone(),
            products: left.fields.len() * left.fields.len() * right.fields.len(),
        });
    }
    let mut table = Table::sandwich(algebra, left, right, None);
    if let Some(grades) = grades {
        let kept: Vec<BladeMask> = table
            .output_blades()
            .iter()
            .copied()
            .filter(|&b| grades.contains(&grade(b)))
            .collect();
        table = table.keeping(&kept);
    }
    let describe = || (operation.name().to_string(), left.name.clone(), right.name.clone());
    let output = Output::Type(result_type(algebra, table.output_blades(), describe)?);
    Ok(tabled(operation, (lhs, rhs), output, table))
}

/// A product lowered to `table`.
fn tabled(operation: Operation, (lhs, rhs): (usize, usize), output: Output, table: Table) -> Function {
    let cost = table.cost();
    Function {
        operation: Some(operation),
        method: operation.name().to_string(),
        lhs,
        rhs: Some(rhs),
        output,
        code: Code::Table(table),
        finish: Finish::Coefficients,
        cost,
    }
}

/// `lhs.transform(rhs)`: the sandwich of a unit versor, `a x ~a` with `a ~a = 1`.
///
/// A unit versor maps each grade to itself, so only the sandwich's blades of the operand's grades
/// are kept, and the program is the cheapest of three that agree whenever `a ~a = 1`: the fused
/// sandwich, `x + a (x ~a − ~a x)` and `x + (a x − x a) ~a`. For a type whose `a ~a` has no scalar
/// part (so it is never 1) the transform is the sandwich.
fn transform(algebra: &Algebra, lhs: usize, rhs: usize) -> Result<Function, Error> {
    let (left, right) = (&algebra.types[lhs], &algebra.types[rhs]);
    let unit = !expand::norm_squared(algebra, left).outputs.is_empty();
    let grades: Vec<u32> = right.fields.iter().map(|f| grade(f.blade)).collect();
    if too_big_to_expand(left, right) {
        return sandwich_by_reach(algebra, Operation::Transform, (lhs, rhs), unit.then_some(&grades));
    }
    let mut sandwich = expand::sandwich(algebra, left, right);
    let norm = if unit {
        sandwich.outputs.retain(|&blade, _| grades.contains(&grade(blade)));
        Norm::Unit
    } else {
        Norm::General
    };
    let blades = sandwich.blades();
    let describe = || {
        (
            Operation::Transform.name().to_string(),
            left.name.clone(),
            right.name.clone(),
        )
    };
    let output = Output::Type(result_type(algebra, &blades, describe)?);
    let declared = algebra.declared_lowering(Operation::Transform);
    let table = || {
        tabled(
            Operation::Transform,
            (lhs, rhs),
            output,
            Table::sandwich(algebra, left, right, Some(&blades)),
        )
    };
    if declared == Some(Lowering::Table) || (declared.is_none() && sandwich.term_count() > MAX_UNROLLED_TERMS) {
        return Ok(table());
    }
    let mut function = finish(
        algebra,
        Some(Operation::Transform),
        Operation::Transform.name().to_string(),
        lhs,
        Some(rhs),
        output,
        &sandwich,
    );
    use_cheapest_commutator_form(algebra, &mut function, (left, right), norm, &blades);
    if declared.is_none() && too_many_locals(&function) {
        return Ok(table());
    }
    Ok(function)
}

/// Replaces the program of a sandwich (or transform) `function` of `operand` by `versor` with a
/// commutator form of it, on either side, if one costs fewer multiplies (or as many and fewer adds).
fn use_cheapest_commutator_form(
    algebra: &Algebra,
    function: &mut Function,
    (versor, operand): (&SparseType, &SparseType),
    norm: Norm,
    outputs: &[BladeMask],
) {
    for side in [Side::Left, Side::Right] {
        let form = expand::commutator_form(algebra, versor, operand, side, norm, outputs);
        let program = lower_with(algebra, versor, Some(operand), |names| {
            program::lower_commutator_form(&form, names)
        });
        let cost = program.cost();
        if (cost.multiplies, cost.adds) < (function.cost.multiplies, function.cost.adds) {
            (function.code, function.cost) = (Code::Unrolled(program), cost);
        }
    }
}

fn finish(
    algebra: &Algebra,
    operation: Option<Operation>,
    method: String,
    lhs: usize,
    rhs: Option<usize>,
    output: Output,
    expansion: &Expansion,
) -> Function {
    let program = lower(algebra, expansion, &algebra.types[lhs], rhs.map(|r| &algebra.types[r]));
    let cost = program.cost();
    Function {
        operation,
        method,
        lhs,
        rhs,
        output,
        code: Code::Unrolled(program),
        finish: Finish::Coefficients,
        cost,
    }
}

/// The functions a unary operation emits on a type: none (polarity on a degenerate metric, inverse
/// where `a ~a` is not a scalar), one, or one per grade (grade projection).
pub fn unary(algebra: &Algebra, operation: Operation, ty: usize) -> Result<Vec<Function>, Error> {
    let declared = &algebra.types[ty];
    let typed = |method: String, expansion: Expansion| -> Result<Function, Error> {
        let describe = || (method.clone(), declared.name.clone(), String::new());
        let output = Output::Type(result_type(algebra, &expansion.blades(), describe)?);
        Ok(finish(
            algebra,
            Some(operation),
            method.clone(),
            ty,
            None,
            output,
            &expansion,
        ))
    };
    match operation {
        Operation::Polarity if Rules::new(&algebra.metric).pseudoscalar_square().is_zero() => Ok(vec![]),
        Operation::Reverse
        | Operation::Involute
        | Operation::Conjugate
        | Operation::RightComplement
        | Operation::LeftComplement
        | Operation::Polarity => Ok(vec![typed(
            operation.name().to_string(),
            expand::unary(algebra, operation, declared),
        )?]),
        Operation::Grade => {
            let mut grades: Vec<u32> = declared.fields.iter().map(|f| grade(f.blade)).collect();
            grades.sort_unstable();
            grades.dedup();
            grades
                .into_iter()
                .map(|k| typed(format!("grade_{k}"), expand::grade_part(declared, k)))
                .collect()
        }
        Operation::NormSquared => {
            let product = expand::norm_squared(algebra, declared);
            Ok(vec![finish(
                algebra,
                Some(operation),
                operation.name().to_string(),
                ty,
                None,
                Output::Scalar,
                &product,
            )])
        }
        Operation::Inverse => {
            let product = expand::times_own_reverse(algebra, declared);
            if product.blades() != [0] {
                return Ok(vec![]);
            }
            let mut function = finish(
                algebra,
                Some(operation),
                operation.name().to_string(),
                ty,
                None,
                Output::Type(ty),
                &product,
            );
            function.finish = Finish::DivideReverseByNorm;
            // One division for 1/(a ~a), then one multiply per coefficient.
            function.cost = function.cost
                + Cost {
                    multiplies: declared.fields.len(),
                    adds: 0,
                    divisions: 1,
                };
            Ok(vec![function])
        }
        _ => Ok(vec![]),
    }
}

/// `lhs + rhs` or `lhs - rhs`, where a declared type holds both operands' blades.
pub fn sum(algebra: &Algebra, lhs: usize, rhs: usize, subtract: bool) -> Option<Function> {
    let expansion = expand::sum(&algebra.types[lhs], &algebra.types[rhs], subtract);
    let mut blades: Vec<BladeMask> = algebra.types[lhs].fields.iter().map(|f| f.blade).collect();
    blades.extend(algebra.types[rhs].fields.iter().map(|f| f.blade));
    let output = result_type(algebra, &blades, Default::default).ok()?;
    let method = if subtract { "sub" } else { "add" };
    Some(finish(
        algebra,
        None,
        method.to_string(),
        lhs,
        Some(rhs),
        Output::Type(output),
        &expansion,
    ))
}

/// The exact cost of `lhs.operation(rhs)` (or of the unary `lhs.operation()` when `rhs` is `None`;
/// for grade projection, the sum over all grades). `Ok(None)` if no such function is emitted.
pub fn cost(algebra: &Algebra, operation: Operation, lhs: &str, rhs: Option<&str>) -> Result<Option<Cost>, Error> {
    let index = |name: &str| algebra.types.iter().position(|t| t.name == name);
    let Some(lhs) = index(lhs) else { return Ok(None) };
    match (operation.is_binary(), rhs) {
        (true, Some(rhs)) => match index(rhs) {
            Some(rhs) => Ok(Some(binary(algebra, operation, lhs, rhs)?.cost)),
            None => Ok(None),
        },
        (false, None) => {
            let functions = unary(algebra, operation, lhs)?;
            Ok((!functions.is_empty()).then(|| functions.iter().fold(Cost::default(), |total, f| total + f.cost)))
        }
        _ => Ok(None),
    }
}
