//! The cost model against known minimal counts.
mod common;

use ga_codegen::{functions, Algebra, Cost, Operation};

#[test]
fn pga_motor_product_is_the_cayley_minimum() {
    let algebra = Algebra::new(&common::pga()).unwrap();
    let cost = functions::cost(&algebra, Operation::Geometric, "Motor", Some("Motor"))
        .unwrap()
        .unwrap();
    assert_eq!(
        cost,
        Cost {
            multiplies: 48,
            adds: 40,
            divisions: 0
        }
    );
}

#[test]
fn fused_pga_motor_sandwich_of_a_point_beats_two_products() {
    let algebra = Algebra::new(&common::pga()).unwrap();
    let fused = functions::cost(&algebra, Operation::Sandwich, "Motor", Some("Point"))
        .unwrap()
        .unwrap();
    eprintln!("PGA motor sandwich point: {fused}");
    assert!(fused.multiplies < 48, "{fused}");
}

#[test]
fn cga_even_product_has_256_multiplies() {
    let algebra = Algebra::new(&common::cga()).unwrap();
    let cost = functions::cost(&algebra, Operation::Geometric, "Even", Some("Even"))
        .unwrap()
        .unwrap();
    assert_eq!(cost.multiplies, 256);
}
