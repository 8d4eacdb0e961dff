//! `transform` against `sandwich` on random unit versors (products of normalised vectors, so that
//! `a ~a = 1`): the two agree to rounding, in PGA, in CGA on both bases, and in random signatures and
//! bilinear forms with the full multivector as the versor type.
use crate::common;

use ga_codegen::blade::BladeMask;
use ga_codegen::{functions, Algebra, AlgebraDeclaration, Evaluator, Layout, Lowering, Operation, TypeDeclaration};
use proptest::prelude::*;

/// A unit versor from raw vectors (dense, 2ⁿ coefficients each, only the grade-1 entries of the
/// `allowed` basis vectors read), each normalised to square ±1. `None` if a vector is nearly null or
/// the squares multiply to −1 (then `a ~a = −1`).
fn unit_versor(evaluator: &Evaluator, raw: &[Vec<f64>], allowed: impl Fn(usize) -> bool) -> Option<Vec<f64>> {
    let blades = evaluator.blade_count();
    let mut versor = vec![0.0; blades];
    versor[0] = 1.0;
    let mut sign = 1.0;
    for coefficients in raw {
        let mut v = vec![0.0; blades];
        for bit in (0..blades.trailing_zeros() as usize).filter(|&bit| allowed(bit)) {
            v[1 << bit] = coefficients[1 << bit];
        }
        let square = evaluator.binary(Operation::Geometric, &v, &v).unwrap()[0];
        if square.abs() < 0.25 {
            return None;
        }
        sign *= square.signum();
        let v: Vec<f64> = v.iter().map(|c| c / square.abs().sqrt()).collect();
        versor = evaluator.binary(Operation::Geometric, &versor, &v).unwrap();
    }
    (sign > 0.0).then_some(versor)
}

/// The fields of a declared type holding `dense`, or `None` if it has blades outside the type.
fn fields(algebra: &Algebra, ty: usize, dense: &[f64]) -> Option<Vec<f64>> {
    let declared = &algebra.types[ty];
    let outside = dense
        .iter()
        .enumerate()
        .any(|(blade, &c)| c.abs() > 1e-12 && declared.field_of(blade as BladeMask).is_none());
    if outside {
        return None;
    }
    Some(
        declared
            .fields
            .iter()
            .map(|f| f.sign as f64 * dense[f.blade as usize])
            .collect(),
    )
}

fn assert_transform_is_sandwich(algebra: &Algebra, versor: &str, operand: &str, a: &[f64], x: &[f64]) {
    let index = |name: &str| algebra.types.iter().position(|t| t.name == name).unwrap();
    let (lhs, rhs) = (index(versor), index(operand));
    let transform = functions::binary(algebra, Operation::Transform, lhs, rhs).unwrap();
    let sandwich = functions::binary(algebra, Operation::Sandwich, lhs, rhs).unwrap();
    let (got, expected) = (transform.code.evaluate(a, x), sandwich.code.evaluate(a, x));
    let scale = expected.values().fold(1.0f64, |m, v| m.max(v.abs()));
    for (blade, value) in &expected {
        let transformed = got.get(blade).copied().unwrap_or(0.0);
        assert!(
            (transformed - value).abs() <= 1e-9 * scale,
            "{versor} transform {operand}, blade {blade:b}: {transformed} vs {value}"
        );
    }
    assert!(got.keys().all(|blade| expected.contains_key(blade)));
}

fn raw_vectors(n: usize, count: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Vec<Vec<f64>>> {
    prop::collection::vec(prop::collection::vec(-3.0f64..3.0, 1 << n), count)
}

fn operand(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-3.0f64..3.0, 1 << n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Motors are products of two or four unit planes.
    #[test]
    fn pga_motors(raw in raw_vectors(4, 2..=4), x in operand(4)) {
        let algebra = Algebra::new(&common::pga()).unwrap();
        let evaluator = Evaluator::of(&algebra);
        let mut raw = raw;
        raw.truncate(raw.len() / 2 * 2);
        // Planes n + d e0 with |n| = 1: the e0 part never makes the square vanish.
        let motor = unit_versor(&evaluator, &raw, |_| true);
        prop_assume!(motor.is_some());
        let motor = motor.unwrap();
        let a = fields(&algebra, algebra.types.iter().position(|t| t.name == "Motor").unwrap(), &motor).unwrap();
        for operand in ["Point", "Line", "Plane", "Motor"] {
            let ty = algebra.types.iter().position(|t| t.name == operand).unwrap();
            let values: Vec<f64> = x[..algebra.types[ty].fields.len()].to_vec();
            assert_transform_is_sandwich(&algebra, "Motor", operand, &a, &values);
        }
    }

    /// Even versors of CGA on both bases; on the null basis also rigid motors (products of planes,
    /// which have no n0 component).
    #[test]
    fn cga_versors(raw in raw_vectors(5, 2..=4), x in operand(5)) {
        let mut raw = raw;
        raw.truncate(raw.len() / 2 * 2);
        for declaration in [common::cga(), common::null_cga()] {
            let algebra = Algebra::new(&declaration).unwrap();
            let evaluator = Evaluator::of(&algebra);
            let even = algebra.types.iter().position(|t| t.name == "Even").unwrap();
            let Some(versor) = unit_versor(&evaluator, &raw, |_| true) else { continue };
            let a = fields(&algebra, even, &versor).unwrap();
            let vector = algebra.types.iter().position(|t| t.name == "Vector").unwrap();
            let values = x[..algebra.types[vector].fields.len()].to_vec();
            assert_transform_is_sandwich(&algebra, "Even", "Vector", &a, &values);
        }
        let algebra = Algebra::new(&common::null_cga()).unwrap();
        let evaluator = Evaluator::of(&algebra);
        let n0 = 3;
        if let Some(motor) = unit_versor(&evaluator, &raw, |bit| bit != n0) {
            let a = fields(&algebra, algebra.types.iter().position(|t| t.name == "Motor").unwrap(), &motor).unwrap();
            assert_transform_is_sandwich(&algebra, "Motor", "Vector", &a, &x[..5]);
        }
    }

    /// Any signature or form, the full multivector as the versor type, a random operand type.
    #[test]
    fn random_algebras(
        (form, raw, x, grades) in common::form().prop_flat_map(|form| {
            let n = form.dimension();
            (Just(form), raw_vectors(n, 1..=3), operand(n), prop::collection::btree_set(0u32..=n as u32, 1..=2))
        })
    ) {
        let types = vec![
            common::grades("Operand", &grades.iter().copied().collect::<Vec<_>>()),
            TypeDeclaration { name: "Multivector".to_string(), layout: Layout::All },
        ];
        let declaration = form.declaration(types, Some(vec![Operation::Sandwich, Operation::Transform]));
        let algebra = Algebra::new(&declaration).unwrap();
        let evaluator = Evaluator::of(&algebra);
        let versor = unit_versor(&evaluator, &raw, |_| true);
        prop_assume!(versor.is_some());
        let versor = versor.unwrap();
        let a = fields(&algebra, 1, &versor).unwrap();
        let values = x[..algebra.types[0].fields.len()].to_vec();
        assert_transform_is_sandwich(&algebra, "Multivector", "Operand", &a, &values);
        // And both lowered to tables (two products each).
        let tabled = AlgebraDeclaration {
            lowering: vec![(Operation::Sandwich, Lowering::Table), (Operation::Transform, Lowering::Table)],
            expressions: vec![],
            ..declaration
        };
        assert_transform_is_sandwich(&Algebra::new(&tabled).unwrap(), "Multivector", "Operand", &a, &values);
    }
}
