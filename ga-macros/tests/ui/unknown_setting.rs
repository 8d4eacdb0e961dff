ga_macros::algebra! {
    mod vga {
        scalar = f64;
        signature = [3, 0, 1];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
