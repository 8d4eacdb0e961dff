//! Table-driven products (`ga_codegen::table`), compiled: the sandwich of two full Cl(5,1) multivectors
//! (too big to unroll, tabled automatically; it used to overflow rustc's stack in debug builds) against the
//! dense evaluator, and PGA with every product declared `(table)` against the same products unrolled.

use ga_codegen::blade::BladeNaming;
use ga_codegen::{Evaluator, Operation};

ga_macros::algebra! {
    /// Cl(5,1): the geometric product of full multivectors (4096 monomials) is unrolled, the sandwich and
    /// transform (about 133 thousand) are tabled.
    mod cl51 {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = 1, e6 = -1];
        types {
            Multivector = all;
        }
        ops = [geometric, sandwich, transform, reverse];
    }
}

/// PGA's standard types with every product tabled.
macro_rules! pga {
    ($module:ident, [$($ops:tt)*]) => {
        ga_macros::algebra! {
            mod $module {
                scalar = f64;
                basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
                types {
                    Motor = grades(0, 2, 4);
                    Plane = grades(1);
                    Line = grades(2);
                    Point = grades(3);
                    Multivector = all;
                }
                ops = [$($ops)*];
            }
        }
    };
}

pga!(
    pga_unrolled,
    [
        geometric,
        outer,
        regressive,
        left_contraction,
        commutator,
        scalar_product,
        sandwich,
        transform
    ]
);
pga!(
    pga_tabled,
    [
        geometric(table),
        outer(table),
        regressive(table),
        left_contraction(table),
        commutator(table),
        scalar_product(table),
        sandwich(table),
        transform(table),
    ]
);

/// A fixed xorshift sequence in [−1, 1].
struct Numbers(u64);

impl Numbers {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % 2001) as f64 / 1000.0 - 1.0
    }
}

/// Dense coefficients (indexed by blade mask) of a Cl(5,1) value.
fn dense(blade_names: &[&str], values: &[f64], naming: &BladeNaming) -> Vec<f64> {
    let mut out = vec![0.0; 64];
    for (name, value) in blade_names.iter().zip(values) {
        let (blade, sign) = naming.parse(name).expect("emitted names parse");
        out[blade as usize] = sign as f64 * value;
    }
    out
}

fn assert_close(got: &[f64], expected: &[f64], what: &str) {
    let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (blade, (g, e)) in got.iter().zip(expected).enumerate() {
        assert!((g - e).abs() <= 1e-13 * scale, "{what}: blade {blade:b}: {g} vs {e}");
    }
}

#[test]
fn the_full_cl51_sandwich_is_tabled_and_equals_the_evaluator() {
    use cl51::{Multivector, Sandwich, Transform};
    let names: Vec<String> = (1..=6).map(|i| format!("e{i}")).collect();
    let naming = BladeNaming::new(&names);
    let evaluator = Evaluator::new(&[1, 1, 1, 1, 1, -1]).unwrap();
    let mut numbers = Numbers(0x9e37_79b9_7f4a_7c15);
    for _ in 0..4 {
        let a = Multivector::from_array(std::array::from_fn(|_| numbers.next()));
        let x = Multivector::from_array(std::array::from_fn(|_| numbers.next()));
        let (da, dx) = (
            dense(Multivector::BLADES, &a.to_array(), &naming),
            dense(Multivector::BLADES, &x.to_array(), &naming),
        );
        let expected = evaluator.binary(Operation::Sandwich, &da, &dx).unwrap();
        let got = dense(Multivector::BLADES, &a.sandwich(x).to_array(), &naming);
        assert_close(&got, &expected, "sandwich");
        // The unrolled geometric product agrees with the tabled sandwich's two stages.
        let twice = dense(Multivector::BLADES, &(a * x * a.reverse()).to_array(), &naming);
        assert_close(&twice, &expected, "a x ~a by geometric products");

        // A unit versor (two unit vectors): transform keeps the operand's grades and equals the sandwich.
        let unit = |numbers: &mut Numbers| {
            let mut v = [0.0; 64];
            v[1..6].iter_mut().for_each(|c| *c = numbers.next()); // e1 … e5, positive squares
            let v = Multivector::from_array(v);
            v * (1.0 / (v * v).scalar.sqrt())
        };
        let versor = unit(&mut numbers) * unit(&mut numbers);
        let mut vector = [0.0; 64];
        vector[1..7].iter_mut().for_each(|c| *c = numbers.next());
        let vector = Multivector::from_array(vector);
        assert_close(
            &versor.transform(vector).to_array(),
            &versor.sandwich(vector).to_array(),
            "transform",
        );
    }
}

#[test]
fn tabled_functions_say_so_and_stay_const() {
    // The tabled sandwich is still a `const fn`.
    const MOVED: cl51::Multivector = cl51::Multivector {
        scalar: 2.0,
        ..cl51::Multivector::zero()
    }
    .sandwich_multivector(cl51::Multivector {
        e1: 1.0,
        ..cl51::Multivector::zero()
    });
    assert_eq!(MOVED.e1, 4.0);
    assert_eq!(MOVED.to_array().iter().filter(|c| **c != 0.0).count(), 1);
}

#[test]
fn pga_products_by_tables_equal_the_unrolled_products() {
    use ga_macros_tables_pga::*;
    let mut numbers = Numbers(0x2545_f491_4f6c_dd1d);
    for _ in 0..16 {
        let values: [f64; 16] = std::array::from_fn(|_| numbers.next());
        compare_all(&values);
    }
}

/// One comparison per product kind, between modules generated from the same declaration.
mod ga_macros_tables_pga {
    use super::{assert_close, pga_tabled as t, pga_unrolled as u};

    macro_rules! compare {
        ($method:ident, $lhs:ident, $rhs:ident, $values:expr) => {{
            let v = $values;
            compare!($method, $lhs, $rhs, v, v.iter().rev().copied().collect::<Vec<f64>>())
        }};
        ($method:ident, $lhs:ident, $rhs:ident, $left:expr, $right:expr) => {{
            let (left, right) = ($left, $right);
            let (a, b) = (
                u::$lhs::from_array(std::array::from_fn(|i| left[i])),
                u::$rhs::from_array(std::array::from_fn(|i| right[i])),
            );
            let (ta, tb) = (t::$lhs::from_array(a.to_array()), t::$rhs::from_array(b.to_array()));
            let (unrolled, tabled) = (a.$method(b), ta.$method(tb));
            let what = concat!(stringify!($lhs), ".", stringify!($method), "(", stringify!($rhs), ")");
            assert_close(&to_vec(tabled), &to_vec(unrolled), what);
        }};
    }

    trait Coefficients {
        fn coefficients(self) -> Vec<f64>;
    }
    impl Coefficients for f64 {
        fn coefficients(self) -> Vec<f64> {
            vec![self]
        }
    }
    macro_rules! coefficients {
        ($($module:ident :: $ty:ident),*) => {$(
            impl Coefficients for $module::$ty {
                fn coefficients(self) -> Vec<f64> {
                    self.to_array().to_vec()
                }
            }
        )*};
    }
    coefficients!(u::Motor, u::Plane, u::Line, u::Point, u::Multivector);
    coefficients!(t::Motor, t::Plane, t::Line, t::Point, t::Multivector);

    fn to_vec(value: impl Coefficients) -> Vec<f64> {
        value.coefficients()
    }

    pub fn compare_all(values: &[f64; 16]) {
        use t::{
            Commutator as _, Geometric as _, LeftContraction as _, Outer as _, Regressive as _, Sandwich as _,
            ScalarProduct as _, Transform as _,
        };
        use u::{
            Commutator as _, Geometric as _, LeftContraction as _, Outer as _, Regressive as _, Sandwich as _,
            ScalarProduct as _, Transform as _,
        };
        compare!(geometric, Motor, Motor, values);
        compare!(geometric, Multivector, Multivector, values);
        compare!(outer, Plane, Plane, values);
        compare!(regressive, Point, Point, values);
        compare!(left_contraction, Plane, Line, values);
        compare!(commutator, Line, Point, values);
        compare!(scalar_product, Line, Line, values);
        compare!(sandwich, Motor, Point, values);
        compare!(sandwich, Multivector, Line, values);
        // `transform` holds for unit versors only: planes with a unit normal, and motors made of two.
        let unit_plane = |offset: usize| {
            let plane = u::Plane::from_array(std::array::from_fn(|i| values[offset + i]));
            plane * (1.0 / (plane.e1 * plane.e1 + plane.e2 * plane.e2 + plane.e3 * plane.e3).sqrt())
        };
        let (first, second) = (unit_plane(0), unit_plane(4));
        let motor: u::Motor = first * second;
        compare!(transform, Motor, Line, motor.to_array(), &values[8..]);
        compare!(transform, Plane, Point, first.to_array(), &values[12..]);
    }
}
