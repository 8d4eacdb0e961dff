ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Vector = grades(1);
            Rotor = grades(0, 2);
        }
        fn both(a: Vector, b: Vector) -> Rotor = a && b;
    }
}

fn main() {}
