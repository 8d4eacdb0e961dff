// `exp` is not a polynomial: it cannot be part of a larger formula, nor take one as its argument, nor be called
// from another expression.
ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Bivector = grades(2);
            Rotor = grades(0, 2);
            Multivector = all;
        }
        fn twice(b: Bivector) -> Rotor = exp(b) * 2.0;
    }
}

ga_macros::algebra! {
    mod argument {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Bivector = grades(2);
            Rotor = grades(0, 2);
            Multivector = all;
        }
        fn half(b: Bivector) -> Rotor = exp(b * 0.5);
    }
}

ga_macros::algebra! {
    mod called {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Bivector = grades(2);
            Rotor = grades(0, 2);
            Multivector = all;
        }
        fn rotor(b: Bivector) -> Rotor = exp(b);
        fn squared(b: Bivector) -> Rotor = rotor(b) * rotor(b);
    }
}

fn main() {}
