//! Big algebras through the macro: Cl(9,6) (15 dimensions, 32768 blades), Cl(4,4) and Cl(8,2), each
//! with scalars, vectors and bivectors and the operations that keep those grades. The compiled code
//! is checked against the dense evaluator on random inputs (transforms on random unit versors).

use ga_codegen::blade::BladeNaming;
use ga_codegen::{Evaluator, Operation};

/// Declares one algebra module with the shared type set and operations.
macro_rules! algebra {
    ($module:ident, [$($basis:tt)*]) => {
        ga_macros::algebra! {
            pub mod $module {
                scalar = f64;
                basis = [$($basis)*];
                types {
                    Scalar = grades(0);
                    Vector = grades(1);
                    Bivector = grades(2);
                }
                ops = [commutator, left_contraction, right_contraction, scalar_product, hestenes_inner, fat_dot,
                       transform, reverse, involute, conjugate, grade, norm_squared, inverse];
            }
        }
    };
}

algebra!(
    cl96,
    [
        e1 = 1,
        e2 = 1,
        e3 = 1,
        e4 = 1,
        e5 = 1,
        e6 = 1,
        e7 = 1,
        e8 = 1,
        e9 = 1,
        e10 = -1,
        e11 = -1,
        e12 = -1,
        e13 = -1,
        e14 = -1,
        e15 = -1
    ]
);
algebra!(
    cl44,
    [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1, e6 = -1, e7 = -1, e8 = -1]
);
algebra!(
    cl82,
    [
        e1 = 1,
        e2 = 1,
        e3 = 1,
        e4 = 1,
        e5 = 1,
        e6 = 1,
        e7 = 1,
        e8 = 1,
        e9 = -1,
        e10 = -1
    ]
);

/// Small integers from a fixed xorshift sequence (exact products), or floats for versors.
struct Numbers(u64);

impl Numbers {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % 7) as f64 - 3.0
    }
}

/// Dense coefficients (indexed by blade mask) of emitted values.
trait Dense {
    fn dense(&self, naming: &BladeNaming, blades: usize) -> Vec<f64>;
}

impl Dense for f64 {
    fn dense(&self, _: &BladeNaming, blades: usize) -> Vec<f64> {
        let mut out = vec![0.0; blades];
        out[0] = *self;
        out
    }
}

/// Implements [`Dense`] for the emitted types of one module.
macro_rules! dense {
    ($module:ident) => {
        dense!($module, Scalar);
        dense!($module, Vector);
        dense!($module, Bivector);
    };
    ($module:ident, $ty:ident) => {
        impl Dense for $module::$ty {
            fn dense(&self, naming: &BladeNaming, blades: usize) -> Vec<f64> {
                let mut out = vec![0.0; blades];
                for (name, value) in $module::$ty::BLADES.iter().zip(self.to_array()) {
                    let (blade, sign) = naming.parse(name).expect("emitted names parse");
                    out[blade as usize] = sign as f64 * value;
                }
                out
            }
        }
    };
}

dense!(cl96);
dense!(cl44);
dense!(cl82);

/// Checks one binary function against the evaluator's `operation`.
fn check<A: Dense + Copy, B: Dense + Copy, R: Dense>(
    evaluator: &Evaluator,
    naming: &BladeNaming,
    operation: Operation,
    (a, b): (A, B),
    function: impl Fn(A, B) -> R,
) {
    let blades = evaluator.blade_count();
    let expected = evaluator
        .binary(operation, &a.dense(naming, blades), &b.dense(naming, blades))
        .unwrap();
    let expected = if operation == Operation::ScalarProduct {
        evaluator.grade_part(&expected, 0)
    } else {
        expected
    };
    let got = function(a, b).dense(naming, blades);
    let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (blade, (g, e)) in got.iter().zip(&expected).enumerate() {
        assert!(
            (g - e).abs() <= 1e-12 * scale,
            "{operation:?}: blade {blade:b}: {g} vs {e}"
        );
    }
}

/// Declares the conformance test of one module, with the squares of its basis.
macro_rules! conformance {
    ($test:ident, $module:ident, $squares:expr) => {
        #[test]
        fn $test() {
            use $module::*;
            let squares: Vec<i64> = $squares;
            let n = squares.len();
            let evaluator = Evaluator::new(&squares).unwrap();
            let names: Vec<String> = (1..=n).map(|i| format!("e{i}")).collect();
            let naming = BladeNaming::new(&names);
            let mut numbers = Numbers(0x853c_49e6_748f_ea9b ^ n as u64);
            let (mut vector_versors, mut bivector_versors) = (0, 0);
            for _ in 0..8 {
                let s = Scalar::from_array([numbers.next()]);
                let v = Vector::from_array(std::array::from_fn(|_| numbers.next()));
                let b = Bivector::from_array(std::array::from_fn(|_| numbers.next()));
                macro_rules! every_pair {
                    ($operation:expr, $method:ident) => {
                        check(&evaluator, &naming, $operation, (s, s), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (s, v), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (s, b), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (v, s), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (v, v), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (v, b), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (b, s), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (b, v), |x, y| x.$method(y));
                        check(&evaluator, &naming, $operation, (b, b), |x, y| x.$method(y));
                    };
                }
                every_pair!(Operation::Commutator, commutator);
                every_pair!(Operation::LeftContraction, left_contraction);
                every_pair!(Operation::RightContraction, right_contraction);
                every_pair!(Operation::ScalarProduct, scalar_product);
                every_pair!(Operation::HestenesInner, hestenes_inner);
                every_pair!(Operation::FatDot, fat_dot);

                let blades = evaluator.blade_count();
                for (operation, got) in [
                    (Operation::Reverse, b.reverse().dense(&naming, blades)),
                    (Operation::Involute, v.involute().dense(&naming, blades)),
                    (Operation::Conjugate, b.conjugate().dense(&naming, blades)),
                ] {
                    let input = if operation == Operation::Involute {
                        v.dense(&naming, blades)
                    } else {
                        b.dense(&naming, blades)
                    };
                    assert_eq!(got, evaluator.unary(operation, &input).unwrap(), "{operation:?}");
                }
                assert_eq!(
                    b.norm_squared(),
                    evaluator.norm_squared(&b.dense(&naming, blades)).unwrap()
                );
                assert_eq!(v.grade_1(), v);

                // Unit versors: a vector and a simple bivector u ∧ v, normalised (`a ~a = 1` needs a
                // positive norm; the others are skipped). `transform` is then the sandwich.
                if v.norm_squared() > 0.0 {
                    let unit = v * (1.0 / v.norm_squared().sqrt());
                    check(&evaluator, &naming, Operation::Sandwich, (unit, v), |x, y| {
                        x.transform(y)
                    });
                    check(&evaluator, &naming, Operation::Sandwich, (unit, b), |x, y| {
                        x.transform(y)
                    });
                    vector_versors += 1;
                }
                let u = Vector::from_array(std::array::from_fn(|_| numbers.next()));
                let (u, w) = (u.to_array(), v.to_array());
                let simple = Bivector::from_array(std::array::from_fn(|index| {
                    let (blade, _) = naming.parse(Bivector::BLADES[index]).unwrap();
                    let (i, j) = (
                        blade.trailing_zeros() as usize,
                        31 - blade.leading_zeros() as usize,
                    );
                    u[i] * w[j] - u[j] * w[i]
                }));
                if simple.norm_squared() > 0.0 {
                    let unit = simple * (1.0 / simple.norm_squared().sqrt());
                    check(&evaluator, &naming, Operation::Sandwich, (unit, v), |x, y| {
                        x.transform(y)
                    });
                    check(&evaluator, &naming, Operation::Sandwich, (unit, b), |x, y| {
                        x.transform(y)
                    });
                    bivector_versors += 1;
                }
                let inverse = v.inverse();
                assert!((v.left_contraction(inverse).to_array()[0] - 1.0).abs() < 1e-12);
            }
            assert!(
                vector_versors > 0 && bivector_versors > 0,
                "some random versors are unit"
            );
        }
    };
}

conformance!(cl96_vectors_and_bivectors, cl96, [vec![1; 9], vec![-1; 6]].concat());
conformance!(cl44_vectors_and_bivectors, cl44, [vec![1; 4], vec![-1; 4]].concat());
conformance!(cl82_vectors_and_bivectors, cl82, [vec![1; 8], vec![-1; 2]].concat());
