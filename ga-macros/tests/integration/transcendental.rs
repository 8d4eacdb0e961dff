//! `exp`, `log`, `sqrt` and `normalized` generated in closed form (`ga_codegen::transcendental`), checked against
//! the exponential series summed with the generated geometric product, and by round trips: at zero, at tiny and
//! large angles, for pure translations (PGA, CGA on the null basis) and for boosts (Cl(2,1)).

ga_macros::algebra! {
    mod pga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e0 = 0];
        types {
            Motor = blades(scalar, e23, e31, e12, e10, e20, e30, e1230);
            Line = blades(e23, e31, e12, e10, e20, e30);
            Multivector = all;
        }
        fn exp_line(b: Line) -> Motor = exp(b);
        fn log_motor(m: Motor) -> Line = log(m);
        fn sqrt_motor(m: Motor) -> Motor = sqrt(m);
        fn normalized_motor(m: Motor) -> Motor = normalized(m);
    }
}

ga_macros::algebra! {
    mod cga {
        scalar = f64;
        basis = [e1, e2, e3, n0, ninf];
        metric = [[1, 0, 0, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1, 0, 0], [0, 0, 0, 0, -1], [0, 0, 0, -1, 0]];
        types {
            Motor = blades(scalar, e2_e3, e3_e1, e1_e2, e1_ninf, e2_ninf, e3_ninf, e1_e2_e3_ninf);
            Screw = blades(e2_e3, e3_e1, e1_e2, e1_ninf, e2_ninf, e3_ninf);
            Multivector = all;
        }
        ops = [geometric, reverse];
        fn exp_screw(b: Screw) -> Motor = exp(b);
        fn log_motor(m: Motor) -> Screw = log(m);
        fn sqrt_motor(m: Motor) -> Motor = sqrt(m);
    }
}

/// A test algebra with bivectors, even elements (`Even`, of the grades given) and their closed forms `exp_bivector`
/// and `log_even` (and, with `roots`, `sqrt_even` and `normalized_even`).
macro_rules! bivector_algebra {
    ($(#[$doc:meta])* $name:ident: $scalar:ident [$($basis:tt)*], even = ($($grade:literal),*) { $($roots:tt)* }) => {
        ga_macros::algebra! {
            $(#[$doc])*
            mod $name {
                scalar = $scalar;
                basis = [$($basis)*];
                types {
                    Bivector = grades(2);
                    Even = grades($($grade),*);
                    Multivector = all;
                }
                ops = [geometric];
                fn exp_bivector(b: Bivector) -> Even = exp(b);
                fn log_even(m: Even) -> Bivector = log(m);
                $($roots)*
            }
        }
    };
    ($(#[$doc:meta])* $name:ident: $scalar:ident [$($basis:tt)*], even = ($($grade:literal),*), roots) => {
        bivector_algebra!($(#[$doc])* $name: $scalar [$($basis)*], even = ($($grade),*) {
            fn sqrt_even(m: Even) -> Even = sqrt(m);
            fn normalized_even(m: Even) -> Even = normalized(m);
        });
    };
    ($(#[$doc:meta])* $name:ident: $scalar:ident [$($basis:tt)*], even = ($($grade:literal),*)) => {
        bivector_algebra!($(#[$doc])* $name: $scalar [$($basis)*], even = ($($grade),*) {});
    };
}

bivector_algebra!(
    /// 2D PGA.
    pga2: f64 [e0 = 0, e1 = 1, e2 = 1], even = (0, 2), roots
);
bivector_algebra!(
    /// Cl(2,1): rotations in the e1e2 plane and boosts in e1e3, e2e3.
    lorentz: f64 [e1 = 1, e2 = 1, e3 = -1], even = (0, 2), roots
);
bivector_algebra!(
    /// Rotors of Euclidean 3-space in single precision.
    vga32: f32 [e1 = 1, e2 = 1, e3 = 1], even = (0, 2), roots
);
bivector_algebra!(
    /// Euclidean 4-space: bivectors with two planes of rotation.
    cl4: f64 [e1 = 1, e2 = 1, e3 = 1, e4 = 1], even = (0, 2, 4), roots
);
bivector_algebra!(
    /// Spacetime algebra Cl(1,3): a boost and a rotation in orthogonal planes.
    sta: f64 [e0 = 1, e1 = -1, e2 = -1, e3 = -1], even = (0, 2, 4), roots
);
bivector_algebra!(
    /// CGA Cl(4,1) on its diagonal basis, with every bivector (rotations, translations, dilations, transversions).
    conformal: f64 [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1], even = (0, 2, 4)
);
bivector_algebra!(
    /// Cl(2,2): with two basis vectors of each sign a bivector's planes can have a complex pair of squares, or be
    /// two boosts.
    split: f64 [e1 = 1, e2 = 1, e3 = -1, e4 = -1], even = (0, 2, 4), roots
);
bivector_algebra!(
    /// Cl(3,2), the other five-dimensional signature with two vectors of each sign.
    split5: f64 [e1 = 1, e2 = 1, e3 = 1, e4 = -1, e5 = -1], even = (0, 2, 4)
);

/// The largest coefficient difference between two coefficient arrays.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// `Σ xᵏ/k!` to 60 terms, with the generated product: the reference for `exp`.
macro_rules! series {
    ($module:ident, $x:expr) => {{
        let x: $module::Multivector = $x;
        let mut term = $module::Multivector::ZERO;
        term.scalar = 1.0;
        let mut sum = term;
        for k in 1..60 {
            term = term * x * (1.0 / k as f64);
            sum += term;
        }
        sum
    }};
}

/// `exp(b)` against the series, `log(exp(b)) = b` within `log_tolerance` and `sqrt(m)² = m` (both relative to the
/// size of `exp(b)`); returns `exp(b)` for further checks.
macro_rules! round_trips {
    ($module:ident, $bivector:ident, $exp:ident, $log:ident, $sqrt:ident, $coefficients:expr, $log_tolerance:expr) => {{
        let coefficients = $coefficients;
        let b = $module::$bivector::from_array(coefficients);
        let m = $module::$exp(b);
        let reference = series!($module, $module::Multivector::from(b));
        let scale = reference.to_array().iter().fold(1.0f64, |a, x| a.max(x.abs()));
        let error = distance(&$module::Multivector::from(m).to_array(), &reference.to_array());
        assert!(
            error < 1e-14 * scale,
            "exp({coefficients:?}) is {error:e} from the series"
        );
        let back = $module::$log(m);
        let error = distance(&back.to_array(), &coefficients);
        assert!(
            error < $log_tolerance,
            "log(exp({coefficients:?})) is {error:e} off: {back:?}"
        );
        let root = $module::$sqrt(m);
        assert!(distance(&(root * root).to_array(), &m.to_array()) < 1e-14 * scale);
        (b, m, root)
    }};
}

#[test]
fn pga_exp_is_the_series_and_log_inverts_it() {
    let lines = [
        [0.0; 6],
        [1e-9, -2e-9, 0.5e-9, 1e-9, 0.0, 3e-9],
        [0.0, 0.0, 0.0, 1.5, -2.0, 0.25], // a pure translation
        [0.3, -0.2, 0.1, 0.5, 1.0, -0.7],
        [1.2, 0.4, -0.6, -3.0, 2.0, 1.0],
        // Half-angle π/2 − 1e-6: a turn by almost π about (1, 2, 2)/3, and along it.
        {
            let h = std::f64::consts::FRAC_PI_2 - 1e-6;
            [h / 3.0, 2.0 * h / 3.0, 2.0 * h / 3.0, 0.4, -0.1, 0.3]
        },
    ];
    for coefficients in lines {
        let size = coefficients.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let (b, m, root) = round_trips!(
            pga,
            Line,
            exp_line,
            log_motor,
            sqrt_motor,
            coefficients,
            1e-13 * (1.0 + size)
        );
        assert!(distance(&root.to_array(), &pga::exp_line(b * 0.5).to_array()) < 1e-14);
        // A scaled motor with a drifted e1230 part normalises back to a unit motor.
        let mut drifted = m * 2.5;
        drifted.e1230 += 1e-6;
        let unit = pga::normalized_motor(drifted);
        let norm = unit * unit.reverse();
        assert!(
            (norm.scalar - 1.0).abs() < 1e-15 && norm.e1230.abs() < 1e-15,
            "{norm:?}"
        );
    }
}

#[test]
fn plane_pga_exp_log_sqrt() {
    for coefficients in [[0.0, 0.0, 0.0], [0.7, -1.0, 2.0], [0.0, 3.0, -1.0], [1e-8, 2e-8, -3.0]] {
        round_trips!(pga2, Bivector, exp_bivector, log_even, sqrt_even, coefficients, 1e-14);
    }
}

#[test]
fn null_basis_cga_exp_log_sqrt() {
    for coefficients in [
        [0.0; 6],
        [0.0, 0.0, 0.0, 1.0, 2.0, -1.0],
        [0.4, -0.3, 0.2, 1.0, 0.5, -2.0],
        [1.1, 0.2, 0.9, -1.0, 0.0, 1.5],
    ] {
        round_trips!(cga, Screw, exp_screw, log_motor, sqrt_motor, coefficients, 1e-13);
    }
}

#[test]
fn lorentz_boosts_and_rotations() {
    // e12 squares to −1 (a rotation), e13 and e23 to +1 (boosts), and mixtures of either sign of ⟨b²⟩₀.
    for coefficients in [
        [0.0, 0.0, 0.0],
        [0.8, 0.0, 0.0],
        [0.0, 1.5, 0.0],
        [0.3, 2.0, -1.0],
        [2.0, 0.5, 0.5],
        [1e-9, 0.0, 1e-9],
    ] {
        let (_, m, _) = round_trips!(
            lorentz,
            Bivector,
            exp_bivector,
            log_even,
            sqrt_even,
            coefficients,
            1e-13
        );
        let scale = m.to_array().iter().fold(1.0f64, |a, x| a.max(x.abs()));
        let unit = lorentz::normalized_even(m * 3.0);
        assert!(distance(&unit.to_array(), &m.to_array()) < 1e-14 * scale);
    }
}

#[test]
fn single_precision_rotors() {
    let b = vga32::Bivector::from_array([0.3, -1.2, 0.4]);
    let r = vga32::exp_bivector(b);
    // Half-angle |b| = 1.3: cos and sin of it, along b.
    let angle = (0.09f32 + 1.44 + 0.16).sqrt();
    assert!((r.scalar - angle.cos()).abs() < 1e-6);
    let back = vga32::log_even(vga32::normalized_even(r * 4.0));
    let error = back
        .to_array()
        .iter()
        .zip(b.to_array())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0f32, f32::max);
    assert!(error < 1e-6, "{error:e}");
}

/// `exp(b)` against the series, relative to the size of the result.
macro_rules! exp_is_the_series {
    ($module:ident, $coefficients:expr) => {{
        let coefficients = $coefficients;
        let b = $module::Bivector::from_array(coefficients);
        let reference = series!($module, $module::Multivector::from(b));
        let scale = reference.to_array().iter().fold(1.0f64, |a, x| a.max(x.abs()));
        let m = $module::Multivector::from($module::exp_bivector(b));
        let error = distance(&m.to_array(), &reference.to_array());
        assert!(
            error < 2e-14 * scale,
            "exp({coefficients:?}) is {error:e} from the series (scale {scale:e})"
        );
    }};
}

#[test]
fn two_planes_of_rotation() {
    // Blades e12, e13, e14, e23, e24, e34: zero, tiny, generic, isoclinic (λ₁ = λ₂ = −1 and −9), nearly isoclinic
    // (the half-sum and half-difference forms), one plane, and planes of very different sizes.
    for coefficients in [
        [0.0; 6],
        [1e-9, 0.0, 2e-9, 0.0, -1e-9, 3e-9],
        [0.3, -0.5, 0.7, 1.1, -0.2, 0.4],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        [3.0, 0.0, 0.0, 0.0, 0.0, 3.0],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0001],
        [2.0, 0.0, 0.0, 0.0, 0.0, 2.0 + 1e-9],
        [0.0, 0.0, 0.0, 2.5, 0.0, 0.0],
        [3.0, 0.0, 0.0, 0.0, 0.0, 1e-3],
    ] {
        exp_is_the_series!(cl4, coefficients);
    }
}

#[test]
fn spacetime_boosts_and_rotations() {
    // Blades e01, e02, e03 (boosts, square +1), e12, e13, e23 (rotations, square −1): pure, mixed with E·B ≠ 0,
    // null (E ⟂ B, |E| = |B|), and tiny.
    for coefficients in [
        [1.5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 2.0],
        [1.0, 0.5, -0.3, 0.2, 0.8, -1.1],
        [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        [1e-8, 0.0, 2e-8, 0.0, 1e-8, 0.0],
        [2.0, 1.0, 0.0, 0.0, 0.0, 3.0],
    ] {
        exp_is_the_series!(sta, coefficients);
    }
}

#[test]
fn conformal_bivectors() {
    for coefficients in [
        [0.3, -0.2, 0.5, 0.1, 0.7, -0.4, 0.2, 0.6, -0.3, 0.9],
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        [0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0],
        [1.2, 0.3, -0.4, 2.0, 0.1, 0.0, -1.5, 0.2, 0.8, 0.6],
    ] {
        exp_is_the_series!(conformal, coefficients);
        // Every bivector of Cl(4,1) turns in at most two planes with real squares: log inverts exp.
        let b = conformal::Bivector::from_array(coefficients);
        let back = conformal::log_even(conformal::exp_bivector(b));
        assert!(
            distance(&back.to_array(), &coefficients) < 1e-12,
            "log(exp({coefficients:?})) = {back:?}"
        );
    }
}

#[test]
fn two_plane_square_roots_and_normalisation() {
    // sqrt(m)² = m and sqrt(exp(b)) = exp(b/2); normalized(k m) = m, for Cl(4) and STA elements turning in two
    // planes (the 4-vector part of m ~m then squares to a positive or a negative scalar).
    macro_rules! check {
        ($module:ident, $coefficients:expr) => {{
            let b = $module::Bivector::from_array($coefficients);
            let m = $module::exp_bivector(b);
            let scale = m.to_array().iter().fold(1.0f64, |a, x| a.max(x.abs()));
            let root = $module::sqrt_even(m);
            assert!(
                distance(&(root * root).to_array(), &m.to_array()) < 1e-13 * scale,
                "{m:?}"
            );
            assert!(distance(&root.to_array(), &$module::exp_bivector(b * 0.5).to_array()) < 1e-13 * scale);
            let unit = $module::normalized_even(m * 2.5);
            assert!(
                distance(&unit.to_array(), &m.to_array()) < 1e-13 * scale,
                "{unit:?} against {m:?}"
            );
        }};
    }
    for coefficients in [
        [0.3, -0.5, 0.7, 1.1, -0.2, 0.4],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        [0.0, 0.0, 0.0, 1.2, 0.0, 0.0],
    ] {
        check!(cl4, coefficients);
    }
    for coefficients in [
        [1.0, 0.5, -0.3, 0.2, 0.8, -1.1],
        [1.5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
    ] {
        check!(sta, coefficients);
    }
}

#[test]
fn two_plane_logarithms() {
    // log(exp(b)) = b while each plane turns by less than π/2 (Cl(4): isoclinic, nearly isoclinic, generic, one
    // plane, tiny), and exp(log(m)) = m beyond that.
    for coefficients in [
        [0.0; 6],
        [1e-9, 0.0, 2e-9, 0.0, -1e-9, 3e-9],
        [0.3, -0.5, 0.7, 1.1, -0.2, 0.4],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0001],
        [0.0, 0.0, 0.0, 1.2, 0.0, 0.0],
        [1.4, 0.0, 0.0, 0.0, 0.0, 0.2],
    ] {
        let b = cl4::Bivector::from_array(coefficients);
        let m = cl4::exp_bivector(b);
        let back = cl4::log_even(m);
        assert!(
            distance(&back.to_array(), &coefficients) < 1e-12,
            "log(exp({coefficients:?})) = {back:?}"
        );
    }
    for coefficients in [[2.0, 0.3, -0.4, 1.0, 0.5, 2.5], [3.0, 0.0, 0.0, 0.0, 0.0, 2.9]] {
        let m = cl4::exp_bivector(cl4::Bivector::from_array(coefficients));
        let again = cl4::exp_bivector(cl4::log_even(m));
        assert!(
            distance(&again.to_array(), &m.to_array()) < 1e-12,
            "exp(log(m)) = {again:?}, m = {m:?}"
        );
    }
    // STA: boosts, rotations, both with E·B ≠ 0, and a null bivector.
    for coefficients in [
        [1.5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 1.2],
        [1.0, 0.5, -0.3, 0.2, 0.8, -1.1],
        [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        [2.0, 1.0, 0.0, 0.0, 0.0, 1.3],
    ] {
        let b = sta::Bivector::from_array(coefficients);
        let back = sta::log_even(sta::exp_bivector(b));
        assert!(
            distance(&back.to_array(), &coefficients) < 1e-12,
            "log(exp({coefficients:?})) = {back:?}"
        );
    }
}

#[test]
fn careless_arguments_give_not_a_number_never_a_quiet_value() {
    let nan_everywhere = |values: &[f64]| values.iter().all(|x| x.is_nan());
    // log of the zero element, of an element with ⟨m ~m⟩₀ < 0 (a pure boost bivector of Cl(2,1) as an "even
    // element") and of NaN: no logarithm, every coefficient NaN (a zero screw would be a quiet wrong answer).
    assert!(nan_everywhere(&pga::log_motor(pga::Motor::ZERO).to_array()));
    assert!(nan_everywhere(
        &lorentz::log_even(lorentz::Even::from_array([0.0, 0.0, 1.0, 0.0])).to_array()
    ));
    assert!(nan_everywhere(
        &pga::log_motor(pga::Motor::from_array([f64::NAN; 8])).to_array()
    ));
    assert!(nan_everywhere(&cl4::log_even(cl4::Even::ZERO).to_array()));
    // The same with two basis vectors of each sign (the complex-pair branches).
    assert!(nan_everywhere(&split::log_even(split::Even::ZERO).to_array()));
    assert!(nan_everywhere(
        &split::log_even(split::Even::from_array([f64::NAN; 8])).to_array()
    ));
    assert!(split::exp_bivector(split::Bivector::from_array([f64::NAN; 6]))
        .to_array()
        .iter()
        .any(|x| x.is_nan()));
    // A complex pair too large for cosh overflows rather than returning a finite value.
    let huge = split::exp_bivector(split::Bivector::from_array([1e3, 1e3, 0.0, 0.0, -1e3, 1e3]));
    assert!(huge.to_array().iter().any(|x| !x.is_finite()), "{huge:?}");
    // exp and normalized pass NaN on; normalized of zero has no scale to divide by.
    assert!(pga::exp_line(pga::Line::from_array([f64::NAN; 6]))
        .to_array()
        .iter()
        .any(|x| x.is_nan()));
    assert!(cl4::exp_bivector(cl4::Bivector::from_array([f64::NAN; 6]))
        .to_array()
        .iter()
        .any(|x| x.is_nan()));
    assert!(pga::normalized_motor(pga::Motor::ZERO)
        .to_array()
        .iter()
        .any(|x| x.is_nan()));
    // A huge translation is exact (1 + t), and a huge boost overflows to infinity rather than to a finite value.
    let huge = pga::exp_line(pga::Line::from_array([0.0, 0.0, 0.0, 1e300, -1e300, 0.0]));
    assert_eq!((huge.scalar, huge.e10, huge.e20), (1.0, 1e300, -1e300));
    let boost = lorentz::exp_bivector(lorentz::Bivector::from_array([0.0, 1e3, 0.0]));
    assert!(boost.to_array().iter().any(|x| x.is_infinite()), "{boost:?}");
}

/// Checks that a test bivector's planes have a complex pair of squares, or real ones, as `complex_pair` claims
/// (if it claims either): the sign of the discriminant `⟨b²⟩₀² − ⟨W²⟩₀`, from the generated product
/// (`b² = λ₁ + λ₂ + W` with W its 4-vector part).
macro_rules! assert_squares {
    ($module:ident, $coefficients:expr, $complex_pair:expr) => {{
        let b = $module::Multivector::from($module::Bivector::from_array($coefficients));
        let square = b * b;
        let mut wedge = square;
        wedge.scalar = 0.0;
        let discriminant = square.scalar * square.scalar - (wedge * wedge).scalar;
        if let Some(complex_pair) = $complex_pair {
            assert_eq!(discriminant < 0.0, complex_pair, "{:?}", $coefficients);
        }
    }};
}

#[test]
fn split_signature_complex_squares_and_boosts() {
    // Blades e12, e13, e14, e23, e24, e34 of Cl(2,2) (e12 and e34 rotate, the others boost). λ = ±2i; the same
    // scaled into the series (|λ| = 0.08, 2e-6, 2e-18); a pair barely complex and barely real; two isoclinic rotations and
    // boosts (a double root); two close boosts (the hyperbolic half-sum forms); a boost and a rotation; generic.
    let complex = [1.0, 1.0, 0.0, 0.0, -1.0, 1.0];
    let cases = [
        (complex, Some(true)),
        (complex.map(|x| 0.2 * x), Some(true)),
        (complex.map(|x| 1e-3 * x), Some(true)),
        (complex.map(|x| 1e-9 * x), Some(true)),
        ([1.0, 1.0, 0.0, 0.0, -1.0, 1.0 + 1e-7], Some(true)),
        ([1.0, 1.0 + 1e-7, 0.0, 0.0, -1.0, 1.0], None),
        ([1.0, 0.0, 0.0, 0.0, 0.0, 1.0], None),
        ([0.0, 1.0, 0.0, 0.0, 1.0, 0.0], None),
        ([0.0, 1.0, 0.0, 0.0, 1.0001, 0.0], Some(false)),
        ([0.0, 1.3, 0.0, 0.0, 0.0, 0.7], Some(false)),
        ([0.3, -0.5, 0.7, 1.1, -0.2, 0.4], None),
    ];
    for (coefficients, complex_pair) in cases {
        // The cases are what they claim to be.
        assert_squares!(split, coefficients, complex_pair);
        exp_is_the_series!(split, coefficients);
        let (b, m, root) = round_trips!(split, Bivector, exp_bivector, log_even, sqrt_even, coefficients, 1e-12);
        let scale = m.to_array().iter().fold(1.0f64, |a, x| a.max(x.abs()));
        assert!(distance(&root.to_array(), &split::exp_bivector(b * 0.5).to_array()) < 1e-13 * scale);
        let unit = split::normalized_even(m * 2.5);
        assert!(
            distance(&unit.to_array(), &m.to_array()) < 1e-13 * scale,
            "{unit:?} against {m:?}"
        );
    }
    // Beyond the principal range (λ = ±18i turns by 3 > π/2 in the complex plane) log finds another logarithm:
    // exp(log(m)) = m.
    for coefficients in [complex.map(|x| 3.0 * x), [2.0, 0.3, -0.4, 1.0, 0.5, 2.5]] {
        let m = split::exp_bivector(split::Bivector::from_array(coefficients));
        let again = split::exp_bivector(split::log_even(m));
        let scale = m.to_array().iter().fold(1.0f64, |a, x| a.max(x.abs()));
        assert!(
            distance(&again.to_array(), &m.to_array()) < 1e-12 * scale,
            "exp(log(m)) = {again:?}, m = {m:?}"
        );
    }
    // A unit element with a complex pair and ⟨m⟩₀ < 0 has no logarithm (c₁c₂ = |c₁|² > 0 for every b): NaN.
    let m = split::exp_bivector(split::Bivector::from_array(complex.map(|x| 3.0 * x)));
    assert!(
        split::log_even(m * -1.0).to_array().iter().all(|x| x.is_nan()),
        "{:?}",
        split::log_even(m * -1.0)
    );
}

#[test]
fn split_five_dimensional_signature() {
    // Cl(3,2) (blades e12, e13, e14, e15, e23, e24, e25, e34, e35, e45): exp against the series and log(exp(b)) = b
    // for bivectors with a complex pair (generic, and λ = ±2i), two isoclinic rotations (e12 + e45) and boosts
    // (e14 + e35), two boosts apart, and zero.
    for (coefficients, complex_pair) in [
        ([0.4, -0.3, 0.2, 0.5, 0.1, -0.6, 0.3, 0.2, -0.4, 0.7], Some(true)),
        ([0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -1.0, 0.0, 1.0], Some(true)),
        ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], None),
        ([0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0], None),
        ([0.0, 0.0, 1.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.7, 0.0], Some(false)),
        ([0.0; 10], None),
    ] {
        assert_squares!(split5, coefficients, complex_pair);
        exp_is_the_series!(split5, coefficients);
        let b = split5::Bivector::from_array(coefficients);
        let back = split5::log_even(split5::exp_bivector(b));
        assert!(
            distance(&back.to_array(), &coefficients) < 1e-12,
            "log(exp({coefficients:?})) = {back:?}"
        );
    }
}

ga_macros::algebra! {
    /// Cl(1,0,1): one Euclidean and one null vector, whose only bivector squares to zero.
    mod degenerate {
        scalar = f64;
        basis = [e1 = 1, e0 = 0];
        types {
            Bivector = grades(2);
            Even = grades(0, 2);
        }
        /// exp of a null bivector: `1 + b`.
        fn exp_bivector(b: Bivector) -> Even = exp(b);
        fn log_even(m: Even) -> Bivector = log(m);
        /// Documentation on a fused expression is the emitted function's.
        ///
        /// (Once refused as an attribute.)
        fn twice(b: Bivector) -> Bivector = b + b;
    }
}

ga_macros::algebra! {
    /// Two null vectors that are also orthogonal: the metric is zero.
    mod all_null {
        scalar = f32;
        basis = [a = 0, b = 0];
        types {
            Bivector = grades(2);
            Even = grades(0, 2);
        }
        fn exp_bivector(b: Bivector) -> Even = exp(b);
        fn log_even(m: Even) -> Bivector = log(m);
    }
}

#[test]
fn metrics_whose_invariants_vanish() {
    // Every bivector squares to zero, so exp(b) = 1 + b and log(1 + b) = b (the emitted code once did not compile:
    // its empty invariants were untyped literals).
    for x in [0.5, -3.0, 0.0, 1e-9, 1e9] {
        let m = degenerate::exp_bivector(degenerate::Bivector { e10: x });
        assert_eq!((m.scalar, m.e10), (1.0, x));
        assert_eq!(degenerate::log_even(m).e10, x);
    }
    assert_eq!(degenerate::twice(degenerate::Bivector { e10: 0.5 }).e10, 1.0);
    let m = all_null::exp_bivector(all_null::Bivector { a_b: 0.25 });
    assert_eq!((m.scalar, m.a_b), (1.0, 0.25));
    assert_eq!(all_null::log_even(m).a_b, 0.25);
}
