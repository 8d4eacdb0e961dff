ga_macros::algebra! {
    mod positive {
        scalar = f64;
        basis = [e1 = 1, e2 = 2];
        types {
            Vector = grades(1);
        }
    }
}

ga_macros::algebra! {
    mod negative {
        scalar = f64;
        basis = [e1 = 1, e2 = -2];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
