ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            /// A direction in the plane.
            #[derive(Hash, serde::Serialize)]
            Vector = grades(1);
            #[derive(Clone, PartialOrd)]
            #[cfg(feature = "rotors")]
            Rotor = grades(0, 2);
        }
    }
}

fn main() {}
