ga_macros::algebra! {
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types {
            Translator = blades(scalar, e05);
        }
    }
}

fn main() {}
