ga_macros::algebra! {
    mod vga {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Vector = grades(1);
        }
        ops = [geometric, wedge];
    }
}

fn main() {}
