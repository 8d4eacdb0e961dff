ga_macros::algebra! {
    mod null {
        scalar = f64;
        basis = [n0, ninf];
        metric = [
            [0, -1],
            [1, 0],
        ];
        types {
            Vector = grades(1);
        }
    }
}

fn main() {}
