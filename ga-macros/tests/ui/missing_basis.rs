ga_macros::algebra! {
    mod vga {
        scalar = f64;
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
