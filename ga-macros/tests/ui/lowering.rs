// A lowering other than `table` or `unrolled`, and a table for an operation that is not a product.
ga_macros::algebra! {
    mod misspelt {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Vector = grades(1);
            Multivector = all;
        }
        ops = [geometric(tables)];
    }
}

ga_macros::algebra! {
    mod unary {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Multivector = all;
        }
        ops = [geometric(table), reverse(table)];
    }
}

fn main() {}
