ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Bivector = blades(e11);
        }
    }
}

fn main() {}
