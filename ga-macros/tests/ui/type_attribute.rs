ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            /// A direction in the plane.
            #[derive(Hash)]
            Vector = grades(1);
        }
    }
}

fn main() {}
