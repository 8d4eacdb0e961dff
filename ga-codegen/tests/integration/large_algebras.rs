//! Cl(9,6), Cl(4,4) and Cl(8,2) with scalars, vectors and bivectors: every emitted program against
//! the dense evaluator on random integer inputs (exact). The compiled code of the same declarations
//! is tested in ga-macros/tests/integration/large_algebras.rs.
use crate::common;

use std::sync::OnceLock;

use ga_codegen::{functions, Algebra, AlgebraDeclaration, Evaluator, Operation, ScalarType};
use proptest::prelude::*;

/// The operations that keep grades 0 to 2 (so the three types hold every result), but `transform`,
/// which needs unit versors (tested on them in the ga-macros test).
const OPERATIONS: [Operation; 6] = [
    Operation::Commutator,
    Operation::LeftContraction,
    Operation::RightContraction,
    Operation::ScalarProduct,
    Operation::HestenesInner,
    Operation::FatDot,
];

struct Compiled {
    squares: Vec<i64>,
    algebra: Algebra,
    /// Every binary function, with its operation.
    functions: Vec<(Operation, functions::Function)>,
}

fn compile(positive: usize, negative: usize) -> Compiled {
    let squares: Vec<i64> = [vec![1; positive], vec![-1; negative]].concat();
    let names: Vec<String> = (1..=squares.len()).map(|i| format!("e{i}")).collect();
    let basis: Vec<(&str, i64)> = names.iter().map(String::as_str).zip(squares.iter().copied()).collect();
    let declaration = AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis: common::basis(&basis),
        metric: None,
        types: vec![
            common::grades("Scalar", &[0]),
            common::grades("Vector", &[1]),
            common::grades("Bivector", &[2]),
        ],
        operations: Some(OPERATIONS.to_vec()),
        lowering: vec![],
        expressions: vec![],
    };
    let algebra = Algebra::new(&declaration).unwrap();
    let mut compiled = Vec::new();
    for operation in OPERATIONS {
        for lhs in 0..3 {
            for rhs in 0..3 {
                compiled.push((operation, functions::binary(&algebra, operation, lhs, rhs).unwrap()));
            }
        }
    }
    Compiled {
        squares,
        algebra,
        functions: compiled,
    }
}

fn cl96() -> &'static Compiled {
    static COMPILED: OnceLock<Compiled> = OnceLock::new();
    COMPILED.get_or_init(|| compile(9, 6))
}

fn cl44() -> &'static Compiled {
    static COMPILED: OnceLock<Compiled> = OnceLock::new();
    COMPILED.get_or_init(|| compile(4, 4))
}

fn cl82() -> &'static Compiled {
    static COMPILED: OnceLock<Compiled> = OnceLock::new();
    COMPILED.get_or_init(|| compile(8, 2))
}

fn check(compiled: &Compiled, values: &[f64]) -> Result<(), TestCaseError> {
    let algebra = &compiled.algebra;
    let evaluator = Evaluator::new(&compiled.squares).unwrap();
    let blades = evaluator.blade_count();
    let fields = |ty: usize, offset: usize| &values[offset..offset + algebra.types[ty].fields.len()];
    let dense = |ty: usize, values: &[f64]| {
        let mut dense = vec![0.0; blades];
        for (field, &value) in algebra.types[ty].fields.iter().zip(values) {
            dense[field.blade as usize] = field.sign as f64 * value;
        }
        dense
    };
    for (operation, function) in &compiled.functions {
        let rhs = function.rhs.unwrap();
        let (a, b) = (fields(function.lhs, 0), fields(rhs, 105));
        let expected = evaluator
            .binary(*operation, &dense(function.lhs, a), &dense(rhs, b))
            .unwrap();
        let expected = if *operation == Operation::ScalarProduct {
            evaluator.grade_part(&expected, 0)
        } else {
            expected
        };
        let mut got = vec![0.0; blades];
        for (blade, value) in function.code.evaluate(a, b) {
            got[blade as usize] = value;
        }
        prop_assert_eq!(got, expected, "{:?} {} {}", operation, function.lhs, rhs);
    }
    Ok(())
}

fn values() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec((-3i32..=3).prop_map(f64::from), 210)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn cl96_programs_equal_the_evaluator(values in values()) {
        check(cl96(), &values)?;
    }

    #[test]
    fn cl44_programs_equal_the_evaluator(values in values()) {
        check(cl44(), &values)?;
    }

    #[test]
    fn cl82_programs_equal_the_evaluator(values in values()) {
        check(cl82(), &values)?;
    }
}
