// Cl(2,2): with two vectors of each sign a bivector's invariants λ₁, λ₂ can be a complex pair, which is not
// generated.
ga_macros::algebra! {
    mod split {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = -1, e4 = -1];
        types {
            Bivector = grades(2);
            Even = grades(0, 2, 4);
            Multivector = all;
        }
        fn exp_bivector(b: Bivector) -> Even = exp(b);
    }
}

fn main() {}
