// Names the emitted module defines or uses: the trait of each emitted binary operation, `From`, …
ga_macros::algebra! {
    mod geometric_trait {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Geometric = grades(1);
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    mod sandwich_trait {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Multivector = all;
            Sandwich = grades(0, 2);
        }
        ops = [geometric, sandwich];
    }
}

ga_macros::algebra! {
    mod from_trait {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            From = grades(1);
            Multivector = all;
        }
    }
}

// Free when the operation is not emitted.
ga_macros::algebra! {
    #[allow(dead_code)]
    mod unused_trait {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Sandwich = grades(0, 2);
            Multivector = all;
        }
        ops = [geometric];
    }
}

fn main() {}
