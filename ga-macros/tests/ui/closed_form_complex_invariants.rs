// Cl(2,2): with two vectors of each sign the squares λ₁, λ₂ of a bivector's two planes can be a complex pair, which
// is not generated: exp, log and normalized are each refused.
ga_macros::algebra! {
    mod exponential {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = -1, e4 = -1];
        types { Bivector = grades(2); Even = grades(0, 2, 4); Multivector = all; }
        fn exp_bivector(b: Bivector) -> Even = exp(b);
    }
}

ga_macros::algebra! {
    mod logarithm {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = -1, e4 = -1];
        types { Bivector = grades(2); Even = grades(0, 2, 4); Multivector = all; }
        fn log_even(m: Even) -> Bivector = log(m);
    }
}

ga_macros::algebra! {
    mod normalisation {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = -1, e4 = -1];
        types { Bivector = grades(2); Even = grades(0, 2, 4); Multivector = all; }
        fn normalized_even(m: Even) -> Even = normalized(m);
    }
}

fn main() {}
