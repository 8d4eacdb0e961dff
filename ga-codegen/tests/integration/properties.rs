//! Algebraic laws over random signatures (degenerate ones included, n ≤ 6) and random general
//! bilinear forms (n ≤ 5), and the emitted programs against the dense runtime evaluator. Integer
//! operands and dyadic metric entries keep every comparison exact, except where a non-dyadic
//! pseudoscalar square makes the polarity round.
use crate::common;

use std::sync::OnceLock;

use common::{form, Form};
use ga_codegen::blade::{grade, BladeNaming};
use ga_codegen::functions::Code;
use ga_codegen::{
    functions, Algebra, AlgebraDeclaration, Evaluator, Layout, Lowering, Operation, ScalarType, TypeDeclaration,
};
use proptest::prelude::*;

fn dense(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec((-3i32..=3).prop_map(f64::from), 1 << n)
}

fn form_and_operands(count: usize) -> impl Strategy<Value = (Form, Vec<Vec<f64>>)> {
    form().prop_flat_map(move |form| {
        let n = form.dimension();
        (Just(form), prop::collection::vec(dense(n), count))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn geometric_product_is_associative_and_distributive((form, m) in form_and_operands(3)) {
        let ev = form.evaluator();
        let gp = |a: &[f64], b: &[f64]| ev.binary(Operation::Geometric, a, b).unwrap();
        prop_assert_eq!(gp(&gp(&m[0], &m[1]), &m[2]), gp(&m[0], &gp(&m[1], &m[2])));
        let sum: Vec<f64> = m[1].iter().zip(&m[2]).map(|(x, y)| x + y).collect();
        let separate: Vec<f64> = gp(&m[0], &m[1]).iter().zip(gp(&m[0], &m[2])).map(|(x, y)| x + y).collect();
        prop_assert_eq!(gp(&m[0], &sum), separate);
    }

    #[test]
    fn reverse_is_an_anti_automorphism((form, m) in form_and_operands(2)) {
        let ev = form.evaluator();
        let reverse = |a: &[f64]| ev.unary(Operation::Reverse, a).unwrap();
        let left = reverse(&ev.binary(Operation::Geometric, &m[0], &m[1]).unwrap());
        let right = ev.binary(Operation::Geometric, &reverse(&m[1]), &reverse(&m[0])).unwrap();
        prop_assert_eq!(left, right);
    }

    #[test]
    fn sandwich_equals_two_geometric_products((form, m) in form_and_operands(2)) {
        let ev = form.evaluator();
        let ax = ev.binary(Operation::Geometric, &m[0], &m[1]).unwrap();
        let expected = ev.binary(Operation::Geometric, &ax, &ev.unary(Operation::Reverse, &m[0]).unwrap()).unwrap();
        prop_assert_eq!(ev.binary(Operation::Sandwich, &m[0], &m[1]).unwrap(), expected);
    }
}

/// On basis blades, the outer product, contractions and inner products are grade selections of the
/// geometric product (the definitions in the reference data's README).
#[test]
fn products_are_grade_selected_geometric_products_on_blades() {
    for squares in [
        vec![1, 1, 1],
        vec![0, 1, 1, 1],
        vec![1, -1, 0, 1, -1],
        vec![0, 0, 1, -1],
    ] {
        let ev = Evaluator::new(&squares).unwrap();
        let count = ev.blade_count();
        let unit = |b: usize| (0..count).map(|i| f64::from(u8::from(i == b))).collect::<Vec<f64>>();
        for a in 0..count {
            for b in 0..count {
                let (r, s) = (grade(a as u32) as i64, grade(b as u32) as i64);
                let gp = ev.binary(Operation::Geometric, &unit(a), &unit(b)).unwrap();
                let select = |k: i64| {
                    if k < 0 {
                        vec![0.0; count]
                    } else {
                        ev.grade_part(&gp, k as u32)
                    }
                };
                let zero_if = |c: bool, v: Vec<f64>| if c { vec![0.0; count] } else { v };
                let cases = [
                    (Operation::Outer, select(r + s)),
                    (Operation::LeftContraction, select(s - r)),
                    (Operation::RightContraction, select(r - s)),
                    (Operation::ScalarProduct, select(0)),
                    (Operation::FatDot, select((r - s).abs())),
                    (
                        Operation::HestenesInner,
                        zero_if(r == 0 || s == 0, select((r - s).abs())),
                    ),
                ];
                for (operation, expected) in cases {
                    let got = ev.binary(operation, &unit(a), &unit(b)).unwrap();
                    assert_eq!(got, expected, "{operation:?} of blades {a:b} and {b:b} in {squares:?}");
                }
            }
        }
    }
}

/// A random sparse type: a random subset of blades, some named with permuted (sign-flipped) factors.
fn sparse_type(n: usize) -> impl Strategy<Value = Vec<(u32, bool)>> {
    prop::collection::vec((0u32..(1 << n), any::<bool>()), 1..=(1usize << n).min(12)).prop_map(|mut blades| {
        blades.sort_by_key(|b| b.0);
        blades.dedup_by_key(|b| b.0);
        blades
    })
}

/// The name of a blade with its first two factors swapped (a sign flip), when it has two.
fn permuted_name(naming: &BladeNaming, basis_names: &[String], blade: u32) -> Option<String> {
    let factors: Vec<usize> = (0..basis_names.len()).filter(|i| blade & (1 << i) != 0).collect();
    if factors.len() < 2 {
        return None;
    }
    let mut order = factors.clone();
    order.swap(0, 1);
    let name = format!("e{}", order.iter().map(|i| i.to_string()).collect::<String>());
    (naming.parse(&name) == Ok((blade, -1))).then_some(name)
}

fn declaration(form: &Form, types: &[Vec<(u32, bool)>]) -> AlgebraDeclaration {
    let names: Vec<String> = (0..form.dimension()).map(|i| format!("e{i}")).collect();
    let naming = BladeNaming::new(&names);
    let mut declared: Vec<TypeDeclaration> = types
        .iter()
        .enumerate()
        .map(|(index, blades)| {
            let names = blades
                .iter()
                .map(|&(b, permute)| {
                    permute
                        .then(|| permuted_name(&naming, &names, b))
                        .flatten()
                        .unwrap_or_else(|| naming.name(b))
                })
                .collect();
            TypeDeclaration {
                name: format!("T{index}"),
                layout: Layout::Blades(names),
            }
        })
        .collect();
    declared.push(TypeDeclaration {
        name: "Multivector".to_string(),
        layout: Layout::All,
    });
    let (basis, metric) = form.basis(&names);
    AlgebraDeclaration {
        scalar: ScalarType::F64,
        basis,
        metric,
        types: declared,
        operations: None,
        lowering: vec![],
        expressions: vec![],
    }
}

/// Dense coefficients of a sparse value (field = sign × canonical coefficient).
fn to_dense(algebra: &Algebra, ty: usize, values: &[f64]) -> Vec<f64> {
    let mut dense = vec![0.0; 1 << algebra.dimension()];
    for (field, &value) in algebra.types[ty].fields.iter().zip(values) {
        dense[field.blade as usize] = field.sign as f64 * value;
    }
    dense
}

/// The dense value of a function's program output, read through its result type's field signs.
fn program_output(function: &functions::Function, lhs: &[f64], rhs: &[f64], n: usize) -> Vec<f64> {
    let mut dense = vec![0.0; 1 << n];
    for (blade, value) in function.code.evaluate(lhs, rhs) {
        dense[blade as usize] = value;
    }
    dense
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn emitted_programs_equal_the_evaluator(
        (form, types, values) in form().prop_flat_map(|form| {
            let n = form.dimension();
            (Just(form), prop::collection::vec(sparse_type(n), 2), prop::collection::vec((-3i32..=3).prop_map(f64::from), 12))
        })
    ) {
        let algebra = Algebra::new(&declaration(&form, &types)).unwrap();
        let ev = Evaluator::of(&algebra);
        let n = form.dimension();
        let lhs = &values[..algebra.types[0].fields.len()];
        let rhs = &values[..algebra.types[1].fields.len()];
        let (a, b) = (to_dense(&algebra, 0, lhs), to_dense(&algebra, 1, rhs));
        // Every product unrolled (these types are small) and lowered to tables.
        let mut tabled = declaration(&form, &types);
        tabled.lowering = Operation::ALL.into_iter().filter(|op| op.is_binary()).map(|op| (op, Lowering::Table)).collect();
        let tabled = Algebra::new(&tabled).unwrap();
        // `transform` equals these only for unit versors: see tests/transform.rs.
        for operation in Operation::ALL.into_iter().filter(|&op| op.is_binary() && op != Operation::Transform) {
            let expected = ev.binary(operation, &a, &b).unwrap();
            let expected = if operation == Operation::ScalarProduct { ev.grade_part(&expected, 0) } else { expected };
            let function = functions::binary(&algebra, operation, 0, 1).unwrap();
            prop_assert!(matches!(function.code, Code::Unrolled(_)));
            prop_assert_eq!(&program_output(&function, lhs, rhs, n), &expected, "{:?}", operation);
            let function = functions::binary(&tabled, operation, 0, 1).unwrap();
            prop_assert!(matches!(function.code, Code::Table(_)));
            prop_assert_eq!(program_output(&function, lhs, rhs, n), expected, "{:?} by tables", operation);
        }
        for operation in [Operation::Reverse, Operation::Involute, Operation::Conjugate, Operation::RightComplement, Operation::LeftComplement] {
            for function in functions::unary(&algebra, operation, 0).unwrap() {
                prop_assert_eq!(program_output(&function, lhs, &[], n), ev.unary(operation, &a).unwrap(), "{:?}", operation);
            }
        }
        // Divided by a pseudoscalar square that need not be a power of two: equal to rounding.
        for function in functions::unary(&algebra, Operation::Polarity, 0).unwrap() {
            let (got, expected) = (program_output(&function, lhs, &[], n), ev.unary(Operation::Polarity, &a).unwrap());
            for (g, e) in got.iter().zip(&expected) {
                prop_assert!((g - e).abs() <= 1e-9 * (1.0 + e.abs()), "polarity: {:?} vs {:?}", got, expected);
            }
        }
        for function in functions::unary(&algebra, Operation::Grade, 0).unwrap() {
            let k: u32 = function.method.trim_start_matches("grade_").parse().unwrap();
            prop_assert_eq!(program_output(&function, lhs, &[], n), ev.grade_part(&a, k));
        }
        let norm = functions::unary(&algebra, Operation::NormSquared, 0).unwrap();
        prop_assert_eq!(program_output(&norm[0], lhs, &[], n)[0], ev.norm_squared(&a).unwrap());
    }
}

/// The sandwich of every pair of standard PGA and CGA types, with its algebra.
fn standard_sandwiches() -> &'static [(Algebra, Vec<functions::Function>)] {
    static SANDWICHES: OnceLock<Vec<(Algebra, Vec<functions::Function>)>> = OnceLock::new();
    SANDWICHES.get_or_init(|| {
        [common::pga(), common::cga(), common::null_cga()]
            .iter()
            .map(|declaration| {
                let algebra = Algebra::new(declaration).unwrap();
                let count = algebra.types.len();
                let sandwiches = (0..count * count)
                    .map(|pair| functions::binary(&algebra, Operation::Sandwich, pair / count, pair % count).unwrap())
                    .collect();
                (algebra, sandwiches)
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Every sandwich of the standard PGA and CGA types (where the commutator form `(a ~a) x + a C`
    /// often wins over the fused cubic) against the evaluator, on arbitrary versors: exact.
    #[test]
    fn sandwiches_of_the_standard_types_equal_the_evaluator(values in prop::collection::vec((-3i32..=3).prop_map(f64::from), 64)) {
        for (algebra, sandwiches) in standard_sandwiches() {
            let ev = Evaluator::of(algebra);
            for function in sandwiches {
                let (lhs, rhs) = (function.lhs, function.rhs.unwrap());
                let (a, x) = (&values[..algebra.types[lhs].fields.len()], &values[32..32 + algebra.types[rhs].fields.len()]);
                let expected = ev.binary(Operation::Sandwich, &to_dense(algebra, lhs, a), &to_dense(algebra, rhs, x)).unwrap();
                prop_assert_eq!(program_output(function, a, x, algebra.dimension()), expected, "{} sandwich {}", &algebra.types[lhs].name, &algebra.types[rhs].name);
            }
        }
    }
}
