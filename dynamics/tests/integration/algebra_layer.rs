//! The algebra layer in both algebras: rigid transforms, exp/log (against the power series and by
//! round trip, at the hard angles), normalisation, the Π-pairing.

use dynamics::exponential::{exp, log};
use dynamics::motor::{self, from_pose, normalise, pose, rotor, translator};
use dynamics::{Algebra, Cga, MotorCoordinates, Pga, ScrewCoordinates};
use nalgebra::{UnitQuaternion, Vector3};

fn screw<A: Algebra>(l: [f64; 3], t: [f64; 3]) -> A::Screw {
    A::screw(ScrewCoordinates {
        l: Vector3::from(l),
        t: Vector3::from(t),
    })
}

fn motor_distance<A: Algebra>(x: A::Motor, y: A::Motor) -> f64 {
    let (x, y) = (A::motor_coordinates(x), A::motor_coordinates(y));
    let parts = [x.scalar - y.scalar, x.pseudoscalar - y.pseudoscalar];
    parts
        .iter()
        .map(|d| d.abs())
        .fold((x.l - y.l).amax().max((x.t - y.t).amax()), f64::max)
}

/// exp by its power series Σ Bᵏ/k!, with powers from the algebra's own products.
fn exp_series<A: Algebra>(b: A::Screw) -> A::Motor {
    let mut term = motor::identity::<A>();
    let mut sum = term;
    for k in 1..40 {
        term = A::motor_times_screw(term, b) * (1.0 / k as f64);
        sum = sum + term;
    }
    sum
}

macro_rules! for_both_algebras {
    ($($test:ident),* $(,)?) => {
        mod pga { $( #[test] fn $test() { super::$test::<dynamics::Pga>(); } )* }
        mod cga { $( #[test] fn $test() { super::$test::<dynamics::Cga>(); } )* }
    };
}

for_both_algebras!(
    rotor_rotates_right_handed,
    translator_moves_points,
    pose_round_trips,
    exp_matches_the_power_series,
    log_inverts_exp,
    exp_log_at_hard_angles,
    normalise_removes_drift,
    pairing_is_dual,
    energy_like_pairing_is_symmetric,
);

fn rotor_rotates_right_handed<A: Algebra>() {
    // theory §2: e1 → cos θ e1 + sin θ e2 for n̂ = e3.
    let theta = 0.3;
    let r = rotor::<A>(Vector3::z(), theta);
    let moved = A::position(A::transform_point(r, A::point(Vector3::x())));
    assert!(
        (moved - Vector3::new(theta.cos(), theta.sin(), 0.0)).norm() < 1e-15,
        "{moved}"
    );
}

fn translator_moves_points<A: Algebra>() {
    let c = Vector3::new(1.0, -2.0, 0.5);
    let x = Vector3::new(0.3, 0.1, -0.7);
    let moved = A::position(A::transform_point(translator::<A>(c), A::point(x)));
    assert!((moved - (x + c)).norm() < 1e-15);
}

fn pose_round_trips<A: Algebra>() {
    let position = Vector3::new(0.4, -1.5, 2.0);
    let rotation = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 1.1));
    let (p, q) = pose::<A>(from_pose::<A>(position, &rotation));
    assert!((p - position).norm() < 1e-14);
    assert!(q.angle_to(&rotation) < 1e-14);
    // And the motor moves a body point like the isometry does.
    let body_point = Vector3::new(1.0, 2.0, 3.0);
    let world = A::position(A::transform_point(
        from_pose::<A>(position, &rotation),
        A::point(body_point),
    ));
    assert!((world - (rotation * body_point + position)).norm() < 1e-14);
}

fn random_screws<A: Algebra>() -> Vec<A::Screw> {
    // A fixed pseudo-random set: rotation parts up to |a| ≈ 1.4 (< π/2), translations up to 3.
    let mut state = 0x2545F4914F6CDD1Du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..50)
        .map(|_| {
            screw::<A>(
                [0.8 * next(), 0.8 * next(), 0.8 * next()],
                [3.0 * next(), 3.0 * next(), 3.0 * next()],
            )
        })
        .collect()
}

fn exp_matches_the_power_series<A: Algebra>() {
    for b in random_screws::<A>() {
        let error = motor_distance::<A>(exp::<A>(b), exp_series::<A>(b));
        assert!(error < 1e-13, "{error}");
    }
}

fn log_inverts_exp<A: Algebra>() {
    for b in random_screws::<A>() {
        let back = A::screw_coordinates(log::<A>(exp::<A>(b)));
        let original = A::screw_coordinates(b);
        assert!((back.l - original.l).amax() < 1e-13 && (back.t - original.t).amax() < 1e-13);
    }
}

fn exp_log_at_hard_angles<A: Algebra>() {
    // Rotation angles φ = 2|a|: 1e-12, 1e-6, π − 1e-9; pure translation; screw motion along the axis.
    let axis = Vector3::new(1.0, 2.0, -2.0) / 3.0;
    for angle in [1e-12, 1e-6, 1e-3, 1.0, std::f64::consts::PI - 1e-9] {
        for translation in [Vector3::zeros(), Vector3::new(0.5, -1.0, 2.0), 1.5 * axis] {
            let m = motor::normalise::<A>(A::compose(translator::<A>(translation), rotor::<A>(axis, angle)));
            let back = exp::<A>(log::<A>(m));
            let error = motor_distance::<A>(back, m);
            assert!(error < 1e-14, "angle {angle}, translation {translation}: {error}");
            let rotation_part = A::screw_coordinates(log::<A>(m)).l.norm();
            assert!(
                (rotation_part - angle / 2.0).abs() < 1e-15 * angle.max(1.0),
                "{rotation_part}"
            );
        }
    }
    let pure_translation = exp::<A>(screw::<A>([0.0; 3], [1.0, 2.0, 3.0]));
    let c = A::motor_coordinates(pure_translation);
    assert_eq!((c.scalar, c.l, c.pseudoscalar), (1.0, Vector3::zeros(), 0.0));
    assert_eq!(c.t, Vector3::new(1.0, 2.0, 3.0));
}

fn normalise_removes_drift<A: Algebra>() {
    // theory §2: a 1e-4 drift inside the subalgebra is corrected to round-off.
    let m = from_pose::<A>(
        Vector3::new(1.0, 2.0, -3.0),
        &UnitQuaternion::from_scaled_axis(Vector3::new(0.5, 0.2, -0.9)),
    );
    let c = A::motor_coordinates(m);
    let drifted = A::motor(MotorCoordinates {
        scalar: c.scalar * (1.0 + 1e-4),
        l: c.l * (1.0 - 1e-4),
        t: c.t + Vector3::repeat(1e-4),
        pseudoscalar: c.pseudoscalar + 1e-4,
    });
    assert!(motor::norm_error::<A>(drifted) > 1e-5);
    let residual = motor::norm_error::<A>(normalise::<A>(drifted));
    assert!(residual < 1e-15, "{residual}");
}

fn pairing_is_dual<A: Algebra>() {
    // theory §1.4: ⟨lᵢ∧tⱼ⟩_Π = δᵢⱼ, lᵢ∧lⱼ = tᵢ∧tⱼ = 0.
    let unit = |k: usize| {
        let mut c = [0.0; 6];
        c[k] = 1.0;
        screw::<A>([c[0], c[1], c[2]], [c[3], c[4], c[5]])
    };
    for i in 0..6 {
        for j in 0..6 {
            let expected = if (i < 3) != (j < 3) && i % 3 == j % 3 { 1.0 } else { 0.0 };
            assert_eq!(A::wedge_pi(unit(i), unit(j)), expected, "{i} {j}");
        }
    }
}

fn energy_like_pairing_is_symmetric<A: Algebra>() {
    let screws = random_screws::<A>();
    for pair in screws.windows(2) {
        let (x, y) = (pair[0], pair[1]);
        assert!((A::wedge_pi(x, y) - A::wedge_pi(y, x)).abs() < 1e-14);
        let (cx, cy) = (A::screw_coordinates(x), A::screw_coordinates(y));
        assert!((A::wedge_pi(x, y) - (cx.l.dot(&cy.t) + cx.t.dot(&cy.l))).abs() < 1e-13);
    }
}

/// Both algebras move points and screws like the same rigid motion, checked against nalgebra.
/// CGA's error is larger: its points carry ½|x|² terms (theory §1.2), so round-off grows with
/// squared distances; the measured worst cases here are about 1.4e-15 (PGA) and 2.5e-13 (CGA).
#[test]
fn cga_and_pga_motors_agree_through_coordinates() {
    let (mut worst_pga, mut worst_cga) = (0.0f64, 0.0f64);
    for (b_pga, b_cga) in random_screws::<Pga>().into_iter().zip(random_screws::<Cga>()) {
        let (m_pga, m_cga) = (exp::<Pga>(b_pga), exp::<Cga>(b_cga));
        let (position, rotation) = pose::<Pga>(m_pga);
        let x = Vector3::new(0.3, -1.0, 2.0);
        let expected = rotation * x + position;
        worst_pga = worst_pga.max((Pga::position(Pga::transform_point(m_pga, Pga::point(x))) - expected).norm());
        worst_cga = worst_cga.max((Cga::position(Cga::transform_point(m_cga, Cga::point(x))) - expected).norm());
        let w = screw::<Pga>([0.1, 0.2, 0.3], [1.0, -1.0, 0.5]);
        let w_cga = screw::<Cga>([0.1, 0.2, 0.3], [1.0, -1.0, 0.5]);
        let (a, b) = (
            Pga::screw_coordinates(Pga::transform_screw(m_pga, w)),
            Cga::screw_coordinates(Cga::transform_screw(m_cga, w_cga)),
        );
        assert!((a.l - b.l).amax() < 1e-13 && (a.t - b.t).amax() < 1e-13);
    }
    println!("worst point error against nalgebra: PGA {worst_pga:.1e}, CGA {worst_cga:.1e}");
    assert!(worst_pga < 1e-14, "{worst_pga}");
    assert!(worst_cga < 1e-12, "{worst_cga}");
}
