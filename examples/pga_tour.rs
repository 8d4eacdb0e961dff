//! A tour of the generated PGA: declare the algebra, build a rotor and a translator, compose them
//! into a motor, move a point, and join two points into a line.
//!
//! ```sh
//! cargo run --example pga_tour
//! ```

ga_macros::algebra! {
    /// 3D projective geometric algebra Cl(3,0,1), e0 first.
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Plane = grades(1);
            Line = grades(2);
            /// x e032 + y e013 + z e021 + e123 is the point (x, y, z).
            Point = grades(3);
            Motor = grades(0, 2, 4);
            Translator = blades(scalar, e01, e02, e03);
            Multivector = all;
        }
    }
}

use pga::{Line, Motor, Point, Sandwich, Translator};

/// The point (x, y, z); `e032` and `e021` are stored as −`e023` and −`e012`.
fn point(x: f64, y: f64, z: f64) -> Point {
    Point {
        e012: -z,
        e013: y,
        e023: -x,
        e123: 1.0,
    }
}

/// The Euclidean coordinates of a finite point.
fn coordinates(p: Point) -> [f64; 3] {
    [-p.e023 / p.e123, p.e013 / p.e123, -p.e012 / p.e123]
}

/// Translation by (x, y, z): 1 − ½ e0 (x e1 + y e2 + z e3).
fn translator(x: f64, y: f64, z: f64) -> Translator {
    Translator {
        scalar: 1.0,
        e01: -x / 2.0,
        e02: -y / 2.0,
        e03: -z / 2.0,
    }
}

/// Rotation by `angle` about the z axis (through the origin), counterclockwise seen from +z.
fn rotor_about_z(angle: f64) -> Motor {
    let half = angle / 2.0;
    Motor {
        scalar: half.cos(),
        e12: -half.sin(),
        ..Motor::ZERO
    }
}

/// One unit along x; composed with itself at compile time, since every product is a `const fn`.
const STEP_X: Translator = Translator {
    scalar: 1.0,
    e01: -0.5,
    e02: 0.0,
    e03: 0.0,
};
const TWO_STEPS_X: Translator = STEP_X.geometric_translator(STEP_X);

fn assert_near(got: [f64; 3], expected: [f64; 3]) {
    let error = got.iter().zip(expected).map(|(g, e)| (g - e).abs()).fold(0.0, f64::max);
    assert!(error < 1e-12, "got {got:?}, expected {expected:?}");
}

fn main() {
    // Rotate a quarter turn about z, then translate by (1, 2, 3): the motor is translator × rotor.
    let motor: Motor = translator(1.0, 2.0, 3.0) * rotor_about_z(std::f64::consts::FRAC_PI_2);
    let moved = motor.sandwich(point(1.0, 0.0, 0.0));
    println!("(1, 0, 0) moves to {:?}", coordinates(moved));
    assert_near(coordinates(moved), [1.0, 3.0, 3.0]);

    // Composing motors is their geometric product (here as the const fn form, usable in constants):
    // (1, 3, 3) turns to (−3, 1, 3) and moves to (−2, 3, 6).
    let twice = motor.geometric_motor(motor);
    assert_near(coordinates(twice.sandwich(point(1.0, 0.0, 0.0))), [-2.0, 3.0, 6.0]);

    assert_near(coordinates(TWO_STEPS_X.sandwich(point(0.0, 0.0, 0.0))), [2.0, 0.0, 0.0]);

    // The join (regressive product, `&`) of two points is the line through them; joining it with
    // a third point on it gives zero, with a point off it a plane.
    let axis: Line = point(0.0, 0.0, 0.0) & point(0.0, 0.0, 1.0);
    println!("the z axis: {axis:?}");
    assert_eq!(axis & point(0.0, 0.0, 5.0), pga::Plane::ZERO);
    assert_ne!(axis & point(1.0, 0.0, 0.0), pga::Plane::ZERO);

    // A unit motor's reverse undoes it. (Motors get no `inverse`: M ~M = s + p e0123 is not a
    // scalar for every even element, and the compiler emits `inverse` only where it is.)
    let back = motor.reverse().sandwich(moved);
    assert_near(coordinates(back), [1.0, 0.0, 0.0]);
    println!("every check passed");
}
