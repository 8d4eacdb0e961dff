// Every term cancels and no result type is declared: refused at the expression's name.
ga_macros::algebra! {
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types { Line = grades(2); }
        ops = [reverse];
        fn cancels(l: Line) = l - l;
    }
}

fn main() {}
