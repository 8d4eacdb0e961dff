//! CGA on the null basis e1, e2, e3, n0, ninf (n0 · ninf = −1) against the diagonal Cl(4,1) on
//! e1, …, e5, through the change of basis ninf = e4 + e5, n0 = (e5 − e4)/2, extended to blades as an
//! outermorphism Φ. Every metric operation commutes with Φ; the metric-free ones follow the basis
//! pseudoscalar, which Φ maps to −I (the change of basis has determinant −1).
use crate::common;

use ga_codegen::metric::Metric;
use ga_codegen::{functions, Algebra, Cost, Evaluator, Operation};
use proptest::prelude::*;

const N: usize = 5;
const BLADES: usize = 1 << N;

fn null_evaluator() -> Evaluator {
    let algebra = Algebra::new(&common::null_cga()).unwrap();
    Evaluator::of(&algebra)
}

fn diagonal_evaluator() -> Evaluator {
    Evaluator::new(&[1, 1, 1, 1, -1]).unwrap()
}

/// Φ as a 32×32 matrix: column `a` holds the diagonal-basis coefficients of the null blade `a`, the
/// outer product of the images of its vectors.
fn change_of_basis() -> Vec<Vec<f64>> {
    let diagonal = diagonal_evaluator();
    let vector = |coefficients: [(usize, f64); 2]| {
        let mut v = vec![0.0; BLADES];
        for (bit, c) in coefficients {
            v[1 << bit] += c;
        }
        v
    };
    let images = [
        vector([(0, 1.0), (0, 0.0)]),
        vector([(1, 1.0), (1, 0.0)]),
        vector([(2, 1.0), (2, 0.0)]),
        vector([(4, 0.5), (3, -0.5)]), // n0 = (e5 − e4)/2
        vector([(3, 1.0), (4, 1.0)]),  // ninf = e4 + e5
    ];
    (0..BLADES)
        .map(|blade| {
            let mut image = vec![0.0; BLADES];
            image[0] = 1.0;
            for (bit, vector) in images.iter().enumerate() {
                if blade & (1 << bit) != 0 {
                    image = diagonal.binary(Operation::Outer, &image, vector).unwrap();
                }
            }
            image
        })
        .collect()
}

fn apply(phi: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; BLADES];
    for (column, &coefficient) in phi.iter().zip(x) {
        for (o, c) in out.iter_mut().zip(column) {
            *o += coefficient * c;
        }
    }
    out
}

fn negated(x: Vec<f64>) -> Vec<f64> {
    x.into_iter().map(|c| -c).collect()
}

fn multivector() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec((-4i32..=4).prop_map(f64::from), BLADES)
}

/// The binary operations that use the metric, and so commute with Φ.
const METRIC_BINARY: [Operation; 9] = [
    Operation::Geometric,
    Operation::Outer,
    Operation::LeftContraction,
    Operation::RightContraction,
    Operation::ScalarProduct,
    Operation::HestenesInner,
    Operation::FatDot,
    Operation::Commutator,
    Operation::Sandwich,
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn every_operation_matches_the_diagonal_cga((a, b) in (multivector(), multivector())) {
        let (null, diagonal, phi) = (null_evaluator(), diagonal_evaluator(), change_of_basis());
        let (pa, pb) = (apply(&phi, &a), apply(&phi, &b));
        for operation in METRIC_BINARY {
            prop_assert_eq!(apply(&phi, &null.binary(operation, &a, &b).unwrap()), diagonal.binary(operation, &pa, &pb).unwrap(), "{:?}", operation);
        }
        // Relative to the basis pseudoscalar: Φ(I_null) = −I, so the join changes sign.
        prop_assert_eq!(
            apply(&phi, &null.binary(Operation::Regressive, &a, &b).unwrap()),
            negated(diagonal.binary(Operation::Regressive, &pa, &pb).unwrap())
        );
        for operation in [Operation::Reverse, Operation::Involute, Operation::Conjugate] {
            prop_assert_eq!(apply(&phi, &null.unary(operation, &a).unwrap()), diagonal.unary(operation, &pa).unwrap(), "{:?}", operation);
        }
        // A I⁻¹ with I⁻¹ = I/(I I): the null pseudoscalar is −I, with the same square.
        prop_assert_eq!(apply(&phi, &null.unary(Operation::Polarity, &a).unwrap()), negated(diagonal.unary(Operation::Polarity, &pa).unwrap()));
        for k in 0..=N as u32 {
            prop_assert_eq!(apply(&phi, &null.grade_part(&a, k)), diagonal.grade_part(&pa, k));
        }
        prop_assert_eq!(null.norm_squared(&a).unwrap(), diagonal.norm_squared(&pa).unwrap());
    }

    /// The complements are metric-free: on the null basis they are the same blade maps as on any other
    /// metric over the same basis, and LC undoes RC.
    #[test]
    fn complements_ignore_the_metric(a in multivector()) {
        let (null, euclidean) = (null_evaluator(), Evaluator::new(&[1; N]).unwrap());
        for operation in [Operation::RightComplement, Operation::LeftComplement] {
            prop_assert_eq!(null.unary(operation, &a).unwrap(), euclidean.unary(operation, &a).unwrap());
        }
        let round_trip = null.unary(Operation::LeftComplement, &null.unary(Operation::RightComplement, &a).unwrap()).unwrap();
        prop_assert_eq!(round_trip, a);
    }
}

#[test]
fn blades_wedge_their_right_complement_into_the_basis_pseudoscalar() {
    let null = null_evaluator();
    for blade in 0..BLADES {
        let mut unit = vec![0.0; BLADES];
        unit[blade] = 1.0;
        let wedge = null
            .binary(
                Operation::Outer,
                &unit,
                &null.unary(Operation::RightComplement, &unit).unwrap(),
            )
            .unwrap();
        let mut pseudoscalar = vec![0.0; BLADES];
        pseudoscalar[BLADES - 1] = 1.0;
        assert_eq!(wedge, pseudoscalar, "blade {blade:05b}");
    }
}

/// The emitted programs of the null-basis types against the evaluator, exactly (the metric is
/// integral, the inputs are small integers).
#[test]
fn emitted_programs_equal_the_evaluator() {
    let algebra = Algebra::new(&common::null_cga()).unwrap();
    let evaluator = Evaluator::of(&algebra);
    let dense = |ty: usize, values: &[f64]| {
        let mut dense = vec![0.0; BLADES];
        for (field, &value) in algebra.types[ty].fields.iter().zip(values) {
            dense[field.blade as usize] = field.sign as f64 * value;
        }
        dense
    };
    let output = |function: &functions::Function, lhs: &[f64], rhs: &[f64]| {
        let mut dense = vec![0.0; BLADES];
        for (blade, value) in function.code.evaluate(lhs, rhs) {
            dense[blade as usize] = value;
        }
        dense
    };
    let values: Vec<f64> = (0..40).map(|i| f64::from((i * 7 + 3) % 9) - 4.0).collect();
    for lhs in 0..algebra.types.len() {
        for rhs in 0..algebra.types.len() {
            let x = &values[..algebra.types[lhs].fields.len()];
            let y = &values[5..5 + algebra.types[rhs].fields.len()];
            let (a, b) = (dense(lhs, x), dense(rhs, y));
            for operation in Operation::ALL
                .into_iter()
                .filter(|&op| op.is_binary() && op != Operation::Transform)
            {
                let function = functions::binary(&algebra, operation, lhs, rhs).unwrap();
                let expected = evaluator.binary(operation, &a, &b).unwrap();
                let expected = if operation == Operation::ScalarProduct {
                    evaluator.grade_part(&expected, 0)
                } else {
                    expected
                };
                assert_eq!(output(&function, x, y), expected, "{operation:?} {lhs} {rhs}");
            }
        }
        let a = dense(lhs, &values[..algebra.types[lhs].fields.len()]);
        for operation in [Operation::Reverse, Operation::Polarity, Operation::RightComplement] {
            for function in functions::unary(&algebra, operation, lhs).unwrap() {
                let x = &values[..algebra.types[lhs].fields.len()];
                assert_eq!(
                    output(&function, x, &[]),
                    evaluator.unary(operation, &a).unwrap(),
                    "{operation:?}"
                );
            }
        }
    }
}

/// The null basis makes CGA rigid motors as sparse as PGA's: 1, eᵢⱼ, eᵢ∞, e123∞.
#[test]
fn null_basis_motor_product_costs_what_pga_does() {
    let algebra = Algebra::new(&common::null_cga()).unwrap();
    let motor = algebra.type_named("Motor").unwrap();
    assert_eq!(motor.fields.len(), 8);
    let cost = functions::cost(&algebra, Operation::Geometric, "Motor", Some("Motor"))
        .unwrap()
        .unwrap();
    assert_eq!(
        cost,
        Cost {
            multiplies: 48,
            adds: 40,
            divisions: 0
        }
    );
}

#[test]
fn the_null_metric_is_not_diagonal() {
    let metric = Algebra::new(&common::null_cga()).unwrap().metric;
    assert!(!metric.is_diagonal());
    assert_eq!(
        metric,
        Metric::from_matrix(&common::null_cga().metric.unwrap()).unwrap()
    );
}
