//! A fused expression of eight operands (the shape of a second derivative through a product rule): it is emitted
//! with its declared signature, which `cargo clippy -D warnings` accepts (the emitted function carries the
//! `too_many_arguments` allowance), and it equals the sum of its products taken one by one.

ga_macros::algebra! {
    mod euclidean {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Vector = grades(1);
            Bivector = grades(2);
            Trivector = grades(3);
        }
        ops = [outer];
        /// `a ∧ b + c ∧ d + e ∧ f + g ∧ h`.
        fn four_planes(a: Vector, b: Vector, c: Vector, d: Vector, e: Vector, f: Vector, g: Vector, h: Vector) -> Bivector =
            (a ^ b) + (c ^ d) + (e ^ f) + (g ^ h);
    }
}

use euclidean::{Outer as _, Vector};

#[test]
fn eight_operands_fuse_into_one_function() {
    let v = |k: f64| Vector {
        e1: k,
        e2: 2.0 - k,
        e3: k * k - 1.0,
    };
    let [a, b, c, d, e, f, g, h] = [0.5, -1.0, 2.0, 0.25, 3.0, -0.5, 1.5, 0.75].map(v);
    let fused = euclidean::four_planes(a, b, c, d, e, f, g, h);
    let step_by_step = [a.outer(b), c.outer(d), e.outer(f), g.outer(h)];
    let sum = |field: fn(&euclidean::Bivector) -> f64| step_by_step.iter().map(field).sum::<f64>();
    assert_eq!(fused.e12, sum(|p| p.e12));
    assert_eq!(fused.e13, sum(|p| p.e13));
    assert_eq!(fused.e23, sum(|p| p.e23));
}
