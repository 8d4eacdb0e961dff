// A linear map in a name that is not a parameter, in a parameter the expression is not linear in, and
// another attribute: each refused at its token.
ga_macros::algebra! {
    mod pga {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types { Motor = grades(0, 2, 4); Line = grades(2); Plane = grades(1); Point = grades(3); Odd = grades(1, 3); }
        #[linear(x)]
        fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;
    }
}

ga_macros::algebra! {
    mod pga2 {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types { Motor = grades(0, 2, 4); Line = grades(2); Plane = grades(1); Point = grades(3); Odd = grades(1, 3); }
        #[linear(m)]
        fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;
    }
}

ga_macros::algebra! {
    mod pga3 {
        scalar = f64;
        basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1];
        types { Motor = grades(0, 2, 4); Line = grades(2); Plane = grades(1); Point = grades(3); Odd = grades(1, 3); }
        #[inline]
        fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;
    }
}

fn main() {}
