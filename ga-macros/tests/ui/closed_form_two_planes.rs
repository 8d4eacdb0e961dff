// An even element of Cl(4) can turn in two planes of non-zero square (e12 + e34): its logarithm is not generated
// (its exponential is).
ga_macros::algebra! {
    mod cl4 {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1];
        types {
            Bivector = grades(2);
            Even = grades(0, 2, 4);
            Multivector = all;
        }
        fn exp_bivector(b: Bivector) -> Even = exp(b);
        fn log_even(m: Even) -> Bivector = log(m);
    }
}

fn main() {}
