//! Emitted code for CGA on a null basis (declared with `metric`) against emitted code for the diagonal
//! Cl(4,1), through the change of basis ninf = e4 + e5, n0 = (e5 − e4)/2 applied blade by blade as an
//! outermorphism Φ. Metric operations commute with Φ; the regressive product and the polarity are
//! relative to the basis pseudoscalar, which Φ maps to −I, so they change sign.

ga_macros::algebra! {
    /// CGA on e1, e2, e3 and the null vectors n0 (origin) and ninf (infinity).
    mod null {
        scalar = f64;
        basis = [e1, e2, e3, n0, ninf];
        metric = [
            [1, 0, 0, 0, 0],
            [0, 1, 0, 0, 0],
            [0, 0, 1, 0, 0],
            [0, 0, 0, 0, -1],
            [0, 0, 0, -1, 0],
        ];
        types {
            Vector = grades(1);
            /// A rigid motion: 8 coefficients, as in PGA.
            Motor = blades(scalar, e1_e2, e1_e3, e2_e3, e1_ninf, e2_ninf, e3_ninf, e1_e2_e3_ninf);
            Even = grades(0, 2, 4);
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    /// CGA Cl(4,1) on an orthonormal basis.
    mod diagonal {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1];
        types {
            Vector = grades(1);
            Even = grades(0, 2, 4);
            Multivector = all;
        }
    }
}

use diagonal::{Geometric as _, Outer as _};

/// Φ of a null-basis multivector: each null blade is the outer product of its vectors' images.
fn change_of_basis(x: null::Multivector) -> diagonal::Multivector {
    let unit = |name: &str| {
        let mut v = diagonal::Multivector::ZERO;
        match name {
            "e1" => v.e1 = 1.0,
            "e2" => v.e2 = 1.0,
            "e3" => v.e3 = 1.0,
            "n0" => (v.e4, v.e5) = (-0.5, 0.5),
            "ninf" => (v.e4, v.e5) = (1.0, 1.0),
            other => panic!("no basis vector {other}"),
        }
        v
    };
    let mut image = diagonal::Multivector::ZERO;
    for (name, coefficient) in null::Multivector::BLADES.iter().zip(x.to_array()) {
        let mut blade = diagonal::Multivector::ZERO;
        blade.scalar = 1.0;
        if *name != "scalar" {
            for vector in name.split('_') {
                blade = blade.outer(unit(vector));
            }
        }
        image += blade * coefficient;
    }
    image
}

/// Small integer coefficients from a fixed xorshift sequence: every product is exact.
struct Numbers(u64);

impl Numbers {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % 9) as f64 - 4.0
    }

    fn multivector(&mut self) -> null::Multivector {
        null::Multivector::from_array(std::array::from_fn(|_| self.next()))
    }
}

#[test]
fn every_operation_matches_the_diagonal_algebra() {
    let mut numbers = Numbers(0x9e37_79b9_7f4a_7c15);
    for _ in 0..50 {
        let (a, b) = (numbers.multivector(), numbers.multivector());
        let (pa, pb) = (change_of_basis(a), change_of_basis(b));
        let scalar = |s: f64| {
            let mut m = diagonal::Multivector::ZERO;
            m.scalar = s;
            m
        };
        let binary = [
            (
                change_of_basis(a.geometric_multivector(b)),
                pa.geometric_multivector(pb),
            ),
            (change_of_basis(a.outer_multivector(b)), pa.outer_multivector(pb)),
            (
                change_of_basis(a.left_contraction_multivector(b)),
                pa.left_contraction_multivector(pb),
            ),
            (
                change_of_basis(a.right_contraction_multivector(b)),
                pa.right_contraction_multivector(pb),
            ),
            (
                scalar(a.scalar_product_multivector(b)),
                scalar(pa.scalar_product_multivector(pb)),
            ),
            (
                change_of_basis(a.hestenes_inner_multivector(b)),
                pa.hestenes_inner_multivector(pb),
            ),
            (change_of_basis(a.fat_dot_multivector(b)), pa.fat_dot_multivector(pb)),
            (
                change_of_basis(a.commutator_multivector(b)),
                pa.commutator_multivector(pb),
            ),
            (change_of_basis(a.sandwich_multivector(b)), pa.sandwich_multivector(pb)),
            (
                change_of_basis(a.regressive_multivector(b)),
                -pa.regressive_multivector(pb),
            ),
        ];
        for (index, (got, expected)) in binary.into_iter().enumerate() {
            assert_eq!(got, expected, "binary operation {index}");
        }
        let unary = [
            (change_of_basis(a.reverse()), pa.reverse()),
            (change_of_basis(a.involute()), pa.involute()),
            (change_of_basis(a.conjugate()), pa.conjugate()),
            (change_of_basis(a.polarity()), -pa.polarity()),
            (change_of_basis(a.grade_2().into()), pa.grade_2().into()),
        ];
        for (index, (got, expected)) in unary.into_iter().enumerate() {
            assert_eq!(got, expected, "unary operation {index}");
        }
        assert_eq!(a.norm_squared(), pa.norm_squared());
    }
}

#[test]
fn null_basis_motors_compose_like_the_diagonal_even_versors() {
    let mut numbers = Numbers(0x2545_f491_4f6c_dd1d);
    for _ in 0..50 {
        let motor = |numbers: &mut Numbers| null::Motor::from_array(std::array::from_fn(|_| numbers.next()));
        let (m, n) = (motor(&mut numbers), motor(&mut numbers));
        let lift = |m: null::Motor| change_of_basis(null::Multivector::from(m));
        let product: null::Motor = m.geometric_motor(n);
        assert_eq!(lift(product), lift(m).geometric(lift(n)));
        let point = null::Vector::from_array(std::array::from_fn(|_| numbers.next()));
        let moved = change_of_basis(m.sandwich_vector(point));
        assert_eq!(moved, lift(m).sandwich_multivector(change_of_basis(point.into())));
    }
}
