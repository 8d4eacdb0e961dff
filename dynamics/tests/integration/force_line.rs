//! The wrench of a force f along the line through a (theory §3) is the line itself, built from the
//! algebras' own products: in CGA the dual of the OPNS line, `(up(a) ∧ up(a+f) ∧ n∞) I5`; in PGA
//! `f I3 − (a∧f) I3 e0`. `forces::force_line` builds it from coordinates instead, `Σ fᵢlᵢ + (a⨯f)ᵢtᵢ`.

use crate::common;

use common::Random;
use dynamics::cga::generated as cga;
use dynamics::pga::generated as pga;
use dynamics::{forces, Algebra, Cga, Pga};
use nalgebra::Vector3;

/// CGA's products sum terms of size |a|²|f| (≲ 230 here) that cancel down to |a||f|: measured worst
/// coefficient difference over the 100 random lines 4.3e-14.
const CGA_TOLERANCE: f64 = 1e-13;
/// PGA's products form the same single products aᵢfⱼ as the cross product: measured difference 0.
const PGA_TOLERANCE: f64 = 1e-14;

fn up(x: Vector3<f64>) -> cga::Vector {
    // Written out here (theory §1.2), not taken from `Cga::point`: up(x) = x + ½|x|² n∞ + n0.
    cga::Vector {
        e1: x.x,
        e2: x.y,
        e3: x.z,
        n0: 1.0,
        ninf: 0.5 * x.norm_squared(),
    }
}

fn cga_dual_line(a: Vector3<f64>, f: Vector3<f64>) -> cga::Bivector {
    let infinity = cga::Vector {
        ninf: 1.0,
        ..cga::Vector::ZERO
    };
    // I₅ = e12345 = −e1_e2_e3_n0_ninf (e4∧e5 = −n0∧n∞ with e4 = ½n∞ − n0, e5 = ½n∞ + n0).
    let pseudoscalar = cga::Odd {
        e1_e2_e3_n0_ninf: -1.0,
        ..cga::Odd::ZERO
    };
    let line = up(a).outer_vector(up(a + f)).outer_vector(infinity);
    line.geometric_odd(pseudoscalar).grade_2()
}

fn pga_line(a: Vector3<f64>, f: Vector3<f64>) -> pga::Motor {
    let vector = |v: Vector3<f64>| pga::Plane {
        e1: v.x,
        e2: v.y,
        e3: v.z,
        e0: 0.0,
    };
    let i3 = pga::Point {
        e123: 1.0,
        ..pga::Point::ZERO
    };
    let e0 = pga::Plane {
        e0: 1.0,
        ..pga::Plane::ZERO
    };
    let direction = vector(f).geometric_point(i3);
    let moment = vector(a).outer_plane(vector(f)).geometric_point(i3).geometric_plane(e0);
    direction - moment
}

#[test]
fn force_line_is_the_dual_cga_line() {
    let mut random = Random::new(17);
    let mut worst = 0.0f64;
    for _ in 0..100 {
        let (a, f) = (random.vector(5.0), random.vector(3.0));
        let expected = cga_dual_line(a, f);
        let actual = forces::force_line::<Cga>(f, a);
        // Every bivector coefficient, including those off span{lᵢ, tᵢ} (eᵢ∧n0, n0∧n∞), which must vanish.
        let difference = (expected - cga::Bivector::from(actual)).to_array();
        worst = difference.iter().fold(worst, |w, d| w.max(d.abs()));
    }
    println!("CGA: worst coefficient difference {worst:.1e}");
    assert!(worst < CGA_TOLERANCE, "{worst:.2e}");
}

#[test]
fn force_line_is_the_pga_line() {
    let mut random = Random::new(23);
    let mut worst = 0.0f64;
    for _ in 0..100 {
        let (a, f) = (random.vector(5.0), random.vector(3.0));
        let expected = pga_line(a, f);
        let actual = forces::force_line::<Pga>(f, a);
        let difference = [
            expected.scalar,
            expected.e23 - actual.e23,
            expected.e31 - actual.e31,
            expected.e12 - actual.e12,
            expected.e10 - actual.e10,
            expected.e20 - actual.e20,
            expected.e30 - actual.e30,
            expected.e1230,
        ];
        worst = difference.iter().fold(worst, |w, d| w.max(d.abs()));
    }
    println!("PGA: worst coefficient difference {worst:.1e}");
    assert!(worst < PGA_TOLERANCE, "{worst:.2e}");
}

/// The PGA line passes through a and a + f and not through a point beside it: `L × X = 0` iff X is on L
/// (theory §1.3).
#[test]
fn pga_force_line_passes_through_its_point() {
    let mut random = Random::new(29);
    for _ in 0..100 {
        let (a, f) = (random.vector(5.0), random.vector(3.0));
        let line = forces::force_line::<Pga>(f, a);
        let incidence = |x: Vector3<f64>| {
            let product = pga::Line::commutator_point(line, Pga::point(x));
            [product.e123, product.e230, product.e310, product.e120]
                .iter()
                .fold(0.0f64, |w, c| w.max(c.abs()))
        };
        let beside = f.cross(&Vector3::new(0.3, -0.4, 0.5)).normalize();
        assert!(incidence(a) < 1e-13 && incidence(a + 0.7 * f) < 1e-13);
        assert!(incidence(a + beside) > 1e-3 * f.norm());
    }
}
