ga_macros::algebra! {
    /// The Minkowski plane on two null vectors, with a rational metric entry.
    #[allow(dead_code)]
    pub mod minkowski {
        scalar = f64;
        basis = [e1, n0, ninf];
        metric = [
            [1, 0, 0],
            [0, 0, -1/2],
            [0, -1/2, 0],
        ];
        types {
            Vector = grades(1);
            Even = grades(0, 2);
            Multivector = all;
        }
        ops = [geometric, outer, polarity];
    }
}

fn main() {
    let _ = std::mem::size_of::<(minkowski::Vector, minkowski::Even, minkowski::Multivector)>();
}
