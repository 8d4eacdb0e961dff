//! `features = [display]`: `Display` writes the non-zero coefficients as a sum of blades.

ga_macros::algebra! {
    #[allow(dead_code)]
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Motor = grades(0, 2, 4);
            Rotor = blades(scalar, e23, e31, e12);
        }
        ops = [geometric];
        features = [display];
    }
}

fn main() {
    let mut m = pga::Motor::ZERO;
    assert_eq!(m.to_string(), "0");
    assert_eq!(format!("{m:.2}"), "0.00");
    (m.scalar, m.e12, m.e0123) = (1.5, 2.0, -0.5);
    assert_eq!(m.to_string(), "1.5 + 2*e12 - 0.5*e0123");
    (m.scalar, m.e01) = (0.0, -1.0 / 3.0);
    assert_eq!(format!("{m:.3}"), "-0.333*e01 + 2.000*e12 - 0.500*e0123");
    // A permuted field prints under its own name, with its own sign.
    let r = pga::Rotor { scalar: 0.0, e23: 0.0, e31: -1.0, e12: 0.25 };
    assert_eq!(r.to_string(), "-1*e31 + 0.25*e12");
    assert_eq!(pga::Rotor { e23: f64::NAN, ..pga::Rotor::ZERO }.to_string(), "NaN*e23");
}
