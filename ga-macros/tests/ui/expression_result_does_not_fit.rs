ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Vector = grades(1);
            Rotor = grades(0, 2);
        }
        // `a * a` of a vector is a scalar: its `e12` terms cancel.
        fn squared(a: Vector) -> Vector = a * a;
    }
}

fn main() {}
