ga_macros::algebra! {
    mod both {
        scalar = f64;
        basis = [e1 = 1, n0, ninf = 0];
        metric = [
            [1, 0, 0],
            [0, 0, -1],
            [0, -1, 0],
        ];
        types {
            Vector = grades(1);
        }
    }
}

ga_macros::algebra! {
    mod neither {
        scalar = f64;
        basis = [e1 = 1, e2];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
