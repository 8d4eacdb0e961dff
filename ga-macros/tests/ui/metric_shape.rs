ga_macros::algebra! {
    mod short_row {
        scalar = f64;
        basis = [e1, n0, ninf];
        metric = [
            [1, 0, 0],
            [0, 0],
            [0, -1, 0],
        ];
        types {
            Vector = grades(1);
        }
    }
}

ga_macros::algebra! {
    mod missing_row {
        scalar = f64;
        basis = [e1, n0, ninf];
        metric = [
            [1, 0, 0],
            [0, 0, -1],
        ];
        types {
            Vector = grades(1);
        }
    }
}

ga_macros::algebra! {
    mod huge {
        scalar = f64;
        basis = [a, b];
        metric = [
            [1, 100000000],
            [100000000, 1],
        ];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
