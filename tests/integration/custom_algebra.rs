//! Algebras no other test declares, through the `algebra!` macro, checked operation by operation
//! against the dense runtime evaluator (`ga_codegen::Evaluator`):
//! - Cl(1,2,1) with the null vector in the middle of the basis, f64, types declared by grades and by
//!   blades, including permuted names and a blade list in scrambled order. The null vector is named
//!   `e0` but is bit 2 (`basis = [e1, e2, e0, e3]`): blade names follow bit order, so the canonical
//!   name of e1 ∧ e0 is `e10` and `e01` is a permuted name for −`e10`;
//! - the same algebra in f32;
//! - a second f64 algebra, non-degenerate Cl(1,2) whose basis names share no prefix, so blades are
//!   named `x_y`, `t_y_x`, …, and the polarity exists.
//!
//! Every binary operation is checked on every ordered pair of declared types (with the operator
//! sugar), every unary operation on every type, plus sums, scalar arithmetic, `inverse` and the
//! `From` embeddings. The f64 inputs are random small integers, so every product is exact and the
//! comparison is `==`; the f32 inputs are random reals, compared to a relative tolerance.

use ga_codegen::{Evaluator, Operation};

ga_macros::algebra! {
    /// Cl(1,2,1): e1² = 1, e2² = −1, e0² = 0, e3² = −1, in this bit order.
    mod mixed {
        scalar = f64;
        basis = [e1 = 1, e2 = -1, e0 = 0, e3 = -1];
        types {
            Vector = grades(1);
            Bivector = grades(2);
            Even = grades(4, 0, 2);
            /// Permuted names: `e21` = −`e12`, `e30` = −`e03`.
            Spinor = blades(scalar, e21, e30);
            /// Scrambled order and mixed grades: `e231` = +`e123` (an even permutation),
            /// `e01` = −`e10`, `e230` = −`e203`.
            Skew = blades(e231, e01, scalar, e230);
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    /// The same Cl(1,2,1) in single precision.
    mod mixed_f32 {
        scalar = f32;
        basis = [e1 = 1, e2 = -1, e0 = 0, e3 = -1];
        types {
            Vector = grades(1);
            Even = grades(0, 2, 4);
            Spinor = blades(scalar, e21, e30);
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    /// Cl(1,2) without a common name prefix: blade names join the basis names with `_`.
    mod spacetime {
        scalar = f64;
        basis = [x = 1, y = -1, t = -1];
        types {
            Vector = grades(1);
            Rotor = blades(scalar, y_x, t_y, x_t);
            Pseudoscalar = blades(t_y_x);
            Multivector = all;
        }
    }
}

/// SplitMix64: a tiny deterministic generator, so that a failure reproduces.
struct Random(u64);

impl Random {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// An integer in [−5, 5]: small enough that every product is exact in f64.
    fn small_integer(&mut self) -> f64 {
        (self.next_u64() % 11) as f64 - 5.0
    }

    /// A real in [−2, 2).
    fn real(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 51) as f64 - 2.0
    }
}

/// A generated type seen as its field names and values, converted to f64.
trait Fields: Copy {
    fn blades() -> &'static [&'static str];
    fn values(self) -> Vec<f64>;
    fn from_values(values: &[f64]) -> Self;
}

/// f64 and f32, so that one conversion serves both precisions without a cast clippy would flag.
trait Scalar: Copy + Into<f64> {
    fn from_f64(value: f64) -> Self;
}

impl Scalar for f64 {
    fn from_f64(value: f64) -> f64 {
        value
    }
}

impl Scalar for f32 {
    fn from_f64(value: f64) -> f32 {
        value as f32
    }
}

/// The bare scalar returned by `scalar_product` and `norm_squared`.
impl<S: Scalar> Fields for S {
    fn blades() -> &'static [&'static str] {
        &["scalar"]
    }
    fn values(self) -> Vec<f64> {
        vec![self.into()]
    }
    fn from_values(values: &[f64]) -> S {
        S::from_f64(values[0])
    }
}

macro_rules! impl_fields {
    ($($ty:path),* $(,)?) => {
        $(
            impl Fields for $ty {
                fn blades() -> &'static [&'static str] {
                    <$ty>::BLADES
                }
                fn values(self) -> Vec<f64> {
                    self.to_array().into_iter().map(Into::into).collect()
                }
                fn from_values(values: &[f64]) -> Self {
                    Self::from_array(std::array::from_fn(|i| Scalar::from_f64(values[i])))
                }
            }
        )*
    };
}

impl_fields!(
    mixed::Vector,
    mixed::Bivector,
    mixed::Even,
    mixed::Spinor,
    mixed::Skew,
    mixed::Multivector,
    mixed_f32::Vector,
    mixed_f32::Even,
    mixed_f32::Spinor,
    mixed_f32::Multivector,
    spacetime::Vector,
    spacetime::Rotor,
    spacetime::Pseudoscalar,
    spacetime::Multivector,
);

/// How the inputs are drawn and how closely results must match.
#[derive(Clone, Copy)]
enum Precision {
    /// f64 with integer inputs: results must be equal.
    Exact,
    /// f32 with real inputs: results must agree to this relative tolerance.
    Relative(f64),
}

/// One declared algebra under test: its basis, how its blade names split into basis names, and the
/// oracle.
struct AlgebraUnderTest {
    basis: &'static [&'static str],
    /// Splits a blade name (not `scalar`) into its factors' basis names.
    factors: fn(&str) -> Vec<String>,
    evaluator: Evaluator,
    precision: Precision,
    random: std::cell::RefCell<Random>,
}

/// Samples per (operation, type pair).
const SAMPLES: usize = 12;

impl AlgebraUnderTest {
    fn new(
        basis: &'static [&'static str],
        squares: &[i64],
        factors: fn(&str) -> Vec<String>,
        precision: Precision,
    ) -> Self {
        AlgebraUnderTest {
            basis,
            factors,
            evaluator: Evaluator::new(squares).unwrap(),
            precision,
            random: std::cell::RefCell::new(Random(0x5eed)),
        }
    }

    /// The canonical blade (bitmask) of a field name and the sign of the field relative to it,
    /// worked out here independently of the compiler: the sign of the permutation sorting the
    /// factors into basis order.
    fn blade(&self, name: &str) -> (usize, f64) {
        if name == "scalar" {
            return (0, 1.0);
        }
        let indices: Vec<usize> = (self.factors)(name)
            .iter()
            .map(|factor| {
                self.basis
                    .iter()
                    .position(|b| b == factor)
                    .unwrap_or_else(|| panic!("{factor} in {name} is a basis vector"))
            })
            .collect();
        let inversions = (0..indices.len())
            .flat_map(|i| (i + 1..indices.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| indices[i] > indices[j])
            .count();
        let mask = indices.iter().fold(0, |mask, i| mask | 1 << i);
        (mask, if inversions.is_multiple_of(2) { 1.0 } else { -1.0 })
    }

    fn dense<T: Fields>(&self, value: T) -> Vec<f64> {
        let mut dense = vec![0.0; self.evaluator.blade_count()];
        for (name, x) in T::blades().iter().zip(value.values()) {
            let (mask, sign) = self.blade(name);
            dense[mask] = sign * x;
        }
        dense
    }

    fn sample<T: Fields>(&self) -> T {
        let mut random = self.random.borrow_mut();
        let values: Vec<f64> = T::blades()
            .iter()
            .map(|_| match self.precision {
                Precision::Exact => random.small_integer(),
                Precision::Relative(_) => random.real(),
            })
            .collect();
        T::from_values(&values)
    }

    fn assert_matches(&self, got: &[f64], expected: &[f64], context: &dyn Fn() -> String) {
        let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (mask, (g, e)) in got.iter().zip(expected).enumerate() {
            let ok = match self.precision {
                Precision::Exact => g == e,
                Precision::Relative(tolerance) => (g - e).abs() <= tolerance * scale,
            };
            assert!(ok, "{}: blade mask {mask:#b}: got {g}, expected {e}", context());
        }
    }

    /// Checks `apply` (a generated binary function) against the evaluator's `operation`.
    fn binary<L: Fields, R: Fields, O: Fields>(&self, operation: Operation, apply: impl Fn(L, R) -> O) {
        for _ in 0..SAMPLES {
            let (a, b): (L, R) = (self.sample(), self.sample());
            let (dense_a, dense_b) = (self.dense(a), self.dense(b));
            let mut expected = self.evaluator.binary(operation, &dense_a, &dense_b).unwrap();
            if operation == Operation::ScalarProduct {
                expected = self.evaluator.grade_part(&expected, 0);
            }
            self.assert_matches(&self.dense(apply(a, b)), &expected, &|| {
                format!(
                    "{} of {} and {} on {dense_a:?} and {dense_b:?}",
                    operation.name(),
                    std::any::type_name::<L>(),
                    std::any::type_name::<R>()
                )
            });
        }
    }

    /// Checks a generated function of one operand against `expected` on dense coefficients.
    fn unary<T: Fields, O: Fields>(&self, what: &str, apply: impl Fn(T) -> O, expected: impl Fn(&[f64]) -> Vec<f64>) {
        for _ in 0..SAMPLES {
            let a: T = self.sample();
            let dense_a = self.dense(a);
            self.assert_matches(&self.dense(apply(a)), &expected(&dense_a), &|| {
                format!("{what} of {} on {dense_a:?}", std::any::type_name::<T>())
            });
        }
    }

    /// `a + b` or `a − b` against the dense sum or difference.
    fn sum<L: Fields, R: Fields, O: Fields>(&self, sign: f64, apply: impl Fn(L, R) -> O) {
        for _ in 0..SAMPLES {
            let (a, b): (L, R) = (self.sample(), self.sample());
            let (dense_a, dense_b) = (self.dense(a), self.dense(b));
            let expected: Vec<f64> = dense_a.iter().zip(&dense_b).map(|(x, y)| x + sign * y).collect();
            self.assert_matches(&self.dense(apply(a, b)), &expected, &|| {
                format!(
                    "sum (sign {sign}) of {} and {}",
                    std::any::type_name::<L>(),
                    std::any::type_name::<R>()
                )
            });
        }
    }

    /// `Target::from(a)` holds the same multivector as `a`.
    fn embedding<Source: Fields, Target: Fields + From<Source>>(&self) {
        self.unary("From embedding", Target::from, |a: &[f64]| a.to_vec());
    }

    /// `a * a.inverse()` and `a.inverse() * a` are 1 wherever `a ~a` is not zero (to rounding: the
    /// inverse divides).
    fn inverse<T: Fields, O: Fields>(&self, inverse: impl Fn(T) -> T, times: impl Fn(T, T) -> O) {
        let tolerance = match self.precision {
            Precision::Exact => 1e-12,
            Precision::Relative(tolerance) => tolerance,
        };
        let mut one = vec![0.0; self.evaluator.blade_count()];
        one[0] = 1.0;
        let mut checked = 0;
        while checked < SAMPLES {
            let a: T = self.sample();
            if self.evaluator.norm_squared(&self.dense(a)).unwrap() == 0.0 {
                continue;
            }
            for product in [times(a, inverse(a)), times(inverse(a), a)] {
                let got = self.dense(product);
                let error = got.iter().zip(&one).map(|(g, e)| (g - e).abs()).fold(0.0, f64::max);
                assert!(
                    error <= tolerance,
                    "{} times its inverse is {got:?}",
                    std::any::type_name::<T>()
                );
            }
            checked += 1;
        }
    }
}

/// Every binary operation (trait method and operator sugar) and the sum of one ordered type pair.
macro_rules! check_binary {
    ($algebra:expr, $lhs:ty, $rhs:ty) => {{
        let algebra = &$algebra;
        algebra.binary(Operation::Geometric, |a: $lhs, b: $rhs| a.geometric(b));
        algebra.binary(Operation::Geometric, |a: $lhs, b: $rhs| a * b);
        algebra.binary(Operation::Outer, |a: $lhs, b: $rhs| a.outer(b));
        algebra.binary(Operation::Outer, |a: $lhs, b: $rhs| a ^ b);
        algebra.binary(Operation::LeftContraction, |a: $lhs, b: $rhs| a.left_contraction(b));
        algebra.binary(Operation::LeftContraction, |a: $lhs, b: $rhs| a | b);
        algebra.binary(Operation::RightContraction, |a: $lhs, b: $rhs| a.right_contraction(b));
        algebra.binary(Operation::ScalarProduct, |a: $lhs, b: $rhs| a.scalar_product(b));
        algebra.binary(Operation::HestenesInner, |a: $lhs, b: $rhs| a.hestenes_inner(b));
        algebra.binary(Operation::FatDot, |a: $lhs, b: $rhs| a.fat_dot(b));
        algebra.binary(Operation::Regressive, |a: $lhs, b: $rhs| a.regressive(b));
        algebra.binary(Operation::Regressive, |a: $lhs, b: $rhs| a & b);
        algebra.binary(Operation::Commutator, |a: $lhs, b: $rhs| a.commutator(b));
        algebra.binary(Operation::Sandwich, |a: $lhs, b: $rhs| a.sandwich(b));
        algebra.sum(1.0, |a: $lhs, b: $rhs| a + b);
        algebra.sum(-1.0, |a: $lhs, b: $rhs| a - b);
    }};
}

/// `check_binary!` on every ordered pair of the listed types.
macro_rules! check_all_pairs {
    ($algebra:expr, [$($lhs:ty),*]) => {
        check_all_pairs!(@rows $algebra, [$($lhs),*], [$($lhs),*]);
    };
    (@rows $algebra:expr, [$($lhs:ty),*], $rhs:tt) => {
        $( check_all_pairs!(@row $algebra, $lhs, $rhs); )*
    };
    (@row $algebra:expr, $lhs:ty, [$($rhs:ty),*]) => {
        $( check_binary!($algebra, $lhs, $rhs); )*
    };
}

/// The blade maps, norm and scalar arithmetic of one type. Grade projections, polarity and
/// `inverse` exist only for some types, so their tests list them separately.
macro_rules! check_unary {
    ($algebra:expr, $ty:ty) => {{
        let algebra = &$algebra;
        let ev = &algebra.evaluator;
        algebra.unary(
            "reverse",
            |a: $ty| a.reverse(),
            |a| ev.unary(Operation::Reverse, a).unwrap(),
        );
        algebra.unary(
            "involute",
            |a: $ty| a.involute(),
            |a| ev.unary(Operation::Involute, a).unwrap(),
        );
        algebra.unary(
            "conjugate",
            |a: $ty| a.conjugate(),
            |a| ev.unary(Operation::Conjugate, a).unwrap(),
        );
        algebra.unary(
            "right_complement",
            |a: $ty| a.right_complement(),
            |a| ev.unary(Operation::RightComplement, a).unwrap(),
        );
        algebra.unary(
            "left_complement",
            |a: $ty| a.left_complement(),
            |a| ev.unary(Operation::LeftComplement, a).unwrap(),
        );
        algebra.unary(
            "norm_squared",
            |a: $ty| a.norm_squared(),
            |a| {
                let mut dense = vec![0.0; a.len()];
                dense[0] = ev.norm_squared(a).unwrap();
                dense
            },
        );
        algebra.unary("negation", |a: $ty| -a, |a| a.iter().map(|x| -x).collect());
        algebra.unary("scaling", |a: $ty| a * 3.0, |a| a.iter().map(|x| 3.0 * x).collect());
        algebra.unary(
            "scaling on the left",
            |a: $ty| 3.0 * a,
            |a| a.iter().map(|x| 3.0 * x).collect(),
        );
        algebra.unary("division", |a: $ty| a / 2.0, |a| a.iter().map(|x| x / 2.0).collect());
        algebra.unary(
            "compound assignment",
            |a: $ty| {
                let mut b = a;
                b *= 2.0;
                b += a;
                b -= a * 4.0;
                b
            },
            |a| a.iter().map(|x| -x).collect(),
        );
        algebra.unary(
            "from_array of to_array",
            |a: $ty| <$ty>::from_array(a.to_array()),
            |a| a.to_vec(),
        );
        assert_eq!(<$ty>::ZERO, <$ty>::default());
        assert_eq!(<$ty>::zero(), <$ty>::default());
    }};
}

/// `grade_k` against the evaluator's grade projection, for each listed k.
macro_rules! check_grades {
    ($algebra:expr, $ty:ty, [$($method:ident = $k:literal),*]) => {{
        let algebra = &$algebra;
        $( algebra.unary(stringify!($method), |a: $ty| a.$method(), |a| algebra.evaluator.grade_part(a, $k)); )*
    }};
}

/// `e231` → `e2`, `e3`, `e1`.
fn single_character_factors(name: &str) -> Vec<String> {
    name.strip_prefix('e')
        .expect("blade names start with e")
        .chars()
        .map(|c| format!("e{c}"))
        .collect()
}

/// `t_y_x` → `t`, `y`, `x`.
fn underscore_factors(name: &str) -> Vec<String> {
    name.split('_').map(String::from).collect()
}

fn mixed_under_test(precision: Precision) -> AlgebraUnderTest {
    AlgebraUnderTest::new(
        &["e1", "e2", "e0", "e3"],
        &[1, -1, 0, -1],
        single_character_factors,
        precision,
    )
}

fn spacetime_under_test() -> AlgebraUnderTest {
    AlgebraUnderTest::new(&["x", "y", "t"], &[1, -1, -1], underscore_factors, Precision::Exact)
}

#[test]
fn degenerate_f64_binary_operations_match_the_evaluator() {
    use mixed::*;
    check_all_pairs!(
        mixed_under_test(Precision::Exact),
        [Vector, Bivector, Even, Spinor, Skew, Multivector]
    );
}

#[test]
fn degenerate_f64_unary_operations_match_the_evaluator() {
    use mixed::*;
    let algebra = mixed_under_test(Precision::Exact);
    check_unary!(algebra, Vector);
    check_unary!(algebra, Bivector);
    check_unary!(algebra, Even);
    check_unary!(algebra, Spinor);
    check_unary!(algebra, Skew);
    check_unary!(algebra, Multivector);
    check_grades!(algebra, Vector, [grade_1 = 1]);
    check_grades!(algebra, Even, [grade_0 = 0, grade_2 = 2, grade_4 = 4]);
    check_grades!(algebra, Spinor, [grade_0 = 0, grade_2 = 2]);
    check_grades!(algebra, Skew, [grade_0 = 0, grade_2 = 2, grade_3 = 3]);
    check_grades!(
        algebra,
        Multivector,
        [grade_0 = 0, grade_1 = 1, grade_2 = 2, grade_3 = 3, grade_4 = 4]
    );
    // Only types whose a ~a is a scalar get an inverse: here only Vector (in four dimensions a
    // bivector times its reverse has a grade-4 part).
    algebra.inverse(|a: Vector| a.inverse(), |a, b| a * b);
}

#[test]
fn degenerate_f64_embeddings_keep_the_multivector() {
    use mixed::*;
    let algebra = mixed_under_test(Precision::Exact);
    algebra.embedding::<Vector, Multivector>();
    algebra.embedding::<Bivector, Even>();
    algebra.embedding::<Bivector, Multivector>();
    // Spinor stores −e12 and −e03, Even stores e12 and e03: the embedding flips those signs.
    algebra.embedding::<Spinor, Even>();
    algebra.embedding::<Spinor, Multivector>();
    algebra.embedding::<Skew, Multivector>();
    algebra.embedding::<Even, Multivector>();
}

#[test]
fn result_types_are_the_smallest_declared_types() {
    use mixed::*;
    // The annotations are the assertions: each line compiles only with this result type.
    let (v, s, k) = (Vector::ZERO, Spinor::ZERO, Skew::ZERO);
    let _: Even = v * v; // scalar + bivector: Even (8) is smaller than Multivector (16)
    let _: Bivector = v ^ v;
    let _: Even = s * s; // e21 e30 is the grade-4 pseudoscalar
    let _: Spinor = Even::ZERO.grade_0(); // of the types holding the scalar, Spinor has the fewest fields
    let _: Multivector = k * v;
    let _: f64 = s.scalar_product(k); // scalar_product and norm_squared return the bare scalar
    let _: f64 = k.norm_squared();
    let _: Even = (v ^ v) ^ (v ^ v); // grade 4 alone: no type holds just the pseudoscalar
}

#[test]
fn single_precision_operations_match_the_evaluator() {
    use mixed_f32::*;
    let algebra = mixed_under_test(Precision::Relative(1e-5));
    check_all_pairs!(algebra, [Vector, Even, Spinor, Multivector]);
    check_unary!(algebra, Vector);
    check_unary!(algebra, Even);
    check_unary!(algebra, Spinor);
    check_unary!(algebra, Multivector);
    check_grades!(algebra, Even, [grade_0 = 0, grade_2 = 2, grade_4 = 4]);
    algebra.inverse(|a: Vector| a.inverse(), |a, b| a * b);
    algebra.embedding::<Spinor, Even>();
    algebra.embedding::<Vector, Multivector>();
}

#[test]
fn prefixless_f64_operations_match_the_evaluator() {
    use spacetime::*;
    let algebra = spacetime_under_test();
    check_all_pairs!(algebra, [Vector, Rotor, Pseudoscalar, Multivector]);
    check_unary!(algebra, Vector);
    check_unary!(algebra, Rotor);
    check_unary!(algebra, Pseudoscalar);
    check_unary!(algebra, Multivector);
    check_grades!(algebra, Vector, [grade_1 = 1]);
    check_grades!(algebra, Rotor, [grade_0 = 0, grade_2 = 2]);
    check_grades!(algebra, Pseudoscalar, [grade_3 = 3]);
    check_grades!(
        algebra,
        Multivector,
        [grade_0 = 0, grade_1 = 1, grade_2 = 2, grade_3 = 3]
    );
    // Non-degenerate: the polarity exists.
    check_polarity(&algebra);
    algebra.inverse(|a: Vector| a.inverse(), |a, b| a * b);
    algebra.inverse(|a: Rotor| a.inverse(), |a, b| a * b);
    algebra.inverse(|a: Pseudoscalar| a.inverse(), |a, b| a * b);
    algebra.embedding::<Rotor, Multivector>();
    algebra.embedding::<Pseudoscalar, Multivector>();
}

fn check_polarity(algebra: &AlgebraUnderTest) {
    use spacetime::*;
    let ev = &algebra.evaluator;
    algebra.unary(
        "polarity",
        |a: Vector| a.polarity(),
        |a| ev.unary(Operation::Polarity, a).unwrap(),
    );
    algebra.unary(
        "polarity",
        |a: Rotor| a.polarity(),
        |a| ev.unary(Operation::Polarity, a).unwrap(),
    );
    algebra.unary(
        "polarity",
        |a: Pseudoscalar| a.polarity(),
        |a| ev.unary(Operation::Polarity, a).unwrap(),
    );
    algebra.unary(
        "polarity",
        |a: Multivector| a.polarity(),
        |a| ev.unary(Operation::Polarity, a).unwrap(),
    );
}
