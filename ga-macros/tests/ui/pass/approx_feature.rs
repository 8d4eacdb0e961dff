//! `features = [approx]`: `approx::AbsDiffEq`, `RelativeEq` and `UlpsEq`, coefficient by coefficient.

ga_macros::algebra! {
    #[allow(dead_code)]
    mod vga {
        scalar = f32;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Vector = grades(1);
            Rotor = grades(0, 2);
            Multivector = all;
        }
        ops = [geometric, reverse, transform];
        features = [approx];
    }
}

use vga::Transform as _;
use approx::{assert_abs_diff_eq, assert_relative_eq, assert_relative_ne, assert_ulps_eq, relative_eq};

fn main() {
    // A quarter turn in the e1e2 plane, as cos(π/4) − sin(π/4) e12.
    let half = std::f32::consts::FRAC_PI_8 * 2.0;
    let r = vga::Rotor { scalar: half.cos(), e12: -half.sin(), ..vga::Rotor::ZERO };
    let turned = r.transform(vga::Vector { e1: 1.0, e2: 0.0, e3: 0.0 });
    let expected = vga::Vector { e1: 0.0, e2: 1.0, e3: 0.0 };
    assert_abs_diff_eq!(turned, expected, epsilon = 1e-6);
    assert_relative_eq!(r * r.reverse(), vga::Rotor { scalar: 1.0, ..vga::Rotor::ZERO }, max_relative = 1e-6);
    assert_ulps_eq!(r, r);
    assert_relative_ne!(turned, vga::Vector { e3: 1e-3, ..expected });
    assert!(relative_eq!(expected, expected * (1.0 + f32::EPSILON)));
    assert!(!relative_eq!(expected, expected * 1.001));
}
