// Blade names join basis vector names with `_` here, so `x_y` would name both a basis vector and
// the blade x ∧ y.
ga_macros::algebra! {
    mod plane {
        scalar = f64;
        basis = [x = 1, y = 1, x_y = 1];
        types {
            Vector = grades(1);
            Multivector = all;
        }
    }
}

fn main() {}
