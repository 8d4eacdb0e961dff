ga_macros::algebra! {
    mod vga {
        scalar = f64;
        metric = [1, 1];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
