// `exp` is generated for bivector types only.
ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1];
        types {
            Rotor = grades(0, 2);
            Multivector = all;
        }
        fn exp_rotor(r: Rotor) -> Rotor = exp(r);
    }
}

fn main() {}
