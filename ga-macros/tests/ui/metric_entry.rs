ga_macros::algebra! {
    mod bad_entries {
        scalar = f64;
        basis = [n0, ninf];
        metric = [
            [0.5, -1],
            [-1, 1/0],
        ];
        types {
            Vector = grades(1);
        }
    }
}

ga_macros::algebra! {
    mod not_a_number {
        scalar = f64;
        basis = [n0, ninf];
        metric = [
            [0, x],
            [-1 / 2, 0],
        ];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
