// Both types would give the methods `geometric_foo_bar`, `outer_foo_bar`, …
ga_macros::algebra! {
    mod plane {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            FooBar = grades(1);
            Foo_bar = grades(0, 2);
            Multivector = all;
        }
    }
}

fn main() {}
