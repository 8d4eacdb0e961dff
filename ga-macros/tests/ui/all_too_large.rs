ga_macros::algebra! {
    mod big {
        scalar = f64;
        basis = [e0 = 1, e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = 1, e6 = 1, e7 = 1, e8 = 1, e9 = 1, ea = 1];
        types {
            Vector = grades(1);
            Multivector = all;
        }
    }
}

fn main() {}
